// Level sets written as .vdb and read back with OpenVDB itself.
#include <gtest/gtest.h>

#include <openvdb/openvdb.h>
#include <openvdb/tools/Interpolation.h>

#include <cmath>
#include <filesystem>

#include "io/volumes/LevelSetVdb.hpp"

namespace dfrecon {
namespace {

// A sphere of radius 5 sampled on anisotropic voxels.
DenseDistanceVolume sphereVolume() {
    DenseDistanceVolume v;
    v.nx = v.ny = 30;
    v.nz = 12;
    v.originMm[0] = v.originMm[1] = -7.25;
    v.originMm[2] = -7.5;
    v.voxelMm[0] = v.voxelMm[1] = 0.5;
    v.voxelMm[2] = 1.25;
    for (int k = 0; k < v.nz; ++k)
        for (int j = 0; j < v.ny; ++j)
            for (int i = 0; i < v.nx; ++i) {
                const double x = v.originMm[0] + i * v.voxelMm[0],
                             y = v.originMm[1] + j * v.voxelMm[1],
                             z = v.originMm[2] + k * v.voxelMm[2];
                v.valuesMm.push_back(float(std::sqrt(x * x + y * y + z * z) - 5));
            }
    return v;
}

TEST(LevelSetVdb, ReadsBackAsANamedLevelSetWithItsTransformAndMetadata) {
    const std::string path =
        (std::filesystem::temp_directory_path() / "dfrecon-test-sphere.vdb").string();
    LevelSetWriteOptions options;
    options.gridName = "Left Kidney";
    options.metadata = {{"units", "mm"}};
    writeLevelSetVdb(sphereVolume(), path, options);

    openvdb::initialize();
    openvdb::io::File file(path);
    file.open();
    const openvdb::GridBase::Ptr base = file.readGrid("Left Kidney");
    file.close();
    std::filesystem::remove(path);
    const auto grid = openvdb::gridPtrCast<openvdb::FloatGrid>(base);
    ASSERT_TRUE(grid);
    EXPECT_EQ(grid->getGridClass(), openvdb::GRID_LEVEL_SET);
    EXPECT_EQ(grid->metaValue<std::string>("units"), "mm");
    const openvdb::Vec3d voxel = grid->voxelSize();
    EXPECT_DOUBLE_EQ(voxel[0], 0.5);
    EXPECT_DOUBLE_EQ(voxel[2], 1.25);
    EXPECT_FLOAT_EQ(grid->background(), float(3 * 1.25));

    // World-space samples: zero on the sphere, negative inside (flood fill).
    const openvdb::tools::GridSampler<openvdb::FloatGrid, openvdb::tools::BoxSampler> sampler(
        *grid);
    for (int a = 0; a < 12; ++a) {
        const double t = 2 * M_PI * a / 12;
        EXPECT_NEAR(sampler.wsSample(openvdb::Vec3d(5 * std::cos(t), 5 * std::sin(t), 0)), 0.0,
                    0.1);
    }
    EXPECT_LT(sampler.wsSample(openvdb::Vec3d(0, 0, 0)), 0);
    EXPECT_GT(sampler.wsSample(openvdb::Vec3d(6.9, 0, 0)), 0);
}

TEST(LevelSetVdb, RejectsInconsistentVolumesAndWritesNothing) {
    DenseDistanceVolume broken = sphereVolume();
    broken.valuesMm.pop_back();
    const std::string path =
        (std::filesystem::temp_directory_path() / "dfrecon-test-broken.vdb").string();
    EXPECT_THROW(writeLevelSetVdb(broken, path, {}), std::invalid_argument);
    EXPECT_FALSE(std::filesystem::exists(path));
}

}  // namespace
}  // namespace dfrecon
