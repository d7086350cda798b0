#pragma once
// ROIs on a voxel grid: the grid that holds a set of ROIs, and the voxels of
// any grid (a planning CT's, a NIfTI's) whose centres lie inside an ROI:
// inside its reconstructed solid (ray parity against the triangles, what
// `dfrecon rasterize` writes by default, so a label map's volume converges
// to the surface's), or where its 3D distance field is negative
// (field/DistanceField3D, `rasterize --inside field`). Either way a centre
// on a contour plane is inside exactly when it is inside the contours.
#include <cstddef>
#include <vector>

#include "contours/ContourSet.hpp"
#include "field/DistanceField3D.hpp"
#include "geometry/TriangleSoup.hpp"
#include "geometry/VolumeGrid.hpp"

namespace dfrecon {

/// The frame every ROI of `rois` shares, or patient LPS (the identity)
/// where they differ. O(ROIs).
PlaneFrame sharedFrame(const std::vector<const Roi*>& rois);

/// A grid of cubic voxels of `voxelMm` on the ROIs' shared axes (patient
/// LPS where they have none), covering their contours plus one and a half
/// voxels, and half the largest slice spacing beyond the end planes (where
/// caps reach). Placed so that the contours' least coordinates and the
/// lowest flat cap fall between centres, not on them: a centre on a flat
/// face is inside or not by rounding, and a whole row or layer of them
/// moves the volume by half a voxel times the face's area. Throws
/// std::invalid_argument beyond 4096 voxels a side. O(points).
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

/// The linear indices of the voxels of `grid` whose centres lie inside the
/// closed surface `solid` (patient mm; every edge used by an even number of
/// triangles, as in any valid closed solid), in increasing order: those
/// with an odd number of the surface's crossings on the ray from the centre
/// along the grid's first axis. Every triangle adds its crossing to each
/// row of voxel centres its shadow (along that axis) covers; a row through
/// an edge or a corner of a shadow is counted as if moved by a symbolic
/// perturbation (exact orientation tests on the points as given), so an
/// edge two triangles share counts once and a fold twice or never: the
/// parity is exact, and only a centre within rounding of the surface may
/// fall either side. A centre on one of `planes` (of an ROI in plane frame
/// `frame`) is judged by that plane's contours as voxelsInside judges it.
/// O(triangles + crossings log crossings + voxels in the solid's box).
std::vector<std::size_t> voxelsInsideSolid(const TriangleSoup& solid, const PlaneFrame& frame,
                                           const VolumeGeometry& grid,
                                           const std::vector<Slice>& planes = {});

}  // namespace dfrecon
