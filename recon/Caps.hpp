#pragma once
// Caps: how a reconstruction closes contours that have no partner beyond
// them (the first and last slice, a branch or a cavity that ends). A cap is
// a piece of the surface like a slab: it lies between the end contours'
// plane and a plane `offsetMm` beyond it and meets the rest of the surface
// only in those contours, sharing their vertices, so the surface is a valid
// solid whenever each piece is a clean sheet bordered by exactly its
// contours (docs/reconstruction.md, "Caps" and "Valid by construction").
// Where a cap of the chosen shape cannot be made so, a flat prism cap
// (recon/PrismClosing), valid by construction, takes its place.
#include <array>
#include <cstddef>
#include <optional>
#include <utility>
#include <vector>

#include "field/SliceFields.hpp"

namespace dfrecon {

struct Layer;
struct LayerPart;
class SurfaceBuilder;

/// How ends are closed: contours with no partner beyond them (first and last
/// slice, a branch that stops).
enum class CapMode {
    Flat,  // a flat lid at the cap offset, its rim continuing the side's slope from the last slab
           // (vertical for voxel contours)
    Dome,  // a dome from the contour rising to the cap offset at its deepest point
    None,  // left open (the surface has boundary loops there)
};

/// The one list of the cap modes' names, which the command line parses and
/// reports print (report/EnumNames.hpp reads it); capModeName reads it too.
inline constexpr std::array<std::pair<const char*, CapMode>, 3> kCapModeNames{{
    {"flat", CapMode::Flat},
    {"dome", CapMode::Dome},
    {"none", CapMode::None},
}};

/// The name of `mode` in kCapModeNames. O(1).
const char* capModeName(CapMode mode);

/// How far beyond its plane the cap of an end contour reaches: `requestedMm`,
/// or half `gapMm` (the spacing to the neighbouring plane) where that is
/// negative. A contour that ends between two planes of the stack
/// (`betweenPlanes`) caps no further than the middle of their gap, where the
/// other plane's caps end; the caps at the ends of the stack take the
/// request as it is. O(1).
double capOffsetMm(double requestedMm, double gapMm, bool betweenPlanes);

/// What a cap asks of the reconstruction it closes. A flat cap whose end
/// narrows is joined to its lid as any slab is joined, so it needs the
/// reconstruction's fields, layers, slab joining and piece check.
class CapSite {
  public:
    virtual ~CapSite() = default;
    virtual SurfaceBuilder& builder() = 0;
    /// The fields of `parts`, one slice each, in order, on `grid` (nullopt:
    /// the window of the reconstruction's grid around them).
    virtual SliceFields fieldsOf(const std::vector<LayerPart>& parts,
                                 std::optional<SliceGrid> grid) = 0;
    /// Keeps `isolines` of the field of `of`'s contours (its negative side on
    /// their left) as a new layer at `zMm`, turned to run as contours run
    /// (the solid on their left); it lives as long as the reconstruction.
    virtual const Layer& addIsolineLayer(double zMm, std::vector<Polygon> isolines,
                                         const LayerPart& of) = 0;
    /// Joins `lower` to `upper` as the two planes of a slab below the
    /// recursion's top level, so contours that end there are closed by
    /// prisms, not capped again; the fields are one slice each, on one grid.
    virtual void joinLayers(const LayerPart& lower, const SliceFields& lowerField,
                            const LayerPart& upper, const SliceFields& upperField) = 0;
    /// Whether the triangles added since `before` are a clean piece whose
    /// only border is the contours of `end` (the test every slab is held
    /// to, as a mesh file holds it); the site may note that the piece was
    /// checked.
    virtual bool isCleanCap(std::size_t before, const LayerPart& end) = 0;
};

/// The entry point: caps the contours of `end`, slice `slice` of `fields`,
/// upward from their plane when `reach.up` (else downward), reaching
/// `reach.offsetMm` beyond it, in the shape `mode` asks for (CapMode::None adds nothing).
/// Everything it adds lies between the plane and the offset, and is meant to
/// be bordered by exactly the end contours' edges. A dome that is not such a
/// clean sheet, or whose outer contours are too small to hold an inner
/// vertex, becomes a flat prism cap here; a flat cap is not checked here, as
/// the caller checks the piece it belongs to anyway (the slab a contour ends
/// in) or calls capEndsAsPiece. A hole of `end` whose cavity narrows
/// toward the end (guaranteedCap says when) is not capped with the rest: it
/// gets a flat lid of its own at half the offset, what lies in it a cap at
/// half that, so the cavity stays closed. A flat cap's rim follows the
/// trend of the region it closes, a cavity's own end (its outermost
/// contour a hole) narrowing where the cavity beyond is wider; such a
/// cavity cap is left out of smoothing (SurfaceBuilder::markLoftSince).
/// Work: a flat cap over an end that narrows
/// costs one slab's reconstruction on the window around the end contours
/// (their field and the lid's, the medial axes, the strips), over an end
/// that does not, a prism cap's; a dome tests a lattice of the slice's
/// pixels, a third of the offset apart, against the end contours
/// (O(lattice points · contour points)), triangulates the region with them
/// (O(m log m) in the m points) and checks the sheet (O(t log t) in its t
/// triangles).
/// Which way a cap goes from its plane and how far.
struct CapReach {
    bool up = true;       // upward (else downward) from the end's plane
    double offsetMm = 0;  // how far beyond the plane it may reach
    /// The contours come from voxels (recon/PixelLattice): the end's voxel
    /// layer is a prism, so a flat cap keeps vertical walls to its lid
    /// instead of following the slope of the staircase below.
    bool voxelEnds = false;
};
void capEnds(CapSite& site, CapMode mode, const LayerPart& end, CapReach reach,
             const SliceFields& fields, std::size_t slice);

/// capEnds for a piece of its own (the ends of the stack): what it adds is
/// checked as a piece (CapSite::isCleanCap) and, when it is not clean,
/// replaced by a flat prism cap. So with CapMode::Flat or Dome the cap is a
/// clean piece bordered by exactly the end contours. Work: capEnds' and
/// the check's, O(t log t) in the cap's triangles.
void capEndsAsPiece(CapSite& site, CapMode mode, const LayerPart& end, CapReach reach,
                    const SliceFields& fields, std::size_t slice);

/// The contours of `end` extruded by `offsetMm` (up or down from their
/// plane) under a flat lid, a prism closing with nothing on the other side,
/// valid by construction. Θ(n log n) in the contour points.
void prismCap(SurfaceBuilder& builder, const LayerPart& end, bool up, double offsetMm);

/// The guaranteed cap of `end`, slice `slice` of `fields`: prismCap, except
/// where a cavity closes before the end does — a hole of the end plane
/// whose cavity narrows toward the end (the slice on the other side holds
/// more of it) gets a flat lid of its own at half the offset, and what lies
/// inside it (an island) its cap at half that, so the cavity stays closed
/// instead of running through the lid to the outside. capEnds splits the
/// same way. Valid by construction: vertical prisms over disjoint contours,
/// each nested one shallower than the one around it, lids at distinct
/// heights. Θ(n log n) in the contour points, plus O(h · n) to find what
/// encloses each of the h contours.
void guaranteedCap(SurfaceBuilder& builder, const LayerPart& end, CapReach reach,
                   const SliceFields& fields, std::size_t slice);

}  // namespace dfrecon
