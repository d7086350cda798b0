#pragma once
// Contour simplification with a guaranteed bound (reconstruction paper §2.3):
// Douglas–Peucker on closed polygons, inserting the original point farthest
// from the current polygon until every original point is within epsilon.
// Kept vertices are original vertices, and each simplified edge records the
// largest distance from the original chain it replaces, which later error
// bounds add up.
#include <cstddef>
#include <vector>

#include "geometry/Polygon.hpp"

namespace dfrecon {

struct SimplifiedContour {
    Polygon points;                          // kept original vertices, in order
    std::vector<std::size_t> originalIndex;  // where each kept vertex was
    /// Edge k joins points[k] and points[k+1 mod m]; its deviation is the max
    /// distance of the original vertices from originalIndex[k] to
    /// originalIndex[k+1] (cyclically) to that edge. Always <= epsilon.
    std::vector<double> edgeDeviationMm;
};

/// Simplifies one closed contour (at least 3 points) so every original point
/// is within `epsilonMm` of the result, keeping at least 3 vertices.
/// epsilonMm <= 0 returns the contour unchanged. O(n log n) for typical
/// contours, O(n²) worst case.
SimplifiedContour simplifyContour(const Polygon& contour, double epsilonMm);

/// Simplifies all contours of a slice, then refines (inserts the farthest
/// original point of) any simplified edge that makes a contour
/// self-intersect or cross another contour, until none does. The input must
/// be valid (as loading guarantees); the result then is too, and the bound
/// still holds. Contours stay in input order.
std::vector<SimplifiedContour> simplifySlice(const std::vector<Polygon>& contours,
                                             double epsilonMm);

}  // namespace dfrecon
