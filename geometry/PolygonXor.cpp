#include "geometry/PolygonXor.hpp"

#include <CGAL/Boolean_set_operations_2.h>
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Polygon_set_2.h>

namespace dfrecon {

namespace {

using Kernel = CGAL::Exact_predicates_exact_constructions_kernel;
using CgalPolygon = CGAL::Polygon_2<Kernel>;
using PolygonWithHoles = CGAL::Polygon_with_holes_2<Kernel>;

CgalPolygon toCgal(const Polygon& polygon) {
    CgalPolygon out;
    for (const Point2& p : polygon) out.push_back(Kernel::Point_2(p.x, p.y));
    if (out.is_clockwise_oriented()) out.reverse_orientation();
    return out;
}

Polygon fromCgal(const CgalPolygon& polygon, bool clockwise) {
    Polygon out;
    for (auto it = polygon.vertices_begin(); it != polygon.vertices_end(); ++it)
        out.push_back({CGAL::to_double(it->x()), CGAL::to_double(it->y())});
    if ((signedArea(out) < 0) != clockwise) std::reverse(out.begin(), out.end());
    return out;
}

}  // namespace

std::vector<Polygon> xorRegions(const std::vector<Polygon>& contours) {
    std::vector<CgalPolygon> polygons;
    for (const Polygon& contour : contours) polygons.push_back(toCgal(contour));
    // The range form merges divide-and-conquer; one polygon at a time would
    // rebuild the growing arrangement every step (quadratic).
    CGAL::Polygon_set_2<Kernel> region;
    region.symmetric_difference(polygons.begin(), polygons.end());
    std::vector<PolygonWithHoles> pieces;
    region.polygons_with_holes(std::back_inserter(pieces));
    std::vector<Polygon> out;
    for (const PolygonWithHoles& piece : pieces) {
        out.push_back(fromCgal(piece.outer_boundary(), false));
        for (auto hole = piece.holes_begin(); hole != piece.holes_end(); ++hole)
            out.push_back(fromCgal(*hole, true));
    }
    return out;
}

}  // namespace dfrecon
