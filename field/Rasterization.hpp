#pragma once
// ROIs on a voxel grid: the grid that holds a set of ROIs, and the voxels of
// any grid (a planning CT's, a NIfTI's) whose centres lie inside an ROI,
// read from its 3D distance field (field/DistanceField3D: inside where it is
// negative, so the voxels follow the surface the reconstruction follows,
// flat caps included). What `dfrecon rasterize` writes as a label map.
#include <cstddef>
#include <vector>

#include "contours/ContourSet.hpp"
#include "field/DistanceField3D.hpp"
#include "geometry/VolumeGrid.hpp"

namespace dfrecon {

/// The frame every ROI of `rois` shares, or patient LPS (the identity)
/// where they differ. O(ROIs).
PlaneFrame sharedFrame(const std::vector<const Roi*>& rois);

/// A grid of cubic voxels of `voxelMm` on the ROIs' shared axes (patient
/// LPS where they have none), covering their contours plus a voxel, and
/// half the largest slice spacing beyond the end planes (where caps reach).
/// Throws std::invalid_argument beyond 4096 voxels a side. O(points).
VolumeGeometry gridAroundRois(const std::vector<const Roi*>& rois, double voxelMm);

/// The linear indices (VolumeGeometry::linearIndex) of the voxels of `grid`
/// whose centres lie where `field` (of an ROI in plane frame `frame`) is
/// negative, in increasing order. Voxels beyond the field's box are outside;
/// only the voxels of that box are visited. A voxel centre on one of
/// `planes` (within 0.01 mm, as planning systems put contours on image
/// planes) is inside exactly when it is inside that plane's contours (the
/// even-odd rule they were read by, Sunday's half-open rule at vertices,
/// the exact side test near an edge), whatever
/// the field's pixel size: sampled fields put centres a few micrometres from
/// a contour on the wrong side. O(voxels in the box), plus O(e log e) per
/// row of voxels on a plane for its e contour edges.
std::vector<std::size_t> voxelsInside(const DistanceField3D& field, const PlaneFrame& frame,
                                      const VolumeGeometry& grid,
                                      const std::vector<Slice>& planes = {});

}  // namespace dfrecon
