// A bound for a piece of a triangle that lies over the fan of triangles
// around one vertex v of a surface, where no one triangle or pair of them
// settles it (deviationBound's corner and straddle rules). Planes through
// v, the fan's axis and each neighbour cut space into sectors, one per
// triangle of the fan; geometry/VertexFans keeps only fans whose sectors
// tile space and are convex, and gives the planes' normals. The part of
// the piece in a sector is convex too, so if every corner of the part is
// within the limit of that sector's triangle, the whole part is (the
// distance to a triangle is convex). Written once as plain C, like
// straddle_bound.cl: kernels/collapse_bound.cl includes it as OpenCL C,
// simplify/BoundRules.hpp as C++ with REAL = double and REAL4 = Vec3,
// so the batch and its reference take the same steps with the same
// roundings. Needs point_triangle_distance, dot3 and clip_polygon
// (straddle_bound.cl); FAN_FN is the function specifier.

#ifndef FAN_FN
#define FAN_FN inline
#endif
#ifndef FAN_MAX
#define FAN_MAX 16  // neighbours a fan may have: VertexFans::kMaxNeighbours
#endif

#ifdef __OPENCL_VERSION__
#pragma OPENCL FP_CONTRACT OFF
#endif

// For piece p0 p1 p2 and the fan of vertex v (neighbours ring[0 .. m),
// sector normals normals[0 .. m), as VertexFans gives them): the largest
// distance from a corner of the piece's part in a sector to that sector's
// triangle, an upper bound of the distance from the piece to the fan.
// INFINITY for an empty fan; a value over `limit` as soon as one corner is.
// O(m) point–triangle distances.
FAN_FN REAL fan_distance(REAL4 p0, REAL4 p1, REAL4 p2, REAL4 v, const REAL4* ring,
                         const REAL4* normals, int m, REAL limit) {
    if (m < 3) return INFINITY;
    const REAL4 piece[3] = {p0, p1, p2};
    // Sides of the corners to every plane, once: they find each corner's
    // sector and the sectors the piece misses.
    REAL side[3][FAN_MAX];
    for (int i = 0; i < m; ++i)
        for (int k = 0; k < 3; ++k) side[k][i] = dot3(piece[k] - v, normals[i]);
    // A corner far from its own sector's triangle settles nothing: most
    // pieces that fail, fail here, before any clipping.
    for (int k = 0; k < 3; ++k)
        for (int i = 0; i < m; ++i) {
            const int j = i + 1 == m ? 0 : i + 1;
            if (side[k][i] >= 0 && side[k][j] <= 0) {
                const REAL d = point_triangle_distance(piece[k], v, ring[i], ring[j]);
                if (d > limit) return d;
                break;
            }
        }
    REAL worst = 0;
    for (int i = 0; i < m; ++i) {
        const int j = i + 1 == m ? 0 : i + 1;
        // Wholly behind either plane: no part in this sector.
        if ((side[0][i] < 0 && side[1][i] < 0 && side[2][i] < 0) ||
            (side[0][j] > 0 && side[1][j] > 0 && side[2][j] > 0))
            continue;
        REAL4 inside[4], part[5];
        const int inFirst = clip_polygon(piece, 3, v, normals[i], (REAL)1, inside);
        const int inPart = clip_polygon(inside, inFirst, v, normals[j], (REAL)-1, part);
        for (int k = 0; k < inPart; ++k) {
            const REAL d = point_triangle_distance(part[k], v, ring[i], ring[j]);
            if (d > worst) worst = d;
        }
        if (worst > limit) return worst;
    }
    return worst;
}
