#include "recon/SlidingSections.hpp"

#include <algorithm>
#include <cmath>

#include "geometry/Polygon.hpp"
#include "recon/PrismClosing.hpp"

namespace dfrecon {

namespace {

constexpr int kOverlapSamples = 40;  // a side of the overlap's sample grid
constexpr int kFitSamples = 64;      // points compared per turn tried
constexpr int kTurns = 256;          // starts of the upper contour tried

/// Each vertex's share of the contour's length from vertex 0, in [0, 1).
std::vector<double> lengthShares(const Polygon& polygon) {
    std::vector<double> shares(polygon.size(), 0);
    double run = 0;
    for (std::size_t i = 1; i < polygon.size(); ++i) {
        run += length(polygon[i] - polygon[i - 1]);
        shares[i] = run;
    }
    const double total = run + length(polygon.front() - polygon.back());
    for (double& s : shares) s /= total;
    return shares;
}

/// The point at share u (any real: taken modulo 1) of the contour's length.
Point2 pointAtShare(const Polygon& polygon, const std::vector<double>& shares, double u) {
    u -= std::floor(u);
    const std::size_t n = polygon.size();
    const auto after = std::upper_bound(shares.begin(), shares.end(), u);
    const std::size_t i = std::size_t(after - shares.begin()) - 1;  // shares[0] = 0 <= u
    const double from = shares[i], to = i + 1 < n ? shares[i + 1] : 1.0;
    const double t = to > from ? (u - from) / (to - from) : 0;
    return polygon[i] + t * (polygon[(i + 1) % n] - polygon[i]);
}

/// How much the regions of `a` and of `b` moved by `shift` share, sampled
/// at the centres of a grid over both boxes.
struct Overlap {
    double ofUnion = 0;    // intersection over union
    double ofSmaller = 0;  // intersection over the smaller region
};

Overlap alignedOverlap(const Polygon& a, const Polygon& b, Point2 shift) {
    Box2 box = boundingBox(a);
    for (const Point2& p : b) box.add(p + shift);
    const double dx = (box.max.x - box.min.x) / kOverlapSamples,
                 dy = (box.max.y - box.min.y) / kOverlapSamples;
    std::size_t both = 0, either = 0, onlyA = 0, onlyB = 0;
    for (int j = 0; j < kOverlapSamples; ++j)
        for (int i = 0; i < kOverlapSamples; ++i) {
            const Point2 p{box.min.x + (i + 0.5) * dx, box.min.y + (j + 0.5) * dy};
            const bool inA = windingNumber(p, a) != 0, inB = windingNumber(p - shift, b) != 0;
            both += inA && inB;
            either += inA || inB;
            onlyA += inA && !inB;
            onlyB += inB && !inA;
        }
    if (either == 0) return {};
    const std::size_t smaller = both + std::min(onlyA, onlyB);
    return {double(both) / double(either), smaller == 0 ? 0 : double(both) / double(smaller)};
}

/// How far `polygon` reaches along the unit vector `along`.
double extentAlong(const Polygon& polygon, Point2 along) {
    double lo = INFINITY, hi = -INFINITY;
    for (const Point2& p : polygon) {
        lo = std::min(lo, dot(p, along));
        hi = std::max(hi, dot(p, along));
    }
    return hi - lo;
}

/// Outer contours of `part` with no hole of `part` inside (an ending ring
/// is left to its caps).
std::vector<bool> plainOuter(const LayerPart& part) {
    const std::vector<Polygon>& contours = part.layer->contours;
    std::vector<bool> plain(part.contours.size(), false);
    for (std::size_t i = 0; i < part.contours.size(); ++i) {
        const Polygon& c = contours[part.contours[i]];
        plain[i] = c.size() >= 3 && signedArea(c) > 0;
    }
    for (std::uint32_t h : part.contours) {
        const Polygon& hole = contours[h];
        if (hole.empty() || signedArea(hole) >= 0) continue;
        for (std::size_t i = 0; i < part.contours.size(); ++i)
            if (plain[i] && windingNumber(hole[0], contours[part.contours[i]]) != 0)
                plain[i] = false;
    }
    return plain;
}

}  // namespace

std::vector<SlidPair> matchSlidingSections(const LayerPart& lowerEnding,
                                           const LayerPart& upperEnding, double slabHeightMm,
                                           const SlidingSectionOptions& options) {
    std::vector<SlidPair> pairs;
    if (lowerEnding.contours.empty() || upperEnding.contours.empty() || !(slabHeightMm > 0))
        return pairs;
    const std::vector<bool> lowerPlain = plainOuter(lowerEnding),
                            upperPlain = plainOuter(upperEnding);
    const std::size_t n = lowerEnding.contours.size(), m = upperEnding.contours.size();
    // overlap[i * m + k]: how well lower i and upper k fit, 0 where they may
    // not be joined.
    std::vector<double> overlap(n * m, 0.0);
    for (std::size_t i = 0; i < n; ++i) {
        if (!lowerPlain[i]) continue;
        const Polygon& a = lowerEnding.layer->contours[lowerEnding.contours[i]];
        const double areaA = signedArea(a);
        const Point2 ca = regionCentroid(a);
        for (std::size_t k = 0; k < m; ++k) {
            if (!upperPlain[k]) continue;
            const Polygon& b = upperEnding.layer->contours[upperEnding.contours[k]];
            const double ratio = signedArea(b) / areaA;
            const bool alike = ratio >= 0.5 && ratio <= 2;
            const bool tapering =
                !alike && ratio >= 1 / options.maxTaperRatio && ratio <= options.maxTaperRatio;
            const Point2 shift = ca - regionCentroid(b);
            const double slide = length(shift);
            if (!(alike || tapering) || slide > options.maxSlideSlabs * slabHeightMm) continue;
            if (slide > 0) {
                const Point2 along = (1 / slide) * shift;
                if (slide > options.maxSlideExtents *
                                std::max(extentAlong(a, along), extentAlong(b, along)))
                    continue;
            }
            const Overlap fit = alignedOverlap(a, b, shift);
            if (alike ? fit.ofUnion >= options.minAlignedOverlap
                      : fit.ofSmaller >= options.minTaperContainment)
                overlap[i * m + k] = fit.ofUnion;
        }
    }
    for (std::size_t i = 0; i < n; ++i) {
        const auto row = overlap.begin() + std::ptrdiff_t(i * m);
        const auto best = std::max_element(row, row + std::ptrdiff_t(m));
        if (*best <= 0) continue;
        const std::size_t k = std::size_t(best - row);
        bool mutual = true;
        for (std::size_t j = 0; j < n && mutual; ++j) mutual = j == i || overlap[j * m + k] < *best;
        if (mutual) pairs.push_back({std::uint32_t(i), std::uint32_t(k)});
    }
    return pairs;
}

std::pair<AxisPositions, AxisPositions> slidCorrespondence(const Polygon& lower,
                                                           const Polygon& upper) {
    const std::vector<double> lowerShares = lengthShares(lower), upperShares = lengthShares(upper);
    const Point2 shift = regionCentroid(lower) - regionCentroid(upper);
    std::vector<Point2> lowerSamples;
    for (int s = 0; s < kFitSamples; ++s)
        lowerSamples.push_back(pointAtShare(lower, lowerShares, double(s) / kFitSamples));
    double bestTurn = 0, bestCost = INFINITY;
    for (int r = 0; r < kTurns; ++r) {
        const double turn = double(r) / kTurns;
        double cost = 0;
        for (int s = 0; s < kFitSamples && cost < bestCost; ++s) {
            const Point2 d = pointAtShare(upper, upperShares, double(s) / kFitSamples + turn) +
                             shift - lowerSamples[std::size_t(s)];
            cost += dot(d, d);
        }
        if (cost < bestCost) bestCost = cost, bestTurn = turn;
    }
    AxisPositions lowerAt{1.0, 0, lowerShares};
    // The upper vertex at share u sits at parameter u − turn: walked from
    // the one with the smallest parameter, the parameters increase.
    AxisPositions upperAt{1.0, 0, {}};
    std::vector<double> parameter(upper.size());
    for (std::size_t j = 0; j < upper.size(); ++j) {
        parameter[j] = upperShares[j] - bestTurn;
        parameter[j] -= std::floor(parameter[j]);
    }
    upperAt.first =
        std::size_t(std::min_element(parameter.begin(), parameter.end()) - parameter.begin());
    for (std::size_t i = 0; i < upper.size(); ++i)
        upperAt.positions.push_back(parameter[(upperAt.first + i) % upper.size()]);
    return {lowerAt, upperAt};
}

}  // namespace dfrecon
