// Closest-primitive fields in the plane: for every pixel of a slice grid, the
// signed distance to the nearest contour segment or vertex and that
// primitive's id (field/PrimitiveId.hpp). One launch covers a batch of slices
// (the third global dimension).
//
// Needs real.cl first. Segments and chords come as (a, b - a) with their
// projectors (b - a) / |b - a|^2 from the host, so that the parameter of
// the nearest point is one dot product, with no division
// (closest_point.cl's segment_parameter divides); point-segment distances
// come in three widths (lanes, one point, four corners) since OpenCL C has
// no overloads. Coordinates are millimetres
// relative to the grid origin, so magnitudes stay small. Pixel (i, j) has its
// centre at ((i + 0.5) * pixelMm, (j + 0.5) * pixelMm). TILE (the work-group
// side in pixels), LANES and LEAF come from the host too.
//
// Nearest segment, exactly (the brute-force scan's answer, which
// tests/field/test_SliceFields.cpp holds it to). The host builds per slice a
// tree over the segments (field/SliceFields.cpp): leaf k holds segments
// [k * LEAF, (k + 1) * LEAF) of the slice in (contour, index) order, a short
// run of a contour; the tree is a heap (node n has children 2n and 2n + 1,
// leaves at leafBase + k, index 0 unused; missing leaves have empty boxes).
// Every node has a box holding its segments and a capsule: a chord segment
// and a radius dev such that every point of its segments lies within dev of
// the chord. So for any point p and segment s of node N,
//   d(p, s) >= d(p, box(N))   and   d(p, s) >= d(p, chord(N)) - dev(N),
// and a node farther than a distance already reached holds no segment nearer
// than it: branch and bound never drops the nearest segment. Three ways use
// it, chosen per tile of TILE x TILE pixels by tile_candidates (its header
// says which segments can be nearest to a pixel of the tile):
//  - a tile whose candidates lie in leaves of at most leafListsFrom
//    segments lists those candidates; each
//    work-item filters that list for every BLOCK_ROWS of its rows by the
//    same test (blockCandidates), and its pixels scan what is left, like a
//    brute-force scan of a few segments;
//  - a denser tile lists the leaves that hold its candidates; each
//    work-item filters them per BLOCK_ROWS rows the same way (blockLeaves),
//    and each row scans the segments of only those leaves whose capsule
//    one of its lanes can reach within its distance to its own nearest
//    segment in the row below (scanLeaves): where a contour has several
//    segments a pixel, a row of lanes needs a few leaves of its block's,
//    where a list of segments would have it scan them all;
//  - a tile with more leaves than a list holds (or, when the caller asks for
//    no leaf lists, more segments) has each row of LANES pixels walk the
//    tree, starting from the nearest segments of the row below and the leaf
//    that holds them, then the sibling subtree of each ancestor of that
//    leaf: every leaf once, skipping the subtrees beyond reach.
// Rounding is covered by `reach`: a node is skipped only when its computed
// bound exceeds the computed best distance by REACH_RELATIVE and slackMm,
// each far above the rounding of both (a few ulps of the coordinates'
// magnitude, which the host passes in slackMm). Ties go to the lower segment
// index, whatever order segments are met in: the result is that of a scan in
// segment order keeping the first strict minimum. Work per row of LANES
// pixels: its block's list; its block's leaves and the segments of those
// within reach; or O(depth + the segments of leaves within the lanes'
// nearest distance).
#ifndef TILE
#define TILE 8
#endif
#ifndef LEAF
#define LEAF 8
#endif
// Rows of a work-item that share one list filtered from their tile's, and
// the most entries such a list has room for (a tile's list longer than that
// is scanned whole).
#ifndef BLOCK_ROWS
#define BLOCK_ROWS 8
#endif
#ifndef BLOCK_LIST
#define BLOCK_LIST 96
#endif
// A tile's count with this bit set lists leaves of the tree, not segments
// (the host passes its own).
#ifndef LEAF_LISTED
#define LEAF_LISTED 0x80000000u
#endif
// A tile's count with this bit set has its work-items' lanes go down its
// columns rather than along its rows (the host passes its own).
#ifndef COLUMNS
#define COLUMNS 0x40000000u
#endif
// tile_candidates' lanesAlong (FieldKernelOptions::lanesAlong): by the
// contour (the default), columns, or any other value for rows.
#define LANES_ALONG_CONTOUR 0u
#define LANES_ALONG_COLUMNS 2u
// The most segments a lane's bound moves on along the contour from one step
// to the next (the field kernel's `ahead`): two leaves. 8, 16 and 32 gave
// 3.63, 3.62 and 3.64 leaves a row at 10 000 segments, no cap 4.05.
#define MAX_MOVE (2 * LEAF)
// Leaves tile_candidates keeps to list the segments of a sparse tile from:
// more than those hold more segments than the default leafListsFrom.
#define KEPT_LEAVES 16
// Pixels per work-item, as vector lanes: 8 suits CPU devices (explicit
// SIMD), 1 suits GPUs (many small work-items). The lanes of a work-item walk
// the tree together: a subtree is entered when any lane may find a nearer
// (or tied) segment in it.
#ifndef LANES
#define LANES 1
#endif
#if defined(REAL_IS_DOUBLE)
#define REACH_RELATIVE (1 + 64 * DBL_EPSILON)
#define MASK4 long4  // what comparisons of REAL4 give
#else
#define REACH_RELATIVE (1 + 64 * FLT_EPSILON)
#define MASK4 int4
#endif
// Whether all four lanes of a MASK4 are set, tested as one integer of
// bytes: PoCL's all() reduces the lanes one step at a time, and the corner
// tests take one per segment and node.
#define ALL4(mask) (as_uint(convert_char4(mask)) == 0xffffffffu)
#if LANES == 1
#define REALV REAL
#define INTV int
#define CONVERT_REALV(x) ((REAL)(x))
#define CONVERT_FLOATV(x) ((float)(x))
#define CONVERT_MASKV(x) ((int)(x))
#define VSTORE(v, offset, p) ((p)[offset] = (v))
#define VLOAD(offset, p) ((p)[offset])
#define MASKV int  // scalar comparisons give int whatever the operand type
#define UINTV uint
#define SELECT_ID(a, b, mask) ((mask) ? (b) : (a))
#define MASK_SCALAR int
#define LANE_OFFSETS 0
#define PICK(a, b, mask) ((mask) ? (b) : (a))
#define ANY(mask) (mask)
#define LANE_MIN(v) (v)
#else
#define REALV CONCAT(REAL, LANES)
#define INTV CONCAT(int, LANES)
#define CONVERT_REALV CONCAT(convert_, REALV)
#define CONVERT_FLOATV CONCAT(convert_float, LANES)
#define CONVERT_MASKV CONCAT(convert_, MASKV)
#define VSTORE CONCAT(vstore, LANES)
#define VLOAD CONCAT(vload, LANES)
// Vector comparison and select() masks have the lane type's width.
#if defined(REAL_IS_DOUBLE)
#define MASKV CONCAT(long, LANES)
#define MASK_SCALAR long
#else
#define MASKV CONCAT(int, LANES)
#define MASK_SCALAR int
#endif
#if LANES == 4
#define LANE_OFFSETS ((INTV)(0, 1, 2, 3))
#define LANE_MIN(v) fmin(fmin((v).s0, (v).s1), fmin((v).s2, (v).s3))
#elif LANES == 8
#define LANE_OFFSETS ((INTV)(0, 1, 2, 3, 4, 5, 6, 7))
#define LANE_MIN(v)                                        \
    fmin(fmin(fmin((v).s0, (v).s1), fmin((v).s2, (v).s3)), \
         fmin(fmin((v).s4, (v).s5), fmin((v).s6, (v).s7)))
#else
#error "LANES must be 1, 4 or 8"
#endif
#define PICK(a, b, mask) select(a, b, mask)  // per lane: b where mask is set
#define UINTV CONCAT(uint, LANES)
// select() on uint lanes wants int lanes of mask.
#define SELECT_ID(a, b, mask) select(a, b, CONCAT(convert_int, LANES)(mask))
// Lanes narrowed to bytes and tested as one integer: PoCL's any() reduces
// the lanes one step at a time, and the leaf tests take one per leaf.
#if LANES == 4
#define ANY(mask) (as_uint(convert_char4(mask)) != 0)
#else
#define ANY(mask) (as_ulong(convert_char8(mask)) != 0)
#endif
#endif

// Squared distance from the lanes' points (px, py) to box (xmin, ymin, xmax,
// ymax); +inf for an empty box (xmin = +inf, xmax = -inf).
inline REALV boxDistance2(REAL4 box, REALV px, REAL py) {
    const REALV dx = fmax(fmax(box.x - px, px - box.z), (REALV)(0));
    const REAL dy = fmax(fmax(box.y - py, py - box.w), (REAL)0);
    return dx * dx + dy * dy;
}

// Squared distance from the lanes' points to segment s = (ax, ay, bx - ax,
// by - ay) with projector (b - a) / |b - a|^2 (0 for a point); *t receives
// the parameter of the nearest point (0 = a, 1 = b). The host divides once
// per segment, as the division would otherwise dominate the scans, and
// stores b - a and its projector so that a scan reads them as they are
// used (a few operations fewer per segment than b and 1 / length^2).
inline REALV segmentDistance2(REAL4 s, REAL2 projector, REALV px, REAL py, REALV* t) {
    const REAL abx = s.z, aby = s.w;
    const REALV apx = px - s.x;
    const REAL apy = py - s.y;
    *t = clamp(apx * projector.x + apy * projector.y, (REAL)0, (REAL)1);
    const REALV qx = apx - *t * abx, qy = apy - *t * aby;
    return qx * qx + qy * qy;
}

// The lanes' nearest segment so far: (squared distance, segment index)
// compared lexicographically, so the lower index wins ties in any order of
// visits; bestT is its parameter; reach and reach2 say how far a box may be
// and still hold a segment that beats or ties it.
typedef struct {
    REALV best2, bestT, reach, reach2;
    MASKV bestSeg;
} Nearest;

inline void consider(Nearest* n, __global const REAL4* segments, __global const REAL2* projectors,
                     uint seg, REALV px, REAL py) {
    REALV t;
    const REALV d2 = segmentDistance2(segments[seg], projectors[seg], px, py, &t);
    const MASKV better =
        isless(d2, n->best2) | (isequal(d2, n->best2) & ((MASKV)(seg) < n->bestSeg));
    n->best2 = PICK(n->best2, d2, better);
    n->bestT = PICK(n->bestT, t, better);
    n->bestSeg = PICK(n->bestSeg, (MASKV)(seg), better);
}

// consider() for segments met in increasing index order: a strict < then
// keeps the lowest index among ties, and the chain of dependent comparisons
// per segment is one instead of three.
inline void considerInOrder(Nearest* n, __global const REAL4* segments,
                            __global const REAL2* projectors, uint seg, REALV px, REAL py) {
    REALV t;
    const REALV d2 = segmentDistance2(segments[seg], projectors[seg], px, py, &t);
    const MASKV better = isless(d2, n->best2);
    n->best2 = PICK(n->best2, d2, better);
    n->bestT = PICK(n->bestT, t, better);
    n->bestSeg = PICK(n->bestSeg, (MASKV)(seg), better);
}

// Into n, the nearer of two minima by (distance, index) per lane.
inline void mergeMinima(Nearest* n, const Nearest* a, const Nearest* b) {
    const MASKV better =
        isless(b->best2, a->best2) | (isequal(b->best2, a->best2) & (b->bestSeg < a->bestSeg));
    const REALV best2 = PICK(a->best2, b->best2, better), bestT = PICK(a->bestT, b->bestT, better);
    n->bestSeg = PICK(a->bestSeg, b->bestSeg, better);
    n->best2 = best2, n->bestT = bestT;
}

// The lanes' nearest of `listed` segments listed in increasing index order.
// Two interleaved halves are scanned side by side, so that each comparison
// waits for the one before last rather than the last, and merged by
// (distance, index): the result is the same as one scan in list order.
inline void scanList(Nearest* n, __global const REAL4* segments, __global const REAL2* projectors,
                     const uint* list, uint listed, REALV px, REAL py) {
    Nearest odd = *n;
    uint k = 0;
    for (; k + 1 < listed; k += 2) {
        considerInOrder(n, segments, projectors, list[k], px, py);
        considerInOrder(&odd, segments, projectors, list[k + 1], px, py);
    }
    if (k < listed) considerInOrder(n, segments, projectors, list[k], px, py);
    mergeMinima(n, n, &odd);
}

inline void updateReach(Nearest* n, REAL slackMm) {
    n->reach = sqrt(n->best2) * REACH_RELATIVE + slackMm;
    n->reach2 = n->reach * n->reach;
}

inline void visitLeaf(Nearest* n, __global const REAL4* segments, __global const REAL2* projectors,
                      uint first, uint count, uint leaf, REALV px, REAL py) {
    const uint begin = first + leaf * LEAF;
    for (uint seg = begin; seg < min(begin + LEAF, first + count); ++seg)
        consider(n, segments, projectors, seg, px, py);
}

// Per lane, whether node `node`'s capsule (its chord widened by dev) is
// within reach.
inline MASKV capsuleWithinReach(const Nearest* n, __global const REAL4* chords,
                                __global const REAL2* chordProjectors, __global const REAL* devs,
                                uint node, REALV px, REAL py) {
    const REALV capsule = n->reach + devs[node];
    REALV t;
    return islessequal(segmentDistance2(chords[node], chordProjectors[node], px, py, &t),
                       capsule * capsule);
}

// Whether any lane may find a segment of node `node` that beats or ties its
// best: the node's box and capsule (chord widened by dev) both within reach.
inline bool worthVisiting(const Nearest* n, __global const REAL4* boxes,
                          __global const REAL4* chords, __global const REAL2* chordProjectors,
                          __global const REAL* devs, uint node, REALV px, REAL py) {
    const MASKV inBox = islessequal(boxDistance2(boxes[node], px, py), n->reach2);
    if (!ANY(inBox)) return false;
    return ANY(inBox & capsuleWithinReach(n, chords, chordProjectors, devs, node, px, py));
}

// Squared distance from point c to segment s = (ax, ay, bx - ax, by - ay)
// with its projector.
inline REAL pointSegmentDistance2(REAL2 c, REAL4 s, REAL2 projector) {
    const REAL2 ap = c - s.xy;
    const REAL2 q = ap - clamp(dot(ap, projector), (REAL)0, (REAL)1) * s.zw;
    return dot(q, q);
}

// The segment of leaf `leaf` (of a slice's segments first .. first+count-1)
// nearest point c, if nearer than *best2: updates *best2 and *nearest.
inline void nearestOfLeaf(REAL2 c, __global const REAL4* segments, __global const REAL2* projectors,
                          uint first, uint count, uint leaf, REAL* best2, uint* nearest) {
    for (uint seg = first + leaf * LEAF; seg < min(first + (leaf + 1) * LEAF, first + count);
         ++seg) {
        const REAL d2 = pointSegmentDistance2(c, segments[seg], projectors[seg]);
        if (d2 < *best2) *best2 = d2, *nearest = seg;
    }
}

// The same tests for one point c (scalar): whether node `node` may hold a
// segment within `reach` of c.
inline bool nodeWithin(REAL2 c, REAL reach, __global const REAL4* boxes,
                       __global const REAL4* chords, __global const REAL2* chordProjectors,
                       __global const REAL* devs, uint node) {
    const REAL4 b = boxes[node];
    const REAL dx = fmax(fmax(b.x - c.x, c.x - b.z), (REAL)0);
    const REAL dy = fmax(fmax(b.y - c.y, c.y - b.w), (REAL)0);
    if (dx * dx + dy * dy > reach * reach) return false;
    const REAL4 k = chords[node];
    const REAL capsule = reach + devs[node];
    return pointSegmentDistance2(c, k, chordProjectors[node]) <= capsule * capsule;
}

// The tile's four corner pixel centres, as lanes of a REAL4.
typedef struct {
    REAL4 x, y;
} Corners;

// Squared distances from the corners to segment s = (ax, ay, bx - ax,
// by - ay) with its projector.
inline REAL4 cornerSegmentDistance2(const Corners* k, REAL4 s, REAL2 projector) {
    const REAL abx = s.z, aby = s.w;
    const REAL4 apx = k->x - s.x, apy = k->y - s.y;
    const REAL4 t = clamp(apx * projector.x + apy * projector.y, (REAL4)(0), (REAL4)(1));
    const REAL4 qx = apx - t * abx, qy = apy - t * aby;
    return qx * qx + qy * qy;
}

// The corners of the box of pixel centres lo..hi.
inline Corners boxCorners(REAL2 lo, REAL2 hi) {
    const Corners k = {(REAL4)(lo.x, hi.x, lo.x, hi.x), (REAL4)(lo.y, lo.y, hi.y, hi.y)};
    return k;
}

// Whether segment s (with its projector) is farther than
// beaten2 at every corner: then it is nearest to no pixel of the box
// (tile_candidates says why).
inline bool beatenAtEveryCorner(const Corners* k, REAL4 s, REAL2 projector, REAL4 beaten2) {
    return ALL4(isgreater(cornerSegmentDistance2(k, s, projector), beaten2));
}

// Whether every segment of node `node` is farther than the contour point q
// from every pixel of the tile, by more than marginMm2 in squared distance,
// given beaten2 = |corner - q|^2 + marginMm2 per corner (see tile_candidates)
// and beaten = sqrt(beaten2). The capsule bound d(corner, chord) - dev
// exceeds beaten exactly when d(corner, chord)^2 exceeds (dev + beaten)^2:
// compared so, without a square root per node.
inline bool nodeDominated(const Corners* k, REAL4 beaten2, REAL4 beaten,
                          __global const REAL4* boxes, __global const REAL4* chords,
                          __global const REAL2* chordProjectors, __global const REAL* devs,
                          uint node) {
    const REAL4 b = boxes[node];
    const REAL4 dx = fmax(fmax(b.x - k->x, k->x - b.z), (REAL4)(0));
    const REAL4 dy = fmax(fmax(b.y - k->y, k->y - b.w), (REAL4)(0));
    const MASK4 outsideBox = isgreater(dx * dx + dy * dy, beaten2);
    if (ALL4(outsideBox)) return true;
    const REAL4 capsule = beaten + devs[node];
    return ALL4(outsideBox |
                isgreater(cornerSegmentDistance2(k, chords[node], chordProjectors[node]),
                          capsule * capsule));
}

// For the box of pixel centres lo..hi and the contour point nearest its
// centre on segment `q` (with its projector): per corner,
// |corner - foot|^2 + marginMm2, the squared distance a segment must exceed
// at every corner to be farther than the foot from every pixel of the box
// (tile_candidates says why).
inline REAL4 beatenAtCorners(const Corners* k, REAL2 c, REAL4 q, REAL2 projector, REAL marginMm2) {
    const REAL t = clamp(dot(c - q.xy, projector), (REAL)0, (REAL)1);
    const REAL2 foot = q.xy + t * q.zw;
    const REAL4 fx = k->x - foot.x, fy = k->y - foot.y;
    return fx * fx + fy * fy + marginMm2;
}

// Appends to a tile's list the segments of leaf `leaf` that the tile's
// corner test keeps, counting them in *n up to stopAt + 1 (only the first
// `capacity` are written).
inline void listLeafSegments(const Corners* corners, REAL4 beaten2, __global const REAL4* segments,
                             __global const REAL2* projectors, uint first, uint count, uint leaf,
                             uint stopAt, uint capacity, __global uint* list, uint* n) {
    for (uint seg = first + leaf * LEAF;
         seg < min(first + (leaf + 1) * LEAF, first + count) && *n <= stopAt; ++seg)
        if (!beatenAtEveryCorner(corners, segments[seg], projectors[seg], beaten2)) {
            if (*n < capacity) list[*n] = seg;
            ++*n;
        }
}

// The arguments both kernels take first, in this order; field/SliceFields.cpp
// sets them (SliceGeometry::setArgs, TileParams) in one call each.
//
// The geometry of the batch's slices, their segments in (slice, contour,
// index) order and per slice the heap of its tree: per segment, (a, b - a)
// and its projector, and its ids (segment id, id of its end vertex); per
// node, its box, its chord as (a, b - a) with its projector, and its dev.
// The segment and node tables come twice, as they are (XY) and with x and y
// swapped (YX, the frame of lanes down a column; devs and ids do not
// change). Per slice s of the batch: its segments sliceFirst[s] ..
// sliceFirst[s] + sliceCount[s], its heap's node 0 at treeFirst[s] and its
// first leaf node leafBase[s] (its number of leaves). OpenCL C 1.2 allows no
// pointers in a kernel's struct arguments, hence a list; tile_candidates
// reads the XY tables only.
// (Left as written: clang-format would lay the list out as expressions.)
// clang-format off
#define SLICE_GEOMETRY                                                        \
    __global const REAL4* segmentsXY, __global const REAL4* segmentsYX,       \
    __global const REAL2* projectorsXY, __global const REAL2* projectorsYX,   \
    __global const uint2* ids,                                                \
    __global const REAL4* boxesXY, __global const REAL4* boxesYX,             \
    __global const REAL4* chordsXY, __global const REAL4* chordsYX,           \
    __global const REAL2* chordProjectorsXY,                                  \
    __global const REAL2* chordProjectorsYX,                                  \
    __global const REAL* devs,                                                \
    __global const uint* sliceFirst, __global const uint* sliceCount,         \
    __global const uint* treeFirst, __global const uint* leafBase
// clang-format on
//
// The scalars, one argument: the host's twin (TileParams in
// field/SliceFields.cpp) must lay them out alike with REAL double or float,
// so the REALs come first and the uints after them, padded to a multiple of
// 8 bytes, leaving neither compiler any padding to add.
typedef struct {
    REAL pixelMm;        // pixel (i, j) has its centre at ((i + 0.5) pixelMm, (j + 0.5) pixelMm)
    REAL slackMm;        // above the rounding of distances at these coordinates (`reach`)
    REAL marginMm2;      // above the rounding of squared distances (tile_candidates)
    uint width, height;  // of the grid, in pixels
    uint capacity;       // entries of a tile's list
    uint leafListsFrom;  // tile_candidates: leaves listed above this many segments
    uint lanesAlong;     // tile_candidates: LANES_ALONG_CONTOUR, LANES_ALONG_COLUMNS or rows
    uint padding;
} TileParams;

// One work-item per (tile x, tile y, slice of the batch): the segments that
// can be nearest to a pixel of the TILE x TILE tile, when there are at most
// `capacity`. A segment s is left out when some point q of the contour is
// nearer than s to every pixel of the tile: g(p) = d(p, s)^2 - |p - q|^2 is
// a minimum of functions linear in p (|p - x|^2 - |p - q|^2 over the points
// x of s), so concave, and its minimum over the tile's box (of pixel
// centres) is at a corner. q is the point of the contour nearest the centre,
// found by branch and bound over the tree; when g exceeds marginMm2 (far
// above the rounding of squared distances of coordinates this large) at all
// four corners, s is farther than q's segment from every pixel by more than
// rounding, so it never wins or ties there. A node whose lower bound (box,
// then capsule) passes the test at every corner holds no candidate, so a
// second walk of the tree that skips such nodes finds the leaves that hold
// candidates. When they hold more than leafListsFrom segments, those leaves
// are the list (count | LEAF_LISTED); else their segments that pass the
// test are. Writes the count, or capacity + 1 when there are more: the
// field kernel then walks the tree for each pixel instead. O(depth +
// capacity) nodes per tile for contours no denser than its pixels.
__kernel void tile_candidates(SLICE_GEOMETRY, const TileParams params, __global uint* candidates,
                              __global uint* candidateCount) {
    // Tiles are listed in the rows' frame (x and y as they are).
    __global const REAL4* segments = segmentsXY;
    __global const REAL2* projectors = projectorsXY;
    __global const REAL4* boxes = boxesXY;
    __global const REAL4* chords = chordsXY;
    __global const REAL2* chordProjectors = chordProjectorsXY;
    const uint width = params.width, height = params.height;
    const REAL pixelMm = params.pixelMm, slackMm = params.slackMm, marginMm2 = params.marginMm2;
    const uint capacity = params.capacity, leafListsFrom = params.leafListsFrom,
               lanesAlong = params.lanesAlong;
    const uint tx = get_global_id(0), ty = get_global_id(1), s = get_global_id(2);
    const uint tilesX = (width + TILE - 1) / TILE, tilesY = (height + TILE - 1) / TILE;
    if (tx >= tilesX || ty >= tilesY) return;
    const uint i0 = tx * TILE, j0 = ty * TILE;
    const uint i1 = min(i0 + TILE, width) - 1, j1 = min(j0 + TILE, height) - 1;
    const REAL2 lo = (REAL2)((i0 + (REAL)0.5) * pixelMm, (j0 + (REAL)0.5) * pixelMm);
    const REAL2 hi = (REAL2)((i1 + (REAL)0.5) * pixelMm, (j1 + (REAL)0.5) * pixelMm);
    const REAL2 c = (lo + hi) / 2;
    const uint first = sliceFirst[s], count = sliceCount[s];
    const uint tree = treeFirst[s];
    __global const REAL4* box = boxes + tree;
    __global const REAL4* chord = chords + tree;
    __global const REAL2* chordProjector = chordProjectors + tree;
    __global const REAL* dev = devs + tree;
    const uint leaves = leafBase[s];
    const size_t at = ((size_t)s * tilesY + ty) * tilesX + tx;
    __global uint* list = candidates + at * capacity;

    // min_s d(c, s): the leaf down the nearer side, then depth first (left
    // before right, without a stack) through what may still be nearer.
    REAL best2 = INFINITY;
    uint node = 1;
    while (node < leaves) {
        const REAL4 l = box[2 * node], r = box[2 * node + 1];
        const REAL dl =
            fmax(fmax(l.x - c.x, c.x - l.z), (REAL)0) + fmax(fmax(l.y - c.y, c.y - l.w), (REAL)0);
        const REAL dr =
            fmax(fmax(r.x - c.x, c.x - r.z), (REAL)0) + fmax(fmax(r.y - c.y, c.y - r.w), (REAL)0);
        node = 2 * node + (dr < dl ? 1 : 0);
    }
    uint nearest = 0;
    nearestOfLeaf(c, segments, projectors, first, count, node - leaves, &best2, &nearest);
    REAL reach = sqrt(best2) * REACH_RELATIVE + slackMm;  // kept as best2 falls
    node = count > 0 ? 1 : 0;
    while (node != 0) {
        if (nodeWithin(c, reach, box, chord, chordProjector, dev, node)) {
            if (node < leaves) {
                node *= 2;
                continue;
            }
            nearestOfLeaf(c, segments, projectors, first, count, node - leaves, &best2, &nearest);
            reach = sqrt(best2) * REACH_RELATIVE + slackMm;
        }
        while (node & 1) node >>= 1;
        if (node != 0) ++node;
    }
    const Corners corners = boxCorners(lo, hi);
    const REAL4 beaten2 =
        count > 0 ? beatenAtCorners(&corners, c, segments[nearest], projectors[nearest], marginMm2)
                  : (REAL4)(INFINITY);
    const REAL4 beaten = sqrt(beaten2);
    // Lanes down the columns where the nearest segment runs closer to the
    // rows than to the columns: the lanes then lie along its normal, where
    // pixels share their nearest points, rather than along the contour,
    // where each lane needs other segments. Dense tiles only, by default:
    // a segment list is filtered per block of pixels the same either way.
    const REAL4 q = count > 0 ? segments[nearest] : (REAL4)(0);
    const bool acrossContour = fabs(q.z) > fabs(q.w);
    const uint columns = lanesAlong == LANES_ALONG_COLUMNS ? COLUMNS : 0u;
    const uint denseColumns =
        lanesAlong == LANES_ALONG_CONTOUR && acrossContour ? COLUMNS : columns;

    // The leaves that hold candidates, in order (a left-first walk visits
    // leaves in order), and how many segments they hold: where that is more
    // than leafListsFrom, they are the tile's list. The first KEPT_LEAVES
    // are kept, so that a sparse tile tests their segments without walking
    // the tree again.
    const uint leafRoom = min(capacity, (uint)BLOCK_LIST);
    uint kept[KEPT_LEAVES];
    uint n = 0, inLeaves = 0;
    node = count > 0 ? 1 : 0;
    while (node != 0 && n <= max(leafRoom, (uint)KEPT_LEAVES)) {
        if (!nodeDominated(&corners, beaten2, beaten, box, chord, chordProjector, dev, node)) {
            if (node < leaves) {
                node *= 2;
                continue;
            }
            if (n < leafRoom) list[n] = node - leaves;
            if (n < KEPT_LEAVES) kept[n] = node - leaves;
            ++n;
            inLeaves += min((uint)LEAF, count - (node - leaves) * LEAF);
        }
        while (node & 1) node >>= 1;
        if (node != 0) ++node;
    }
    if (inLeaves > leafListsFrom) {
        candidateCount[at] = (n <= leafRoom ? (n | LEAF_LISTED) : capacity + 1) | denseColumns;
        return;
    }
    // Stops one past what a segment list may hold.
    const uint stopAt = min(capacity, leafListsFrom);
    if (n <= KEPT_LEAVES) {  // the walk above was whole
        const uint keptLeaves = n;
        n = 0;
        for (uint k = 0; k < keptLeaves && n <= stopAt; ++k)
            listLeafSegments(&corners, beaten2, segments, projectors, first, count, kept[k], stopAt,
                             capacity, list, &n);
        candidateCount[at] = n | (n > capacity ? denseColumns : columns);
        return;
    }

    // Else (lists longer than leafListsFrom allows leaves for) the candidate
    // segments, walking the tree again.
    n = 0;
    node = count > 0 ? 1 : 0;
    while (node != 0 && n <= stopAt) {
        if (!nodeDominated(&corners, beaten2, beaten, box, chord, chordProjector, dev, node)) {
            if (node < leaves) {
                node *= 2;
                continue;
            }
            listLeafSegments(&corners, beaten2, segments, projectors, first, count, node - leaves,
                             stopAt, capacity, list, &n);
        }
        while (node & 1) node >>= 1;
        if (node != 0) ++node;
    }
    candidateCount[at] = n | (n > capacity ? denseColumns : columns);
}

// The entries of a tile's list (in segment order) that can be nearest to a
// pixel of the block of pixel centres lo..hi within the tile, in the same
// order, into `out`: those that the point of the contour nearest the block's
// centre does not beat at all four corners (tile_candidates' test, on a
// smaller box). That point is taken on segment `hint` where one is given (any
// point of the contour makes the test hold; a near one makes it strong).
// O(listed).
inline uint blockCandidates(__global const REAL4* segments, __global const REAL2* projectors,
                            __global const uint* list, uint listed, REAL2 lo, REAL2 hi,
                            REAL marginMm2, uint hint, uint* out) {
    const REAL2 c = (lo + hi) / 2;
    uint nearest = hint;
    if (hint == 0xffffffffu) {
        REAL best2 = INFINITY;
        nearest = list[0];
        for (uint k = 0; k < listed; ++k) {
            const REAL d2 = pointSegmentDistance2(c, segments[list[k]], projectors[list[k]]);
            if (d2 < best2) best2 = d2, nearest = list[k];
        }
    }
    const Corners corners = boxCorners(lo, hi);
    const REAL4 beaten2 =
        beatenAtCorners(&corners, c, segments[nearest], projectors[nearest], marginMm2);
    // Each entry written, and kept by moving on past it: no branch taken as
    // the data fall (n <= k, so it stays within the list's room).
    uint n = 0;
    for (uint k = 0; k < listed; ++k) {
        const uint seg = list[k];
        out[n] = seg;
        n += !beatenAtEveryCorner(&corners, segments[seg], projectors[seg], beaten2);
    }
    return n;
}

// blockCandidates for a tile that lists leaves: the leaves of its list that
// can hold the nearest segment of a pixel of the block lo..hi (nodeDominated
// fails), in order. Without a hint (*hint = 0xffffffff), the contour point
// comes from the nearest segment of the leaf whose chord is nearest the
// block's centre, and *hint receives that segment. O(listed + LEAF).
inline uint blockLeaves(__global const REAL4* segments, __global const REAL2* projectors,
                        uint first, uint count, __global const REAL4* box,
                        __global const REAL4* chord, __global const REAL2* chordProjector,
                        __global const REAL* dev, uint leaves, __global const uint* list,
                        uint listed, REAL2 lo, REAL2 hi, REAL marginMm2, uint* hint, uint* out) {
    const REAL2 c = (lo + hi) / 2;
    uint nearest = *hint;
    if (nearest == 0xffffffffu) {
        REAL best2 = INFINITY;
        uint leaf = list[0];
        for (uint k = 0; k < listed; ++k) {
            const uint node = leaves + list[k];
            const REAL d2 = pointSegmentDistance2(c, chord[node], chordProjector[node]);
            if (d2 < best2) best2 = d2, leaf = list[k];
        }
        best2 = INFINITY;
        nearestOfLeaf(c, segments, projectors, first, count, leaf, &best2, &nearest);
        *hint = nearest;
    }
    const Corners corners = boxCorners(lo, hi);
    const REAL4 beaten2 =
        beatenAtCorners(&corners, c, segments[nearest], projectors[nearest], marginMm2);
    const REAL4 beaten = sqrt(beaten2);
    uint n = 0;  // as in blockCandidates: written, then kept or not
    for (uint k = 0; k < listed; ++k) {
        out[n] = list[k];
        n += !nodeDominated(&corners, beaten2, beaten, box, chord, chordProjector, dev,
                            leaves + list[k]);
    }
    return n;
}

// Squared distance from each lane's point to its own segment
// segments[seg[lane]], all lanes at once. The lanes' coordinates are put
// together in registers: written to memory one by one and read back as a
// vector, they would wait for the stores to drain.
inline REALV laneSegmentDistance2(__global const REAL4* segments, __global const REAL2* projectors,
                                  const MASK_SCALAR* seg, REALV px, REAL py) {
#define SEGMENT(l)                             \
    const REAL4 s##l = segments[(uint)seg[l]]; \
    const REAL2 u##l = projectors[(uint)seg[l]]
#if LANES == 8
    SEGMENT(0);
    SEGMENT(1);
    SEGMENT(2);
    SEGMENT(3);
    SEGMENT(4);
    SEGMENT(5);
    SEGMENT(6);
    SEGMENT(7);
#define LANES_OF(f) ((REALV)(s0.f, s1.f, s2.f, s3.f, s4.f, s5.f, s6.f, s7.f))
#define PROJECTORS_OF(f) ((REALV)(u0.f, u1.f, u2.f, u3.f, u4.f, u5.f, u6.f, u7.f))
#elif LANES == 4
    SEGMENT(0);
    SEGMENT(1);
    SEGMENT(2);
    SEGMENT(3);
#define LANES_OF(f) ((REALV)(s0.f, s1.f, s2.f, s3.f))
#define PROJECTORS_OF(f) ((REALV)(u0.f, u1.f, u2.f, u3.f))
#else
    SEGMENT(0);
#define LANES_OF(f) (s0.f)
#define PROJECTORS_OF(f) (u0.f)
#endif
    const REALV ax = LANES_OF(x), ay = LANES_OF(y);
    const REALV abx = LANES_OF(z), aby = LANES_OF(w);
    const REALV ux = PROJECTORS_OF(x), uy = PROJECTORS_OF(y);
#undef LANES_OF
#undef PROJECTORS_OF
#undef SEGMENT
    const REALV apx = px - ax, apy = py - ay;
    const REALV t = clamp(apx * ux + apy * uy, (REAL)0, (REAL)1);
    const REALV qx = apx - t * abx, qy = apy - t * aby;
    return qx * qx + qy * qy;
}

// The lanes' nearest segment among those of `listed` leaves (in order), by
// scanning only the leaves some lane may find a nearer or tied segment in:
// `within2`, each lane's squared distance to some segment, bounds its
// nearest, and each leaf's capsule is tested against it as the walk does.
// The segments of the other leaves are farther by more than rounding, so
// the result is that of scanning every leaf. Two minima side by side, as in
// scanList. O(listed + LEAF · leaves scanned).
inline void scanLeaves(Nearest* n, __global const REAL4* segments, __global const REAL2* projectors,
                       uint first, uint count, __global const REAL4* chord,
                       __global const REAL2* chordProjector, __global const REAL* dev, uint leaves,
                       const uint* list, uint listed, REALV within2, REALV px, REAL py,
                       REAL slackMm) {
    Nearest bound;
    bound.best2 = within2;
    updateReach(&bound, slackMm);
    Nearest even = *n, odd = *n;
    for (uint chunk = 0; chunk < listed; chunk += 64) {
        // Which of up to 64 leaves are within reach, as bits, before any is
        // scanned: a branch per leaf, taken as the data fall, cost more
        // than testing them all first (a tenth of the 10 000-segment
        // bench). The capsule alone: a leaf's box hardly prunes more.
        ulong reached = 0;
        for (uint k = chunk; k < min(chunk + 64, listed); ++k)
            reached |= (ulong)ANY(capsuleWithinReach(&bound, chord, chordProjector, dev,
                                                     leaves + list[k], px, py))
                       << (k - chunk);
        while (reached != 0) {
            const uint k = chunk + 63 - clz(reached & -reached);  // lowest bit first
            reached &= reached - 1;
            const uint begin = first + list[k] * LEAF, end = min(begin + LEAF, first + count);
            uint seg = begin;
            for (; seg + 1 < end; seg += 2) {
                considerInOrder(&even, segments, projectors, seg, px, py);
                considerInOrder(&odd, segments, projectors, seg + 1, px, py);
            }
            if (seg < end) considerInOrder(&even, segments, projectors, seg, px, py);
        }
    }
    mergeMinima(n, &even, &odd);
}

// The lanes' primitive ids (field/PrimitiveId.hpp): of their nearest
// segment seg[lane] (ids[k] = (segment id, id of its end vertex)), or of
// the end vertex their nearest point is (parameter t at 0 or 1; the start
// vertex id is segment id | 1). The ids are put together in registers, as
// in laneSegmentDistance2.
inline UINTV laneIds(__global const uint2* ids, const MASK_SCALAR* seg, REALV t) {
#define ID(l) const uint2 e##l = ids[(uint)seg[l]]
#if LANES == 8
    ID(0);
    ID(1);
    ID(2);
    ID(3);
    ID(4);
    ID(5);
    ID(6);
    ID(7);
    const UINTV start = (UINTV)(e0.x, e1.x, e2.x, e3.x, e4.x, e5.x, e6.x, e7.x);
    const UINTV end = (UINTV)(e0.y, e1.y, e2.y, e3.y, e4.y, e5.y, e6.y, e7.y);
#elif LANES == 4
    ID(0);
    ID(1);
    ID(2);
    ID(3);
    const UINTV start = (UINTV)(e0.x, e1.x, e2.x, e3.x), end = (UINTV)(e0.y, e1.y, e2.y, e3.y);
#else
    ID(0);
    const UINTV start = e0.x, end = e0.y;
#endif
#undef ID
    const UINTV id = SELECT_ID(start, end, isgreaterequal(t, (REALV)(1)));
    return SELECT_ID(id, start | 1u, islessequal(t, (REALV)(0)));
}

// The first of crossings[lo, hi) (one row's, sorted by k) with k > i, or hi:
// its w is the winding number at pixel i (signed_distance_2d says how
// crossings are laid out). Binary search.
inline uint firstCrossingAfter(__global const int2* crossings, uint lo, uint hi, uint i) {
    while (lo < hi) {
        const uint mid = (lo + hi) / 2;
        if ((uint)crossings[mid].x > i)
            hi = mid;
        else
            lo = mid + 1;
    }
    return lo;
}

// Writes the lanes' pixels (i0 .. i0 + LANES - 1, up to the row's width)
// of row `row`: distances signed by the winding numbers from the row's
// crossings, and ids. O(log crossings + the crossings among the pixels).
__attribute__((always_inline)) inline void writeRow(__global const uint* rowFirst,
                                                    __global const int2* crossings, size_t row,
                                                    uint i0, uint width, REALV unsigned_, UINTV id,
                                                    __global float* distance,
                                                    __global uint* nearestId) {
    const uint rowEnd = rowFirst[row + 1];
    const uint lo = firstCrossingAfter(crossings, rowFirst[row], rowEnd, i0);
    const INTV lane = (INTV)(i0) + LANE_OFFSETS;
    INTV winding = (INTV)(lo < rowEnd ? crossings[lo].y : 0);
    for (uint c = lo; c < rowEnd && (uint)crossings[c].x < i0 + LANES; ++c) {
        // Lanes at or right of this crossing no longer count it.
        const int counted = crossings[c].y - (c + 1 < rowEnd ? crossings[c + 1].y : 0);
        winding -= PICK((INTV)(0), (INTV)(counted), lane >= (INTV)(crossings[c].x));
    }
    const REALV signed_ = PICK(unsigned_, -unsigned_, CONVERT_MASKV(winding != (INTV)(0)));
    const size_t pixel = row * width + i0;
    if (i0 + LANES <= width) {
        VSTORE(CONVERT_FLOATV(signed_), 0, distance + pixel);
        VSTORE(id, 0, nearestId + pixel);
    } else {
        float d[LANES];
        uint idl[LANES];
        VSTORE(CONVERT_FLOATV(signed_), 0, d);
        VSTORE(id, 0, idl);
        for (uint l = 0; i0 + l < width; ++l)
            distance[pixel + l] = d[l], nearestId[pixel + l] = idl[l];
    }
}

// Where writeColumn's lanes stand in their rows' crossings: next[lane] is
// the first crossing with k > the column last written (or the row's end),
// winding[lane] its w (0 at the end), and changeAt the least k among them,
// the first column at which any of them moves on.
typedef struct {
    uint next[LANES];
    int winding[LANES];
    uint changeAt;
} ColumnCrossings;

// writeRow for lanes down a column: pixel i of rows `firstRow` + lane (of
// all the batch's rows), up to `lanesIn` of them. Columns come in
// increasing order, so each lane's place in its crossings only moves on,
// and only at a column that holds one (most columns hold none): O(1) per
// pixel beyond the crossings passed.
__attribute__((always_inline)) inline void writeColumn(
    __global const uint* rowFirst, __global const int2* crossings, size_t firstRow, uint lanesIn,
    uint i, uint width, REALV unsigned_, UINTV id, ColumnCrossings* at, __global float* distance,
    __global uint* nearestId) {
    if (i >= at->changeAt) {
        uint changeAt = 0xffffffffu;
        for (uint l = 0; l < lanesIn; ++l) {
            const uint rowEnd = rowFirst[firstRow + l + 1];
            uint c = at->next[l];
            while (c < rowEnd && (uint)crossings[c].x <= i) ++c;
            at->next[l] = c;
            at->winding[l] = c < rowEnd ? crossings[c].y : 0;
            if (c < rowEnd) changeAt = min(changeAt, (uint)crossings[c].x);
        }
        at->changeAt = changeAt;
    }
    float d[LANES];
    uint idl[LANES];
    VSTORE(CONVERT_FLOATV(unsigned_), 0, d);
    VSTORE(id, 0, idl);
    for (uint l = 0; l < lanesIn; ++l) {
        const size_t pixel = (firstRow + l) * width + i;
        distance[pixel] = at->winding[l] != 0 ? -d[l] : d[l];
        nearestId[pixel] = idl[l];
    }
}

// One work-item per LANES pixels of a tile of slice s of the batch, in one
// of two frames the tile's count picks (COLUMNS): lanes along a row (pixels
// i0 .. i0+LANES-1) for each of the tile's TILE rows in turn, or lanes down
// a column (TILE / LANES work-items share the tile's rows) for each of its
// columns in turn. In the second frame the work-item reads the transposed
// geometry (x and y swapped: segmentsYX, boxesYX, chordsYX and the
// projectors), so the same
// code computes both; `step` is then a column and the lanes are rows. Each
// step takes the tile's list of segments or of leaves when it has one, else
// the walk of the tree; both of the latter start from the nearest segments
// of the step before, so their bound is tight from the start. ids[k] =
// (segment id, id of its end vertex); the start vertex id is segment id | 1.
// Sign: the crossings of row j are crossings[rowFirst[r] .. rowFirst[r + 1])
// with r = s * height + j, sorted by k, each (k, w): the contour crosses the
// row between pixel k - 1 and k (windingCrossing() counts it for pixels
// i < k), and w is the winding those crossings from this one to the row's
// end add. So the winding number at pixel i is the w of the first crossing
// with k > i (0 if none): writeRow finds it by binary search, writeColumn
// by moving on from the column before.
__kernel __attribute__((reqd_work_group_size(TILE / LANES, 1, 1))) void signed_distance_2d(
    SLICE_GEOMETRY, const TileParams params, __global const uint* candidates,
    __global const uint* candidateCount, __global const uint* rowFirst,
    __global const int2* crossings, __global float* distance, __global uint* nearestId) {
    const uint width = params.width, height = params.height;
    const REAL pixelMm = params.pixelMm, slackMm = params.slackMm, marginMm2 = params.marginMm2;
    const uint capacity = params.capacity;
    const uint tx = get_global_id(0) * LANES / TILE, ty = get_global_id(1), s = get_global_id(2);
    const uint within = get_global_id(0) * LANES % TILE;  // the work-item's lanes in the tile
    const uint tilesX = (width + TILE - 1) / TILE, tilesY = (height + TILE - 1) / TILE;
    const size_t tile = ((size_t)s * tilesY + ty) * tilesX + tx;
    const uint counted = candidateCount[tile];
    const bool down = (counted & COLUMNS) != 0;
    const uint listed = counted & ~COLUMNS;
    // The work-item's frame: lanes laneFirst.. along one axis (of laneLimit
    // pixels), steps stepFirst.. along the other (of stepLimit).
    const uint laneFirst = (down ? ty : tx) * TILE + within, laneLimit = down ? height : width;
    const uint stepFirst = (down ? tx : ty) * TILE, stepLimit = down ? width : height;
    if (laneFirst >= laneLimit) return;  // padding of the last tiles (no barriers below)
    __global const REAL4* segments = down ? segmentsYX : segmentsXY;
    __global const REAL2* projectors = down ? projectorsYX : projectorsXY;
    const REALV px = (CONVERT_REALV((INTV)(laneFirst) + LANE_OFFSETS) + (REAL)0.5) * pixelMm;
    const uint first = sliceFirst[s], count = sliceCount[s];
    const uint tree = treeFirst[s];
    __global const REAL4* box = (down ? boxesYX : boxesXY) + tree;
    __global const REAL4* chord = (down ? chordsYX : chordsXY) + tree;
    __global const REAL2* chordProjector = (down ? chordProjectorsYX : chordProjectorsXY) + tree;
    __global const REAL* dev = devs + tree;
    const uint leaves = leafBase[s];
    __global const uint* list = candidates + tile * capacity;

    MASK_SCALAR segs[LANES];  // each lane's nearest segment in the step before
    // ... moved on along the contour as far as it moved from the step before
    // that, by at most MAX_MOVE segments: where the nearest point slides
    // along the contour from step to step, a near bound (any segment
    // bounds). Where it jumps (across the medial axis, or to another
    // contour), a jump repeated lands anywhere, and that lane's loose bound
    // made its whole row scan more leaves: with the move capped, a row
    // scans 3.62 leaves instead of 4.05 at 10 000 segments (3.44 with exact
    // bounds).
    MASK_SCALAR ahead[LANES];
    uint block[BLOCK_LIST];  // the list's entries for the current BLOCK_ROWS steps
    uint blockListed = 0;
    const uint lastLane = min(laneFirst + LANES, laneLimit) - 1;
    ColumnCrossings columnCrossings;  // writeColumn's; its first call finds the windings
    columnCrossings.changeAt = 0;
    if (down)
        for (uint l = 0; l < LANES; ++l) {
            const size_t row = (size_t)s * height + min(laneFirst + l, lastLane);
            columnCrossings.next[l] =
                firstCrossingAfter(crossings, rowFirst[row], rowFirst[row + 1], stepFirst);
        }
    const uint lastStep = min(stepFirst + TILE, stepLimit) - 1;
    for (uint j = stepFirst; j <= lastStep; ++j) {
        const REAL py = (j + (REAL)0.5) * pixelMm;
        // The box of pixel centres of this step and the next BLOCK_ROWS - 1.
#define BLOCK_LO (REAL2)((laneFirst + (REAL)0.5) * pixelMm, py)
#define BLOCK_HI                              \
    (REAL2)((lastLane + (REAL)0.5) * pixelMm, \
            (min(j + BLOCK_ROWS - 1, lastStep) + (REAL)0.5) * pixelMm)
        Nearest n;
        n.best2 = (REALV)(INFINITY), n.bestT = (REALV)(0);
        n.bestSeg = (MASKV)(0);
        if (listed & LEAF_LISTED) {
            const uint leafCount = listed & ~LEAF_LISTED;
            uint hint = j == stepFirst ? 0xffffffffu : (uint)segs[LANES / 2];
            if ((j - stepFirst) % BLOCK_ROWS == 0)
                blockListed = blockLeaves(segments, projectors, first, count, box, chord,
                                          chordProjector, dev, leaves, list, leafCount, BLOCK_LO,
                                          BLOCK_HI, marginMm2, &hint, block);
            // Each lane's bound: its nearest segment in the step before,
            // moved on along the contour as far as it moved then (ahead).
            // The lesser of that and the unmoved segment was no tighter
            // overall: 5.13 against 5.05 ms at 10 000 segments, as the
            // second gather cost more than the leaves it saved. On the
            // tile's first step, the lesser of the distances to the segment
            // nearest the block's centre and to the first point of each leaf
            // of the block (its first segment's start: a contour point, so a
            // bound too): for
            // lanes far from the centre the segment alone is loose, and
            // those rows scanned 7.8 leaves instead of 4.0. On every step
            // the vertices would make the bound nearly exact (3.47 leaves a
            // row instead of 3.62), but cost more than the segments saved.
            REALV t;
            REALV within2;
            if (j == stepFirst) {
                within2 = segmentDistance2(segments[hint], projectors[hint], px, py, &t);
                for (uint k = 0; k < blockListed; ++k) {
                    const REAL4 vertex = segments[first + block[k] * LEAF];
                    const REALV dx = px - vertex.x;
                    const REAL dy = py - vertex.y;
                    within2 = fmin(within2, dx * dx + dy * dy);
                }
            } else {
                within2 = laneSegmentDistance2(segments, projectors, ahead, px, py);
            }
            scanLeaves(&n, segments, projectors, first, count, chord, chordProjector, dev, leaves,
                       block, blockListed, within2, px, py, slackMm);
        } else if (listed <= capacity && listed <= BLOCK_LIST) {
            if ((j - stepFirst) % BLOCK_ROWS == 0 && listed > 0)
                blockListed = blockCandidates(
                    segments, projectors, list, listed, BLOCK_LO, BLOCK_HI, marginMm2,
                    j == stepFirst ? 0xffffffffu : (uint)segs[LANES / 2], block);
            scanList(&n, segments, projectors, block, blockListed, px, py);
        } else if (listed <= capacity) {
            // Longer lists than a block holds (a capacity set by the caller):
            // the whole list, a block at a time.
            for (uint k = 0; k < listed; k += BLOCK_LIST) {
                const uint m = min(listed - k, (uint)BLOCK_LIST);
                for (uint e = 0; e < m; ++e) block[e] = list[k + e];
                scanList(&n, segments, projectors, block, m, px, py);
            }
        } else if (count > 0) {
            uint start;  // a leaf near the lanes, where the walk starts
            if (j == stepFirst) {
                // No step before: the leaf down the nearer side of each node.
                start = 1;
                while (start < leaves) {
                    const REAL left = LANE_MIN(boxDistance2(box[2 * start], px, py));
                    const REAL right = LANE_MIN(boxDistance2(box[2 * start + 1], px, py));
                    start = 2 * start + (right < left ? 1 : 0);
                }
            } else {
                for (int l = 0; l < LANES; ++l)
                    if (l == 0 || segs[l] != segs[l - 1])
                        consider(&n, segments, projectors, (uint)segs[l], px, py);
                start = leaves + ((uint)segs[LANES / 2] - first) / LEAF;
            }
            updateReach(&n, slackMm);
            // The start leaf, then the sibling subtree of each of its
            // ancestors, nearest first: every leaf once. Depth first within a
            // subtree, left before right, without a stack: after a node,
            // climb past right children and step to the sibling.
            if (worthVisiting(&n, box, chord, chordProjector, dev, start, px, py)) {
                visitLeaf(&n, segments, projectors, first, count, start - leaves, px, py);
                updateReach(&n, slackMm);
            }
            for (uint below = start; below > 1; below >>= 1) {
                const uint root = below ^ 1;
                uint node = root;
                for (;;) {
                    if (worthVisiting(&n, box, chord, chordProjector, dev, node, px, py)) {
                        if (node < leaves) {
                            node *= 2;
                            continue;
                        }
                        visitLeaf(&n, segments, projectors, first, count, node - leaves, px, py);
                        updateReach(&n, slackMm);
                    }
                    while (node != root && (node & 1)) node >>= 1;
                    if (node == root) break;
                    ++node;
                }
            }
        }

#undef BLOCK_LO
#undef BLOCK_HI
        if (listed & LEAF_LISTED) {  // segs still holds the step before's
            const MASKV moved = j == stepFirst ? (MASKV)(0)
                                               : clamp(n.bestSeg - VLOAD(0, segs),
                                                       (MASKV)(-MAX_MOVE), (MASKV)(MAX_MOVE));
            VSTORE(clamp(n.bestSeg + moved, (MASKV)(first), (MASKV)(first + count - 1)), 0, ahead);
        }
        VSTORE(n.bestSeg, 0, segs);
        const UINTV id = count > 0 ? laneIds(ids, segs, n.bestT) : (UINTV)(0xffffffffu);
        const REALV unsigned_ = sqrt(n.best2);
        if (down)
            writeColumn(rowFirst, crossings, (size_t)s * height + laneFirst,
                        lastLane - laneFirst + 1, j, width, unsigned_, id, &columnCrossings,
                        distance, nearestId);
        else
            writeRow(rowFirst, crossings, (size_t)s * height + j, laneFirst, width, unsigned_, id,
                     distance, nearestId);
    }
}
