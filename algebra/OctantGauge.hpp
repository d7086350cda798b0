#pragma once
// Margins that differ between the two senses of an axis (5 mm everywhere
// but 3 mm posterior), as planning systems offer them: the Minkowski sum
// with a body made of eight ellipsoid octants, each with the semi-axes of
// its three directions. That body is convex, and its gauge
//   g(v) = sqrt(Σ_i (v_i / a_i(sign v_i))²)
// (≤ 1 exactly inside it) measures how far a point is "in margins" from
// another. A point p lies in the grown solid when some point q of the ROI
// has g(p − q) ≤ 1, in the shrunk one when every point q of its boundary
// has g(q − p) > 1. This file finds min_q g over a triangle surface
// exactly: within each octant around p the gauge is a Euclidean distance
// after scaling by that octant's axes, so each triangle is cut by the three
// coordinate planes through p, each piece scaled, and its distance to p
// measured.
#include <array>

#include "geometry/TriangleBvh.hpp"

namespace dfrecon {

/// Semi-axes (mm, > 0) per patient direction, as planning systems list
/// margins: right (−x), left (+x), anterior (−y), posterior (+y), superior
/// (+z), inferior (−z) in DICOM's LPS.
struct OctantBody {
    std::array<double, 6> mm{1, 1, 1, 1, 1, 1};

    /// The semi-axis along axis i (0 x, 1 y, 2 z) on the side of `sign`.
    double axis(int i, double sign) const {
        static constexpr int kNegative[3] = {0, 2, 5}, kPositive[3] = {1, 3, 4};
        return mm[std::size_t(sign < 0 ? kNegative[i] : kPositive[i])];
    }
    double largest() const;
    double smallest() const;
    /// The gauge g(v). O(1).
    double gauge(Vec3 v) const;
    /// The largest gauge of a unit vector in the plane of unit vectors u,
    /// v: how fast min_q g(p − q) can change per mm along that plane. O(1).
    double largestInPlane(Vec3 u, Vec3 v) const;
};

/// min over the points q of the triangles of `bvh` of body.gauge(p − q)
/// (or of body.gauge(q − p) when `reversed`), or `cap` when that is not
/// less than `cap`. Exact up to rounding. O(log T + triangles within
/// cap · body.largest() of p).
double smallestGauge(const TriangleBvh& bvh, Vec3 p, const OctantBody& body, bool reversed,
                     double cap);

}  // namespace dfrecon
