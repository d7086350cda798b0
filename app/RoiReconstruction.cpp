#include "app/RoiReconstruction.hpp"

#include <mutex>
#include <optional>
#include <sstream>

#include "api/Stopwatch.hpp"
#include "app/EnumNames.hpp"
#include "app/Failure.hpp"
#include "app/Progress.hpp"
#include "app/Reports.hpp"
#include "app/SimplifyReport.hpp"
#include "geometry/MeshCheck.hpp"
#include "io/MeshIO.hpp"
#include "io/RtStruct.hpp"

namespace dfrecon::app {

namespace {

// OpenMesh's writers are process-wide singletons; ROIs reconstructed at once
// write one at a time.
std::mutex meshWriting;

}  // namespace

StructureTag structureTagOf(const Roi& roi) {
    return StructureTag{roi.name, roi.colour};
}

RoiOutcome failedRoi(const Roi& roi, std::exception_ptr error) {
    Failure failure = describeFailure(error);
    // The command line was read before any ROI: what one ROI's
    // reconstruction refuses as an argument is that ROI's data.
    if (failure.exitCode == kExitUsage) failure.exitCode = kExitBadInput;
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

namespace {

// Where the ROI ends and starts again (contours/PlaneGaps): [below, above]
// of each gap, in the plane frame's mm.
nlohmann::ordered_json planeGapsJson(const Roi& roi) {
    nlohmann::ordered_json gaps = nlohmann::ordered_json::array();
    for (std::size_t i : roi.restartsAt) gaps.push_back({roi.slices[i - 1].zMm, roi.slices[i].zMm});
    return gaps;
}

}  // namespace

nlohmann::ordered_json roiReport(const Roi& roi, const RoiSurface& result,
                                 const RtStructRoiInfo* dicom, const ReconstructSettings& settings,
                                 const RoiWriting& writing,
                                 const nlohmann::ordered_json& simplification) {
    const ReconstructionStats& s = result.stats;
    const MeshCheckReport& check = result.check;
    const double contourVolume = result.contourVolumeMm3;
    const std::optional<const char*> holes =
        dicom ? std::optional(nameOf(kHoleConventionNames, dicom->holes)) : std::nullopt;
    nlohmann::ordered_json broken = nlohmann::ordered_json::array();
    for (const auto& [below, above] : result.brokenPieces) broken.push_back({below, above});
    nlohmann::ordered_json report{{"roi", roi.name},
                                  {"roiNumber", valueOrNull(roi.number)},
                                  {"output", valueOrNull(writing.written, writing.path)},
                                  {"written", writing.written}};
    appendItems(report, meshCheckJson(check));
    appendItems(report,
                {{"contourVolumeMm3", contourVolume},
                 {"contourVolumeCc", contourVolume / 1000},
                 {"brokenSlabsMm", broken},
                 {"touchesOpened", s.touchesOpened},
                 {"piecesClosedAgain", s.repairedPieces},
                 {"facesRefusedByOpenMesh", writing.refusedFaces},
                 {"slices", s.slices},
                 {"pieces", s.runs},
                 {"planesLeftEmptyMm", planeGapsJson(roi)},
                 {"planes", roi.frame.orientationName()},
                 {"holeConvention", valueOrNull(holes)},
                 {"contourReading", contourReadingJson(roi.reading)},
                 {"slabThicknessMm", valueOrNull(roi.slabThicknessMm > 0, roi.slabThicknessMm)},
                 {"contourPoints", s.contourPoints},
                 {"pixelMm", s.pixelMm},
                 {"cap", nameOf(kCapModeNames, settings.options.cap)},
                 {"interpolation", nameOf(kInterpolationNames, settings.options.interpolation)},
                 {"smoothedVertices", s.smoothedVertices},
                 {"smoothUnbentVertices", s.smoothUnbentVertices},
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
                   {"check", result.checkSeconds},
                   {"smooth", s.smoothSeconds},
                   {"write", writing.seconds}}}});
    return report;
}

RoiOutcome writeRoiSurface(ocl::Runtime& runtime, const Roi& roi, const MeshOutput& output,
                           const ContourInput& input, const ReconstructSettings& settings,
                           const RoiWriteOptions& how) {
    RoiOutcome outcome;
    std::ostringstream out, err;
    RoiSurface result;
    {
        // One progress line per stage: reconstructing, then simplifying.
        std::optional<Progress> progress;
        std::string stage;
        RoiReconstructOptions options{settings.options, settings.maxErrorMm};
        result = dfrecon::reconstructRoi(
            runtime, roi, options, [&](const std::string& now, double fraction) {
                if (now != stage) {
                    progress.reset();
                    progress.emplace(now + " " + roi.name, how.showProgress && !how.quiet);
                    stage = now;
                }
                if (fraction >= 0) progress->update(fraction);
            });
    }
    const nlohmann::ordered_json simplification =
        result.simplification
            ? simplificationJson(*result.simplification, SimplifyOptions{settings.maxErrorMm}, true)
            : nlohmann::ordered_json(nullptr);
    const MeshCheckReport& check = result.check;
    // Open ends are what --cap none asks for; anything else broken is not a
    // result (exit 4), and is written only when the user allows it.
    const bool valid = result.usable(settings.options.cap);
    const bool written = valid || settings.allowInvalid;
    Stopwatch watch;
    std::size_t refused = 0;
    if (written) {
        TriMesh mesh = toTriMesh(result.surface, &refused);
        // The mesh holds the surface now (the bone of the head CT: 66 MB of
        // soup beside OpenMesh's 2.8 M faces while they are written).
        if (!how.keepSurface) result.surface = {};
        MeshWriteOptions write;
        write.binary = !settings.ascii;
        write.structure = structureTagOf(roi);
        const std::lock_guard<std::mutex> lock(meshWriting);
        writeMeshOutput(std::move(mesh), output, write);
    }
    const double writeSeconds = watch.lap();

    const double contourVolume = result.contourVolumeMm3;
    {
        out << roi.name << ": " << check.vertices << " vertices, " << check.triangles
            << " triangles, volume " << check.volumeMm3 / 1000 << " cc (contours "
            << contourVolume / 1000 << " cc), "
            << (check.validSolid() ? "closed valid solid" : "NOT a valid closed solid");
        if (check.genus >= 0) out << ", genus " << check.genus;
        out << (written ? " -> " + output.label() : std::string(", not written")) << "\n";
    }
    if (!valid && !how.quiet) {
        err << "dfrecon: " << roi.name << ": not a valid closed solid between z =";
        for (const auto& [below, above] : result.brokenPieces)
            err << " [" << below << ", " << above << "]";
        err << " mm (plane frame)"
            << (written ? "; written anyway (--allow-invalid)" : "; not written") << "\n";
    }
    RoiWriting writing{output.path, written, refused, writeSeconds};
    nlohmann::ordered_json report =
        roiReport(roi, result, input.dicomInfo(roi), settings, writing, simplification);
    outcome.invalid = !valid;
    outcome.report = std::move(report);
    if (how.keepSurface) outcome.surface = std::move(result.surface);
    outcome.out = out.str();
    outcome.err = err.str();
    return outcome;
}

}  // namespace dfrecon::app
