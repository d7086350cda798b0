#pragma once
// A triangle cut into cells no wider than a spacing, each with its
// centroid and area: the samples of surface integrals (compare's surface
// distances, algebra's distance-to-target histograms) that stand for
// exactly the points of their cell. The walks are templates (the visit is
// inlined); choosing a spacing within a budget of cells is not.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

#include "geometry/TriangleSoup.hpp"
#include "geometry/Vec3.hpp"

namespace dfrecon {

// The smallest ball around triangle abc: its centre (the circumcentre of
// an acute triangle, else the midpoint of the longest edge, both on the
// triangle) and squared radius. Every point of the triangle lies within the
// radius of the centre, and no point does better.
struct CellBall {
    Vec3 centre;
    double radius2 = 0;
};
inline CellBall smallestBallOf(const Vec3& a, const Vec3& b, const Vec3& c) {
    const Vec3 ab = b - a, bc = c - b, ca = a - c;
    const double lab = dot(ab, ab), lbc = dot(bc, bc), lca = dot(ca, ca);
    // The angle opposite the longest edge is not acute: its midpoint.
    if (lab >= lbc + lca) return {0.5 * (a + b), 0.25 * lab};
    if (lbc >= lca + lab) return {0.5 * (b + c), 0.25 * lbc};
    if (lca >= lab + lbc) return {0.5 * (c + a), 0.25 * lca};
    const Vec3 u = ab, v = c - a, w = cross(u, v);
    const double w2 = dot(w, w);
    const Vec3 offset = (0.5 / w2) * (dot(u, u) * cross(v, w) + dot(v, v) * cross(w, u));
    return {a + offset, dot(offset, offset)};
}

namespace detail {

inline double triangleArea(const Vec3& a, const Vec3& b, const Vec3& c) {
    return 0.5 * length(cross(b - a, c - a));
}

template <class Visit>
bool cellsOf(const Vec3& a, const Vec3& b, const Vec3& c, double spacingMm, Visit& visit,
             int depth) {
    const double spacing2 = spacingMm * spacingMm;
    const CellBall ball = smallestBallOf(a, b, c);
    // The relative slack lets cells cut to exactly the spacing through
    // rounding; 40 levels leave any cell of a valid mesh far below it.
    if (ball.radius2 <= spacing2 * (1 + 1e-9) || depth >= 40)
        return visit(ball.centre, triangleArea(a, b, c));
    // Name the corners so that v→e1 and v→e2 are the two longest edges.
    const double ab = dot(b - a, b - a), bc = dot(c - b, c - b), ca = dot(a - c, a - c);
    Vec3 v = a, e1 = b, e2 = c;
    double shortest2 = bc, longest2 = std::max(ab, ca);
    if (ab <= bc && ab <= ca) {
        v = c, e1 = a, e2 = b, shortest2 = ab, longest2 = std::max(bc, ca);
    } else if (ca <= ab && ca <= bc) {
        v = b, e1 = c, e2 = a, shortest2 = ca, longest2 = std::max(ab, bc);
    }
    const double twiceArea = length(cross(b - a, c - a));
    if (twiceArea * twiceArea * 4 < longest2 * longest2 && shortest2 * 4 > longest2) {
        // Flat and obtuse (no edge short): cut at the foot of the height over
        // the longest edge into two right slivers, which rows suit.
        Vec3 p = a, q = b, apex = c;
        if (bc >= ab && bc >= ca) {
            p = b, q = c, apex = a;
        } else if (ca >= ab && ca >= bc) {
            p = c, q = a, apex = b;
        }
        const Vec3 pq = q - p;
        const Vec3 foot = p + (dot(apex - p, pq) / dot(pq, pq)) * pq;
        return cellsOf(p, foot, apex, spacingMm, visit, depth + 1) &&
               cellsOf(foot, q, apex, spacingMm, visit, depth + 1);
    }
    if (shortest2 * 3 > longest2) {
        // Well shaped (the angle at v over about 35°): n² similar copies,
        // each with the ball's radius over n.
        const int n = std::max(2, int(std::ceil(std::sqrt(ball.radius2) / spacingMm)));
        const Vec3 du = (1.0 / n) * (e1 - v), dv = (1.0 / n) * (e2 - v);
        auto at = [&](int i, int j) { return v + double(i) * du + double(j) * dv; };
        for (int j = 0; j < n; ++j)
            for (int i = 0; i + j < n; ++i) {
                if (!cellsOf(at(i, j), at(i + 1, j), at(i, j + 1), spacingMm, visit, depth + 1))
                    return false;
                if (i + j + 1 < n && !cellsOf(at(i + 1, j), at(i + 1, j + 1), at(i, j + 1),
                                              spacingMm, visit, depth + 1))
                    return false;
            }
        return true;
    }
    // Tall or thin (the long edges nearly parallel): rows parallel to the
    // shortest edge, each cut into columns: cells are
    // four-sided, about 1.3 spacings a side (a ball of radius 0.92 spacings
    // holds one, leaving room for the shear of the rows' ends), about twice
    // the area of the largest triangle the spacing allows. A sliver's rows
    // are one cell wide and as tall as its width leaves room for, so its
    // cells number about its length over twice the spacing.
    const bool thin = shortest2 < 1.9 * spacing2;
    const double rowStep = thin ? std::sqrt(3.8 * spacing2 - shortest2) : 1.3 * spacingMm;
    const double columnStep = 1.3 * spacingMm;
    const double height = twiceArea / std::sqrt(shortest2);  // from v to the shortest edge
    const int rows = std::max(2, int(std::ceil(height / rowStep)));
    auto along = [&](const Vec3& e, int i) { return v + (double(i) / rows) * (e - v); };
    for (int i = 0; i < rows; ++i) {
        const Vec3 p = along(e1, i), q = along(e2, i), p1 = along(e1, i + 1), q1 = along(e2, i + 1);
        const int columns = thin ? 1 : std::max(1, int(std::ceil(length(q1 - p1) / columnStep)));
        for (int j = 0; j < columns; ++j) {
            const double f0 = double(j) / columns, f1 = double(j + 1) / columns;
            const Vec3 u = p + f0 * (q - p), u1 = p + f1 * (q - p), w = p1 + f0 * (q1 - p1),
                       w1 = p1 + f1 * (q1 - p1);
            const Vec3 centre = 0.25 * (u + u1 + w + w1);
            const double reach2 =
                std::max({dot(u - centre, u - centre), dot(u1 - centre, u1 - centre),
                          dot(w - centre, w - centre), dot(w1 - centre, w1 - centre)});
            // The first row's cells are triangles (u = u1 = v), checked by
            // their own ball.
            const bool triangle = i == 0;
            if (!triangle && reach2 <= spacing2) {
                const double area = triangleArea(u, w1, w) + triangleArea(u, u1, w1);
                if (!visit(centre, area)) return false;
                continue;
            }
            if (!cellsOf(u, w1, w, spacingMm, visit, depth + 1)) return false;
            if (!triangle && !cellsOf(u, u1, w1, spacingMm, visit, depth + 1)) return false;
        }
    }
    return true;
}

}  // namespace detail

// Calls visit(point, weightMm2) for every cell of the triangle (p0, p1,
// p2): cells each within spacingMm of their sample point (the centre of a
// triangle cell's smallest ball, smallestBallOf; the mean of a four-sided
// cell's corners), each weighed by its area, so the weights sum to the
// triangle's area and each sample stands for exactly the points of its
// cell. Cells come near the largest the spacing allows, whatever the
// triangle's shape: a well-shaped triangle is cut into n² similar copies, n
// the least that brings their balls within the spacing; a tall or thin one
// (contour meshes are mostly these: a plane spacing long, a contour step
// wide) into rows across its long edges, each cut into columns, so that a
// sliver's cells number about its length over twice the spacing (a grid of
// similar cells would need that squared); a flat obtuse one is first cut
// into two right ones at its height.
//
// This form stops as soon as visit returns false, and returns false then
// (true when every cell was visited): counting up to a budget costs the
// budget, not the cells.
template <class Visit>
bool forEachCellWhile(const Vec3& p0, const Vec3& p1, const Vec3& p2, double spacingMm,
                      Visit&& visit) {
    return detail::cellsOf(p0, p1, p2, spacingMm, visit, 0);
}

// Every cell, as forEachCellWhile with a visit that never stops.
template <class Visit>
void forEachCell(const Vec3& p0, const Vec3& p1, const Vec3& p2, double spacingMm, Visit&& visit) {
    forEachCellWhile(p0, p1, p2, spacingMm, [&](const Vec3& point, double weightMm2) {
        visit(point, weightMm2);
        return true;
    });
}

/// The spacing to cut every surface of `soups` into cells at, asked for
/// `spacingMm`: that one where none of them then has more than `maxCells`
/// cells, else the first spacing found, growing from it, where none has —
/// or, where a surface has more triangles than `maxCells`, one at which
/// every triangle is a cell of its own (no spacing gives fewer: such a
/// surface is sampled once per triangle). O(min(S, maxCells) + T) per step for S cells and T
/// triangles, a few steps: past the budget cells are not all counted but estimated from the area of
/// those counted (a metre-sized cube at 0.2 mm has 10^8 of them).
double cellSpacingWithinBudget(const std::vector<const TriangleSoup*>& soups, double spacingMm,
                               std::size_t maxCells);

}  // namespace dfrecon
