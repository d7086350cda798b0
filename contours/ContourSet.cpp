#include "contours/ContourSet.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "contours/PlaneGaps.hpp"

namespace dfrecon {

std::size_t Roi::contourCount() const {
    std::size_t n = 0;
    for (const Slice& s : slices) n += s.contours.size();
    return n;
}

std::size_t Roi::pointCount() const {
    std::size_t n = 0;
    for (const Slice& s : slices)
        for (const Polygon& c : s.contours) n += c.size();
    return n;
}

const Roi* ContourSet::findRoi(const std::string& name) const {
    for (const Roi& roi : rois)
        if (roi.name == name) return &roi;
    return nullptr;
}

const Roi* ContourSet::findRoiNumber(int number) const {
    for (const Roi& roi : rois)
        if (roi.number == number) return &roi;
    return nullptr;
}

// A point of `inner` that is not on `outer`'s boundary, so the winding test is
// decisive even when the two contours touch. Vertices first, then edge
// midpoints; touching contours share at most isolated points, so one exists.
static bool isInside(const Polygon& inner, const Polygon& outer, const Box2& outerBox) {
    auto decide = [&](Point2 p, bool& decided) {
        decided = false;
        if (!outerBox.contains(p)) {
            decided = true;
            return false;
        }
        if (distanceToBoundary(p, outer) <= 1e-9 * (1 + length(p))) return false;
        decided = true;
        return windingNumber(p, outer) != 0;
    };
    for (std::size_t i = 0; i < inner.size(); ++i) {
        bool decided = false;
        bool inside = decide(inner[i], decided);
        if (decided) return inside;
        const Point2 mid = 0.5 * (inner[i] + inner[(i + 1) % inner.size()]);
        inside = decide(mid, decided);
        if (decided) return inside;
    }
    return false;  // identical boundaries; validation rejects this as an overlap
}

std::vector<int> nestingDepths(const Slice& slice) {
    const std::size_t n = slice.contours.size();
    std::vector<Box2> boxes(n);
    for (std::size_t i = 0; i < n; ++i) boxes[i] = boundingBox(slice.contours[i]);
    std::vector<int> depth(n, 0);
    for (std::size_t i = 0; i < n; ++i)
        for (std::size_t j = 0; j < n; ++j) {
            if (i == j) continue;
            const Box2 &bi = boxes[i], &bj = boxes[j];
            const bool boxInside = bi.min.x >= bj.min.x && bi.max.x <= bj.max.x &&
                                   bi.min.y >= bj.min.y && bi.max.y <= bj.max.y;
            if (boxInside && isInside(slice.contours[i], slice.contours[j], bj)) ++depth[i];
        }
    return depth;
}

std::size_t normaliseOrientation(Slice& slice) {
    const std::vector<int> depth = nestingDepths(slice);
    std::size_t reversed = 0;
    for (std::size_t i = 0; i < slice.contours.size(); ++i) {
        const bool wantCcw = depth[i] % 2 == 0;
        const bool isCcw = signedArea(slice.contours[i]) > 0;
        if (wantCcw != isCcw) {
            std::reverse(slice.contours[i].begin(), slice.contours[i].end());
            ++reversed;
        }
    }
    return reversed;
}

namespace {

// The box of every contour point mapped by `place` (plane x, y, z → Vec3).
template <class Place>
Extent3 boxOfPoints(const Roi& roi, Place place) {
    Extent3 e;
    for (const Slice& s : roi.slices)
        for (const Polygon& c : s.contours)
            for (Point2 p : c) {
                const Vec3 v = place(Vec3{p.x, p.y, s.zMm});
                for (int k = 0; k < 3; ++k) {
                    e.min[k] = e.empty ? v[k] : std::min(e.min[k], v[k]);
                    e.max[k] = e.empty ? v[k] : std::max(e.max[k], v[k]);
                }
                e.empty = false;
            }
    return e;
}

}  // namespace

Extent3 extentOf(const Roi& roi) {
    return boxOfPoints(roi, [](Vec3 p) { return p; });
}

Extent3 patientExtentOf(const Roi& roi) {
    return boxOfPoints(roi, [&](Vec3 p) { return roi.frame.toPatient(p); });
}

void changeFrame(Roi& roi, const PlaneFrame& target) {
    const PlaneFrame source = roi.frame;
    if (source.u == target.u && source.v == target.v && source.n == target.n) return;
    const double normals = dot(source.n, target.n);
    if (!(std::abs(std::abs(normals) - 1) < 1e-9))
        throw std::invalid_argument("changeFrame: the frames' planes are not parallel");
    // (u, v, n) and (u', v', n') are both right-handed, so with n' = -n the
    // in-plane map has determinant -1 and every contour turns round.
    const bool mirrored = normals < 0;
    for (Slice& slice : roi.slices) {
        for (Polygon& contour : slice.contours) {
            for (Point2& p : contour) {
                const Vec3 q = target.fromPatient(source.toPatient({p.x, p.y, slice.zMm}));
                p = {q.x, q.y};
            }
            if (mirrored) std::reverse(contour.begin(), contour.end());
        }
        // Not through the rotation: the plane position stays the file's value.
        if (mirrored) slice.zMm = -slice.zMm;
    }
    if (mirrored) {
        std::reverse(roi.slices.begin(), roi.slices.end());
        // A run that restarted at plane r (between r - 1 and r) restarts,
        // counted from the other end, at n - r.
        for (std::size_t& r : roi.restartsAt) r = roi.slices.size() - r;
        std::reverse(roi.restartsAt.begin(), roi.restartsAt.end());
    }
    roi.frame = target;
}

SpacingStats spacingOf(const Roi& roi) {
    SpacingStats s;
    if (roi.slices.size() < 2) return s;
    s.minMm = INFINITY;
    for (std::size_t i = 1; i < roi.slices.size(); ++i) {
        const double gap = roi.slices[i].zMm - roi.slices[i - 1].zMm;
        s.minMm = std::min(s.minMm, gap);
        s.maxMm = std::max(s.maxMm, gap);
    }
    s.meanMm = (roi.slices.back().zMm - roi.slices.front().zMm) / double(roi.slices.size() - 1);
    s.uniform = s.maxMm - s.minMm <= kUniformSpacingToleranceMm;
    return s;
}

std::vector<double> planeThicknessesMm(const std::vector<double>& planeZMm,
                                       double slabThicknessMm) {
    const std::size_t n = planeZMm.size();
    std::vector<double> thickness(n, std::max(0.0, slabThicknessMm));
    if (slabThicknessMm > 0 || n < 2) return thickness;
    for (std::size_t i = 0; i < n; ++i) {
        const double below = i > 0 ? planeZMm[i] - planeZMm[i - 1] : -1;
        const double above = i + 1 < n ? planeZMm[i + 1] - planeZMm[i] : -1;
        thickness[i] =
            std::max(0.0, below < 0 ? above : (above < 0 ? below : 0.5 * (below + above)));
    }
    return thickness;
}

double contourVolumeMm3(const Roi& roi) {
    double volume = 0;
    std::size_t begin = 0;
    for (std::size_t k = 0; k <= roi.restartsAt.size(); ++k) {
        const std::size_t end = k < roi.restartsAt.size() ? roi.restartsAt[k] : roi.slices.size();
        std::vector<double> planeZMm;
        for (std::size_t i = begin; i < end; ++i) planeZMm.push_back(roi.slices[i].zMm);
        std::vector<double> thickness = planeThicknessesMm(planeZMm, roi.slabThicknessMm);
        if (end - begin == 1) thickness[0] = lonePlaneThicknessMm(roi);
        for (std::size_t i = begin; i < end; ++i) {
            volume += netArea(roi.slices[i].contours) * thickness[i - begin];
        }
        begin = end;
    }
    return volume;
}

}  // namespace dfrecon
