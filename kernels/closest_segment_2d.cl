// Closest-primitive fields in the plane: for every pixel of a slice grid, the
// signed distance to the nearest contour segment or vertex and that
// primitive's id (field/PrimitiveId.hpp). One launch covers a batch of slices
// (the third global dimension).
//
// Needs real.cl and closest_point.cl first. Coordinates are millimetres
// relative to the grid origin, so magnitudes stay small. Pixel (i, j) has its centre at
// ((i + 0.5) * pixelMm, (j + 0.5) * pixelMm). TILE (the fine tile and
// work-group side) and LANES come from the host too.
//
// Culling (tile_candidates, run coarse then fine): pixels are grouped in
// square tiles. For a tile with centre c and half-diagonal h (over its pixel
// centres), every pixel p in it has |p - c| <= h, so
//   d(p, s) >= d(c, s) - h   and   min_s d(p, s) <= min_s d(c, s) + h.
// Only segments with d(c, s) <= min_s d(c, s) + 2h can be nearest to any
// pixel of the tile. The candidate list keeps segment order, so ties resolve
// as in a brute-force scan.
#ifndef TILE
#define TILE 8
#endif
// Pixels per work-item in the field kernel, as vector lanes: 8 suits CPU
// devices (explicit SIMD), 1 suits GPUs (many small work-items).
#ifndef LANES
#define LANES 1
#endif
#if LANES == 1
#define REALV REAL
#define INTV int
#define CONVERT_REALV(x) ((REAL)(x))
#define VSTORE(v, offset, p) ((p)[offset] = (v))
#define MASKV int  // scalar isless() gives int whatever the operand type
#define MASK_SCALAR int
#define LANE_OFFSETS 0
#define PICK(a, b, mask) ((mask) ? (b) : (a))
#else
#define REALV CONCAT(REAL, LANES)
#define INTV CONCAT(int, LANES)
#define CONVERT_REALV CONCAT(convert_, REALV)
#define VSTORE CONCAT(vstore, LANES)
// Vector isless()/select() masks have the lane type's width.
#if defined(REAL_IS_DOUBLE)
#define MASKV CONCAT(long, LANES)
#define MASK_SCALAR long
#else
#define MASKV CONCAT(int, LANES)
#define MASK_SCALAR int
#endif
#if LANES == 4
#define LANE_OFFSETS ((INTV)(0, 1, 2, 3))
#elif LANES == 8
#define LANE_OFFSETS ((INTV)(0, 1, 2, 3, 4, 5, 6, 7))
#else
#error "LANES must be 1, 4 or 8"
#endif
#define PICK(a, b, mask) select(a, b, mask)  // per lane: b where mask is set
#endif

// Squared distance from p to segment s = (ax, ay, bx, by); t receives the
// clamped parameter of the nearest point (0 = start vertex, 1 = end vertex).
inline REAL segmentDistance2(REAL2 p, REAL4 s, REAL* t) {
    const REAL2 a = s.xy, ab = s.zw - s.xy, ap = p - a;
    const REAL u = segment_parameter(ap.x, ap.y, ab.x, ab.y);
    *t = u;
    const REAL2 q = ap - u * ab;
    return dot(q, q);
}

// One work-item per (tile x, tile y, slice of the batch) for tiles of
// `tile` pixels. Scans the candidates of the enclosing parent tile (a
// coarser level of the same kind; parentTile = 0 for none, or when that list
// overflowed: the whole slice). Writes up to `capacity` candidate segment
// indices (global, in segment order) and the full count, which may exceed
// capacity: users then scan the whole slice.
__kernel void tile_candidates(__global const REAL4* segments, __global const uint* sliceFirst,
                              __global const uint* sliceCount, const uint width, const uint height,
                              const REAL pixelMm, const uint tile, const uint parentTile,
                              __global const uint* parentCandidates,
                              __global const uint* parentCount, const uint parentCapacity,
                              const uint capacity, __global uint* candidates,
                              __global uint* candidateCount) {
    const uint tx = get_global_id(0), ty = get_global_id(1), s = get_global_id(2);
    const uint tilesX = (width + tile - 1) / tile, tilesY = (height + tile - 1) / tile;
    if (tx >= tilesX || ty >= tilesY) return;
    const uint i0 = tx * tile, j0 = ty * tile;
    const uint i1 = min(i0 + tile, width) - 1, j1 = min(j0 + tile, height) - 1;
    // The box of the tile's pixel centres: fields are only sampled there.
    const REAL2 lo = (REAL2)((i0 + (REAL)0.5) * pixelMm, (j0 + (REAL)0.5) * pixelMm);
    const REAL2 hi = (REAL2)((i1 + (REAL)0.5) * pixelMm, (j1 + (REAL)0.5) * pixelMm);
    const REAL2 centre = (lo + hi) / 2;
    const REAL halfDiagonal = length(hi - lo) / 2;

    // Where to look: the parent's list, or every segment of the slice.
    const uint first = sliceFirst[s];
    uint count = sliceCount[s];
    __global const uint* from = 0;
    if (parentTile > 0) {
        const uint parentsX = (width + parentTile - 1) / parentTile;
        const uint parentsY = (height + parentTile - 1) / parentTile;
        const size_t parent = ((size_t)s * parentsY + j0 / parentTile) * parentsX + i0 / parentTile;
        if (parentCount[parent] <= parentCapacity) {
            count = parentCount[parent];
            from = parentCandidates + parent * parentCapacity;
        }
    }

    REAL best2 = INFINITY, t;
    for (uint k = 0; k < count; ++k) {
        const uint seg = from ? from[k] : first + k;
        best2 = fmin(best2, segmentDistance2(centre, segments[seg], &t));
    }
    // Compared squared; relative slack so rounding never drops the nearest.
    const REAL reach = (sqrt(best2) + 2 * halfDiagonal) * (REAL)(1 + 1e-5) + (REAL)1e-6 * pixelMm;
    const REAL reach2 = reach * reach;

    const size_t at = ((size_t)s * tilesY + ty) * tilesX + tx;
    __global uint* list = candidates + at * capacity;
    uint n = 0;
    for (uint k = 0; k < count; ++k) {
        const uint seg = from ? from[k] : first + k;
        if (segmentDistance2(centre, segments[seg], &t) <= reach2) {
            if (n < capacity) list[n] = seg;
            ++n;
        }
    }
    candidateCount[at] = n;
}

// One work-item per LANES consecutive pixels (i0 .. i0+LANES-1, j) of slice
// s of the batch, computed in vector lanes (explicit SIMD for CPU devices;
// GPUs scalarise it); a work-group is one TILE x TILE tile, so every loop
// bound is the same for all its work-items. ids[k] = (segment id, id of its
// end vertex); the start vertex id is segment id | 1.
// Crossings of row j: crossings[rowFirst[r] .. rowFirst[r + 1]) with
// r = s * height + j, each (k, dir): the contour crosses the row between
// pixel k - 1 and k going up (dir = +1) or down (-1). The winding number at
// pixel i is the sum of dir over crossings with k > i (Sunday's rule with
// the ray to +x), non-zero meaning inside.
__kernel __attribute__((reqd_work_group_size(TILE / LANES, TILE, 1))) void signed_distance_2d(
    __global const REAL4* segments, __global const uint2* ids, __global const uint* sliceFirst,
    __global const uint* sliceCount, __global const uint* rowFirst, __global const int2* crossings,
    const uint width, const uint height, const REAL pixelMm, const uint capacity,
    __global const uint* candidates, __global const uint* candidateCount, __global float* distance,
    __global uint* nearestId) {
    const uint i0 = get_global_id(0) * LANES, j = get_global_id(1), s = get_global_id(2);
    if (j >= height) return;  // padding rows of the last tile row (no barriers below)
    const uint tilesX = (width + TILE - 1) / TILE, tilesY = (height + TILE - 1) / TILE;
    const size_t tile = ((size_t)s * tilesY + j / TILE) * tilesX + i0 / TILE;
    const INTV lane = (INTV)(i0) + LANE_OFFSETS;
    const REALV px = (CONVERT_REALV(lane) + (REAL)0.5) * pixelMm;
    const REAL py = (j + (REAL)0.5) * pixelMm;

    const uint listed = candidateCount[tile];
    const bool useList = listed <= capacity;
    const uint n = useList ? listed : sliceCount[s];
    __global const uint* list = candidates + tile * capacity;
    // Per lane: the nearest segment so far and its parameter; ids are looked
    // up once at the end.
    REALV best2 = (REALV)(INFINITY), bestT = (REALV)(0);
    MASKV bestSeg = (MASKV)(0);
    for (uint k = 0; k < n; ++k) {
        const uint seg = useList ? list[k] : sliceFirst[s] + k;
        const REAL4 sg = segments[seg];
        const REAL abx = sg.z - sg.x, aby = sg.w - sg.y;
        const REAL len2 = abx * abx + aby * aby;
        const REAL inverse = len2 > 0 ? 1 / len2 : 0;
        const REALV apx = px - sg.x;
        const REAL apy = py - sg.y;
        const REALV t = clamp((apx * abx + apy * aby) * inverse, (REAL)0, (REAL)1);
        const REALV qx = apx - t * abx, qy = apy - t * aby;
        const REALV d2 = qx * qx + qy * qy;
        const MASKV better = isless(d2, best2);
        best2 = PICK(best2, d2, better);
        bestT = PICK(bestT, t, better);
        bestSeg = PICK(bestSeg, (MASKV)(seg), better);
    }

    const size_t row = (size_t)s * height + j;
    INTV winding = (INTV)(0);
    for (uint c = rowFirst[row]; c < rowFirst[row + 1]; ++c) {
        const int2 crossing = crossings[c];
        winding += PICK((INTV)(0), (INTV)(crossing.y), (INTV)(crossing.x) > lane);
    }

    REAL d[LANES], tl[LANES];
    int w[LANES];
    MASK_SCALAR segs[LANES];
    VSTORE(sqrt(best2), 0, d);
    VSTORE(bestT, 0, tl);
    VSTORE(winding, 0, w);
    VSTORE(bestSeg, 0, segs);
    for (int l = 0; l < LANES; ++l) {
        if (i0 + l >= width) break;
        uint id = 0xffffffffu;
        if (n > 0) {
            const uint2 e = ids[(uint)segs[l]];
            id = tl[l] <= 0 ? (e.x | 1u) : (tl[l] >= 1 ? e.y : e.x);
        }
        const size_t pixel = row * width + i0 + l;
        distance[pixel] = w[l] != 0 ? -(float)d[l] : (float)d[l];
        nearestId[pixel] = id;
    }
}
