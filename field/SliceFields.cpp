#include "field/SliceFields.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <future>
#include <limits>
#include <stdexcept>
#include <string>
#include <type_traits>

#include "cl/DeviceBuffer.hpp"
#include "cl/HostScratch.hpp"
#include "cl/Precision.hpp"
#include "geometry/ClosestPoint.hpp"

namespace dfrecon {

namespace {

// Host tables and lists live in kept scratch memory: fresh pages for them on
// every call cost up to 0.8 ms of a 5.5 ms field (cl/HostScratch.hpp).
using ocl::ScratchVector;

// Tile sides in pixels (a work-group's): wide tiles where segments are
// shorter than kWideTilesBelowPx on average. There nearly every tile lists
// leaves, and a wide tile lists them with a quarter of the tree walks for
// little more filtering per block of pixels: 5000, 10 000 and 20 000
// segments took 10, 5 and 5 % less time; 1 000 and 3 000 took 26 and 3 %
// more, as segment lists grow with the tile (docs/fields.md).
constexpr std::uint32_t kTile = 16, kWideTile = 32;
constexpr double kWideTilesBelowPx = 0.5;
constexpr std::uint32_t kLeaf = 8;  // segments per leaf of the box tree
// Candidates a tile lists at most; beyond, its pixels walk the tree. Each
// work-item filters the list again per 8 rows, so long lists still scan
// faster than the walk: 96 and 192 were slower on dense contours, 512 and
// 640 no faster (docs/fields.md).
constexpr int kListCapacity = 320;
// Tiles whose candidates lie in leaves of more segments than this list the
// leaves instead (FieldKernelOptions::leafListsFrom): 32 to 128 were no
// better on the bench's contours (docs/fields.md).
constexpr int kLeafListsFrom = 96;
// The bit of a tile's count that says it lists leaves (the kernel's
// LEAF_LISTED).
constexpr cl_uint kLeafListed = 0x80000000u;
// The bit that says its work-items' lanes go down its columns (the kernel's
// COLUMNS).
constexpr cl_uint kColumns = 0x40000000u;
// Segments in a batch from which the rows' crossings are found on a thread
// of their own (runBatch): 10 000 and 5 000 segments took 3 % less time,
// 2 000 the same, 1 000 and 100 up to 15 % more (the thread's start).
constexpr std::size_t kCrossingsThreadFrom = 2000;
// Pixels per launch: bounds the output buffers (8 bytes a pixel) and gives
// progress reports between launches.
constexpr std::size_t kPixelsPerBatch = std::size_t(1) << 22;

void checkLimits(const std::vector<Slice>& slices) {
    for (const Slice& slice : slices) {
        if (slice.contours.size() >= kMaxContoursPerSlice)
            throw PrimitiveLimitExceeded("slice z=" + std::to_string(slice.zMm) + " has over " +
                                         std::to_string(kMaxContoursPerSlice - 1) + " contours");
        for (const Polygon& c : slice.contours)
            if (c.size() >= kMaxPrimitivesPerContour)
                throw PrimitiveLimitExceeded(
                    "a contour at z=" + std::to_string(slice.zMm) + " has over " +
                    std::to_string(kMaxPrimitivesPerContour - 1) + " points");
    }
}

// Segments of a run of slices, flattened in (slice, contour, index) order:
// endpoints relative to the grid origin and the ids the kernel reports; per
// slice a heap of boxes and capsules over leaves of kLeaf consecutive
// segments (the kernel's header says how it is read).
template <class Real4>
struct FlatSegments {
    ScratchVector<Real4> segments;
    ScratchVector<cl_uint2> ids;  // (segment id, end vertex id)
    std::vector<cl_uint> sliceFirst, sliceCount;
    ScratchVector<Real4> boxes;   // (xmin, ymin, xmax, ymax) per node
    ScratchVector<Real4> chords;  // per node: (ax, ay, bx, by), a segment that lies within
    ScratchVector<double> devs;   // dev of all its segments (in the Real coordinates)
    std::vector<cl_uint> treeFirst, leafBase;  // per slice: its heap in boxes, first leaf node
    double magnitudeMm = 0;                    // largest coordinate, for the rounding slack
    double lengthMm = 0;                       // of all the segments, for the tile size
};

template <class Real4>
Real4 emptyBox() {
    constexpr double inf = std::numeric_limits<double>::infinity();
    Real4 box;
    box.s[0] = inf, box.s[1] = inf, box.s[2] = -inf, box.s[3] = -inf;
    return box;
}

template <class Real4>
Real4 unite(Real4 a, Real4 b) {
    Real4 box;
    box.s[0] = std::min(a.s[0], b.s[0]), box.s[1] = std::min(a.s[1], b.s[1]);
    box.s[2] = std::max(a.s[2], b.s[2]), box.s[3] = std::max(a.s[3], b.s[3]);
    return box;
}

// Segments (ax, ay, bx, by) as the kernel reads them: (ax, ay, bx - ax,
// by - ay), the differences rounded once from the exact ones.
template <class Real4>
ScratchVector<Real4> originAndStep(const ScratchVector<Real4>& segments) {
    ScratchVector<Real4> kernelForm(segments.size());
    std::transform(segments.begin(), segments.end(), kernelForm.begin(), [](const Real4& s) {
        using Real = std::decay_t<decltype(s.s[0])>;
        Real4 r = s;
        r.s[2] = Real(double(s.s[2]) - double(s.s[0]));
        r.s[3] = Real(double(s.s[3]) - double(s.s[1]));
        return r;
    });
    return kernelForm;
}

// Each segment's projector (b - a) / |b - a|^2, (0, 0) for a point: the
// nearest point of the segment to p has parameter dot(p - a, projector)
// clamped to [0, 1], with no division in the kernel.
template <class Real2, class Real4>
ScratchVector<Real2> projectorsOf(const ScratchVector<Real4>& segments) {
    ScratchVector<Real2> projectors(segments.size());
    std::transform(segments.begin(), segments.end(), projectors.begin(), [](const Real4& s) {
        const double dx = double(s.s[2]) - double(s.s[0]), dy = double(s.s[3]) - double(s.s[1]);
        const double length2 = dx * dx + dy * dy;
        const double inverse = length2 > 0 ? 1 / length2 : 0;
        using Real = std::decay_t<decltype(s.s[0])>;
        Real2 r;
        r.s[0] = Real(dx * inverse), r.s[1] = Real(dy * inverse);
        return r;
    });
    return projectors;
}

// The same vectors with x and y swapped ((y0, x0, y1, x1) or (y, x)): the
// kernel's frame for lanes down a column.
template <class RealN>
ScratchVector<RealN> swappedXY(const ScratchVector<RealN>& vectors) {
    ScratchVector<RealN> swapped(vectors.size());
    std::transform(vectors.begin(), vectors.end(), swapped.begin(), [](const RealN& v) {
        RealN r = v;
        for (std::size_t k = 0; k + 1 < sizeof(v.s) / sizeof(v.s[0]); k += 2)
            r.s[k] = v.s[k + 1], r.s[k + 1] = v.s[k];
        return r;
    });
    return swapped;
}

// A table the kernels read in both of the field kernel's frames: as it is
// (lanes along rows) and with x and y swapped (lanes down columns), each
// with its buffer. On CPU devices the buffers are these vectors themselves
// (DeviceBuffer::reading), so the table stays where it was made.
template <class T>
struct FramedTable {
    FramedTable(ocl::Runtime& runtime, ScratchVector<T> table)
        : xy(std::move(table)),
          yx(swappedXY(xy)),
          xyBuffer(ocl::DeviceBuffer<T>::reading(runtime, xy)),
          yxBuffer(ocl::DeviceBuffer<T>::reading(runtime, yx)) {}
    FramedTable(const FramedTable&) = delete;
    FramedTable& operator=(const FramedTable&) = delete;

    const ScratchVector<T> xy, yx;
    const ocl::DeviceBuffer<T> xyBuffer, yxBuffer;
};

// The kernels' TileParams (kernels/closest_segment_2d.cl), member for
// member: the kernels read these bytes as they are, so the layout is
// asserted below for both of REAL's types.
template <class Real>
struct TileParams {
    Real pixelMm, slackMm, marginMm2;
    cl_uint width, height, capacity, leafListsFrom, lanesAlong;
    cl_uint padding = 0;
};

template <class Real>
constexpr bool tileParamsLaidOutAsTheKernels() {
    using P = TileParams<Real>;
    constexpr std::size_t r = sizeof(Real), u = sizeof(cl_uint);
    return std::is_standard_layout_v<P> && std::is_trivially_copyable_v<P> &&
           offsetof(P, pixelMm) == 0 && offsetof(P, slackMm) == r &&
           offsetof(P, marginMm2) == 2 * r && offsetof(P, width) == 3 * r &&
           offsetof(P, height) == 3 * r + u && offsetof(P, capacity) == 3 * r + 2 * u &&
           offsetof(P, leafListsFrom) == 3 * r + 3 * u &&
           offsetof(P, lanesAlong) == 3 * r + 4 * u && offsetof(P, padding) == 3 * r + 5 * u &&
           sizeof(P) == 3 * r + 6 * u;
}
static_assert(tileParamsLaidOutAsTheKernels<cl_double>() && sizeof(TileParams<cl_double>) == 48);
static_assert(tileParamsLaidOutAsTheKernels<cl_float>() && sizeof(TileParams<cl_float>) == 36);

// The tree of segments[first, first + count): O(count). Capsules are
// computed in double from the coordinates the kernel reads; its b - a
// rounded once (originAndStep) and a dev rounded down to float are covered
// by the kernel's slack.
template <class Real4>
void appendTree(FlatSegments<Real4>& flat, std::size_t first, std::size_t count) {
    std::size_t leaves = 1;
    while (leaves * kLeaf < count) leaves *= 2;
    // Beyond, the kernel's uint node indices (up to 2·leaves) would overflow.
    if (leaves > (std::size_t(1) << 30))
        throw PrimitiveLimitExceeded("a slice has too many segments for the field kernel");
    flat.treeFirst.push_back(cl_uint(flat.boxes.size()));
    flat.leafBase.push_back(cl_uint(leaves));
    const std::size_t heap = flat.boxes.size();
    flat.boxes.resize(heap + 2 * leaves, emptyBox<Real4>());
    flat.chords.resize(heap + 2 * leaves, Real4{});
    flat.devs.resize(heap + 2 * leaves, 0.0);
    Real4* box = flat.boxes.data() + heap;
    Real4* chord = flat.chords.data() + heap;
    double* dev = flat.devs.data() + heap;
    const auto point = [](const Real4& r, int end) {
        return Point2{double(r.s[2 * end]), double(r.s[2 * end + 1])};
    };
    const auto chordOf = [&](Point2 a, Point2 b) {
        Real4 r;
        r.s[0] = a.x, r.s[1] = a.y, r.s[2] = b.x, r.s[3] = b.y;
        return r;
    };
    // Squared distance from p to the chord a + t·ab (the shared closest-point
    // parameter, with b - a formed once per chord rather than per call).
    const auto chordDistance2 = [](Point2 p, Point2 a, Point2 ab) {
        const Point2 ap = p - a;
        const Point2 q = ap - nearestSegmentParameter(ap.x, ap.y, ab.x, ab.y) * ab;
        return dot(q, q);
    };
    for (std::size_t leaf = 0; leaf * kLeaf < count; ++leaf) {
        const std::size_t begin = first + leaf * kLeaf,
                          end = std::min(begin + kLeaf, first + count);
        const Point2 a = point(flat.segments[begin], 0), b = point(flat.segments[end - 1], 1);
        Real4& into = box[leaves + leaf];
        double& radius = dev[leaves + leaf];
        // Distance to a segment is convex: the ends bound the segment. In
        // squares, with one square root per leaf (hypot per end cost a
        // quarter of the host's time on dense contours).
        const Point2 ab = b - a;
        double radius2 = 0;
        for (std::size_t k = begin; k < end; ++k) {
            const Real4 s = flat.segments[k];
            Real4 segmentBox;
            segmentBox.s[0] = std::min(s.s[0], s.s[2]), segmentBox.s[1] = std::min(s.s[1], s.s[3]);
            segmentBox.s[2] = std::max(s.s[0], s.s[2]), segmentBox.s[3] = std::max(s.s[1], s.s[3]);
            into = unite(into, segmentBox);
            radius2 = std::max(
                {radius2, chordDistance2(point(s, 0), a, ab), chordDistance2(point(s, 1), a, ab)});
        }
        radius = std::sqrt(radius2);
        chord[leaves + leaf] = chordOf(a, b);
    }
    for (std::size_t n = leaves - 1; n >= 1; --n) {
        const std::size_t l = 2 * n, r = l + 1;
        box[n] = unite(box[l], box[r]);
        if (!(box[r].s[0] <= box[r].s[2])) {  // right side empty
            chord[n] = chord[l], dev[n] = dev[l];
            continue;
        }
        // Each child's segments lie within its dev of its chord, whose
        // points lie within the larger distance of its ends from ours.
        const Point2 a = point(chord[l], 0), b = point(chord[r], 1), ab = b - a;
        chord[n] = chordOf(a, b);
        for (const std::size_t c : {l, r})
            dev[n] = std::max(
                dev[n], dev[c] + std::sqrt(std::max(chordDistance2(point(chord[c], 0), a, ab),
                                                    chordDistance2(point(chord[c], 1), a, ab))));
    }
}

// Segments of slices[begin, end): one per contour point. O(contours).
std::size_t segmentCount(const std::vector<Slice>& slices, std::size_t begin, std::size_t end) {
    std::size_t count = 0;
    for (std::size_t s = begin; s < end; ++s)
        for (const Polygon& contour : slices[s].contours) count += contour.size();
    return count;
}

template <class Real4>
FlatSegments<Real4> flatten(const std::vector<Slice>& slices, std::size_t begin, std::size_t end,
                            const SliceGrid& grid) {
    FlatSegments<Real4> flat;
    flat.magnitudeMm = double(std::max(grid.width, grid.height)) * grid.pixelMm;
    const std::size_t total = segmentCount(slices, begin, end);
    // Written in place: a segment or id pair put together on the stack and
    // copied in was read back before its stores had landed, which stalled
    // each copy (two fifths of this function's time at 10 000 segments).
    flat.segments.resize(total);
    flat.ids.resize(total);
    std::size_t at = 0;
    for (std::size_t s = begin; s < end; ++s) {
        const std::size_t first = at;
        const auto& contours = slices[s].contours;
        for (std::uint32_t c = 0; c < contours.size(); ++c) {
            const std::uint32_t n = std::uint32_t(contours[c].size());
            for (std::uint32_t k = 0; k < n; ++k, ++at) {
                const std::uint32_t next = k + 1 == n ? 0 : k + 1;  // no division per segment
                const Point2 a = contours[c][k] - grid.originMm,
                             b = contours[c][next] - grid.originMm;
                flat.magnitudeMm = std::max({flat.magnitudeMm, std::abs(a.x), std::abs(a.y)});
                // Not length(): its hypot took a fifth of this loop, and
                // the mean length only picks the tile size.
                flat.lengthMm += std::sqrt(dot(b - a, b - a));
                Real4& r = flat.segments[at];
                r.s[0] = a.x, r.s[1] = a.y, r.s[2] = b.x, r.s[3] = b.y;
                cl_uint2& id = flat.ids[at];
                id.s[0] = PrimitiveId{c, k, false}.encode();
                id.s[1] = PrimitiveId{c, next, true}.encode();
            }
        }
        flat.sliceFirst.push_back(cl_uint(first));
        flat.sliceCount.push_back(cl_uint(at - first));
        appendTree(flat, first, at - first);
    }
    return flat;
}

// The tables of a batch's geometry that both kernels take first
// (SLICE_GEOMETRY in kernels/closest_segment_2d.cl), made from `flat`, which
// must outlive them: on CPU devices the buffers are host vectors themselves
// (DeviceBuffer::reading), flat's among them.
template <class Real, class Real4>
struct SliceGeometry {
    using Real2 = std::conditional_t<std::is_same_v<Real, cl_double>, cl_double2, cl_float2>;

    SliceGeometry(ocl::Runtime& runtime, FlatSegments<Real4>& flat)
        : segments(runtime, originAndStep(flat.segments)),
          projectors(runtime, projectorsOf<Real2>(flat.segments)),
          boxes(runtime, std::move(flat.boxes)),
          chords(runtime, originAndStep(flat.chords)),
          chordProjectors(runtime, projectorsOf<Real2>(flat.chords)),
          devTable(flat.devs.begin(), flat.devs.end()),
          devs(ocl::DeviceBuffer<Real>::reading(runtime, devTable)),
          ids(ocl::DeviceBuffer<cl_uint2>::reading(runtime, flat.ids)),
          sliceFirst(ocl::DeviceBuffer<cl_uint>::reading(runtime, flat.sliceFirst)),
          sliceCount(ocl::DeviceBuffer<cl_uint>::reading(runtime, flat.sliceCount)),
          treeFirst(ocl::DeviceBuffer<cl_uint>::reading(runtime, flat.treeFirst)),
          leafBase(ocl::DeviceBuffer<cl_uint>::reading(runtime, flat.leafBase)) {}

    // Sets the kernel's SLICE_GEOMETRY arguments from argument `first` on;
    // returns the index of the argument after them.
    cl_uint setArgs(cl::Kernel& kernel, cl_uint first) const {
        for (const cl::Buffer* buffer :
             {&segments.xyBuffer.get(), &segments.yxBuffer.get(), &projectors.xyBuffer.get(),
              &projectors.yxBuffer.get(), &ids.get(), &boxes.xyBuffer.get(), &boxes.yxBuffer.get(),
              &chords.xyBuffer.get(), &chords.yxBuffer.get(), &chordProjectors.xyBuffer.get(),
              &chordProjectors.yxBuffer.get(), &devs.get(), &sliceFirst.get(), &sliceCount.get(),
              &treeFirst.get(), &leafBase.get()})
            kernel.setArg(first++, *buffer);
        return first;
    }

    const FramedTable<Real4> segments;
    const FramedTable<Real2> projectors;
    const FramedTable<Real4> boxes, chords;
    const FramedTable<Real2> chordProjectors;
    const ScratchVector<Real> devTable;
    const ocl::DeviceBuffer<Real> devs;
    const ocl::DeviceBuffer<cl_uint2> ids;
    const ocl::DeviceBuffer<cl_uint> sliceFirst, sliceCount, treeFirst, leafBase;
};

// Where the contours cross each pixel row, as the kernel reads them: per row
// sorted by k, each (k, w) with windingCrossing() counting the edge for
// pixels i < k exactly (the same double arithmetic as windingNumber() at
// each pixel centre, so the sign is the reference's everywhere, on the
// contour too), w the sum of the directions from this crossing to the row's
// end. O(segments · rows they span + crossings · log).
struct RowCrossings {
    ScratchVector<cl_uint> rowFirst;  // size rows + 1
    ScratchVector<cl_int2> crossings;
};

RowCrossings rowCrossings(const std::vector<Slice>& slices, std::size_t begin, std::size_t end,
                          const SliceGrid& grid) {
    std::vector<std::vector<cl_int2>> perRow((end - begin) * std::size_t(grid.height));
    for (std::size_t s = begin; s < end; ++s)
        for (const Polygon& contour : slices[s].contours)
            for (std::size_t k = 0; k < contour.size(); ++k) {
                const Point2 a = contour[k], b = contour[k + 1 == contour.size() ? 0 : k + 1];
                if (a.y == b.y) continue;
                const double lo = std::min(a.y, b.y), hi = std::max(a.y, b.y);
                // A row or so more on each side; the half-open test decides.
                const int j0 = int(std::clamp(std::floor((lo - grid.originMm.y) / grid.pixelMm) - 1,
                                              0.0, double(grid.height)));
                const int j1 = int(std::clamp(std::ceil((hi - grid.originMm.y) / grid.pixelMm) + 1,
                                              -1.0, double(grid.height - 1)));
                for (int j = j0; j <= j1; ++j) {
                    const double y = grid.pixelCentre(0, j).y;
                    const bool up = a.y <= y && y < b.y, down = b.y <= y && y < a.y;
                    if (!up && !down) continue;
                    const auto counted = [&](int i) {
                        return windingCrossing(grid.pixelCentre(i, j), a, b) != 0;
                    };
                    // Counted for i < k: the rounded side test is monotone in
                    // x, so start at the interpolated crossing and settle.
                    const double x = a.x + (y - a.y) * (b.x - a.x) / (b.y - a.y);
                    int first =
                        int(std::clamp(std::floor((x - grid.originMm.x) / grid.pixelMm - 0.5) + 1,
                                       0.0, double(grid.width)));
                    while (first > 0 && !counted(first - 1)) --first;
                    while (first < grid.width && counted(first)) ++first;
                    if (first > 0)
                        perRow[(s - begin) * std::size_t(grid.height) + std::size_t(j)].push_back(
                            {{first, up ? 1 : -1}});
                }
            }
    RowCrossings rows;
    rows.rowFirst.push_back(0);
    for (auto& row : perRow) {
        std::sort(row.begin(), row.end(),
                  [](const cl_int2& a, const cl_int2& b) { return a.s[0] < b.s[0]; });
        for (std::size_t c = row.size(); c-- > 1;) row[c - 1].s[1] += row[c].s[1];
        rows.crossings.insert(rows.crossings.end(), row.begin(), row.end());
        rows.rowFirst.push_back(cl_uint(rows.crossings.size()));
    }
    return rows;
}

/// How the field kernels run, decided once per computeSliceFields from its
/// FieldKernelOptions: pixels per work-item, the tile side (0: by the
/// segments' density, per batch), the tiles' list capacity, from how many
/// candidates a tile lists leaves, whether lanes run along rows, and where
/// the counts go (null: nowhere).
struct KernelLayout {
    std::uint32_t lanes = 8, tile = 0;
    cl_uint capacity = 0, leafListsFrom = 0, lanesAlong = 0;
    FieldKernelStats* stats = nullptr;
};

/// Slices [begin, end) of a batch, every one with contours.
struct SliceRange {
    std::size_t begin = 0, end = 0;
};

template <class Real, class Real4>
void runBatch(ocl::Runtime& runtime, const std::vector<Slice>& slices, SliceRange range,
              const SliceGrid& grid, const KernelLayout& layout, SliceFields& out) {
    const std::size_t begin = range.begin, end = range.end;
    const std::uint32_t lanes = layout.lanes;
    std::uint32_t tile = layout.tile;
    const cl_uint capacity = layout.capacity;
    FieldKernelStats* stats = layout.stats;
    // The rows' crossings (only the field kernel reads them), for a batch of
    // many segments on a thread of their own while this one builds the
    // tables: found after the tables, they ran beside the candidate listing,
    // which already has every core, and the host work before the first
    // launch left a core idle. Fewer segments make tables too quick for the
    // thread's start to pay (kCrossingsThreadFrom).
    std::future<RowCrossings> crossingRows;
    if (segmentCount(slices, begin, end) >= kCrossingsThreadFrom)
        crossingRows =
            std::async(std::launch::async, [&] { return rowCrossings(slices, begin, end, grid); });
    FlatSegments<Real4> flat = flatten<Real4>(slices, begin, end, grid);
    const std::size_t batch = end - begin;

    // The tables the kernels read, kept here while they run.
    using ocl::DeviceBuffer;
    const SliceGeometry<Real, Real4> geometry(runtime, flat);
    if (tile == 0) {
        const double meanLengthPx =
            flat.lengthMm / double(std::max<std::size_t>(1, flat.segments.size())) / grid.pixelMm;
        tile = meanLengthPx < kWideTilesBelowPx ? kWideTile : kTile;
    }
    const std::size_t tilesX = (std::size_t(grid.width) + tile - 1) / tile;
    const std::size_t tilesY = (std::size_t(grid.height) + tile - 1) / tile;
    // The tile lists, in kept host memory on CPU devices too: a new device
    // allocation is fresh pages, which the kernel would fault in one by one
    // (a 512² grid's lists take 1.3 MB).
    const std::size_t listRoom = tilesX * tilesY * batch * capacity;
    const bool cpu = runtime.device().kind == ocl::DeviceKind::Cpu;
    const ocl::ScratchArray<cl_uint> listMemory(cpu ? listRoom : 0);
    const auto candidates =
        cpu ? DeviceBuffer<cl_uint>::over(runtime, listMemory.data(), listRoom, CL_MEM_READ_WRITE)
            : DeviceBuffer<cl_uint>(runtime, listRoom);
    DeviceBuffer<cl_uint> candidateCount(runtime, tilesX * tilesY * batch);
    // The kernel writes straight into the result where the device shares host
    // memory: a download of 8 bytes a pixel cost a tenth of a 512² field.
    const std::size_t offset = begin * grid.pixelCount();
    const auto distance = DeviceBuffer<cl_float>::over(runtime, out.distanceMm.data() + offset,
                                                       batch * grid.pixelCount());
    const auto nearest = DeviceBuffer<cl_uint>::over(runtime, out.nearestId.data() + offset,
                                                     batch * grid.pixelCount());

    const std::string options = ocl::realOptions<Real>() + " -DTILE=" + std::to_string(tile) +
                                " -DLANES=" + std::to_string(lanes) +
                                " -DLEAF=" + std::to_string(kLeaf) +
                                " -DBLOCK_LIST=" + std::to_string(kListCapacity) +
                                " -DLEAF_LISTED=" + std::to_string(kLeafListed) + "u" +
                                " -DCOLUMNS=" + std::to_string(kColumns) + "u";
    const cl::Program& program = runtime.program({"real.cl", "closest_segment_2d.cl"}, options);
    TileParams<Real> params{};
    params.pixelMm = Real(grid.pixelMm);
    // Far above the rounding of coordinates of this size (kernel header).
    params.slackMm =
        Real(64 * double(std::numeric_limits<Real>::epsilon()) * (flat.magnitudeMm + grid.pixelMm));
    // Squared distances round by a few ulps of the squared magnitude; this
    // margin is far above (kernel header, tile_candidates).
    params.marginMm2 = Real(256 * double(std::numeric_limits<Real>::epsilon()) *
                            (flat.magnitudeMm + grid.pixelMm) * (flat.magnitudeMm + grid.pixelMm));
    params.width = cl_uint(grid.width), params.height = cl_uint(grid.height);
    params.capacity = capacity, params.leafListsFrom = layout.leafListsFrom;
    params.lanesAlong = layout.lanesAlong;
    RowCrossings rows;  // kept until the kernels finish
    try {
        // Kernels read the host memory of the tables above on CPU devices:
        // whatever is thrown after a launch, they finish before it is freed.
        const ocl::QueueDrain drain(runtime.queue());
        cl::Kernel cull(program, "tile_candidates");
        cl_uint a = geometry.setArgs(cull, 0);
        cull.setArg(a++, params);
        cull.setArg(a++, candidates.get());
        cull.setArg(a++, candidateCount.get());
        // Work-groups of a fixed 4 × 4 tiles (padding tiles return at once):
        // PoCL builds one work-group function per local size, and windows of
        // every size would each get a new one.
        runtime.queue().enqueueNDRangeKernel(
            cull, cl::NullRange,
            cl::NDRange(ocl::roundUp(tilesX, 4), ocl::roundUp(tilesY, 4), batch),
            cl::NDRange(4, 4, 1));
        runtime.queue().flush();
        rows = crossingRows.valid() ? crossingRows.get() : rowCrossings(slices, begin, end, grid);
        const auto rowFirst = DeviceBuffer<cl_uint>::reading(runtime, rows.rowFirst);
        const auto crossings = DeviceBuffer<cl_int2>::reading(runtime, rows.crossings);

        cl::Kernel field(program, "signed_distance_2d");
        a = geometry.setArgs(field, 0);
        field.setArg(a++, params);
        field.setArg(a++, candidates.get());
        field.setArg(a++, candidateCount.get());
        field.setArg(a++, rowFirst.get());
        field.setArg(a++, crossings.get());
        field.setArg(a++, distance.get());
        field.setArg(a++, nearest.get());
        // A work-item computes `lanes` pixels of a tile's rows, row after row.
        runtime.queue().enqueueNDRangeKernel(field, cl::NullRange,
                                             cl::NDRange(tilesX * tile / lanes, tilesY, batch),
                                             cl::NDRange(tile / lanes, 1, 1));
        distance.mapForHost(runtime, false);
        nearest.mapForHost(runtime, true);
        if (stats) {
            stats->tilePixels = tile;
            for (const cl_uint counted : candidateCount.download(runtime)) {
                const cl_uint listed = counted & ~kColumns;
                ++stats->tiles;
                if (counted & kColumns) ++stats->columnTiles;
                if (listed & kLeafListed)
                    ++stats->leafListingTiles;
                else if (listed > capacity)
                    ++stats->overflowingTiles;
                else
                    stats->listed += listed;
            }
        }
    } catch (const cl::Error& e) {
        throw ocl::toClError(e, "closest_segment_2d.cl");
    }
}

SliceFields emptyFields(const std::vector<Slice>& slices, const SliceGrid& grid) {
    SliceFields fields;
    fields.grid = grid;
    for (const Slice& s : slices) fields.zMm.push_back(s.zMm);
    fields.distanceMm.assign(slices.size() * grid.pixelCount(),
                             std::numeric_limits<float>::infinity());
    fields.nearestId.assign(slices.size() * grid.pixelCount(), kNoPrimitive);
    return fields;
}

}  // namespace

SliceFields computeSliceFields(ocl::Runtime& runtime, const std::vector<Slice>& slices,
                               const SliceGrid& grid, const std::function<void(double)>& progress,
                               const FieldKernelOptions& options) {
    checkLimits(slices);
    KernelLayout layout;
    layout.lanes = std::uint32_t(options.lanes);
    if (layout.lanes == 0) layout.lanes = runtime.device().kind == ocl::DeviceKind::Cpu ? 8 : 1;
    if (layout.lanes != 1 && layout.lanes != 4 && layout.lanes != 8)
        throw std::invalid_argument("field kernel lanes must be 1, 4 or 8");
    layout.tile = std::uint32_t(options.tilePixels);
    if (layout.tile != 0 && layout.tile != kTile && layout.tile != kWideTile)
        throw std::invalid_argument("field kernel tiles must be 0 (by density), 16 or 32 pixels");
    layout.capacity = cl_uint(
        options.tileListCapacity < 0 ? kListCapacity : std::min(options.tileListCapacity, 1 << 16));
    layout.leafListsFrom =
        cl_uint(options.leafListsFrom < 0 ? kLeafListsFrom : options.leafListsFrom);
    layout.lanesAlong = cl_uint(options.lanesAlong);
    layout.stats = options.stats;
    SliceFields fields = emptyFields(slices, grid);
    if (options.stats) *options.stats = {};
    const std::size_t perBatch =
        std::max<std::size_t>(1, kPixelsPerBatch / std::max<std::size_t>(1, grid.pixelCount()));
    const bool fp64 = runtime.device().doublePrecision && !options.singlePrecision;
    for (std::size_t begin = 0; begin < slices.size();) {
        // Slices without contours keep +inf / kNoPrimitive; batches skip them.
        if (slices[begin].contours.empty()) {
            ++begin;
            continue;
        }
        std::size_t end = begin;
        while (end < slices.size() && end - begin < perBatch && !slices[end].contours.empty())
            ++end;
        ocl::withRealTypes(fp64, [&](auto real, auto real4) {
            runBatch<decltype(real), decltype(real4)>(runtime, slices, {begin, end}, grid, layout,
                                                      fields);
        });
        begin = end;
        if (progress) progress(double(begin) / double(slices.size()));
    }
    return fields;
}

SliceFields computeSliceFieldsReference(const std::vector<Slice>& slices, const SliceGrid& grid) {
    checkLimits(slices);
    SliceFields fields = emptyFields(slices, grid);
    for (std::size_t s = 0; s < slices.size(); ++s) {
        const auto& contours = slices[s].contours;
        if (contours.empty()) continue;
        for (int j = 0; j < grid.height; ++j)
            for (int i = 0; i < grid.width; ++i) {
                const Point2 p = grid.pixelCentre(i, j);
                double best2 = std::numeric_limits<double>::infinity();
                std::uint32_t bestId = kNoPrimitive;
                int winding = 0;
                for (std::uint32_t c = 0; c < contours.size(); ++c) {
                    const Polygon& poly = contours[c];
                    const std::uint32_t n = std::uint32_t(poly.size());
                    for (std::uint32_t k = 0; k < n; ++k) {
                        const Point2 a = poly[k], b = poly[(k + 1) % n];
                        const double t = nearestSegmentParameter(p, a, b);
                        const Point2 q = p - (a + t * (b - a));
                        const double d2 = dot(q, q);
                        if (d2 < best2) {
                            best2 = d2;
                            bestId = t <= 0   ? PrimitiveId{c, k, true}.encode()
                                     : t >= 1 ? PrimitiveId{c, (k + 1) % n, true}.encode()
                                              : PrimitiveId{c, k, false}.encode();
                        }
                    }
                    winding += windingNumber(p, poly);
                }
                const std::size_t at = fields.index(s, i, j);
                const double d = std::sqrt(best2);
                fields.distanceMm[at] = float(winding != 0 ? -d : d);
                fields.nearestId[at] = bestId;
            }
    }
    return fields;
}

}  // namespace dfrecon
