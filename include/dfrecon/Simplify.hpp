#pragma once
// Error-bounded simplification (reconstruction paper §6.2: edge collapses
// whose every new triangle stays within the bound of the original surface),
// then an independent check of the result: dense samples and exact distances
// both ways, and to the contours when given.
#include "contours/ContourSet.hpp"
#include "simplify/Simplification.hpp"
#include "simplify/SimplificationVerifier.hpp"

namespace dfrecon {

struct VerifiedSimplification {
    Simplified result;                // the surface and the collapse statistics
    SimplificationDistance verified;  // measured distances (maxMm() the largest)
    double verifySeconds = 0;

    /// The measured distance is within the bound asked for. O(1).
    bool withinBound(double maxErrorMm) const { return verified.maxMm() <= maxErrorMm; }
};

/// Simplifies `surface` within options.maxErrorMm (simplify/Simplification)
/// and measures the result against `surface` (and `contours`, when given)
/// at max(50 000, 4 × triangles) samples plus every vertex, each distance
/// within maxErrorMm / 8 of exact. `runtime` may be null (host only).
/// Throws what simplifySurface throws. O(simplification + samples · log F).
VerifiedSimplification simplifyVerified(ocl::Runtime* runtime, const TriangleSoup& surface,
                                        const SimplifyOptions& options,
                                        const Roi* contours = nullptr);

}  // namespace dfrecon
