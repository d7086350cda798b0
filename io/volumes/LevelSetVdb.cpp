#include "io/volumes/LevelSetVdb.hpp"

#include <openvdb/openvdb.h>
#include <openvdb/tools/Interpolation.h>
#include <openvdb/tools/SignedFloodFill.h>

#include <algorithm>
#include <cmath>
#include <mutex>
#include <stdexcept>

#include "contours/InputError.hpp"
#include "io/files/AtomicWrite.hpp"
#include "io/files/InputsInUse.hpp"

namespace dfrecon {

namespace {

// index → world: scale and translate, then the frame's rotation when the
// volume's axes are not the patient's (OpenVDB maps row vectors: world =
// index · M, so row a of M is the world image of index axis a).
openvdb::math::Transform::Ptr transformOf(const DenseDistanceVolume& volume,
                                          const PlaneFrame& frame) {
    const openvdb::Vec3d voxel(volume.voxelMm[0], volume.voxelMm[1], volume.voxelMm[2]);
    const openvdb::Vec3d origin(volume.originMm[0], volume.originMm[1], volume.originMm[2]);
    if (frame.isIdentity())
        return openvdb::math::Transform::Ptr(new openvdb::math::Transform(
            openvdb::math::MapBase::Ptr(new openvdb::math::ScaleTranslateMap(voxel, origin))));
    openvdb::math::Mat4d m = openvdb::math::Mat4d::identity();
    const Vec3 axes[3] = {frame.u, frame.v, frame.n};
    for (int a = 0; a < 3; ++a)
        for (int c = 0; c < 3; ++c) m(a, c) = voxel[a] * axes[a][c];
    const Vec3 translation = frame.toPatient({origin[0], origin[1], origin[2]});
    for (int c = 0; c < 3; ++c) m(3, c) = translation[c];
    return openvdb::math::Transform::Ptr(
        new openvdb::math::Transform(openvdb::math::MapBase::Ptr(new openvdb::math::AffineMap(m))));
}

}  // namespace

void writeLevelSetVdb(const DenseDistanceVolume& volume, const std::string& path,
                      const LevelSetWriteOptions& options) {
    if (volume.nx <= 0 || volume.ny <= 0 || volume.nz <= 0 ||
        volume.valuesMm.size() !=
            std::size_t(volume.nx) * std::size_t(volume.ny) * std::size_t(volume.nz))
        throw std::invalid_argument("level set volume: dimensions do not match its values");
    if (!(options.bandVoxels > 0)) throw std::invalid_argument("level set band must be positive");
    static std::once_flag initialised;
    std::call_once(initialised, [] { openvdb::initialize(); });

    // Measured in the largest voxel side, so that across every cell the
    // surface crosses, whatever its direction, both values are stored.
    const double largest = std::max({volume.voxelMm[0], volume.voxelMm[1], volume.voxelMm[2]});
    const float background = float(options.bandVoxels * largest);
    openvdb::FloatGrid::Ptr grid = openvdb::FloatGrid::create(background);
    grid->setName(options.gridName);
    grid->setGridClass(openvdb::GRID_LEVEL_SET);
    grid->setTransform(transformOf(volume, options.frame));
    auto accessor = grid->getAccessor();
    for (int k = 0; k < volume.nz; ++k)
        for (int j = 0; j < volume.ny; ++j)
            for (int i = 0; i < volume.nx; ++i) {
                const float v =
                    volume.valuesMm[(std::size_t(k) * std::size_t(volume.ny) + std::size_t(j)) *
                                        std::size_t(volume.nx) +
                                    std::size_t(i)];
                if (std::fabs(v) < background) accessor.setValue(openvdb::Coord(i, j, k), v);
            }
    // Inactive voxels inside get -background, as level-set tools expect.
    openvdb::tools::signedFloodFill(grid->tree());
    for (const auto& [key, value] : options.metadata)
        grid->insertMeta(key, openvdb::StringMetadata(value));

    writeAtomically(path, [&](const std::string& temp) {
        openvdb::io::File file(temp);
        file.write({grid});
        file.close();
        return true;
    });
}

struct LevelSetSampler::Grid {
    openvdb::FloatGrid::ConstPtr grid;
    std::string name;
};

LevelSetSampler::LevelSetSampler(const std::string& path, const std::string& gridName)
    : grid_(std::make_unique<Grid>()) {
    const ReadingInput reading(path);
    static std::once_flag initialised;
    std::call_once(initialised, [] { openvdb::initialize(); });
    openvdb::GridPtrVecPtr grids;
    try {
        openvdb::io::File file(path);
        file.open();
        grids = file.getGrids();
        file.close();
    } catch (const std::bad_alloc&) {
        throw;  // main() says which file, as for any input
    } catch (const std::exception& e) {
        throw InputError(path, 0, std::string("not a readable OpenVDB file: ") + e.what());
    }
    for (const openvdb::GridBase::Ptr& base : *grids) {
        auto grid = openvdb::gridPtrCast<openvdb::FloatGrid>(base);
        if (!grid || (!gridName.empty() && grid->getName() != gridName)) continue;
        grid_->grid = grid;
        grid_->name = grid->getName();
        return;
    }
    throw InputError(path, 0,
                     gridName.empty() ? "no float grid in the file"
                                      : "no float grid named '" + gridName + "' in the file");
}

LevelSetSampler::~LevelSetSampler() = default;
LevelSetSampler::LevelSetSampler(LevelSetSampler&&) noexcept = default;

const std::string& LevelSetSampler::gridName() const {
    return grid_->name;
}

double LevelSetSampler::operator()(Vec3 p) const {
    // A sampler per call: accessors cache nodes and are not thread-safe.
    openvdb::tools::GridSampler<openvdb::FloatGrid, openvdb::tools::BoxSampler> sampler(
        *grid_->grid);
    return sampler.wsSample(openvdb::Vec3d(p.x, p.y, p.z));
}

}  // namespace dfrecon
