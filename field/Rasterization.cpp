#include "field/Rasterization.hpp"

#include <algorithm>
#include <array>
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
    double lowestCap = INFINITY;
    for (const Roi* roi : rois) {
        // sharedFrame gives the ROI's own frame or, where frames differ, LPS.
        const bool ownFrame = roi->frame.u == frame.u && roi->frame.v == frame.v;
        const Extent3 extent = ownFrame ? extentOf(*roi) : patientExtentOf(*roi);
        const SpacingStats spacing = spacingOf(*roi);
        const double reach = 0.5 * (spacing.maxMm > 0 ? spacing.maxMm : 1.0);
        // The caps reach half a spacing out along the ROI's own normal.
        const bool alongZ = std::abs(dot(roi->frame.n, frame.n)) > 0.5;
        // Contours drawn on a lattice (along image rows, from label maps) put
        // their extremes on lines of the lattice; half a voxel more keeps
        // those lines between centres rather than through them.
        for (int a = 0; a < 3; ++a) {
            const double margin = 1.5 * voxelMm + (alongZ ? (a == 2 ? reach : 0) : reach);
            lo[a] = std::min(lo[a], extent.min[a] - margin);
            hi[a] = std::max(hi[a], extent.max[a] + margin);
        }
        if (alongZ && ownFrame) lowestCap = std::min(lowestCap, extent.min[2] - reach);
    }
    // A flat cap is a large face across the layers: a layer of centres on it
    // would count its whole area or none of it (half a voxel's depth of the
    // cap's area too much or too little). So the layers are placed to have
    // the lowest cap between two of them; on planes evenly spaced every end
    // cap is then as far from the layers, and for an odd number of voxels
    // per half spacing (3 mm planes, 1 mm voxels) the layers fall on the
    // contour planes, where the contours decide exactly.
    if (std::isfinite(lowestCap)) lo[2] = lowestCap - 1.5 * voxelMm;
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

// Centres on a contour plane, judged by the plane's contours. Centres come
// row by row, so on a grid aligned with the planes one ContourRow serves a
// whole row of voxels.
class ContourPlanes {
  public:
    explicit ContourPlanes(const std::vector<Slice>& planes) : planes_(planes) {}

    /// For a centre at `p` (plane frame): inside or outside its plane's
    /// contours, or nothing when it lies on no plane (beyond kOnPlaneMm).
    std::optional<bool> inside(const Vec3& p) {
        const Slice* plane = planeAt(p.z);
        if (!plane) return std::nullopt;
        if (!row_ || &row_->slice() != plane || row_->y() != p.y) row_.emplace(*plane, p.y);
        return row_->inside(p.x);
    }

    /// Does a plane lie within kOnPlaneMm of [zLo, zHi]? A row of centres
    /// whose ends are zLo and zHi (plane frame) meets no plane otherwise.
    /// O(log planes).
    bool anyNear(double zLo, double zHi) const {
        auto it = std::lower_bound(planes_.begin(), planes_.end(), zLo - kOnPlaneMm,
                                   [](const Slice& s, double v) { return s.zMm < v; });
        return it != planes_.end() && it->zMm <= zHi + kOnPlaneMm;
    }

  private:
    // The plane of planes_ (sorted by z) within kOnPlaneMm of z, or nullptr.
    const Slice* planeAt(double z) const {
        auto it = std::lower_bound(planes_.begin(), planes_.end(), z - kOnPlaneMm,
                                   [](const Slice& s, double v) { return s.zMm < v; });
        return it != planes_.end() && it->zMm <= z + kOnPlaneMm ? &*it : nullptr;
    }

    const std::vector<Slice>& planes_;
    std::optional<ContourRow> row_;
};

// Does a row through a point of edge a→b of a counter-clockwise triangle
// count as covered by it? As if the row were moved by (ε, ε²) (symbolic
// perturbation): then it lies off every line, left of this edge exactly
// when the edge runs down, or runs along the first axis forwards. Two
// triangles on either side of a shared edge run it in opposite directions,
// so exactly one of them takes the row.
bool takesRowOnEdge(Point2 a, Point2 b) {
    return b.y < a.y || (b.y == a.y && b.x > a.x);
}

// Is the row at p (j, k) covered by the counter-clockwise triangle abc in
// that perturbed sense? Exact.
bool rowCovered(Point2 p, const Point2 (&corner)[3]) {
    for (int e = 0; e < 3; ++e) {
        const Point2 a = corner[e], b = corner[(e + 1) % 3];
        const int side = exactOrientation(a, b, p);
        if (side < 0 || (side == 0 && !takesRowOnEdge(a, b))) return false;
    }
    return true;
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
    ContourPlanes onPlanes(planes);
    for (int k = first[2]; k <= last[2]; ++k)
        for (int j = first[1]; j <= last[1]; ++j)
            for (int i = first[0]; i <= last[0]; ++i) {
                const Vec3 p = frame.fromPatient(grid.worldOfIndex(i, j, k));
                if (const std::optional<bool> on = onPlanes.inside(p)) {
                    if (*on) inside.push_back(grid.linearIndex(i, j, k));
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

std::vector<std::size_t> voxelsInsideSolid(const TriangleSoup& solid, const PlaneFrame& frame,
                                           const VolumeGeometry& grid,
                                           const std::vector<Slice>& planes) {
    if (solid.triangles.empty()) return {};
    // In index coordinates the rows of centres are the lines of integer
    // (j, k) along the first axis. Each point is mapped once, so triangles
    // sharing an edge see the same rounded ends.
    std::vector<std::array<double, 3>> q(solid.points.size());
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (std::size_t v = 0; v < q.size(); ++v) {
        q[v] = grid.indexOfWorld(solid.points[v]);
        for (int a = 0; a < 3; ++a) {
            lo[a] = std::min(lo[a], q[v][a]);
            hi[a] = std::max(hi[a], q[v][a]);
        }
    }
    // The contours lie on the surface, so its box holds every centre inside.
    int first[3], last[3];
    for (int a = 0; a < 3; ++a) {
        first[a] = int(std::max(std::ceil(lo[a]), 0.0));
        last[a] = int(std::min(std::floor(hi[a]), grid.size[a] - 1.0));
        if (first[a] > last[a]) return {};
    }
    const std::size_t rowsAlongJ = std::size_t(last[1] - first[1] + 1);
    auto rowOf = [&](int j, int k) {
        return std::size_t(k - first[2]) * rowsAlongJ + std::size_t(j - first[1]);
    };

    struct Crossing {
        std::size_t row;
        double i;
    };
    std::vector<Crossing> crossings;
    for (const auto& t : solid.triangles) {
        const std::array<double, 3>* c[3] = {&q[t[0]], &q[t[1]], &q[t[2]]};
        Point2 shadow[3] = {
            {(*c[0])[1], (*c[0])[2]}, {(*c[1])[1], (*c[1])[2]}, {(*c[2])[1], (*c[2])[2]}};
        const int turn = exactOrientation(shadow[0], shadow[1], shadow[2]);
        if (turn == 0) continue;  // parallel to the rows: its neighbours count
        if (turn < 0) {
            std::swap(shadow[1], shadow[2]);
            std::swap(c[1], c[2]);
        }
        const std::array<double, 3>& a = *c[0];
        const Vec3 n = cross(Vec3{(*c[1])[0] - a[0], (*c[1])[1] - a[1], (*c[1])[2] - a[2]},
                             Vec3{(*c[2])[0] - a[0], (*c[2])[1] - a[1], (*c[2])[2] - a[2]});
        const double iLo = std::min({a[0], (*c[1])[0], (*c[2])[0]});
        const double iHi = std::max({a[0], (*c[1])[0], (*c[2])[0]});
        const int jFrom =
            std::max(first[1], int(std::ceil(std::min({shadow[0].x, shadow[1].x, shadow[2].x}))));
        const int jTo =
            std::min(last[1], int(std::floor(std::max({shadow[0].x, shadow[1].x, shadow[2].x}))));
        const int kFrom =
            std::max(first[2], int(std::ceil(std::min({shadow[0].y, shadow[1].y, shadow[2].y}))));
        const int kTo =
            std::min(last[2], int(std::floor(std::max({shadow[0].y, shadow[1].y, shadow[2].y}))));
        for (int k = kFrom; k <= kTo; ++k)
            for (int j = jFrom; j <= jTo; ++j) {
                if (!rowCovered({double(j), double(k)}, shadow)) continue;
                // The triangle's plane at (j, k); kept within its span where
                // it is nearly parallel to the row.
                const double i = a[0] - (n.y * (j - a[1]) + n.z * (k - a[2])) / n.x;
                crossings.push_back({rowOf(j, k), std::clamp(i, iLo, iHi)});
            }
    }
    std::sort(crossings.begin(), crossings.end(), [](const Crossing& l, const Crossing& r) {
        return l.row != r.row ? l.row < r.row : l.i < r.i;
    });

    std::vector<std::size_t> inside;
    ContourPlanes onPlanes(planes);
    auto next = crossings.begin();
    for (int k = first[2]; k <= last[2]; ++k)
        for (int j = first[1]; j <= last[1]; ++j) {
            const std::size_t row = rowOf(j, k);
            auto passed = next;  // crossings of this row at or before the centre
            auto end = std::find_if(next, crossings.end(),
                                    [row](const Crossing& c) { return c.row != row; });
            // Only a row that comes near a plane asks each centre for it.
            const double zFirst = frame.fromPatient(grid.worldOfIndex(first[0], j, k)).z;
            const double zLast = frame.fromPatient(grid.worldOfIndex(last[0], j, k)).z;
            const bool nearPlane = !planes.empty() && onPlanes.anyNear(std::min(zFirst, zLast),
                                                                       std::max(zFirst, zLast));
            for (int i = first[0]; i <= last[0]; ++i) {
                const std::size_t voxel = grid.linearIndex(i, j, k);
                if (nearPlane)
                    if (const std::optional<bool> on =
                            onPlanes.inside(frame.fromPatient(grid.worldOfIndex(i, j, k)))) {
                        if (*on) inside.push_back(voxel);
                        continue;
                    }
                while (passed != end && passed->i <= i) ++passed;
                if ((end - passed) % 2 == 1) inside.push_back(voxel);
            }
            next = end;
        }
    return inside;
}

}  // namespace dfrecon
