// Lower bounds of the distance to a convex set (a triangle, a box) that stay
// tight far from it, for culling a whole source triangle's samples at once.
// The distance to a convex set K is a convex function of the point, so its
// tangent plane at any point c lies below it everywhere:
//     d(p, K) >= d(c, K) + g . (p - c),   g = (c - q) / |c - q|,
// q the point of K nearest to c (g = 0 where c lies in K). Unlike the
// Lipschitz bound d(c, K) - |p - c|, its error is of second order in
// |p - c| / d(c, K), so for points of a small triangle far from K it is
// nearly exact.
//
// Culling a source triangle v0 v1 v2: take any target triangle t1 and its
// distances u_i = d(v_i, t1). On the source triangle d(., t1) is at most the
// affine interpolation of the u_i (a convex function lies below its chords),
// and a tangent bound is affine, so if the bound exceeds u_i at all three
// corners it exceeds d(p, t1) at every point p of the triangle: nothing
// under it can be strictly nearer than t1 there. Likewise, a bound at least
// `band` at the corners is at least `band` on the whole triangle. `slack`,
// subtracted from every bound, covers rounding and points up to slack / 2
// off the triangle (each side of the comparison moves by at most that).
//
// Written once as plain C: kernels/surface_distance.cl includes it as OpenCL
// C after closest_point.cl, sdm/ClosestPrimitives.cpp as C++ with REAL =
// double and REAL4 = Vec3, so the kernels and their reference take the same
// steps with the same roundings. Needs dot3, sqrt and clamp (as
// closest_point.cl does); TANGENT_FN is the function specifier. O(1) each.

#ifndef TANGENT_FN
#define TANGENT_FN inline
#endif

#ifdef __OPENCL_VERSION__
#pragma OPENCL FP_CONTRACT OFF
#endif

// The lower bound normal . p + offset of d(p, K).
typedef struct {
    REAL4 normal;
    REAL offset;
} TangentBound;

// The tangent bound at c, from q, the point of K nearest to c.
TANGENT_FN TangentBound tangent_bound(REAL4 c, REAL4 q) {
    const REAL4 away = c - q;
    const REAL distance = sqrt(dot3(away, away));
    TangentBound bound;
    bound.normal = distance > 0 ? ((REAL)1 / distance) * away : (REAL)0 * away;
    bound.offset = distance > 0 ? distance - dot3(bound.normal, c) : (REAL)0;
    return bound;
}

TANGENT_FN REAL tangent_lower(TangentBound bound, REAL4 p) {
    return dot3(bound.normal, p) + bound.offset;
}

// The tangent bound at c of the distance to the box [lo, hi].
TANGENT_FN TangentBound tangent_bound_of_box(REAL4 c, REAL4 lo, REAL4 hi) {
    REAL4 q = c;
    q.x = clamp(c.x, lo.x, hi.x);
    q.y = clamp(c.y, lo.y, hi.y);
    q.z = clamp(c.z, lo.z, hi.z);
    return tangent_bound(c, q);
}

// Whether `bound` rules its set out for every point of source triangle
// v0 v1 v2 (and within slack / 2 of it): above the interpolated upper bounds
// u0 u1 u2 of the nearest distance, or at least `band`, at all corners.
TANGENT_FN int tangent_excludes(TangentBound bound, REAL4 v0, REAL4 v1, REAL4 v2, REAL u0, REAL u1,
                                REAL u2, REAL band, REAL slack) {
    const REAL l0 = tangent_lower(bound, v0) - slack, l1 = tangent_lower(bound, v1) - slack,
               l2 = tangent_lower(bound, v2) - slack;
    return (l0 > u0 && l1 > u1 && l2 > u2) || (l0 >= band && l1 >= band && l2 >= band);
}

#ifdef __OPENCL_VERSION__
#pragma OPENCL FP_CONTRACT DEFAULT
#endif
