// The atlas (paper §3.2, §5): charts never share a texel, every triangle is
// sampled, samples lie on their triangles, and no point of the surface is
// farther from a sample of its own triangle than the Lemma 2 bound — checked
// by measuring that distance at many random surface points.
#include <gtest/gtest.h>

#include <random>

#include "sdm/Atlas.hpp"
#include "shapes/MeshShapes.hpp"

using namespace dfrecon;

namespace {

// The farthest any of `probes` random points per triangle is from the
// nearest sample of its own triangle (brute force over that triangle's
// samples).
double largestGapToSamples(const TriangleSoup& soup, const AtlasSamples& samples, int probes) {
    std::vector<std::vector<Vec3>> byTriangle(soup.triangles.size());
    for (std::size_t k = 0; k < samples.point.size(); ++k)
        byTriangle[samples.triangle[k]].push_back(samples.point[k]);
    std::mt19937 random(7);
    std::uniform_real_distribution<double> unit(0, 1);
    double largest = 0;
    for (std::size_t t = 0; t < soup.triangles.size(); ++t) {
        const auto& tri = soup.triangles[t];
        for (int k = 0; k < probes + 3; ++k) {
            double u = unit(random), v = unit(random);
            if (u + v > 1) u = 1 - u, v = 1 - v;
            if (k < 3) u = k == 1, v = k == 2;  // the corners too
            const Vec3 p = soup.points[tri[0]] + u * (soup.points[tri[1]] - soup.points[tri[0]]) +
                           v * (soup.points[tri[2]] - soup.points[tri[0]]);
            double nearest = INFINITY;
            for (const Vec3& s : byTriangle[t]) nearest = std::min(nearest, length(p - s));
            largest = std::max(largest, nearest);
        }
    }
    return largest;
}

}  // namespace

TEST(Atlas, FixedSizeChartsAreDisjointAndEveryTriangleIsSampled) {
    const TriangleSoup sphere = geodesicSphere(8, 20);  // 1280 triangles
    const Atlas atlas = buildAtlas(sphere, {128});
    EXPECT_EQ(atlas.width, 128);
    EXPECT_EQ(atlas.height, 128);
    std::vector<int> owners(atlas.texelTriangle.size(), 0);
    for (std::size_t t = 0; t < atlas.charts.size(); ++t) {
        const TriangleChart& c = atlas.charts[t];
        ASSERT_GE(c.x, 0);
        ASSERT_GE(c.y, 0);
        ASSERT_LE(c.x + c.width, atlas.width);
        ASSERT_LE(c.y + c.height, atlas.height);
        for (int j = c.y; j < c.y + c.height; ++j)
            for (int i = c.x; i < c.x + c.width; ++i) ++owners[std::size_t(j * atlas.width + i)];
    }
    for (int o : owners) EXPECT_LE(o, 1);
    std::vector<int> texelsOf(sphere.triangles.size(), 0);
    for (std::int32_t t : atlas.texelTriangle)
        if (t >= 0) ++texelsOf[std::size_t(t)];
    for (int n : texelsOf) EXPECT_GE(n, 1);
    EXPECT_GT(atlas.usedTexels(), atlas.texelTriangle.size() / 3) << "packing wastes most texels";
}

TEST(Atlas, EveryPointIsWithinTheLemma2BoundOfASample) {
    for (const TriangleSoup& soup : {geodesicSphere(4, 20), boxMesh({0, 0, 0}, {30, 10, 5}, 3)}) {
        for (const AtlasOptions& options : {AtlasOptions{64}, AtlasOptions{0, 0.8}}) {
            const Atlas atlas = buildAtlas(soup, options);
            const AtlasSamples samples = atlasSamples(atlas, soup);
            if (options.maxErrorMm > 0) {
                EXPECT_NEAR(atlas.samplingBoundMm(), 0.8, 1e-12);
            }
            const double gap = largestGapToSamples(soup, samples, 400);
            EXPECT_LE(gap, atlas.samplingBoundMm()) << "texel " << atlas.texelMm << " mm";
            // The bound is not loose by more than a texel's diagonal.
            EXPECT_GT(gap, 0.3 * atlas.samplingBoundMm());
            // Samples lie on their triangles.
            for (std::size_t k = 0; k < samples.point.size(); ++k) {
                const auto& tri = soup.triangles[samples.triangle[k]];
                const Vec3 a = soup.points[tri[0]], b = soup.points[tri[1]],
                           c = soup.points[tri[2]];
                const Vec3 n = cross(b - a, c - a);
                EXPECT_NEAR(dot(samples.point[k] - a, n) / length(n), 0, 1e-9);
            }
        }
    }
}

TEST(Atlas, RefusesWhatCannotFit) {
    const TriangleSoup sphere = geodesicSphere(8, 20);              // 1280 triangles
    EXPECT_THROW(buildAtlas(sphere, {32}), std::invalid_argument);  // 1024 texels
    AtlasOptions tiny;
    tiny.maxErrorMm = 1e-4;
    EXPECT_THROW(buildAtlas(sphere, tiny), std::invalid_argument);  // 10^11 texels
    EXPECT_THROW(buildAtlas(TriangleSoup{}, {}), std::invalid_argument);
}

TEST(Atlas, DegenerateTrianglesStillGetASample) {
    TriangleSoup soup;
    soup.points = {{0, 0, 0}, {10, 0, 0}, {5, 0, 0}, {1, 1, 1}};
    soup.triangles = {{0, 1, 2}, {3, 3, 3}};  // collinear; a point
    const Atlas atlas = buildAtlas(soup, {16});
    const AtlasSamples samples = atlasSamples(atlas, soup);
    std::vector<int> count(2, 0);
    for (std::uint32_t t : samples.triangle) ++count[t];
    EXPECT_GE(count[0], 1);
    EXPECT_GE(count[1], 1);
    for (std::size_t k = 0; k < samples.point.size(); ++k)
        if (samples.triangle[k] == 1) {
            EXPECT_EQ(samples.point[k], (Vec3{1, 1, 1}));
        }
}
