#pragma once
// Contours that follow a pixel lattice: the borders of label maps and masks
// (a segmentation tool's, an atlas's, dfrecon's own io/labels/MaskContours),
// whose every vertex lies on the lattice of half-pixel steps of its image.
// Between two planes of such contours the voxels bound the structure: it
// lies inside one of the two planes' regions, never beyond both, and smooth
// interpolation must not bulge out of them (recon/LoftSmoothing).
#include <vector>

#include "contours/ContourSet.hpp"

namespace dfrecon {

/// Whether every contour vertex of `slices` lies on one lattice of step q in
/// x and y (q the smallest non-zero step along x or y of any edge, at least
/// 0.05 mm; each coordinate within 0.1 % of q of a multiple of it from the
/// first vertex), with at least 64 vertices. Planning systems' freehand or
/// interpolated contours land on no lattice. O(points).
bool followsPixelLattice(const std::vector<Slice>& slices);

}  // namespace dfrecon
