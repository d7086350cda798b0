#include "contours/PlaneGaps.hpp"

#include <algorithm>
#include <cmath>

namespace dfrecon {

namespace {

// Planes closer than this are one (io's kSamePlaneToleranceMm: contours of
// one plane as planning systems write them).
constexpr double kSamePlaneMm = 0.01;
// A gap this many times the reference spacing leaves at least one plane out.
constexpr double kGapFactor = 1.5;

// Whether two frames stack their planes along one line: the same normal, or
// the opposite one (positions then negated).
int stackSense(const PlaneFrame& a, const PlaneFrame& b) {
    const double d = dot(a.n, b.n);
    if (std::fabs(d - 1) < 1e-9) return 1;
    if (std::fabs(d + 1) < 1e-9) return -1;
    return 0;
}

double median(std::vector<double> values) {
    if (values.empty()) return 0;
    const auto middle = values.begin() + std::ptrdiff_t(values.size() / 2);
    std::nth_element(values.begin(), middle, values.end());
    return *middle;
}

}  // namespace

void findPlaneGaps(ContourSet& set) {
    std::vector<bool> done(set.rois.size(), false);
    for (std::size_t first = 0; first < set.rois.size(); ++first) {
        if (done[first] || set.rois[first].slices.empty()) continue;
        // The ROIs on this stack, and every plane any of them is drawn on
        // (in the first one's positions).
        std::vector<std::size_t> members;
        std::vector<double> planes;
        for (std::size_t r = first; r < set.rois.size(); ++r) {
            const Roi& roi = set.rois[r];
            const int sense = stackSense(set.rois[first].frame, roi.frame);
            if (done[r] || roi.slices.empty() || sense == 0) continue;
            done[r] = true;
            members.push_back(r);
            for (const Slice& s : roi.slices) planes.push_back(sense * s.zMm);
        }
        std::sort(planes.begin(), planes.end());
        std::vector<double> image;
        for (double z : planes)
            if (image.empty() || z - image.back() > kSamePlaneMm) image.push_back(z);
        std::vector<double> imageGaps;
        for (std::size_t i = 1; i < image.size(); ++i) imageGaps.push_back(image[i] - image[i - 1]);
        const double imageSpacing = median(imageGaps);
        for (std::size_t r : members) {
            Roi& roi = set.rois[r];
            const int sense = stackSense(set.rois[first].frame, roi.frame);
            roi.imagePlaneSpacingMm = imageSpacing;
            roi.restartsAt.clear();
            const std::size_t n = roi.slices.size();
            if (n < 2) continue;
            double ownSmallest = INFINITY;
            for (std::size_t i = 1; i < n; ++i)
                ownSmallest = std::min(ownSmallest, roi.slices[i].zMm - roi.slices[i - 1].zMm);
            const double reference = n >= 3 ? ownSmallest : imageSpacing;
            for (std::size_t i = 1; i < n; ++i) {
                const double below = roi.slices[i - 1].zMm, above = roi.slices[i].zMm;
                if (reference <= 0 || above - below <= kGapFactor * reference) continue;
                // An image plane strictly between the two (in the stack's
                // first frame's positions).
                const double lo = std::min(sense * below, sense * above) + kSamePlaneMm;
                const double hi = std::max(sense * below, sense * above) - kSamePlaneMm;
                const auto at = std::upper_bound(image.begin(), image.end(), lo);
                if (at != image.end() && *at < hi) roi.restartsAt.push_back(i);
            }
        }
    }
}

std::vector<Roi> planeRuns(const Roi& roi) {
    if (roi.restartsAt.empty()) return {roi};
    std::vector<Roi> runs;
    std::size_t begin = 0;
    for (std::size_t k = 0; k <= roi.restartsAt.size(); ++k) {
        const std::size_t end = k < roi.restartsAt.size() ? roi.restartsAt[k] : roi.slices.size();
        Roi run = roi;
        run.restartsAt.clear();
        run.slices.assign(roi.slices.begin() + std::ptrdiff_t(begin),
                          roi.slices.begin() + std::ptrdiff_t(end));
        runs.push_back(std::move(run));
        begin = end;
    }
    return runs;
}

double lonePlaneThicknessMm(const Roi& roi) {
    if (roi.slabThicknessMm > 0) return roi.slabThicknessMm;
    return std::max(0.0, roi.imagePlaneSpacingMm);
}

}  // namespace dfrecon
