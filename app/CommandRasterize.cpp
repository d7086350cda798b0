// dfrecon rasterize IN --roi NAME --like REF -o OUT.nrrd: an ROI as a binary
// label map on a reference grid, read from its 3D distance field (inside
// where the field is negative), for 3D Slicer and other label-map tools.
#include <cmath>
#include <iostream>

#include <nlohmann/json.hpp>

#include "app/Commands.hpp"
#include "app/Inputs.hpp"
#include "app/NumberChecks.hpp"
#include "app/Progress.hpp"
#include "app/Reports.hpp"
#include "app/StandardStreams.hpp"
#include "app/Stopwatch.hpp"
#include "field/DistanceField3D.hpp"
#include "io/LabelVolume.hpp"

namespace dfrecon::app {

namespace {

struct RasterizeArgs {
    std::string input, output, roi, like;
    double voxelMm = 0, pixelMm = 0;
    bool json = false;
};

// A grid with cubic voxels of `voxelMm` on the ROI's own axes (its plane
// frame), covering its contours plus half a slice spacing beyond the ends.
VolumeGeometry gridAroundRoi(const Roi& roi, double voxelMm) {
    const Extent3 extent = extentOf(roi);
    const SpacingStats spacing = spacingOf(roi);
    const double reach = 0.5 * (spacing.maxMm > 0 ? spacing.maxMm : 1.0);
    VolumeGeometry g;
    double lo[3];
    for (int a = 0; a < 3; ++a) {
        const double margin = a == 2 ? reach + voxelMm : voxelMm;
        lo[a] = extent.min[a] - margin;
        const double span = extent.max[a] + margin - lo[a];
        if (span / voxelMm > 4096)
            throw std::invalid_argument("--voxel-mm gives over 4096 voxels a side");
        g.size[a] = int(std::ceil(span / voxelMm)) + 1;
        g.spacingMm[a] = voxelMm;
    }
    const Vec3 origin = roi.frame.toPatient({lo[0], lo[1], lo[2]});
    g.originMm = {origin.x, origin.y, origin.z};
    const Vec3 axes[3] = {roi.frame.u, roi.frame.v, roi.frame.n};
    for (int a = 0; a < 3; ++a) g.direction[a] = {axes[a].x, axes[a].y, axes[a].z};
    return g;
}

void runRasterize(const RasterizeArgs& args, const GlobalOptions& global) {
    const Stopwatch watch;
    if (args.like.empty() == (args.voxelMm <= 0))
        throw std::invalid_argument(
            "give the grid with exactly one of --like REF or --voxel-mm MM");
    if (args.output.size() < 5 || args.output.compare(args.output.size() - 5, 5, ".nrrd") != 0)
        throw std::invalid_argument("output '" + args.output + "' needs the .nrrd extension");
    const ContourInput input = loadContours(args.input, global);
    const Roi& roi = *selectRois(input.contours, args.roi, false).front();
    const VolumeGeometry grid =
        args.like.empty() ? gridAroundRoi(roi, args.voxelMm) : readLabelVolume(args.like).geometry;

    ocl::Runtime runtime(global.device);
    const SpacingStats spacing = spacingOf(roi);
    DistanceField3D field;
    {
        Progress progress("field of " + roi.name, !global.quiet);
        const SliceFields fields =
            computeSliceFields(runtime, roi.slices, gridForSlices(roi.slices, args.pixelMm),
                               [&](double f) { progress.update(f); });
        field = layersFromSlices(fields, spacing.meanMm > 0 ? spacing.meanMm : 1.0);
        propagateAlongZ(runtime, field);
    }
    // Beyond the field's layers and pixels everything is outside; within,
    // the interpolated field decides (its zero set is the surface the
    // reconstruction follows, the flat caps included).
    const SliceGrid& g = field.grid;
    const double xMin = g.originMm.x, yMin = g.originMm.y;
    const double xMax = xMin + g.width * g.pixelMm, yMax = yMin + g.height * g.pixelMm;
    std::vector<std::uint8_t> mask(grid.voxelCount(), 0);
    std::size_t inside = 0;
    for (int k = 0; k < grid.size[2]; ++k)
        for (int j = 0; j < grid.size[1]; ++j)
            for (int i = 0; i < grid.size[0]; ++i) {
                const Vec3 p = roi.frame.fromPatient(grid.worldOfIndex(i, j, k));
                if (p.z < field.zMm.front() || p.z > field.zMm.back() || p.x < xMin || p.x > xMax ||
                    p.y < yMin || p.y > yMax)
                    continue;
                if (sampleField(field, p.x, p.y, p.z) < 0) {
                    mask[grid.linearIndex(i, j, k)] = 1;
                    ++inside;
                }
            }
    writeMaskNrrd(args.output, grid, mask);
    const double voxelMm3 = grid.spacingMm[0] * grid.spacingMm[1] * grid.spacingMm[2];
    if (args.json)
        std::cout << nlohmann::ordered_json{{"command", "rasterize"},
                                            {"input", args.input},
                                            {"roi", roi.name},
                                            {"output", args.output},
                                            {"grid",
                                             args.like.empty() ? "around the ROI" : args.like},
                                            {"size", xyzJson(grid.size)},
                                            {"spacingMm", xyzJson(grid.spacingMm)},
                                            {"insideVoxels", inside},
                                            {"volumeCc", double(inside) * voxelMm3 / 1000},
                                            {"seconds", watch.total()}}
                         .dump(2)
                  << "\n";
    else
        std::cout << roi.name << ": " << inside << " voxels inside ("
                  << double(inside) * voxelMm3 / 1000 << " cc) -> " << args.output << "\n";
}

}  // namespace

void addRasterizeCommand(CLI::App& root, const GlobalOptions& global) {
    auto args = std::make_shared<RasterizeArgs>();
    CLI::App* cmd = root.add_subcommand(
        "rasterize", "Write an ROI as a binary label map (NRRD) on a reference grid");
    cmd->footer(
        "A voxel is inside when the ROI's 3D distance field (as `dfrecon field` computes it) is "
        "negative at its centre: on a contour plane that is the exact inside of the contours, "
        "between planes the field's interpolation, at the ends the flat caps half a spacing "
        "out. The NRRD (uint8 0/1, gzip, LPS space directions and origin) opens in 3D Slicer "
        "as a label map or segmentation. Exit codes: 0 done, 1 usage, 2 bad input, 3 runtime "
        "failure.");
    cmd->add_option("file", args->input,
                    "Input contours: .slices (- reads it from standard input), DICOM RTSTRUCT "
                    "(.dcm) or a label volume")
        ->required();
    cmd->add_option("-o,--output", args->output, "Output label map (.nrrd)")
        ->required()
        ->check(kNotStandardStream);
    cmd->add_option("--roi", args->roi,
                    "ROI name, or DICOM ROI number (default: the only ROI of the file)");
    cmd->add_option("--like", args->like,
                    "Reference grid: a NRRD or NIfTI volume (e.g. the CT or a segmentation) whose "
                    "size, spacing, origin and directions the output takes");
    cmd->add_option("--voxel-mm", args->voxelMm,
                    "Or a grid of cubic voxels this size (mm) on the ROI's axes, around its "
                    "contours")
        ->check(kPositive);
    cmd->add_option("--pixel-mm", args->pixelMm,
                    "Field pixel size in mm (default 0: the ROI's extent fits 512 px)")
        ->capture_default_str()
        ->check(kNonNegative);
    cmd->add_flag("--json", args->json, "Print a JSON report instead of text");
    cmd->callback([args, &global] { runRasterize(*args, global); });
}

}  // namespace dfrecon::app
