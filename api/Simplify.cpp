#include "dfrecon/Simplify.hpp"

#include <algorithm>

#include "api/Stopwatch.hpp"

namespace dfrecon {

namespace {

// Enough samples that the sampled maximum is close to the true one; every
// vertex of both surfaces is added on top.
std::size_t verifySamples(const TriangleSoup& a, const TriangleSoup& b) {
    return std::max<std::size_t>(50000, 4 * std::max(a.triangles.size(), b.triangles.size()));
}

}  // namespace

VerifiedSimplification simplifyVerified(ocl::Runtime* runtime, const TriangleSoup& surface,
                                        const SimplifyOptions& options, const Roi* contours) {
    VerifiedSimplification out;
    out.result = simplifySurface(runtime, surface, options);
    const Stopwatch watch;
    out.verified =
        verifySimplification(surface, out.result.surface, contours, options.maxErrorMm / 8,
                             verifySamples(surface, out.result.surface));
    out.verifySeconds = watch.total();
    return out;
}

}  // namespace dfrecon
