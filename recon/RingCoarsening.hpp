#pragma once
// Smooth mode's refinement halves every rung of a band that sags, so the
// middle ring it makes has a vertex per rung: as many as both contours
// together, where the curve across the band needs no more than either. This
// merges neighbouring vertices of those rings wherever the merged triangles
// still follow the smooth surface to within the tolerance, and keeps the
// surface a valid solid: every pass is checked, and a merge that made
// triangles cross is undone.
#include <array>
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

/// One pass of collapses and what it takes to undo them: the engine of
/// coarsenMiddleRings, which is all a caller needs.
class RingCoarseningPass {
  public:
    /// What a merged triangle is measured against.
    struct Judge {
        const SliceInterpolant& field;
        const RingCoarseningOptions& options;
        // How far vertex v's zero set is moved outward at height z, mm.
        const std::function<double(std::size_t, double)>& bulgeMm;
    };

    RingCoarseningPass(MarkedTriangles surface, std::size_t firstMade, const Judge& judge);

    /// Collapses what it can; returns the ids of the triangles changed
    /// (the triangles are renumbered: the two at each collapsed edge go).
    std::vector<std::size_t> collapse();
    /// Undoes every collapse one of whose triangles is in `defective`;
    /// returns the ids of the triangles it put back (changed ones, and the
    /// two removed ones appended at the end), empty when none was undone.
    std::vector<std::size_t> undo(const std::vector<std::size_t>& defective);
    /// Every collapse still made, undone; the ids as undo's.
    std::vector<std::size_t> undoAll();
    /// Triangles of every collapse still made (changed ones).
    std::vector<std::size_t> liveTriangles() const;
    std::size_t liveCollapses() const;

  private:
    struct Collapse {
        std::uint32_t from, into;          // v went into w
        std::vector<std::size_t> changed;  // triangle ids (current numbering)
        std::array<std::array<std::uint32_t, 3>, 2> removed;
        std::array<std::uint32_t, 2> removedPieces;
        bool live = true;
    };
    bool free(std::uint32_t v) const;
    std::vector<std::uint32_t> neighbours(std::uint32_t v) const;
    bool follows(const Vec3& p, std::uint32_t v) const;
    bool tryCollapse(std::uint32_t v, std::uint32_t w, const std::vector<std::uint32_t>& nv,
                     std::vector<bool>& gone);
    std::vector<std::size_t> undoWhere(const std::vector<bool>& which);

    MarkedTriangles surface_;
    std::size_t first_;
    Judge judge_;
    std::vector<std::uint32_t> fanStart_, fan_;  // per made vertex, its triangles at the start
    std::vector<bool> locked_;
    std::vector<std::uint32_t> degree_;  // per vertex, its triangles now
    std::vector<Collapse> collapses_;
    std::vector<std::uint32_t> ownerOf_;  // per triangle, the collapse that changed it, or none
};

}  // namespace dfrecon
