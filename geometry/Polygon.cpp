#include "geometry/Polygon.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <algorithm>
#include <limits>

#include "geometry/ClosestPoint.hpp"
#include "geometry/Vec3.hpp"

namespace dfrecon {

double netArea(const std::vector<Polygon>& contours) {
    double area = 0;
    for (const Polygon& contour : contours) area += signedArea(contour);
    return area;
}

double signedArea(const Polygon& polygon) {
    if (polygon.size() < 3) return 0;
    // Relative to the first point: keeps cancellation small far from the origin.
    const Point2 o = polygon.front();
    double twice = 0;
    for (std::size_t i = 1; i + 1 < polygon.size(); ++i)
        twice += cross(polygon[i] - o, polygon[i + 1] - o);
    return 0.5 * twice;
}

double perimeterMm(const Polygon& polygon) {
    double sum = 0;
    for (std::size_t k = 0; k < polygon.size(); ++k)
        sum += length(polygon[(k + 1) % polygon.size()] - polygon[k]);
    return sum;
}

Point2 regionCentroid(const Polygon& polygon) {
    // Relative to the first point, as signedArea, so far from the origin the
    // products keep their precision.
    if (polygon.empty()) return {0, 0};
    const Point2 o = polygon[0];
    double twiceArea = 0, x = 0, y = 0;
    for (std::size_t i = 0; i < polygon.size(); ++i) {
        const Point2 a = polygon[i] - o, b = polygon[(i + 1) % polygon.size()] - o;
        const double w = cross(a, b);
        twiceArea += w;
        x += (a.x + b.x) * w;
        y += (a.y + b.y) * w;
    }
    if (std::abs(twiceArea) < 1e-12) {
        Point2 sum{0, 0};
        for (const Point2& p : polygon) sum = sum + (p - o);
        return o + (1.0 / double(polygon.size())) * sum;
    }
    return o + Point2{x / (3 * twiceArea), y / (3 * twiceArea)};
}

int windingNumber(Point2 p, const Polygon& polygon) {
    int winding = 0;
    const std::size_t n = polygon.size();
    for (std::size_t i = 0; i < n; ++i)
        winding += windingCrossing(p, polygon[i], polygon[(i + 1) % n]);
    return winding;
}

double nearestSegmentParameter(Point2 p, Point2 a, Point2 b) {
    return nearestSegmentParameter(p.x - a.x, p.y - a.y, b.x - a.x, b.y - a.y);
}

double distanceToSegment(Point2 p, Point2 a, Point2 b) {
    return length(p - (a + nearestSegmentParameter(p, a, b) * (b - a)));
}

double distanceToBoundary(Point2 p, const Polygon& polygon) {
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < polygon.size(); ++i)
        best = std::min(best, distanceToSegment(p, polygon[i], polygon[(i + 1) % polygon.size()]));
    return best;
}

// Is c within the bounding box of ab (used once c is known collinear with ab)?
static bool withinSpan(Point2 a, Point2 b, Point2 c) {
    return std::min(a.x, b.x) <= c.x && c.x <= std::max(a.x, b.x) && std::min(a.y, b.y) <= c.y &&
           c.y <= std::max(a.y, b.y);
}

// The rounded cross product took pieces of one segment, split at a rounded
// crossing point and a few 1e-17 off the line, for segments crossing each
// other.
int exactOrientation(Point2 a, Point2 b, Point2 c) {
    using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
    return int(CGAL::orientation(Kernel::Point_2(a.x, a.y), Kernel::Point_2(b.x, b.y),
                                 Kernel::Point_2(c.x, c.y)));
}

SegmentContact segmentContact(Point2 a, Point2 b, Point2 c, Point2 d) {
    const int o1 = exactOrientation(a, b, c), o2 = exactOrientation(a, b, d);
    const int o3 = exactOrientation(c, d, a), o4 = exactOrientation(c, d, b);

    if (o1 == 0 && o2 == 0) {
        // Collinear: project on the dominant axis and compare the overlap.
        const bool useX = std::abs(b.x - a.x) >= std::abs(b.y - a.y);
        auto coord = [useX](Point2 p) { return useX ? p.x : p.y; };
        const double lo = std::max(std::min(coord(a), coord(b)), std::min(coord(c), coord(d)));
        const double hi = std::min(std::max(coord(a), coord(b)), std::max(coord(c), coord(d)));
        if (lo > hi) return SegmentContact::None;
        return lo == hi ? SegmentContact::Touch : SegmentContact::Overlap;
    }
    if (o1 * o2 < 0 && o3 * o4 < 0) return SegmentContact::Cross;
    if ((o1 == 0 && withinSpan(a, b, c)) || (o2 == 0 && withinSpan(a, b, d)) ||
        (o3 == 0 && withinSpan(c, d, a)) || (o4 == 0 && withinSpan(c, d, b)))
        return SegmentContact::Touch;
    return SegmentContact::None;
}

Box2 boundingBox(const Polygon& polygon) {
    Box2 box;
    for (Point2 p : polygon) box.add(p);
    return box;
}

Polygon circlePolygon(Point2 centre, double radius, int points, bool clockwise) {
    Polygon polygon;
    for (int i = 0; i < points; ++i) {
        const double t = 2 * kPi * (clockwise ? -i : i) / points;
        polygon.push_back({centre.x + radius * std::cos(t), centre.y + radius * std::sin(t)});
    }
    return polygon;
}

bool allCollinear(const Polygon& polygon) {
    for (std::size_t k = 2; k < polygon.size(); ++k) {
        const Point2 u = polygon[1] - polygon[0], v = polygon[k] - polygon[0];
        if (u.x * v.y - u.y * v.x != 0) return false;
    }
    return true;
}

}  // namespace dfrecon
