#pragma once
// Zero isolines of a field sampled at pixel centres, as closed polygons in
// millimetres: geometry/IsoLines.hpp's marching squares mapped onto a SliceGrid.
// Used for the intermediate contours of the recursion: the zero set of
// D_lower + D_upper is the contour half-way between two slices
// (reconstruction paper Fig. 7).
#include <vector>

#include "field/SliceGrid.hpp"
#include "geometry/Polygon.hpp"

namespace dfrecon {

/// The borders of the region where `values` < 0 (row-major on `grid`;
/// values outside the grid count as positive), with crossings placed by
/// linear interpolation along pixel-centre edges. Every polygon is closed
/// and simple, no two cross; outer borders run counter-clockwise and hole
/// borders clockwise (the orientation convention of Slice). Saddle cells
/// connect their negative corners when the cell's mean is negative. O(pixels).
std::vector<Polygon> zeroIsolines(const std::vector<float>& values, const SliceGrid& grid);

}  // namespace dfrecon
