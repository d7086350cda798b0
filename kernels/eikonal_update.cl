// The local eikonal update on one triangle, the single piece of arithmetic
// both geodesic solvers share: segment/LocalUpdate.hpp includes this file
// into C++ (fast marching, and the C++ reference of the fast iterative
// method), and kernels/eikonal_fim.cl is built after it. One text, so the
// solvers compute the same thing step for step. Plain C: needs REAL
// (double or float) defined; EIKONAL_FN is the function specifier.

#ifndef EIKONAL_FN
#define EIKONAL_FN inline
#endif

#ifdef __OPENCL_VERSION__
// No fused multiply-adds: the C++ build has none either (ISO C++ mode,
// -ffp-contract=off), so device and reference round alike.
#pragma OPENCL FP_CONTRACT OFF
#endif

#define EIKONAL_VIA_A 0     // the front reached C along edge CA
#define EIKONAL_VIA_B 1     // along edge CB
#define EIKONAL_VIA_FACE 2  // across the triangle, from a point of segment AB

// Arrival time at corner C of the triangle (C; A, B) whose corners A and B
// have arrival times ta and tb, for the eikonal equation |grad T| = slowness
// (slowness = 1 / speed, taken at C for the whole triangle). la = |CA|,
// lb = |CB|, cos_c = cosine of the angle at C: the triangle lives in its own
// plane, so an unfolded ("virtual") triangle works as well as a real one.
//
// Across the face (only when across_face is set: both times known and from
// the same front, see eikonal_upwind_label): T
// linear on the triangle with |grad T| = slowness gives a quadratic in T(C);
// its larger root counts only if the characteristic reaching C comes from
// inside the angle at C (upwind condition), i.e. from a point of segment AB.
// Otherwise, or when it is slower, the front comes along an edge
// (Dijkstra-like): ta + la·slowness or tb + lb·slowness.
//
// Writes which way won to *upwind and, for EIKONAL_VIA_FACE, where the
// characteristic crosses AB to *weight_b (0 at A, 1 at B; 0 or 1 for the
// edges). Infinite ta or tb are allowed (that edge then never wins) as long
// as across_face is 0.
EIKONAL_FN REAL eikonal_triangle_update(REAL ta, REAL tb, REAL la, REAL lb, REAL cos_c,
                                        REAL slowness, int across_face, int* upwind,
                                        REAL* weight_b) {
    REAL best = ta + la * slowness;
    int via = EIKONAL_VIA_A;
    REAL weight = 0;
    const REAL along_b = tb + lb * slowness;
    if (along_b < best) {
        best = along_b;
        via = EIKONAL_VIA_B;
        weight = 1;
    }
    if (across_face) {
        // With E = [CA CB] and G = E^T E, the linear T has |grad T|^2 =
        // δ^T G^-1 δ for δ = (ta - T(C), tb - T(C)). Measuring times from ta
        // (u = tb - ta, d = T(C) - ta) keeps the quadratic free of the
        // cancellation that large times would cause; its discriminant
        // simplifies to det(G)·(|AB|^2 slowness^2 - u^2).
        const REAL u = tb - ta;
        const REAL ab = la * lb * cos_c;
        const REAL qa = lb * lb - ab, qb = la * la - ab;  // adj(G)·(1, 1)
        const REAL opposite2 = qa + qb;                   // |AB|^2
        const REAL det = la * la * lb * lb * (1 - cos_c * cos_c);
        const REAL reach = opposite2 * slowness * slowness - u * u;
        if (det > 0 && reach > 0) {
            const REAL d = (qb * u + sqrt(det * reach)) / opposite2;
            // adj(G)·(T(C) - ta, T(C) - tb): the characteristic's direction
            // in the basis (CA, CB), up to a positive factor.
            const REAL mu_a = qa * d + ab * u, mu_b = qb * d - la * la * u;
            if (mu_a >= 0 && mu_b >= 0 && mu_a + mu_b > 0 && ta + d < best) {
                best = ta + d;
                via = EIKONAL_VIA_FACE;
                weight = mu_b / (mu_a + mu_b);
            }
        }
    }
    *upwind = via;
    *weight_b = weight;
    return best;
}

// The label a vertex takes from an update: that of the corner the front came
// from. Callers combine corners across a face only when they carry the same
// label: where fronts of different sources collide, a plane through one
// corner of each would describe the collision point moving along the
// border, faster than either front (two fronts meeting at 90° give a plane
// wave of speed √2 along the diagonal), and distances near the farthest
// points from all sources would come out far too small.
EIKONAL_FN int eikonal_upwind_label(int upwind, int label_a, int label_b) {
    return upwind == EIKONAL_VIA_B ? label_b : label_a;
}
