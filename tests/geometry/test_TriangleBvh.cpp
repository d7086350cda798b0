// Nearest-triangle queries against brute force, the closest point on a
// triangle against dense sampling of it, and the pair search against all pairs.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <set>
#include <stdexcept>
#include <utility>
#include <vector>

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

namespace {

// The nearest triangle by trying every one (the first of equals) and its
// squared distance.
std::pair<std::size_t, double> bruteForceNearest(const TriangleSoup& soup, Vec3 p) {
    std::pair<std::size_t, double> best{SIZE_MAX, INFINITY};
    for (std::size_t t = 0; t < soup.triangles.size(); ++t) {
        const auto& tri = soup.triangles[t];
        const Vec3 q = closestPointOnTriangle(p, soup.points[tri[0]], soup.points[tri[1]],
                                              soup.points[tri[2]]);
        if (dot(p - q, p - q) < best.second) best = {t, dot(p - q, p - q)};
    }
    return best;
}

}  // namespace

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
            const auto [nearest, brute2] = bruteForceNearest(soup, p);
            const TriangleBvh::Nearest found = bvh.nearest(p);
            EXPECT_EQ(found.distance2, brute2) << count << " triangles";
            EXPECT_EQ(found.triangle, nearest) << count << " triangles";
            // Bounded: nothing strictly within the answer's own distance.
            EXPECT_EQ(bvh.nearestWithin(p, brute2).triangle, SIZE_MAX);
            EXPECT_EQ(bvh.nearestWithin(p, std::nextafter(brute2, INFINITY)).triangle, nearest);
        }
    }
}

// Nested triangles, each 1.5 times the size of the one before: the area
// heuristic peels the largest off at every level. The tree must still stay
// shallow enough for the searches' fixed stacks (64 in the kernels) and
// answer as brute force.
TEST(TriangleBvh, PeelingSplitsStayShallowAndExact) {
    TriangleSoup soup;
    const std::size_t count = 800;
    for (std::size_t k = 0; k < count; ++k) {
        const double size = std::pow(1.5, double(k) / 2);
        const auto first = std::uint32_t(soup.points.size());
        soup.points.push_back({0, 0, 0});
        soup.points.push_back({size, 0, 0});
        soup.points.push_back({0.3 * size, size, 0.5 * size});
        soup.triangles.push_back({first, first + 1, first + 2});
    }
    const TriangleBvh bvh(soup);
    // The deepest leaf.
    std::vector<std::pair<int, int>> stack{{0, 0}};
    int deepest = 0;
    while (!stack.empty()) {
        const auto [node, depth] = stack.back();
        stack.pop_back();
        deepest = std::max(deepest, depth);
        const TriangleBvh::Node& n = bvh.nodes()[std::size_t(node)];
        if (n.left >= 0) {
            stack.push_back({n.left, depth + 1});
            stack.push_back({n.right, depth + 1});
        }
    }
    EXPECT_LE(deepest, 24 + int(std::ceil(std::log2(double(count) / 4))) + 1);
    std::mt19937 random(7);
    std::uniform_real_distribution<double> scale(0, 60), direction(-1, 1);
    for (int trial = 0; trial < 200; ++trial) {
        const double s = std::pow(1.5, scale(random));
        const Vec3 p{s * direction(random), s * direction(random), s * direction(random)};
        EXPECT_EQ(bvh.nearest(p).distance2, bruteForceNearest(soup, p).second);
    }
}

// A hierarchy for pairs only visits every pair whose boxes overlap (its
// float boxes are rounded outward), each once, split over tasks or not, and
// refuses nearest searches.
TEST(TriangleBvh, PairSearchVisitsEveryOverlappingPairOnce) {
    const TriangleSoup soup = dfrecon::testing::randomTriangles(3, 3000, 40, 1.0);
    std::vector<Box3> boxes(soup.triangles.size());
    for (std::size_t t = 0; t < boxes.size(); ++t)
        for (std::uint32_t v : soup.triangles[t]) boxes[t].add(soup.points[v]);
    std::set<std::pair<std::size_t, std::size_t>> expected;
    for (std::size_t i = 0; i < boxes.size(); ++i)
        for (std::size_t j = i + 1; j < boxes.size(); ++j)
            if (boxes[i].overlaps(boxes[j])) expected.insert({i, j});
    ASSERT_GT(expected.size(), 100u);
    for (const BvhQueries queries : {BvhQueries::All, BvhQueries::PairsOnly}) {
        const TriangleBvh bvh(soup, BvhSplit::Halving, queries);
        std::multiset<std::pair<std::size_t, std::size_t>> whole, split;
        bvh.selfPairs([&](std::size_t i, std::size_t j) {
            whole.insert({std::min(i, j), std::max(i, j)});
        });
        for (const TriangleBvh::NodePair& task : bvh.selfPairTasks(64))
            bvh.selfPairsUnder(task, [&](std::size_t i, std::size_t j) {
                split.insert({std::min(i, j), std::max(i, j)});
            });
        EXPECT_EQ(whole, split);
        // Every overlapping pair, once; any other only within float rounding.
        for (const auto& pair : expected) EXPECT_EQ(whole.count(pair), 1u);
        EXPECT_EQ(std::set(whole.begin(), whole.end()).size(), whole.size());
        EXPECT_LE(whole.size(), expected.size() + expected.size() / 100);
    }
    const TriangleBvh pairsOnly(soup, BvhSplit::Halving, BvhQueries::PairsOnly);
    EXPECT_THROW(pairsOnly.nearest({0, 0, 0}), std::logic_error);
}

// Skipping node pairs of one group (nodeGroups) leaves out only pairs of
// triangles within one group other than 0, and every pair across groups is
// still visited, in the order the search without skipping visits it.
TEST(TriangleBvh, NodeGroupsSkipOnlyPairsWithinAGroup) {
    const TriangleSoup soup = dfrecon::testing::randomTriangles(5, 3000, 40, 1.0);
    // Groups in runs along x (as strips of a piece are), with group 0 mixed in.
    std::vector<std::uint32_t> group(soup.triangles.size());
    for (std::size_t t = 0; t < group.size(); ++t) {
        const Vec3 p = soup.points[soup.triangles[t][0]];
        group[t] = t % 7 == 0 ? 0 : 1 + std::uint32_t(std::floor((p.x + 40) / 10));
    }
    const TriangleBvh bvh(soup, BvhSplit::Halving, BvhQueries::PairsOnly);
    const std::vector<std::uint32_t> nodeGroup = bvh.nodeGroups(group);
    auto skip = [&](int a, int b) {
        return nodeGroup[std::size_t(a)] != 0 &&
               nodeGroup[std::size_t(a)] == nodeGroup[std::size_t(b)];
    };
    auto sameGroup = [&](std::size_t i, std::size_t j) {
        return group[i] != 0 && group[i] == group[j];
    };
    std::vector<std::pair<std::size_t, std::size_t>> all, skipping;
    std::size_t skipped = 0;
    for (const TriangleBvh::NodePair& task : bvh.selfPairTasks(64)) {
        bvh.selfPairsUnder(task, [&](std::size_t i, std::size_t j) {
            if (!sameGroup(i, j)) all.emplace_back(i, j);
        });
        bvh.selfPairsUnder(
            task,
            [&](std::size_t i, std::size_t j) {
                if (!sameGroup(i, j)) skipping.emplace_back(i, j);
            },
            [&](int a, int b) {
                skipped += skip(a, b);
                return skip(a, b);
            });
    }
    ASSERT_GT(all.size(), 100u);
    EXPECT_GT(skipped, 0u);
    EXPECT_EQ(all, skipping);
    // A node's group is its triangles' own where they all share one.
    std::vector<std::uint32_t> none(soup.triangles.size(), 0);
    for (std::uint32_t g : bvh.nodeGroups(none)) EXPECT_EQ(g, 0u);
    std::vector<std::uint32_t> one(soup.triangles.size(), 3);
    for (std::uint32_t g : bvh.nodeGroups(one)) EXPECT_EQ(g, 3u);
}
