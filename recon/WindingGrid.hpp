#pragma once
// Inside/outside of a slice at every pixel, as the winding number of its
// contours: the sign source for the 2D distance fields (non-zero = inside,
// which is right for holes and islands once contours are oriented by nesting).
#include <vector>

#include "cl/Runtime.hpp"
#include "io/ContourSet.hpp"
#include "recon/SliceGrid.hpp"

namespace dfrecon {

/// Winding number at each pixel centre, row-major (index j·width + i),
/// computed by the `winding_number_grid` OpenCL kernel in float32 relative to
/// the grid origin. O(pixels · segments) work.
std::vector<int> windingGrid(ocl::Runtime& runtime, const std::vector<Polygon>& contours,
                             const SliceGrid& grid);

/// The plain C++ reference in double precision; same layout. Agrees with the
/// kernel except at pixel centres within float rounding of a contour.
std::vector<int> windingGridReference(const std::vector<Polygon>& contours, const SliceGrid& grid);

}  // namespace dfrecon
