#pragma once
// The fast iterative method (FIM; Jeong & Whitaker 2008, on triangle meshes
// Fu, Kirby & Whitaker 2011): a parallel eikonal solver in OpenCL
// (kernels/eikonal_fim.cl) with the same local update, stencils (obtuse
// angles unfolded), speeds and label rule as FastMarching, and a plain C++
// reference that runs the same iteration sequentially.
//
// Each iteration updates every vertex of an active list from its stencils
// (Jacobi style: all read the times of the previous iteration); a vertex
// whose time moved by at most the tolerance leaves the list and activates
// the vertices it may update if they would improve by more than the
// tolerance. Times only ever decrease, so the iteration ends; it converges
// to the solution fast marching computes (the same discrete equations, the
// upwind condition making updates from later vertices irrelevant), up to
// the tolerance accumulated along a path. On the device the result does not
// depend on the order work-items run in, so it equals the reference's up to
// floating-point rounding (identical on a double-precision device with no
// fused multiply-adds; float on devices without double precision).
//
// Work: O(S · a) stencil evaluations for S stencils, a = how often a vertex
// becomes active again (small on smooth meshes); iterations ≈ the number of
// edges along the longest geodesic, each costing four kernel launches and
// one read of the next list's size.
#include <memory>
#include <vector>

#include "cl/Runtime.hpp"
#include "segment/FastMarching.hpp"

namespace dfrecon {

struct FimOptions {
    /// A vertex is settled when its time moves by at most this fraction of a
    /// typical edge's crossing time (mean edge length × mean slowness).
    double tolerance = 1e-9;
    /// Give up after this many iterations (0: 4 × vertices + 100).
    int maxIterations = 0;
};

struct FimStats {
    int iterations = 0;
    std::size_t vertexUpdates = 0;  // active-list entries processed, all iterations
    bool converged = false;         // the active list emptied
    bool doublePrecision = true;    // the device computed in double
};

/// FIM on an OpenCL device. The stencils, speeds and work buffers are
/// uploaded once; solve() can be called repeatedly. Not thread-safe.
class EikonalFim {
  public:
    /// `speed`: F per vertex (> 0), or empty for 1. Throws
    /// std::invalid_argument for bad speeds, ClError on device failure.
    EikonalFim(ocl::Runtime& runtime, const UpdateStencils& stencils,
               const std::vector<double>& speed = {}, const FimOptions& options = {});
    ~EikonalFim();
    EikonalFim(const EikonalFim&) = delete;
    EikonalFim& operator=(const EikonalFim&) = delete;

    GeodesicField solve(const std::vector<GeodesicSource>& sources, FimStats* stats = nullptr);

    class Device;  // the buffers and kernels, in float or double

  private:
    std::unique_ptr<Device> device_;
};

/// The same iteration in plain C++ (double precision), for testing the
/// kernel and for machines without OpenCL.
GeodesicField eikonalFimReference(const UpdateStencils& stencils,
                                  const std::vector<GeodesicSource>& sources,
                                  const std::vector<double>& speed = {},
                                  const FimOptions& options = {}, FimStats* stats = nullptr);

}  // namespace dfrecon
