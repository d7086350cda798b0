#include "app/SimplifyReport.hpp"

#include <algorithm>
#include <cmath>

#include "app/Progress.hpp"
#include "simplify/SimplificationVerifier.hpp"

namespace dfrecon::app {

nlohmann::ordered_json simplificationJson(const VerifiedSimplification& simplified,
                                          const SimplifyOptions& options, bool againstContours,
                                          std::optional<double> fieldAbsMaxMm) {
    const TwoSidedDistance& both = simplified.verified.surfaces;
    nlohmann::ordered_json distances{{"inputToResultMaxMm", both.aToB.maxMm},
                                     {"resultToInputMaxMm", both.bToA.maxMm},
                                     {"meanMm", 0.5 * (both.aToB.meanMm + both.bToA.meanMm)}};
    if (againstContours) distances["contoursToResultMaxMm"] = simplified.verified.contours.maxMm;
    distances["maxMm"] = simplified.verified.maxMm();
    distances["samples"] = both.aToB.samples + both.bToA.samples;
    if (fieldAbsMaxMm) distances["fieldAbsMaxMm"] = *fieldAbsMaxMm;
    const SimplifyStats& s = simplified.result.stats;
    return {
        {"maxErrorMm", options.maxErrorMm},
        {"trianglesBefore", s.trianglesBefore},
        {"triangles", s.triangles},
        {"vertices", s.vertices},
        {"collapses", s.collapses},
        {"boundMm",
         {{"resultToInput", s.surfaceToInputBoundMm}, {"inputToResult", s.inputToSurfaceBoundMm}}},
        {"verified", distances},
        {"withinBound", simplified.withinBound(options.maxErrorMm)},
        {"originalPieces", s.pieces},
        {"retries", s.retries},
        {"seconds",
         {{"initialBatch", s.initialSeconds},
          {"decimate", s.decimateSeconds},
          {"verify", simplified.verifySeconds}}}};
}

nlohmann::ordered_json simplifyAndVerify(ocl::Runtime& runtime, TriangleSoup& surface,
                                         const SimplifyRequest& request,
                                         const GlobalOptions& global) {
    VerifiedSimplification simplified;
    {
        Progress progress(request.label, !global.quiet);
        simplified = simplifyVerified(&runtime, surface, request.options, request.contours);
    }
    std::optional<double> fieldAbsMaxMm;
    if (request.field) {
        // Not a bound: the field is interpolated, and its zero set is the
        // contours' surface, not the mesh simplified.
        double worst = 0;
        for (const Vec3& p : sampleTriangles(simplified.result.surface, 20000, 3))
            worst = std::max(worst, std::abs((*request.field)(p)));
        fieldAbsMaxMm = worst;
    }
    nlohmann::ordered_json report =
        simplificationJson(simplified, request.options, request.contours != nullptr, fieldAbsMaxMm);
    surface = std::move(simplified.result.surface);
    return report;
}

}  // namespace dfrecon::app
