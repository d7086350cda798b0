#include "field/SliceFields.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "cl/DeviceBuffer.hpp"
#include "cl/Precision.hpp"

namespace dfrecon {

namespace {

// Culling levels: coarse tiles scan all segments of a slice, fine tiles
// (the kernel's TILE, one work-group each) scan their coarse tile's list.
constexpr std::uint32_t kCoarseTile = 32;
constexpr std::uint32_t kTile = 8;
constexpr cl_uint kCoarseCapacity = 4096, kFineCapacity = 1024;
constexpr std::size_t kCandidateBytes = 128u << 20;  // candidate lists per launch

std::size_t tilesOf(const SliceGrid& grid, std::uint32_t tile) {
    return ((std::size_t(grid.width) + tile - 1) / tile) *
           ((std::size_t(grid.height) + tile - 1) / tile);
}

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
// endpoints relative to the grid origin and the ids the kernel reports.
template <class Real4>
struct FlatSegments {
    std::vector<Real4> segments;
    std::vector<cl_uint2> ids;  // (segment id, end vertex id)
    std::vector<cl_uint> sliceFirst, sliceCount;
};

template <class Real4>
FlatSegments<Real4> flatten(const std::vector<Slice>& slices, std::size_t begin, std::size_t end,
                            Point2 origin) {
    FlatSegments<Real4> flat;
    for (std::size_t s = begin; s < end; ++s) {
        flat.sliceFirst.push_back(cl_uint(flat.segments.size()));
        const auto& contours = slices[s].contours;
        for (std::uint32_t c = 0; c < contours.size(); ++c) {
            const std::uint32_t n = std::uint32_t(contours[c].size());
            for (std::uint32_t k = 0; k < n; ++k) {
                const Point2 a = contours[c][k] - origin, b = contours[c][(k + 1) % n] - origin;
                Real4 r;
                r.s[0] = a.x, r.s[1] = a.y, r.s[2] = b.x, r.s[3] = b.y;
                flat.segments.push_back(r);
                flat.ids.push_back({{PrimitiveId{c, k, false}.encode(),
                                     PrimitiveId{c, (k + 1) % n, true}.encode()}});
            }
        }
        flat.sliceCount.push_back(cl_uint(flat.segments.size()) - flat.sliceFirst.back());
    }
    return flat;
}

// Where each contour crosses each pixel row, as (first pixel to the right,
// direction), in double precision with the half-open rule of windingNumber().
struct RowCrossings {
    std::vector<cl_uint> rowFirst;  // size rows + 1
    std::vector<cl_int2> crossings;
};

RowCrossings rowCrossings(const std::vector<Slice>& slices, std::size_t begin, std::size_t end,
                          const SliceGrid& grid) {
    std::vector<std::vector<cl_int2>> perRow((end - begin) * std::size_t(grid.height));
    for (std::size_t s = begin; s < end; ++s)
        for (const Polygon& contour : slices[s].contours)
            for (std::size_t k = 0; k < contour.size(); ++k) {
                const Point2 a = contour[k], b = contour[(k + 1) % contour.size()];
                if (a.y == b.y) continue;
                const double lo = std::min(a.y, b.y), hi = std::max(a.y, b.y);
                const int j0 =
                    std::max(0, int(std::floor((lo - grid.originMm.y) / grid.pixelMm - 0.5)));
                const int j1 = std::min(
                    grid.height - 1, int(std::ceil((hi - grid.originMm.y) / grid.pixelMm - 0.5)));
                for (int j = j0; j <= j1; ++j) {
                    const double y = grid.pixelCentre(0, j).y;
                    const bool up = a.y <= y && y < b.y, down = b.y <= y && y < a.y;
                    if (!up && !down) continue;
                    const double x = a.x + (y - a.y) * (b.x - a.x) / (b.y - a.y);
                    const double k0 = std::floor((x - grid.originMm.x) / grid.pixelMm - 0.5) + 1;
                    const int first = int(std::clamp(k0, 0.0, double(grid.width)));
                    perRow[(s - begin) * std::size_t(grid.height) + std::size_t(j)].push_back(
                        {{first, up ? 1 : -1}});
                }
            }
    RowCrossings rows;
    rows.rowFirst.push_back(0);
    for (const auto& row : perRow) {
        rows.crossings.insert(rows.crossings.end(), row.begin(), row.end());
        rows.rowFirst.push_back(cl_uint(rows.crossings.size()));
    }
    return rows;
}

template <class Real, class Real4>
void runBatch(ocl::Runtime& runtime, const std::vector<Slice>& slices, std::size_t begin,
              std::size_t end, const SliceGrid& grid, std::uint32_t lanes, SliceFields& out) {
    const FlatSegments<Real4> flat = flatten<Real4>(slices, begin, end, grid.originMm);
    const RowCrossings rows = rowCrossings(slices, begin, end, grid);
    const std::size_t batch = end - begin;
    const cl_uint maxCount = *std::max_element(flat.sliceCount.begin(), flat.sliceCount.end());
    const cl_uint coarseCapacity = std::max<cl_uint>(1, std::min(maxCount, kCoarseCapacity));
    const cl_uint fineCapacity = std::max<cl_uint>(1, std::min(maxCount, kFineCapacity));

    ocl::DeviceBuffer<Real4> segments(runtime, flat.segments);
    ocl::DeviceBuffer<cl_uint2> ids(runtime, flat.ids);
    ocl::DeviceBuffer<cl_uint> sliceFirst(runtime, flat.sliceFirst),
        sliceCount(runtime, flat.sliceCount);
    ocl::DeviceBuffer<cl_uint> rowFirst(runtime, rows.rowFirst);
    ocl::DeviceBuffer<cl_int2> crossings(runtime, rows.crossings);
    const std::size_t coarseTiles = tilesOf(grid, kCoarseTile) * batch;
    const std::size_t fineTiles = tilesOf(grid, kTile) * batch;
    ocl::DeviceBuffer<cl_uint> coarse(runtime, coarseTiles * coarseCapacity);
    ocl::DeviceBuffer<cl_uint> coarseCount(runtime, coarseTiles);
    ocl::DeviceBuffer<cl_uint> fine(runtime, fineTiles * fineCapacity);
    ocl::DeviceBuffer<cl_uint> fineCount(runtime, fineTiles);
    ocl::DeviceBuffer<cl_float> distance(runtime, batch * grid.pixelCount(), CL_MEM_WRITE_ONLY);
    ocl::DeviceBuffer<cl_uint> nearest(runtime, batch * grid.pixelCount(), CL_MEM_WRITE_ONLY);

    const std::string options = ocl::realOptions<Real>() + " -DTILE=" + std::to_string(kTile) +
                                " -DLANES=" + std::to_string(lanes);
    const cl::Program& program =
        runtime.program({"real.cl", "closest_point.cl", "closest_segment_2d.cl"}, options);
    try {
        auto cull = [&](std::uint32_t tile, std::uint32_t parentTile,
                        const ocl::DeviceBuffer<cl_uint>& parent,
                        const ocl::DeviceBuffer<cl_uint>& parentCount, cl_uint parentCapacity,
                        cl_uint capacity, const ocl::DeviceBuffer<cl_uint>& list,
                        const ocl::DeviceBuffer<cl_uint>& listCount) {
            cl::Kernel kernel(program, "tile_candidates");
            int a = 0;
            kernel.setArg(a++, segments.get());
            kernel.setArg(a++, sliceFirst.get());
            kernel.setArg(a++, sliceCount.get());
            kernel.setArg(a++, cl_uint(grid.width));
            kernel.setArg(a++, cl_uint(grid.height));
            kernel.setArg(a++, Real(grid.pixelMm));
            kernel.setArg(a++, cl_uint(tile));
            kernel.setArg(a++, cl_uint(parentTile));
            kernel.setArg(a++, parent.get());
            kernel.setArg(a++, parentCount.get());
            kernel.setArg(a++, parentCapacity);
            kernel.setArg(a++, capacity);
            kernel.setArg(a++, list.get());
            kernel.setArg(a++, listCount.get());
            // Work-groups of a fixed 4 × 4 tiles (padding tiles return at
            // once): PoCL builds one work-group function per local size, and
            // windows of every size would each get a new one.
            runtime.queue().enqueueNDRangeKernel(
                kernel, cl::NullRange,
                cl::NDRange(ocl::roundUp((std::size_t(grid.width) + tile - 1) / tile, 4),
                            ocl::roundUp((std::size_t(grid.height) + tile - 1) / tile, 4), batch),
                cl::NDRange(4, 4, 1));
        };
        // The coarse level has no parent; it gets its own buffers as dummies.
        cull(kCoarseTile, 0, coarse, coarseCount, 0, coarseCapacity, coarse, coarseCount);
        cull(kTile, kCoarseTile, coarse, coarseCount, coarseCapacity, fineCapacity, fine,
             fineCount);

        cl::Kernel field(program, "signed_distance_2d");
        int a = 0;
        field.setArg(a++, segments.get());
        field.setArg(a++, ids.get());
        field.setArg(a++, sliceFirst.get());
        field.setArg(a++, sliceCount.get());
        field.setArg(a++, rowFirst.get());
        field.setArg(a++, crossings.get());
        field.setArg(a++, cl_uint(grid.width));
        field.setArg(a++, cl_uint(grid.height));
        field.setArg(a++, Real(grid.pixelMm));
        field.setArg(a++, fineCapacity);
        field.setArg(a++, fine.get());
        field.setArg(a++, fineCount.get());
        field.setArg(a++, distance.get());
        field.setArg(a++, nearest.get());
        // Work-groups of one fine tile, so a group walks one candidate list;
        // each work-item computes `lanes` pixels of a row.
        const std::size_t tilesX = (std::size_t(grid.width) + kTile - 1) / kTile;
        const std::size_t tilesY = (std::size_t(grid.height) + kTile - 1) / kTile;
        runtime.queue().enqueueNDRangeKernel(
            field, cl::NullRange, cl::NDRange(tilesX * kTile / lanes, tilesY * kTile, batch),
            cl::NDRange(kTile / lanes, kTile, 1));
    } catch (const cl::Error& e) {
        throw ocl::toClError(e, "closest_segment_2d.cl");
    }
    const std::vector<cl_float> d = distance.download(runtime);
    const std::vector<cl_uint> id = nearest.download(runtime);
    const std::size_t offset = begin * grid.pixelCount();
    std::copy(d.begin(), d.end(), out.distanceMm.begin() + std::ptrdiff_t(offset));
    std::copy(id.begin(), id.end(), out.nearestId.begin() + std::ptrdiff_t(offset));
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
    std::uint32_t lanes = std::uint32_t(options.lanes);
    if (lanes == 0) lanes = runtime.device().kind == ocl::DeviceKind::Cpu ? 8 : 1;
    if (lanes != 1 && lanes != 4 && lanes != 8)
        throw std::invalid_argument("field kernel lanes must be 1, 4 or 8");
    SliceFields fields = emptyFields(slices, grid);
    const std::size_t listBytesPerSlice =
        (tilesOf(grid, kTile) * kFineCapacity + tilesOf(grid, kCoarseTile) * kCoarseCapacity) *
        sizeof(cl_uint);
    const std::size_t perBatch = std::max<std::size_t>(1, kCandidateBytes / listBytesPerSlice);
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
            runBatch<decltype(real), decltype(real4)>(runtime, slices, begin, end, grid, lanes,
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
