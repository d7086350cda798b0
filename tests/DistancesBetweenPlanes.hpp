#pragma once
// How far a reconstructed surface lies from the analytic shape its contours
// were cut from, between the first and the last contour plane (beyond them
// the caps guess where the shape ends).
#include <cmath>
#include <vector>

#include "contours/ContourSet.hpp"
#include "geometry/TriangleSoup.hpp"
#include "shapes/AnalyticShapes.hpp"
#include "simplify/SimplificationVerifier.hpp"

namespace dfrecon::testing {

/// |signed distance| to `shape` of `samples` points of `surface` (area
/// weighted, seeded) that lie between `roi`'s first and last plane.
inline std::vector<double> distancesBetweenPlanes(const AnalyticShape& shape, const Roi& roi,
                                                  const TriangleSoup& surface,
                                                  std::size_t samples = 20000) {
    const double lo = roi.slices.front().zMm, hi = roi.slices.back().zMm;
    std::vector<double> distances;
    for (const Vec3& p : sampleTriangles(surface, samples, 5))
        if (p.z >= lo && p.z <= hi) distances.push_back(std::abs(shape.signedDistance(p)));
    return distances;
}

}  // namespace dfrecon::testing
