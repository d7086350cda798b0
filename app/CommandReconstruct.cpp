// dfrecon reconstruct IN.slices -o OUT: contours to a closed surface
// (docs/reconstruction.md), with a report of its size, volume and topology.
#include <filesystem>
#include <iostream>

#include <nlohmann/json.hpp>

#include "api/Stopwatch.hpp"
#include "app/Commands.hpp"
#include "app/HtmlReport.hpp"
#include "app/Inputs.hpp"
#include "app/NeighbourSeparationStep.hpp"
#include "app/OutputOptions.hpp"
#include "app/Progress.hpp"
#include "app/RoiReconstruction.hpp"
#include "app/StandardStreams.hpp"
#include "cl/WorkerRuntimes.hpp"
#include "geometry/OrderedParallel.hpp"
#include "io/dicom/RtStruct.hpp"
#include "io/files/JsonText.hpp"
#include "io/mesh/MeshIO.hpp"
#include "report/ExitCodes.hpp"
#include "report/ReconstructSettings.hpp"

namespace dfrecon::app {

namespace {

struct ReconstructArgs {
    std::string input, output, roi, reportPath;
    std::string neighbours = "independent";  // several ROIs: "independent", "report" or "apart"
    bool all = false, json = false;
    unsigned jobs = 0;  // ROIs at once; 0: defaultJobs()
    ReconstructSettings settings;
};

// Where the ROI with file stem `stem` goes: `single` for one ROI, else
// OUTPUT/STEM.EXT in the folder format (a folder's name gives no extension).
MeshOutput outputFor(const ReconstructArgs& args, const MeshOutput& single, const std::string& stem,
                     bool several) {
    namespace fs = std::filesystem;
    if (!several) return single;
    const MeshFormat format = args.settings.folderFormat();
    return {(fs::path(args.output) / (stem + meshFormatExtension(format))).string(), format};
}

// The HTML report's table: one row per ROI, from its --json report.
const std::vector<std::string> kRoiReportColumns{
    "roi", "volumeCc", "contourVolumeCc", "validSolid", "triangles", "seconds", "error"};

nlohmann::ordered_json roiReportRow(const nlohmann::ordered_json& report) {
    nlohmann::ordered_json row;
    for (const char* key :
         {"roi", "volumeCc", "contourVolumeCc", "validSolid", "triangles", "error"})
        row[key] = report.contains(key) ? report[key] : nlohmann::ordered_json();
    row["seconds"] = report.contains("seconds") ? report["seconds"].value("total", 0.0) : 0.0;
    return row;
}

void runReconstruct(const ReconstructArgs& args, const GlobalOptions& global) {
    namespace fs = std::filesystem;
    const Stopwatch watch;
    const ContourInput load = loadContours(args.input, global, onlyRoi(args.roi));
    const std::vector<const Roi*> rois = selectRois(load.contours, args.roi, args.all);
    // The colour an ROI is drawn in: the one `convert` gives it in an RTSTRUCT.
    const std::vector<Rgb> colours = displayColours(load.contours);
    auto colourOf = [&](const Roi& roi) {
        return colours[std::size_t(&roi - load.contours.rois.data())];
    };
    const bool several = rois.size() > 1 || (args.all && !isMeshOutputPath(args.output) &&
                                             !isStandardStream(args.output));
    MeshOutput single;
    if (several) {
        if (isStandardStream(args.output))
            throw std::invalid_argument("-o - takes one ROI's mesh; several ROIs need a folder");
        fs::create_directories(args.output);
    } else {
        single = meshOutput(args.output, args.settings.format, args.json);
    }
    const std::vector<std::string> stems = uniqueFileStems(rois);
    nlohmann::ordered_json reports = nlohmann::ordered_json::array();
    std::string invalid, failed;
    int firstFailure = 0;
    HtmlReport page;
    std::string leftOut;  // surfaces past the report's triangle budget
    // With several workers each ROI's own bar would fight for the line, so
    // the bar counts ROIs instead.
    const std::size_t jobs = jobsFor(args.jobs, rois.size());
    ocl::WorkerRuntimes runtimes(global.device, jobs);
    Progress overall("reconstructing " + std::to_string(rois.size()) + " ROIs",
                     jobs > 1 && !global.quiet);
    const RoiWriteOptions how{global.quiet, jobs <= 1, !args.reportPath.empty()};
    // The share of the bar the writing fills: all of it, or its second half
    // when every ROI is reconstructed first.
    double writtenFrom = 0;
    auto take = [&](std::size_t i, RoiOutcome outcome) {
        overall.finish();
        if (!args.json) reportStream(single.toStandardOutput()) << outcome.out << std::flush;
        std::cerr << outcome.err << std::flush;
        if (outcome.failure != 0) {
            failed += (failed.empty() ? "" : ", ") + rois[i]->name;
            if (firstFailure == 0) firstFailure = outcome.failure;
        } else if (outcome.invalid) {
            invalid += (invalid.empty() ? "" : ", ") + rois[i]->name;
        }
        if (!args.reportPath.empty() && outcome.failure == 0 &&
            !addSurface(page, {rois[i]->name, colourOf(*rois[i]), std::move(outcome.surface), {}}))
            leftOut += (leftOut.empty() ? "" : ", ") + rois[i]->name;
        reports.push_back(std::move(outcome.report));
        overall.update(writtenFrom + (1 - writtenFrom) * double(i + 1) / double(rois.size()));
    };
    // With several ROIs one that fails is reported and the rest go on.
    auto failedOrThrow = [&](std::size_t i) {
        if (!several) throw;
        return failedRoi(*rois[i], std::current_exception());
    };
    nlohmann::ordered_json neighbours = nullptr;
    if (several && args.neighbours != "independent") {
        // Every ROI first, then the neighbours kept apart, then the files.
        std::vector<std::optional<RoiSurface>> surfaces(rois.size());
        std::vector<std::optional<RoiOutcome>> failures(rois.size());
        std::vector<double> seconds(rois.size(), 0.0);
        forEachInOrder(
            rois.size(), jobs,
            [&](std::size_t i, std::size_t worker) {
                const Stopwatch roiWatch;
                try {
                    if (rois[i]->defect) throw *rois[i]->defect;
                    RoiSurface surface = reconstructForWriting(runtimes[worker], *rois[i],
                                                               args.settings, how, false);
                    seconds[i] = roiWatch.total();
                    return std::pair(std::optional(std::move(surface)),
                                     std::optional<RoiOutcome>());
                } catch (...) {
                    return std::pair(std::optional<RoiSurface>(), std::optional(failedOrThrow(i)));
                }
            },
            [&](std::size_t i, auto done) {
                surfaces[i] = std::move(done.first);
                failures[i] = std::move(done.second);
                overall.update(0.5 * double(i + 1) / double(rois.size()));
            });
        neighbours =
            neighbourSeparationJson(runtimes[0], rois, surfaces, args.neighbours == "apart");
        writtenFrom = 0.5;
        forEachInOrder(
            rois.size(), jobs,
            [&](std::size_t i, std::size_t worker) {
                if (failures[i]) return std::move(*failures[i]);
                const Stopwatch roiWatch;
                try {
                    simplifyForWriting(runtimes[worker], *rois[i], *surfaces[i], args.settings,
                                       how);
                    RoiOutcome outcome = writeReconstructedRoi(
                        *rois[i], std::move(*surfaces[i]),
                        outputFor(args, single, stems[i], several), load, args.settings, how);
                    outcome.report["seconds"]["total"] = seconds[i] + roiWatch.total();
                    return outcome;
                } catch (...) {
                    return failedOrThrow(i);
                }
            },
            take);
    } else {
        forEachInOrder(
            rois.size(), jobs,
            [&](std::size_t i, std::size_t worker) {
                try {
                    if (rois[i]->defect) throw *rois[i]->defect;
                    const Stopwatch roiWatch;
                    RoiOutcome outcome = writeRoiSurface(runtimes[worker], *rois[i],
                                                         outputFor(args, single, stems[i], several),
                                                         load, args.settings, how);
                    outcome.report["seconds"]["total"] = roiWatch.total();
                    return outcome;
                } catch (...) {
                    return failedOrThrow(i);
                }
            },
            take);
    }
    overall.finish();
    if (!neighbours.is_null() && !args.json)
        reportStream(single.toStandardOutput()) << neighbourSeparationLine(neighbours);
    if (!args.reportPath.empty()) {
        page.title = "dfrecon reconstruct " + fs::path(args.input).filename().string();
        page.columns = kRoiReportColumns;
        if (!leftOut.empty())
            page.note = "Not drawn (more than " + std::to_string(kMaxReportTriangles) +
                        " triangles in all): " + leftOut + ".";
        for (const nlohmann::ordered_json& report : reports)
            page.rows.push_back(roiReportRow(report));
        writeHtmlReport(args.reportPath, page);
    }
    const ocl::Runtime& runtime = runtimes.first();
    nlohmann::ordered_json empty = nlohmann::ordered_json::array();
    if (args.all)
        for (const Roi& roi : load.contours.rois)
            if (roi.slices.empty() && !roi.defect) empty.push_back(roi.name);
    // ROIs with no closed contour (points, markers, contours of no area)
    // are listed, not failures: no voxel tool fills them either.
    if (!empty.empty() && !global.quiet && !args.json) {
        std::string names;
        for (const auto& name : empty)
            names += (names.empty() ? "" : ", ") + name.get<std::string>();
        std::cerr << "dfrecon: no closed contour, nothing written: " << names << "\n";
    }
    if (args.json)
        std::cout << jsonText(nlohmann::ordered_json{{"command", "reconstruct"},
                                                     {"input", args.input},
                                                     {"format", contourFormatName(load.format)},
                                                     {"device", runtime.device().deviceName},
                                                     {"maxDepth", args.settings.options.maxDepth},
                                                     {"contourErrorMm",
                                                      args.settings.options.contourErrorMm},
                                                     {"seconds", watch.total()},
                                                     {"rois", reports},
                                                     {"emptyRois", empty},
                                                     {"neighbours", neighbours}},
                              2)
                  << "\n";
    if (!failed.empty())
        throw ItemsFailed("failed: " + failed +
                              (invalid.empty() ? "" : "; not a valid closed solid: " + invalid) +
                              " (the other ROIs were done)",
                          firstFailure);
    if (!invalid.empty())
        throw InvalidResult("not a valid closed solid: " + invalid +
                            (args.settings.allowInvalid
                                 ? " (written anyway: --allow-invalid)"
                                 : " (not written; --allow-invalid writes it)"));
}

}  // namespace

void addReconstructCommand(CLI::App& root, const GlobalOptions& global) {
    auto args = std::make_shared<ReconstructArgs>();
    CLI::App* cmd = root.add_subcommand(
        "reconstruct", "Reconstruct a closed triangle surface from the contours of an ROI");
    cmd->footer(
        "One ROI: OUT is a mesh file (.ply .stl .obj .off .vtk .vtp). Several ROIs (--all): OUT "
        "is a folder that gets NAME.ply per ROI (NAME_NUMBER.ply where names repeat; --format "
        "picks another format). Every format but OFF names the ROI, and PLY, OBJ (with "
        "NAME.mtl beside it), VTK and VTP carry its colour where the contours give one "
        "(docs/formats.md). Coordinates "
        "are the contours' (DICOM: patient LPS mm; sagittal, coronal and oblique stacks are "
        "reconstructed in their planes and written back in patient space). Contour points "
        "are mesh vertices; normals point "
        "outward. Caps: 'flat' closes each end contour with a flat lid at the cap offset whose "
        "rim follows the side's narrowing at the end plane, the parabola through the last two "
        "slabs "
        "(contours on a pixel lattice, from voxels: a vertical wall, as the last voxel layer), so "
        "straight sides give exactly the volume planning systems count (area x spacing per "
        "slice); 'dome' rises from the contour to the cap offset (rounder ends; more volume than "
        "'flat' where an end narrows fast); 'none' leaves the ends open. Every "
        "surface is checked as the file will hold it (floats); one that is not a valid closed "
        "solid is reported with the slabs where it fails and not written (unless "
        "--allow-invalid). Exit codes: 0 done, 1 usage, 2 bad input, 3 runtime failure, 4 a "
        "surface is not a valid closed solid. See docs/reconstruction.md.");
    cmd->add_option("file", args->input, contourInputHelp())->required();
    cmd->add_option("-o,--output", args->output,
                    "Output mesh file, - for standard output (with --format), or folder with "
                    "--all")
        ->required();
    cmd->add_option("--roi", args->roi,
                    "ROI name, or DICOM ROI number (default: the only ROI of the file)");
    cmd->add_flag("--all", args->all, "Every ROI of the file that has contours");
    addReconstructSettingsOptions(*cmd, args->settings);
    cmd->add_option("--neighbours", args->neighbours,
                    "Several ROIs: 'independent' reconstructs each ROI on its own, as one ROI "
                    "alone; 'report' also finds the pairs whose contours overlap on no plane "
                    "but whose surfaces overlap between the planes and measures each overlap "
                    "exactly, mm3 (--json: neighbours; all surfaces are held until then); "
                    "'apart' moves those surfaces out of each other first (each vertex inside a "
                    "neighbour halfway to it, or all the way where the neighbour has none in "
                    "the overlap, and 0.01 mm beyond, in two rounds; a triangle passing "
                    "through a neighbour is split at its centroid, whose vertex moves likewise; "
                    "contour points stay "
                    "vertices; a move that would make a surface cross itself is undone) and "
                    "reports the overlap left. See docs/reconstruction.md, 'Neighbours'")
        ->capture_default_str()
        ->check(CLI::IsMember({"independent", "report", "apart"}));
    cmd->add_option("-j,--jobs", args->jobs,
                    "ROIs reconstructed at once, each with its own OpenCL queue (default 0: one "
                    "per CPU core; never more than one per core or per ROI; 1: one after the "
                    "other, each with its own "
                    "progress bar). Results and reports come in ROI order either way")
        ->capture_default_str()
        ->check(CLI::Range(0, 256));
    cmd->add_option("--report", args->reportPath,
                    "Also write REPORT.html: one self-contained page (no network needed to "
                    "open it) with the ROI table (volume, contour volume, validity, "
                    "triangles, seconds) beside an interactive 3D view of the surfaces in "
                    "their ROI colours (three.js, embedded)");
    cmd->add_flag("--json", args->json, "Print a JSON report instead of text");
    asOutput(cmd->get_option("--output"), OutputKind::FileOrFolder);
    asOutput(cmd->get_option("--report"), OutputKind::File);
    cmd->callback([args, &global] { runReconstruct(*args, global); });
}

}  // namespace dfrecon::app
