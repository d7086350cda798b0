// Rounding a soup's points to floats, as files hold them: every coordinate
// of every point, whatever the count (GCC 12.2's vectorizer once left the x
// and y of the points after the last group of four unrounded).
#include <gtest/gtest.h>

#include "geometry/TriangleSoup.hpp"

using namespace dfrecon;

namespace {

// Through memory, so that no optimisation can skip the conversions.
bool isFloat(double v) {
    volatile float f = static_cast<float>(v);
    return double(f) == v;
}

}  // namespace

TEST(TriangleSoup, RoundPointsToFloatRoundsEveryCoordinate) {
    for (std::size_t count = 1; count <= 9; ++count) {
        TriangleSoup soup;
        for (std::size_t k = 0; k < count; ++k)
            soup.points.push_back({-187.3 + double(k) / 3.0, 91.7 / 7.0 + double(k), -1234.56789});
        roundPointsToFloat(soup);
        for (std::size_t k = 0; k < count; ++k) {
            const Vec3& p = soup.points[k];
            for (double c : {p.x, p.y, p.z})
                EXPECT_TRUE(isFloat(c)) << count << " points, point " << k;
            EXPECT_NEAR(p.x, -187.3 + double(k) / 3.0, 1e-4);
        }
    }
}
