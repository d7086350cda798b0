#pragma once
// The margins planning systems draw, as the baselines of the exact margin
// benchmark: the ROI rasterised on a voxel grid, then grown or shrunk by
// thresholding a distance map of the mask, so that the result is made of
// whole voxels and only as exact as the grid.
//
// The mask both functions start from (the planning-system stack):
//   - isotropic voxels of `voxelMm` in the ROI's plane coordinates (an
//     axial ROI's frame is the identity; for any other orthonormal frame
//     volumes and distances are the same in plane coordinates);
//   - voxel centres on the first plane in z, and x/y cells whose edges start
//     at the contours' bounding box, so that a contour on a voxel boundary
//     does not pass through centres;
//   - a centre at height z takes the contours of the nearest plane, within
//     half a plane spacing (half-open: a tie goes to the upper plane; the
//     end planes reach half their one gap out, a single plane half its slab
//     thickness or half a voxel), filled even-odd at the centres;
//   - the grid is the contours' bounding box (the planes' half-spacing reach
//     in z) padded by ceil(|marginMm| / voxelMm) + 2 voxels on every side,
//     so the grown mask never reaches the grid's edge.
// Distances are between voxel centres: on an isotropic grid their squares
// are whole numbers of voxelMm², which both functions round to before
// thresholding, so that they count exactly the same voxels when the distance
// maps are exact.
#include <cstddef>

#include "contours/ContourSet.hpp"

namespace dfrecon {

struct VoxelMarginResult {
    double volumeMm3 = 0;    // voxels × voxelMm³
    std::size_t voxels = 0;  // voxels of the grown or shrunk mask
    double seconds = 0;      // wall-clock, rasterising included
};

/// The ROI's mask (above) grown (marginMm > 0) or shrunk (< 0) by
/// thresholding an exact 3D Euclidean distance transform of the mask:
/// grown = voxels whose centre is within marginMm of a mask voxel centre;
/// shrunk = mask voxels farther than |marginMm| from every non-mask voxel
/// centre; marginMm = 0 gives the mask. Exact (2D per plane by OpenCV's
/// Felzenszwalb–Huttenlocher transform, 1D along z by the same algorithm).
/// Throws std::invalid_argument for an ROI without slices or contours, a
/// voxel size that is not positive, or a margin that is not finite.
/// O(voxels of the padded grid + points · rows).
VoxelMarginResult edtVoxelMargin(const Roi& roi, double voxelMm, double marginMm);

/// The same mask grown or shrunk by plastimatch's exact distance map
/// (`plastimatch dmap --algorithm maurer`: signed, negative inside, zero on
/// the mask's boundary voxels, positive outside): the mask is written as a
/// MetaImage (.mha) in a temporary folder, removed afterwards, and the map
/// read back. Grown: mask voxels and those within marginMm of the mask.
/// Shrunk: plastimatch's inside distances stop at the mask's boundary
/// voxels, not at the non-mask voxels, so the map is made of the inverted
/// mask, and mask voxels farther than |marginMm| from it are kept. Signs
/// are not relied on (the mask says which side a voxel is on), so either
/// sign convention gives the same voxels. Same exceptions as edtVoxelMargin;
/// std::runtime_error naming the command when plastimatch is missing or
/// fails, or its output cannot be read. O(voxels) here, plus plastimatch's
/// process and files (seconds includes them).
VoxelMarginResult plastimatchVoxelMargin(const Roi& roi, double voxelMm, double marginMm);

}  // namespace dfrecon
