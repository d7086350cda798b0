#include "recon/StepSlabs.hpp"

#include <vector>

#include "geometry/Polygon.hpp"

namespace dfrecon {
namespace {

// Does `b` hold the points of `a` in the same cyclic order, from b's point
// nearest a's first? Repeated contours keep their points (a copy, or the same
// pixels traced the same way), so no point-to-edge search is needed.
bool samePoints(const Polygon& a, const Polygon& b, double toleranceMm) {
    if (a.size() != b.size() || a.empty()) return false;
    std::size_t start = 0;
    double nearest = length(b[0] - a[0]);
    for (std::size_t i = 1; i < b.size(); ++i) {
        const double d = length(b[i] - a[0]);
        if (d < nearest) nearest = d, start = i;
    }
    if (nearest > toleranceMm) return false;
    for (std::size_t i = 0; i < a.size(); ++i)
        if (length(b[(start + i) % b.size()] - a[i]) > toleranceMm) return false;
    return true;
}

}  // namespace

bool sameContours(const Layer& a, const Layer& b, double toleranceMm) {
    if (a.contours.size() != b.contours.size()) return false;
    // Candidates must agree in point count and bounds first (O(1) each), so
    // a plane of many small contours costs one cheap test per pair, as the
    // plane reading's own pairing does, and a point walk only per match.
    std::vector<Box2> boxesOfB;
    for (const Polygon& contour : b.contours) boxesOfB.push_back(boundingBox(contour));
    auto near = [&](Point2 p, Point2 q) { return length(p - q) <= toleranceMm; };
    std::vector<bool> used(b.contours.size(), false);
    for (const Polygon& contour : a.contours) {
        const Box2 box = boundingBox(contour);
        bool found = false;
        for (std::size_t j = 0; j < b.contours.size() && !found; ++j)
            if (!used[j] && b.contours[j].size() == contour.size() &&
                near(box.min, boxesOfB[j].min) && near(box.max, boxesOfB[j].max) &&
                samePoints(contour, b.contours[j], toleranceMm))
                used[j] = found = true;
        if (!found) return false;
    }
    return true;
}

bool isStepSlab(const std::deque<Layer>& layers, std::size_t s) {
    // Far below any contouring accuracy, yet above the rounding of a copied
    // contour written as DICOM decimal strings.
    constexpr double kRepeatToleranceMm = 1e-3;
    if (s == 0 || s + 2 >= layers.size()) return false;
    return sameContours(layers[s - 1], layers[s], kRepeatToleranceMm) &&
           sameContours(layers[s + 1], layers[s + 2], kRepeatToleranceMm) &&
           !sameContours(layers[s], layers[s + 1], kRepeatToleranceMm);
}

}  // namespace dfrecon
