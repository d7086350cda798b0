// dfrecon reconstruct IN.slices -o OUT: contours to a closed surface
// (docs/reconstruction.md), with a report of its size, volume and topology.
#include <filesystem>
#include <iostream>
#include <memory>
#include <mutex>
#include <optional>
#include <sstream>

#include <nlohmann/json.hpp>

#include "app/Commands.hpp"
#include "app/EnumNames.hpp"
#include "app/ExitCodes.hpp"
#include "app/Failure.hpp"
#include "app/Inputs.hpp"
#include "app/NumberChecks.hpp"
#include "app/OrderedParallel.hpp"
#include "app/Progress.hpp"
#include "app/Reports.hpp"
#include "app/SimplifyReport.hpp"
#include "app/StandardStreams.hpp"
#include "app/Stopwatch.hpp"
#include "geometry/MeshCheck.hpp"
#include "io/MeshIO.hpp"
#include "io/RtStruct.hpp"
#include "recon/Reconstruction.hpp"

namespace dfrecon::app {

namespace {

struct ReconstructArgs {
    std::string input, output, roi, format,
        capName = nameOf(kCapModeNames, CapMode::Flat),
        interpolationName = nameOf(kInterpolationNames, Interpolation::Linear);
    bool all = false, json = false, ascii = false, allowInvalid = false;
    unsigned jobs = 0;      // ROIs at once; 0: defaultJobs()
    double maxErrorMm = 0;  // 0: no simplification
    ReconstructionOptions options;
};

// Where the ROI with file stem `stem` goes: `single` for one ROI, else
// OUTPUT/STEM.ply (the folder's name cannot give an extension).
MeshOutput outputFor(const ReconstructArgs& args, const MeshOutput& single, const std::string& stem,
                     bool several) {
    namespace fs = std::filesystem;
    if (!several) return single;
    return {(fs::path(args.output) / (stem + ".ply")).string(), ".ply"};
}

/// What one ROI gives: its report and the lines it prints, held until the
/// command prints them in ROI order.
struct RoiOutcome {
    nlohmann::ordered_json report;
    std::string out, err;  // for stdout and stderr
    int failure = 0;       // exit code of the error that stopped this ROI, 0 if none
};

/// The outcome of an ROI that failed: reported, and the others go on.
RoiOutcome failedRoi(const Roi& roi, std::exception_ptr error) {
    const Failure failure = describeFailure(error);
    RoiOutcome outcome;
    outcome.failure = failure.exitCode;
    outcome.err = "dfrecon: ROI '" + roi.name + "': " + failure.message + "\n";
    outcome.report = {{"roi", roi.name},
                      {"roiNumber", valueOrNull(roi.number)},
                      {"output", nullptr},
                      {"written", false},
                      {"validSolid", false},
                      {"error", failure.message},
                      {"exitCode", failure.exitCode}};
    return outcome;
}

// OpenMesh's writers are process-wide singletons; ROIs reconstructed at once
// write one at a time.
std::mutex meshWriting;

RoiOutcome reconstructRoi(ocl::Runtime& runtime, const Roi& roi, const MeshOutput& output,
                          const ContourInput& input, const ReconstructArgs& args,
                          const GlobalOptions& global, bool showProgress) {
    RoiOutcome outcome;
    std::ostringstream out, err;
    Reconstruction result;
    {
        Progress progress("reconstructing " + roi.name, showProgress && !global.quiet);
        result =
            reconstructSurface(runtime, roi, args.options, [&](double f) { progress.update(f); });
    }
    // Sagittal, coronal and oblique stacks were reconstructed in their planes.
    toPatient(result.surface, roi.frame);
    nlohmann::ordered_json simplification = nullptr;
    if (args.maxErrorMm > 0) {
        SimplifyRequest request;
        request.options.maxErrorMm = args.maxErrorMm;
        request.contours = &roi;
        request.label = "simplifying " + roi.name;
        GlobalOptions options = global;
        options.quiet = global.quiet || !showProgress;  // simplifyAndVerify says nothing else
        simplification = simplifyAndVerify(runtime, result.surface, request, options);
    }
    // The reconstruction checked its surface as floats in the plane frame;
    // a rotated frame or a simplified surface is checked again as written.
    roundPointsToFloat(result.surface);
    Stopwatch watch;
    const MeshCheckReport check = simplification.is_null() && roi.frame.isIdentity()
                                      ? result.check
                                      : checkMesh(result.surface);
    const double checkSeconds = watch.lap() + result.stats.checkSeconds;
    // Open ends are what --cap none asks for; anything else broken is not a
    // result (exit 4), and is written only when the user allows it.
    const bool valid = check.validSolid() || args.options.cap == CapMode::None;
    const bool written = valid || args.allowInvalid;
    std::size_t refused = 0;
    if (written) {
        const TriMesh mesh = toTriMesh(result.surface, &refused);
        MeshWriteOptions write;
        write.binary = !args.ascii;
        const std::lock_guard<std::mutex> lock(meshWriting);
        writeMeshOutput(mesh, output, write);
    }
    const double writeSeconds = watch.lap();

    const ReconstructionStats& s = result.stats;
    const double contourVolume = contourVolumeMm3(roi);
    if (!args.json) {
        out << roi.name << ": " << check.vertices << " vertices, " << check.triangles
            << " triangles, volume " << check.volumeMm3 / 1000 << " cc (contours "
            << contourVolume / 1000 << " cc), "
            << (check.validSolid() ? "closed valid solid" : "NOT a valid closed solid");
        if (check.genus >= 0) out << ", genus " << check.genus;
        out << (written ? " -> " + output.label() : std::string(", not written")) << "\n";
    }
    if (!valid && !global.quiet) {
        err << "dfrecon: " << roi.name << ": not a valid closed solid between z =";
        for (const auto& [below, above] : result.brokenPieces)
            err << " [" << below << ", " << above << "]";
        err << " mm (plane frame)"
            << (written ? "; written anyway (--allow-invalid)" : "; not written") << "\n";
    }
    const RtStructRoiInfo* dicom = input.dicomInfo(roi);
    const std::optional<const char*> holes =
        dicom ? std::optional(nameOf(kHoleConventionNames, dicom->holes)) : std::nullopt;
    nlohmann::ordered_json broken = nlohmann::ordered_json::array();
    for (const auto& [below, above] : result.brokenPieces) broken.push_back({below, above});
    nlohmann::ordered_json report{{"roi", roi.name},
                                  {"roiNumber", valueOrNull(roi.number)},
                                  {"output", valueOrNull(written, output.path)},
                                  {"written", written}};
    appendItems(report, meshCheckJson(check));
    appendItems(report,
                {{"contourVolumeMm3", contourVolume},
                 {"contourVolumeCc", contourVolume / 1000},
                 {"brokenSlabsMm", broken},
                 {"touchesOpened", s.touchesOpened},
                 {"piecesClosedAgain", s.repairedPieces},
                 {"facesRefusedByOpenMesh", refused},
                 {"slices", s.slices},
                 {"planes", roi.frame.orientationName()},
                 {"holeConvention", valueOrNull(holes)},
                 {"slabThicknessMm", valueOrNull(roi.slabThicknessMm > 0, roi.slabThicknessMm)},
                 {"contourPoints", s.contourPoints},
                 {"pixelMm", s.pixelMm},
                 {"cap", nameOf(kCapModeNames, args.options.cap)},
                 {"interpolation", nameOf(kInterpolationNames, args.options.interpolation)},
                 {"smoothedVertices", s.smoothedVertices},
                 {"smoothKeptLinearPieces", s.smoothRevertedPieces},
                 {"smoothFellBackToLinear", s.smoothFellBack},
                 {"strips", s.strips},
                 {"rejectedStrips", s.rejectedStrips},
                 {"intermediateLayers", s.recursions},
                 {"deepestLevel", s.deepestLevel},
                 {"closedAtDepthLimit", s.limitClosings},
                 {"endContours", s.caps},
                 {"slabsClosedAsPrisms", s.fallbackSlabs},
                 {"simplification", simplification},
                 {"seconds",
                  {{"simplify", s.simplifySeconds},
                   {"fields", s.fieldsSeconds},
                   {"medialAxes", s.medialSeconds},
                   {"triangulation", s.triangulationSeconds},
                   {"check", checkSeconds},
                   {"write", writeSeconds}}}});
    outcome.report = std::move(report);
    outcome.out = out.str();
    outcome.err = err.str();
    return outcome;
}

void runReconstruct(const ReconstructArgs& args, const GlobalOptions& global) {
    namespace fs = std::filesystem;
    const Stopwatch watch;
    const ContourInput load = loadContours(args.input, global);
    const std::vector<const Roi*> rois = selectRois(load.contours, args.roi, args.all);
    const bool several = rois.size() > 1 || (args.all && !isMeshExtension(args.output) &&
                                             !isStandardStream(args.output));
    MeshOutput single;
    if (several) {
        if (isStandardStream(args.output))
            throw std::invalid_argument("-o - takes one ROI's mesh; several ROIs need a folder");
        if (!args.format.empty())
            throw std::invalid_argument("--format is for -o -; several ROIs are written as .ply");
        fs::create_directories(args.output);
    } else {
        single = meshOutput(args.output, args.format, args.json);
    }
    const std::vector<std::string> stems = uniqueFileStems(rois);
    nlohmann::ordered_json reports = nlohmann::ordered_json::array();
    std::string invalid, failed;
    int firstFailure = 0;
    // One OpenCL queue per worker: a shared in-order queue would make each
    // ROI wait for the other's kernels. With several workers each ROI's own
    // bar would fight for the line, so the bar counts ROIs instead.
    const std::size_t jobs =
        args.jobs > 0 ? std::min<std::size_t>(args.jobs, rois.size()) : defaultJobs(rois.size());
    std::vector<std::unique_ptr<ocl::Runtime>> runtimes(std::max<std::size_t>(1, jobs));
    runtimes[0] = std::make_unique<ocl::Runtime>(global.device);
    Progress overall("reconstructing " + std::to_string(rois.size()) + " ROIs",
                     jobs > 1 && !global.quiet);
    forEachInOrder(
        rois.size(), jobs,
        [&](std::size_t i, std::size_t worker) {
            // With several ROIs one that fails is reported and the rest go on.
            try {
                if (rois[i]->defect) throw *rois[i]->defect;
                if (!runtimes[worker])
                    runtimes[worker] = std::make_unique<ocl::Runtime>(global.device);
                return reconstructRoi(*runtimes[worker], *rois[i],
                                      outputFor(args, single, stems[i], several), load, args,
                                      global, jobs <= 1);
            } catch (...) {
                if (!several) throw;
                return failedRoi(*rois[i], std::current_exception());
            }
        },
        [&](std::size_t i, RoiOutcome outcome) {
            overall.finish();
            reportStream(single.toStandardOutput()) << outcome.out << std::flush;
            std::cerr << outcome.err << std::flush;
            if (outcome.failure != 0) {
                failed += (failed.empty() ? "" : ", ") + rois[i]->name;
                if (firstFailure == 0) firstFailure = outcome.failure;
            } else if (!outcome.report["validSolid"].get<bool>() &&
                       args.options.cap != CapMode::None) {
                invalid += (invalid.empty() ? "" : ", ") + rois[i]->name;
            }
            reports.push_back(std::move(outcome.report));
            overall.update(double(i + 1) / double(rois.size()));
        });
    overall.finish();
    const ocl::Runtime& runtime = *runtimes[0];
    nlohmann::ordered_json empty = nlohmann::ordered_json::array();
    if (args.all)
        for (const Roi& roi : load.contours.rois)
            if (roi.slices.empty()) empty.push_back(roi.name);
    if (args.json)
        std::cout << nlohmann::ordered_json{{"command", "reconstruct"},
                                            {"input", args.input},
                                            {"format", load.format},
                                            {"device", runtime.device().deviceName},
                                            {"maxDepth", args.options.maxDepth},
                                            {"contourErrorMm", args.options.contourErrorMm},
                                            {"seconds", watch.total()},
                                            {"rois", reports},
                                            {"emptyRois", empty}}
                         .dump(2)
                  << "\n";
    if (!failed.empty())
        throw ItemsFailed("failed: " + failed +
                              (invalid.empty() ? "" : "; not a valid closed solid: " + invalid) +
                              " (the other ROIs were done)",
                          firstFailure);
    if (!invalid.empty())
        throw InvalidResult("not a valid closed solid: " + invalid +
                            (args.allowInvalid ? " (written anyway: --allow-invalid)"
                                               : " (not written; --allow-invalid writes it)"));
}

}  // namespace

void addReconstructCommand(CLI::App& root, const GlobalOptions& global) {
    auto args = std::make_shared<ReconstructArgs>();
    CLI::App* cmd = root.add_subcommand(
        "reconstruct", "Reconstruct a closed triangle surface from the contours of an ROI");
    cmd->footer(
        "One ROI: OUT is a mesh file (.ply .stl .obj .off). Several ROIs (--all): OUT is a "
        "folder that gets NAME.ply per ROI (NAME_NUMBER.ply where names repeat). Coordinates "
        "are the contours' (DICOM: patient LPS mm; sagittal, coronal and oblique stacks are "
        "reconstructed in their planes and written back in patient space). Contour points "
        "are mesh vertices; normals point "
        "outward. Caps: 'flat' closes each end contour with a flat lid at the cap offset whose "
        "rim continues the side's slope from the last slab, so straight sides give exactly the "
        "volume planning systems count (area x spacing per slice); 'dome' rises from the contour "
        "to the cap offset (less volume, rounder ends); 'none' leaves the ends open. Every "
        "surface is checked as the file will hold it (floats); one that is not a valid closed "
        "solid is reported with the slabs where it fails and not written (unless "
        "--allow-invalid). Exit codes: 0 done, 1 usage, 2 bad input, 3 runtime failure, 4 a "
        "surface is not a valid closed solid. See docs/reconstruction.md.");
    cmd->add_option("file", args->input,
                    "Input contours: .slices (- reads it from standard input) or DICOM RTSTRUCT "
                    "(.dcm)")
        ->required();
    cmd->add_option("-o,--output", args->output,
                    "Output mesh file, - for standard output (with --format), or folder with "
                    "--all")
        ->required();
    addMeshFormatOption(*cmd, args->format);
    cmd->add_option("--roi", args->roi,
                    "ROI name, or DICOM ROI number (default: the only ROI of the file)");
    cmd->add_flag("--all", args->all, "Every ROI of the file that has contours");
    cmd->add_option("--pixel-mm", args->options.pixelMm,
                    "Field pixel size in mm (default 0: the ROI's extent plus margin fits 256 px)")
        ->capture_default_str()
        ->check(kNonNegative);
    cmd->add_option("--contour-error", args->options.contourErrorMm,
                    "Simplify contours first so every original point stays within this many mm "
                    "(0 = keep every point)")
        ->capture_default_str()
        ->check(kNonNegative);
    cmd->add_option("--max-depth", args->options.maxDepth,
                    "Recursion levels for branching regions; at the limit what is left is closed "
                    "by a step of spacing / 2^(depth+1)")
        ->capture_default_str()
        ->check(CLI::Range(0, 12));
    cmd->add_option("--cap", args->capName, "End caps: flat, dome or none")
        ->capture_default_str()
        ->check(CLI::IsMember(namesOf(kCapModeNames)));
    cmd->add_option("--interpolation", args->interpolationName,
                    "Between planes: 'linear' runs straight from contour to contour; 'smooth' "
                    "bends the strips onto a monotone cubic in z of the planes' distance fields "
                    "(C1 across planes, still through every contour point, still a valid solid: "
                    "a slab where bending would break it stays linear)")
        ->capture_default_str()
        ->check(CLI::IsMember(namesOf(kInterpolationNames)));
    cmd->add_option("--smooth-tolerance", args->options.smoothToleranceMm,
                    "Smooth mode: strips are halved in z until no straight edge strays farther "
                    "than this from the smooth surface, mm")
        ->capture_default_str()
        ->check(kPositive);
    cmd->add_option("--cap-offset", args->options.capOffsetMm,
                    "How far beyond an end contour its cap reaches, mm (default: half the DICOM "
                    "contour slab thickness if given, else half the slice spacing; at most half "
                    "the gap to the next slice)")
        ->check(kNonNegative);
    cmd->add_option("--max-error", args->maxErrorMm,
                    "Then simplify with this two-sided bound in mm, as dfrecon simplify does "
                    "(0 = keep every triangle); the report gives the certified bound and the "
                    "verified distance to the full surface and the contours")
        ->capture_default_str()
        ->check(kNonNegative);
    cmd->add_flag("--allow-invalid", args->allowInvalid,
                  "Write a surface that is not a valid closed solid anyway (it is reported, "
                  "and the exit code is still 4)");
    cmd->add_option("-j,--jobs", args->jobs,
                    "ROIs reconstructed at once, each with its own OpenCL queue (default 0: one "
                    "per CPU core, at most one per ROI; 1: one after the other, each with its own "
                    "progress bar). Results and reports come in ROI order either way")
        ->capture_default_str()
        ->check(CLI::Range(0, 256));
    cmd->add_flag("--ascii", args->ascii, "ASCII PLY/STL instead of binary");
    cmd->add_flag("--json", args->json, "Print a JSON report instead of text");
    cmd->callback([args, &global] {
        args->options.cap = parseEnum(kCapModeNames, args->capName, "--cap");
        args->options.interpolation =
            parseEnum(kInterpolationNames, args->interpolationName, "--interpolation");
        runReconstruct(*args, global);
    });
}

}  // namespace dfrecon::app
