#pragma once
// Geodesic centroidal segmentation of a surface (geodesic centroidal
// segmentation paper): farthest-point seeds, geodesic Voronoi regions by
// fast marching or the OpenCL fast iterative method, geodesic Lloyd. The
// stage's own entry point is already the public one; this header names it.
#include "segment/Segmentation.hpp"

namespace dfrecon {

// segmentMesh(const MeshGraph&, const SegmentOptions&) -> Segmentation:
// see segment/Segmentation.hpp for the guarantees and cost.

}  // namespace dfrecon
