#pragma once
// Geodesic Lloyd iterations towards a centroidal Voronoi tessellation of a
// surface (the paper's §3.3), with the topological-disk constraint of §3.1.
//
// Each iteration moves every seed to the intrinsic centre of mass of its
// region — the minimiser of E_i(w) = ∫_{V_i} d(w, x)² dx for the weighted
// geodesic distance d — and recomputes the regions from the moved seeds;
// it stops when no vertex changes region (or no seed moves).
//
// The centre is found by gradient descent as the paper does:
// ∇E_i(w) = −2 ∫ d(w, x) n_w(x) dx with n_w(x) the unit tangent at w of the
// geodesic from w to x. A march from w over the region records how each
// vertex was reached (UpwindRecord); following those records back to w is
// tracing the geodesics back. n_w is carried forward along the same records
// (each vertex takes the direction of the point where its characteristic
// crosses the upwind edge, interpolated linearly; w's neighbours the
// direction of the edge from w, projected into w's tangent plane), which
// traces all of the region's geodesics back at once: O(region) per step
// instead of O(region × path length). The integral is the first-order
// (lumped vertex area) sum. The step −∇E / (2·area) is the mean of the log
// map d·n_w; its end point is mapped back onto the surface as the region
// vertex whose log-map coordinates d·n_w are nearest to it. Steps repeat
// while they lower E_i (at most centerSteps), so a seed never moves to a
// worse centre.
//
// Topological disks: after every region computation, a region whose faces
// are not a disk (a front that closed around a handle, or a cell split in
// two) gets a new seed at its vertex farthest from its seed (where the front
// collapsed onto itself), and the regions are recomputed; at most
// maxAddedSeeds seeds are added in all.
#include <functional>
#include <vector>

#include "segment/FastMarching.hpp"
#include "segment/GeodesicVoronoi.hpp"
#include "segment/MeshGraph.hpp"

namespace dfrecon {

struct LloydOptions {
    int maxIterations = 10;
    int centerSteps = 8;  // gradient-descent steps per region and iteration
    bool diskConstraint = true;
    int maxAddedSeeds = -1;  // seeds the disk constraint may add; -1: the initial count
    /// Called after each iteration with (iteration, maxIterations).
    std::function<void(int, int)> onIteration;
};

struct LloydResult {
    std::vector<int> seeds;  // final seed vertices; region i belongs to seeds[i]
    GeodesicField field;     // distance to the nearest seed, label = its index
    VoronoiRegions regions;
    /// Σ_x A_x d(x)² (mm⁴ for uniform speed, A_x the lumped vertex area):
    /// energy[0] for the first regions, energy[i] after iteration i.
    std::vector<double> energy;
    int iterations = 0;
    bool converged = false;  // stopped because the regions stopped changing
    int seedsAdded = 0;      // by the disk constraint
    int nonDiskRegions = 0;  // regions still not disks at the end
};

/// Lloyd iterations from `seeds` (distinct vertex indices) with the metric
/// of `marching`. Each iteration costs one multi-source march plus, per
/// region, up to centerSteps marches over the region. Throws
/// std::invalid_argument for no seeds or a bad seed index.
LloydResult geodesicLloyd(const MeshGraph& graph, const FastMarching& marching,
                          std::vector<int> seeds, const LloydOptions& options = {});

/// The intrinsic centre of mass of the region made of `regionVertices`,
/// by the gradient descent above from `seed`, and its E_i (first-order sum
/// with `vertexAreas`).
struct RegionCentre {
    int vertex = -1;
    double energy = 0;
};
RegionCentre regionCentre(const MeshGraph& graph, const FastMarching& marching,
                          const std::vector<double>& vertexAreas,
                          const std::vector<int>& regionVertices, int seed, int steps);

}  // namespace dfrecon
