#include "shapes/RandomLabelVolumes.hpp"

#include <algorithm>
#include <cmath>
#include <random>

namespace dfrecon {

namespace {

class Painter {
  public:
    explicit Painter(LabelVolume& volume) : volume_(volume) {}
    /// Sets voxel (i, j, k) to `label` unless an earlier shape took it.
    void set(int i, int j, int k, std::int32_t label) {
        std::int32_t& v = volume_.labels[volume_.geometry.linearIndex(i, j, k)];
        if (v == 0) v = label;
    }
    /// Paints an axis-aligned ellipsoid (centre and radii in voxels).
    void ellipsoid(const Vec3& centre, const Vec3& radii, std::int32_t label) {
        const double cx = centre.x, cy = centre.y, cz = centre.z;
        const double rx = radii.x, ry = radii.y, rz = radii.z;
        const auto& size = volume_.geometry.size;
        for (int k = std::max(0, int(cz - rz)); k <= std::min(size[2] - 1, int(cz + rz) + 1); ++k)
            for (int j = std::max(0, int(cy - ry)); j <= std::min(size[1] - 1, int(cy + ry) + 1);
                 ++j)
                for (int i = std::max(0, int(cx - rx));
                     i <= std::min(size[0] - 1, int(cx + rx) + 1); ++i) {
                    const double x = (i - cx) / rx, y = (j - cy) / ry, z = (k - cz) / rz;
                    if (x * x + y * y + z * z <= 1) set(i, j, k, label);
                }
    }

  private:
    LabelVolume& volume_;
};

LabelVolume emptyVolume(int nx, int ny, int nz, double pixelMm, double planeMm) {
    LabelVolume volume;
    volume.geometry.size = {{nx, ny, nz}};
    volume.geometry.spacingMm = {{pixelMm, pixelMm, planeMm}};
    volume.labels.assign(volume.geometry.voxelCount(), 0);
    return volume;
}

}  // namespace

LabelVolume hostileLabelVolume(std::uint32_t seed) {
    std::mt19937 random(seed);
    auto uniform = [&](double lo, double hi) {
        return std::uniform_real_distribution<double>(lo, hi)(random);
    };
    const int planes = int(uniform(8, 16));
    const double pixel = uniform(0.7, 1.3);
    LabelVolume volume = emptyVolume(30, 30, planes, pixel, uniform(1, 4));
    Painter paint(volume);
    const double nz = planes;
    const int blobs = std::uniform_int_distribution<int>(2, 4)(random);
    for (int b = 0; b < blobs; ++b) {
        const double cx = uniform(6, 24), cy = uniform(6, 24), cz = uniform(1, nz - 2);
        const double rx = uniform(2, 6), ry = uniform(2, 6), rz = uniform(1, nz / 2);
        paint.ellipsoid({cx, cy, cz}, {rx, ry, rz}, 1);
    }
    // A tube: a random walk of discs, one per plane.
    double tx = uniform(5, 25), ty = uniform(5, 25);
    const double radius = uniform(1.2, 3);
    for (int k = int(uniform(0, 3)); k < planes - int(uniform(0, 3)); ++k) {
        tx = std::clamp(tx + uniform(-2.5, 2.5), 3.0, 27.0);
        ty = std::clamp(ty + uniform(-2.5, 2.5), 3.0, 27.0);
        for (int j = 0; j < 30; ++j)
            for (int i = 0; i < 30; ++i)
                if (std::hypot(i - tx, j - ty) <= radius) paint.set(i, j, k, 2);
    }
    // A shell with an island in its cavity: three nested contours per plane.
    const double sx = uniform(10, 20), sy = uniform(10, 20), sz = nz / 2;
    const double outer = uniform(6, 9), inner = outer - uniform(1.5, 3), island = uniform(1, 2.5);
    const double zScale = volume.geometry.spacingMm[2] / pixel;
    for (int k = 0; k < planes; ++k)
        for (int j = 0; j < 30; ++j)
            for (int i = 0; i < 30; ++i) {
                const double r = std::sqrt((i - sx) * (i - sx) + (j - sy) * (j - sy) +
                                           (k - sz) * (k - sz) * zScale * zScale);
                if ((r <= outer && r > inner) || r <= island) paint.set(i, j, k, 3);
            }
    return volume;
}

LabelVolume manyBlobLabelVolume(std::uint32_t seed, int blobs, int side, int planes) {
    std::mt19937 random(seed);
    auto uniform = [&](double lo, double hi) {
        return std::uniform_real_distribution<double>(lo, hi)(random);
    };
    LabelVolume volume = emptyVolume(side, side, planes, 0.5, 2);
    Painter paint(volume);
    for (int b = 0; b < blobs; ++b) {
        // Drawn in this order, centre first (the volumes are seeded).
        const Vec3 centre{uniform(4, side - 4), uniform(4, side - 4), uniform(1, planes - 2)};
        const Vec3 radii{uniform(2, 8), uniform(2, 8), uniform(1, 6)};
        paint.ellipsoid(centre, radii, 1);
    }
    return volume;
}

}  // namespace dfrecon
