#pragma once
// Error-bounded simplification of a closed surface (paper §6): OpenMesh's
// decimation (CheckedDecimater) with ModErrorBound (two-sided bound, no self-intersections) and
// ModNormalFlipping, initial priorities of all edges in one OpenCL batch.
#include <cstddef>

#include "cl/Runtime.hpp"
#include "geometry/TriangleSoup.hpp"

namespace dfrecon {

/// The smallest bound simplification accepts: 1 nm. Coordinates are within
/// a kilometre of the origin (io/files/InputLimits.hpp), where doubles resolve
/// 1.2e-10 mm, and the coverage of a collapse splits pieces of the original
/// surface down to a tenth of the bound: below about 10^4 units of that
/// resolution the halves of a piece would round onto their parent and the
/// splitting would never end.
inline constexpr double kMinMaxErrorMm = 1e-6;

struct SimplifyOptions {
    double maxErrorMm = 0.5;  ///< two-sided bound; at least kMinMaxErrorMm
    /// The largest angle a face's normal may turn in one collapse (stops
    /// flips and the slivers that come just before them).
    double maxNormalTurnDeg = 60;
    /// Evaluate the initial priorities on the device (else on the CPU).
    bool initialBatchOnDevice = true;
};

struct SimplifyStats {
    std::size_t verticesBefore = 0, trianglesBefore = 0, vertices = 0, triangles = 0;
    std::size_t collapses = 0;
    /// The certified bounds of the result, recomputed on the final mesh:
    /// every point of it to the input, every input vertex to it.
    double surfaceToInputBoundMm = 0, inputToSurfaceBoundMm = 0;
    /// Runs again with vertices locked near a self-intersection that a
    /// stale priority let through (rare; 0 on every test and benchmark mesh).
    std::size_t retries = 0;
    std::size_t cpuEvaluations = 0, batchEvaluations = 0;
    /// Pieces of the original surface kept on the result's faces (its
    /// triangles, split where no single face covers them).
    std::size_t pieces = 0;
    /// Queued collapses found stale when taken, and re-queued.
    std::size_t staleCollapses = 0;
    double initialSeconds = 0, decimateSeconds = 0;
};

struct Simplified {
    TriangleSoup surface;
    SimplifyStats stats;
};

/// Simplifies `input` (a closed, manifold surface) as far as the bound
/// allows. The result has no self-intersection the input did not have near
/// it, keeps genus and orientation, and is within options.maxErrorMm of the
/// input in both directions at every point of the result and every vertex
/// of the input. `runtime` may be null (CPU only). Throws
/// std::invalid_argument for a non-manifold input or a bad option (a bound
/// below kMinMaxErrorMm).
Simplified simplifySurface(ocl::Runtime* runtime, const TriangleSoup& input,
                           const SimplifyOptions& options);

}  // namespace dfrecon
