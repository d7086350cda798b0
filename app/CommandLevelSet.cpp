// dfrecon field IN.slices -o OUT.vdb: the ROI's 3D signed distance field
// (reconstruction paper §6.1) as an OpenVDB level set.
#include <iostream>

#include <nlohmann/json.hpp>

#include "api/Stopwatch.hpp"
#include "app/Commands.hpp"
#include "app/Inputs.hpp"
#include "app/OutputOptions.hpp"
#include "app/Progress.hpp"
#include "app/StandardStreams.hpp"
#include "dfrecon/Field.hpp"
#include "io/files/JsonText.hpp"
#include "io/volumes/LevelSetVdb.hpp"
#include "report/NumberChecks.hpp"
#include "report/Reports.hpp"

namespace dfrecon::app {

namespace {

// What the values are, as the .vdb's metadata says.
constexpr const char* kPropagatedDistance =
    "in-slice Euclidean + |dz| (reconstruction paper 6.1): never below the Euclidean distance; "
    "negative inside";
constexpr const char* kEuclideanDistance =
    "exact Euclidean distance to the reconstructed surface (closest triangle, signed by "
    "pseudo-normals); negative inside";

struct FieldArgs {
    std::string input, output, roi;
    double pixelMm = 0, bandVoxels = 3;
    bool isotropic = false, json = false, euclidean = false;
};

void runField(const FieldArgs& args, const GlobalOptions& global) {
    Stopwatch watch;
    const ContourInput load = loadContours(args.input, global, onlyRoi(args.roi));
    const Roi& roi = *selectRois(load.contours, args.roi, false).front();

    ocl::Runtime runtime(global.device);
    RoiDistanceVolume field;
    {
        Progress progress("fields of " + roi.name, !global.quiet);
        RoiFieldOptions options;
        options.pixelMm = args.pixelMm;
        options.isotropic = args.isotropic;
        options.progress = [&](double f) { progress.update(f); };
        field = args.euclidean ? roiEuclideanDistanceVolume(runtime, roi, options)
                               : roiDistanceVolume(runtime, roi, options);
    }
    const DenseDistanceVolume& volume = field.volume;
    watch.restartLap();
    LevelSetWriteOptions options;
    options.gridName = roi.name;
    options.frame = roi.frame;
    options.bandVoxels = args.bandVoxels;
    options.metadata = {{"source", args.input},
                        {"units", "mm"},
                        {"distance", args.euclidean ? kEuclideanDistance : kPropagatedDistance},
                        {"slice_spacing_mm", std::to_string(field.sliceSpacingMm)},
                        {"program", std::string("dfrecon ") + DFRECON_VERSION}};
    writeLevelSetVdb(volume, args.output, options);
    const double writeSeconds = watch.lap();

    // The volume is sampled in the plane frame; users and the .vdb transform
    // see patient LPS.
    const Vec3 originLps =
        roi.frame.toPatient({volume.originMm[0], volume.originMm[1], volume.originMm[2]});
    if (args.json) {
        std::cout << jsonText(nlohmann::ordered_json{{"command", "field"},
                                                     {"input", args.input},
                                                     {"roi", roi.name},
                                                     {"output", args.output},
                                                     {"distance",
                                                      args.euclidean ? "euclidean" : "propagated"},
                                                     {"voxels", {volume.nx, volume.ny, volume.nz}},
                                                     {"voxelMm", xyzJson(volume.voxelMm)},
                                                     {"originMm", xyzJson(originLps)},
                                                     {"axes",
                                                      {{"i", xyzJson(roi.frame.u)},
                                                       {"j", xyzJson(roi.frame.v)},
                                                       {"k", xyzJson(roi.frame.n)}}},
                                                     {"bandVoxels", args.bandVoxels},
                                                     {"device", runtime.device().deviceName},
                                                     {"seconds",
                                                      {{"total", watch.total()},
                                                       {"fields", field.fieldsSeconds},
                                                       {"propagate", field.propagateSeconds},
                                                       {"write", writeSeconds}}}},
                              2)
                  << "\n";
    } else {
        std::cout << roi.name << ": " << volume.nx << " x " << volume.ny << " x " << volume.nz
                  << " voxels of " << volume.voxelMm[0] << " x " << volume.voxelMm[1] << " x "
                  << volume.voxelMm[2] << " mm -> " << args.output << "\n";
    }
}

}  // namespace

void addFieldCommand(CLI::App& root, const GlobalOptions& global) {
    auto args = std::make_shared<FieldArgs>();
    CLI::App* cmd = root.add_subcommand(
        "field", "The ROI's 3D signed distance field as an OpenVDB level set (.vdb)");
    cmd->footer(
        "By default the slices' exact 2D fields propagated along z (distance = in-slice "
        "Euclidean + |dz|, never below the true Euclidean distance; negative inside; its zero "
        "set passes through the contours, ends closing half a slice spacing beyond the end "
        "slices, as the flat caps do). With --euclidean, the exact Euclidean distance to the "
        "ROI's reconstructed surface (reconstruct's defaults), so every level set is an exact "
        "margin. Grid named after the ROI, voxel "
        "(i, j, k) centred at the reported origin + i, j, k voxel sizes along the reported "
        "axes, in patient LPS mm (the axes are x, y, z for axial stacks); metadata: "
        "source, units, distance, slice_spacing_mm, program. Opens in Blender, Houdini and "
        "OpenVDB tools (vdb_print). Exit codes: 0 done, 1 usage, 2 bad input, 3 runtime failure.");
    cmd->add_option("file", args->input, contourInputHelp())->required();
    cmd->add_option("-o,--output", args->output, "Output .vdb file")
        ->required()
        ->check(kNotStandardStream);
    cmd->add_option("--roi", args->roi, "ROI name (default: the only ROI of the file)");
    cmd->add_option("--pixel-mm", args->pixelMm,
                    "Voxel size in x and y, mm (default 0: the ROI's extent plus margin fits "
                    "~512 px)")
        ->capture_default_str()
        ->check(kNonNegative);
    cmd->add_flag("--isotropic", args->isotropic,
                  "Cubic voxels: resample z at the x/y voxel size (default: z step = half the "
                  "slice spacing, so slices and cap planes are voxel layers; half the smallest "
                  "gap when uneven)");
    cmd->add_option("--band", args->bandVoxels,
                    "Narrow band half-width in voxels (of the largest voxel side)")
        ->capture_default_str()
        ->check(kPositive);
    cmd->add_flag("--euclidean", args->euclidean,
                  "Exact Euclidean signed distance to the reconstructed surface instead of the "
                  "propagated field (slower: one nearest-triangle query per voxel)");
    cmd->add_flag("--json", args->json, "Print a JSON report instead of text");
    asOutput(cmd->get_option("--output"), OutputKind::File);
    cmd->callback([args, &global] {
        if (args->output.size() < 4 || args->output.substr(args->output.size() - 4) != ".vdb")
            throw std::invalid_argument("output '" + args->output + "' must end in .vdb");
        runField(*args, global);
    });
}

}  // namespace dfrecon::app
