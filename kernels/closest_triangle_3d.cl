// Closest-primitive queries in space: the point of a triangle nearest to a
// point, and the nearest triangle of a surface through a bounding volume
// hierarchy laid out as recon/TriangleBvh exports it. The 3D member of the
// closest-primitive family (closest_segment_2d.cl is the planar one); the
// same Voronoi-region walk as closestPointOnTriangle in recon/TriangleBvh.cpp.
//
// REAL is double when the device has fp64 (the host passes -DREAL=double
// -DREAL_IS_DOUBLE), else float. Vectors are REAL4 with w unused.
#ifndef REAL
#define REAL float
#endif
#define CONCAT(a, b) CONCAT_(a, b)
#define CONCAT_(a, b) a##b
#define REAL4 CONCAT(REAL, 4)
#if defined(REAL_IS_DOUBLE)
#pragma OPENCL EXTENSION cl_khr_fp64 : enable
#endif
// No fused multiply-adds: the C++ reference (built without contraction)
// must see the same roundings, or near-ties pick different triangles.
#pragma OPENCL FP_CONTRACT OFF
#ifndef BVH_STACK
#define BVH_STACK 64
#endif

inline REAL dot3(REAL4 a, REAL4 b) {
    return a.x * b.x + a.y * b.y + a.z * b.z;
}

// Features of a triangle, as TriangleFeature in recon/TriangleBvh.hpp: the
// corners, the edges' interiors (edge k runs from corner k to k+1), the face.
#define FEATURE_VERTEX_A 0
#define FEATURE_VERTEX_B 1
#define FEATURE_VERTEX_C 2
#define FEATURE_EDGE_AB 3
#define FEATURE_EDGE_BC 4
#define FEATURE_EDGE_CA 5
#define FEATURE_FACE 6

REAL4 closest_point_on_triangle_feature(REAL4 p, REAL4 a, REAL4 b, REAL4 c, int* feature) {
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

inline REAL4 closest_point_on_triangle(REAL4 p, REAL4 a, REAL4 b, REAL4 c) {
    int feature;
    return closest_point_on_triangle_feature(p, a, b, c, &feature);
}

inline REAL point_triangle_distance(REAL4 p, REAL4 a, REAL4 b, REAL4 c) {
    const REAL4 d = p - closest_point_on_triangle(p, a, b, c);
    return sqrt(dot3(d, d));
}

// Squared distance from p to the box [lo, hi] (0 inside).
inline REAL box_distance2(REAL4 p, REAL4 lo, REAL4 hi) {
    const REAL4 d = fmax(fmax(lo - p, p - hi), (REAL4)(0));
    return dot3(d, d);
}

// The surface's triangles and the hierarchy over them, as
// recon/TriangleBvhArrays.hpp lays them out. Node k has box
// [node_lo[k], node_hi[k]]; node_links[k] = (left, right, first, count),
// left < 0 for a leaf whose triangles are order[first .. first+count).
// triangles[t] = (a, b, c, tag), balls[t] a ball around it (centre, radius
// in w); several hierarchies may share the arrays,
// each from its own root node, with the tag naming the object.
typedef struct {
    __global const REAL4* points;
    __global const int4* triangles;
    __global const REAL4* node_lo;
    __global const REAL4* node_hi;
    __global const int4* node_links;
    __global const uint* order;
    __global const REAL4* balls;  // per triangle: centroid, radius in w
} Surface;

// Narrows (*best2, *nearest) to the triangles under node `root` that are
// nearer to p than sqrt(*best2); subtrees whose boxes are no nearer are
// skipped, so a good starting bound (a hint) prunes most of the tree.
void search_nearest_triangle(const Surface* s, int root, REAL4 p, REAL* best2, uint* nearest) {
    // Each entry keeps its box's distance, computed once when pushed.
    int stack[BVH_STACK];
    REAL stack_d2[BVH_STACK];
    int size = 0;
    stack[size] = root;
    stack_d2[size++] = box_distance2(p, s->node_lo[root], s->node_hi[root]);
    while (size > 0) {
        --size;
        if (stack_d2[size] >= *best2) continue;
        const int4 link = s->node_links[stack[size]];
        if (link.x < 0) {
            for (int k = 0; k < link.w; ++k) {
                const uint t = s->order[link.z + k];
                // The triangle's ball: a cheap lower bound (TriangleBvh::Ball).
                const REAL4 ball = s->balls[t];
                const REAL4 to_centre = p - ball;
                const REAL reach = sqrt(dot3(to_centre, to_centre)) - ball.w;
                if (reach > 0 && reach * reach >= *best2) continue;
                const int4 tri = s->triangles[t];
                const REAL4 q = closest_point_on_triangle(p, s->points[tri.x], s->points[tri.y],
                                                          s->points[tri.z]);
                const REAL d2 = dot3(p - q, p - q);
                if (d2 < *best2) {
                    *best2 = d2;
                    *nearest = t;
                }
            }
            continue;
        }
        // Nearer child last, so it is searched first.
        const REAL left = box_distance2(p, s->node_lo[link.x], s->node_hi[link.x]);
        const REAL right = box_distance2(p, s->node_lo[link.y], s->node_hi[link.y]);
        const bool left_nearer = left < right;
        stack[size] = left_nearer ? link.y : link.x;
        stack_d2[size++] = left_nearer ? right : left;
        stack[size] = left_nearer ? link.x : link.y;
        stack_d2[size++] = left_nearer ? left : right;
    }
}

// The squared distance from p to triangle t.
inline REAL triangle_distance2(const Surface* s, uint t, REAL4 p) {
    const int4 tri = s->triangles[t];
    const REAL4 q =
        closest_point_on_triangle(p, s->points[tri.x], s->points[tri.y], s->points[tri.z]);
    return dot3(p - q, p - q);
}

// The distance from p to the surface under root 0 and the nearest
// triangle's index. *nearest on entry is a hint (a triangle likely near p,
// or UINT_MAX) that prunes the search from the start, as
// TriangleBvh::nearest's hint does.
REAL nearest_triangle(const Surface* s, REAL4 p, uint* nearest) {
    REAL best2 = *nearest != UINT_MAX ? triangle_distance2(s, *nearest, p) : INFINITY;
    search_nearest_triangle(s, 0, p, &best2, nearest);
    return sqrt(best2);
}
