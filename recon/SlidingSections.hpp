#pragma once
// A thin structure lying nearly flat (a plate tilted 20 degrees from the
// planes, an oblique nerve or muscle at 5 mm planes) is cut into sections
// that slide farther than their own width from plane to plane: no section
// overlaps the next, so no medial axis joins them and each would be capped
// on its own, a stack of loose lids where the anatomy is one sheet (and
// shape-based interpolation loses half its volume). Such a pair — a section
// ending below and one beginning right above it, the same shape once the
// slide is taken out — is joined by a band whose rungs pair the points at
// the same share of each contour's length, turned to fit best.
#include <cstdint>
#include <utility>
#include <vector>

#include "recon/StripStitching.hpp"
#include "recon/SurfaceBuilder.hpp"

namespace dfrecon {

struct SlidingSectionOptions {
    /// The most a pair's centroids may lie apart, in slab heights: 3 joins
    /// sheets tilted down to 18 degrees from the planes.
    double maxSlideSlabs = 3;
    /// ... and in the sections' own extent along the slide (the larger's):
    /// a sheet or tube slides its extent times its thickness over the slab
    /// height, so 2 joins what is at least half as thick as the slab is
    /// high, and not two specks far apart for their size.
    double maxSlideExtents = 2;
    /// The least area the two must share (intersection over union) once the
    /// slide is taken out.
    double minAlignedOverlap = 0.5;
    /// A sheet's last section (its tapering rim) may be smaller than the one
    /// before by up to this factor; it must then lie within it once aligned
    /// (minTaperContainment of its area).
    double maxTaperRatio = 8;
    double minTaperContainment = 0.9;
};

/// A pair of sections to join: indices into the two parts' contour lists.
struct SlidPair {
    std::uint32_t lower = 0, upper = 0;
};

/// Pairs among contours that end in a slab (`lowerEnding` on its lower
/// plane, `upperEnding` on its upper one, none joined to anything across
/// the slab): outer contours (no ending hole inside either) whose centroids
/// lie within options.maxSlideSlabs × `slabHeightMm` and within
/// options.maxSlideExtents × their extent along that slide, and whose
/// regions, centroids put on each other, overlap by
/// options.minAlignedOverlap (intersection over union, sampled on a 40 × 40
/// grid) where their areas are within a factor of two, or where one is up
/// to options.maxTaperRatio times smaller (a rim), lies within the other
/// by options.minTaperContainment of its area; each the other's best such
/// partner (by intersection over union). Work: O(pairs × (1600 + points) points).
std::vector<SlidPair> matchSlidingSections(const LayerPart& lowerEnding,
                                           const LayerPart& upperEnding, double slabHeightMm,
                                           const SlidingSectionOptions& options = {});

/// Where the vertices of `lower` and `upper` fall along one common
/// parameter of period 1 (for stitchStrip): each vertex at its share of its
/// contour's length, the upper contour's start turned so that, the slide
/// taken out, points of equal parameter lie closest (least squares over 64
/// samples, 256 turns tried). O(points + 16 384 log points).
std::pair<AxisPositions, AxisPositions> slidCorrespondence(const Polygon& lower,
                                                           const Polygon& upper);

}  // namespace dfrecon
