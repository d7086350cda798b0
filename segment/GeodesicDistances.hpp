#pragma once
// Geodesic distances with whichever solver is faster for the mesh and the
// device: fast marching (C++, one core) or the fast iterative method
// (OpenCL). Both give the same discrete solution (EikonalFim.hpp).
//
// Measured on this project's reference machine (2 shared cores, PoCL's CPU
// device, `dfrecon-bench segment`): fast marching beats PoCL's FIM at every
// size tried, about 100× at 10K vertices and 8× at 1M (FIM's iterations
// each cost kernel launches and a read-back, and PoCL has two cores to
// spread them over). So on a CPU device the choice is always fast marching.
// On a GPU the FIM's parallelism pays for large meshes; kFimMinVerticesOnGpu
// is where we switch, an estimate that has not been measured on a GPU yet.
#include <string>
#include <vector>

#include "cl/Runtime.hpp"
#include "segment/FastMarching.hpp"

namespace dfrecon {

enum class GeodesicSolver { Automatic, FastMarching, FastIterative };
const char* toString(GeodesicSolver solver);

/// The smallest mesh (vertices) for which Automatic picks the FIM on a GPU.
inline constexpr int kFimMinVerticesOnGpu = 200000;

/// What Automatic resolves to for a mesh of `vertexCount` vertices with
/// `runtime` (nullptr: no OpenCL device, so fast marching).
GeodesicSolver chooseGeodesicSolver(int vertexCount, const ocl::Runtime* runtime);

/// Arrival times and labels from `sources` with speed F per vertex (empty:
/// 1). FastIterative needs a runtime (std::invalid_argument otherwise).
/// `used`, if set, receives the solver that ran.
GeodesicField geodesicDistances(const UpdateStencils& stencils,
                                const std::vector<GeodesicSource>& sources,
                                const std::vector<double>& speed, ocl::Runtime* runtime,
                                GeodesicSolver solver = GeodesicSolver::Automatic,
                                GeodesicSolver* used = nullptr);

}  // namespace dfrecon
