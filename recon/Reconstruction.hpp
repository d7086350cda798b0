#pragma once
// Contours in, a closed surface out (reconstruction paper §2.1, §4): exact 2D
// fields of every slice, medial axes between neighbours, strips traced along
// each axis that joins one contour to one contour, recursion with the axis as
// an intermediate contour wherever contours branch, merge or do not match,
// prism closings at the recursion limit, and caps at the ends.
#include <array>
#include <cstddef>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "cl/Runtime.hpp"
#include "contours/ContourSet.hpp"
#include "field/SliceFields.hpp"
#include "geometry/MeshCheck.hpp"
#include "geometry/TriangleSoup.hpp"
#include "recon/Caps.hpp"

namespace dfrecon {

/// How the surface runs between two planes.
enum class Interpolation {
    Linear,  // straight from contour to contour (ruled strips)
    Smooth,  // C1 across the planes: strips bent onto a cubic in z of the slices'
             // fields, each slab's volume matched to its sections' (recon/LoftSmoothing),
             // still through every contour point
};

inline constexpr std::array<std::pair<const char*, Interpolation>, 2> kInterpolationNames{{
    {"linear", Interpolation::Linear},
    {"smooth", Interpolation::Smooth},
}};

/// Default grid side of the reconstruction's fields. Mesh vertices are the
/// contour points whatever the pixel size; pixels only guide which points
/// correspond and where contours branch, so half the resolution of the
/// field export suffices (docs/reconstruction.md).
inline constexpr int kReconstructionGridPixels = 256;

struct ReconstructionOptions {
    double pixelMm = 0;         // field pixel size; <= 0: kReconstructionGridPixels a side
    double contourErrorMm = 0;  // simplify contours within this bound first (0: keep all points)
    int maxDepth = 4;           // recursion levels for branching regions
    CapMode cap = CapMode::Flat;
    double capOffsetMm = -1;  // how far beyond an end contour its cap reaches; < 0: half the ROI's
                              // slab thickness if it has one, else half the spacing
    /// Smooth by default: straight strips lose volume between planes (1–6 %
    /// on atlas anatomy against its true surface, docs/reconstruction.md).
    Interpolation interpolation = Interpolation::Smooth;
    /// Smooth mode: bands are halved in z until no straight edge strays
    /// farther than this from the smooth surface.
    double smoothToleranceMm = 0.05;
    /// Smooth mode: the rings refinement made are thinned where the merged
    /// triangles stay within smoothToleranceMm (recon/RingCoarsening); off
    /// keeps every vertex refinement made (for comparison).
    bool coarsenRings = true;
    /// A section that ends below and one that begins above, the same shape
    /// slid farther than its width (a thin sheet or tube lying nearly flat),
    /// are joined by a straight band instead of two caps
    /// (recon/SlidingSections); not for contours on a pixel lattice, whose
    /// voxels say where the structure is.
    bool joinSlidSections = true;
    /// Smooth mode: a slab whose lower plane repeats the plane below and
    /// whose upper plane repeats the plane above is closed as a step at its
    /// middle (recon/StepSlabs); off interpolates across it like any slab.
    bool stepBetweenRepeats = true;
    FieldKernelOptions kernel;
};

struct ReconstructionStats {
    double pixelMm = 0;
    std::size_t slices = 0, contourPoints = 0;  // after contour simplification
    std::size_t runs = 1;    // pieces the ROI falls into where planes are left empty (PlaneGaps)
    std::size_t slabs = 0;   // pairs of neighbouring slices
    std::size_t strips = 0;  // contour pairs joined by tracing an axis
    std::size_t slidStrips = 0;  // section pairs that slid apart, joined (recon/SlidingSections)
    std::size_t rejectedStrips = 0;    // strips that folded through themselves, solved again
    std::size_t recursions = 0;        // intermediate contour layers made
    int deepestLevel = 0;              // deepest recursion level used
    std::size_t limitClosings = 0;     // regions closed by prisms at the recursion limit
    std::size_t caps = 0;              // end contours capped (or left open with CapMode::None)
    std::size_t fallbackSlabs = 0;     // slabs whose pieces met, closed as one prism piece
    std::size_t stepSlabs = 0;         // slabs between repeated contours, closed as a step
    std::size_t touchesOpened = 0;     // points where contours of one plane touched, opened
    std::size_t repairedPieces = 0;    // slabs or caps closed again after the whole-surface check
    std::size_t smoothedVertices = 0;  // smooth mode: vertices bent onto the smooth surface
    std::size_t smoothRevertedPieces = 0;  // smooth mode: pieces kept linear for validity
    std::size_t smoothUnbentVertices =
        0;  // smooth mode: bent vertices put back straight (validity)
    std::size_t smoothHalfUnbentVertices =
        0;  // smooth mode: bent vertices moved halfway back to straight (validity)
    std::size_t smoothCoarsenedVertices = 0;  // smooth mode: ring vertices merged away
    bool smoothFellBack = false;              // smooth mode: the whole surface kept linear
    // Seconds per stage. The slabs run on the cores left free, and their
    // fields, axes and triangulation count per thread: the stages can add up
    // to more than the wall time.
    double simplifySeconds = 0, fieldsSeconds = 0, medialSeconds = 0, triangulationSeconds = 0,
           checkSeconds = 0;
    /// Smooth mode: bending the strips onto the interpolant and bringing
    /// slabs to their volumes, with the checks and repairs that keeps them
    /// valid (not in checkSeconds).
    double smoothSeconds = 0;
};

struct Reconstruction {
    TriangleSoup surface;  // outward-oriented triangles
    ReconstructionStats stats;
    MeshCheckReport check;  // of `surface`
    /// The z ranges (mm, in the contours' plane frame) of the slabs and caps
    /// that are still not valid (empty when check.validSolid()).
    std::vector<std::pair<double, double>> brokenPieces;
};

/// Reconstructs one ROI. With CapMode::Flat or Dome the result is a valid
/// closed solid by construction (docs/reconstruction.md, "Valid by
/// construction"), checked with its points rounded to float as mesh files
/// store them — `check` says so, and `brokenPieces` where it is not. Contour
/// points are mesh vertices, to float precision (unless simplified away, or
/// moved 1 µm where contours of a plane touched). `progress` receives the
/// fraction done (from the calling thread). The slabs between planes are
/// built on the calling thread and the cores the process has free
/// (geometry/CoreBudget), each helper with its own OpenCL queue on
/// `runtime`'s context, and joined in order: the surface is the same,
/// point for point, on any number of cores. Throws
/// std::invalid_argument for an ROI without contours, ClError on device
/// failure. Work: the fields, O(pixels) per slab for the axes, O(points)
/// for the strips.
/// An ROI that ends and starts again where planes are left empty
/// (Roi::restartsAt) is reconstructed run by run, each run a closed solid
/// capped at its ends like any ROI, and the runs' surfaces joined: an empty
/// plane lies between any two, and each cap reaches at most half its gap
/// beyond its end plane, so no two runs meet and the whole is valid when
/// every run is (its check is the runs' checks summed).
Reconstruction reconstructSurface(ocl::Runtime& runtime, const Roi& roi,
                                  const ReconstructionOptions& options = {},
                                  const std::function<void(double)>& progress = {});

}  // namespace dfrecon
