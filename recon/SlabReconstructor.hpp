#pragma once
// One slab at a time: the reconstruction paper's §4 between two planes of
// contours. The medial axes of the two planes' summed fields say which
// contours join (recon/MedialAxis); a contour that meets exactly one becomes a
// strip (recon/StripStitching); where contours branch, merge or do not
// match, the zero set of the summed field becomes an intermediate layer and
// both halves are solved again (recon/IsoContours), down to
// ReconstructionOptions::maxDepth, where prisms close what is left
// (recon/PrismClosing), valid by construction. Contours that end are capped
// (recon/Caps, for which this is the CapSite).
//
// Every slab is a piece of the surface checked on its own, as floats: a slab
// whose piece is not clean is closed again as one prism piece. A
// SlabReconstructor builds on its own SurfaceBuilder and OpenCL queue, so
// one per thread builds slabs side by side (recon/ParallelSlabs).
#include <cstddef>
#include <cstdint>
#include <deque>
#include <optional>
#include <vector>

#include "cl/Runtime.hpp"
#include "field/SliceFields.hpp"
#include "recon/Caps.hpp"
#include "recon/MedialAxis.hpp"
#include "recon/PrismClosing.hpp"
#include "recon/Reconstruction.hpp"
#include "recon/SlabVolumes.hpp"
#include "recon/StripStitching.hpp"
#include "recon/SurfaceBuilder.hpp"

namespace dfrecon {

/// The fields of a slab's two sides: slices `lower` and `upper` of `fields`
/// hold the fields of exactly the lower and the upper side's contours.
struct SlabFields {
    const SliceFields& fields;
    std::size_t lower = 0, upper = 1;
};

/// What a slab reads of the whole stack beyond its two planes.
struct StackTraits {
    /// The planes and their net areas (may be null): their trend sets the
    /// area of the recursion's intermediate contours.
    const PlaneSections* planes = nullptr;
    /// The contours come from voxels (recon/PixelLattice): caps of contours
    /// that end between planes keep vertical walls, as the voxels do.
    bool fromVoxels = false;
};

class SlabReconstructor final : public CapSite {
  public:
    /// Builds on `builder` with `runtime`'s queue, over `grid` (the ROI's);
    /// counts and seconds go to `stats`, which must outlive it.
    /// `stack`: what is known of the whole stack (its planes' areas, whether
    /// its contours come from voxels).
    SlabReconstructor(ocl::Runtime& runtime, const ReconstructionOptions& options,
                      const SliceGrid& grid, ReconstructionStats& stats,
                      SurfaceBuilder builder = {}, StackTraits stack = {});

    SurfaceBuilder& builder() override { return builder_; }

    /// The slab between two original planes, whose fields are slices
    /// `lowerSlice` and `upperSlice` of `fields`, as the builder's current
    /// piece: joined by strips and recursion, or, where that piece is not
    /// clean, closed as one prism piece. Work: the slab's medial axes, its
    /// strips and the piece check, O(p log p) in its p triangles, times the
    /// recursion's levels where contours do not match.
    void originalSlab(const Layer& lower, const Layer& upper, const SliceFields& fields,
                      std::size_t lowerSlice, std::size_t upperSlice);

    /// Caps every contour of `end` (up or down from its plane) by `offsetMm`
    /// as a piece of its own (recon/Caps).
    void capLayer(const Layer& end, CapReach reach, const SliceFields& fields, std::size_t slice);
    /// The guaranteed cap (recon/Caps guaranteedCap): the end contours
    /// extruded under a flat lid, closing cavities under lids of their own.
    void guaranteedCapLayer(const Layer& end, CapReach reach, const SliceFields& fields,
                            std::size_t slice);
    /// The guaranteed closing of the slab between two layers: one prism
    /// piece over all their contours. True when it holds as floats
    /// (closeByPrisms).
    bool closeSlabByPrisms(const Layer& lower, const Layer& upper);
    /// The slab between two layers of repeated contours (recon/StepSlabs)
    /// as one prism piece stepping at its middle height; false, with nothing
    /// added, where that closing does not hold as floats.
    bool stepSlab(const Layer& lower, const Layer& upper);

    /// Per piece, whether its own pairs were searched (clean) at the
    /// coordinates a mesh file holds: the whole check need not search them
    /// again (geometry/StackedMeshCheck).
    const std::vector<bool>& searchedPieces() const { return searched_; }
    void markSearched(std::uint32_t piece);

    /// Hands over what was built since the builder held only its first
    /// `sharedPoints` points, with whether its piece was searched, and
    /// forgets it (intermediate layers included): the next slab starts
    /// afresh on the same points.
    SurfacePart takePart(std::size_t sharedPoints, bool& searched);

  private:
    // What caps ask of the reconstruction (CapSite).
    SliceFields fieldsOf(const std::vector<LayerPart>& parts,
                         std::optional<SliceGrid> grid) override;
    const Layer& addIsolineLayer(double zMm, std::vector<Polygon> isolines,
                                 const LayerPart& of) override;
    void joinLayers(const LayerPart& lower, const SliceFields& lowerField, const LayerPart& upper,
                    const SliceFields& upperField) override;
    bool isCleanCap(std::size_t before, const LayerPart& end) override;

    bool slab(const LayerPart& lower, const LayerPart& upper, SlabFields sides, int depth);
    /// Joins pairs of ending sections that slid farther than their width
    /// between the planes (recon/SlidingSections) by straight bands, and
    /// takes them off the ending lists.
    void joinSlidSections(LayerPart& endingLower, LayerPart& endingUpper);
    /// The band stitchStrip makes between two contours (marked a loft band
    /// where `loft`), kept unless it folds through itself as a mesh file
    /// holds it (then nothing is added: false); its own pairs are then known
    /// clean. O(p log p) in its p triangles.
    bool stitchUnfolded(const std::vector<std::uint32_t>& lowerIds, const AxisPositions& lowerAt,
                        const std::vector<std::uint32_t>& upperIds, const AxisPositions& upperAt,
                        bool loft);
    bool strip(const LayerPart& x, const LayerPart& y, const MedialAxis& axis,
               const SliceGrid& axisGrid, std::uint32_t lowerLocal, std::uint32_t upperLocal);
    void recurse(const LayerPart& x, const LayerPart& y, int depth, SlabFields sides,
                 const SliceSum* knownSum);
    void cap(const LayerPart& end, CapReach reach, const SliceFields& fields, std::size_t slice);
    bool isCleanPiece(std::size_t before, std::initializer_list<const LayerPart*> sides) const;
    bool breakTheirPiece(std::size_t before) const;
    SliceGrid windowAround(const std::vector<LayerPart>& parts) const;
    void markSearched() { markSearched(builder_.piece()); }

    ocl::Runtime& runtime_;
    const ReconstructionOptions& options_;
    const SliceGrid& grid_;
    ReconstructionStats& stats_;
    SurfaceBuilder builder_;
    StackTraits stack_;
    std::vector<bool> searched_;  // per piece
    std::deque<Layer> layers_;    // intermediate contours; LayerParts point into it
};

}  // namespace dfrecon
