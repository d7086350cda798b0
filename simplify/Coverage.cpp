#include "simplify/Coverage.hpp"

#include <algorithm>

namespace dfrecon {

CoverCandidate coverCandidate(Vec3 a, Vec3 b, Vec3 c, int id) {
    CoverCandidate candidate{{a, b, c}, id, (1.0 / 3.0) * (a + b + c), 0};
    for (const Vec3& q : candidate.p)
        candidate.radius = std::max(candidate.radius, length(q - candidate.centre));
    // Rounding must never make the bound exceed the true distance.
    candidate.radius = candidate.radius * (1 + 1e-12) + 1e-300;
    return candidate;
}

double cornerDistance(const OriginalPiece& piece, const CoverCandidate& candidate) {
    double d = 0;
    for (const Vec3& q : piece.p)
        d = std::max(d, pointTriangleDistance(q, candidate.p[0], candidate.p[1], candidate.p[2]));
    return d;
}

}  // namespace dfrecon
