#include "simplify/DeviationBound.hpp"

#include <algorithm>
#include <array>
#include <cstdint>

#include "simplify/BoundRules.hpp"

namespace dfrecon {

double fanDistance(const DeviationSurface& surface, Vec3 a, Vec3 b, Vec3 c, std::uint32_t vertex,
                   double limitMm) {
    const VertexFans& fans = surface.fans;
    const std::uint32_t first = fans.first()[vertex], m = fans.first()[vertex + 1] - first;
    if (m < 3) return INFINITY;
    const TriangleSoup& soup = surface.soup();
    std::array<Vec3, VertexFans::kMaxNeighbours> ring;
    for (std::uint32_t k = 0; k < m; ++k) ring[k] = soup.points[fans.ring()[first + k]];
    return shared::fan_distance(a, b, c, soup.points[vertex], ring.data(),
                                &fans.sectorNormals()[first], int(m), limitMm);
}

namespace {

// The fan rule over the fan of the vertex of triangle t nearest `centre`
// (the first of equals), as fan_bound in kernels/collapse_bound.cl.
double fanOfNearestCorner(const DeviationSurface& surface, const Vec3 p[3], std::size_t t,
                          Vec3 centre, double limit) {
    const TriangleSoup& soup = surface.soup();
    const auto& tri = soup.triangles[t];
    std::uint32_t v = tri[0];
    double nearest2 = dot(soup.points[tri[0]] - centre, soup.points[tri[0]] - centre);
    for (int k = 1; k < 3; ++k) {
        const double d2 = dot(soup.points[tri[k]] - centre, soup.points[tri[k]] - centre);
        if (d2 < nearest2) {
            nearest2 = d2;
            v = tri[k];
        }
    }
    return fanDistance(surface, p[0], p[1], p[2], v, limit);
}

}  // namespace

int longestEdge(const Vec3 p[3]) {
    const double l0 = dot(p[1] - p[0], p[1] - p[0]), l1 = dot(p[2] - p[1], p[2] - p[1]),
                 l2 = dot(p[0] - p[2], p[0] - p[2]);
    return l0 >= l1 && l0 >= l2 ? 0 : (l1 >= l2 ? 1 : 2);
}

double deviationBound(const DeviationSurface& surface, Vec3 a, Vec3 b, Vec3 c,
                      const DeviationLimits& limits) {
    return deviationBoundWithin(surface, a, b, c, limits, {}).value;
}

DeviationEstimate deviationBoundWithin(const DeviationSurface& original, Vec3 a, Vec3 b, Vec3 c,
                                       const DeviationLimits& limits, DeviationBudget budget) {
    const std::size_t maxPieces = budget.maxPieces;
    const double enough = budget.enough;
    const double limit = limits.limitMm;
    const double finest = limits.finestFraction * limit;
    const double searchRadius2 = limit * limit * (1 + 1e-9);  // any sqrt(d2) <= limit
    const TriangleBvh& bvh = original.bvh;
    const TriangleSoup& surface = bvh.soup();
    struct Piece {
        Vec3 p[3];
        std::size_t near;  // the triangle of S nearest the parent's centre
    };
    auto cornerDistance = [&](const Piece& piece, std::size_t t) {
        const auto& s = surface.triangles[t];
        const Vec3 s0 = surface.points[s[0]], s1 = surface.points[s[1]], s2 = surface.points[s[2]];
        double corners = 0;
        for (const Vec3& q : piece.p)
            corners = std::max(corners, pointTriangleDistance(q, s0, s1, s2));
        return corners;
    };
    // Depth-first; each split replaces one piece by two, and pieces stop
    // splitting below `finest`, so the stack stays small for any triangle
    // not vastly larger than the limit — bounded anyway by refusing to split
    // when full.
    std::array<Piece, 64> stack;  // as PIECE_STACK in kernels/collapse_bound.cl
    std::size_t size = 0;
    stack[size++] = {{a, b, c}, SIZE_MAX};
    double bound = 0;
    double lower = 0;  // the largest centre distance met: the bound is at least that
    for (std::size_t pieces = 0; size > 0; ++pieces) {
        const double known = std::max(bound, lower);
        if (pieces == maxPieces || known > enough) return {known, false, pieces};
        const Piece piece = stack[--size];
        // Most pieces of a split lie over the same original triangle as their
        // parent: try it before searching.
        if (piece.near != SIZE_MAX) {
            const double corners = cornerDistance(piece, piece.near);
            if (corners <= limit) {
                bound = std::max(bound, corners);
                continue;
            }
        }
        const Vec3 centre = (1.0 / 3.0) * (piece.p[0] + piece.p[1] + piece.p[2]);
        // Over the fan of a vertex of that triangle the piece may settle
        // whole, before any search (at 0.25 mm, half the pieces that get
        // here do).
        if (piece.near != SIZE_MAX) {
            const double fan = fanOfNearestCorner(original, piece.p, piece.near, centre, limit);
            if (fan <= limit) {
                bound = std::max(bound, fan);
                continue;
            }
        }
        double radius = 0;
        for (const Vec3& q : piece.p) radius = std::max(radius, length(q - centre));
        // Only a nearest triangle within the limit matters (else the piece
        // is over it), so farther subtrees are skipped even without a hint;
        // the answer within it is nearest()'s, ties included. A piece over
        // the limit ends the search, and only then is the whole tree searched.
        const TriangleBvh::Nearest nearest = bvh.nearestWithin(centre, searchRadius2, piece.near);
        if (!(nearest.distance <= limit))  // over: the distance, for reports
            return {bvh.nearest(centre, piece.near).distance, true, pieces};
        lower = std::max(lower, nearest.distance);
        double settled = nearest.distance + radius;
        if (settled > limit && nearest.triangle != piece.near)
            settled = std::min(settled, cornerDistance(piece, nearest.triangle));
        // Over the edge between the parent's triangle and this one.
        if (settled > limit && piece.near != SIZE_MAX && nearest.triangle != piece.near) {
            const auto& s = surface.triangles[piece.near];
            const auto& t = surface.triangles[nearest.triangle];
            const auto& q = surface.points;
            settled = std::min(settled, shared::straddle_distance(
                                            piece.p[0], piece.p[1], piece.p[2], q[s[0]], q[s[1]],
                                            q[s[2]], int(s[0]), int(s[1]), int(s[2]), q[t[0]],
                                            q[t[1]], q[t[2]], int(t[0]), int(t[1]), int(t[2])));
        }
        if (settled <= limit) {
            bound = std::max(bound, settled);
            continue;
        }
        if (radius < finest || size + 2 > stack.size()) return {settled, true, pieces};
        // Halve the longest edge: pieces get rounder, so their number grows
        // with area / size², where splitting in four similar triangles keeps
        // a long sliver's shape and grows with length².
        const int k = longestEdge(piece.p);
        const Vec3 mid = 0.5 * (piece.p[k] + piece.p[(k + 1) % 3]);
        const Vec3 apex = piece.p[(k + 2) % 3];
        const std::size_t near = nearest.triangle;
        stack[size++] = {{piece.p[k], mid, apex}, near};
        stack[size++] = {{mid, piece.p[(k + 1) % 3], apex}, near};
    }
    return {bound, true, 0};
}

}  // namespace dfrecon
