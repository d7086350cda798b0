#pragma once
// The direction "original → simplified" of the simplifier's two-sided error:
// every piece of the original surface is kept on ("homed at") a face of the
// simplified surface that covers it — every corner of the piece within the
// bound of that face. The distance to one triangle is convex, so then every
// point of the piece is within the bound: a guarantee for the whole
// original surface, contour edges included, not only for its vertices
// (which is all OpenMesh's ModHausdorff checks).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

#include "simplify/BoundRules.hpp"
#include "simplify/DeviationBound.hpp"

namespace dfrecon {

/// A triangle of the original surface, or a part of one.
struct OriginalPiece {
    Vec3 p[3];
};

/// A triangle that may cover pieces: its corners and their vertex ids
/// (candidates sharing two ids share that edge), an id for the caller, and
/// the ball around it, for a cheap lower bound of a distance to it. Make
/// with coverCandidate.
struct CoverCandidate {
    Vec3 p[3];
    std::array<std::uint32_t, 3> vertices;
    int id = -1;
    TriangleBvh::Ball ball;
};
CoverCandidate coverCandidate(Vec3 a, Vec3 b, Vec3 c, std::array<std::uint32_t, 3> vertices,
                              int id);

/// The largest corner distance from `piece` to `candidate`: an upper bound
/// of the distance from any point of the piece to the candidate.
double cornerDistance(const OriginalPiece& piece, const CoverCandidate& candidate);

/// Covers `piece` by `candidates`: if one covers it whole (trying
/// `firstTry` first when ≥ 0, the usual answer; else the nearest by corner
/// distance, the first of equals, with `likely` ≥ 0 measured first only to
/// rule others out sooner: the same answer), calls
/// onCovered(piece, candidate index, distance); else, if the nearest and
/// a neighbour of it cover it cut at their bisecting plane
/// (coverAcrossAnEdge), reports the parts; otherwise halves its longest
/// edge and covers each part the same way, down to parts of circumradius
/// limits.finestFraction · limit or kMaxCoverDepth halvings, whichever comes
/// first. Returns the largest distance reported, or a value above the limit
/// as soon as a part cannot be covered (onCovered may then have been called
/// for other parts). The same pieces and candidates give the same answer.
/// Which candidates coverPiece measures first (indices, or -1).
struct CoverHints {
    int firstTry = -1;  // tried first: the usual answer
    int likely = -1;    // measured first, only to rule others out sooner
};
template <class OnCovered>
double coverPiece(const OriginalPiece& piece, const std::vector<CoverCandidate>& candidates,
                  CoverHints hints, const DeviationLimits& limits, OnCovered&& onCovered,
                  int depth = 0);

/// Most halvings of one original triangle in coverPiece. Three halvings of
/// the longest edge about halve a piece, so this is some 2^-40 of its size:
/// pieces reach the finest size long before on any surface within the input
/// limits and a bound above kMinMaxErrorMm. It bounds the recursion where
/// rounding would not let a piece shrink (a part not covered there only
/// refuses the collapse, as any uncovered part does).
inline constexpr int kMaxCoverDepth = 120;

/// The straddle rule (kernels/straddle_bound.cl) for coverage: with the
/// piece cut by the plane bisecting the angle between candidate `nearest`
/// and the first candidate (in index order) sharing an edge with it, both
/// cover every corner of their part within `limit` (crossing points in
/// both). Reports the parts, as triangles, through onCovered and returns
/// the largest distance; INFINITY (nothing reported) when no neighbour
/// does. Where a piece lies across the edge between two faces, halving
/// needs parts down to the size of the slack; this needs at most four.
/// O(candidates).
template <class OnCovered>
double coverAcrossAnEdge(const OriginalPiece& piece, const std::vector<CoverCandidate>& candidates,
                         int nearest, double limit, OnCovered& onCovered);

template <class OnCovered>
double coverAcrossAnEdge(const OriginalPiece& piece, const std::vector<CoverCandidate>& candidates,
                         int nearest, double limit, OnCovered& onCovered) {
    const CoverCandidate& a = candidates[std::size_t(nearest)];
    const auto& ia = a.vertices;
    for (std::size_t k = 0; k < candidates.size(); ++k) {
        const CoverCandidate& b = candidates[k];
        const auto& ib = b.vertices;
        Vec3 e, m;  // none unless b shares an edge with a
        if (!shared::straddle_plane(a.p[0], a.p[1], a.p[2], int(ia[0]), int(ia[1]), int(ia[2]),
                                    b.p[0], b.p[1], b.p[2], int(ib[0]), int(ib[1]), int(ib[2]), &e,
                                    &m))
            continue;
        const double d =
            shared::straddle_distance_across(piece.p[0], piece.p[1], piece.p[2], a.p[0], a.p[1],
                                             a.p[2], b.p[0], b.p[1], b.p[2], e, m);
        if (!(d <= limit)) continue;
        // The parts are exactly the corners and crossing points that
        // straddle_distance measured; each is cut into triangles from its
        // first corner. All are kept, even of no area: a degenerate piece of
        // the input still has points to keep within the bound.
        for (const auto& [owner, sign] : {std::pair{nearest, 1.0}, std::pair{int(k), -1.0}}) {
            Vec3 part[4];
            const int corners = shared::clip_polygon(piece.p, 3, e, m, sign, part);
            for (int c = 1; c + 1 < corners; ++c)
                onCovered(OriginalPiece{{part[0], part[c], part[c + 1]}}, owner, d);
        }
        return d;
    }
    return INFINITY;
}

template <class OnCovered>
double coverPiece(const OriginalPiece& piece, const std::vector<CoverCandidate>& candidates,
                  CoverHints hints, const DeviationLimits& limits, OnCovered&& onCovered,
                  int depth) {
    const int firstTry = hints.firstTry;
    int likely = hints.likely;
    const double limit = limits.limitMm;
    if (firstTry >= 0) {
        const double d = cornerDistance(piece, candidates[std::size_t(firstTry)]);
        if (d <= limit) {
            onCovered(piece, firstTry, d);
            return d;
        }
    }
    int best = -1;
    double bestDistance = INFINITY;
    // The nearest is at most as far as `likely`: a candidate surely farther
    // cannot be it, nor tie with it (hence strictly farther).
    if (likely == firstTry) likely = -1;
    const double likelyDistance =
        likely >= 0 ? cornerDistance(piece, candidates[std::size_t(likely)]) : INFINITY;
    const Vec3 centre = (1.0 / 3.0) * (piece.p[0] + piece.p[1] + piece.p[2]);
    for (std::size_t k = 0; k < candidates.size(); ++k) {
        if (int(k) == firstTry) continue;
        // Convexity again: the largest corner distance is at least the
        // centre's, one distance instead of three to rule a candidate out;
        // and that is at least the distance to the candidate's ball, which
        // rules out most of the candidates around a collapse. Both compared
        // squared: this loop runs for every piece and every candidate, and
        // waited on its square roots.
        const CoverCandidate& c = candidates[k];
        const double ballDistance2 = dot(centre - c.ball.centre, centre - c.ball.centre);
        const auto square = [](double x) { return x * x; };
        if (ballDistance2 > square(c.ball.radius) &&
            (ballDistance2 >= square(bestDistance + c.ball.radius) ||
             ballDistance2 > square(likelyDistance + c.ball.radius)))
            continue;
        double d = likelyDistance;
        if (int(k) != likely) {
            const Vec3 q = closestPointOnTriangle(centre, c.p[0], c.p[1], c.p[2]);
            const double atCentre2 = dot(centre - q, centre - q);
            if (atCentre2 >= square(bestDistance) || atCentre2 > square(likelyDistance)) continue;
            d = cornerDistance(piece, c);
        }
        if (d < bestDistance) {
            bestDistance = d;
            best = int(k);
        }
    }
    if (bestDistance <= limit) {
        onCovered(piece, best, bestDistance);
        return bestDistance;
    }
    if (best >= 0) {
        const double across = coverAcrossAnEdge(piece, candidates, best, limit, onCovered);
        if (across <= limit) return across;
    }
    double radius = 0;
    for (const Vec3& q : piece.p) radius = std::max(radius, length(q - centre));
    if (radius < limits.finestFraction * limit || depth == kMaxCoverDepth) return bestDistance;
    const int k = longestEdge(piece.p);  // halved: see deviationBound
    const Vec3 mid = 0.5 * (piece.p[k] + piece.p[(k + 1) % 3]);
    const Vec3 apex = piece.p[(k + 2) % 3];
    const OriginalPiece parts[2] = {{{piece.p[k], mid, apex}}, {{mid, piece.p[(k + 1) % 3], apex}}};
    double worst = 0;
    for (const OriginalPiece& part : parts) {
        worst =
            std::max(worst, coverPiece(part, candidates, {best, -1}, limits, onCovered, depth + 1));
        if (worst > limit) return worst;
    }
    return worst;
}

}  // namespace dfrecon
