#pragma once
// Exact 2D signed distance fields with correspondence ids: for every pixel of
// every slice, the Euclidean distance (mm, negative inside) to the nearest
// point of the slice's original double-precision contours, and which
// primitive (field/PrimitiveId.hpp) that point belongs to.
#include <cstdint>
#include <functional>
#include <vector>

#include "cl/Runtime.hpp"
#include "contours/ContourSet.hpp"
#include "field/PrimitiveId.hpp"
#include "field/SliceGrid.hpp"

namespace dfrecon {

/// The fields of a stack of slices on one grid, stored slice after slice,
/// each row-major (pixel (i, j) of slice s at s·W·H + j·W + i).
struct SliceFields {
    SliceGrid grid;
    std::vector<double> zMm;               // one per slice
    std::vector<float> distanceMm;         // signed: < 0 inside, > 0 outside
    std::vector<std::uint32_t> nearestId;  // PrimitiveId::encode(), or kNoPrimitive

    std::size_t sliceCount() const { return zMm.size(); }
    std::size_t index(std::size_t slice, int i, int j) const {
        return slice * grid.pixelCount() + std::size_t(j) * std::size_t(grid.width) +
               std::size_t(i);
    }
};

/// What the field kernel's tile lists held, over every tile of the slices
/// it computed (slices without contours have none).
struct FieldKernelStats {
    std::size_t tiles = 0;
    /// Tiles with more candidates than the capacity: their pixels walked the
    /// segment tree instead of scanning a list.
    std::size_t overflowingTiles = 0;
    /// Tiles that listed leaves of the segment tree, not segments.
    std::size_t leafListingTiles = 0;
    /// Tiles whose work-items' lanes went down its columns, not along its rows.
    std::size_t columnTiles = 0;
    /// Candidate segments in all the segment lists.
    std::size_t listed = 0;
    /// The side of the tiles, in pixels, of the last batch of slices
    /// (FieldKernelOptions::tilePixels).
    std::uint32_t tilePixels = 0;
    /// Candidate segments per tile listing segments, on average.
    double meanListed() const {
        const std::size_t listing = tiles - overflowingTiles - leafListingTiles;
        return listing > 0 ? double(listed) / double(listing) : 0;
    }
};

/// Which way a work-item's pixels lie in its tile.
enum class LanesAlong {
    /// Down the columns where the contour nearest the tile's centre runs
    /// closer to the rows than to the columns, in tiles dense enough to list
    /// leaves or walk the tree: the pixels then lie along the contour's
    /// normal and share their nearest segments. Along the rows elsewhere.
    Contour = 0,
    Rows = 1,
    Columns = 2,
};

/// How the field kernel runs; the defaults are right for every device.
struct FieldKernelOptions {
    /// Pixels each work-item computes in vector lanes: 0 = by device (8 on
    /// CPUs, where it is explicit SIMD; 1 elsewhere), or 1, 4, 8. Results are
    /// the same; tests run every width.
    int lanes = 0;
    /// Float arithmetic, what devices without fp64 get (about 1e-6 relative
    /// error instead of 1e-12).
    bool singlePrecision = false;
    /// Candidates a tile lists at most before its pixels walk the segment
    /// tree instead: -1 = the default. Results are the same (0: always walk;
    /// tests run both ways).
    int tileListCapacity = -1;
    /// Tiles whose candidates lie in leaves of the segment tree (runs of 8
    /// segments) holding more segments than this list those leaves instead:
    /// each row then scans the segments of the leaves it can reach, where
    /// dense contours would have it scan every candidate of its block. -1 = the default; 0 =
    /// every tile with a contour; results are the same (tests run all ways).
    int leafListsFrom = -1;
    /// Which way each work-item's pixels lie; results are the same (tests run
    /// every way).
    LanesAlong lanesAlong = LanesAlong::Contour;
    /// The side of a tile, in pixels: 0 = by density (32 where a batch's
    /// segments are shorter than half a pixel on average, else 16), or 16
    /// or 32. Results are the same; tests run both.
    int tilePixels = 0;
    /// When set, receives what the tile lists held (one more download of a
    /// count per tile; for benchmarks and tests).
    FieldKernelStats* stats = nullptr;
};

/// Fields of all `slices` on `grid` with the OpenCL kernels of
/// kernels/closest_segment_2d.cl: a tree of boxes and capsules over runs of
/// consecutive segments per slice; each tile (16×16 pixels, 32×32 for dense
/// contours) lists the segments that can
/// be nearest to one of its pixels (when few) or the leaves of the tree that
/// hold them (when many: each row of pixels then scans the leaves it can
/// reach from the row below's nearest), else its pixels walk the tree row by
/// row from the row below's nearest. In dense tiles where the contour runs
/// along the rows, a work-item's pixels go down a column instead, along the
/// contour's normal, where they share their nearest segments (LanesAlong).
/// All only skip what is provably farther
/// than the best, so the result is the brute-force scan's (ties to the lower
/// segment index). Many slices per launch; fp64 on devices that
/// have it. Sign from the winding number of all contours, from each row's
/// crossings found with windingCrossing() (so exactly windingNumber()'s, on
/// the contour too): holes, islands and touching contours come out right.
/// Work per slice: O(segments · rows they span) on the host; per tile
/// O(depth + its list); per pixel its tile's list (at most
/// tileListCapacity), its block's leaves and the segments of those within
/// reach, or O(depth + the segments near it). `progress`, if
/// set, receives the fraction of slices done after each batch. Throws
/// PrimitiveLimitExceeded beyond the PrimitiveId limits, ClError on device
/// failure.
SliceFields computeSliceFields(ocl::Runtime& runtime, const std::vector<Slice>& slices,
                               const SliceGrid& grid,
                               const std::function<void(double)>& progress = {},
                               const FieldKernelOptions& options = {});

/// The plain C++ brute-force reference: every segment at every pixel in
/// double precision, sign from windingNumber(). O(pixels·segments).
SliceFields computeSliceFieldsReference(const std::vector<Slice>& slices, const SliceGrid& grid);

}  // namespace dfrecon
