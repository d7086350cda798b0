#include "io/labels/MaskContours.hpp"

#include <algorithm>
#include <cmath>

#include "contours/InputError.hpp"
#include "geometry/IsoLines.hpp"

namespace dfrecon {

namespace {

// Largest |cos| between two volume axes still taken as orthogonal: NIfTI
// sforms stored in float are orthogonal only to about 1e-7.
constexpr double kMaxAxisCosine = 1e-4;

Vec3 unit(Vec3 a) {
    return (1.0 / length(a)) * a;
}

Vec3 directionOf(const VolumeGeometry& geometry, int axis) {
    const auto& d = geometry.direction[std::size_t(axis)];
    return {d[0], d[1], d[2]};
}

// The right-handed frame with u along axis 0 and v along axis 1 (made
// exactly orthonormal); its n is ±direction[2]. `nSign` receives the sign.
PlaneFrame frameOf(const VolumeGeometry& geometry, const std::string& source, double& nSign) {
    const Vec3 d0 = unit(directionOf(geometry, 0)), d1 = unit(directionOf(geometry, 1)),
               d2 = unit(directionOf(geometry, 2));
    for (double c : {dot(d0, d1), dot(d0, d2), dot(d1, d2)})
        if (!(std::abs(c) <= kMaxAxisCosine))
            throw InputError(source, 0,
                             "the volume's axes are not orthogonal (sheared grid); contours "
                             "need orthogonal axes");
    PlaneFrame frame;
    frame.u = d0;
    // Gram-Schmidt leaves exactly orthogonal axes unchanged (identity stays
    // identity), and cleans the float noise of nearly orthogonal ones.
    frame.v = unit(d1 - dot(d1, d0) * d0);
    frame.n = cross(frame.u, frame.v);
    nSign = dot(frame.n, d2) > 0 ? 1.0 : -1.0;
    return frame;
}

struct PixelBox {
    int iMin, jMin, iMax, jMax;
};

}  // namespace

ContourSet contoursFromLabels(const LabelVolume& volume, const MaskContourOptions& options) {
    const VolumeGeometry& geometry = volume.geometry;
    const std::string& source = options.sourceName;
    if (volume.labels.size() != geometry.voxelCount() || geometry.voxelCount() == 0)
        throw InputError(source, 0, "the label count does not match the volume's size");
    const int width = geometry.size[0], height = geometry.size[1], planes = geometry.size[2];
    if (!options.planePositionsMm.empty()) {
        if (options.planePositionsMm.size() != std::size_t(planes))
            throw InputError(source, 0, "plane positions: one per plane needed");
        for (std::size_t k = 1; k < options.planePositionsMm.size(); ++k)
            if (!(options.planePositionsMm[k] > options.planePositionsMm[k - 1]))
                throw InputError(source, 0, "plane positions are not strictly increasing");
    }
    double nSign = 1;
    const PlaneFrame frame = frameOf(geometry, source, nSign);
    const Vec3 origin{geometry.originMm[0], geometry.originMm[1], geometry.originMm[2]};
    // Plane coordinates of voxel (i, j, k): x0 + i·sx, y0 + j·sy, z0 + k·sz.
    const double x0 = dot(origin, frame.u), y0 = dot(origin, frame.v), z0 = dot(origin, frame.n);
    const double sx = geometry.spacingMm[0], sy = geometry.spacingMm[1];
    const double sz = nSign * geometry.spacingMm[2];

    std::map<std::int32_t, Roi> rois;
    std::vector<float> image;
    for (int k = 0; k < planes; ++k) {
        const std::int32_t* plane =
            volume.labels.data() + std::size_t(k) * std::size_t(width) * std::size_t(height);
        // One pass finds each label's box, so each label's image covers only
        // its own pixels (outside the image counts as outside the label).
        std::map<std::int32_t, PixelBox> boxes;
        for (int j = 0; j < height; ++j)
            for (int i = 0; i < width; ++i) {
                const std::int32_t label =
                    plane[std::size_t(j) * std::size_t(width) + std::size_t(i)];
                if (label == options.backgroundLabel) continue;
                auto [it, added] = boxes.try_emplace(label, PixelBox{i, j, i, j});
                if (added) continue;
                PixelBox& box = it->second;
                box = {std::min(box.iMin, i), std::min(box.jMin, j), std::max(box.iMax, i),
                       std::max(box.jMax, j)};
            }
        const double zMm = options.planePositionsMm.empty()
                               ? z0 + k * sz
                               : options.planePositionsMm[std::size_t(k)];
        for (const auto& [label, box] : boxes) {
            // One pixel of +½ round the box: the marching squares' own
            // outside value (+1) would move border crossings off the midpoints.
            const int w = box.iMax - box.iMin + 3, h = box.jMax - box.jMin + 3;
            const int iFirst = box.iMin - 1, jFirst = box.jMin - 1;
            image.assign(std::size_t(w) * std::size_t(h), 0.5f);
            for (int j = 1; j + 1 < h; ++j)
                for (int i = 1; i + 1 < w; ++i)
                    if (plane[std::size_t(j + jFirst) * std::size_t(width) +
                              std::size_t(i + iFirst)] == label)
                        image[std::size_t(j) * std::size_t(w) + std::size_t(i)] = -0.5f;
            // Index → plane millimetres is a positive scaling plus a shift,
            // so the borders keep their orientation.
            SampleLattice lattice;
            lattice.originMm = {x0, y0};
            lattice.stepMm = {sx, sy};
            lattice.indexOffset = {double(iFirst), double(jFirst)};
            Slice slice{zMm, negativeRegionBorders(image, w, h, lattice)};
            rois[label].slices.push_back(std::move(slice));
        }
    }

    ContourSet set;
    for (auto& [label, roi] : rois) {
        const auto name = options.names.find(label);
        roi.name = name != options.names.end() ? name->second : "label_" + std::to_string(label);
        if (const auto colour = options.colours.find(label); colour != options.colours.end())
            roi.colour = colour->second;
        roi.number = label;
        roi.frame = frame;
        roi.slabThicknessMm = geometry.spacingMm[2];
        std::sort(roi.slices.begin(), roi.slices.end(),
                  [](const Slice& a, const Slice& b) { return a.zMm < b.zMm; });
        // The volume's own axes (RAS, feet-first slices) would leave an axial
        // stack in a mirrored or rotated frame that every output must undo.
        changeFrame(roi, canonicalFrame(frame));
        set.rois.push_back(std::move(roi));
    }
    return set;
}

}  // namespace dfrecon
