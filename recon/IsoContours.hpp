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

/// What isolinesEnclosing aims at: a region of `areaMm2`, at a level within
/// [0, maxLevelMm], and, where `within` is given (row-major on the grid), a
/// region that stays where it is <= 0.
struct EnclosedArea {
    double areaMm2 = 0;
    double maxLevelMm = 0;
    const std::vector<float>* within = nullptr;
};

/// The isolines of `values` at the level c in [0, target.maxLevelMm] whose
/// region {values < c} (cut to {within <= 0}) encloses target.areaMm2 (to
/// 1 %, never more), or at maxLevelMm where even that encloses less; the
/// zero isolines themselves where they already enclose the target or
/// enclose nothing (a level is never raised to make a region where there
/// was none). The recursion's intermediate contours: the zero set of
/// D_lower + D_upper pinches where the two sides overlap little in
/// projection (a small contour below a large one), and the slab loses the
/// volume its sections imply; raised to the mean of the two sides' areas,
/// within the union of their regions (min(D_lower, D_upper) <= 0, where the
/// zero set always lies), the middle contour interpolates the sections'
/// areas linearly, as the planning system's contour volume counts them, and
/// never reaches where neither plane's contours do (a label map's voxels
/// bound it). Work: up to 14 zeroIsolines calls.
std::vector<Polygon> isolinesEnclosing(const std::vector<float>& values, const SliceGrid& grid,
                                       const EnclosedArea& target);

}  // namespace dfrecon
