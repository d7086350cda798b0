// The nearest triangle of a surface through a bounding volume hierarchy,
// laid out as field/DeviceSurface uploads it: the 3D member of the
// closest-primitive family (closest_segment_2d.cl is the planar one), the
// same search as TriangleBvh::nearestWithin in geometry/TriangleBvh.cpp.
// Needs real.cl and closest_point.cl first; vectors are REAL4 with w unused.
// No fused multiply-adds: the C++ reference (built without contraction)
// must see the same roundings, or near-ties pick different triangles.
#pragma OPENCL FP_CONTRACT OFF
#ifndef BVH_STACK
#define BVH_STACK 64
#endif

// Squared distance from p to the box [lo, hi] (0 inside).
inline REAL box_distance2(REAL4 p, REAL4 lo, REAL4 hi) {
    const REAL4 d = fmax(fmax(lo - p, p - hi), (REAL4)(0));
    return dot3(d, d);
}

// The surface's triangles and the hierarchy over them, as
// field/DeviceSurface.hpp lays them out. Node k has box
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
