#pragma once
// The region that closed contours bound under the even-odd rule (DICOM's
// CLOSEDPLANAR_XOR, and the reading of CLOSED_PLANAR contours that share
// edges, as mask converters write holes that reach the image border).
#include <vector>

#include "geometry/Polygon.hpp"

namespace dfrecon {

/// The exclusive-or of the regions of `contours` (each simple; they may
/// cross, overlap or share edges), as the boundaries of the result: outer
/// boundaries counter-clockwise, holes clockwise, no two crossing. Exact
/// arithmetic (CGAL's Boolean set operations), so shared edges cancel
/// exactly; crossing points are rounded to double. O((n + k) log n) for n
/// points and k crossings.
std::vector<Polygon> xorRegions(const std::vector<Polygon>& contours);

}  // namespace dfrecon
