// Neighbours kept apart: two labels of one voxelised ball (touching on every
// plane, overlapping on none) reconstructed each on its own overlap between
// the planes; moved apart, they overlap far less (measured by compare's
// exact overlap, an independent route), stay valid solids and keep every
// contour point as a vertex. Structures drawn overlapping are left alone.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <string>
#include <tuple>

#include "compare/OverlapVolume.hpp"
#include "dfrecon/Reconstruct.hpp"
#include "geometry/MeshCheck.hpp"
#include "io/contours/SlicesFile.hpp"
#include "io/labels/MaskContours.hpp"
#include "neighbours/NeighbourSeparation.hpp"
#include "shapes/RandomLabelVolumes.hpp"
#include "tests/CpuRuntime.hpp"

namespace dfrecon {
namespace {

// The split ball of tests/data/neighbours (split_ball.py made its labels,
// `dfrecon convert` their contours).
ContourSet splitBall() {
    return readSlicesFile(std::string(DFRECON_TEST_DATA) + "/neighbours/split-ball.slices")
        .contours;
}

std::vector<NeighbourSurface> asNeighbours(const ContourSet& set,
                                           std::vector<RoiSurface>& surfaces) {
    std::vector<NeighbourSurface> rois;
    for (std::size_t i = 0; i < set.rois.size(); ++i) {
        NeighbourSurface roi{set.rois[i].name, &surfaces[i].surface, set.rois[i].frame, {}};
        for (const Slice& slice : set.rois[i].slices) roi.planeZMm.push_back(slice.zMm);
        rois.push_back(std::move(roi));
    }
    return rois;
}

std::vector<RoiSurface> reconstructAll(const ContourSet& set) {
    std::vector<RoiSurface> surfaces;
    for (const Roi& roi : set.rois) surfaces.push_back(reconstructRoi(cpuRuntime(), roi));
    return surfaces;
}

using PointKey = std::tuple<double, double, double>;

// The vertices of `soup` on one of `roi`'s planes.
std::set<PointKey> onPlanes(const TriangleSoup& soup, const Roi& roi) {
    std::set<PointKey> points;
    for (const Vec3& p : soup.points)
        for (const Slice& slice : roi.slices)
            if (std::abs(p.z - slice.zMm) <= 1e-4) points.insert({p.x, p.y, p.z});
    return points;
}

double overlapMm3(const TriangleSoup& a, const TriangleSoup& b) {
    return overlapOf(a, b).intersectionMm3;
}

TEST(NeighbourSeparation, TouchingLabelsOverlapFarLessAndKeepTheirContours) {
    const ContourSet set = splitBall();
    ASSERT_EQ(set.rois.size(), 2u);
    std::vector<RoiSurface> surfaces = reconstructAll(set);
    const std::vector<RoiSurface> before = surfaces;
    const double overlapBefore = overlapMm3(surfaces[0].surface, surfaces[1].surface);
    ASSERT_GT(overlapBefore, 1.0);  // 5.6 mm³ as built

    std::vector<NeighbourSurface> rois = asNeighbours(set, surfaces);
    const NeighbourSeparation separation = keepNeighboursApart(&cpuRuntime(), rois);
    ASSERT_EQ(separation.pairs.size(), 1u);
    const NeighbourPair& pair = separation.pairs[0];
    EXPECT_FALSE(pair.overlapOnPlanes);
    EXPECT_GT(pair.insideA, 0u);
    EXPECT_GT(pair.insideB, 0u);
    EXPECT_GT(pair.movedA + pair.movedB, 0u);

    const double overlapAfter = overlapMm3(surfaces[0].surface, surfaces[1].surface);
    EXPECT_LT(overlapAfter, 0.1 * overlapBefore);
    for (std::size_t i = 0; i < 2; ++i) {
        const MeshCheckReport check = checkMesh(surfaces[i].surface);
        EXPECT_TRUE(check.validSolid());
        ASSERT_TRUE(separation.measures[i]);
        EXPECT_NEAR(separation.measures[i]->volumeMm3, check.volumeMm3, 1e-6 * check.volumeMm3);
        // Each gives up part of the lens, never more than all of it.
        EXPECT_LT(check.volumeMm3, before[i].check.volumeMm3);
        EXPECT_GT(check.volumeMm3, before[i].check.volumeMm3 - overlapBefore);
        // Not a vertex on a plane moved: the contours are the surface's
        // sections still, every contour point a vertex.
        EXPECT_EQ(onPlanes(surfaces[i].surface, set.rois[i]),
                  onPlanes(before[i].surface, set.rois[i]));
        std::set<PointKey> vertices;
        for (const Vec3& p : surfaces[i].surface.points) vertices.insert({p.x, p.y, p.z});
        for (const Slice& slice : set.rois[i].slices)
            for (const Polygon& contour : slice.contours)
                for (const Point2& q : contour)
                    EXPECT_TRUE(vertices.count(
                        {double(float(q.x)), double(float(q.y)), double(float(slice.zMm))}))
                        << q.x << " " << q.y << " " << slice.zMm;
    }
}

// A closed box [lo, hi], oriented outward.
TriangleSoup box(Vec3 lo, Vec3 hi) {
    TriangleSoup soup;
    for (int k = 0; k < 8; ++k)
        soup.points.push_back({k & 1 ? hi.x : lo.x, k & 2 ? hi.y : lo.y, k & 4 ? hi.z : lo.z});
    soup.triangles = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                      {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
    return soup;
}

TEST(NeighbourSeparation, ATriangleThroughItsNeighbourGetsAVertexThatMovesOut) {
    // A tetrahedron on planes z = 0 and 10 and a plate on planes z = 1 and 5
    // skewering its slanted face: no vertex of either lies inside the other,
    // so moving vertices alone changes nothing; the triangles are split
    // where they pass through the other and the new vertices move out.
    TriangleSoup tetra;
    tetra.points = {{0, 0, 0}, {20, 0, 0}, {0, 20, 0}, {0, 0, 10}};
    tetra.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
    TriangleSoup plate = box({-5, 6.2, 1}, {30, 7.2, 5});
    ASSERT_TRUE(checkMesh(tetra).validSolid());
    ASSERT_TRUE(checkMesh(plate).validSolid());
    const double overlapBefore = overlapMm3(tetra, plate);
    ASSERT_GT(overlapBefore, 1.0);

    std::vector<NeighbourSurface> rois = {{"tetra", &tetra, {}, {0, 10}},
                                          {"plate", &plate, {}, {1, 5}}};
    const NeighbourSeparation separation = keepNeighboursApart(nullptr, rois);
    ASSERT_EQ(separation.pairs.size(), 1u);
    EXPECT_GT(separation.pairs[0].movedA, 0u);
    EXPECT_GT(tetra.points.size(), 4u);  // split
    EXPECT_TRUE(checkMesh(tetra).validSolid());
    EXPECT_TRUE(checkMesh(plate).validSolid());
    // The plate runs through the tetrahedron's inside, which stays: only
    // the lens at the face can go (29.2 -> 23.8 mm³ as built).
    EXPECT_LT(overlapMm3(tetra, plate), 0.9 * overlapBefore);
    // The corners, all on their planes, stay where they were.
    const std::vector<Vec3> corners = {{0, 0, 0}, {20, 0, 0}, {0, 20, 0}, {0, 0, 10}};
    for (std::size_t v = 0; v < corners.size(); ++v) EXPECT_EQ(tetra.points[v], corners[v]);
    const TriangleSoup plateCorners = box({-5, 6.2, 1}, {30, 7.2, 5});
    for (std::size_t v = 0; v < plateCorners.points.size(); ++v)
        EXPECT_EQ(plate.points[v], plateCorners.points[v]);
}

TEST(NeighbourSeparation, HostileLabelStacksStayValidWithEveryContourPoint) {
    // Random label volumes as segmentation tools make them (touching,
    // nested, pixel staircases): moved apart, every surface is still a
    // valid closed solid as written (floats) and keeps its on-plane
    // vertices where they were.
    // Seeds 26, 28, 117 and 166 once broke a surface (splits beside touches
    // opened by a micrometre; a fold judged differently from either side).
    for (std::uint32_t seed : {1u, 2u, 3u, 4u, 26u, 28u, 117u, 166u}) {
        SCOPED_TRACE("seed " + std::to_string(seed));
        ContourSet set = contoursFromLabels(hostileLabelVolume(seed));
        set.rois.erase(std::remove_if(set.rois.begin(), set.rois.end(),
                                      [](const Roi& roi) { return roi.slices.empty(); }),
                       set.rois.end());
        std::vector<RoiSurface> surfaces = reconstructAll(set);
        std::vector<std::set<PointKey>> planeVertices;
        for (std::size_t i = 0; i < set.rois.size(); ++i)
            planeVertices.push_back(onPlanes(surfaces[i].surface, set.rois[i]));
        std::vector<NeighbourSurface> rois = asNeighbours(set, surfaces);
        keepNeighboursApart(nullptr, rois);
        for (std::size_t i = 0; i < set.rois.size(); ++i) {
            TriangleSoup written = surfaces[i].surface;
            roundPointsToFloat(written);
            const MeshCheckReport report = checkMesh(written);
            EXPECT_TRUE(report.validSolid())
                << set.rois[i].name << ": degenerate " << report.degenerateTriangles
                << ", intersecting " << report.intersectingPairs << ", boundary "
                << report.boundaryEdges << ", non-manifold " << report.nonManifoldEdges;
            EXPECT_EQ(onPlanes(surfaces[i].surface, set.rois[i]), planeVertices[i])
                << set.rois[i].name;
        }
    }
}

TEST(NeighbourSeparation, TheKernelAndItsTwinMoveTheSame) {
    const ContourSet set = splitBall();
    std::vector<RoiSurface> onDevice = reconstructAll(set), onHost = onDevice;
    std::vector<NeighbourSurface> deviceRois = asNeighbours(set, onDevice),
                                  hostRois = asNeighbours(set, onHost);
    const NeighbourSeparation device = keepNeighboursApart(&cpuRuntime(), deviceRois);
    const NeighbourSeparation host = keepNeighboursApart(nullptr, hostRois);
    ASSERT_EQ(device.pairs.size(), host.pairs.size());
    EXPECT_EQ(device.pairs[0].insideA, host.pairs[0].insideA);
    EXPECT_EQ(device.pairs[0].insideB, host.pairs[0].insideB);
    EXPECT_EQ(device.pairs[0].movedA, host.pairs[0].movedA);
    EXPECT_EQ(device.pairs[0].movedB, host.pairs[0].movedB);
    EXPECT_NEAR(device.pairs[0].deepestMm, host.pairs[0].deepestMm, 1e-9);
    // PoCL computes in double: the same closest points up to rounding, and
    // the moved points are rounded to float as written.
    for (std::size_t i = 0; i < 2; ++i) {
        ASSERT_EQ(onDevice[i].surface.points.size(), onHost[i].surface.points.size());
        double worst = 0;
        for (std::size_t v = 0; v < onHost[i].surface.points.size(); ++v)
            worst = std::max(worst,
                             length(onDevice[i].surface.points[v] - onHost[i].surface.points[v]));
        EXPECT_LE(worst, 1e-5);
    }
}

TEST(NeighbourSeparation, ReportOnlyMovesNothing) {
    const ContourSet set = splitBall();
    std::vector<RoiSurface> surfaces = reconstructAll(set);
    const std::vector<RoiSurface> before = surfaces;
    std::vector<NeighbourSurface> rois = asNeighbours(set, surfaces);
    NeighbourSeparationOptions options;
    options.move = false;
    const NeighbourSeparation found = keepNeighboursApart(nullptr, rois, options);
    ASSERT_EQ(found.pairs.size(), 1u);
    EXPECT_GT(found.pairs[0].insideA + found.pairs[0].insideB, 0u);
    EXPECT_EQ(found.pairs[0].movedA + found.pairs[0].movedB, 0u);
    for (std::size_t i = 0; i < 2; ++i)
        EXPECT_EQ(surfaces[i].surface.points, before[i].surface.points);
}

TEST(NeighbourSeparation, StructuresDrawnOverlappingAreLeftAsDrawn) {
    // A ball and a smaller one inside it, and a ball overlapping the big one
    // on its planes (a PTV around its GTV, two organs drawn over each
    // other): overlapping on a shared plane, so nothing moves.
    ContourSet set;
    auto ball = [](const std::string& name, Point2 centre, double radius) {
        Roi roi;
        roi.name = name;
        for (int k = -4; k <= 4; ++k) {
            const double z = 2.0 * k, r2 = radius * radius - z * z;
            if (r2 > 1) roi.slices.push_back({z, {circlePolygon(centre, std::sqrt(r2), 48)}});
        }
        return roi;
    };
    set.rois = {ball("outer", {0, 0}, 10), ball("inner", {1, 0}, 5), ball("beside", {12, 0}, 8)};
    std::vector<RoiSurface> surfaces = reconstructAll(set);
    const std::vector<RoiSurface> before = surfaces;
    std::vector<NeighbourSurface> rois = asNeighbours(set, surfaces);
    const NeighbourSeparation separation = keepNeighboursApart(&cpuRuntime(), rois);
    ASSERT_FALSE(separation.pairs.empty());
    for (const NeighbourPair& pair : separation.pairs) {
        EXPECT_TRUE(pair.overlapOnPlanes) << pair.a << " " << pair.b;
        EXPECT_EQ(pair.movedA + pair.movedB, 0u);
    }
    for (std::size_t i = 0; i < surfaces.size(); ++i)
        EXPECT_EQ(surfaces[i].surface.points, before[i].surface.points);
}

}  // namespace
}  // namespace dfrecon
