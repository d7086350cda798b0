#pragma once
// The slabs of a stack of planes, built side by side: one SlabReconstructor
// per thread on the cores left free (geometry/CoreBudget), each with its own
// OpenCL queue, handed back in slab order so the surface is the same, point
// for point, whatever the number of threads.
#include <cstddef>
#include <deque>
#include <functional>
#include <vector>

#include "cl/Runtime.hpp"
#include "field/SliceFields.hpp"
#include "recon/Reconstruction.hpp"
#include "recon/SlabReconstructor.hpp"
#include "recon/SurfaceBuilder.hpp"

namespace dfrecon {

/// What every slab of a stack reads: the planes' layers (slab s lies between
/// layers s and s + 1), their fields (slice s for layer s) on `grid`, and
/// the contour points every builder starts with.
struct SlabStack {
    const ReconstructionOptions& options;
    const SliceGrid& grid;
    const std::deque<Layer>& layers;
    const SliceFields& fields;
    const std::vector<Vec3>& contourPoints;
    StackTraits traits;  // the planes' net areas, voxel contours
};

/// One slab built apart: its part of the surface, whether its piece's own
/// pairs were searched, the counts it added and the seconds it took.
struct BuiltSlab {
    SurfacePart part;
    bool searched = false;
    ReconstructionStats stats;
    double seconds = 0;
};

/// The slabs of `stack`, slab s as piece s + 1, built on the calling thread
/// and on the cores left free. A slab reads only its two layers' contour
/// points and the planes' fields, so each thread builds on a builder of its
/// own that starts with the contour points, and the calling thread hands
/// each slab to `append` in slab order as soon as it and those before it are
/// done (so few finished parts wait at once). Helper threads get their own
/// OpenCL queue on `runtime`'s context. Progress (0.5 to 1, as slabs finish)
/// is reported from the calling thread only. An exception in any thread is
/// rethrown here once all have stopped. Returns how many helper threads ran.
std::size_t buildSlabs(ocl::Runtime& runtime, const SlabStack& stack,
                       const std::function<void(double)>& progress,
                       const std::function<void(std::size_t, BuiltSlab&&)>& append);

}  // namespace dfrecon
