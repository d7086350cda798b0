#pragma once
// Fast marching on triangle meshes (Kimmel & Sethian 1998; the paper's
// §2.1): arrival times of fronts started at source vertices, for the
// eikonal equation |∇T| = 1/F with a per-vertex speed F > 0, and for each
// vertex the label of the source whose front got there first (geodesic
// Voronoi cells, §2.2).
//
// Units: with F = 1 the arrival time is the geodesic distance in mm. In
// general T is the weighted distance ∫ P ds with metric weight P = 1/F (the
// paper's eq. 1–2): a slower region is "longer". The triangle update uses
// the slowness of the vertex being updated for the whole triangle.
//
// The local update is kernels/eikonal_update.cl (shared with the OpenCL
// solver) on the stencils of UpdateStencils, so obtuse angles are unfolded
// there. Labels follow the upwind corner, and fronts of different labels
// never combine across a triangle (each crosses it along its own edges;
// kernels/eikonal_update.cl says why), so T is the distance to the nearest
// source without the collapse that mixing colliding fronts causes.
//
// Complexity: O(S log N) for S stencils (≈ 3 per triangle, 4 per unfolded
// obtuse corner) and N vertices: each stencil is evaluated twice, each
// improvement is a push on a binary heap with lazy deletion (stale entries
// are skipped when popped), and the heap holds about the front's length.
#include <limits>
#include <vector>

#include "segment/UpdateStencils.hpp"

namespace dfrecon {

inline constexpr double kUnreached = std::numeric_limits<double>::infinity();

struct GeodesicSource {
    int vertex = 0;
    double time = 0;  // initial arrival time at the vertex
    int label = 0;    // what the vertices this front reaches first are labelled
};

/// Arrival time and closest-source label per vertex. Vertices no front
/// reached (other components, or past a stop) have kUnreached and label -1.
struct GeodesicField {
    std::vector<double> time;
    std::vector<int> label;

    explicit GeodesicField(std::size_t vertices = 0)
        : time(vertices, kUnreached), label(vertices, -1) {}
};

/// How one vertex got its time: from the triangle (target; a, b) with the
/// characteristic crossing ab at weightB (a == b for an update along an edge;
/// a == -1 for a source).
struct UpwindRecord {
    int a = -1, b = -1;
    double weightB = 0;
};

struct MarchOptions {
    /// Stop once the front passes this arrival time (vertices beyond keep
    /// whatever time they had, possibly a tentative one).
    double maxTime = kUnreached;
    /// If set (one flag per vertex), stop once every flagged vertex is final.
    const std::vector<char>* stopWhenFinal = nullptr;
    /// If set, receives the vertices in the order they became final.
    std::vector<int>* finalOrder = nullptr;
    /// If set (resized to the vertex count), receives each improved vertex's
    /// upwind record: geodesics can be traced back through it.
    std::vector<UpwindRecord>* upwind = nullptr;
};

class FastMarching {
  public:
    /// `speed`: F per vertex (> 0, finite), or empty for F = 1. Throws
    /// std::invalid_argument for a wrong size or a speed that is not positive.
    explicit FastMarching(const UpdateStencils& stencils, const std::vector<double>& speed = {});

    const UpdateStencils& stencils() const { return stencils_; }
    int vertexCount() const { return stencils_.vertexCount(); }
    /// 1/F per vertex.
    const std::vector<double>& slowness() const { return slowness_; }

    /// A fresh field from `sources` (vertex indices must be valid; a vertex
    /// may appear once).
    GeodesicField solve(const std::vector<GeodesicSource>& sources,
                        const MarchOptions& options = {}) const;

    /// Marches `sources` over an existing field: a vertex changes only where
    /// the new fronts arrive sooner than its current time, so the work is
    /// proportional to the region that changes (farthest-point sampling adds
    /// one source at a time this way). With a fresh field it is solve().
    void march(GeodesicField& field, const std::vector<GeodesicSource>& sources,
               const MarchOptions& options = {}) const;

  private:
    const UpdateStencils& stencils_;
    std::vector<double> slowness_;
};

/// 1/F per vertex for `speed` (empty: all 1). Throws std::invalid_argument
/// for a wrong size or a speed that is not a positive finite number.
std::vector<double> slownessFromSpeed(const std::vector<double>& speed, int vertexCount);

/// The vertex with the largest finite time (ties: the lowest index), or -1.
int farthestVertex(const GeodesicField& field);

}  // namespace dfrecon
