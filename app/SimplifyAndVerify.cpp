#include "app/SimplifyAndVerify.hpp"

#include <algorithm>
#include <cmath>

#include "app/Progress.hpp"
#include "simplify/SimplificationVerifier.hpp"

namespace dfrecon::app {

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
