#pragma once
// How far a triangle strays from a surface, as a certified upper bound: the
// direction "simplified → original" of the simplifier's two-sided error.
#include <cmath>
#include <cstddef>

#include "geometry/TriangleBvh.hpp"
#include "geometry/VertexFans.hpp"

namespace dfrecon {

/// The surface S deviations are measured from, indexed for deviationBound:
/// its triangle hierarchy (nearest triangles) and its vertex fans (the fan
/// rule). Built once per surface; `soup` must outlive it. O(T log T).
struct DeviationSurface {
    explicit DeviationSurface(const TriangleSoup& soup) : bvh(soup), fans(soup) {}
    const TriangleSoup& soup() const { return bvh.soup(); }
    TriangleBvh bvh;
    VertexFans fans;
};

struct DeviationLimits {
    double limitMm = 0;  ///< the bound to certify (the simplifier's max error)
    /// Pieces smaller than this fraction of the limit are not split further;
    /// one still unsettled there is reported as over the limit (its centroid
    /// is already within that fraction of it).
    double finestFraction = 0.1;
};

/// An upper bound of max over p in abc of dist(p, S), or a value above
/// limits.limitMm when that maximum may exceed it. The triangle is split in
/// two recursively (at the middle of its longest edge); a piece is settled
/// by the first of these rules that gives a value ≤ the limit:
///   max over corners dist(corner, s'), s' the triangle of S nearest the
///                             parent's centroid (the distance to one
///                             triangle is convex: on a piece it peaks at a
///                             corner);
///   the fan rule (kernels/fan_bound.cl) over the fan of the vertex of s'
///                             nearest the centroid;
/// and else, with centroid c, circumradius R about c and s the triangle of
/// S nearest c, the smallest of
///   dist(c, S) + R            (the distance to S changes by at most 1 per mm)
///   max over corners dist(corner, s)
///   the straddle rule (kernels/straddle_bound.cl) over s' and s.
/// The result is the largest settling value; a centroid farther than the
/// limit ends the search at once (a true violation). O(pieces · log |S|);
/// pieces grow with area / (limit − dist)².
double deviationBound(const DeviationSurface& surface, Vec3 a, Vec3 b, Vec3 c,
                      const DeviationLimits& limits);

/// The fan rule alone (kernels/fan_bound.cl): an upper bound of the
/// distance from every point of triangle abc to the fan of triangles around
/// `vertex`, a vertex of S. INFINITY when the vertex has no fan (see
/// VertexFans), or a value over limitMm as soon as one is found. O(fan size).
double fanDistance(const DeviationSurface& surface, Vec3 a, Vec3 b, Vec3 c, std::uint32_t vertex,
                   double limitMm);

/// deviationBound, or only a lower bound of it when more than `maxPieces`
/// pieces would be needed or once that lower bound exceeds `enough` (the
/// caller only asks whether the bound is at most `enough`): the largest
/// settling bound and centroid distance met by then (the bound is at least
/// each). Pieces are taken in the same order whatever the budget, so the
/// lower bound only grows with `piecesTaken`. O(min(maxPieces, pieces) ·
/// log |S|).
struct DeviationEstimate {
    double value;
    bool complete;            ///< value is deviationBound's, not just a lower bound of it
    std::size_t piecesTaken;  ///< pieces looked at when incomplete
};
/// How far deviationBoundWithin may go: at most `maxPieces` pieces, and no
/// further once the lower bound exceeds `enough`.
struct DeviationBudget {
    std::size_t maxPieces = SIZE_MAX;
    double enough = INFINITY;
};
DeviationEstimate deviationBoundWithin(const DeviationSurface& surface, Vec3 a, Vec3 b, Vec3 c,
                                       const DeviationLimits& limits, DeviationBudget budget);

/// Which edge of p is longest: k for the edge p[k] → p[(k+1) % 3] (the
/// first of equal ones).
int longestEdge(const Vec3 p[3]);

}  // namespace dfrecon
