// Surface distance maps (paper §3-4): for each sample point on an object,
// the closest primitive (triangle, edge or vertex) of the other objects, its
// object, the signed distance and the closest point. One work-item per
// sample; the same steps as closestPrimitivesReference in
// sdm/ClosestPrimitives.cpp. Needs closest_triangle_3d.cl first.
//
// The scene's objects share the Surface arrays; object o's hierarchy starts
// at node object_root[o] (< 0: empty), and triangles[t].w is t's object.
// pseudo_normals[7 t + f] is the outward pseudo-normal of feature f of
// triangle t (FEATURE_* order); distances to objects with object_closed set
// are negative inside them.
__kernel void closest_primitive(
    __global const REAL4* sample_points, __global const uint* sample_object,
    __global const uint4* sample_hint, uint sample_count, __global const REAL4* points,
    __global const int4* triangles, __global const REAL4* node_lo, __global const REAL4* node_hi,
    __global const int4* node_links, __global const uint* order, __global const REAL4* balls,
    __global const int* object_root, uint object_count, __global const REAL4* pseudo_normals,
    __global const uchar* object_closed, int target, REAL max_distance2, __global REAL* distance,
    __global uint* nearest, __global uchar* feature, __global REAL4* closest) {
    const uint k = get_global_id(0);
    if (k >= sample_count) return;
    const Surface surface = {points, triangles, node_lo, node_hi, node_links, order, balls};
    const REAL4 p = sample_points[k];
    const uint own = sample_object[k];
    REAL best2 = max_distance2;
    uint t = UINT_MAX;
    // The hints first (the nearest triangles to the centre and corners of
    // the sample's triangle): a tight bound prunes most of every hierarchy.
    const uint4 hints = sample_hint[k];
    const uint hint[4] = {hints.x, hints.y, hints.z, hints.w};
    for (int h = 0; h < 4; ++h) {
        if (hint[h] == UINT_MAX) continue;
        const uint o = (uint)triangles[hint[h]].w;
        if (o == own || (target >= 0 && o != (uint)target)) continue;
        const REAL d2 = triangle_distance2(&surface, hint[h], p);
        if (d2 < best2) {
            best2 = d2;
            t = hint[h];
        }
    }
    for (uint o = 0; o < object_count; ++o) {
        if (o == own || (target >= 0 && o != (uint)target) || object_root[o] < 0) continue;
        search_nearest_triangle(&surface, object_root[o], p, &best2, &t);
    }
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
