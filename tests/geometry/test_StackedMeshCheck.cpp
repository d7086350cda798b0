// The stacked check against the whole check (checkMesh, the reference): on
// towers of rings stacked between planes, valid, broken within pieces,
// broken across planes, and with loops that touch; and the separation test
// on each condition it rests on.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "geometry/MeshCheck.hpp"
#include "geometry/Polygon.hpp"
#include "geometry/StackedMeshCheck.hpp"

using namespace dfrecon;

namespace {

// A closed tower: rings of `sides` vertices (loops) on planes z = 0, 1, …,
// planes - 1, each band between two planes with a free ring half-way (not a
// loop: it may be moved), a cone below the first ring and above the last.
// Piece p lies between plane p - 1 and plane p.
struct Tower {
    TriangleSoup soup;
    std::vector<std::uint32_t> pieceOf;
    PieceStack stack;
    std::vector<std::uint32_t> freeVertices;  // half-way rings and apexes
};

void addTower(Tower& t, int planes, int sides, Point2 centre, double radius) {
    if (t.stack.planeZMm.empty())
        for (int k = 0; k < planes; ++k) {
            t.stack.planeZMm.push_back(k);
            t.stack.planeLoops.emplace_back();
        }
    auto ring = [&](double z, double r) {
        const std::uint32_t first = std::uint32_t(t.soup.points.size());
        for (int i = 0; i < sides; ++i) {
            const double a = 2 * M_PI * i / sides;
            t.soup.points.push_back({centre.x + r * std::cos(a), centre.y + r * std::sin(a), z});
        }
        return first;
    };
    auto band = [&](std::uint32_t lower, std::uint32_t upper, std::uint32_t piece) {
        for (int i = 0; i < sides; ++i) {
            const std::uint32_t a = lower + std::uint32_t(i),
                                b = lower + std::uint32_t((i + 1) % sides),
                                c = upper + std::uint32_t((i + 1) % sides),
                                d = upper + std::uint32_t(i);
            t.soup.triangles.push_back({a, b, c});
            t.soup.triangles.push_back({a, c, d});
            t.pieceOf.insert(t.pieceOf.end(), 2, piece);
        }
    };
    auto cone = [&](std::uint32_t rim, Vec3 apex, bool up, std::uint32_t piece) {
        const std::uint32_t tip = std::uint32_t(t.soup.points.size());
        t.soup.points.push_back(apex);
        t.freeVertices.push_back(tip);
        for (int i = 0; i < sides; ++i) {
            const std::uint32_t a = rim + std::uint32_t(i),
                                b = rim + std::uint32_t((i + 1) % sides);
            t.soup.triangles.push_back(up ? std::array{tip, a, b} : std::array{tip, b, a});
            t.pieceOf.push_back(piece);
        }
    };
    std::vector<std::uint32_t> rings;
    for (int k = 0; k < planes; ++k) {
        rings.push_back(ring(k, radius * (1 + 0.2 * std::sin(k))));
        std::vector<std::uint32_t>& loop = t.stack.planeLoops[std::size_t(k)].emplace_back();
        for (int i = 0; i < sides; ++i) loop.push_back(rings.back() + std::uint32_t(i));
    }
    cone(rings.front(), {centre.x, centre.y, -0.5}, false, 0);
    for (int k = 0; k + 1 < planes; ++k) {
        const std::uint32_t middle = ring(k + 0.5, radius * 0.9);
        for (int i = 0; i < sides; ++i) t.freeVertices.push_back(middle + std::uint32_t(i));
        band(rings[std::size_t(k)], middle, std::uint32_t(k + 1));
        band(middle, rings[std::size_t(k + 1)], std::uint32_t(k + 1));
    }
    cone(rings.back(), {centre.x, centre.y, planes - 0.5}, true, std::uint32_t(planes));
}

Tower tower(int planes = 5, int sides = 12) {
    Tower t;
    addTower(t, planes, sides, {0, 0}, 1);
    return t;
}

void expectSameReport(const MeshCheckReport& stacked, const MeshCheckReport& whole) {
    EXPECT_EQ(stacked.validSolid(), whole.validSolid());
    EXPECT_EQ(stacked.intersectingPairs, whole.intersectingPairs);
    EXPECT_EQ(stacked.intersectingExamples, whole.intersectingExamples);
    EXPECT_EQ(stacked.defectiveTriangles, whole.defectiveTriangles);
    EXPECT_EQ(stacked.boundaryEdges, whole.boundaryEdges);
    EXPECT_EQ(stacked.nonManifoldVertices, whole.nonManifoldVertices);
    EXPECT_EQ(stacked.genus, whole.genus);
    EXPECT_DOUBLE_EQ(stacked.volumeMm3, whole.volumeMm3);
}

// Three free vertices (half-way rings, apexes) moved sideways at random,
// always within their slab: enough to pull rings through their tower's axis.
void shakeFreeVertices(Tower& t, std::mt19937& random) {
    std::uniform_real_distribution<double> shift(-1.6, 1.6);
    for (int moves = 0; moves < 3; ++moves) {
        const std::uint32_t v = t.freeVertices[std::size_t(random() % t.freeVertices.size())];
        t.soup.points[v].x += shift(random);
        t.soup.points[v].y += shift(random);
    }
}

}  // namespace

TEST(StackedMeshCheck, AValidTowerIsSeparatedAndReportedAsTheWholeCheckDoes) {
    const Tower t = tower();
    ASSERT_TRUE(checkMesh(t.soup).validSolid());
    EXPECT_TRUE(stackSeparatesPieces(t.soup, t.pieceOf, t.stack));
    expectSameReport(checkStackedMesh(t.soup, t.pieceOf, t.stack), checkMesh(t.soup));
}

TEST(StackedMeshCheck, PairsWithinPiecesAreFoundAsTheWholeCheckFindsThem) {
    // Half-way rings pulled through their tower's axis (and apexes pushed
    // sideways) at random, always within their slab: the pieces stay
    // separated and the colliding pairs are all within pieces.
    std::mt19937 random(7);
    int broken = 0;
    for (int trial = 0; trial < 40; ++trial) {
        Tower t = tower();
        shakeFreeVertices(t, random);
        ASSERT_TRUE(stackSeparatesPieces(t.soup, t.pieceOf, t.stack));
        const MeshCheckReport whole = checkMesh(t.soup);
        broken += whole.intersectingPairs > 0;
        expectSameReport(checkStackedMesh(t.soup, t.pieceOf, t.stack), whole);
    }
    EXPECT_GT(broken, 10);  // the trials did break surfaces
}

TEST(StackedMeshCheck, APieceReachingPastItsPlaneIsCheckedWhole) {
    // A half-way vertex of the band between planes 1 and 2 pulled below
    // plane 1, into the band beneath: pairs across pieces.
    Tower t = tower();
    const std::uint32_t v = t.freeVertices[1 + 12];  // the second half-way ring
    t.soup.points[v].z = 0.6;
    EXPECT_FALSE(stackSeparatesPieces(t.soup, t.pieceOf, t.stack));
    const MeshCheckReport whole = checkMesh(t.soup);
    EXPECT_GT(whole.intersectingPairs, 0u);
    expectSameReport(checkStackedMesh(t.soup, t.pieceOf, t.stack), whole);
}

TEST(StackedMeshCheck, LoopsThatTouchAreNotSeparated) {
    // Two towers whose rings meet at a point on one plane (same place,
    // different vertices): their pieces above and below meet there.
    Tower t;
    addTower(t, 3, 8, {0, 0}, 1);
    addTower(t, 3, 8, {2.0, 0}, 1);
    // Radii on plane 1 are 1.2 sin(1) + 1 > 1: the rings overlap, and
    // crossing loops are refused as well.
    EXPECT_FALSE(stackSeparatesPieces(t.soup, t.pieceOf, t.stack));
    EXPECT_FALSE(planeLoopsApart(t.soup, t.stack));
    expectSameReport(checkStackedMesh(t.soup, t.pieceOf, t.stack), checkMesh(t.soup));
    // Loops known apart are not tested again (the caller's promise).
    t.stack.loopsKnownApart = true;
    EXPECT_TRUE(stackSeparatesPieces(t.soup, t.pieceOf, t.stack));

    Tower apart;
    addTower(apart, 3, 8, {0, 0}, 0.5);
    addTower(apart, 3, 8, {3, 0}, 0.5);
    EXPECT_TRUE(stackSeparatesPieces(apart.soup, apart.pieceOf, apart.stack));
    EXPECT_TRUE(planeLoopsApart(apart.soup, apart.stack));
    // Touching exactly: a vertex of one ring moved onto a vertex of the other.
    const std::uint32_t a = apart.stack.planeLoops[1][0][0];  // angle 0 of the first
    const std::uint32_t b = apart.stack.planeLoops[1][1][4];  // angle π of the second
    apart.soup.points[a].x = apart.soup.points[b].x;
    apart.soup.points[a].y = apart.soup.points[b].y;
    EXPECT_FALSE(stackSeparatesPieces(apart.soup, apart.pieceOf, apart.stack));
    const MeshCheckReport whole = checkMesh(apart.soup);
    EXPECT_FALSE(whole.validSolid());
    expectSameReport(checkStackedMesh(apart.soup, apart.pieceOf, apart.stack), whole);
}

TEST(StackedMeshCheck, ATriangleMeetingItsPlaneOutsideTheLoopsIsNotSeparated) {
    // A chord: a triangle with two loop vertices that are not neighbours.
    Tower t = tower(3, 8);
    const std::vector<std::uint32_t>& loop = t.stack.planeLoops[0][0];
    t.soup.triangles.push_back({loop[0], loop[3], t.freeVertices[1]});
    t.pieceOf.push_back(1);
    EXPECT_FALSE(stackSeparatesPieces(t.soup, t.pieceOf, t.stack));
    // The loops themselves are apart: knowing so changes nothing here.
    EXPECT_TRUE(planeLoopsApart(t.soup, t.stack));
    t.stack.loopsKnownApart = true;
    EXPECT_FALSE(stackSeparatesPieces(t.soup, t.pieceOf, t.stack));
    expectSameReport(checkStackedMesh(t.soup, t.pieceOf, t.stack), checkMesh(t.soup));
    // A loop vertex that is not at its plane's height.
    Tower off = tower(3, 8);
    off.soup.points[off.stack.planeLoops[1][0][2]].z += 1e-9;
    EXPECT_FALSE(stackSeparatesPieces(off.soup, off.pieceOf, off.stack));
    // Planes out of order.
    Tower unordered = tower(3, 8);
    std::swap(unordered.stack.planeZMm[0], unordered.stack.planeZMm[1]);
    EXPECT_FALSE(stackSeparatesPieces(unordered.soup, unordered.pieceOf, unordered.stack));
}

TEST(StackedMeshCheck, PiecesMarkedSearchedAreNotSearchedAgain) {
    // A collision inside piece 2 only: found unless piece 2 is marked
    // searched (the caller's promise that it was searched clean).
    Tower t = tower();
    const std::uint32_t v = t.freeVertices[1 + 12];  // half-way ring of piece 2
    t.soup.points[v].x = -1.5;
    const MeshCheckReport whole = checkMesh(t.soup);
    ASSERT_GT(whole.intersectingPairs, 0u);
    for (const auto& [i, j] : whole.intersectingExamples) {
        ASSERT_EQ(t.pieceOf[i], 2u);
        ASSERT_EQ(t.pieceOf[j], 2u);
    }
    t.stack.searched = {true, true, false};
    expectSameReport(checkStackedMesh(t.soup, t.pieceOf, t.stack), whole);
    t.stack.searched = {false, false, true};
    EXPECT_EQ(checkStackedMesh(t.soup, t.pieceOf, t.stack).intersectingPairs, 0u);
}

TEST(StackedMeshCheck, PairsOfTrianglesThatDidNotMoveAreNotSearchedAndNothingIsMissed) {
    // As smoothing checks a bent surface: the tower was valid, so the pairs
    // of triangles none of whose corners moved are one clean group; every
    // collision involves a moved triangle and is still found.
    std::mt19937 random(11);
    int broken = 0;
    for (int trial = 0; trial < 40; ++trial) {
        Tower t = tower();
        ASSERT_TRUE(checkMesh(t.soup).validSolid());
        const std::vector<Vec3> before = t.soup.points;
        shakeFreeVertices(t, random);
        t.stack.cleanGroup.assign(t.soup.triangles.size(), 1);
        for (std::size_t k = 0; k < t.soup.triangles.size(); ++k)
            for (std::uint32_t v : t.soup.triangles[k])
                if (!(t.soup.points[v] == before[v])) t.stack.cleanGroup[k] = 0;
        const MeshCheckReport whole = checkMesh(t.soup);
        broken += whole.intersectingPairs > 0;
        expectSameReport(checkStackedMesh(t.soup, t.pieceOf, t.stack), whole);
    }
    EXPECT_GT(broken, 10);
}
