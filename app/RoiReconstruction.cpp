#include "app/RoiReconstruction.hpp"

#include <mutex>
#include <optional>
#include <sstream>

#include "api/Stopwatch.hpp"
#include "app/Progress.hpp"
#include "app/SimplifyAndVerify.hpp"
#include "geometry/MeshCheck.hpp"
#include "io/dicom/RtStruct.hpp"
#include "io/mesh/MeshIO.hpp"
#include "report/EnumNames.hpp"
#include "report/Failure.hpp"
#include "report/Reports.hpp"

namespace dfrecon::app {

namespace {

// OpenMesh's writers are process-wide singletons; ROIs reconstructed at once
// write one at a time.
std::mutex meshWriting;

}  // namespace

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

RoiSurface reconstructForWriting(ocl::Runtime& runtime, const Roi& roi,
                                 const ReconstructSettings& settings, const RoiWriteOptions& how,
                                 bool simplify) {
    // One progress line per stage: reconstructing, then simplifying.
    std::optional<Progress> progress;
    std::string stage;
    RoiReconstructOptions options{settings.options, simplify ? settings.maxErrorMm : 0};
    return dfrecon::reconstructRoi(
        runtime, roi, options, [&](const std::string& now, double fraction) {
            if (now != stage) {
                progress.reset();
                progress.emplace(now + " " + roi.name, how.showProgress && !how.quiet);
                stage = now;
            }
            if (fraction >= 0) progress->update(fraction);
        });
}

RoiOutcome writeRoiSurface(ocl::Runtime& runtime, const Roi& roi, const MeshOutput& output,
                           const ContourInput& input, const ReconstructSettings& settings,
                           const RoiWriteOptions& how) {
    return writeReconstructedRoi(roi, reconstructForWriting(runtime, roi, settings, how, true),
                                 output, input, settings, how);
}

void simplifyForWriting(ocl::Runtime& runtime, const Roi& roi, RoiSurface& result,
                        const ReconstructSettings& settings, const RoiWriteOptions& how) {
    if (!(settings.maxErrorMm > 0) || result.simplification) return;
    Progress progress("simplifying " + roi.name, how.showProgress && !how.quiet);
    simplifyRoiSurface(runtime, roi, result, settings.maxErrorMm);
}

RoiOutcome writeReconstructedRoi(const Roi& roi, RoiSurface result, const MeshOutput& output,
                                 const ContourInput& input, const ReconstructSettings& settings,
                                 const RoiWriteOptions& how) {
    RoiOutcome outcome;
    std::ostringstream out, err;
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
