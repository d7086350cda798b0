// The mesh checker on meshes whose answers are known by construction:
// closed genus-0 and genus-1 surfaces, and each kind of defect on purpose.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <numeric>
#include <random>
#include <set>

#include "geometry/MeshCheck.hpp"
#include "io/mesh/MeshIO.hpp"
#include "tests/TestMeshes.hpp"
#include "tests/geometry/RandomSoup.hpp"

using namespace dfrecon;

namespace {

TriangleSoup octahedron(Vec3 c = {}, double r = 1) {
    TriangleSoup s;
    s.points = {{c.x + r, c.y, c.z}, {c.x - r, c.y, c.z}, {c.x, c.y + r, c.z},
                {c.x, c.y - r, c.z}, {c.x, c.y, c.z + r}, {c.x, c.y, c.z - r}};
    s.triangles = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4},
                   {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
    return s;
}

TriangleSoup torus(double R, double r, int n, int m) {
    return dfrecon::testing::torusMesh(R, r, n, m);
}

TriangleSoup merged(TriangleSoup a, const TriangleSoup& b) {
    const auto offset = std::uint32_t(a.points.size());
    a.points.insert(a.points.end(), b.points.begin(), b.points.end());
    for (auto t : b.triangles) a.triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
    return a;
}

}  // namespace

TEST(MeshCheck, OctahedronIsAValidGenusZeroSolid) {
    const MeshCheckReport r = checkMesh(octahedron());
    EXPECT_TRUE(r.validSolid());
    EXPECT_EQ(r.vertices, 6u);
    EXPECT_EQ(r.edges, 12u);
    EXPECT_EQ(r.eulerCharacteristic, 2);
    EXPECT_EQ(r.genus, 0);
    EXPECT_EQ(r.components, 1u);
    EXPECT_NEAR(r.volumeMm3, 4.0 / 3.0, 1e-12);
    EXPECT_NEAR(r.areaMm2, 8 * std::sqrt(3.0) / 2, 1e-12);
}

TEST(MeshCheck, TorusHasGenusOne) {
    const MeshCheckReport r = checkMesh(torus(10, 3, 48, 24));
    EXPECT_TRUE(r.validSolid()) << r.intersectingPairs;
    EXPECT_EQ(r.eulerCharacteristic, 0);
    EXPECT_EQ(r.genus, 1);
    EXPECT_NEAR(r.volumeMm3, 2 * M_PI * M_PI * 10 * 9, 0.02 * 2 * M_PI * M_PI * 90);
}

TEST(MeshCheck, TwoSeparateSolidsAreTwoComponents) {
    const MeshCheckReport r = checkMesh(merged(octahedron(), octahedron({5, 0, 0})));
    EXPECT_TRUE(r.validSolid());
    EXPECT_EQ(r.components, 2u);
    EXPECT_EQ(r.genus, 0);
}

TEST(MeshCheck, MissingTriangleLeavesABoundary) {
    TriangleSoup s = octahedron();
    s.triangles.pop_back();
    const MeshCheckReport r = checkMesh(s);
    EXPECT_EQ(r.boundaryEdges, 3u);
    EXPECT_FALSE(r.watertight());
    EXPECT_EQ(r.genus, -1);
}

TEST(MeshCheck, FlippedTriangleIsMisoriented) {
    TriangleSoup s = octahedron();
    std::swap(s.triangles[3][0], s.triangles[3][1]);
    const MeshCheckReport r = checkMesh(s);
    EXPECT_EQ(r.misorientedEdges, 3u);
    EXPECT_FALSE(r.watertight());
}

TEST(MeshCheck, ThirdTriangleOnAnEdgeIsNonManifold) {
    TriangleSoup s = octahedron();
    s.points.push_back({2, 2, 0});
    s.triangles.push_back({0, 2, 6});
    const MeshCheckReport r = checkMesh(s);
    EXPECT_EQ(r.nonManifoldEdges, 1u);
    EXPECT_FALSE(r.watertight());
}

TEST(MeshCheck, SolidsSharingOnlyAVertexAreNonManifoldThere) {
    // Two octahedra tip to tip: vertex 0 of the first is vertex 1 of the second.
    TriangleSoup s = merged(octahedron(), octahedron({2, 0, 0}));
    for (auto& t : s.triangles)
        for (auto& v : t)
            if (v == 7) v = 0;
    const MeshCheckReport r = checkMesh(s);
    EXPECT_EQ(r.nonManifoldVertices, 1u);
    EXPECT_EQ(r.intersectingPairs, 0u);  // they only touch at the shared vertex
}

TEST(MeshCheck, OverlappingSolidsIntersect) {
    const MeshCheckReport r = checkMesh(merged(octahedron(), octahedron({0.5, 0.3, 0.2})));
    EXPECT_TRUE(r.watertight());
    EXPECT_GT(r.intersectingPairs, 0u);
    EXPECT_FALSE(r.validSolid());
    EXPECT_FALSE(r.intersectingExamples.empty());
}

TEST(MeshCheck, FoldedNeighboursIntersect) {
    // Two coplanar triangles on one edge, on the same side of it.
    TriangleSoup s;
    s.points = {{0, 0, 0}, {1, 0, 0}, {0.5, 1, 0}, {0.5, 0.5, 0}};
    s.triangles = {{0, 1, 2}, {1, 0, 3}};
    EXPECT_EQ(checkMesh(s).intersectingPairs, 1u);
    s.points[3] = {0.5, -1, 0};  // now on the other side: a flat, valid pair
    EXPECT_EQ(checkMesh(s).intersectingPairs, 0u);
}

TEST(MeshCheck, TriangleTriangleCases) {
    const Vec3 t[3] = {{0, 0, 0}, {2, 0, 0}, {0, 2, 0}};
    const Vec3 crossing[3] = {{0.5, 0.5, -1}, {0.5, 0.5, 1}, {3, 3, 0.5}};
    const Vec3 above[3] = {{0, 0, 1}, {2, 0, 1}, {0, 2, 1}};
    const Vec3 touching[3] = {{2, 0, 0}, {3, 0, 1}, {3, 1, -1}};
    const Vec3 coplanarOverlap[3] = {{1, 1, 0}, {3, 1, 0}, {1, 3, 0}};
    const Vec3 coplanarApart[3] = {{3, 3, 0}, {4, 3, 0}, {3, 4, 0}};
    EXPECT_TRUE(trianglesIntersect(t, crossing));
    EXPECT_FALSE(trianglesIntersect(t, above));
    EXPECT_TRUE(trianglesIntersect(t, touching));
    EXPECT_TRUE(trianglesIntersect(t, coplanarOverlap));
    EXPECT_FALSE(trianglesIntersect(t, coplanarApart));
}

TEST(MeshCheck, TrianglesOfOneWallMeetOnlyWhereTheyOverlap) {
    // Two triangles of one vertical wall (the plane y = x + 44.5) from
    // neighbouring slabs, coplanar up to the rounding of a computed lid
    // point: 0.5 mm apart, they must not count as meeting (the orientation
    // signs of a segment lying in the other's plane are noise).
    const Vec3 lower[3] = {{-53.763598326359826, -9.2635583610257584, 20},
                           {-52.081589958158986, -7.581589958964976, 20},
                           {-52.5, -8, 21}};
    const Vec3 apart[3] = {{-53, -8.5, 21}, {-52.5, -8, 22}, {-53, -8.5, 22}};
    const Vec3 overlapping[3] = {{-52.5, -8, 20.5}, {-52, -7.5, 21.5}, {-53, -8.5, 21.5}};
    EXPECT_FALSE(trianglesIntersect(lower, apart));
    EXPECT_FALSE(trianglesIntersect(apart, lower));
    EXPECT_TRUE(trianglesIntersect(lower, overlapping));
    EXPECT_TRUE(trianglesIntersect(overlapping, lower));
}

TEST(MeshCheck, ReadsBrokenFilesWithoutDroppingFaces) {
    // An edge shared by three triangles: OpenMesh's half-edge reader drops
    // one, the soup keeps all three.
    const auto path = std::filesystem::temp_directory_path() / "dfrecon-test-nonmanifold.obj";
    std::ofstream(path) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\n"
                        << "f 1 2 3\nf 2 1 4\nf 1 2 5\n";
    const TriangleSoup soup = readTriangleSoup(path.string());
    EXPECT_EQ(soup.triangles.size(), 3u);
    EXPECT_EQ(checkMesh(soup).nonManifoldEdges, 1u);
}

TEST(MeshCheck, WrittenMeshesReadBackValid) {
    TriMesh mesh;
    const TriangleSoup s = octahedron({1, 2, 3}, 4);
    std::vector<TriMesh::VertexHandle> v;
    for (Vec3 p : s.points) v.push_back(mesh.add_vertex({p.x, p.y, p.z}));
    for (auto t : s.triangles) mesh.add_face(v[t[0]], v[t[1]], v[t[2]]);
    EXPECT_TRUE(checkMesh(toTriangleSoup(mesh)).validSolid());
    const auto path = std::filesystem::temp_directory_path() / "dfrecon-test-octa.ply";
    writeMesh(mesh, path.string());
    const MeshCheckReport r = checkMesh(readTriangleSoup(path.string()));
    EXPECT_TRUE(r.validSolid());
    EXPECT_NEAR(r.volumeMm3, 4.0 / 3.0 * 64, 1e-9);
}

TEST(MeshCheck, BvhFindsEveryIntersectingPairOfARandomSoup) {
    // Independent triangles (no shared vertices): the checker's count must
    // equal the all-pairs count.
    const TriangleSoup s = dfrecon::testing::randomTriangles(9, 400, 20, 1.5);
    std::size_t expected = 0;
    for (std::size_t i = 0; i < s.triangles.size(); ++i)
        for (std::size_t j = i + 1; j < s.triangles.size(); ++j) {
            const Vec3 a[3] = {s.points[3 * i], s.points[3 * i + 1], s.points[3 * i + 2]};
            const Vec3 b[3] = {s.points[3 * j], s.points[3 * j + 1], s.points[3 * j + 2]};
            expected += trianglesIntersect(a, b);
        }
    EXPECT_GT(expected, 10u);
    EXPECT_EQ(checkMesh(s).intersectingPairs, expected);
}

TEST(MeshCheck, HostileSoupsEndQuickly) {
    // 2 000 triangles around one vertex, in 1 000 separate pairs: the fan
    // test compared every pair of them (10^14 steps at ten million).
    TriangleSoup star;
    star.points.push_back({0, 0, 0});
    const int n = 4000;
    for (int k = 0; k < n; ++k) {
        const double angle = 2 * M_PI * k / n;
        star.points.push_back({std::cos(angle), std::sin(angle), double(k % 2)});
    }
    for (std::uint32_t k = 1; k + 1 <= std::uint32_t(n); k += 2)
        star.triangles.push_back({0, k, k + 1});
    const MeshCheckReport fan = checkMesh(star);
    EXPECT_EQ(fan.nonManifoldVertices, 1u);
    // 1500 copies of one triangle: 1.1·10^6 intersecting pairs, counted up
    // to the cap and then no further.
    TriangleSoup copies;
    for (std::uint32_t k = 0; k < 1500; ++k) {
        copies.points.push_back({0, 0, 0});
        copies.points.push_back({10, 0, 0});
        copies.points.push_back({0, 10, 0});
        copies.triangles.push_back({3 * k, 3 * k + 1, 3 * k + 2});
    }
    const MeshCheckReport same = checkMesh(copies);
    EXPECT_EQ(same.intersectingPairs, kMaxCountedIntersections);
    EXPECT_TRUE(same.intersectingPairsCapped);
    EXPECT_FALSE(same.validSolid());
    EXPECT_FALSE(checkMesh(star).intersectingPairsCapped);
}

// A soup large enough to be searched on every core, against an independent
// sweep over all pairs whose x ranges overlap, and against checkMeshNear
// (a grid, not the hierarchy) with every triangle a suspect.
TEST(MeshCheck, ParallelSearchAndSuspectSearchFindEveryPair) {
    const TriangleSoup s = dfrecon::testing::randomTriangles(5, 30000, 120, 1.5);
    const std::size_t n = s.triangles.size();
    auto corners = [&](std::size_t t, Vec3 out[3]) {
        for (int k = 0; k < 3; ++k) out[k] = s.points[s.triangles[t][std::size_t(k)]];
    };
    std::vector<std::pair<double, double>> x(n);
    std::vector<std::size_t> byX(n);
    for (std::size_t t = 0; t < n; ++t) {
        Vec3 c[3];
        corners(t, c);
        x[t] = {std::min({c[0].x, c[1].x, c[2].x}), std::max({c[0].x, c[1].x, c[2].x})};
        byX[t] = t;
    }
    std::sort(byX.begin(), byX.end(), [&](std::size_t a, std::size_t b) { return x[a] < x[b]; });
    std::size_t expected = 0;
    for (std::size_t i = 0; i < n; ++i)
        for (std::size_t j = i + 1; j < n && x[byX[j]].first <= x[byX[i]].second; ++j) {
            Vec3 a[3], b[3];
            corners(byX[i], a);
            corners(byX[j], b);
            expected += trianglesIntersect(a, b);
        }
    EXPECT_GT(expected, 100u);
    const MeshCheckReport whole = checkMesh(s);
    EXPECT_EQ(whole.intersectingPairs, expected);
    std::vector<std::size_t> all(n);
    std::iota(all.begin(), all.end(), 0);
    const MeshCheckReport near = checkMeshNear(s, all);
    EXPECT_EQ(near.intersectingPairs, expected);
    EXPECT_EQ(near.defectiveTriangles, whole.defectiveTriangles);
    EXPECT_EQ(near.intersectingExamples, whole.intersectingExamples);
}

// checkMeshNear searches only the pairs of its suspects: a closed torus with
// a triangle added through it is found from that triangle, and the
// topology (its three boundary edges) is checked in full either way.
TEST(MeshCheck, SuspectSearchSeesOnlyItsSuspectsPairs) {
    TriangleSoup s = torus(3, 1, 24, 12);
    const std::uint32_t base = std::uint32_t(s.points.size());
    s.points.push_back({3, -0.5, -2});  // through the tube at (3, 0, 0)
    s.points.push_back({3, 0.5, -2});
    s.points.push_back({3, 0, 2});
    s.triangles.push_back({base, base + 1, base + 2});
    const std::size_t added = s.triangles.size() - 1;
    const MeshCheckReport whole = checkMesh(s);
    const MeshCheckReport near = checkMeshNear(s, {added});
    EXPECT_GT(whole.intersectingPairs, 0u);
    EXPECT_EQ(near.intersectingPairs, whole.intersectingPairs);
    EXPECT_EQ(near.defectiveTriangles, whole.defectiveTriangles);
    const MeshCheckReport elsewhere = checkMeshNear(s, {0});
    EXPECT_EQ(elsewhere.intersectingPairs, 0u);
    EXPECT_EQ(elsewhere.boundaryEdges, 3u);
    EXPECT_FALSE(elsewhere.validSolid());
}

TEST(MeshCheck, CleanGroupsSkipOnlyThePairsWithinAGroup) {
    // Two octahedra passing through each other: every colliding pair has one
    // triangle of each, so marking each solid a clean group of its own
    // (their own pairs are clean) must leave the report checkMesh's.
    const TriangleSoup a = octahedron(), b = octahedron({0.5, 0.3, 0.2});
    const TriangleSoup s = merged(a, b);
    const MeshCheckReport whole = checkMesh(s);
    ASSERT_GT(whole.intersectingPairs, 0u);
    CleanGroups groups(s.triangles.size(), 1);
    std::fill(groups.begin() + std::ptrdiff_t(a.triangles.size()), groups.end(), 2);
    const MeshCheckReport known = checkMeshKnowing(s, groups);
    EXPECT_EQ(known.intersectingPairs, whole.intersectingPairs);
    EXPECT_EQ(known.defectiveTriangles, whole.defectiveTriangles);
    EXPECT_EQ(known.boundaryEdges, whole.boundaryEdges);
    // Group 0 vouches for nothing.
    EXPECT_EQ(checkMeshKnowing(s, CleanGroups(s.triangles.size(), 0)).intersectingPairs,
              whole.intersectingPairs);
    // One group over both says every pair is clean: none is tested (the
    // caller's promise), the topology is still checked.
    const MeshCheckReport trusted = checkMeshKnowing(s, CleanGroups(s.triangles.size(), 7));
    EXPECT_EQ(trusted.intersectingPairs, 0u);
    EXPECT_EQ(trusted.boundaryEdges, whole.boundaryEdges);
    // Among a subset, likewise.
    std::vector<bool> degenerate(s.triangles.size(), false);
    std::vector<std::size_t> all(s.triangles.size());
    std::iota(all.begin(), all.end(), std::size_t(0));
    EXPECT_EQ(collidingPairsAmong(s, degenerate, all, SIZE_MAX, &groups).pairs.size(),
              whole.intersectingPairs);
}

// The edge counts and components against an independent edge list (a map
// from each vertex pair to its uses), on soups drawn from a few vertices so
// that every kind of edge occurs: used once, twice either way, three or
// more times, and triangles with a vertex twice (which use one edge twice).
TEST(MeshCheck, EdgeCountsMatchAnEdgeListOnRandomSoups) {
    std::mt19937 random(17);
    for (int round = 0; round < 40; ++round) {
        const std::uint32_t vertexCount = 4 + std::uint32_t(round % 9);
        TriangleSoup soup;
        std::uniform_real_distribution<double> coordinate(-1, 1);
        for (std::uint32_t v = 0; v < vertexCount + 2; ++v)  // two never used
            soup.points.push_back({coordinate(random), coordinate(random), coordinate(random)});
        std::uniform_int_distribution<std::uint32_t> vertex(0, vertexCount - 1);
        const int triangles = 1 + round % 17;
        for (int t = 0; t < triangles; ++t) {
            std::array<std::uint32_t, 3> tri{vertex(random), vertex(random), vertex(random)};
            if (t % 5 == 4) tri[2] = tri[0];  // a vertex twice
            soup.triangles.push_back(tri);
        }
        // Each edge's uses: (triangle, runs from the lower vertex).
        std::map<std::pair<std::uint32_t, std::uint32_t>, std::vector<std::pair<std::size_t, bool>>>
            edges;
        std::vector<std::size_t> parent(soup.points.size());
        std::iota(parent.begin(), parent.end(), 0);
        std::function<std::size_t(std::size_t)> root = [&](std::size_t x) {
            return parent[x] == x ? x : parent[x] = root(parent[x]);
        };
        std::set<std::uint32_t> used;
        for (std::size_t t = 0; t < soup.triangles.size(); ++t)
            for (int k = 0; k < 3; ++k) {
                const std::uint32_t a = soup.triangles[t][k], b = soup.triangles[t][(k + 1) % 3];
                used.insert(a);
                if (a == b) continue;
                edges[{std::min(a, b), std::max(a, b)}].push_back({t, a < b});
                parent[root(a)] = root(b);
            }
        std::size_t boundary = 0, nonManifold = 0, misoriented = 0, components = 0;
        std::set<std::size_t> defective;
        for (const auto& [edge, uses] : edges) {
            const bool bad = uses.size() != 2 || uses[0].second == uses[1].second;
            boundary += uses.size() == 1;
            nonManifold += uses.size() > 2;
            misoriented += uses.size() == 2 && uses[0].second == uses[1].second;
            if (bad)
                for (const auto& use : uses) defective.insert(use.first);
        }
        for (std::uint32_t v : used) components += root(v) == v;
        const MeshCheckReport report = checkMesh(soup);
        SCOPED_TRACE("round " + std::to_string(round));
        EXPECT_EQ(report.edges, edges.size());
        EXPECT_EQ(report.boundaryEdges, boundary);
        EXPECT_EQ(report.nonManifoldEdges, nonManifold);
        EXPECT_EQ(report.misorientedEdges, misoriented);
        EXPECT_EQ(report.vertices, used.size());
        EXPECT_EQ(report.components, components);
        for (std::size_t t : defective)
            EXPECT_TRUE(std::binary_search(report.defectiveTriangles.begin(),
                                           report.defectiveTriangles.end(), t))
                << "triangle " << t;
    }
}
