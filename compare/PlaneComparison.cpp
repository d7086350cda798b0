#include "compare/PlaneComparison.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>
#include <vector>

#include "compare/OverlapRatios.hpp"
#include "contours/PlaneGaps.hpp"
#include "geometry/BoxGrid.hpp"
#include "geometry/PolygonXor.hpp"

namespace dfrecon {

namespace {

// A closed interval of edge parameters; empty when lo > hi.
struct Interval {
    double lo = 1, hi = 0;
    bool empty() const { return lo > hi; }
};

Interval hull(Interval a, Interval b) {
    if (a.empty()) return b;
    if (b.empty()) return a;
    return {std::min(a.lo, b.lo), std::max(a.hi, b.hi)};
}

Interval intersect(Interval a, Interval b) {
    return {std::max(a.lo, b.lo), std::min(a.hi, b.hi)};
}

// {t : α + β t ∈ [lo, hi]}, all t when β = 0 and α is inside.
Interval linearWithin(double alpha, double beta, double lo, double hi) {
    if (beta == 0) return alpha >= lo && alpha <= hi ? Interval{-INFINITY, INFINITY} : Interval{};
    const double t0 = (lo - alpha) / beta, t1 = (hi - alpha) / beta;
    return {std::min(t0, t1), std::max(t0, t1)};
}

// {t : |p + t d − c| ≤ r}, d ≠ 0.
Interval withinDisc(Point2 p, Point2 d, Point2 c, double r) {
    const Point2 f = p - c;
    const double a = dot(d, d), halfB = dot(f, d), cTerm = dot(f, f) - r * r;
    const double discriminant = halfB * halfB - a * cTerm;
    if (discriminant < 0) return {};
    const double root = std::sqrt(discriminant);
    return {(-halfB - root) / a, (-halfB + root) / a};
}

// The parameters t of p + t d within r of segment [a, b]. The set of points
// within r of a segment (a capsule) is convex, so its trace on a line is
// one interval: the hull of the traces of its two end discs and of its
// rectangle.
Interval withinCapsule(Point2 p, Point2 d, Point2 a, Point2 b, double r) {
    Interval result = hull(withinDisc(p, d, a, r), withinDisc(p, d, b, r));
    const Point2 axis = b - a;
    const double length2 = dot(axis, axis);
    if (length2 == 0) return result;
    const Point2 normal{-axis.y, axis.x};
    const double normalLength = std::sqrt(length2);
    const Point2 f = p - a;
    // Along the axis within [0, |ab|²] (unnormalised), across within r.
    const Interval along = linearWithin(dot(f, axis), dot(d, axis), 0, length2);
    const Interval across =
        linearWithin(dot(f, normal), dot(d, normal), -r * normalLength, r * normalLength);
    return hull(result, intersect(along, across));
}

Box3 edgeBox(Point2 a, Point2 b, double grow) {
    Box3 box;
    box.add(Vec3{a.x, a.y, 0});
    box.add(Vec3{b.x, b.y, 0});
    box.lo = box.lo - Vec3{grow, grow, 0};
    box.hi = box.hi + Vec3{grow, grow, 0};
    return box;
}

double pathLength(const std::vector<Polygon>& contours) {
    double length = 0;
    for (const Polygon& contour : contours)
        for (std::size_t i = 0; i < contour.size(); ++i)
            length += dfrecon::length(contour[(i + 1) % contour.size()] - contour[i]);
    return length;
}

bool boxesMeet(const std::vector<Polygon>& a, const std::vector<Polygon>& b) {
    Box3 boxA, boxB;
    for (const Polygon& c : a)
        for (Point2 p : c) boxA.add(Vec3{p.x, p.y, 0});
    for (const Polygon& c : b)
        for (Point2 p : c) boxB.add(Vec3{p.x, p.y, 0});
    return boxA.overlaps(boxB);
}

// The area common to the regions of `a` and `b` (each nested, not
// crossing itself): all contours of both exclusive-or'ed are A ⊕ B, and
// |A ∩ B| = (|A| + |B| − |A ⊕ B|) / 2.
double intersectionArea(const std::vector<Polygon>& a, const std::vector<Polygon>& b) {
    if (a.empty() || b.empty() || !boxesMeet(a, b)) return 0;
    std::vector<Polygon> both = a;
    both.insert(both.end(), b.begin(), b.end());
    const double areaA = netArea(a), areaB = netArea(b);
    const double exclusive = netArea(xorRegions(both, kMaxPlaneCrossings));
    return std::clamp(0.5 * (areaA + areaB - exclusive), 0.0, std::min(areaA, areaB));
}

// The smallest gap between consecutive values (∞ for fewer than two).
double smallestGap(const std::vector<double>& sorted) {
    double gap = INFINITY;
    for (std::size_t i = 1; i < sorted.size(); ++i) gap = std::min(gap, sorted[i] - sorted[i - 1]);
    return gap;
}

std::vector<double> planesOf(const Roi& roi) {
    std::vector<double> z;
    for (const Slice& slice : roi.slices) z.push_back(slice.zMm);
    return z;
}

// One plane of either input, with the contours each has there.
struct MatchedPlane {
    double zMm = 0;
    const std::vector<Polygon>* a = nullptr;
    const std::vector<Polygon>* b = nullptr;
};

// Merges the two sorted plane lists, planes within `matchMm` becoming one.
std::vector<MatchedPlane> matchPlanes(const Roi& a, const Roi& b, double matchMm) {
    std::vector<MatchedPlane> planes;
    std::size_t i = 0, j = 0;
    while (i < a.slices.size() || j < b.slices.size()) {
        const Slice* sa = i < a.slices.size() ? &a.slices[i] : nullptr;
        const Slice* sb = j < b.slices.size() ? &b.slices[j] : nullptr;
        if (sa && sb && std::abs(sa->zMm - sb->zMm) <= matchMm) {
            planes.push_back({sa->zMm, &sa->contours, &sb->contours});
            ++i, ++j;
        } else if (sa && (!sb || sa->zMm < sb->zMm)) {
            planes.push_back({sa->zMm, &sa->contours, nullptr});
            ++i;
        } else {
            planes.push_back({sb->zMm, nullptr, &sb->contours});
            ++j;
        }
    }
    return planes;
}

const std::vector<Polygon>& orNone(const std::vector<Polygon>* contours) {
    static const std::vector<Polygon> none;
    return contours ? *contours : none;
}

}  // namespace

double PlaneComparison::dice() const {
    return diceOf(volumeAMm3, volumeBMm3, intersectionMm3);
}

double PlaneComparison::jaccard() const {
    return jaccardOf(volumeAMm3, volumeBMm3, intersectionMm3);
}

double lengthOutsideTolerance(const std::vector<Polygon>& test,
                              const std::vector<Polygon>& reference, double toleranceMm) {
    if (!(toleranceMm >= 0)) throw std::invalid_argument("tolerance must be >= 0");
    std::vector<std::pair<Point2, Point2>> edges;
    std::vector<Box3> boxes;
    double edgeLengths = 0;
    for (const Polygon& contour : reference)
        for (std::size_t i = 0; i < contour.size(); ++i) {
            const Point2 a = contour[i], b = contour[(i + 1) % contour.size()];
            edges.push_back({a, b});
            boxes.push_back(edgeBox(a, b, toleranceMm));
            edgeLengths += length(b - a);
        }
    if (edges.empty()) return pathLength(test);
    // Cells about an edge long: each query then meets a few cells.
    const double cellMm = std::max({edgeLengths / double(edges.size()), toleranceMm, 1e-3});
    const BoxGrid grid(boxes, cellMm);
    double outside = 0;
    std::vector<Interval> covered;
    for (const Polygon& contour : test)
        for (std::size_t i = 0; i < contour.size(); ++i) {
            const Point2 p = contour[i], q = contour[(i + 1) % contour.size()];
            const double edgeLength = length(q - p);
            if (edgeLength == 0) continue;
            covered.clear();
            grid.overlapping(edgeBox(p, q, 0), [&](std::uint32_t k) {
                const Interval t = intersect(
                    withinCapsule(p, q - p, edges[k].first, edges[k].second, toleranceMm), {0, 1});
                if (!t.empty()) covered.push_back(t);
            });
            std::sort(covered.begin(), covered.end(),
                      [](Interval x, Interval y) { return x.lo < y.lo; });
            double within = 0, reach = 0;
            for (const Interval& t : covered) {
                const double from = std::max(t.lo, reach);
                if (t.hi > from) within += t.hi - from;
                reach = std::max(reach, t.hi);
            }
            outside += edgeLength * std::max(0.0, 1 - within);
        }
    return outside;
}

// Does `roi` go on across the planes between lo and hi: is there a run of
// its planes (Roi::restartsAt) with one at or below lo and one at or above
// hi? A run's planes stand for the space between them; planes left empty
// inside an ROI do not (contours/PlaneGaps). O(runs).
bool runCrosses(const Roi& roi, double lo, double hi, double matchMm) {
    std::size_t begin = 0;
    for (std::size_t k = 0; k <= roi.restartsAt.size(); ++k) {
        const std::size_t end = k < roi.restartsAt.size() ? roi.restartsAt[k] : roi.slices.size();
        if (end > begin && roi.slices[begin].zMm <= lo + matchMm &&
            roi.slices[end - 1].zMm >= hi - matchMm)
            return true;
        begin = end;
    }
    return false;
}

// The thickness each matched plane stands for: planeThicknessesMm over the
// runs of the planes of both, the planes of both running on across a gap
// where either ROI does, ending where neither does (planes left empty in
// both); a plane alone in such a run stands for its ROI's image spacing, as
// contourVolumeMm3 counts it. So each ROI's volume here is its contour
// volume wherever the two share their runs. O(planes · runs).
std::vector<double> matchedThicknessesMm(const std::vector<MatchedPlane>& planes, const Roi& a,
                                         const Roi& b, double slabMm, double matchMm) {
    std::vector<double> thickness(planes.size(), 0);
    std::size_t begin = 0;
    for (std::size_t i = 1; i <= planes.size(); ++i) {
        const bool runEnds =
            i == planes.size() || !(runCrosses(a, planes[i - 1].zMm, planes[i].zMm, matchMm) ||
                                    runCrosses(b, planes[i - 1].zMm, planes[i].zMm, matchMm));
        if (!runEnds) continue;
        std::vector<double> zMm;
        for (std::size_t k = begin; k < i; ++k) zMm.push_back(planes[k].zMm);
        std::vector<double> run = planeThicknessesMm(zMm, slabMm);
        if (run.size() == 1)
            run[0] = std::max(planes[begin].a ? lonePlaneThicknessMm(a) : 0.0,
                              planes[begin].b ? lonePlaneThicknessMm(b) : 0.0);
        std::copy(run.begin(), run.end(), thickness.begin() + std::ptrdiff_t(begin));
        begin = i;
    }
    return thickness;
}

PlaneComparison comparePlanes(const Roi& a, const Roi& bIn, const PlaneComparisonOptions& options) {
    PlaneComparison result;
    result.toleranceMm = options.toleranceMm;
    Roi b = bIn;
    try {
        changeFrame(b, a.frame);
    } catch (const std::invalid_argument&) {
        result.whyNot = "their planes are not parallel";
        return result;
    }
    const std::vector<MatchedPlane> planes = matchPlanes(a, b, options.planeMatchMm);
    std::vector<double> planeZMm;
    for (const MatchedPlane& plane : planes) planeZMm.push_back(plane.zMm);
    // Interleaved or differently spaced planes bring planes of both closer
    // than either's own: then a plane of one has no counterpart in the other
    // to compare with. A plane one of them lacks (a structure that ends
    // sooner, or skips a plane) keeps the gaps and is compared with none.
    const double ownGap = std::max(a.slices.size() > 1 ? smallestGap(planesOf(a)) : 0.0,
                                   b.slices.size() > 1 ? smallestGap(planesOf(b)) : 0.0);
    if (planes.size() > 1 && ownGap == 0) {
        result.whyNot = "each has one plane, and they differ";
        return result;
    }
    if (planes.size() > 1 && !(smallestGap(planeZMm) >= ownGap - options.planeMatchMm)) {
        result.whyNot =
            "the planes of one lie between those of the other (different positions or spacing)";
        return result;
    }
    const double slab = a.slabThicknessMm == b.slabThicknessMm ? a.slabThicknessMm : 0;
    const std::vector<double> thickness =
        matchedThicknessesMm(planes, a, b, slab, options.planeMatchMm);
    result.samePlanes = true;
    result.planes = planes.size();
    for (std::size_t i = 0; i < planes.size(); ++i) {
        const std::vector<Polygon>& contoursA = orNone(planes[i].a);
        const std::vector<Polygon>& contoursB = orNone(planes[i].b);
        result.volumeAMm3 += netArea(contoursA) * thickness[i];
        result.volumeBMm3 += netArea(contoursB) * thickness[i];
        result.intersectionMm3 += intersectionArea(contoursA, contoursB) * thickness[i];
        result.pathLengthAMm += pathLength(contoursA);
        result.pathLengthBMm += pathLength(contoursB);
        result.addedPathLengthMm +=
            lengthOutsideTolerance(contoursB, contoursA, options.toleranceMm);
        result.addedPathLengthAMm +=
            lengthOutsideTolerance(contoursA, contoursB, options.toleranceMm);
    }
    return result;
}

}  // namespace dfrecon
