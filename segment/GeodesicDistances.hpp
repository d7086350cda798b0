#pragma once
// Geodesic distances with whichever solver is faster for the mesh and the
// device: fast marching (C++, one core) or the fast iterative method
// (OpenCL). Both give the same discrete solution (EikonalFim.hpp).
//
// Measured on this project's reference machine (2 shared cores, PoCL's CPU
// device, double precision; `dfrecon-bench segment` and best-of-3 runs):
// on geodesic spheres, whose regular triangles let a settled vertex stay
// settled (≈1.2 vertex updates per vertex), PoCL's FIM took about the same
// time as fast marching up to 1.8× more up to 100K vertices, and 0.6×–1.3×
// fast marching's time from 225K to 1M (varying from run to run); on
// irregular meshes (scans, or the same spheres with jittered vertices: 5–13
// updates per vertex) it is 3–9× slower at every size tried, up to 1M. The
// gain on regular meshes is within the run-to-run noise of a shared machine
// and the loss elsewhere is large, so on a CPU device the choice is always
// fast marching. On a GPU the FIM's parallelism should pay
// for large meshes; kFimMinVerticesOnGpu is where we switch, an estimate
// that has not been measured on a GPU.
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
