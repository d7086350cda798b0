#pragma once
// Axis-aligned boxes in space: the bounds of triangles and of hierarchy nodes.
#include <algorithm>
#include <cmath>

#include "geometry/Vec3.hpp"

namespace dfrecon {

struct Box3 {
    Vec3 lo{INFINITY, INFINITY, INFINITY}, hi{-INFINITY, -INFINITY, -INFINITY};
    void add(Vec3 p) {
        lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
        hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
    }
    void add(const Box3& b) {
        add(b.lo);
        add(b.hi);
    }
    bool overlaps(const Box3& b) const {
        return lo.x <= b.hi.x && b.lo.x <= hi.x && lo.y <= b.hi.y && b.lo.y <= hi.y &&
               lo.z <= b.hi.z && b.lo.z <= hi.z;
    }
    /// Squared distance from p to the box (0 inside).
    double distance2(Vec3 p) const {
        // Plain comparisons: this is the inner loop of every nearest query.
        auto gap = [](double l, double h, double v) {
            return v < l ? l - v : (v > h ? v - h : 0.0);
        };
        const double dx = gap(lo.x, hi.x, p.x), dy = gap(lo.y, hi.y, p.y),
                     dz = gap(lo.z, hi.z, p.z);
        return dx * dx + dy * dy + dz * dz;
    }
};

}  // namespace dfrecon
