// The voxel margin baselines on shapes whose voxel counts are known exactly:
// a box of square contours (grown, shrunk and unchanged), a single voxel
// grown into a lattice ball, and plastimatch's distance map against the
// exact transform.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <sstream>
#include <stdexcept>
#include <string>

#include "baselines/VoxelMargins.hpp"

using namespace dfrecon;

namespace {

// x0..x1 × y0..y1 squares on the planes z = z0, z0 + 1, ..., z1.
Roi boxRoi(double x0, double y0, double x1, double y1, int z0, int z1) {
    Roi roi;
    roi.name = "box";
    for (int z = z0; z <= z1; ++z)
        roi.slices.push_back({double(z), {{{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}}});
    return roi;
}

// Circles of `radius` about the z axis on the planes of a sphere of that
// radius at 1 mm spacing (the planes it cuts, poles left out).
Roi sphereRoi(double radius) {
    Roi roi;
    roi.name = "sphere";
    for (int z = -int(radius) + 1; z < radius; ++z) {
        const double r = std::sqrt(radius * radius - double(z) * z);
        Polygon circle;
        for (int i = 0; i < 64; ++i)
            circle.push_back({r * std::cos(2 * kPi * i / 64), r * std::sin(2 * kPi * i / 64)});
        roi.slices.push_back({double(z), {circle}});
    }
    return roi;
}

bool onPath(const std::string& program) {
    const char* path = std::getenv("PATH");
    std::istringstream folders(path ? path : "");
    std::string folder;
    while (std::getline(folders, folder, ':'))
        if (!folder.empty() && ::access((folder + "/" + program).c_str(), X_OK) == 0) return true;
    return false;
}

// 20 × 20 mm squares on the planes z = 0, ..., 20: 21 planes of 1 mm, a
// 20 × 20 × 21 mm stack.
const Roi& box20() {
    static const Roi roi = boxRoi(0, 0, 20, 20, 0, 20);
    return roi;
}

}  // namespace

TEST(EdtVoxelMargin, UnchangedMaskIsThePlanningSystemStack) {
    const VoxelMarginResult mask = edtVoxelMargin(box20(), 1, 0);
    EXPECT_NEAR(mask.volumeMm3, 20 * 20 * 21, 20 * 20 * 1);
    // Cells tile the squares and centres sit on the planes, each reaching
    // half a spacing: exactly 20 × 20 × 21 voxels.
    EXPECT_EQ(mask.voxels, 20u * 20u * 21u);
    EXPECT_NEAR(edtVoxelMargin(box20(), 0.5, 0).volumeMm3, 20 * 20 * 21, 20 * 20 * 0.5);
}

TEST(EdtVoxelMargin, GrownBoxIsTheRoundedBox) {
    // Exactly the voxels whose centre is within 5 voxels of the mask's
    // centres, the lattice points (0..19) × (0..19) × (0..20).
    std::size_t lattice = 0;
    for (int i = -6; i <= 25; ++i)
        for (int j = -6; j <= 25; ++j)
            for (int k = -6; k <= 26; ++k) {
                const int dx = std::max({0, -i, i - 19}), dy = std::max({0, -j, j - 19}),
                          dz = std::max({0, -k, k - 20});
                lattice += dx * dx + dy * dy + dz * dz <= 25;
            }
    const VoxelMarginResult grown = edtVoxelMargin(box20(), 1, 5);
    EXPECT_EQ(grown.voxels, lattice);
    EXPECT_GT(grown.seconds, 0);

    // The box's Minkowski sum with a ball of radius r.
    const double a = 20, b = 20, c = 21, r = 5;
    const double exact = a * b * c + 2 * r * (a * b + b * c + c * a) + kPi * r * r * (a + b + c) +
                         4.0 / 3.0 * kPi * r * r * r;
    // Measured from the mask's outer centres, half a voxel inside its faces,
    // the margin is whole along the axes but its edges and corners round
    // about half a voxel short: -5.2 % at 1 mm voxels (24764 of 26115 mm³),
    // -2.7 % at 0.5 mm, -1.4 % at 0.25 mm.
    EXPECT_NEAR(grown.volumeMm3 / exact, 1 - 0.052, 0.005) << grown.volumeMm3 << " vs " << exact;
    const VoxelMarginResult fine = edtVoxelMargin(box20(), 0.5, 5);
    EXPECT_NEAR(fine.volumeMm3 / exact, 1, 0.03) << fine.volumeMm3 << " vs " << exact;
}

TEST(EdtVoxelMargin, ShrunkBoxIsTheInnerBox) {
    const VoxelMarginResult shrunk = edtVoxelMargin(box20(), 1, -3);
    EXPECT_NEAR(shrunk.volumeMm3 / (14 * 14 * 15), 1, 0.05);
    // Voxels farther than 3 voxels from the outside: 3 layers go from each
    // side, exactly.
    EXPECT_EQ(shrunk.voxels, 14u * 14u * 15u);
    // Shrunk by more than half its width, nothing is left.
    EXPECT_EQ(edtVoxelMargin(box20(), 1, -11).voxels, 0u);
}

TEST(EdtVoxelMargin, OneVoxelGrowsIntoTheLatticeBall) {
    // A lone plane one voxel thick holding one voxel centre, (0.5, 0.5, 0).
    Roi voxel = boxRoi(0, 0, 1, 1, 0, 0);
    voxel.slabThicknessMm = 1;
    for (double r : {1.0, 2.5, 5.0, 7.3}) {
        SCOPED_TRACE(r);
        std::size_t lattice = 0;
        const int n = int(r);
        for (int i = -n; i <= n; ++i)
            for (int j = -n; j <= n; ++j)
                for (int k = -n; k <= n; ++k) lattice += i * i + j * j + k * k <= r * r;
        EXPECT_EQ(edtVoxelMargin(voxel, 1, r).voxels, lattice);
        // The same ball in voxels of half the size, from one of them.
        Roi half = boxRoi(0, 0, 0.5, 0.5, 0, 0);
        half.slabThicknessMm = 0.5;
        EXPECT_EQ(edtVoxelMargin(half, 0.5, r / 2).voxels, lattice);
    }
}

TEST(EdtVoxelMargin, RefusesWhatItCannotRasterise) {
    EXPECT_THROW(edtVoxelMargin(Roi{}, 1, 1), std::invalid_argument);
    EXPECT_THROW(edtVoxelMargin(box20(), 0, 1), std::invalid_argument);
    EXPECT_THROW(edtVoxelMargin(box20(), 1, std::nan("")), std::invalid_argument);
}

TEST(PlastimatchVoxelMargin, AgreesWithTheExactTransform) {
    if (!onPath("plastimatch")) GTEST_SKIP() << "plastimatch is not on PATH";
    const Roi sphere = sphereRoi(8);
    struct Case {
        const Roi* roi;
        double voxelMm, marginMm;
    };
    for (const Case& c : {Case{&box20(), 1, 5}, Case{&box20(), 1, -3}, Case{&box20(), 1, 0},
                          Case{&sphere, 0.5, 3}, Case{&sphere, 0.5, -2.5}}) {
        SCOPED_TRACE(c.roi->name + " " + std::to_string(c.voxelMm) + " " +
                     std::to_string(c.marginMm));
        const VoxelMarginResult exact = edtVoxelMargin(*c.roi, c.voxelMm, c.marginMm);
        const VoxelMarginResult plastimatch = plastimatchVoxelMargin(*c.roi, c.voxelMm, c.marginMm);
        EXPECT_NEAR(plastimatch.volumeMm3 / exact.volumeMm3, 1, 0.01);
        // Both exact between voxel centres: the same voxels.
        EXPECT_EQ(plastimatch.voxels, exact.voxels);
    }
}

TEST(PlastimatchVoxelMargin, MissingPlastimatchNamesTheCommand) {
    const char* path = std::getenv("PATH");
    const std::string saved = path ? path : "";
    ::setenv("PATH", "/nonexistent", 1);
    try {
        plastimatchVoxelMargin(box20(), 1, 2);
        ADD_FAILURE() << "no exception";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("plastimatch dmap"), std::string::npos) << e.what();
    }
    ::setenv("PATH", saved.c_str(), 1);
}
