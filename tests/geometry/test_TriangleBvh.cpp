// Nearest-triangle queries against brute force, and the closest point on a
// triangle against dense sampling of it.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "geometry/TriangleBvh.hpp"
#include "tests/geometry/RandomSoup.hpp"

using namespace dfrecon;

TEST(TriangleBvh, ClosestPointOnTriangleBeatsDenseSamples) {
    std::mt19937 random(4);
    std::uniform_real_distribution<double> u(-3, 3);
    for (int trial = 0; trial < 200; ++trial) {
        const Vec3 a{u(random), u(random), u(random)}, b{u(random), u(random), u(random)},
            c{u(random), u(random), u(random)}, p{u(random), u(random), u(random)};
        const Vec3 q = closestPointOnTriangle(p, a, b, c);
        double sampled = INFINITY;
        const int n = 60;
        for (int i = 0; i <= n; ++i)
            for (int j = 0; i + j <= n; ++j) {
                const Vec3 s = a + (double(i) / n) * (b - a) + (double(j) / n) * (c - a);
                sampled = std::min(sampled, length(p - s));
            }
        EXPECT_LE(length(p - q), sampled + 1e-12);  // nothing on it is nearer
        EXPECT_GE(length(p - q), sampled - 0.2);    // and it is on the triangle
        const Vec3 n3 = cross(b - a, c - a);
        EXPECT_NEAR(dot(q - a, n3) / length(n3), 0, 1e-9);  // in the plane
    }
}

TEST(TriangleBvh, NearestMatchesBruteForce) {
    std::mt19937 random(5);
    const TriangleSoup soup = dfrecon::testing::randomTriangles(5, 500, 30, 2);
    const TriangleBvh bvh(soup);
    std::uniform_real_distribution<double> query(-10, 40);
    for (int trial = 0; trial < 300; ++trial) {
        const Vec3 p{query(random), query(random), query(random)};
        double brute = INFINITY;
        for (const auto& t : soup.triangles)
            brute = std::min(
                brute, length(p - closestPointOnTriangle(p, soup.points[t[0]], soup.points[t[1]],
                                                         soup.points[t[2]])));
        EXPECT_DOUBLE_EQ(bvh.nearest(p).distance, brute);
    }
}

TEST(TriangleBvh, SmallSoupsAndBoundedSearchesMatchBruteForce) {
    // One to nine triangles: the root is a leaf, or one level above leaves.
    std::mt19937 random(6);
    std::uniform_real_distribution<double> query(-10, 40);
    for (int count = 1; count <= 9; ++count) {
        const TriangleSoup soup =
            dfrecon::testing::randomTriangles(unsigned(count), std::uint32_t(count), 30, 2);
        const TriangleBvh bvh(soup);
        for (int trial = 0; trial < 50; ++trial) {
            const Vec3 p{query(random), query(random), query(random)};
            double brute2 = INFINITY;
            std::size_t nearest = SIZE_MAX;
            for (std::size_t t = 0; t < soup.triangles.size(); ++t) {
                const auto& tri = soup.triangles[t];
                const Vec3 q = closestPointOnTriangle(p, soup.points[tri[0]], soup.points[tri[1]],
                                                      soup.points[tri[2]]);
                if (dot(p - q, p - q) < brute2) brute2 = dot(p - q, p - q), nearest = t;
            }
            const TriangleBvh::Nearest found = bvh.nearest(p);
            EXPECT_EQ(found.distance2, brute2) << count << " triangles";
            EXPECT_EQ(found.triangle, nearest) << count << " triangles";
            // Bounded: nothing strictly within the answer's own distance.
            EXPECT_EQ(bvh.nearestWithin(p, brute2).triangle, SIZE_MAX);
            EXPECT_EQ(bvh.nearestWithin(p, std::nextafter(brute2, INFINITY)).triangle, nearest);
        }
    }
}
