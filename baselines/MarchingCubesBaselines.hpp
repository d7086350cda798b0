#pragma once
// The reconstructions users get from today's tools, as the benchmarks'
// baselines, both iso-surfaced by marching cubes (OpenVDB's volumeToMesh):
//   shape-based interpolation (Levin 1986; VTK's
//     vtkVoxelContoursToSurfaceFilter and planning systems work alike): the
//     slices' 2D signed fields interpolated linearly in z;
//   rasterise + marching cubes (plastimatch or Slicer, then VTK or OpenVDB):
//     each plane's contours filled on a pixel grid, stacked at the planes'
//     spacing, iso-surfaced at the half level.
#include "contours/ContourSet.hpp"
#include "field/SliceFields.hpp"
#include "geometry/TriMesh.hpp"
#include "geometry/TriangleSoup.hpp"

namespace dfrecon {

/// Voxels of the fields' pixel size in x, y and z. Beyond each end slice the
/// surface closes half a slice spacing out (the planning-system volume
/// convention): a virtual slice one spacing away holds max(|D|, pixel), so
/// every inside pixel crosses zero exactly halfway. Only a narrow band of
/// voxels is stored (OpenVDB fills the rest by sign). Outward normals.
/// O(voxels in the band + pixels · slices).
TriMesh levinBaseline(const SliceFields& fields);

/// The ROI's planes filled even-odd at the centres of `pixelMm` pixels,
/// stacked at the mean plane spacing (each plane one voxel thick), and
/// iso-surfaced at the half level. Returned as a plain soup, so that what
/// marching cubes makes is checked as it is. Outward normals. O(pixels ·
/// planes + voxels on the surface).
TriangleSoup rasterBaseline(const Roi& roi, double pixelMm);

}  // namespace dfrecon
