// Surface distance maps (paper §3-4): for each sample point on an object,
// the closest primitive (triangle, edge or vertex) of the other objects, its
// object, the signed distance and the closest point. The same steps as
// closestPrimitivesReference in sdm/ClosestPrimitives.cpp. Needs
// closest_triangle_3d.cl and tangent_bound.cl first.
//
// Two passes. source_candidates, one work-item per source triangle (a
// triangle that holds samples), lists the target triangles that can be
// nearest to some point of it: tangent bounds (tangent_bound.cl) rule out
// whole subtrees and triangles, and far from the targets they are nearly
// exact, so a list holds a handful where a search per sample would measure
// about a hundred. closest_primitive, one work-item per sample, then
// measures only the listed triangles whose bound at the sample does not
// rule them out; a source with more than `capacity` candidates, or a sample
// off its triangle, searches the hierarchies instead.
//
// Both kernels take the same leading arguments (the source triangles, the
// scene, the lists), then their own, then the query and the chunk they run
// as one QueryParams.
//
// The scene's objects share the Surface arrays; object o's hierarchy starts
// at node object_root[o] (< 0: empty), and triangles[t].w is t's object.
// pseudo_normals[7 t + f] is the outward pseudo-normal of feature f of
// triangle t (FEATURE_* order); distances to objects with object_closed set
// are negative inside them.
#pragma OPENCL FP_CONTRACT OFF

inline bool is_candidate(uint object, uint own, int target) {
    return object != own && (target < 0 || object == (uint)target);
}

// The scalars of both kernels, one argument: the host's twin (of the same
// name in field/ClosestPrimitives.cpp) must lay them out alike with REAL
// double or float, so the REALs come first and the 32-bit integers after
// them, padded to a multiple of 8 bytes, leaving neither compiler any
// padding to add.
typedef struct {
    REAL max_distance2;             // the band, squared
    REAL max_distance;              // the band (source_candidates)
    REAL slack;                     // the culling's rounding allowance
    uint object_count;              // the scene's objects
    int target;                     // -1: every other object
    uint capacity;                  // entries of a source's list
    uint source_first;              // the chunk's first source
    uint source_count;              // its sources (source_candidates)
    uint sample_first, sample_end;  // its samples (closest_primitive)
    uint padding;
} QueryParams;

// Sources run in chunks (the lists take capacity entries each): work-item i
// takes source s = source_first + i, with corners source_corners[3 s ..
// 3 s + 2] of a triangle of object source_object[s], and writes, at i of
// the chunk's arrays, the nearest triangle to its centre (UINT_MAX: none
// within the band) and its candidates, candidates[i * capacity + k] with
// bounds[...] (the tangent bound at the centre: normal in xyz, offset in
// w), k < candidate_count[i]; a count of capacity + 1 means more.
// O(depth + visited nodes) per source.
__kernel void source_candidates(__global const REAL4* source_corners,
                                __global const uint* source_object, __global const REAL4* points,
                                __global const int4* triangles, __global const REAL4* node_lo,
                                __global const REAL4* node_hi, __global const int4* node_links,
                                __global const uint* order, __global const REAL4* balls,
                                __global const int* object_root, __global uint* candidates,
                                __global REAL4* bounds, __global uint* candidate_count,
                                __global uint* centre_nearest, const QueryParams query) {
    const uint object_count = query.object_count, capacity = query.capacity;
    const int target = query.target;
    const REAL max_distance2 = query.max_distance2, max_distance = query.max_distance,
               slack = query.slack;
    const uint source_first = query.source_first, source_count = query.source_count;
    const uint i = get_global_id(0);
    if (i >= source_count) return;
    const uint s = source_first + i;
    const Surface surface = {points, triangles, node_lo, node_hi, node_links, order, balls};
    const REAL4 v0 = source_corners[3 * s], v1 = source_corners[3 * s + 1],
                v2 = source_corners[3 * s + 2];
    const REAL4 c = ((REAL)1 / 3) * (v0 + v1 + v2);
    const uint own = source_object[s];

    REAL best2 = max_distance2;
    uint t1 = UINT_MAX;
    for (uint o = 0; o < object_count; ++o)
        if (is_candidate(o, own, target) && object_root[o] >= 0)
            search_nearest_triangle(&surface, object_root[o], c, &best2, &t1);
    centre_nearest[i] = t1;
    REAL u0 = INFINITY, u1 = INFINITY, u2 = INFINITY;
    if (t1 != UINT_MAX) {
        u0 = sqrt(triangle_distance2(&surface, t1, v0));
        u1 = sqrt(triangle_distance2(&surface, t1, v1));
        u2 = sqrt(triangle_distance2(&surface, t1, v2));
    }

    __global uint* list = candidates + (size_t)i * capacity;
    __global REAL4* list_bounds = bounds + (size_t)i * capacity;
    uint n = 0;
    for (uint o = 0; o < object_count && n <= capacity; ++o) {
        if (!is_candidate(o, own, target) || object_root[o] < 0) continue;
        // Depth first, left before right, as the reference walks.
        int stack[BVH_STACK];
        int size = 0;
        stack[size++] = object_root[o];
        while (size > 0 && n <= capacity) {
            const int node = stack[--size];
            if (tangent_excludes(tangent_bound_of_box(c, node_lo[node], node_hi[node]), v0, v1, v2,
                                 u0, u1, u2, max_distance, slack))
                continue;
            const int4 link = node_links[node];
            if (link.x >= 0) {
                stack[size++] = link.y;
                stack[size++] = link.x;
                continue;
            }
            for (int k = 0; k < link.w && n <= capacity; ++k) {
                const uint t = order[link.z + k];
                const int4 tri = triangles[t];
                const TangentBound bound = tangent_bound(
                    c, closest_point_on_triangle(c, points[tri.x], points[tri.y], points[tri.z]));
                if (tangent_excludes(bound, v0, v1, v2, u0, u1, u2, max_distance, slack)) continue;
                if (n < capacity) {
                    list[n] = t;
                    REAL4 b = bound.normal;
                    b.w = bound.offset;
                    list_bounds[n] = b;
                }
                ++n;
            }
        }
    }
    candidate_count[i] = n;
}

// Writes sample k's answer for nearest triangle t (UINT_MAX: none within
// the band): the closest point, its feature, and the distance, negative
// inside a closed object by the feature's pseudo-normal. Both kernels end
// with it.
inline void write_answer(__global const REAL4* points, __global const int4* triangles,
                         __global const REAL4* pseudo_normals, __global const uchar* object_closed,
                         REAL4 p, uint t, uint k, __global REAL* distance, __global uint* nearest,
                         __global uchar* feature, __global REAL4* closest) {
    nearest[k] = t;
    if (t == UINT_MAX) {
        distance[k] = INFINITY;
        feature[k] = FEATURE_FACE;
        closest[k] = p;
        return;
    }
    const int4 tri = triangles[t];
    int f;
    const REAL4 q =
        closest_point_on_triangle_feature(p, points[tri.x], points[tri.y], points[tri.z], &f);
    const REAL4 away = p - q;
    REAL d = sqrt(dot3(away, away));
    if (object_closed[tri.w] && dot3(away, pseudo_normals[7 * t + f]) < 0) d = -d;
    distance[k] = d;
    feature[k] = (uchar)f;
    closest[k] = q;
}

// Samples sorted by source, so a chunk's sources serve a run of them:
// work-item i takes sample k = sample_first + i (k < sample_end), whose
// source sample_source[k] is source_first + its index in the chunk's lists.
__kernel void closest_primitive(
    __global const REAL4* source_corners, __global const uint* source_object,
    __global const REAL4* points, __global const int4* triangles, __global const REAL4* node_lo,
    __global const REAL4* node_hi, __global const int4* node_links, __global const uint* order,
    __global const REAL4* balls, __global const int* object_root, __global const uint* candidates,
    __global const REAL4* bounds, __global const uint* candidate_count,
    __global const uint* centre_nearest, __global const REAL4* pseudo_normals,
    __global const uchar* object_closed, __global const REAL4* sample_points,
    __global const uint* sample_source, __global REAL* distance, __global uint* nearest,
    __global uchar* feature, __global REAL4* closest, const QueryParams query) {
    const uint object_count = query.object_count, capacity = query.capacity;
    const int target = query.target;
    const REAL max_distance2 = query.max_distance2, slack = query.slack;
    const uint source_first = query.source_first, sample_first = query.sample_first,
               sample_end = query.sample_end;
    const uint k = sample_first + get_global_id(0);
    if (k >= sample_end) return;
    const Surface surface = {points, triangles, node_lo, node_hi, node_links, order, balls};
    const REAL4 p = sample_points[k];
    const uint s = sample_source[k], in_chunk = s - source_first;
    const uint own = source_object[s];
    REAL best2 = max_distance2;
    uint t = UINT_MAX;
    const uint hint = centre_nearest[in_chunk];
    if (hint != UINT_MAX && is_candidate((uint)triangles[hint].w, own, target)) {
        const REAL d2 = triangle_distance2(&surface, hint, p);
        if (d2 < best2) {
            best2 = d2;
            t = hint;
        }
    }
    const uint listed = candidate_count[in_chunk];
    const REAL4 a = source_corners[3 * s], b = source_corners[3 * s + 1],
                c = source_corners[3 * s + 2];
    const REAL4 off = p - closest_point_on_triangle(p, a, b, c);
    if (listed <= capacity && dot3(off, off) <= (REAL)0.25 * slack * slack) {
        __global const uint* list = candidates + (size_t)in_chunk * capacity;
        __global const REAL4* list_bounds = bounds + (size_t)in_chunk * capacity;
        for (uint i = 0; i < listed; ++i) {
            TangentBound bound;
            bound.normal = list_bounds[i];
            bound.offset = list_bounds[i].w;
            const REAL lower = tangent_lower(bound, p) - slack;
            if (lower > 0 && lower * lower >= best2) continue;
            const REAL d2 = triangle_distance2(&surface, list[i], p);
            if (d2 < best2) {
                best2 = d2;
                t = list[i];
            }
        }
    } else {
        for (uint o = 0; o < object_count; ++o)
            if (is_candidate(o, own, target) && object_root[o] >= 0)
                search_nearest_triangle(&surface, object_root[o], p, &best2, &t);
    }
    write_answer(points, triangles, pseudo_normals, object_closed, p, t, k, distance, nearest,
                 feature, closest);
}

// Points anywhere in space (a grid, the planes of a margin), not on an
// object: work-item i takes point sample_first + i (< sample_end) and
// searches the hierarchies of the candidate objects (every object, or
// query.target) for its closest primitive, signed as closest_primitive
// signs it. The same answers as closestPrimitivesAtReference in
// field/ClosestPrimitives.cpp. O(log T) per point typically.
__kernel void closest_primitive_at(__global const REAL4* points, __global const int4* triangles,
                                   __global const REAL4* node_lo, __global const REAL4* node_hi,
                                   __global const int4* node_links, __global const uint* order,
                                   __global const REAL4* balls, __global const int* object_root,
                                   __global const REAL4* pseudo_normals,
                                   __global const uchar* object_closed,
                                   __global const REAL4* query_points, __global REAL* distance,
                                   __global uint* nearest, __global uchar* feature,
                                   __global REAL4* closest, const QueryParams query) {
    const uint k = query.sample_first + get_global_id(0);
    if (k >= query.sample_end) return;
    const Surface surface = {points, triangles, node_lo, node_hi, node_links, order, balls};
    const REAL4 p = query_points[k];
    REAL best2 = query.max_distance2;
    uint t = UINT_MAX;
    for (uint o = 0; o < query.object_count; ++o)
        if ((query.target < 0 || o == (uint)query.target) && object_root[o] >= 0)
            search_nearest_triangle(&surface, object_root[o], p, &best2, &t);
    write_answer(points, triangles, pseudo_normals, object_closed, p, t, k, distance, nearest,
                 feature, closest);
}
