#include "field/Rasterization.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>

namespace dfrecon {

PlaneFrame sharedFrame(const std::vector<const Roi*>& rois) {
    for (const Roi* roi : rois)
        if (!(roi->frame.u == rois.front()->frame.u && roi->frame.v == rois.front()->frame.v &&
              roi->frame.n == rois.front()->frame.n))
            return PlaneFrame{};
    return rois.front()->frame;
}

VolumeGeometry gridAroundRois(const std::vector<const Roi*>& rois, double voxelMm) {
    const PlaneFrame frame = sharedFrame(rois);
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (const Roi* roi : rois) {
        // sharedFrame gives the ROI's own frame or, where frames differ, LPS.
        const bool ownFrame = roi->frame.u == frame.u && roi->frame.v == frame.v;
        const Extent3 extent = ownFrame ? extentOf(*roi) : patientExtentOf(*roi);
        const SpacingStats spacing = spacingOf(*roi);
        const double reach = 0.5 * (spacing.maxMm > 0 ? spacing.maxMm : 1.0);
        // The caps reach half a spacing out along the ROI's own normal.
        const bool alongZ = std::abs(dot(roi->frame.n, frame.n)) > 0.5;
        for (int a = 0; a < 3; ++a) {
            const double margin = voxelMm + (alongZ ? (a == 2 ? reach : 0) : reach);
            lo[a] = std::min(lo[a], extent.min[a] - margin);
            hi[a] = std::max(hi[a], extent.max[a] + margin);
        }
    }
    VolumeGeometry g;
    for (int a = 0; a < 3; ++a) {
        const double span = hi[a] - lo[a];
        if (span / voxelMm > 4096)
            throw std::invalid_argument("--voxel-mm gives over 4096 voxels a side");
        g.size[a] = int(std::ceil(span / voxelMm)) + 1;
        g.spacingMm[a] = voxelMm;
    }
    const Vec3 origin = frame.toPatient({lo[0], lo[1], lo[2]});
    g.originMm = {origin.x, origin.y, origin.z};
    const Vec3 axes[3] = {frame.u, frame.v, frame.n};
    for (int a = 0; a < 3; ++a) g.direction[a] = {axes[a].x, axes[a].y, axes[a].z};
    return g;
}

namespace {

// Contours lie on image planes to this much (io's kSamePlaneToleranceMm).
constexpr double kOnPlaneMm = 0.01;

// The contours of one plane along one row y = const: where each edge
// crosses it (Sunday's half-open rule: an edge counts when a.y <= y < b.y
// or b.y <= y < a.y), sorted, so the crossings right of any x are a suffix.
class ContourRow {
  public:
    ContourRow(const Slice& slice, double y) : slice_(slice), y_(y) {
        for (std::size_t c = 0; c < slice.contours.size(); ++c) {
            const Polygon& contour = slice.contours[c];
            for (std::size_t k = 0; k < contour.size(); ++k) {
                const Point2 a = contour[k], b = contour[(k + 1) % contour.size()];
                if (!((a.y <= y && b.y > y) || (b.y <= y && a.y > y))) continue;
                const double x = a.x + (y - a.y) * (b.x - a.x) / (b.y - a.y);
                crossings_.push_back({x, c, k});
            }
        }
        std::sort(crossings_.begin(), crossings_.end(),
                  [](const Crossing& l, const Crossing& r) { return l.x < r.x; });
        suffix_.assign(crossings_.size() + 1, 0);
        for (std::size_t i = crossings_.size(); i-- > 0;) suffix_[i] = suffix_[i + 1] + 1;
    }
    double y() const { return y_; }
    const Slice& slice() const { return slice_; }

    /// Is (x, y) inside: an odd number of crossings to its right (the
    /// even-odd rule the contours were read by, which no contour's
    /// orientation can turn over)? Crossings a hair from x are judged by the
    /// exact side test (windingCrossing) instead of their rounded x.
    /// O(log e).
    bool inside(double x) const {
        const double hair = 1e-9 * (1 + std::abs(x));
        auto from = std::lower_bound(crossings_.begin(), crossings_.end(), x - hair,
                                     [](const Crossing& c, double v) { return c.x < v; });
        auto to = std::upper_bound(from, crossings_.end(), x + hair,
                                   [](double v, const Crossing& c) { return v < c.x; });
        int crossed = suffix_[std::size_t(to - crossings_.begin())];
        for (auto it = from; it != to; ++it) {
            const Polygon& contour = slice_.contours[it->contour];
            crossed += windingCrossing({x, y_}, contour[it->edge],
                                       contour[(it->edge + 1) % contour.size()]) != 0;
        }
        return crossed % 2 == 1;
    }

  private:
    struct Crossing {
        double x;
        std::size_t contour, edge;
    };
    const Slice& slice_;
    double y_;
    std::vector<Crossing> crossings_;
    std::vector<int> suffix_;  // suffix_[i]: how many crossings from i to the end
};

// The plane of `planes` (sorted by z) within kOnPlaneMm of z, or nullptr.
const Slice* planeAt(const std::vector<Slice>& planes, double z) {
    auto it = std::lower_bound(planes.begin(), planes.end(), z - kOnPlaneMm,
                               [](const Slice& s, double v) { return s.zMm < v; });
    return it != planes.end() && it->zMm <= z + kOnPlaneMm ? &*it : nullptr;
}

}  // namespace

std::vector<std::size_t> voxelsInside(const DistanceField3D& field, const PlaneFrame& frame,
                                      const VolumeGeometry& grid,
                                      const std::vector<Slice>& planes) {
    // Beyond the field's layers and pixels everything is outside; within,
    // the interpolated field decides (its zero set is the surface the
    // reconstruction follows, the flat caps included).
    const SliceGrid& g = field.grid;
    const double lo[3] = {g.originMm.x, g.originMm.y, field.zMm.front()};
    const double hi[3] = {lo[0] + g.width * g.pixelMm, lo[1] + g.height * g.pixelMm,
                          field.zMm.back()};
    int first[3] = {grid.size[0], grid.size[1], grid.size[2]}, last[3] = {-1, -1, -1};
    for (int corner = 0; corner < 8; ++corner) {
        const Vec3 p = frame.toPatient(
            {corner & 1 ? hi[0] : lo[0], corner & 2 ? hi[1] : lo[1], corner & 4 ? hi[2] : lo[2]});
        const std::array<double, 3> index = grid.indexOfWorld(p);
        for (int a = 0; a < 3; ++a) {
            first[a] = std::min(first[a], int(std::max(std::floor(index[a]), 0.0)));
            last[a] = std::max(last[a], int(std::min(std::ceil(index[a]), grid.size[a] - 1.0)));
        }
    }
    std::vector<std::size_t> inside;
    // A row of voxels on a contour plane is judged by the contours; on a
    // grid aligned with the planes the row's crossings are found once.
    std::optional<ContourRow> row;
    for (int k = first[2]; k <= last[2]; ++k)
        for (int j = first[1]; j <= last[1]; ++j)
            for (int i = first[0]; i <= last[0]; ++i) {
                const Vec3 p = frame.fromPatient(grid.worldOfIndex(i, j, k));
                if (const Slice* plane = planeAt(planes, p.z)) {
                    if (!row || &row->slice() != plane || row->y() != p.y) row.emplace(*plane, p.y);
                    if (row->inside(p.x)) inside.push_back(grid.linearIndex(i, j, k));
                    continue;
                }
                if (p.z < lo[2] || p.z > hi[2] || p.x < lo[0] || p.x > hi[0] || p.y < lo[1] ||
                    p.y > hi[1])
                    continue;
                if (sampleField(field, p.x, p.y, p.z) < 0)
                    inside.push_back(grid.linearIndex(i, j, k));
            }
    return inside;
}

}  // namespace dfrecon
