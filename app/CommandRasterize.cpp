// dfrecon rasterize IN [--roi NAME | --all] --like REF -o OUT: ROIs as one
// label map on a reference grid, each read from its 3D distance field
// (inside where the field is negative), for 3D Slicer, ITK-SNAP and the
// NIfTI tools, with a label table naming and colouring the labels.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <numeric>
#include <set>

#include <nlohmann/json.hpp>

#include "api/Stopwatch.hpp"
#include "app/Commands.hpp"
#include "app/ExitCodes.hpp"
#include "app/Failure.hpp"
#include "app/Inputs.hpp"
#include "app/NumberChecks.hpp"
#include "app/Progress.hpp"
#include "app/Reports.hpp"
#include "app/StandardStreams.hpp"
#include "dfrecon/Field.hpp"
#include "io/ContourFormat.hpp"
#include "io/DicomImageSeries.hpp"
#include "io/FileNames.hpp"
#include "io/JsonText.hpp"
#include "io/LabelTable.hpp"
#include "io/LabelVolume.hpp"
#include "io/RtStruct.hpp"

namespace dfrecon::app {

namespace {

struct RasterizeArgs {
    std::string input, output, roi, like, table;
    bool all = false;
    double voxelMm = 0, pixelMm = 0;
    bool json = false;
};

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
    const ContourInput input = loadContours(args.input, global);
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
    // Each voxel takes a label and its owner: refused before either is
    // allocated, whoever described the grid.
    if (const std::string problem = labelGridProblem(grid, sizeof(std::int32_t));
        !problem.empty()) {
        if (args.like.empty())
            throw std::invalid_argument("--voxel-mm " + CLI::detail::to_string(args.voxelMm) +
                                        ": the grid around the ROIs has " + problem);
        throw InputError(args.like, 0, "its grid has " + problem);
    }

    // Larger structures are painted first so that a structure inside
    // another (an organ inside the body outline) keeps its voxels: a label
    // map holds one label per voxel.
    ocl::Runtime runtime(global.device);
    const std::vector<std::int32_t> labels = labelsOf(rois);
    std::vector<std::vector<std::size_t>> inside(rois.size());
    for (std::size_t r = 0; r < rois.size(); ++r) {
        Progress progress("field of " + rois[r]->name, !global.quiet);
        RoiFieldOptions options;
        options.pixelMm = args.pixelMm;
        options.progress = [&](double f) { progress.update(f); };
        inside[r] = roiVoxelsInside(runtime, *rois[r], grid, options);
    }
    std::vector<std::size_t> order(rois.size());
    std::iota(order.begin(), order.end(), std::size_t(0));
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
        return inside[a].size() > inside[b].size();
    });
    LabelVolume map;
    map.geometry = grid;
    map.labels.assign(grid.voxelCount(), 0);
    std::vector<std::int32_t> owner(grid.voxelCount(), -1);
    for (std::size_t r : order)
        for (std::size_t v : inside[r]) {
            map.labels[v] = labels[r];
            owner[v] = std::int32_t(r);
        }
    LabelTable table;
    for (std::size_t r = 0; r < rois.size(); ++r)
        table[labels[r]] = LabelEntry{rois[r]->name, rois[r]->colour};
    if (segmentation) map.keyValues = segmentationKeys(table, grid.size);
    const std::string tablePath = !args.table.empty() ? args.table
                                  : segmentation      ? std::string()
                                                      : labelVolumeStem(args.output) + ".txt";
    writeLabelVolume(args.output, map);
    if (!tablePath.empty()) writeLabelTable(tablePath, table);

    const double voxelMm3 = grid.spacingMm[0] * grid.spacingMm[1] * grid.spacingMm[2];
    nlohmann::ordered_json roiReports = nlohmann::ordered_json::array();
    for (std::size_t r = 0; r < rois.size(); ++r) {
        const std::size_t kept =
            std::size_t(std::count_if(inside[r].begin(), inside[r].end(),
                                      [&](std::size_t v) { return owner[v] == std::int32_t(r); }));
        // volumeCc is the ROI's own, before overlaps go to the smaller ROI;
        // labelledVolumeCc what the map holds under its label.
        roiReports.push_back({{"roi", rois[r]->name},
                              {"label", labels[r]},
                              {"insideVoxels", inside[r].size()},
                              {"volumeCc", double(inside[r].size()) * voxelMm3 / 1000},
                              {"voxelsGivenToSmallerRois", inside[r].size() - kept},
                              {"labelledVoxels", kept},
                              {"labelledVolumeCc", double(kept) * voxelMm3 / 1000}});
        if (!args.json)
            std::cout << rois[r]->name << ": label " << labels[r] << ", " << inside[r].size()
                      << " voxels inside (" << double(inside[r].size()) * voxelMm3 / 1000 << " cc)"
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
                             {"size", xyzJson(grid.size)},
                             {"spacingMm", xyzJson(grid.spacingMm)},
                             {"rois", roiReports},
                             {"notRead", notRead},
                             {"seconds", watch.total()}},
                         2)
                  << "\n";
    else
        std::cout << "-> " << args.output << (tablePath.empty() ? "" : " and " + tablePath) << "\n";
    if (!notRead.empty())
        throw ItemsFailed(std::to_string(notRead.size()) +
                              " ROI(s) could not be read; the others were rasterized",
                          kExitBadInput);
}

}  // namespace

void addRasterizeCommand(CLI::App& root, const GlobalOptions& global) {
    auto args = std::make_shared<RasterizeArgs>();
    CLI::App* cmd = root.add_subcommand(
        "rasterize",
        "Write ROIs as a label map (NRRD, Slicer .seg.nrrd or NIfTI) on a reference grid");
    cmd->footer(
        "A voxel is inside an ROI when the ROI's 3D distance field (as `dfrecon field` computes "
        "it) is negative at its centre: on a contour plane that is the exact inside of the "
        "contours, between planes the field's interpolation, at the ends the flat caps half a "
        "spacing out. Each ROI's label is its number where the ROIs have distinct positive "
        "numbers (DICOM ROI Number, a label volume's value), else its position 1, 2, ...; where "
        "ROIs overlap the smaller one keeps the voxel (an organ inside the body outline). "
        "Outputs (gzip, LPS geometry): .nrrd (a label map for 3D Slicer, ITK-SNAP), .seg.nrrd "
        "(a 3D Slicer segmentation with each ROI's name and colour), .nii / .nii.gz (NIfTI-1, "
        "RAS sform and qform, for FSL, ANTs, ITK-SNAP). Except for .seg.nrrd a label table "
        "(ITK-SNAP format, names and colours) is written beside it as STEM.txt, which dfrecon "
        "and ITK-SNAP read back. Exit codes: 0 done, 1 usage, 2 bad input (with --all: some "
        "ROIs could not be read; the others are in the map), 3 runtime failure.");
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
    cmd->add_option("--pixel-mm", args->pixelMm,
                    "Field pixel size in mm (default 0: each ROI's extent fits 512 px)")
        ->capture_default_str()
        ->check(kNonNegative);
    cmd->add_flag("--json", args->json, "Print a JSON report instead of text");
    cmd->callback([args, &global] { runRasterize(*args, global); });
}

}  // namespace dfrecon::app
