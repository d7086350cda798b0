#include "recon/ContourSimplification.hpp"

#include <algorithm>
#include <stdexcept>

#include "geometry/ContourValidation.hpp"

namespace dfrecon {

namespace {

// The original chain strictly between kept vertices `from` and `to`
// (cyclic indices) and its farthest point from the edge between them.
struct Farthest {
    std::size_t index = 0;  // original index of the farthest interior point
    double distance = 0;    // 0 when the chain has no interior point
    bool any = false;
};

Farthest farthestOnChain(const Polygon& c, std::size_t from, std::size_t to) {
    const std::size_t n = c.size();
    Farthest best;
    for (std::size_t k = (from + 1) % n; k != to; k = (k + 1) % n) {
        const double d = distanceToSegment(c[k], c[from], c[to]);
        if (!best.any || d > best.distance) best = {k, d, true};
    }
    return best;
}

// Kept original indices in cyclic order → the simplified contour with its
// per-edge deviations.
SimplifiedContour assemble(const Polygon& c, std::vector<std::size_t> kept) {
    std::sort(kept.begin(), kept.end());
    SimplifiedContour out;
    out.originalIndex = kept;
    for (std::size_t k = 0; k < kept.size(); ++k) {
        out.points.push_back(c[kept[k]]);
        out.edgeDeviationMm.push_back(
            farthestOnChain(c, kept[k], kept[(k + 1) % kept.size()]).distance);
    }
    return out;
}

// Douglas–Peucker on the chain from→to (cyclic), appending split points to
// `kept`. Explicit stack: contours may have a million points.
void refineChain(const Polygon& c, std::size_t from, std::size_t to, double epsilon,
                 std::vector<std::size_t>& kept) {
    std::vector<std::pair<std::size_t, std::size_t>> stack{{from, to}};
    while (!stack.empty()) {
        const auto [a, b] = stack.back();
        stack.pop_back();
        const Farthest f = farthestOnChain(c, a, b);
        if (!f.any || f.distance <= epsilon) continue;
        kept.push_back(f.index);
        stack.push_back({a, f.index});
        stack.push_back({f.index, b});
    }
}

// Splits kept edge k of `s` (if its chain has interior points) at the
// farthest original point, then refines both halves to epsilon again: a
// chain can be farther from a shorter edge than from the one it replaced.
// Returns false if the edge is an original edge.
bool splitEdge(const Polygon& c, SimplifiedContour& s, std::size_t k, double epsilon) {
    const std::size_t m = s.originalIndex.size();
    const std::size_t from = s.originalIndex[k], to = s.originalIndex[(k + 1) % m];
    const Farthest f = farthestOnChain(c, from, to);
    if (!f.any) return false;
    std::vector<std::size_t> kept = s.originalIndex;
    kept.push_back(f.index);
    refineChain(c, from, f.index, epsilon, kept);
    refineChain(c, f.index, to, epsilon, kept);
    s = assemble(c, kept);
    return true;
}

}  // namespace

SimplifiedContour simplifyContour(const Polygon& contour, double epsilonMm) {
    const std::size_t n = contour.size();
    if (n < 3) throw std::invalid_argument("simplifyContour: fewer than 3 points");
    std::vector<std::size_t> kept;
    if (!(epsilonMm > 0)) {
        for (std::size_t k = 0; k < n; ++k) kept.push_back(k);
        return assemble(contour, kept);
    }
    // Start from vertex 0 and the vertex farthest from it; refine both chains.
    std::size_t far = 1;
    for (std::size_t k = 2; k < n; ++k)
        if (length(contour[k] - contour[0]) > length(contour[far] - contour[0])) far = k;
    kept = {0, far};
    refineChain(contour, 0, far, epsilonMm, kept);
    refineChain(contour, far, 0, epsilonMm, kept);
    if (kept.size() < 3) {
        // A sliver within epsilon of one segment: keep its widest point so the
        // result still encloses area.
        const Farthest a = farthestOnChain(contour, 0, far), b = farthestOnChain(contour, far, 0);
        kept.push_back(a.any && (!b.any || a.distance >= b.distance) ? a.index : b.index);
    }
    return assemble(contour, kept);
}

std::vector<SimplifiedContour> simplifySlice(const std::vector<Polygon>& contours,
                                             double epsilonMm) {
    std::vector<SimplifiedContour> result;
    for (const Polygon& c : contours) result.push_back(simplifyContour(c, epsilonMm));
    if (!(epsilonMm > 0)) return result;
    // Each pass splits at least one edge, and splitting everything gives back
    // the (valid) originals, so this ends.
    for (;;) {
        std::vector<Polygon> current;
        for (const SimplifiedContour& s : result) current.push_back(s.points);
        const std::optional<ContourDefect> defect = findContourDefect(current);
        if (!defect) return result;
        bool split = false;
        if (defect->kind != ContourDefect::Kind::TooComplex) {
            const std::size_t sizeA = result[defect->contourA].points.size();
            split |= splitEdge(contours[defect->contourA], result[defect->contourA],
                               defect->segmentA, epsilonMm);
            const bool sameEdge =
                defect->contourA == defect->contourB && defect->segmentA == defect->segmentB;
            if (!sameEdge) {
                // If B is A, edges after A's split moved by the points inserted.
                const std::size_t inserted = result[defect->contourA].points.size() - sizeA;
                const std::size_t segmentB =
                    defect->contourA == defect->contourB && defect->segmentB > defect->segmentA
                        ? defect->segmentB + inserted
                        : defect->segmentB;
                split |= splitEdge(contours[defect->contourB], result[defect->contourB], segmentB,
                                   epsilonMm);
            }
        }
        if (!split) {
            // Only original edges involved (or too complex to check): keep the
            // originals, which loading validated.
            result.clear();
            for (const Polygon& c : contours) result.push_back(simplifyContour(c, 0));
            return result;
        }
    }
}

}  // namespace dfrecon
