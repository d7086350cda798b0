// A bound for a piece of a triangle that lies over two adjacent triangles
// of a surface, A and B, and is not within the limit of either alone
// (deviationBound's corner rule needs one triangle for the whole piece).
// Cut the piece by the plane through their shared edge that bisects the
// angle between them: each part is convex, so if every corner of the part on
// A's side is within the limit of A, the whole part is (the distance to a
// triangle is convex), and likewise for B. Written once as plain C:
// kernels/collapse_bound.cl includes it as OpenCL C after closest_point.cl,
// simplify/BoundRules.hpp as C++ with REAL = double and REAL4 = Vec3, so
// the batch and its reference take the same steps with the same roundings
// (simplify/Coverage also cuts pieces of the original with its plane). Needs
// point_triangle_distance, dot3, cross and sqrt; STRADDLE_FN is the function specifier.

#ifndef STRADDLE_FN
#define STRADDLE_FN inline
#endif

#ifdef __OPENCL_VERSION__
#pragma OPENCL FP_CONTRACT OFF
#endif

// The larger of a and b, as fmax without its NaN rules (the same in C and C++).
STRADDLE_FN REAL straddle_larger(REAL a, REAL b) {
    return a > b ? a : b;
}

// Keeps the part of polygon in[0 .. count) where sign · (x − e)·m ≥ 0 in
// out (room for count + 1); returns its corner count. Corners on the plane
// are kept, and the points where edges cross it are made as
// straddle_distance makes them, so the parts on either side share them.
STRADDLE_FN int clip_polygon(const REAL4* in, int count, REAL4 e, REAL4 m, REAL sign, REAL4* out) {
    int kept = 0;
    for (int i = 0; i < count; ++i) {
        const int j = i + 1 == count ? 0 : i + 1;
        const REAL hi = sign * dot3(in[i] - e, m), hj = sign * dot3(in[j] - e, m);
        if (hi >= 0) out[kept++] = in[i];
        if ((hi > 0 && hj < 0) || (hi < 0 && hj > 0))
            out[kept++] = in[i] + (hi / (hi - hj)) * (in[j] - in[i]);
    }
    return kept;
}

// The plane that cuts space between surface triangles a (corners a0 a1
// a2, vertex ids ia0 ia1 ia2) and b: through their shared edge, bisecting
// the angle between them, as a point *e on it and a normal *m towards a's
// side. 0 when a and b share no edge or fold onto each other (then nothing
// is written), else 1. O(1).
STRADDLE_FN int straddle_plane(REAL4 a0, REAL4 a1, REAL4 a2, int ia0, int ia1, int ia2, REAL4 b0,
                               REAL4 b1, REAL4 b2, int ib0, int ib1, int ib2, REAL4* e, REAL4* m) {
    const REAL4 a[3] = {a0, a1, a2};
    const int ia[3] = {ia0, ia1, ia2};
    int shared = -1;  // edge shared of a: corners shared and shared + 1
    for (int k = 0; k < 3; ++k) {
        const int u = ia[k], v = ia[(k + 1) % 3];
        const bool hasU = u == ib0 || u == ib1 || u == ib2;
        const bool hasV = v == ib0 || v == ib1 || v == ib2;
        if (hasU && hasV) shared = k;
    }
    if (shared < 0) return 0;
    const REAL4 e0 = a[shared], e1 = a[(shared + 1) % 3], apex = a[(shared + 2) % 3];
    const REAL4 na = cross(a1 - a0, a2 - a0), nb = cross(b1 - b0, b2 - b0);
    const REAL la = sqrt(dot3(na, na)), lb = sqrt(dot3(nb, nb));
    if (!(la > 0) || !(lb > 0)) return 0;
    const REAL4 normals = ((REAL)1 / la) * na + ((REAL)1 / lb) * nb;
    REAL4 normal = cross(e1 - e0, normals);
    const REAL side = dot3(apex - e0, normal);
    if (!(side != 0)) return 0;                // folded flat, or degenerate
    if (side < 0) normal = (REAL)-1 * normal;  // a's apex on the positive side
    *e = e0;
    *m = normal;
    return 1;
}

// For piece p0 p1 p2 and surface triangles a and b cut by straddle_plane's
// plane (e, m): the largest distance from a corner of the part on a's side
// to a, and of the other part to b (corners on the plane and the points
// where the piece's edges cross it count for both: clip_polygon's parts).
// An upper bound of the distance from the piece to a ∪ b. O(1): at most
// nine point–triangle distances.
STRADDLE_FN REAL straddle_distance_across(REAL4 p0, REAL4 p1, REAL4 p2, REAL4 a0, REAL4 a1,
                                          REAL4 a2, REAL4 b0, REAL4 b1, REAL4 b2, REAL4 e0,
                                          REAL4 m) {
    const REAL4 p[3] = {p0, p1, p2};
    REAL h[3];
    for (int k = 0; k < 3; ++k) h[k] = dot3(p[k] - e0, m);
    REAL worst = 0;
    for (int k = 0; k < 3; ++k) {
        if (h[k] >= 0) worst = straddle_larger(worst, point_triangle_distance(p[k], a0, a1, a2));
        if (h[k] <= 0) worst = straddle_larger(worst, point_triangle_distance(p[k], b0, b1, b2));
        const int j = (k + 1) % 3;
        if ((h[k] > 0 && h[j] < 0) || (h[k] < 0 && h[j] > 0)) {
            const REAL4 x = p[k] + (h[k] / (h[k] - h[j])) * (p[j] - p[k]);
            worst = straddle_larger(worst, point_triangle_distance(x, a0, a1, a2));
            worst = straddle_larger(worst, point_triangle_distance(x, b0, b1, b2));
        }
    }
    return worst;
}

// straddle_distance_across over straddle_plane's plane; INFINITY when a and
// b share no edge or fold onto each other.
STRADDLE_FN REAL straddle_distance(REAL4 p0, REAL4 p1, REAL4 p2, REAL4 a0, REAL4 a1, REAL4 a2,
                                   int ia0, int ia1, int ia2, REAL4 b0, REAL4 b1, REAL4 b2, int ib0,
                                   int ib1, int ib2) {
    REAL4 e0 = a0, m = a0;
    if (!straddle_plane(a0, a1, a2, ia0, ia1, ia2, b0, b1, b2, ib0, ib1, ib2, &e0, &m))
        return INFINITY;
    return straddle_distance_across(p0, p1, p2, a0, a1, a2, b0, b1, b2, e0, m);
}
