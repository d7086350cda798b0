#include "simplify/Coverage.hpp"

#include <algorithm>

namespace dfrecon {

CoverCandidate coverCandidate(Vec3 a, Vec3 b, Vec3 c, std::array<std::uint32_t, 3> vertices,
                              int id) {
    return {{a, b, c}, vertices, id, TriangleBvh::Ball::around(a, b, c)};
}

double cornerDistance(const OriginalPiece& piece, const CoverCandidate& candidate) {
    double d = 0;
    for (const Vec3& q : piece.p)
        d = std::max(d, pointTriangleDistance(q, candidate.p[0], candidate.p[1], candidate.p[2]));
    return d;
}

}  // namespace dfrecon
