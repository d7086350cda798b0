// Initial deviation bounds of the error-bounded edge collapse (paper §6.2),
// one work-item per halfedge of the unchanged mesh: the same value as
// surfaceDeviation in simplify/CollapseBound.cpp — the largest
// deviation_bound of the triangles the collapse creates from the original
// surface — or -1 when one exceeds the limit or is a sliver. Needs
// closest_triangle_3d.cl, straddle_bound.cl and fan_bound.cl first.
#ifndef PIECE_STACK
#define PIECE_STACK 64
#endif

// The surface's vertex fans as geometry/VertexFans lays them out: vertex
// v's neighbours are ring[first[v] .. first[v + 1]), with one sector normal
// each.
typedef struct {
    __global const uint* first;
    __global const uint* ring;
    __global const REAL4* normals;
} Fans;

// fan_distance over the fan of the vertex of triangle t nearest `centre`
// (the first of equals), as fanDistance in simplify/DeviationBound.cpp.
inline REAL fan_bound(const Surface* s, const Fans* fans, uint t, REAL4 centre, REAL4 p0, REAL4 p1,
                      REAL4 p2, REAL limit) {
    const int4 tri = s->triangles[t];
    int v = tri.x;
    REAL4 d = s->points[tri.x] - centre;
    REAL nearest2 = dot3(d, d);
    d = s->points[tri.y] - centre;
    if (dot3(d, d) < nearest2) {
        nearest2 = dot3(d, d);
        v = tri.y;
    }
    d = s->points[tri.z] - centre;
    if (dot3(d, d) < nearest2) v = tri.z;
    const uint first = fans->first[v], m = fans->first[v + 1] - first;
    if (m < 3 || m > FAN_MAX) return INFINITY;
    REAL4 ring[FAN_MAX], normals[FAN_MAX];
    for (uint k = 0; k < m; ++k) {
        ring[k] = s->points[fans->ring[first + k]];
        normals[k] = fans->normals[first + k];
    }
    return fan_distance(p0, p1, p2, s->points[v], ring, normals, (int)m, limit);
}

// deviationBound (simplify/DeviationBound.cpp), step for step: halve the
// triangle's longest edge until each piece is settled by the largest corner
// distance to the triangle nearest its parent's centre, the fan rule over
// a vertex of that triangle, or else by dist(centre) + radius, the corner
// distance to the triangle nearest the centre, or straddle_distance over
// the edge between those two triangles.
inline REAL corner_distance(const Surface* s, uint t, REAL4 p0, REAL4 p1, REAL4 p2) {
    const int4 tri = s->triangles[t];
    const REAL4 s0 = s->points[tri.x], s1 = s->points[tri.y], s2 = s->points[tri.z];
    return fmax(
        fmax(point_triangle_distance(p0, s0, s1, s2), point_triangle_distance(p1, s0, s1, s2)),
        point_triangle_distance(p2, s0, s1, s2));
}

REAL deviation_bound(const Surface* s, const Fans* fans, REAL4 a, REAL4 b, REAL4 c, REAL limit,
                     REAL finest) {
    REAL4 stack[PIECE_STACK][3];
    uint near[PIECE_STACK];
    int size = 0;
    stack[size][0] = a;
    stack[size][1] = b;
    stack[size][2] = c;
    near[size++] = UINT_MAX;
    REAL bound = 0;
    while (size > 0) {
        --size;
        const REAL4 p0 = stack[size][0], p1 = stack[size][1], p2 = stack[size][2];
        const uint hint = near[size];
        if (hint != UINT_MAX) {
            const REAL corners = corner_distance(s, hint, p0, p1, p2);
            if (corners <= limit) {
                bound = fmax(bound, corners);
                continue;
            }
        }
        const REAL4 centre = (p0 + p1 + p2) * (REAL)(1.0 / 3.0);
        if (hint != UINT_MAX) {
            const REAL fan = fan_bound(s, fans, hint, centre, p0, p1, p2, limit);
            if (fan <= limit) {
                bound = fmax(bound, fan);
                continue;
            }
        }
        const REAL radius =
            fmax(fmax(sqrt(dot3(p0 - centre, p0 - centre)), sqrt(dot3(p1 - centre, p1 - centre))),
                 sqrt(dot3(p2 - centre, p2 - centre)));
        uint t = hint;
        const REAL d = nearest_triangle(s, centre, &t);
        if (d > limit) return d;
        REAL settled = d + radius;
        if (settled > limit && t != hint)
            settled = fmin(settled, corner_distance(s, t, p0, p1, p2));
        if (settled > limit && hint != UINT_MAX && t != hint) {
            const int4 ta = s->triangles[hint], tb = s->triangles[t];
            settled = fmin(settled,
                           straddle_distance(p0, p1, p2, s->points[ta.x], s->points[ta.y],
                                             s->points[ta.z], ta.x, ta.y, ta.z, s->points[tb.x],
                                             s->points[tb.y], s->points[tb.z], tb.x, tb.y, tb.z));
        }
        if (settled <= limit) {
            bound = fmax(bound, settled);
            continue;
        }
        if (radius < finest || size + 2 > PIECE_STACK) return settled;
        // Halve the longest edge (the first of equal ones, as longestEdge).
        const REAL l0 = dot3(p1 - p0, p1 - p0), l1 = dot3(p2 - p1, p2 - p1),
                   l2 = dot3(p0 - p2, p0 - p2);
        const int k = (l0 >= l1 && l0 >= l2) ? 0 : (l1 >= l2 ? 1 : 2);
        const REAL4 from = k == 0 ? p0 : (k == 1 ? p1 : p2);
        const REAL4 to = k == 0 ? p1 : (k == 1 ? p2 : p0);
        const REAL4 apex = k == 0 ? p2 : (k == 1 ? p0 : p1);
        const REAL4 mid = (REAL)0.5 * (from + to);
        stack[size][0] = from;
        stack[size][1] = mid;
        stack[size][2] = apex;
        near[size++] = t;
        stack[size][0] = mid;
        stack[size][1] = to;
        stack[size][2] = apex;
        near[size++] = t;
    }
    return bound;
}

// halfedges[h] = (v0, v1); the mesh's faces around vertex v are
// ring_faces[ring_first[v] .. ring_first[v+1]) as vertex-index triples.
// The mesh's vertices are mesh_points; the original surface (the same mesh
// here, but passed separately) is the Surface arguments.
__kernel void collapse_bound(__global const int2* halfedges, uint halfedge_count,
                             __global const REAL4* mesh_points, __global const uint* ring_first,
                             __global const int4* ring_faces, __global const REAL4* points,
                             __global const int4* triangles, __global const REAL4* node_lo,
                             __global const REAL4* node_hi, __global const int4* node_links,
                             __global const uint* order, __global const REAL4* balls,
                             __global const uint* fan_first, __global const uint* fan_ring,
                             __global const REAL4* fan_normals, REAL limit, REAL finest,
                             REAL min_area_ratio, __global float* priority) {
    const uint h = get_global_id(0);
    if (h >= halfedge_count) return;
    const Surface surface = {points, triangles, node_lo, node_hi, node_links, order, balls};
    const Fans fans = {fan_first, fan_ring, fan_normals};
    const int v0 = halfedges[h].x, v1 = halfedges[h].y;
    const REAL4 kept = mesh_points[v1];
    REAL deviation = 0;
    // Slivers first, as trianglesAfterCollapse refuses them before any bound.
    for (uint k = ring_first[v0]; k < ring_first[v0 + 1]; ++k) {
        const int4 f = ring_faces[k];
        if (f.x == v1 || f.y == v1 || f.z == v1) continue;  // the edge's own faces
        const REAL4 a = f.x == v0 ? kept : mesh_points[f.x];
        const REAL4 b = f.y == v0 ? kept : mesh_points[f.y];
        const REAL4 c = f.z == v0 ? kept : mesh_points[f.z];
        const REAL4 e0 = b - a, e1 = c - a, e2 = c - b;
        const REAL longest2 = fmax(fmax(dot3(e0, e0), dot3(e1, e1)), dot3(e2, e2));
        const REAL4 n = cross(e0, e1);
        if (sqrt(dot3(n, n)) <= min_area_ratio * longest2) {
            priority[h] = -1;
            return;
        }
    }
    for (uint k = ring_first[v0]; k < ring_first[v0 + 1]; ++k) {
        const int4 f = ring_faces[k];
        if (f.x == v1 || f.y == v1 || f.z == v1) continue;
        const REAL d = deviation_bound(&surface, &fans, f.x == v0 ? kept : mesh_points[f.x],
                                       f.y == v0 ? kept : mesh_points[f.y],
                                       f.z == v0 ? kept : mesh_points[f.z], limit, finest);
        if (d > limit) {
            priority[h] = -1;
            return;
        }
        deviation = fmax(deviation, d);
    }
    priority[h] = (float)deviation;
}
