#pragma once
// Closest points on segments and triangles, in C++: the text of
// kernels/closest_point.cl compiled as C++ with REAL = double and REAL4 =
// Vec3, so the closest-primitive kernels and their C++ references (the
// triangle hierarchy, the 2D fields' brute force, the verifiers) share one
// implementation (see that file for the method). O(1) each.
#include <algorithm>
#include <cmath>
#include <cstdint>

#include "geometry/Vec3.hpp"

namespace dfrecon {

namespace closest {
using std::clamp;
using std::sqrt;
#define REAL double
#define REAL4 Vec3
#define CLOSEST_FN inline
#include "kernels/closest_point.cl"
#undef CLOSEST_FN
#undef REAL4
#undef REAL
}  // namespace closest

/// The feature of triangle abc whose Voronoi region holds a point: a
/// corner, the interior of an edge (edge k runs from corner k to k+1), or
/// the interior of the face (FEATURE_* of the shared text). Pseudo-normal
/// signs and primitive ids need it.
enum class TriangleFeature : std::uint8_t {
    VertexA = FEATURE_VERTEX_A,
    VertexB = FEATURE_VERTEX_B,
    VertexC = FEATURE_VERTEX_C,
    EdgeAB = FEATURE_EDGE_AB,
    EdgeBC = FEATURE_EDGE_BC,
    EdgeCA = FEATURE_EDGE_CA,
    Face = FEATURE_FACE
};

/// The point of triangle abc nearest to p (Voronoi-region walk, exact up to
/// rounding), and in `feature`, when given, the feature it lies on.
inline Vec3 closestPointOnTriangle(Vec3 p, Vec3 a, Vec3 b, Vec3 c,
                                   TriangleFeature* feature = nullptr) {
    int on = FEATURE_FACE;
    const Vec3 q = closest::closest_point_on_triangle_feature(p, a, b, c, &on);
    if (feature) *feature = TriangleFeature(on);
    return q;
}

/// The distance from p to triangle abc.
inline double pointTriangleDistance(Vec3 p, Vec3 a, Vec3 b, Vec3 c) {
    return closest::point_triangle_distance(p, a, b, c);
}

/// The parameter in [0, 1] of the point of segment (a, b) nearest to p, in
/// the plane, from ap = p - a and ab = b - a (0 for a segment of length 0).
inline double nearestSegmentParameter(double apx, double apy, double abx, double aby) {
    return closest::segment_parameter(apx, apy, abx, aby);
}

}  // namespace dfrecon
