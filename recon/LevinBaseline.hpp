#pragma once
// The reconstruction users get from today's tools, as the benchmark's
// baseline: shape-based interpolation (Levin 1986; VTK's
// vtkVoxelContoursToSurfaceFilter and planning systems work alike) — the
// slices' 2D signed fields interpolated linearly in z and isosurfaced by
// marching cubes (OpenVDB's volumeToMesh).
#include "field/SliceFields.hpp"
#include "geometry/TriMesh.hpp"

namespace dfrecon {

/// Voxels of the fields' pixel size in x, y and z. Beyond each end slice the
/// surface closes half a slice spacing out (the planning-system volume
/// convention): a virtual slice one spacing away holds max(|D|, pixel), so
/// every inside pixel crosses zero exactly halfway. Only a narrow band of
/// voxels is stored (OpenVDB fills the rest by sign). Outward normals.
/// O(voxels in the band + pixels · slices).
TriMesh levinBaseline(const SliceFields& fields);

}  // namespace dfrecon
