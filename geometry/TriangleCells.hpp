#pragma once
// A triangle cut into cells no wider than a spacing, each with its
// centroid and area: the samples of surface integrals (compare's surface
// distances, algebra's distance-to-target histograms) that stand for
// exactly the points of their cell. The walks are templates (the visit is
// inlined); choosing a spacing within a budget of cells is not.
#include <algorithm>
#include <cstddef>
#include <vector>

#include "geometry/TriangleSoup.hpp"
#include "geometry/Vec3.hpp"

namespace dfrecon {

// Calls visit(point, weightMm2) for the centroid of every cell of the
// triangle (p0, p1, p2): cells made by halving the longest edge until every
// cell's corners lie within spacingMm of its centroid, each weighed by its
// area, so the weights sum to the triangle's area and each sample stands
// for exactly the points of its cell. The farthest point of a triangle from
// any point is a corner, so every point of a cell lies within spacingMm of
// its sample. Halving the longest edge keeps cells' angles bounded and a
// sliver's cells few (about its length over the spacing, where a grid of
// similar cells would need that squared).
//
// This form stops as soon as visit returns false, and returns false then
// (true when every cell was visited): counting up to a budget costs the
// budget, not the cells.
template <class Visit>
bool forEachCellWhile(const Vec3& p0, const Vec3& p1, const Vec3& p2, double spacingMm,
                      Visit&& visit) {
    const double spacing2 = spacingMm * spacingMm;
    struct Cell {
        Vec3 a, b, c;
    };
    Cell stack[64];
    int top = 0;
    stack[top++] = {p0, p1, p2};
    while (top > 0) {
        const Cell cell = stack[--top];
        const Vec3 centroid = (1.0 / 3) * (cell.a + cell.b + cell.c);
        const double reach2 = std::max({dot(cell.a - centroid, cell.a - centroid),
                                        dot(cell.b - centroid, cell.b - centroid),
                                        dot(cell.c - centroid, cell.c - centroid)});
        // 60 halvings leave any cell of a valid mesh far below the spacing:
        // the depth only guards the stack.
        if (reach2 <= spacing2 || top >= 62) {
            if (!visit(centroid, 0.5 * length(cross(cell.b - cell.a, cell.c - cell.a))))
                return false;
            continue;
        }
        const double ab = dot(cell.b - cell.a, cell.b - cell.a),
                     bc = dot(cell.c - cell.b, cell.c - cell.b),
                     ca = dot(cell.a - cell.c, cell.a - cell.c);
        if (ab >= bc && ab >= ca) {
            const Vec3 m = 0.5 * (cell.a + cell.b);
            stack[top++] = {cell.a, m, cell.c};
            stack[top++] = {m, cell.b, cell.c};
        } else if (bc >= ca) {
            const Vec3 m = 0.5 * (cell.b + cell.c);
            stack[top++] = {cell.a, cell.b, m};
            stack[top++] = {cell.a, m, cell.c};
        } else {
            const Vec3 m = 0.5 * (cell.c + cell.a);
            stack[top++] = {cell.a, cell.b, m};
            stack[top++] = {m, cell.b, cell.c};
        }
    }
    return true;
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
/// cells, else the first spacing found, growing from it, where none has.
/// O(min(S, maxCells) + T) per step for S cells and T triangles, a few
/// steps: past the budget cells are not all counted but estimated from the
/// area of those counted (a metre-sized cube at 0.2 mm has 10^8 of them).
double cellSpacingWithinBudget(const std::vector<const TriangleSoup*>& soups, double spacingMm,
                               std::size_t maxCells);

}  // namespace dfrecon
