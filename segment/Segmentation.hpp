#pragma once
// segmentMesh: the paper's segmentation pipeline (§3), the entry point of
// `dfrecon segment`. Seeds by farthest-point sampling with the sampling
// speed (§3.1: "edge repulsive", so seeds do not crowd on creases), regions
// and geodesic Lloyd iterations with the region speed ("edge attractive",
// so borders settle on creases), topological-disk constraint throughout.
#include <functional>
#include <vector>

#include "segment/GeodesicLloyd.hpp"
#include "segment/MeshGraph.hpp"
#include "segment/SpeedFunctions.hpp"
#include "segment/UpdateStencils.hpp"

namespace dfrecon {

struct SegmentOptions {
    int regions = 10;  // seeds to start from (the disk constraint may add some)
    /// The speed of the regions and Lloyd iterations. EdgeAttractive (the
    /// paper's choice) samples seeds with EdgeRepulsive; Uniform and
    /// EdgeRepulsive use the same speed for both.
    SpeedKind speed = SpeedKind::EdgeAttractive;
    double curvatureWeightMm = 0;  // e and m of eq. 3; ≤ 0: defaultCurvatureWeight(regions)
    LloydOptions lloyd;
    UnfoldOptions unfold;
    /// Called with the fraction done (0..1) after sampling and each iteration.
    std::function<void(double)> progress;
};

struct RegionReport {
    int seed = 0;
    double areaMm2 = 0;
    double perimeterMm = 0;
    double compactness = 0;  // 4π·area/perimeter²
    int faces = 0;
    bool disk = false;
};

struct Segmentation {
    std::vector<int> initialSeeds;  // from farthest-point sampling (+ componentSeeds)
    std::vector<int> seeds;         // after the Lloyd iterations
    std::vector<int> vertexRegion;  // per vertex (-1: a vertex in no triangle)
    std::vector<int> faceRegion;    // per face
    std::vector<RegionReport> regions;
    std::vector<double> energy;  // Lloyd energy, [0] before the first iteration
    int iterations = 0;
    bool converged = false;
    int seedsAdded = 0;            // by the disk constraint
    int componentSeeds = 0;        // one per component the sampling did not reach
    double curvatureWeightMm = 0;  // the weight used (0 for uniform speed)
    double seconds = 0;
};

/// Throws std::invalid_argument for regions < 1 or more regions than
/// vertices. O(k · N log N) for the sampling, then per Lloyd iteration one
/// march over the mesh and up to centerSteps marches per region.
Segmentation segmentMesh(const MeshGraph& graph, const SegmentOptions& options);

}  // namespace dfrecon
