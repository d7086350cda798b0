#pragma once
// The expensive half of the error-bounded collapse's priorities — how far
// the triangles each collapse creates stray from the original surface — for
// every halfedge of the unchanged mesh in one OpenCL batch
// (kernels/collapse_bound.cl), and the plain C++ reference the kernel is
// tested against (surfaceDeviation, the code the Decimater module runs for
// later collapses).
#include <vector>

#include "cl/Runtime.hpp"
#include "geometry/TriMesh.hpp"
#include "simplify/DeviationBound.hpp"

namespace dfrecon {

/// One value per halfedge index of `mesh`: surfaceDeviation of collapsing
/// it (its from-vertex onto its to-vertex), or -1 if that exceeds
/// maxErrorMm or a created triangle is a sliver. `original` is the surface
/// the bound is measured against (for simplifySurface: `mesh` itself). Topology is not
/// checked (the Decimater does). On a device without fp64 the kernel runs in
/// float and each bound is raised by 1e-6 of the surface's extent so it
/// stays an upper bound. `wanted`, if given (one flag per halfedge), names
/// the halfedges to evaluate; the others get -1 unevaluated (collapses
/// refused anyway, e.g. by the normal-flip test). O(H · pieces · log T)
/// work, spread over the device.
std::vector<float> initialPriorities(ocl::Runtime& runtime, const TriMesh& mesh,
                                     const DeviationSurface& original, double maxErrorMm,
                                     const std::vector<bool>* wanted = nullptr);

/// The same on the CPU with surfaceDeviation, in double precision.
std::vector<float> initialPrioritiesReference(const TriMesh& mesh, const DeviationSurface& original,
                                              double maxErrorMm,
                                              const std::vector<bool>* wanted = nullptr);

}  // namespace dfrecon
