#include "geometry/TouchSeparation.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>

#include "geometry/ContourValidation.hpp"

namespace dfrecon {

namespace {

// The index of the vertex of `contour` at `at`, inserting one into segment
// `segment` when `at` lies inside it.
std::size_t vertexAt(Polygon& contour, std::size_t segment, Point2 at) {
    const std::size_t n = contour.size();
    const std::size_t a = segment, b = (segment + 1) % n;
    if (contour[a] == at) return a;
    if (contour[b] == at) return b;
    // The touch point comes from the other contour; keep this contour's own
    // point when it is the nearer end (rounding can leave `at` a hair off).
    const double da = length(contour[a] - at), db = length(contour[b] - at);
    const double edge = length(contour[b] - contour[a]);
    if (da <= 1e-9 * edge) return a;
    if (db <= 1e-9 * edge) return b;
    contour.insert(contour.begin() + std::ptrdiff_t(a + 1), at);
    return a + 1;
}

// The unit direction into the left side of the contour at vertex k (the
// bisector of the two edges' left normals; a spike's tip gets the normal
// of the first edge).
Point2 leftBisector(const Polygon& contour, std::size_t k) {
    const std::size_t n = contour.size();
    const Point2 p = contour[(k + n - 1) % n], q = contour[k], r = contour[(k + 1) % n];
    auto leftNormal = [](Point2 d) {
        const double l = length(d);
        return l > 0 ? Point2{-d.y / l, d.x / l} : Point2{0, 0};
    };
    const Point2 n1 = leftNormal(q - p), n2 = leftNormal(r - q);
    Point2 m = n1 + n2;
    if (length(m) < 1e-6) m = n1;
    // Reflex vertices: the bisector of the normals still points left.
    return (1 / length(m)) * m;
}

// How far a contour's copy of a touch point at vertex k moves: half the gap,
// less where an adjacent edge is shorter than ten times that.
double touchStep(const Polygon& contour, std::size_t k, double gapMm) {
    const std::size_t n = contour.size();
    const Point2 p = contour[k];
    const double shortest =
        std::min(length(p - contour[(k + 1) % n]), length(p - contour[(k + n - 1) % n]));
    return std::min(0.5 * gapMm, 0.1 * shortest);
}

// Is contour `inner` inside the region `outer` encloses? Judged at the
// vertex of `inner` farthest from the touch point (any other point of
// inner lies strictly on one side of outer, as they only touch).
bool enclosedBy(const Polygon& inner, const Polygon& outer, Point2 touch) {
    std::size_t far = 0;
    for (std::size_t k = 1; k < inner.size(); ++k)
        if (length(inner[k] - touch) > length(inner[far] - touch)) far = k;
    return windingNumber(inner[far], outer) != 0;
}

}  // namespace

std::size_t separateTouchingContours(std::vector<Polygon>& contours, double gapMm) {
    std::size_t opened = 0;
    // One touch per contour per round, as opening one inserts a vertex and
    // shifts the segment numbers of the others; the next round finds them
    // again. A contour touching k others is settled in k rounds.
    for (int round = 0; round < 64; ++round) {
        const std::vector<ContourTouch> touches = findContourTouches(contours);
        if (touches.empty()) break;
        std::vector<bool> changed(contours.size(), false);
        for (const ContourTouch& touch : touches) {
            if (changed[touch.contourA] || changed[touch.contourB]) continue;
            Polygon& a = contours[touch.contourA];
            Polygon& b = contours[touch.contourB];
            if (a.size() < 3 || b.size() < 3) continue;
            // Which way each side moves, as a multiple of its left bisector:
            // +1 shrinks the enclosed region of a counter-clockwise contour.
            const double ccwA = signedArea(a) > 0 ? 1 : -1, ccwB = signedArea(b) > 0 ? 1 : -1;
            double intoA = ccwA, intoB = ccwB;  // siblings: each into its own region
            if (enclosedBy(b, a, touch.at))
                intoA = -ccwA;  // a grows away from b inside it
            else if (enclosedBy(a, b, touch.at))
                intoB = -ccwB;
            const std::size_t ka = vertexAt(a, touch.segmentA, touch.at);
            const std::size_t kb = vertexAt(b, touch.segmentB, touch.at);
            const Point2 pa = a[ka], pb = b[kb];
            const std::size_t contactsBefore = countContourContacts({a, b}, SIZE_MAX - 1);
            const double stepA = touchStep(a, ka, gapMm), stepB = touchStep(b, kb, gapMm);
            // The rule's directions first; where the nesting test misjudged
            // (contours that touch at several points, a copy whose farthest
            // point lies on the other), the other signs in turn: the first
            // that opens this touch without a crossing (an exact test) and
            // leaves the copies apart by at least half the gap they were
            // given (moved the same way, they were a few nanometres apart,
            // which rounding to float closes) is kept.
            for (const auto& [signA, signB] :
                 {std::pair{intoA, intoB}, std::pair{-intoA, intoB}, std::pair{intoA, -intoB},
                  std::pair{-intoA, -intoB}}) {
                a[ka] = pa + (signA * stepA) * leftBisector(a, ka);
                b[kb] = pb + (signB * stepB) * leftBisector(b, kb);
                if (length(a[ka] - b[kb]) >= 0.5 * (stepA + stepB) && !findContourDefect({a, b}) &&
                    countContourContacts({a, b}, SIZE_MAX - 1) < contactsBefore)
                    break;
                a[ka] = pa;
                b[kb] = pb;
            }
            if (a[ka] == pa) {  // no sign left them apart: the rule's, for the checks to judge
                a[ka] = pa + (intoA * stepA) * leftBisector(a, ka);
                b[kb] = pb + (intoB * stepB) * leftBisector(b, kb);
            }
            changed[touch.contourA] = changed[touch.contourB] = true;
            ++opened;
        }
    }
    return opened;
}

}  // namespace dfrecon
