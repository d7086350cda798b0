// dfrecon rasterize IN [--roi NAME | --all] --like REF -o OUT: ROIs as one
// label map on a reference grid, each voxel inside an ROI when its centre is
// inside the ROI's reconstructed solid (or, with --inside field, where its
// 3D distance field is negative), for 3D Slicer, ITK-SNAP and the NIfTI
// tools, with a label table naming and colouring the labels. A .seg.nrrd
// keeps overlapping ROIs whole on layers; the single-label formats give a
// voxel two ROIs share to the smaller.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <numeric>
#include <optional>
#include <set>

#include <nlohmann/json.hpp>

#include "api/Stopwatch.hpp"
#include "app/Commands.hpp"
#include "app/Inputs.hpp"
#include "app/OutputOptions.hpp"
#include "app/Progress.hpp"
#include "app/StandardStreams.hpp"
#include "cl/WorkerRuntimes.hpp"
#include "dfrecon/Field.hpp"
#include "dfrecon/Reconstruct.hpp"
#include "geometry/OrderedParallel.hpp"
#include "io/contours/ContourFormat.hpp"
#include "io/dicom/DicomImageSeries.hpp"
#include "io/dicom/RtStruct.hpp"
#include "io/files/FileNames.hpp"
#include "io/files/JsonText.hpp"
#include "io/labels/LabelTable.hpp"
#include "io/labels/LabelVolume.hpp"
#include "report/EnumNames.hpp"
#include "report/ExitCodes.hpp"
#include "report/Failure.hpp"
#include "report/NumberChecks.hpp"
#include "report/Reports.hpp"

namespace dfrecon::app {

namespace {

// What decides that a voxel centre is inside an ROI.
enum class InsideRule { Surface, Field };
constexpr EnumNames<InsideRule, 2> kInsideRuleNames{
    {{"surface", InsideRule::Surface}, {"field", InsideRule::Field}}};

struct RasterizeArgs {
    std::string input, output, roi, like, table;
    bool all = false;
    double voxelMm = 0, pixelMm = 0;
    InsideRule inside = InsideRule::Surface;
    unsigned jobs = 0;  // ROIs at once; 0: defaultJobs()
    CapMode cap = CapMode::Flat;
    Interpolation interpolation = Interpolation::Smooth;
    bool json = false;
};

// One ROI's voxels, and the volume of the solid they came from (surface
// rule only).
struct RoiVoxels {
    std::vector<std::size_t> inside;
    std::optional<double> surfaceVolumeMm3;
    std::string invalid;  // with --all: why the ROI has no solid to rasterize, else ""
};

// The voxels of `roi` on `grid` by args' rule: its reconstructed solid
// (reconstructed as `dfrecon reconstruct` would with these settings) or its
// 3D field. Throws InvalidResult when the solid is not valid (no inside).
RoiVoxels roiVoxels(ocl::Runtime& runtime, const Roi& roi, const VolumeGeometry& grid,
                    const RasterizeArgs& args, bool showProgress) {
    RoiVoxels out;
    if (args.inside == InsideRule::Field) {
        Progress progress("field of " + roi.name, showProgress);
        RoiFieldOptions options;
        options.pixelMm = args.pixelMm;
        options.progress = [&](double f) { progress.update(f); };
        out.inside = roiVoxelsInside(runtime, roi, grid, options);
        return out;
    }
    Progress progress("surface of " + roi.name, showProgress);
    RoiReconstructOptions options;
    options.reconstruction.pixelMm = args.pixelMm;
    options.reconstruction.cap = args.cap;
    options.reconstruction.interpolation = args.interpolation;
    const RoiSurface solid =
        reconstructRoi(runtime, roi, options, [&](const std::string&, double f) {
            if (f >= 0) progress.update(f);
        });
    if (!solid.check.validSolid())
        throw InvalidResult("ROI " + roi.name +
                            ": its reconstructed surface is not a valid closed solid (" +
                            std::to_string(solid.check.intersectingPairs) +
                            " intersecting pairs, " + std::to_string(solid.check.boundaryEdges) +
                            " open edges; `dfrecon reconstruct` says where), so it has no inside "
                            "to rasterize; --inside field rasterizes its distance field");
    out.inside = roiSolidVoxelsInside(roi, solid, grid);
    out.surfaceVolumeMm3 = solid.check.volumeMm3;
    return out;
}

// The layer of each ROI in a segmentation that keeps overlapping ROIs whole:
// ROIs in `order` (largest first) each go to the first layer where no ROI
// before it has a voxel of its own. O(voxels of the ROIs · layers).
std::vector<int> layersOf(const std::vector<std::vector<std::size_t>>& inside,
                          const std::vector<std::size_t>& order, std::size_t voxelCount) {
    std::vector<int> layer(inside.size(), 0);
    std::vector<std::vector<bool>> taken;
    for (std::size_t r : order) {
        std::size_t l = 0;
        for (; l < taken.size(); ++l)
            if (std::none_of(inside[r].begin(), inside[r].end(),
                             [&](std::size_t v) { return bool(taken[l][v]); }))
                break;
        if (l == taken.size()) taken.emplace_back(voxelCount, false);
        for (std::size_t v : inside[r]) taken[l][v] = true;
        layer[r] = int(l);
    }
    return layer;
}

// Each ROI's label: its number where every selected ROI has a distinct
// positive one (DICOM ROI numbers, a label volume's values), else its
// position 1, 2, ...
std::vector<std::int32_t> labelsOf(const std::vector<const Roi*>& rois) {
    std::vector<std::int32_t> labels;
    std::set<int> seen;
    for (const Roi* roi : rois)
        if (roi->number && *roi->number > 0 && seen.insert(*roi->number).second)
            labels.push_back(*roi->number);
    if (labels.size() == rois.size()) return labels;
    labels.clear();
    for (std::size_t i = 0; i < rois.size(); ++i) labels.push_back(std::int32_t(i + 1));
    return labels;
}

// The grid of a reference: a DICOM image series (its folder or one of its
// files: the planning CT) or a NRRD / NIfTI volume.
VolumeGeometry referenceGrid(const std::string& path) {
    if (std::filesystem::is_directory(path) || isDicomFile(path))
        return gridOf(readDicomImageSeries(path));
    return readLabelVolume(path).geometry;
}

void runRasterize(const RasterizeArgs& args, const GlobalOptions& global) {
    const Stopwatch watch;
    if (args.like.empty() == (args.voxelMm <= 0))
        throw std::invalid_argument(
            "give the grid with exactly one of --like REF or --voxel-mm MM");
    const bool segmentation = endsWithIgnoringCase(args.output, ".seg.nrrd");
    if (!endsWithIgnoringCase(args.output, ".nrrd") && !endsWithIgnoringCase(args.output, ".nii") &&
        !endsWithIgnoringCase(args.output, ".nii.gz"))
        throw std::invalid_argument("output '" + args.output +
                                    "' must end in .nrrd, .seg.nrrd, .nii or .nii.gz");
    if (args.all && !args.roi.empty())
        throw std::invalid_argument("give --roi NAME or --all, not both");
    const ContourInput input = loadContours(args.input, global, onlyRoi(args.roi));
    std::vector<const Roi*> rois;
    std::vector<std::string> notRead;
    for (const Roi* roi : selectRois(input.contours, args.roi, args.all)) {
        if (!roi->defect) {
            rois.push_back(roi);
        } else if (!args.all) {
            throw *roi->defect;
        } else {
            std::cerr << "dfrecon: ROI " << roi->name << " not read: " << roi->defect->what()
                      << "\n";
            notRead.push_back(roi->name);
        }
    }
    if (rois.empty()) throw InputError(args.input, 0, "no ROI could be read");
    const VolumeGeometry grid =
        args.like.empty() ? gridAroundRois(rois, args.voxelMm) : referenceGrid(args.like);
    // Each voxel takes a label (and the writer's copy of it): refused before
    // it is allocated, whoever described the grid.
    if (const std::string problem = labelGridProblem(grid, sizeof(std::int32_t));
        !problem.empty()) {
        if (args.like.empty())
            throw std::invalid_argument("--voxel-mm " + CLI::detail::to_string(args.voxelMm) +
                                        ": the grid around the ROIs has " + problem);
        throw InputError(args.like, 0, "its grid has " + problem);
    }

    // Larger structures are painted first so that, in a single-label map, a
    // structure inside another (an organ inside the body outline) keeps its
    // voxels; a segmentation puts ROIs that overlap on different layers.
    const std::vector<std::int32_t> labels = labelsOf(rois);
    std::vector<std::vector<std::size_t>> inside(rois.size());
    std::vector<std::optional<double>> surfaceVolumeMm3(rois.size());
    std::vector<std::string> invalid;
    std::vector<bool> done(rois.size(), false);
    // Several ROIs at once, each worker with its own OpenCL queue, as
    // reconstruct --all runs them; with several workers one bar counts ROIs.
    const std::size_t jobs = jobsFor(args.jobs, rois.size());
    ocl::WorkerRuntimes runtimes(global.device, jobs);
    Progress overall("rasterizing " + std::to_string(rois.size()) + " ROIs",
                     jobs > 1 && !global.quiet);
    forEachInOrder(
        rois.size(), jobs,
        [&](std::size_t r, std::size_t worker) {
            try {
                return roiVoxels(runtimes[worker], *rois[r], grid, args,
                                 jobs <= 1 && !global.quiet);
            } catch (const InvalidResult& e) {
                if (!args.all) throw;
                RoiVoxels none;
                none.invalid = e.what();
                return none;
            }
        },
        [&](std::size_t r, RoiVoxels voxels) {
            overall.update(double(r + 1) / double(rois.size()));
            if (!voxels.invalid.empty()) {
                overall.finish();
                std::cerr << "dfrecon: " << voxels.invalid << "\n";
                invalid.push_back(rois[r]->name);
                return;
            }
            inside[r] = std::move(voxels.inside);
            surfaceVolumeMm3[r] = voxels.surfaceVolumeMm3;
            done[r] = true;
        });
    overall.finish();
    std::vector<std::size_t> order;
    for (std::size_t r = 0; r < rois.size(); ++r)
        if (done[r]) order.push_back(r);
    if (order.empty()) throw InvalidResult("no ROI could be rasterized");
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
        return inside[a].size() > inside[b].size();
    });
    LabelVolume map;
    map.geometry = grid;
    std::vector<int> layer(rois.size(), 0);
    if (segmentation) {
        layer = layersOf(inside, order, grid.voxelCount());
        for (std::size_t r : order) map.layerCount = std::max(map.layerCount, layer[r] + 1);
        // Each layer is a whole label map (4 bytes a voxel, and the writer's
        // copy in the file's type, 2 bytes for labels up to 65535): refused
        // before they are allocated.
        const std::string problem = std::uint64_t(map.layerCount) > kMaxLabelLayers
                                        ? std::to_string(map.layerCount) + " layers (at most " +
                                              std::to_string(kMaxLabelLayers) + ")"
                                        : labelGridProblem(grid, 6 * std::size_t(map.layerCount));
        if (!problem.empty())
            throw std::invalid_argument(
                "the ROIs overlap so that the segmentation needs " +
                std::to_string(map.layerCount) + " layers, and the grid with them has " + problem +
                "; write a single-label .nrrd or .nii instead, or fewer ROIs");
    }
    map.labels.assign(grid.voxelCount() * std::size_t(map.layerCount), 0);
    for (std::size_t r : order)
        for (std::size_t v : inside[r])
            map.labels[std::size_t(layer[r]) * grid.voxelCount() + v] = labels[r];
    LabelTable table;
    std::map<std::int32_t, int> layerOfLabel;
    for (std::size_t r : order) {
        table[labels[r]] = LabelEntry{rois[r]->name, rois[r]->colour};
        layerOfLabel[labels[r]] = layer[r];
    }
    if (segmentation) map.keyValues = segmentationKeys(table, grid.size, layerOfLabel);
    const std::string tablePath = !args.table.empty() ? args.table
                                  : segmentation      ? std::string()
                                                      : labelVolumeStem(args.output) + ".txt";
    writeLabelVolume(args.output, map);
    if (!tablePath.empty()) writeLabelTable(tablePath, table);

    const double voxelMm3 = grid.spacingMm[0] * grid.spacingMm[1] * grid.spacingMm[2];
    nlohmann::ordered_json roiReports = nlohmann::ordered_json::array();
    for (std::size_t r = 0; r < rois.size(); ++r) {
        if (!done[r]) continue;
        // What the map holds under the ROI's label (labels are distinct): all
        // of it on its layer of a segmentation; in a single-label map less
        // where a smaller ROI, painted after it, took a voxel.
        const std::size_t layerStart = std::size_t(layer[r]) * grid.voxelCount();
        const std::size_t kept =
            std::size_t(std::count_if(inside[r].begin(), inside[r].end(), [&](std::size_t v) {
                return map.labels[layerStart + v] == labels[r];
            }));
        // volumeCc is the ROI's own, before overlaps go to the smaller ROI;
        // labelledVolumeCc what the map holds under its label.
        nlohmann::ordered_json report{
            {"roi", rois[r]->name},
            {"label", labels[r]},
            {"layer", layer[r]},
            {"insideVoxels", inside[r].size()},
            {"volumeCc", double(inside[r].size()) * voxelMm3 / 1000},
            {"surfaceVolumeCc", surfaceVolumeMm3[r]
                                    ? nlohmann::ordered_json(*surfaceVolumeMm3[r] / 1000)
                                    : nlohmann::ordered_json(nullptr)},
            {"voxelsGivenToSmallerRois", inside[r].size() - kept},
            {"labelledVoxels", kept},
            {"labelledVolumeCc", double(kept) * voxelMm3 / 1000}};
        roiReports.push_back(std::move(report));
        if (!args.json)
            std::cout << rois[r]->name << ": label " << labels[r] << ", " << inside[r].size()
                      << " voxels inside (" << double(inside[r].size()) * voxelMm3 / 1000 << " cc"
                      << (surfaceVolumeMm3[r]
                              ? "; surface " + CLI::detail::to_string(*surfaceVolumeMm3[r] / 1000) +
                                    " cc"
                              : std::string())
                      << ")" << (segmentation ? ", layer " + std::to_string(layer[r]) : "")
                      << (kept < inside[r].size() ? ", " + std::to_string(inside[r].size() - kept) +
                                                        " of them labelled as a smaller ROI"
                                                  : std::string())
                      << "\n";
    }
    if (args.json)
        std::cout << jsonText(
                         nlohmann::ordered_json{
                             {"command", "rasterize"},
                             {"input", args.input},
                             {"output", args.output},
                             {"labelTable", tablePath.empty() ? nlohmann::ordered_json(nullptr)
                                                              : nlohmann::ordered_json(tablePath)},
                             {"grid", args.like.empty() ? "around the ROIs" : args.like},
                             {"inside", nameOf(kInsideRuleNames, args.inside)},
                             {"layers", map.layerCount},
                             {"size", xyzJson(grid.size)},
                             {"spacingMm", xyzJson(grid.spacingMm)},
                             {"rois", roiReports},
                             {"notRead", notRead},
                             {"invalid", invalid},
                             {"seconds", watch.total()}},
                         2)
                  << "\n";
    else
        std::cout << "-> " << args.output << (tablePath.empty() ? "" : " and " + tablePath) << "\n";
    if (!notRead.empty())
        throw ItemsFailed(std::to_string(notRead.size()) +
                              " ROI(s) could not be read; the others were rasterized",
                          kExitBadInput);
    if (!invalid.empty())
        throw ItemsFailed(std::to_string(invalid.size()) +
                              " ROI(s) have no valid solid to rasterize; the others were",
                          kExitInvalidResult);
}

}  // namespace

void addRasterizeCommand(CLI::App& root, const GlobalOptions& global) {
    auto args = std::make_shared<RasterizeArgs>();
    CLI::App* cmd = root.add_subcommand(
        "rasterize",
        "Write ROIs as a label map (NRRD, Slicer .seg.nrrd or NIfTI) on a reference grid");
    cmd->footer(
        "By default (--inside surface) each ROI is reconstructed as `dfrecon reconstruct` "
        "reconstructs it (the same --pixel-mm, --cap and --interpolation) and a voxel is inside "
        "when its centre is inside that solid (ray parity against its triangles), so the label "
        "map's volume converges to the surface's as voxels shrink; an ROI whose surface is not a "
        "valid closed solid is an error (exit 4; with --all the others are written). With "
        "--inside field a voxel is inside where the ROI's 3D distance field (as `dfrecon field` "
        "computes it) is negative: faster, but between planes it follows the field's straight "
        "interpolation, smaller than the smooth surface. Either way a centre on a contour plane "
        "(within 0.01 mm) is inside exactly when it is inside the plane's contours, whatever "
        "--pixel-mm. Each ROI's label is its number where the ROIs have distinct positive "
        "numbers (DICOM ROI Number, a label volume's value), else its position 1, 2, ... "
        "Overlapping ROIs: a .seg.nrrd keeps every ROI whole, putting ROIs that overlap on "
        "separate layers (3D Slicer's SegmentN_Layer; a 4-D file when there is more than one "
        "layer); the single-label formats (.nrrd, .nii, .nii.gz) hold one label per voxel and "
        "give a voxel two ROIs share to the smaller one (an organ inside the body outline), "
        "which the report counts (voxelsGivenToSmallerRois). Outputs (gzip, LPS geometry): "
        ".nrrd (a label map for 3D Slicer, ITK-SNAP), .seg.nrrd (a 3D Slicer segmentation with "
        "each ROI's name and colour), .nii / .nii.gz (NIfTI-1, RAS sform and qform, for FSL, "
        "ANTs, ITK-SNAP). Except for .seg.nrrd a label table (ITK-SNAP format, names and "
        "colours) is written beside it as STEM.txt, which dfrecon and ITK-SNAP read back. Exit "
        "codes: 0 done, 1 usage, 2 bad input (with --all: some ROIs could not be read; the "
        "others are in the map), 3 runtime failure, 4 an ROI's surface is not a valid solid "
        "(with --all: the others are in the map).");
    cmd->add_option("file", args->input, contourInputHelp())->required();
    cmd->add_option("-o,--output", args->output,
                    "Output label map: .nrrd, .seg.nrrd, .nii or .nii.gz")
        ->required()
        ->check(kNotStandardStream);
    cmd->add_option("--roi", args->roi,
                    "ROI name, or DICOM ROI number (default: the only ROI of the file)");
    cmd->add_flag("--all", args->all, "Every ROI of the file, in one label map");
    cmd->add_option("--like", args->like,
                    "Reference grid: a DICOM image series (the planning CT's folder, or one of "
                    "its files) or a NRRD or NIfTI volume (the CT, a segmentation) whose size, "
                    "spacing, origin and directions the output takes");
    cmd->add_option("--voxel-mm", args->voxelMm,
                    "Or a grid of cubic voxels this size (mm) on the ROIs' axes (patient LPS "
                    "where they differ), around their contours")
        ->check(kPositive);
    cmd->add_option("--label-table-out", args->table,
                    "Label table to write (.txt ITK-SNAP, .ctbl or .lut VALUE NAME R G B A; "
                    "default: STEM.txt beside the map, none for .seg.nrrd)");
    cmd->add_option_function<std::string>(
           "--inside",
           [args](const std::string& name) {
               args->inside = parseEnum(kInsideRuleNames, name, "--inside");
           },
           "What makes a voxel inside an ROI: 'surface', its centre inside the reconstructed "
           "solid; 'field', its centre where the 3D distance field is negative")
        ->default_str(nameOf(kInsideRuleNames, args->inside))
        ->check(CLI::IsMember(namesOf(kInsideRuleNames)));
    cmd->add_option("--pixel-mm", args->pixelMm,
                    "Field pixel size in mm, of the reconstruction or of the field (default 0: "
                    "each ROI's extent fits 512 px)")
        ->capture_default_str()
        ->check(kNonNegative);
    cmd->add_option_function<std::string>(
           "--cap",
           [args](const std::string& name) { args->cap = parseEnum(kCapModeNames, name, "--cap"); },
           "--inside surface: end caps of the reconstruction, flat or dome (not none: an open "
           "surface has no inside)")
        ->default_str(nameOf(kCapModeNames, args->cap))
        ->check(CLI::IsMember(
            {nameOf(kCapModeNames, CapMode::Flat), nameOf(kCapModeNames, CapMode::Dome)}));
    cmd->add_option_function<std::string>(
           "--interpolation",
           [args](const std::string& name) {
               args->interpolation = parseEnum(kInterpolationNames, name, "--interpolation");
           },
           "--inside surface: the reconstruction between planes, smooth or linear (as "
           "`dfrecon reconstruct`)")
        ->default_str(nameOf(kInterpolationNames, args->interpolation))
        ->check(CLI::IsMember(namesOf(kInterpolationNames)));
    cmd->add_option("-j,--jobs", args->jobs,
                    "ROIs reconstructed (or their fields computed) at once, each with its own "
                    "OpenCL queue (default 0: one per CPU core; never more than one per core or "
                    "per ROI; 1: one after "
                    "the other, each with its own progress bar); the map is the same either way")
        ->capture_default_str()
        ->check(CLI::Range(0, 256));
    cmd->add_flag("--json", args->json, "Print a JSON report instead of text");
    asOutput(cmd->get_option("--output"), OutputKind::File);
    asOutput(cmd->get_option("--label-table-out"), OutputKind::File);
    cmd->callback([args, &global] { runRasterize(*args, global); });
}

}  // namespace dfrecon::app
