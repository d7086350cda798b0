#include "algebra/OctantGauge.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "geometry/ClosestPoint.hpp"

namespace dfrecon {

namespace {

// A convex polygon of at most 3 + 3 corners: a triangle cut by three planes.
struct Piece {
    Vec3 corner[9];
    int count = 0;
};

double component(Vec3 v, int i) {
    return i == 0 ? v.x : i == 1 ? v.y : v.z;
}

// Keeps the part of `in` where sign · x_axis ≥ 0 (Sutherland–Hodgman).
Piece clip(const Piece& in, int axis, double sign) {
    Piece out;
    for (int k = 0; k < in.count; ++k) {
        const Vec3 a = in.corner[k], b = in.corner[(k + 1) % in.count];
        const double da = sign * component(a, axis), db = sign * component(b, axis);
        if (da >= 0) out.corner[out.count++] = a;
        if ((da >= 0) != (db >= 0)) {
            const double t = da / (da - db);
            out.corner[out.count++] = a + t * (b - a);
        }
    }
    return out;
}

// The distance from the origin to a convex planar polygon (or what is left
// of one: a segment, a point).
double distanceToOrigin(const Piece& piece) {
    double best = INFINITY;
    for (int k = 0; k < piece.count; ++k) {
        const Vec3 a = piece.corner[k], b = piece.corner[(k + 1) % piece.count];
        const Vec3 ab = b - a;
        const double length2 = dot(ab, ab);
        const double t = length2 > 0 ? std::clamp(-dot(a, ab) / length2, 0.0, 1.0) : 0.0;
        best = std::min(best, length(a + t * ab));
    }
    if (piece.count < 3) return best;
    // Inside the polygon's interior: the distance to its plane.
    Vec3 normal{0, 0, 0};
    for (int k = 1; k + 1 < piece.count; ++k)
        normal = normal +
                 cross(piece.corner[k] - piece.corner[0], piece.corner[k + 1] - piece.corner[0]);
    const double n = length(normal);
    if (!(n > 0)) return best;
    normal = (1 / n) * normal;
    const Vec3 foot = dot(piece.corner[0], normal) * normal;  // the origin's projection
    for (int k = 0; k < piece.count; ++k) {
        const Vec3 a = piece.corner[k], b = piece.corner[(k + 1) % piece.count];
        if (dot(cross(b - a, foot - a), normal) < 0) return best;
    }
    return std::min(best, std::abs(dot(piece.corner[0], normal)));
}

// min over the triangle (corners relative to p, already reversed if asked)
// of the gauge: per octant the piece in it, scaled to Euclidean.
double triangleGauge(const Vec3 corner[3], const OctantBody& body) {
    double best = INFINITY;
    for (int octant = 0; octant < 8; ++octant) {
        const double sign[3] = {(octant & 1) ? 1.0 : -1.0, (octant & 2) ? 1.0 : -1.0,
                                (octant & 4) ? 1.0 : -1.0};
        // Skip octants the triangle's box misses.
        bool reaches = true;
        for (int i = 0; i < 3 && reaches; ++i) {
            double most = -INFINITY;
            for (int k = 0; k < 3; ++k) most = std::max(most, sign[i] * component(corner[k], i));
            reaches = most >= 0;
        }
        if (!reaches) continue;
        Piece piece;
        piece.count = 3;
        for (int k = 0; k < 3; ++k) piece.corner[k] = corner[k];
        for (int i = 0; i < 3 && piece.count > 0; ++i) piece = clip(piece, i, sign[i]);
        if (piece.count == 0) continue;
        const Vec3 scale{1 / body.axis(0, sign[0]), 1 / body.axis(1, sign[1]),
                         1 / body.axis(2, sign[2])};
        for (int k = 0; k < piece.count; ++k) {
            const Vec3 c = piece.corner[k];
            piece.corner[k] = {c.x * scale.x, c.y * scale.y, c.z * scale.z};
        }
        best = std::min(best, distanceToOrigin(piece));
    }
    return best;
}

// The smallest gauge of v = p − q (or q − p when reversed) over the points
// q of `box`: exact, as both the box and the gauge's square are sums over
// the axes.
double boxGauge(const Box3& box, Vec3 p, const OctantBody& body, bool reversed) {
    double sum = 0;
    for (int i = 0; i < 3; ++i) {
        const double c = component(p, i), lo = component(box.lo, i), hi = component(box.hi, i);
        // v's component runs over [c − hi, c − lo], or its negative.
        double from = c - hi, to = c - lo;
        if (reversed) {
            from = lo - c;
            to = hi - c;
        }
        if (from <= 0 && to >= 0) continue;
        const double nearest = from > 0 ? from : to;
        const double scaled = nearest / body.axis(i, nearest);
        sum += scaled * scaled;
    }
    return std::sqrt(sum);
}

}  // namespace

double OctantBody::largest() const {
    return *std::max_element(mm.begin(), mm.end());
}

double OctantBody::smallest() const {
    return *std::min_element(mm.begin(), mm.end());
}

double OctantBody::gauge(Vec3 v) const {
    const double x = v.x / axis(0, v.x), y = v.y / axis(1, v.y), z = v.z / axis(2, v.z);
    return std::sqrt(x * x + y * y + z * z);
}

double OctantBody::largestInPlane(Vec3 u, Vec3 v) const {
    // The gauge of w(t) = cos t·u + sin t·v is smooth within each octant and
    // continuous across them; a fine sweep with a margin for what falls
    // between two samples (its change per radian is at most the largest
    // gauge of a unit vector, 1/smallest).
    constexpr int kSteps = 3600;
    double most = 0;
    for (int k = 0; k < kSteps; ++k) {
        const double t = 2 * M_PI * k / kSteps;
        most = std::max(most, gauge(std::cos(t) * u + std::sin(t) * v));
    }
    return most + (M_PI / kSteps) / smallest();
}

double smallestGauge(const TriangleBvh& bvh, Vec3 p, const OctantBody& body, bool reversed,
                     double cap) {
    const TriangleSoup& soup = bvh.soup();
    const std::vector<TriangleBvh::Node>& nodes = bvh.nodes();
    double best = cap;
    if (nodes.empty()) return best;
    // A node or triangle whose box's gauge is not below best cannot beat it.
    std::vector<int> stack{0};
    while (!stack.empty()) {
        const TriangleBvh::Node& node = nodes[std::size_t(stack.back())];
        stack.pop_back();
        if (boxGauge(node.box, p, body, reversed) >= best) continue;
        if (node.left >= 0) {
            // Nearer child last, so it is searched first and lowers `best`
            // before the farther one is looked at.
            const double left = boxGauge(nodes[std::size_t(node.left)].box, p, body, reversed),
                         right = boxGauge(nodes[std::size_t(node.right)].box, p, body, reversed);
            stack.push_back(left < right ? node.right : node.left);
            stack.push_back(left < right ? node.left : node.right);
            continue;
        }
        for (std::size_t k = 0; k < node.count; ++k) {
            const auto& t = soup.triangles[bvh.order()[node.first + k]];
            const Vec3 a = soup.points[t[0]], b = soup.points[t[1]], c = soup.points[t[2]];
            Box3 box;
            box.add(a);
            box.add(b);
            box.add(c);
            if (boxGauge(box, p, body, reversed) >= best) continue;
            const double s = reversed ? 1 : -1;  // corners as p − q, or q − p
            const Vec3 corner[3] = {s * (a - p), s * (b - p), s * (c - p)};
            best = std::min(best, triangleGauge(corner, body));
        }
    }
    return best;
}

}  // namespace dfrecon
