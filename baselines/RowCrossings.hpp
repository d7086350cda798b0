#pragma once
// Where a row y = const crosses a plane's contours, sorted: the even-odd
// fill both voxel baselines use (inside between the 1st and 2nd crossing,
// the 3rd and 4th, ...). Half-open in y, so a vertex on the row counts once.
// O(points + crossings log crossings).
#include <algorithm>
#include <vector>

#include "contours/ContourSet.hpp"

namespace dfrecon {

inline void rowCrossings(const Slice& slice, double y, std::vector<double>& crossings) {
    crossings.clear();
    for (const Polygon& contour : slice.contours)
        for (std::size_t e = 0; e < contour.size(); ++e) {
            const Point2 a = contour[e], b = contour[(e + 1) % contour.size()];
            if ((a.y <= y) != (b.y <= y))
                crossings.push_back(a.x + (y - a.y) / (b.y - a.y) * (b.x - a.x));
        }
    std::sort(crossings.begin(), crossings.end());
}

}  // namespace dfrecon
