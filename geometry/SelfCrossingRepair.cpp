#include "geometry/SelfCrossingRepair.hpp"

#include <algorithm>

#include "geometry/ContourValidation.hpp"
#include "geometry/KeyholeSplit.hpp"
#include "geometry/PolygonXor.hpp"

namespace dfrecon {

namespace {

// Where segment (a, b) meets segment (c, d), which cross at interior points
// (the caller knows): a + t (b - a) with t from the two cross products.
Point2 crossingPoint(Point2 a, Point2 b, Point2 c, Point2 d) {
    const double t = cross(c - a, d - c) / cross(b - a, d - c);
    return a + t * (b - a);
}

// Consecutive equal points (a crossing rounded onto a vertex) would be
// zero-length segments, which validation reports as touches.
Polygon withoutRepeats(Polygon loop) {
    loop.erase(std::unique(loop.begin(), loop.end()), loop.end());
    while (loop.size() > 1 && loop.back() == loop.front()) loop.pop_back();
    return loop;
}

}  // namespace

std::optional<std::vector<Polygon>> splitAtSelfCrossings(const Polygon& contour,
                                                         std::size_t maxCuts) {
    std::vector<Polygon> pending{contour}, loops;
    std::size_t cuts = 0;
    while (!pending.empty()) {
        Polygon loop = withoutRepeats(std::move(pending.back()));
        pending.pop_back();
        if (loop.size() < 3 || allCollinear(loop)) continue;  // no area: adds nothing
        const std::optional<ContourDefect> defect = findContourDefect({loop});
        if (!defect) {
            loops.push_back(std::move(loop));
            continue;
        }
        if (defect->kind != ContourDefect::Kind::SelfIntersection ||
            defect->contact != SegmentContact::Cross || ++cuts > maxCuts)
            return std::nullopt;
        const std::size_t n = loop.size();
        const std::size_t i = std::min(defect->segmentA, defect->segmentB);
        const std::size_t j = std::max(defect->segmentA, defect->segmentB);
        const Point2 x = crossingPoint(loop[i], loop[i + 1], loop[j], loop[(j + 1) % n]);
        // The closed path p0 … pi x p(j+1) … and the closed path x p(i+1) … pj.
        Polygon outer(loop.begin(), loop.begin() + std::ptrdiff_t(i + 1));
        outer.push_back(x);
        outer.insert(outer.end(), loop.begin() + std::ptrdiff_t(j + 1), loop.end());
        Polygon inner{x};
        inner.insert(inner.end(), loop.begin() + std::ptrdiff_t(i + 1),
                     loop.begin() + std::ptrdiff_t(j + 1));
        pending.push_back(std::move(outer));
        pending.push_back(std::move(inner));
    }
    return loops;
}

std::optional<std::vector<Polygon>> evenOddRegion(const Polygon& contour, std::size_t maxCuts,
                                                  std::size_t maxWork) {
    std::optional<std::vector<Polygon>> loops = splitAtSelfCrossings(contour, maxCuts);
    if (!loops || loops->empty()) return std::nullopt;
    if (loops->size() == 1) {
        if (signedArea(loops->front()) < 0)
            std::reverse(loops->front().begin(), loops->front().end());
        return loops;
    }
    // CGAL gives regions that meet at a point (a figure eight's lobes) as one
    // boundary through that point twice; cut there, each part keeps the
    // direction it ran in, so outer parts stay counter-clockwise.
    std::vector<Polygon> combined;
    try {
        combined = xorRegions(*loops, maxWork);
    } catch (const TooManyCrossings&) {
        return std::nullopt;
    }
    std::vector<Polygon> region;
    for (const Polygon& boundary : combined)
        for (Polygon& part : splitKeyholes(boundary, 0.0).loops) region.push_back(std::move(part));
    // A path that runs round twice has no odd points: nothing is left to
    // stand for what was drawn, so it is not a repair.
    if (region.empty()) return std::nullopt;
    return region;
}

}  // namespace dfrecon
