#include "app/RoiReconstruction.hpp"

#include <mutex>
#include <optional>
#include <sstream>

#include "app/EnumNames.hpp"
#include "app/Failure.hpp"
#include "app/Progress.hpp"
#include "app/Reports.hpp"
#include "app/SimplifyReport.hpp"
#include "app/Stopwatch.hpp"
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

RoiOutcome reconstructRoi(ocl::Runtime& runtime, const Roi& roi, const MeshOutput& output,
                          const ContourInput& input, const ReconstructSettings& settings,
                          const GlobalOptions& global, bool showProgress) {
    RoiOutcome outcome;
    std::ostringstream out, err;
    Reconstruction result;
    {
        Progress progress("reconstructing " + roi.name, showProgress && !global.quiet);
        result = reconstructSurface(runtime, roi, settings.options,
                                    [&](double f) { progress.update(f); });
    }
    // Sagittal, coronal and oblique stacks were reconstructed in their planes.
    toPatient(result.surface, roi.frame);
    nlohmann::ordered_json simplification = nullptr;
    if (settings.maxErrorMm > 0) {
        SimplifyRequest request;
        request.options.maxErrorMm = settings.maxErrorMm;
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
    const bool valid = check.validSolid() || settings.options.cap == CapMode::None;
    const bool written = valid || settings.allowInvalid;
    std::size_t refused = 0;
    if (written) {
        const TriMesh mesh = toTriMesh(result.surface, &refused);
        MeshWriteOptions write;
        write.binary = !settings.ascii;
        write.structure = structureTagOf(roi);
        const std::lock_guard<std::mutex> lock(meshWriting);
        writeMeshOutput(mesh, output, write);
    }
    const double writeSeconds = watch.lap();

    const ReconstructionStats& s = result.stats;
    const double contourVolume = contourVolumeMm3(roi);
    {
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
                   {"check", checkSeconds},
                   {"write", writeSeconds}}}});
    outcome.invalid = !valid;
    outcome.report = std::move(report);
    outcome.surface = std::move(result.surface);
    outcome.out = out.str();
    outcome.err = err.str();
    return outcome;
}

}  // namespace dfrecon::app
