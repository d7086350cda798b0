// Closest-primitive fields in the plane: for every pixel of a slice grid, the
// signed distance to the nearest contour segment or vertex and that
// primitive's id (recon/PrimitiveId.hpp). One launch covers a batch of slices
// (the third global dimension).
//
// REAL is double when the device has fp64 (the host passes -DREAL=double),
// else float. Coordinates are millimetres relative to the grid origin, so
// magnitudes stay small. Pixel (i, j) has its centre at
// ((i + 0.5) * pixelMm, (j + 0.5) * pixelMm).
//
// Culling (tile_candidates): pixels are grouped in TILE x TILE tiles. For a
// tile with centre c and half-diagonal h, every pixel p in it has
//   d(p) <= min_s d(c, s) + h =: U,
// so only segments whose distance to the tile's box is <= U can be nearest
// to any of its pixels. The candidate list keeps segment order, so ties
// resolve as in a brute-force scan.
#ifndef REAL
#define REAL float
#endif
#define REAL2 CONCAT(REAL, 2)
#define REAL4 CONCAT(REAL, 4)
#define CONCAT(a, b) CONCAT_(a, b)
#define CONCAT_(a, b) a##b
#ifndef TILE
#define TILE 8
#endif

// Squared distance from p to segment s = (ax, ay, bx, by); t receives the
// clamped parameter of the nearest point (0 = start vertex, 1 = end vertex).
inline REAL segmentDistance2(REAL2 p, REAL4 s, REAL* t) {
    const REAL2 a = s.xy, ab = s.zw - s.xy, ap = p - a;
    const REAL len2 = dot(ab, ab);
    REAL u = len2 > 0 ? dot(ap, ab) / len2 : 0;
    u = clamp(u, (REAL)0, (REAL)1);
    *t = u;
    const REAL2 q = ap - u * ab;
    return dot(q, q);
}

// Distance from point p to the axis-aligned box [lo, hi].
inline REAL pointBoxDistance(REAL2 p, REAL2 lo, REAL2 hi) {
    const REAL2 d = fmax(fmax(lo - p, p - hi), (REAL2)(0, 0));
    return length(d);
}

// Does segment ab meet the box [lo, hi]? (Liang–Barsky clipping.)
inline bool segmentHitsBox(REAL2 a, REAL2 b, REAL2 lo, REAL2 hi) {
    REAL t0 = 0, t1 = 1;
    const REAL2 d = b - a;
    const REAL p[4] = {-d.x, d.x, -d.y, d.y};
    const REAL q[4] = {a.x - lo.x, hi.x - a.x, a.y - lo.y, hi.y - a.y};
    for (int k = 0; k < 4; ++k) {
        if (p[k] == 0) {
            if (q[k] < 0) return false;
        } else {
            const REAL r = q[k] / p[k];
            if (p[k] < 0) t0 = fmax(t0, r);
            else t1 = fmin(t1, r);
        }
    }
    return t0 <= t1;
}

// Exact distance between segment s and the box [lo, hi]: zero if they meet,
// else attained at an endpoint of the segment or a corner of the box.
inline REAL segmentBoxDistance(REAL4 s, REAL2 lo, REAL2 hi) {
    if (segmentHitsBox(s.xy, s.zw, lo, hi)) return 0;
    REAL best = fmin(pointBoxDistance(s.xy, lo, hi), pointBoxDistance(s.zw, lo, hi));
    REAL t;
    best = fmin(best, sqrt(segmentDistance2((REAL2)(lo.x, lo.y), s, &t)));
    best = fmin(best, sqrt(segmentDistance2((REAL2)(hi.x, lo.y), s, &t)));
    best = fmin(best, sqrt(segmentDistance2((REAL2)(lo.x, hi.y), s, &t)));
    best = fmin(best, sqrt(segmentDistance2((REAL2)(hi.x, hi.y), s, &t)));
    return best;
}

// One work-item per (tile x, tile y, slice of the batch). Writes up to
// `capacity` candidate segment indices (global) and the full count, which
// may exceed capacity: the field kernel then scans the whole slice.
__kernel void tile_candidates(__global const REAL4* segments, __global const uint* sliceFirst,
                              __global const uint* sliceCount, const uint width, const uint height,
                              const REAL pixelMm, const uint capacity,
                              __global uint* candidates, __global uint* candidateCount) {
    const uint tx = get_global_id(0), ty = get_global_id(1), s = get_global_id(2);
    const uint tilesX = (width + TILE - 1) / TILE, tilesY = (height + TILE - 1) / TILE;
    if (tx >= tilesX || ty >= tilesY) return;
    const uint i0 = tx * TILE, j0 = ty * TILE;
    const uint i1 = min(i0 + TILE, width) - 1, j1 = min(j0 + TILE, height) - 1;
    // The box of the tile's pixel centres: fields are only sampled there.
    const REAL2 lo = (REAL2)((i0 + (REAL)0.5) * pixelMm, (j0 + (REAL)0.5) * pixelMm);
    const REAL2 hi = (REAL2)((i1 + (REAL)0.5) * pixelMm, (j1 + (REAL)0.5) * pixelMm);
    const REAL2 centre = (lo + hi) / 2;
    const REAL halfDiagonal = length(hi - lo) / 2;

    const uint first = sliceFirst[s], count = sliceCount[s];
    REAL best2 = INFINITY, t;
    for (uint k = 0; k < count; ++k)
        best2 = fmin(best2, segmentDistance2(centre, segments[first + k], &t));
    // Relative slack so rounding can never drop the true nearest segment.
    const REAL upper = (sqrt(best2) + halfDiagonal) * (REAL)(1 + 1e-5) + (REAL)1e-6 * pixelMm;

    const size_t tile = ((size_t)s * tilesY + ty) * tilesX + tx;
    __global uint* list = candidates + tile * capacity;
    uint n = 0;
    for (uint k = 0; k < count; ++k) {
        if (segmentBoxDistance(segments[first + k], lo, hi) <= upper) {
            if (n < capacity) list[n] = first + k;
            ++n;
        }
    }
    candidateCount[tile] = n;
}

// One work-item per pixel (i, j) of slice s of the batch. ids[k] = (segment
// id, id of its end vertex); the start vertex id is segment id | 1.
// Crossings of row j: crossings[rowFirst[r] .. rowFirst[r + 1]) with
// r = s * height + j, each (k, dir): the contour crosses the row between
// pixel k - 1 and k going up (dir = +1) or down (-1). The winding number at
// pixel i is the sum of dir over crossings with k > i (Sunday's rule with
// the ray to +x), non-zero meaning inside.
__kernel void signed_distance_2d(__global const REAL4* segments, __global const uint2* ids,
                                 __global const uint* sliceFirst, __global const uint* sliceCount,
                                 __global const uint* rowFirst, __global const int2* crossings,
                                 const uint width, const uint height, const REAL pixelMm,
                                 const uint capacity, __global const uint* candidates,
                                 __global const uint* candidateCount, __global float* distance,
                                 __global uint* nearestId) {
    const uint i = get_global_id(0), j = get_global_id(1), s = get_global_id(2);
    if (i >= width || j >= height) return;
    const uint tilesX = (width + TILE - 1) / TILE, tilesY = (height + TILE - 1) / TILE;
    const size_t tile = ((size_t)s * tilesY + j / TILE) * tilesX + i / TILE;
    const REAL2 p = (REAL2)((i + (REAL)0.5) * pixelMm, (j + (REAL)0.5) * pixelMm);

    const uint listed = candidateCount[tile];
    const bool useList = listed <= capacity;
    const uint n = useList ? listed : sliceCount[s];
    __global const uint* list = candidates + tile * capacity;
    REAL best2 = INFINITY;
    uint bestId = 0xffffffffu;
    for (uint k = 0; k < n; ++k) {
        const uint seg = useList ? list[k] : sliceFirst[s] + k;
        REAL t;
        const REAL d2 = segmentDistance2(p, segments[seg], &t);
        if (d2 < best2) {
            best2 = d2;
            const uint2 id = ids[seg];
            bestId = t <= 0 ? (id.x | 1u) : (t >= 1 ? id.y : id.x);
        }
    }

    const size_t row = (size_t)s * height + j;
    int winding = 0;
    for (uint c = rowFirst[row]; c < rowFirst[row + 1]; ++c) {
        const int2 crossing = crossings[c];
        if (crossing.x > (int)i) winding += crossing.y;
    }
    const float d = (float)sqrt(best2);
    const size_t pixel = row * width + i;
    distance[pixel] = winding != 0 ? -d : d;
    nearestId[pixel] = bestId;
}
