#include "geometry/TriangleCells.hpp"

#include <algorithm>
#include <cmath>

#include "geometry/SurfaceMeasures.hpp"

namespace dfrecon {

namespace {

// The number of cells of `soup` at spacingMm where that is at most
// `limit`. Past the limit the walk stops, and the number is estimated from
// the cells counted over the area they cover (always above `limit`).
double cellCountUpTo(const TriangleSoup& soup, double spacingMm, double limit) {
    double count = 0, countedAreaMm2 = 0;
    for (const auto& tri : soup.triangles) {
        const bool whole =
            forEachCellWhile(soup.points[tri[0]], soup.points[tri[1]], soup.points[tri[2]],
                             spacingMm, [&](const Vec3&, double weightMm2) {
                                 ++count;
                                 countedAreaMm2 += weightMm2;
                                 return count <= limit;
                             });
        if (!whole) {
            const double areaMm2 = measureSurface(soup).areaMm2;
            return countedAreaMm2 > 0 ? std::max(count, count * areaMm2 / countedAreaMm2) : count;
        }
    }
    return count;
}

}  // namespace

double cellSpacingWithinBudget(const std::vector<const TriangleSoup*>& soups, double spacingMm,
                               std::size_t maxCells) {
    const double limit = double(maxCells);
    // Past the longest edge every triangle is one cell, and no spacing makes
    // fewer: a surface of more triangles than the budget stops there.
    double longestEdgeMm = 0;
    for (const TriangleSoup* soup : soups)
        for (const auto& tri : soup->triangles)
            for (int k = 0; k < 3; ++k)
                longestEdgeMm =
                    std::max(longestEdgeMm, length(soup->points[tri[std::size_t(k)]] -
                                                   soup->points[tri[std::size_t((k + 1) % 3)]]));
    for (;;) {
        double cells = 0;
        for (const TriangleSoup* soup : soups)
            cells = std::max(cells, cellCountUpTo(*soup, spacingMm, limit));
        if (cells <= limit || spacingMm >= longestEdgeMm) return spacingMm;
        // Cells fall with the square of the spacing, or slower (at least one
        // per triangle): grow by the root, at least by 5 %.
        spacingMm *= std::max(1.05, std::sqrt(cells / limit));
    }
}

}  // namespace dfrecon
