// Voxels inside a closed surface by ray parity (field/Rasterization's
// voxelsInsideSolid) against independent references: an octahedron whose
// corners and edges lie on rows of voxel centres (exact answer from
// |x| + |y| + |z|), the same on rotated grids, and a torus whose inside is
// told by its winding number (sum of solid angles) at every centre.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "field/Rasterization.hpp"
#include "geometry/MeshCheck.hpp"
#include "geometry/SurfaceMeasures.hpp"
#include "tests/TestMeshes.hpp"

namespace dfrecon {
namespace {

constexpr double kPi = 3.14159265358979323846;

// The octahedron |x| + |y| + |z| = s, each face cut into n² triangles, so
// for s = n / 2 its points lie on half a millimetre's lattice: rows of
// centres one millimetre apart run through corners and along edges.
TriangleSoup octahedron(double s, int n) {
    TriangleSoup soup;
    for (int sx : {-1, 1})
        for (int sy : {-1, 1})
            for (int sz : {-1, 1}) {
                std::vector<std::vector<std::uint32_t>> id(std::size_t(n) + 1);
                for (int a = 0; a <= n; ++a)
                    for (int b = 0; a + b <= n; ++b) {
                        const double x = s * a / n, y = s * b / n, z = s - x - y;
                        id[std::size_t(a)].push_back(std::uint32_t(soup.points.size()));
                        soup.points.push_back({sx * x, sy * y, sz * z});
                    }
                // Outward: (x, y, z) order is counter-clockwise seen from
                // outside in the +++ octant; a mirror turns it over.
                const bool flip = sx * sy * sz < 0;
                auto add = [&](std::uint32_t p, std::uint32_t q, std::uint32_t r) {
                    if (flip) std::swap(q, r);
                    soup.triangles.push_back({p, q, r});
                };
                for (int a = 0; a < n; ++a)
                    for (int b = 0; a + b < n; ++b) {
                        add(id[std::size_t(a)][std::size_t(b)],
                            id[std::size_t(a) + 1][std::size_t(b)],
                            id[std::size_t(a)][std::size_t(b) + 1]);
                        if (a + b + 1 < n)
                            add(id[std::size_t(a) + 1][std::size_t(b)],
                                id[std::size_t(a) + 1][std::size_t(b) + 1],
                                id[std::size_t(a)][std::size_t(b) + 1]);
                    }
            }
    return soup;  // corners repeated per octant: closed by position, as parity needs
}

VolumeGeometry cube(int half, double spacingMm) {
    VolumeGeometry grid;
    grid.size = {2 * half + 1, 2 * half + 1, 2 * half + 1};
    grid.spacingMm = {spacingMm, spacingMm, spacingMm};
    grid.originMm = {-half * spacingMm, -half * spacingMm, -half * spacingMm};
    return grid;
}

std::vector<char> asMask(const std::vector<std::size_t>& inside, const VolumeGeometry& grid) {
    std::vector<char> mask(grid.voxelCount(), 0);
    for (std::size_t v : inside) mask[v] = 1;
    return mask;
}

TEST(VoxelsInsideSolid, OctahedronThroughCornersAndEdgesIsExact) {
    // s = 6.5: rows (j, 0) run along edges, row (0, 0) through two corners,
    // and many through the faces' points; on the millimetre grid no centre
    // lies on a face, on the half millimetre's some do (either side).
    const TriangleSoup solid = octahedron(6.5, 13);
    for (const double spacingMm : {1.0, 0.5}) {
        const VolumeGeometry grid = cube(int(8 / spacingMm), spacingMm);
        const std::vector<std::size_t> inside = voxelsInsideSolid(solid, PlaneFrame{}, grid);
        ASSERT_TRUE(std::is_sorted(inside.begin(), inside.end()));
        const std::vector<char> mask = asMask(inside, grid);
        for (int k = 0; k < grid.size[2]; ++k)
            for (int j = 0; j < grid.size[1]; ++j)
                for (int i = 0; i < grid.size[0]; ++i) {
                    const Vec3 p = grid.worldOfIndex(i, j, k);
                    const double l1 = std::abs(p.x) + std::abs(p.y) + std::abs(p.z);
                    if (spacingMm < 1 && l1 == 6.5) continue;
                    const bool expected = l1 < 6.5;
                    ASSERT_EQ(bool(mask[grid.linearIndex(i, j, k)]), expected)
                        << "spacing " << spacingMm << " at " << p.x << " " << p.y << " " << p.z;
                }
    }
}

TEST(VoxelsInsideSolid, RotatedGridsAgreeWithTheOctahedronsInside) {
    const TriangleSoup solid = octahedron(6.5, 13);
    std::mt19937 random(7);
    std::uniform_real_distribution<double> angle(0, 2 * kPi);
    for (int trial = 0; trial < 6; ++trial) {
        VolumeGeometry grid = cube(12, 0.7);
        // A rotation about a random axis, and a shifted origin.
        const double a = angle(random), b = angle(random);
        const Vec3 axis{std::cos(a) * std::sin(b), std::sin(a) * std::sin(b), std::cos(b)};
        const double t = angle(random), c = std::cos(t), s = std::sin(t);
        const Vec3 e[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
        for (int d = 0; d < 3; ++d) {
            const Vec3 v = c * e[d] + s * cross(axis, e[d]) + (dot(axis, e[d]) * (1 - c)) * axis;
            grid.direction[d] = {v.x, v.y, v.z};
        }
        grid.originMm = {0, 0, 0};
        const Vec3 corner = grid.worldOfIndex(12, 12, 12);
        grid.originMm = {-corner.x + 0.1 * trial, -corner.y, -corner.z};
        const std::vector<char> mask = asMask(voxelsInsideSolid(solid, PlaneFrame{}, grid), grid);
        std::size_t decided = 0;
        for (int k = 0; k < grid.size[2]; ++k)
            for (int j = 0; j < grid.size[1]; ++j)
                for (int i = 0; i < grid.size[0]; ++i) {
                    const Vec3 p = grid.worldOfIndex(i, j, k);
                    const double l1 = std::abs(p.x) + std::abs(p.y) + std::abs(p.z);
                    if (std::abs(l1 - 6.5) < 1e-9) continue;  // on the surface: either side
                    ++decided;
                    ASSERT_EQ(bool(mask[grid.linearIndex(i, j, k)]), l1 < 6.5) << "trial " << trial;
                }
        EXPECT_GT(decided, grid.voxelCount() * 99 / 100);
    }
}

// The winding number of a closed surface about p: the sum of its
// triangles' solid angles (Van Oosterom and Strackee) over 4π.
double windingNumber(const TriangleSoup& soup, const Vec3& p) {
    double total = 0;
    for (const auto& t : soup.triangles) {
        const Vec3 a = soup.points[t[0]] - p, b = soup.points[t[1]] - p, c = soup.points[t[2]] - p;
        const double la = length(a), lb = length(b), lc = length(c);
        total += 2 * std::atan2(dot(a, cross(b, c)),
                                la * lb * lc + dot(a, b) * lc + dot(b, c) * la + dot(c, a) * lb);
    }
    return total / (4 * kPi);
}

TEST(VoxelsInsideSolid, TorusMatchesItsWindingNumber) {
    TriangleSoup solid = dfrecon::testing::torusMesh(9, 3.5, 40, 20);
    ASSERT_TRUE(checkMesh(solid).validSolid());
    for (const double spacingMm : {1.0, 0.5}) {
        VolumeGeometry grid = cube(int(14 / spacingMm), spacingMm);
        grid.originMm[0] += 0.013;  // centres off the torus' points
        const std::vector<char> mask = asMask(voxelsInsideSolid(solid, PlaneFrame{}, grid), grid);
        std::size_t count = 0;
        for (int k = 0; k < grid.size[2]; ++k)
            for (int j = 0; j < grid.size[1]; ++j)
                for (int i = 0; i < grid.size[0]; ++i) {
                    const Vec3 p = grid.worldOfIndex(i, j, k);
                    // Far from the tube the answer is plain; near it ask the
                    // winding number.
                    const double ring = std::hypot(std::hypot(p.x, p.y) - 9, p.z);
                    const bool expected =
                        std::abs(ring - 3.5) > 0.3 ? ring < 3.5 : windingNumber(solid, p) > 0.5;
                    count += expected;
                    ASSERT_EQ(bool(mask[grid.linearIndex(i, j, k)]), expected)
                        << "spacing " << spacingMm << " at " << p.x << " " << p.y << " " << p.z;
                }
        // The voxels' volume converges to the mesh's.
        const double voxelMm3 = std::pow(spacingMm, 3);
        EXPECT_NEAR(double(count) * voxelMm3, measureSurface(solid).volumeMm3,
                    0.03 * measureSurface(solid).volumeMm3);
    }
}

TEST(VoxelsInsideSolid, AnEmptySurfaceOrOneBeyondTheGridHasNoVoxels) {
    EXPECT_TRUE(voxelsInsideSolid({}, PlaneFrame{}, cube(4, 1)).empty());
    TriangleSoup far = octahedron(2.5, 5);
    for (Vec3& p : far.points) p.x += 100;
    EXPECT_TRUE(voxelsInsideSolid(far, PlaneFrame{}, cube(4, 1)).empty());
}

}  // namespace
}  // namespace dfrecon
