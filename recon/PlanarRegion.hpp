#pragma once
// Triangulating planar regions bounded by contours: the flat pieces of a
// reconstructed surface (end caps, and the lids that close a branching region
// at the recursion limit). A constrained Delaunay triangulation (CGAL) of all
// contour edges, with the points where edges of different contours cross
// inserted, keeps the triangles whose weighted winding number is non-zero.
#include <array>
#include <cstdint>
#include <vector>

#include "geometry/Polygon.hpp"

namespace dfrecon {

/// A contour and the weight its winding number counts with (+1 or -1).
struct WeightedContour {
    const Polygon* polygon = nullptr;
    int weight = 1;
};

struct PlanarRegion {
    std::vector<Point2> points;  // triangulation vertices
    /// Triangles counter-clockwise in the plane, and the sign of
    /// Σ weight·winding at each (+1 or -1; triangles where it is 0 are dropped).
    std::vector<std::array<std::uint32_t, 3>> triangles;
    std::vector<int> sign;
    /// edgeChains[c][k]: the points along edge k of contour c (from its
    /// vertex k to vertex k+1), ends included; interior entries are where
    /// other contours' edges cross or touch it.
    std::vector<std::vector<std::vector<std::uint32_t>>> edgeChains;
};

/// Triangulates the plane region where Σ weight·winding(contour) ≠ 0.
/// `steinerPoints` (which must not lie on any contour) are added as interior
/// vertices, e.g. to lift a dome. Contours may cross each other (the
/// crossings become vertices) but none may cross itself. Θ(n log n) for n
/// points in total; faces are classified by walking across edges from the
/// unbounded region, so slivers along contours are classified exactly.
PlanarRegion triangulateRegion(const std::vector<WeightedContour>& contours,
                               const std::vector<Point2>& steinerPoints = {});

}  // namespace dfrecon
