#pragma once
// Smooth mode's refinement halves every rung of a band that sags, so the
// middle ring it makes has a vertex per rung: as many as both contours
// together, where the curve across the band needs no more than either. This
// merges neighbouring vertices of those rings wherever the merged triangles
// still follow the smooth surface to within the tolerance, and keeps the
// surface a valid solid: every pass is checked, and a merge that made
// triangles cross is undone.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

#include "geometry/MeshCheck.hpp"
#include "geometry/TriangleSoup.hpp"
#include "recon/SliceInterpolant.hpp"

namespace dfrecon {

struct RingCoarseningOptions {
    /// How far a merged triangle may stray from the smooth surface, mm.
    double toleranceMm = 0.05;
    /// Also keep merged triangles within the union of the slab's planes'
    /// regions (contours on a pixel lattice).
    bool withinNeighbourPlanes = false;
    /// Each pass can halve a ring where it is smooth; a third took 6 % more
    /// triangles off the benchmark shapes (dfrecon-bench recon) at 4 % more
    /// time, and moved slab means up to 0.02 more.
    int passes = 2;
};

/// The surface's triangles and what smoothing marks on each.
struct MarkedTriangles {
    TriangleSoup& soup;
    std::vector<std::uint32_t>& pieceOf;  // per triangle, its piece (a slab or a cap)
    std::vector<bool>& isLoft;            // per triangle, made between contours
};

/// Half-edge collapses of made vertices into their neighbours on the same
/// ring: vertex v (id >= firstMade, every triangle around it a loft
/// triangle of one piece) goes into a neighbour w at its very z (a
/// horizontal edge: both are middles of rungs between the same two levels)
/// that is made and free likewise, where
///  - the link condition holds (the surface stays a closed, oriented
///    manifold) and v, w and the two corners opposite their edge each keep
///    three triangles or more;
///  - no triangle around v turns by more than 45 degrees or loses its area;
///  - the middles of the new edges at w and the centroids of the triangles
///    that now have w as a corner lie within `toleranceMm` of the smooth
///    surface (|F| of `field` as it is bent to: `bulgeMm(v)` is subtracted),
///    and within the union of the slab's planes' regions when asked
///    (pixel-lattice contours).
/// Contour points and the recursion's intermediate contours (ids below
/// firstMade) never go; no point moves. `surface` must be a valid solid,
/// and `check` its whole check: after each pass the triangles it changed
/// are searched for defects (defectsAfterMoving: the link condition keeps
/// the topology), a collapse whose triangles take part in one is undone,
/// and the search repeated until none is left; at the end `check`
/// describes the result (counts from the collapses, volume and area
/// measured again).
/// The removed vertices stay in `soup.points`, on no triangle
/// (removeUnusedPoints drops them later). Returns the vertices removed.
/// Work per pass: O(T) plus a dozen field look-ups per tried collapse and
/// one or a few O(T) defect searches.
std::size_t coarsenMiddleRings(MarkedTriangles surface, std::size_t firstMade,
                               const SliceInterpolant& field,
                               const std::function<double(std::size_t, double)>& bulgeMm,
                               const RingCoarseningOptions& options, MeshCheckReport& check);

}  // namespace dfrecon
