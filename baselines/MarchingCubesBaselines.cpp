#include "baselines/MarchingCubesBaselines.hpp"
#include "baselines/RowCrossings.hpp"

#include <openvdb/openvdb.h>
#include <openvdb/tools/SignedFloodFill.h>
#include <openvdb/tools/VolumeToMesh.h>

#include <algorithm>
#include <cmath>
#include <mutex>
#include <stdexcept>

namespace dfrecon {

namespace {

void initialiseOpenVdb() {
    static std::once_flag initialised;
    std::call_once(initialised, [] { openvdb::initialize(); });
}

// Marching cubes on `volume` at `isovalue`, as outward triangles.
TriangleSoup isoSurface(const openvdb::FloatGrid& volume, double isovalue) {
    std::vector<openvdb::Vec3s> points;
    std::vector<openvdb::Vec3I> triangles;
    std::vector<openvdb::Vec4I> quads;
    openvdb::tools::volumeToMesh(volume, points, triangles, quads, isovalue);
    TriangleSoup soup;
    soup.points.reserve(points.size());
    for (const openvdb::Vec3s& p : points) soup.points.push_back({p[0], p[1], p[2]});
    // OpenVDB winds its faces clockwise seen from outside; flip to outward.
    for (const openvdb::Vec3I& t : triangles) soup.triangles.push_back({t[2], t[1], t[0]});
    for (const openvdb::Vec4I& q : quads) {
        soup.triangles.push_back({q[3], q[2], q[1]});
        soup.triangles.push_back({q[3], q[1], q[0]});
    }
    return soup;
}

}  // namespace

TriMesh levinBaseline(const SliceFields& fields) {
    initialiseOpenVdb();
    const std::size_t slices = fields.sliceCount();
    if (slices == 0) throw std::invalid_argument("levinBaseline: no slices");
    const SliceGrid& grid = fields.grid;
    const double h = grid.pixelMm;
    const std::size_t pixels = grid.pixelCount();
    const double firstGap = slices > 1 ? fields.zMm[1] - fields.zMm[0] : h;
    const double lastGap = slices > 1 ? fields.zMm[slices - 1] - fields.zMm[slices - 2] : h;
    const double zStart = fields.zMm.front() - firstGap, zEnd = fields.zMm.back() + lastGap;
    const int levels = int(std::ceil((zEnd - zStart) / h)) + 1;
    const float band = float(3 * h);

    // A virtual slice: positive everywhere, mirroring inside depths.
    auto virtualValue = [&](std::size_t slice, std::size_t at) {
        return std::max(std::abs(fields.distanceMm[slice * pixels + at]), float(h));
    };

    openvdb::FloatGrid::Ptr volume = openvdb::FloatGrid::create(band);
    volume->setGridClass(openvdb::GRID_LEVEL_SET);
    // Voxel (i, j, k) centred at the pixel centre of (i, j) and z = zStart + k·h.
    auto transform = openvdb::math::Transform::createLinearTransform(h);
    transform->postTranslate(
        openvdb::Vec3d(grid.originMm.x + 0.5 * h, grid.originMm.y + 0.5 * h, zStart));
    volume->setTransform(transform);
    // The field on plane k: linear between the bracketing slices, towards the
    // virtual slices beyond the ends.
    auto level = [&](int k, std::vector<float>& out) {
        out.assign(pixels, band);
        if (k < 0 || k >= levels) return;
        const double z = zStart + k * h;
        std::size_t below = 0;
        while (below + 1 < slices && fields.zMm[below + 1] <= z) ++below;
        for (std::size_t at = 0; at < pixels; ++at) {
            if (z < fields.zMm.front()) {
                const double t = (z - zStart) / firstGap;
                out[at] = float((1 - t) * virtualValue(0, at) + t * fields.distanceMm[at]);
            } else if (z >= fields.zMm.back()) {
                const double t = (z - fields.zMm.back()) / lastGap;
                out[at] = float((1 - t) * fields.distanceMm[(slices - 1) * pixels + at] +
                                t * virtualValue(slices - 1, at));
            } else {
                const double t =
                    (z - fields.zMm[below]) / (fields.zMm[below + 1] - fields.zMm[below]);
                out[at] = float((1 - t) * fields.distanceMm[below * pixels + at] +
                                t * fields.distanceMm[(below + 1) * pixels + at]);
            }
        }
    };
    // Store voxels in the band and every voxel whose 6-neighbour has the
    // other sign: then each cell the surface crosses has all corners set,
    // and the stored shell closes, so the sign flood fill cannot leak where
    // the field is steep (at caps the band is a single voxel thick).
    auto access = volume->getAccessor();
    std::vector<float> previous, current, next;
    level(-1, previous);
    level(0, current);
    const int width = grid.width, height = grid.height;
    for (int k = 0; k < levels; ++k) {
        level(k + 1, next);
        for (int j = 0; j < height; ++j)
            for (int i = 0; i < width; ++i) {
                const std::size_t at = std::size_t(j) * std::size_t(width) + std::size_t(i);
                const float v = current[at];
                bool keep = std::abs(v) < band;
                auto opposite = [&](float w) { return (w < 0) != (v < 0); };
                keep = keep || opposite(previous[at]) || opposite(next[at]) ||
                       (i > 0 && opposite(current[at - 1])) ||
                       (i + 1 < width && opposite(current[at + 1])) ||
                       (j > 0 && opposite(current[at - std::size_t(width)])) ||
                       (j + 1 < height && opposite(current[at + std::size_t(width)]));
                if (keep) access.setValue(openvdb::Coord(i, j, k), std::clamp(v, -band, band));
            }
        std::swap(previous, current);
        std::swap(current, next);
    }
    openvdb::tools::signedFloodFill(volume->tree());

    return toTriMesh(isoSurface(*volume, 0.0));
}

TriangleSoup rasterBaseline(const Roi& roi, double pixelMm) {
    initialiseOpenVdb();
    if (roi.slices.empty()) throw std::invalid_argument("rasterBaseline: no slices");
    Box2 box;
    for (const Slice& s : roi.slices)
        for (const Polygon& c : s.contours)
            for (Point2 p : c) box.add(p);
    const double h = pixelMm;
    const int width = int(std::ceil((box.max.x - box.min.x) / h)) + 1;
    const double spacing = roi.slices.size() > 1 ? spacingOf(roi).meanMm : 1.0;
    openvdb::FloatGrid::Ptr volume = openvdb::FloatGrid::create(0.0f);
    openvdb::math::Mat4d scale = openvdb::math::Mat4d::identity();
    scale.preScale(openvdb::Vec3d(h, h, spacing));
    scale.postTranslate(openvdb::Vec3d(box.min.x, box.min.y, roi.slices.front().zMm));
    volume->setTransform(openvdb::math::Transform::createLinearTransform(scale));
    auto access = volume->getAccessor();
    std::vector<double> crossings;
    for (const Slice& slice : roi.slices) {
        const int plane = int(std::lround((slice.zMm - roi.slices.front().zMm) / spacing));
        for (int j = 0; box.min.y + j * h <= box.max.y; ++j) {
            const double y = box.min.y + j * h;
            // Even-odd along the row: inside between the 1st and 2nd crossing, ...
            rowCrossings(slice, y, crossings);
            for (std::size_t c = 0; c + 1 < crossings.size(); c += 2)
                for (int i = std::max(0, int(std::ceil((crossings[c] - box.min.x) / h)));
                     i < width && box.min.x + i * h <= crossings[c + 1]; ++i)
                    access.setValue(openvdb::Coord(i, j, plane), 1.0f);
        }
    }
    return isoSurface(*volume, 0.5);
}

}  // namespace dfrecon
