// Closest points on segments and triangles: the arithmetic at the heart of
// the closest-primitive family, written once. The kernels include it as
// OpenCL C (programs list it after real.cl); geometry/ClosestPoint.hpp
// includes the same text as C++ with REAL = double and REAL4 = Vec3, so
// every kernel and its C++ reference take the same steps with the same
// roundings. Plain C: needs REAL and REAL4 (x, y, z used; + - and REAL *
// REAL4 defined) and sqrt and clamp; CLOSEST_FN is the function specifier.

#ifndef CLOSEST_FN
#define CLOSEST_FN inline
#endif

#ifdef __OPENCL_VERSION__
// No fused multiply-adds here: the C++ build has none either, so near-ties
// pick the same primitive on the device and in the reference. The end of the
// file restores the default for the kernels that follow; those that must
// match a C++ reference turn contraction off themselves.
#pragma OPENCL FP_CONTRACT OFF
#endif

CLOSEST_FN REAL dot3(REAL4 a, REAL4 b) {
    return a.x * b.x + a.y * b.y + a.z * b.z;
}

// The parameter in [0, 1] of the point of segment a→b nearest to p, from
// ap = p - a and ab = b - a (0 for a segment of length 0). O(1).
CLOSEST_FN REAL segment_parameter(REAL apx, REAL apy, REAL abx, REAL aby) {
    const REAL len2 = abx * abx + aby * aby;
    return clamp(len2 > 0 ? (apx * abx + apy * aby) / len2 : (REAL)0, (REAL)0, (REAL)1);
}

// Features of a triangle, as TriangleFeature in geometry/ClosestPoint.hpp:
// the corners, the edges' interiors (edge k runs from corner k to k+1), the
// face.
#define FEATURE_VERTEX_A 0
#define FEATURE_VERTEX_B 1
#define FEATURE_VERTEX_C 2
#define FEATURE_EDGE_AB 3
#define FEATURE_EDGE_BC 4
#define FEATURE_EDGE_CA 5
#define FEATURE_FACE 6

// The point of triangle abc nearest to p, and in *feature the feature whose
// Voronoi region holds p (Ericson, Real-Time Collision Detection, 5.1.5):
// exact up to rounding, O(1).
CLOSEST_FN REAL4 closest_point_on_triangle_feature(REAL4 p, REAL4 a, REAL4 b, REAL4 c,
                                                   int* feature) {
    const REAL4 ab = b - a, ac = c - a, ap = p - a;
    const REAL d1 = dot3(ab, ap), d2 = dot3(ac, ap);
    if (d1 <= 0 && d2 <= 0) return *feature = FEATURE_VERTEX_A, a;
    const REAL4 bp = p - b;
    const REAL d3 = dot3(ab, bp), d4 = dot3(ac, bp);
    if (d3 >= 0 && d4 <= d3) return *feature = FEATURE_VERTEX_B, b;
    const REAL vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0) return *feature = FEATURE_EDGE_AB, a + (d1 / (d1 - d3)) * ab;
    const REAL4 cp = p - c;
    const REAL d5 = dot3(ab, cp), d6 = dot3(ac, cp);
    if (d6 >= 0 && d5 <= d6) return *feature = FEATURE_VERTEX_C, c;
    const REAL vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0) return *feature = FEATURE_EDGE_CA, a + (d2 / (d2 - d6)) * ac;
    const REAL va = d3 * d6 - d5 * d4;
    if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
        return *feature = FEATURE_EDGE_BC, b + ((d4 - d3) / ((d4 - d3) + (d5 - d6))) * (c - b);
    const REAL denominator = 1 / (va + vb + vc);
    *feature = FEATURE_FACE;
    return a + (vb * denominator) * ab + (vc * denominator) * ac;
}

CLOSEST_FN REAL4 closest_point_on_triangle(REAL4 p, REAL4 a, REAL4 b, REAL4 c) {
    int feature;
    return closest_point_on_triangle_feature(p, a, b, c, &feature);
}

CLOSEST_FN REAL point_triangle_distance(REAL4 p, REAL4 a, REAL4 b, REAL4 c) {
    const REAL4 d = p - closest_point_on_triangle(p, a, b, c);
    return sqrt(dot3(d, d));
}

#ifdef __OPENCL_VERSION__
#pragma OPENCL FP_CONTRACT DEFAULT
#endif
