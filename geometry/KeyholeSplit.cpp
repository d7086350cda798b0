#include "geometry/KeyholeSplit.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

namespace dfrecon {

namespace {

// Inserts every vertex that lies inside another edge (within tol) into that
// edge, so both sides of a channel share their points exactly. Vertices are
// sorted by x; each edge scans only those within its x range.
Polygon insertTouchingVertices(const Polygon& contour, double tol) {
    const std::size_t n = contour.size();
    std::vector<std::size_t> byX(n);
    for (std::size_t i = 0; i < n; ++i) byX[i] = i;
    std::sort(byX.begin(), byX.end(),
              [&](std::size_t a, std::size_t b) { return contour[a].x < contour[b].x; });
    Polygon refined;
    refined.reserve(n);
    for (std::size_t i = 0; i < n; ++i) {
        const Point2 a = contour[i], b = contour[(i + 1) % n];
        refined.push_back(a);
        const double lo = std::min(a.x, b.x) - tol, hi = std::max(a.x, b.x) + tol;
        auto first = std::lower_bound(byX.begin(), byX.end(), lo,
                                      [&](std::size_t k, double x) { return contour[k].x < x; });
        std::vector<std::pair<double, Point2>> inside;  // (parameter along ab, vertex)
        for (auto it = first; it != byX.end() && contour[*it].x <= hi; ++it) {
            const Point2 p = contour[*it];
            if (p == a || p == b) continue;
            const double t = nearestSegmentParameter(p, a, b);
            if (t <= 0 || t >= 1) continue;
            if (length(a + t * (b - a) - p) <= tol) inside.push_back({t, p});
        }
        std::sort(inside.begin(), inside.end(),
                  [](const auto& l, const auto& r) { return l.first < r.first; });
        for (const auto& [t, p] : inside)
            if (refined.back() != p) refined.push_back(p);
    }
    return refined;
}

// Makes vertices within tol of an earlier vertex exactly equal to it, so
// that revisits can be found by equality.
void snapNearVertices(Polygon& contour, double tol) {
    std::vector<std::size_t> byX(contour.size());
    for (std::size_t i = 0; i < byX.size(); ++i) byX[i] = i;
    std::stable_sort(byX.begin(), byX.end(),
                     [&](std::size_t a, std::size_t b) { return contour[a].x < contour[b].x; });
    for (std::size_t k = 0; k < byX.size(); ++k)
        for (std::size_t m = k + 1; m < byX.size(); ++m) {
            Point2& p = contour[byX[k]];
            Point2& q = contour[byX[m]];
            if (q.x - p.x > tol) break;
            if (q != p && std::abs(q.y - p.y) <= tol && length(q - p) <= tol)
                (byX[m] < byX[k] ? p : q) = (byX[m] < byX[k] ? q : p);
        }
}

void dropConsecutiveRepeats(Polygon& loop) {
    loop.erase(std::unique(loop.begin(), loop.end()), loop.end());
    while (loop.size() > 1 && loop.back() == loop.front()) loop.pop_back();
}

bool hasArea(const Polygon& loop) {
    if (loop.size() < 3) return false;
    const Box2 box = boundingBox(loop);
    const double diagonal = length(box.max - box.min);
    return std::abs(signedArea(loop)) > 1e-12 * diagonal * diagonal;
}

struct PointLess {
    bool operator()(Point2 a, Point2 b) const { return a.x < b.x || (a.x == b.x && a.y < b.y); }
};

}  // namespace

KeyholeSplit splitKeyholes(const Polygon& contour, double toleranceMm) {
    KeyholeSplit result;
    Polygon refined = insertTouchingVertices(contour, toleranceMm);
    snapNearVertices(refined, toleranceMm);
    dropConsecutiveRepeats(refined);

    std::vector<Polygon> pending{std::move(refined)};
    while (!pending.empty()) {
        Polygon path = std::move(pending.back());
        pending.pop_back();
        // The first revisit cuts out the loop between the two visits; what
        // is left keeps one copy of the point and may hold further revisits.
        std::map<Point2, std::size_t, PointLess> seen;
        bool cut = false;
        for (std::size_t k = 0; k < path.size() && !cut; ++k) {
            const auto [it, fresh] = seen.emplace(path[k], k);
            if (fresh) continue;
            const std::size_t i = it->second;
            Polygon loop(path.begin() + std::ptrdiff_t(i), path.begin() + std::ptrdiff_t(k));
            Polygon rest(path.begin(), path.begin() + std::ptrdiff_t(i) + 1);
            rest.insert(rest.end(), path.begin() + std::ptrdiff_t(k) + 1, path.end());
            for (Polygon* part : {&loop, &rest}) {
                dropConsecutiveRepeats(*part);
                if (hasArea(*part)) pending.push_back(std::move(*part));
            }
            ++result.cuts;
            cut = true;
        }
        if (!cut && hasArea(path)) result.loops.push_back(std::move(path));
    }
    if (result.cuts == 0) result.loops = {contour};
    return result;
}

}  // namespace dfrecon
