// Rounding a soup's points to floats, as files hold them: every coordinate
// of every point, whatever the count (GCC 12.2's vectorizer once left the x
// and y of the points after the last group of four unrounded). Dropping the
// points no triangle uses, against a brute-force renumbering.
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

// Points below `first` stay even when unused; the rest keep their order, and
// every triangle still names the same positions.
TEST(TriangleSoup, RemoveUnusedPointsFromKeepsTheFirstAndTheOrder) {
    TriangleSoup soup;
    for (int k = 0; k < 12; ++k) soup.points.push_back({double(k), 0.5 * k, -double(k)});
    // Unused: 1 (below first), 5, 6, 9, 11.
    soup.triangles = {{0, 2, 3}, {3, 4, 7}, {8, 10, 4}, {7, 2, 10}};
    const std::size_t first = 4;
    std::vector<std::array<Vec3, 3>> corners;
    for (const auto& t : soup.triangles)
        corners.push_back({soup.points[t[0]], soup.points[t[1]], soup.points[t[2]]});
    soup.points.reserve(100);
    removeUnusedPointsFrom(soup, first);
    std::vector<double> xs;
    for (const Vec3& p : soup.points) xs.push_back(p.x);
    EXPECT_EQ(xs, (std::vector<double>{0, 1, 2, 3, 4, 7, 8, 10}));
    EXPECT_EQ(soup.points.capacity(), soup.points.size());
    ASSERT_EQ(soup.triangles.size(), corners.size());
    for (std::size_t t = 0; t < corners.size(); ++t)
        for (int k = 0; k < 3; ++k) {
            const Vec3& p = soup.points[soup.triangles[t][std::size_t(k)]];
            const Vec3& q = corners[t][std::size_t(k)];
            EXPECT_TRUE(p.x == q.x && p.y == q.y && p.z == q.z) << "triangle " << t;
        }
}

// A part of a soup as a soup of its own: the same corners in the same
// triangles, each point once (shared corners stay shared), the points in
// the order of their ids in the whole.
TEST(TriangleSoup, SoupOfTrianglesKeepsCornersAndSharing) {
    TriangleSoup soup;
    for (int k = 0; k < 12; ++k) soup.points.push_back({double(k), 0.5 * k, -double(k)});
    soup.triangles = {{0, 2, 3}, {9, 4, 7}, {8, 10, 4}, {7, 2, 10}, {1, 5, 6}};
    auto expectSameCorners = [&](const TriangleSoup& part, const std::vector<std::size_t>& from) {
        ASSERT_EQ(part.triangles.size(), from.size());
        for (std::size_t t = 0; t < from.size(); ++t)
            for (int k = 0; k < 3; ++k) {
                const Vec3& p = part.points[part.triangles[t][std::size_t(k)]];
                const Vec3& q = soup.points[soup.triangles[from[t]][std::size_t(k)]];
                EXPECT_TRUE(p.x == q.x && p.y == q.y && p.z == q.z) << "triangle " << t;
            }
    };
    const TriangleSoup tail = soupOfTriangles(soup, 1, 4);
    expectSameCorners(tail, {1, 2, 3});
    std::vector<double> xs;
    for (const Vec3& p : tail.points) xs.push_back(p.x);
    EXPECT_EQ(xs, (std::vector<double>{2, 4, 7, 8, 9, 10}));
    const std::vector<std::size_t> subset{3, 0};
    const TriangleSoup picked = soupOfTriangles(soup, subset);
    expectSameCorners(picked, subset);
    EXPECT_EQ(picked.points.size(), 5u);                        // 0, 2, 3, 7, 10
    EXPECT_EQ(picked.triangles[0][1], picked.triangles[1][1]);  // point 2, shared
    EXPECT_TRUE(soupOfTriangles(soup, 2, 2).points.empty());
}
