#include "algebra/SolidSurface.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <openvdb/openvdb.h>
#include <openvdb/tools/VolumeToMesh.h>

namespace dfrecon {

namespace {

struct VoxelLattice {
    Vec3 origin;  // centre of voxel (0, 0, 0)
    double voxel = 0;
    int block = 8;
    int blocks[3] = {0, 0, 0};
    Vec3 centre(int i, int j, int k) const {
        return origin + voxel * Vec3{double(i), double(j), double(k)};
    }
};

}  // namespace

TriangleSoup solidSurface(const SpaceField& field, double lipschitz, const Box3& support,
                          const SolidSurfaceOptions& options, SolidSurfaceStats* statsOut) {
    if (!(options.voxelMm > 0) || options.blockVoxels < 1)
        throw std::invalid_argument("solidSurface: the voxel must be > 0 mm and a block ≥ 1 voxel");
    if (!(lipschitz > 0) || !std::isfinite(lipschitz))
        throw std::invalid_argument("solidSurface: the Lipschitz constant must be finite and > 0");
    openvdb::initialize();
    SolidSurfaceStats stats;
    VoxelLattice l;
    l.block = options.blockVoxels;
    l.voxel = options.voxelMm;
    const Vec3 size = support.hi - support.lo;
    // Two voxels of outside all round, so the mesher closes every surface.
    const auto blocksAlong = [&](double extent) {
        return int(std::ceil((extent / l.voxel + 4) / l.block));
    };
    while (double(blocksAlong(size.x)) * blocksAlong(size.y) * blocksAlong(size.z) *
               std::pow(l.block, 3) >
           double(options.maxSamples))
        l.voxel *= 1.25;
    for (int a = 0; a < 3; ++a)
        l.blocks[a] = blocksAlong(a == 0 ? size.x : a == 1 ? size.y : size.z);
    l.origin = support.lo - 2 * l.voxel * Vec3{1, 1, 1};
    stats.voxelMm = l.voxel;

    // Block centres (between voxel centres when the block is even).
    std::vector<Vec3> centres;
    const double half = 0.5 * (l.block - 1);
    for (int k = 0; k < l.blocks[2]; ++k)
        for (int j = 0; j < l.blocks[1]; ++j)
            for (int i = 0; i < l.blocks[0]; ++i)
                centres.push_back(l.centre(i * l.block, j * l.block, k * l.block) +
                                  l.voxel * half * Vec3{1, 1, 1});
    const std::vector<double> atCentre = field(centres);
    stats.blockSamples = centres.size();

    // A block is near when its centre's value could reach zero within the
    // block or its neighbours' first voxels (the mesher reads across).
    const double reach = lipschitz * l.voxel * (std::sqrt(3.0) * 0.5 * l.block + 2);
    const float outside = float(3 * l.voxel);
    openvdb::FloatGrid::Ptr grid = openvdb::FloatGrid::create(outside);
    grid->setTransform(openvdb::math::Transform::createLinearTransform(l.voxel));
    grid->transform().postTranslate(openvdb::Vec3d(l.origin.x, l.origin.y, l.origin.z));
    grid->setGridClass(openvdb::GRID_LEVEL_SET);
    std::vector<Vec3> points;
    std::vector<openvdb::Coord> coords;
    std::size_t b = 0;
    for (int k = 0; k < l.blocks[2]; ++k)
        for (int j = 0; j < l.blocks[1]; ++j)
            for (int i = 0; i < l.blocks[0]; ++i, ++b) {
                const openvdb::Coord lo(i * l.block, j * l.block, k * l.block);
                const openvdb::Coord hi = lo.offsetBy(l.block - 1);
                if (std::abs(atCentre[b]) > reach) {
                    // No boundary here: inside blocks become tiles of
                    // negative value (outside ones are the background).
                    if (atCentre[b] < 0) grid->fill(openvdb::CoordBBox(lo, hi), -outside, false);
                    continue;
                }
                for (int z = lo.z(); z <= hi.z(); ++z)
                    for (int y = lo.y(); y <= hi.y(); ++y)
                        for (int x = lo.x(); x <= hi.x(); ++x) {
                            points.push_back(l.centre(x, y, z));
                            coords.emplace_back(x, y, z);
                        }
            }
    const std::vector<double> values = field(points);
    stats.voxelSamples = points.size();
    {
        auto accessor = grid->getAccessor();
        for (std::size_t n = 0; n < coords.size(); ++n)
            accessor.setValue(coords[n],
                              float(std::clamp(values[n], -double(outside), double(outside))));
    }

    std::vector<openvdb::Vec3s> meshPoints;
    std::vector<openvdb::Vec3I> triangles;
    std::vector<openvdb::Vec4I> quads;
    openvdb::tools::volumeToMesh(*grid, meshPoints, triangles, quads, 0.0);
    TriangleSoup soup;
    for (const openvdb::Vec3s& p : meshPoints) soup.points.push_back({p[0], p[1], p[2]});
    // OpenVDB winds its faces clockwise seen from outside; flip to outward.
    for (const openvdb::Vec3I& t : triangles) soup.triangles.push_back({t[2], t[1], t[0]});
    for (const openvdb::Vec4I& q : quads) {
        soup.triangles.push_back({q[3], q[2], q[1]});
        soup.triangles.push_back({q[3], q[1], q[0]});
    }

    if (!options.projectVertices) {
        if (statsOut) *statsOut = stats;
        return soup;
    }
    // Onto the exact zero set: a Newton step along the central-difference
    // gradient, then a secant step along the same direction.
    const double h = 0.05 * l.voxel;
    const std::size_t count = soup.points.size();
    std::vector<Vec3> probe;
    probe.reserve(7 * count);
    const Vec3 axes[3] = {{h, 0, 0}, {0, h, 0}, {0, 0, h}};
    for (const Vec3& p : soup.points) {
        probe.push_back(p);
        for (const Vec3& a : axes) {
            probe.push_back(p + a);
            probe.push_back(p - a);
        }
    }
    const std::vector<double> f = field(probe);
    std::vector<Vec3> direction(count), moved(count);
    std::vector<double> step(count, 0);
    for (std::size_t v = 0; v < count; ++v) {
        const double* at = &f[7 * v];
        const Vec3 g{(at[1] - at[2]) / (2 * h), (at[3] - at[4]) / (2 * h),
                     (at[5] - at[6]) / (2 * h)};
        const double g2 = dot(g, g);
        if (!(g2 > 1e-12)) {
            moved[v] = soup.points[v];
            continue;
        }
        direction[v] = (1 / std::sqrt(g2)) * g;
        step[v] = -at[0] / std::sqrt(g2);
        // Never farther than a voxel: the mesher's vertex is within one.
        step[v] = std::clamp(step[v], -l.voxel, l.voxel);
        moved[v] = soup.points[v] + step[v] * direction[v];
    }
    const std::vector<double> after = field(moved);
    stats.vertexSamples = probe.size() + moved.size();
    for (std::size_t v = 0; v < count; ++v) {
        const double before = f[7 * v];
        double total = step[v];
        // The secant through (0, before) and (step, after).
        if (step[v] != 0 && after[v] != before)
            total = std::clamp(step[v] * before / (before - after[v]), -l.voxel, l.voxel);
        soup.points[v] = soup.points[v] + total * direction[v];
        stats.largestStepMm = std::max(stats.largestStepMm, std::abs(total));
    }
    if (statsOut) *statsOut = stats;
    return soup;
}

}  // namespace dfrecon
