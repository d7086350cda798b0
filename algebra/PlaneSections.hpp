#pragma once
// The sections, on given planes, of the solid where a field is negative:
// closed polygons whose every vertex lies on the field's zero set (to
// 1e-4 mm: vertices are rounded to a 0.1 µm grid, so that sections of one
// straight edge on two planes agree bit for bit; where the boundary passes within 5 % of a step of
// a lattice sample, the vertex stays that far off the sample, so that the parts of a section that
// pinch there stay apart by more than reconstruction needs), found without sampling the whole plane
// finely.
//
// Each plane is sampled on a coarse lattice first (cells coarseFactor steps
// wide); because the field changes by at most the distance moved along a
// plane (it is 1-Lipschitz there, as algebra/SolidField makes it), a cell
// whose corners are all farther from zero than half its diagonal holds no
// boundary and keeps its corners' sign. The other cells are halved, level
// by level (a quadtree), each level clearing what it can, down to the fine
// step: the samples evaluated lie within a few cells of the boundary at
// each level, a few per fine step of boundary (sampling whole uncleared
// coarse cells took several times as many). Marching squares
// (geometry/IsoLines) joins the crossings, whose cells' corners are all
// evaluated, and each crossing is then moved along its lattice edge onto the zero set
// by regula falsi (Illinois) on the field itself. Between vertices a
// polygon is a chord of the true section: off it by at most step²/(8 r)
// where the section bends with radius r, and by up to a step at a corner
// of the section (a crease of a shrink, or where a difference cuts).
#include <cstddef>
#include <functional>
#include <vector>

#include "contours/ContourSet.hpp"
#include "geometry/Vec3.hpp"

namespace dfrecon {

struct PlaneSectionOptions {
    double stepMm = 0.25;   // the fine lattice's step (mm)
    int coarseFactor = 32;  // coarse cells are this many steps wide (a power of two halves evenly)
    int refineIterations = 12;
    /// Where the lattice starts off the region's corner, as a fraction of
    /// a step: off round coordinates (a box's faces miss its samples); a
    /// caller may try another one (the vertices differ, each still on the
    /// boundary).
    double latticeShift = 0.381966;
    /// Vertices move until the field is within this of zero, or the
    /// bracket is this narrow (mm): far below the 0.1 µm grid they are
    /// rounded to, so that equal boundaries give equal vertices.
    double toleranceMm = 1e-10;
    /// Contours (islands and holes) of less area are dropped (mm²; the
    /// default 1e-4 drops only marching squares' slivers).
    double minContourAreaMm2 = 1e-4;
    /// Values within this of zero count as outside (mm): a plane through a
    /// flat face of the solid (a grown lid) sees the field's rounding
    /// there, not a section. At least the field's own rounding.
    double zeroToleranceMm = 1e-9;
    /// Samples held at once (bounds memory: planes are done in groups).
    std::size_t maxSamplesPerBatch = std::size_t(1) << 22;
    /// Called with the fraction of planes done after each group (for a
    /// progress bar); none: not called.
    std::function<void(double)> progress;
};

/// The lattice shifts tried in turn where the sections of one lattice do
/// not reconstruct into a valid solid (reconstruction still folds on some
/// pairs of planes whose sections nearly coincide): the default first.
/// `dfrecon margin`/`combine` and Python's margin()/combine() alike.
inline constexpr double kLatticeShifts[] = {0.381966, 0.618034, 0.145898};

/// The field at points given in plane coordinates (x, y on the plane, z
/// along its normal): negative inside, 1-Lipschitz along the planes.
using PlaneField = std::function<std::vector<double>(const std::vector<Vec3>& planePoints)>;

/// A rectangle of a plane (plane mm).
struct PlaneRect {
    double xMin = 0, xMax = 0, yMin = 0, yMax = 0;
};

struct PlaneSectionStats {
    std::size_t coarseSamples = 0, fineSamples = 0, refinementSamples = 0;
    std::size_t planes = 0, planesWithSection = 0;
};

/// The section of {field < 0} on each plane z ∈ planeZMm within `region`
/// (the field must be positive on the region's border, or the section is
/// cut there). Returns one Slice per plane with a section, sorted by z,
/// outer contours counter-clockwise and holes clockwise, no two crossing;
/// vertices within 1e-4 mm of the previous one and polygons under
/// options.minContourAreaMm2 are dropped. Throws std::invalid_argument for a
/// step that is not positive or a region of more than 2^31 samples per
/// plane. O(coarse samples + boundary length / step × coarseFactor +
/// vertices × refineIterations) field evaluations, in a few batches.
std::vector<Slice> planeSections(const PlaneField& field, const std::vector<double>& planeZMm,
                                 const PlaneRect& region, const PlaneSectionOptions& options = {},
                                 PlaneSectionStats* stats = nullptr);

}  // namespace dfrecon
