#pragma once
// Neighbours kept apart. Each ROI of a structure set is interpolated on its
// own between the planes, so two structures whose contours never overlap on
// a plane (touching areas of an atlas, organs drawn side by side) can still
// overlap between the planes: each bulges, caps or closes a hole without the
// other (the Brodmann set: 8 cc in all, BA17/BA18 alone 0.46 cc). Summing
// structures, subtracting a neighbour or building a label map then counts
// the lens twice.
//
// keepNeighboursApart finds, for every pair of ROIs, the vertices of each
// inside the other (the other's exact signed distance: the closest-primitive
// kernel of field/, or its C++ twin), and moves each such vertex halfway to
// the other surface's closest point and a clearance beyond, so both meet
// near the lens's middle, each losing about half of it; where the other
// side has no vertex in the lens there (its closest triangle has none
// inside), all the way; a second round moves out what is still inside.
// Only points between the planes move: the contours stay vertices of their
// surfaces, exactly.
// A pair whose contours overlap on a plane both have (a PTV around its GTV,
// the body around every organ) overlaps by design and is left as drawn.
// A move that would make a surface cross itself is halved, up to three
// times, then undone, vertex by vertex, until the surface is a valid closed
// solid again; where a vertex stays stuck inside its neighbour, the
// neighbour's closest triangle gives way (its corners off the planes move
// inward past it). A triangle passing through a neighbour (in the first
// round only one with no corner inside it) is split at its centroid, and
// the new vertex moves like the others (the surface gains vertices between
// the planes, never on them).
// What is left overlaps inside triangles, not at vertices
// (docs/reconstruction.md, "Neighbours kept apart", has the figures).
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "cl/Runtime.hpp"
#include "geometry/PlaneFrame.hpp"
#include "geometry/SurfaceMeasures.hpp"
#include "geometry/TriangleSoup.hpp"

namespace dfrecon {

/// One ROI's surface as the separation sees it.
struct NeighbourSurface {
    std::string name;
    /// Patient mm, a valid closed solid oriented outward; moved in place.
    TriangleSoup* surface = nullptr;
    PlaneFrame frame;              // its planes' frame (plane z = dot(point, frame.n))
    std::vector<double> planeZMm;  // its contour planes, increasing
};

struct NeighbourSeparationOptions {
    /// A point counts as inside a neighbour only deeper than this, mm:
    /// touching contours share points, and rounding to float puts them a
    /// hair to either side.
    double insideToleranceMm = 1e-3;
    /// A vertex this close to one of its ROI's planes lies on it, mm.
    double planeToleranceMm = 1e-3;
    /// How far beyond the lens's middle a moved vertex goes, mm: the two
    /// surfaces, triangulated differently, then leave a gap of about twice
    /// this instead of crossing each other's facets.
    double clearanceMm = 0.01;
    /// False: only find the pairs that meet (and how deep), move nothing.
    bool move = true;
};

/// Two ROIs whose surfaces met: a vertex of one lay inside the other.
struct NeighbourPair {
    std::size_t a = 0, b = 0;  // indices into the ROIs, a < b
    /// Their contours overlap on a plane both have: left as drawn.
    bool overlapOnPlanes = false;
    /// Vertices of a inside b (and of b inside a) before, the deepest (mm).
    std::size_t insideA = 0, insideB = 0;
    double deepestMm = 0;
    /// Of those, moved in the first round; the rest stay where they were,
    /// because moving them would have made the surface cross itself.
    std::size_t movedA = 0, movedB = 0;
    /// Vertices of a inside b (of b inside a) after the last round.
    std::size_t leftInsideA = 0, leftInsideB = 0;
};

struct NeighbourSeparation {
    std::vector<NeighbourPair> pairs;  // every pair that met, by (a, b)
    /// Per ROI: the volume and area of its surface as left, where vertices
    /// moved; none where the surface is unchanged. (Its topology cannot
    /// change, and it stays free of self-intersections.)
    std::vector<std::optional<SurfaceMeasures>> measures;
    double seconds = 0;
};

/// Keeps the ROIs' surfaces apart where their contours are (see above):
/// every vertex between the planes that lies deeper than
/// options.insideToleranceMm inside another ROI of a pair with no overlap on
/// shared planes moves out (unless that would break its surface), measured
/// against the surfaces as they are at the start of each of the two rounds (triangles whose
/// centroid is inside are split there first; in the first round only those with no corner
/// inside). Every surface stays a
/// valid closed solid with the same vertices on its planes. A pair "overlaps on planes" when a
/// vertex or contour-edge midpoint of one on a plane both have lies inside
/// the other (an overlap narrower than the contours' point spacing can go
/// unseen). `runtime`: the distances on its device; null: the C++ twin.
/// Points deeper inside a neighbour than the planes' largest gap are not
/// looked for (a lens between planes is thinner). Work, per round: one
/// hierarchy per ROI and one distance search per vertex of an ROI inside a
/// neighbour's box, plus a local collision search around each changed
/// surface's moved vertices.
NeighbourSeparation keepNeighboursApart(ocl::Runtime* runtime, std::vector<NeighbourSurface>& rois,
                                        const NeighbourSeparationOptions& options = {});

}  // namespace dfrecon
