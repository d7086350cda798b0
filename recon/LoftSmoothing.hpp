#pragma once
// `--interpolation smooth`: the loft bands of a linear reconstruction (the
// strips stitched between two layers of contours) refined in z and bent onto
// the zero set of the slices' C1 interpolant (recon/SliceInterpolant), so the
// surface follows the trend of the neighbouring planes instead of running
// straight from plane to plane. Contour vertices never move, so the surface
// still passes exactly through every contour point; validity is checked and
// kept piece by piece.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "geometry/MeshCheck.hpp"
#include "geometry/PlaneFrame.hpp"
#include "geometry/StackedMeshCheck.hpp"
#include "geometry/TriangleSoup.hpp"
#include "recon/SlabVolumes.hpp"
#include "recon/SliceInterpolant.hpp"

namespace dfrecon {

struct LoftSmoothingStats {
    int rounds = 0;                      // refinement rounds that split something
    std::size_t movedVertices = 0;       // new vertices bent onto the smooth surface
    std::size_t coarsenedVertices = 0;   // refinement's ring vertices merged (RingCoarsening)
    std::size_t revertedPieces = 0;      // pieces whose bent vertices went back (validity)
    int volumePasses = 0;                // passes that changed a slab's bulge
    std::size_t unbentVertices = 0;      // bent vertices put back on the linear surface (validity)
    std::size_t halfUnbentVertices = 0;  // bent vertices moved halfway back to it (validity)
    bool fellBack = false;               // the linear surface was kept
};

/// `surface` is a valid reconstruction whose triangle t lies in piece
/// pieceOf[t] (a slab or a cap) and is part of a loft band iff isLoft[t];
/// its first `contourVertices` vertices are the contour points; its points
/// are rounded to float (as checks see them; std::logic_error otherwise:
/// smoothing keeps its copies of them as floats).
/// Every edge of a loft triangle that is not horizontal, not shorter in z
/// than a quarter of its slab, and whose middle is farther than
/// `toleranceMm` from the smooth surface is halved, in rounds until none is
/// (at most 5; red–green: neighbouring triangles split too, so the mesh
/// stays conforming; edges in a plane, contour edges included, are never
/// split). Every vertex that is not a contour point and all of whose
/// triangles are loft triangles (new ones, and intermediate contours between
/// strips) then moves, at its own z, to the zero set of `field` (Newton
/// steps along the xy gradient); one that would move more than half its
/// slab's height stays.
/// Then the volumes: a bulge moves the zero set outward in the plane by
/// b · 4t(1 − t) (t the height within the slab; nothing at the planes). Each
/// nested part of a slab (a cavity's wall, an island in the cavity: SlabParts)
/// gets a bulge of its own, set by secant steps until the part holds the
/// integral of its own sections' cubic (partVolumeTargets); then each slab's
/// other parts share one, until the slab holds its target (slabVolumeTargets
/// of `planes`, the field's planes); every bent vertex moves again after
/// each step, up to four passes each; a bulge stays within half its slab's
/// height.
/// The surface's points are first moved to the plane-frame places of the
/// floats a mesh file will hold when it is written in patient coordinates
/// (`writtenFrame`: the ROI's plane frame; for the identity, rounding to
/// float), and kept there after every move, so every check sees the
/// surface as written, an oblique stack's included.
/// Where the bent surface is broken (checked as written),
/// the bent vertices around go back onto the linear surface, tested again
/// locally, and the slabs repaired that way bulge again with them held
/// straight. Pieces still broken get their linear triangles back; if the
/// surface is still not valid, the linear surface is restored. On return
/// `check` describes `surface`.
/// The pieces lie as `stack` says (its `searched` is not read): checks are
/// checkStackedMesh's, which search only the pieces whose vertices moved.
/// Work: O(T) per round and pass over the triangles made, one or two
/// whole-mesh checks, local tests around what was repaired.
/// What smoothing reads of the surface per triangle and point, as the
/// builder hands it over (SurfaceBuilder::release).
struct LoftMarks {
    std::vector<std::uint32_t> pieceOf;  // per triangle, its piece of `stack`
    std::vector<bool> isLoft;            // per triangle: made between contours (may bend)
    std::size_t contourVertices = 0;     // points below this id are contour points (never move)
};

/// What smoothing bends towards and keeps to.
struct LoftSmoothingTargets {
    const PlaneSections& planes;     // the field's planes (slab volume targets)
    double toleranceMm;              // Newton steps stop this near the zero set
    const PlaneFrame& writtenFrame;  // the frame the surface is written in (float places)
    /// Keep every bent vertex inside the union of its slab's two planes'
    /// regions (contours on a pixel lattice: the voxels bound the structure).
    bool withinNeighbourPlanes = false;
    /// Thin refinement's rings afterwards (recon/RingCoarsening).
    bool coarsenRings = true;
};

LoftSmoothingStats smoothLofts(TriangleSoup& surface, LoftMarks marks, const PieceStack& stack,
                               const SliceInterpolant& field, const LoftSmoothingTargets& targets,
                               MeshCheckReport& check);

}  // namespace dfrecon
