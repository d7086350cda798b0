#pragma once
// Random structure sets as segmentation tools make them: label volumes of
// blobs, bending tubes and shells with islands in their cavities, at coarse
// voxels, turned into contours by contoursFromLabels (what a label-to-
// RTSTRUCT converter does). Their contours share pixel edges and corners
// between planes, touch within planes, branch 1→N→1 and nest three deep:
// the coincidences reconstruction must survive. Deterministic per seed.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>

#include "io/MaskContours.hpp"

namespace dfrecon::testing {

/// Labels 1 (blobs), 2 (a tube) and 3 (a shell with an island) in a volume
/// of about 30×30×14 voxels with random spacing (0.7–1.3 mm in plane, 1–4 mm
/// between planes); later shapes do not overwrite earlier ones.
inline LabelVolume hostileLabelVolume(std::uint32_t seed) {
    std::mt19937 random(seed);
    auto uniform = [&](double lo, double hi) {
        return std::uniform_real_distribution<double>(lo, hi)(random);
    };
    LabelVolume volume;
    VolumeGeometry& g = volume.geometry;
    g.size = {{30, 30, int(uniform(8, 16))}};
    const double pixel = uniform(0.7, 1.3);
    g.spacingMm = {{pixel, pixel, uniform(1, 4)}};
    volume.labels.assign(g.voxelCount(), 0);
    auto set = [&](int i, int j, int k, std::int32_t label) {
        std::int32_t& v = volume.labels[g.linearIndex(i, j, k)];
        if (v == 0) v = label;
    };
    const double nz = g.size[2];
    // Blobs: ellipsoids that overlap, touch or stand apart.
    const int blobs = std::uniform_int_distribution<int>(2, 4)(random);
    for (int b = 0; b < blobs; ++b) {
        const double cx = uniform(6, 24), cy = uniform(6, 24), cz = uniform(1, nz - 2);
        const double rx = uniform(2, 6), ry = uniform(2, 6), rz = uniform(1, nz / 2);
        for (int k = 0; k < g.size[2]; ++k)
            for (int j = 0; j < 30; ++j)
                for (int i = 0; i < 30; ++i) {
                    const double x = (i - cx) / rx, y = (j - cy) / ry, z = (k - cz) / rz;
                    if (x * x + y * y + z * z <= 1) set(i, j, k, 1);
                }
    }
    // A tube bending through the planes: a random walk of discs.
    double tx = uniform(5, 25), ty = uniform(5, 25);
    const double radius = uniform(1.2, 3);
    for (int k = int(uniform(0, 3)); k < g.size[2] - int(uniform(0, 3)); ++k) {
        tx = std::clamp(tx + uniform(-2.5, 2.5), 3.0, 27.0);
        ty = std::clamp(ty + uniform(-2.5, 2.5), 3.0, 27.0);
        for (int j = 0; j < 30; ++j)
            for (int i = 0; i < 30; ++i)
                if (std::hypot(i - tx, j - ty) <= radius) set(i, j, k, 2);
    }
    // A shell with an island in its cavity: three nested contours per plane.
    const double sx = uniform(10, 20), sy = uniform(10, 20), sz = nz / 2;
    const double outer = uniform(6, 9), inner = outer - uniform(1.5, 3), island = uniform(1, 2.5);
    const double zScale = g.spacingMm[2] / pixel;
    for (int k = 0; k < g.size[2]; ++k)
        for (int j = 0; j < 30; ++j)
            for (int i = 0; i < 30; ++i) {
                const double r = std::sqrt((i - sx) * (i - sx) + (j - sy) * (j - sy) +
                                           (k - sz) * (k - sz) * zScale * zScale);
                if ((r <= outer && r > inner) || r <= island) set(i, j, k, 3);
            }
    return volume;
}

}  // namespace dfrecon::testing
