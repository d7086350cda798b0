#include "app/SimplifyReport.hpp"

#include <algorithm>
#include <cmath>

#include "app/Progress.hpp"
#include "app/Stopwatch.hpp"
#include "simplify/SurfaceDistance.hpp"

namespace dfrecon::app {

namespace {

// Enough samples that the sampled maximum is close to the true one; every
// vertex of both surfaces is added on top.
std::size_t verifySamples(const TriangleSoup& a, const TriangleSoup& b) {
    return std::max<std::size_t>(50000, 4 * std::max(a.triangles.size(), b.triangles.size()));
}

}  // namespace

nlohmann::ordered_json simplifyAndVerify(ocl::Runtime& runtime, TriangleSoup& surface,
                                         const SimplifyRequest& request,
                                         const GlobalOptions& global) {
    Simplified result;
    {
        Progress progress(request.label, !global.quiet);
        result = simplifySurface(&runtime, surface, request.options);
    }
    const Stopwatch watch;
    const SimplificationDistance verified = verifySimplification(
        surface, result.surface, request.contours, request.options.maxErrorMm / 8,
        verifySamples(surface, result.surface));
    const TwoSidedDistance& both = verified.surfaces;
    nlohmann::ordered_json distances{{"inputToResultMaxMm", both.aToB.maxMm},
                                     {"resultToInputMaxMm", both.bToA.maxMm},
                                     {"meanMm", 0.5 * (both.aToB.meanMm + both.bToA.meanMm)}};
    if (request.contours) distances["contoursToResultMaxMm"] = verified.contours.maxMm;
    const double verifiedMax = verified.maxMm();
    distances["maxMm"] = verifiedMax;
    distances["samples"] = both.aToB.samples + both.bToA.samples;
    if (request.field) {
        // Not a bound: the field is interpolated, and its zero set is the
        // contours' surface, not the mesh simplified.
        double worst = 0;
        for (const Vec3& p : sampleTriangles(result.surface, 20000, 3))
            worst = std::max(worst, std::abs((*request.field)(p)));
        distances["fieldAbsMaxMm"] = worst;
    }
    const double verifySeconds = watch.total();
    const SimplifyStats& s = result.stats;
    surface = std::move(result.surface);
    return {
        {"maxErrorMm", request.options.maxErrorMm},
        {"trianglesBefore", s.trianglesBefore},
        {"triangles", s.triangles},
        {"vertices", s.vertices},
        {"collapses", s.collapses},
        {"boundMm",
         {{"resultToInput", s.surfaceToInputBoundMm}, {"inputToResult", s.inputToSurfaceBoundMm}}},
        {"verified", distances},
        {"withinBound", verifiedMax <= request.options.maxErrorMm},
        {"originalPieces", s.pieces},
        {"retries", s.retries},
        {"seconds",
         {{"initialBatch", s.initialSeconds},
          {"decimate", s.decimateSeconds},
          {"verify", verifySeconds}}}};
}

}  // namespace dfrecon::app
