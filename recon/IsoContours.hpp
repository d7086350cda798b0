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

/// The net area (holes subtracted) the polygons of `isolines` enclose, as
/// zeroIsolines orients them. O(points).
double enclosedAreaMm2(const std::vector<Polygon>& isolines);

/// The isolines of `values` at the level c in [0, maxLevelMm] whose region
/// {values < c} encloses `targetAreaMm2` (to 1 %), or at maxLevelMm where
/// even that encloses less; the zero isolines themselves where they already
/// enclose the target or enclose nothing (a level is never raised to make a
/// region where there was none). The recursion's intermediate contours: the
/// zero set of D_lower + D_upper pinches where the two sides overlap little
/// (a small contour below a large one), and the slab between them loses the
/// volume its sections imply; raised to the mean of the two sides' areas, the
/// middle contour interpolates the sections' areas linearly, as the planning
/// system's contour volume counts them. Work: up to 14 zeroIsolines calls.
std::vector<Polygon> isolinesEnclosing(const std::vector<float>& values, const SliceGrid& grid,
                                       double targetAreaMm2, double maxLevelMm);

}  // namespace dfrecon
