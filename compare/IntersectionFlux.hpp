#pragma once
// The volume of two solids' intersection from their surfaces, without
// building the intersection: by the divergence theorem, vol(A ∩ B) is the
// flux of x/3 through ∂(A ∩ B) = (∂A inside B) ∪ (∂B inside A).
//
// Triangles that the other surface does not cross count whole or not at
// all; which, is decided along edges (an edge's ends differ in side exactly
// when the other surface crosses it an odd number of times), from one seed
// per shell. The triangles it does cross are cut along their intersection
// segments, and each cut region's flux is summed over its boundary alone
// (Green's theorem on the triangle's plane: the parts of the triangle's
// edges inside the other solid and the segments, oriented by exact
// predicates), so no arrangement is ever built. Every decision (which pairs
// cross, which side, which way a segment runs) is an exact predicate on the
// input coordinates; only the crossing points are constructed, in double
// precision, once each and shared by both surfaces' regions. The sum is
// therefore the volume of a closed polyhedron whose constructed vertices lie
// within a computed distance of the true ones; the volume's gradient at a
// vertex is a third of its fans' vector area, so each point's error times
// that (only the part normal to the crossed plane counts for the rounding
// of the plane test: along the edge the point stays in its own faces'
// planes) gives the stated bound, tight even where faces cross at 1e-9 rad.
//
// Where the surfaces meet degenerately (a vertex of one on the other, an
// edge through an edge, coplanar faces) there is no general position to
// decide by; the function says so and a caller moves one surface
// (compare/OverlapVolume's overlapOf).
#include <cstddef>

#include "geometry/TriangleSoup.hpp"

namespace dfrecon {

struct IntersectionFlux {
    /// False where the surfaces meet degenerately: volumeMm3 is then 0 and
    /// means nothing.
    bool generalPosition = false;
    double volumeMm3 = 0;
    /// |volumeMm3 − vol(A ∩ B')| ≤ boundMm3, B' being B moved by the shift
    /// (in double, as given): the constructed points' error, propagated
    /// through every term of the sum, and the sum's own rounding.
    double boundMm3 = 0;
    /// Pairs of triangles, one of each surface, that cross.
    std::size_t crossingPairs = 0;
};

/// The volume of the intersection of the solids bounded by `a` and by `b`
/// moved by `shiftOfB`. Both must be valid closed solids, oriented outward
/// (dfrecon check; not checked here). Work: O((n + k) log n) for n
/// triangles and k pairs of triangles whose boxes overlap, in double
/// precision with exact (filtered) predicates; memory O(n + k).
IntersectionFlux intersectionByFlux(const TriangleSoup& a, const TriangleSoup& b,
                                    const Vec3& shiftOfB = {});

}  // namespace dfrecon
