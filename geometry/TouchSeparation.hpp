#pragma once
// Opening the points where contours of one plane touch. Planning systems and
// mask converters draw contours that meet at isolated points (two blobs
// joined at a pixel corner, a hole touching its outline). A solid bounded by
// them is pinched there: not a 2-manifold, so no surface through those
// contours can be a valid solid. The rule applied everywhere: regions are
// open sets, so a touch point belongs to neither side; it is opened by moving
// each contour's copy of the point a tiny distance away from the other
// contour — into its own enclosed region when the two are siblings (two
// outlines, two holes), out of the enclosing contour's region and into the
// enclosed one's when one holds the other (a hole touching its outline).
#include <cstddef>
#include <vector>

#include "geometry/Polygon.hpp"

namespace dfrecon {

/// Opens every touch between two contours of `contours` by `gapMm` (each
/// side moves about half of it; less where an adjacent edge is shorter than
/// ten times that). A touch inside an edge first gets a vertex there. Every
/// other point stays where it was. Returns how many touches were opened.
/// O(n) for n points, plus the contact search (findContourTouches).
std::size_t separateTouchingContours(std::vector<Polygon>& contours, double gapMm);

}  // namespace dfrecon
