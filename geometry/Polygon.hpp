#pragma once
// Planar points and closed polygons in millimetres, with the few exact-enough
// predicates that validation and orientation need.
#include <cmath>
#include <vector>

namespace dfrecon {

struct Point2 {
    double x = 0, y = 0;
};
inline Point2 operator+(Point2 a, Point2 b) {
    return {a.x + b.x, a.y + b.y};
}
inline Point2 operator-(Point2 a, Point2 b) {
    return {a.x - b.x, a.y - b.y};
}
inline Point2 operator*(double s, Point2 a) {
    return {s * a.x, s * a.y};
}
inline bool operator==(Point2 a, Point2 b) {
    return a.x == b.x && a.y == b.y;
}
inline bool operator!=(Point2 a, Point2 b) {
    return !(a == b);
}
inline double dot(Point2 a, Point2 b) {
    return a.x * b.x + a.y * b.y;
}
inline double cross(Point2 a, Point2 b) {
    return a.x * b.y - a.y * b.x;
}
inline double length(Point2 a) {
    return std::hypot(a.x, a.y);
}

/// A closed polygon: the edge from the last point back to the first is
/// implied, and the last point does not repeat the first.
using Polygon = std::vector<Point2>;

/// Do all points lie on one line (a polygon with no area at all, as
/// opposed to a figure eight whose halves cancel)? Exact on the recorded
/// coordinates. O(n).
bool allCollinear(const Polygon& polygon);
/// Shoelace area: positive for counter-clockwise polygons. O(n).
double signedArea(const Polygon& polygon);
/// The length of the closed outline, mm. O(n).
double perimeterMm(const Polygon& polygon);
/// The centre of mass of the enclosed region (either orientation); the
/// mean of the points where it encloses no area. O(n).
Point2 regionCentroid(const Polygon& polygon);
/// The net area of contours oriented as slices keep them (outer ones
/// counter-clockwise, holes clockwise): their signed areas summed, holes
/// subtracted. O(points).
double netArea(const std::vector<Polygon>& contours);

/// What edge a→b adds to the winding number of `p`, by Sunday's crossing
/// rule: +1 if it goes up across the horizontal line through p (half-open:
/// a.y <= p.y < b.y) with p on its left, -1 if it goes down (b.y <= p.y <
/// a.y) with p on its right, else 0. So it counts crossings strictly right
/// of p, and for fixed a, b and p.y the rounded side test is monotone in p.x:
/// along a row it changes once. No trigonometry, no division. O(1).
inline int windingCrossing(Point2 p, Point2 a, Point2 b) {
    const double side = cross(b - a, p - a);
    if (a.y <= p.y) return b.y > p.y && side > 0 ? 1 : 0;
    return b.y <= p.y && side < 0 ? -1 : 0;
}

/// The side of c from the line a→b, exactly for the doubles given (CGAL's
/// filtered predicate): 1 left (abc counter-clockwise), -1 right, 0 on it.
/// O(1); a rounded cross product gets points a hair from the line wrong.
int exactOrientation(Point2 a, Point2 b, Point2 c);

/// Winding number of `polygon` around `p` (non-zero inside, 0 outside): the
/// sum of windingCrossing over its edges; undefined for p exactly on the
/// boundary. O(n).
int windingNumber(Point2 p, const Polygon& polygon);

/// Parameter t in [0, 1] of the point a + t·(b − a) of segment ab nearest
/// to p (0 for a degenerate segment).
double nearestSegmentParameter(Point2 p, Point2 a, Point2 b);

/// Distance from p to the closed segment ab.
double distanceToSegment(Point2 p, Point2 a, Point2 b);

/// Distance from p to the polygon's boundary. O(n).
double distanceToBoundary(Point2 p, const Polygon& polygon);

/// How two closed segments meet.
enum class SegmentContact {
    None,     // disjoint
    Touch,    // share exactly one point that is an endpoint of at least one
    Cross,    // interiors cross at one point
    Overlap,  // collinear with a shared piece of positive length
};

/// Classifies the contact of segments ab and cd with exact orientation tests
/// (CGAL's filtered predicates: exact on the doubles given).
SegmentContact segmentContact(Point2 a, Point2 b, Point2 c, Point2 d);

struct Box2 {
    Point2 min{INFINITY, INFINITY}, max{-INFINITY, -INFINITY};
    void add(Point2 p) {
        min = {std::fmin(min.x, p.x), std::fmin(min.y, p.y)};
        max = {std::fmax(max.x, p.x), std::fmax(max.y, p.y)};
    }
    bool empty() const { return min.x > max.x; }
    bool contains(Point2 p) const {
        return p.x >= min.x && p.x <= max.x && p.y >= min.y && p.y <= max.y;
    }
};
Box2 boundingBox(const Polygon& polygon);

/// A regular polygon with `points` vertices on the circle of `radius`
/// around `centre`, the first at angle 0; counter-clockwise unless
/// `clockwise`.
Polygon circlePolygon(Point2 centre, double radius, int points, bool clockwise = false);

}  // namespace dfrecon
