#pragma once
// Surface distance maps of a scene of meshes (surface distance maps paper
// §3–4, §6.3): for each mesh, at every atlas texel and every vertex, the
// signed distance to the nearest other mesh (negative inside it), which mesh
// that is and its closest point; and per pair, separation, collision and
// penetration. What `dfrecon sdm` computes, without the files.
#include <string>
#include <vector>

#include "cl/Runtime.hpp"
#include "field/SurfaceScene.hpp"
#include "geometry/TriangleSoup.hpp"
#include "sdm/ProximityQueries.hpp"
#include "sdm/SurfaceDistanceMaps.hpp"

namespace dfrecon {

struct SceneMapsOptions {
    AtlasOptions atlas;     // texels, or the sampling bound
    DistanceQuery query;    // a clearance band (maxDistanceMm)
    bool proximity = true;  // also the pairwise proximity queries
    /// What messages call each mesh (its file); the scene's names if empty.
    std::vector<std::string> labels;
};

struct SceneMaps {
    std::vector<ObjectSamples> samples;   // per mesh: atlas, texel and vertex samples
    std::vector<ObjectDistanceMap> maps;  // per mesh: closest primitive per sample
    std::vector<PairProximity> pairs;     // when options.proximity
    double mapSeconds = 0, proximitySeconds = 0;
};

/// The maps of every mesh of `scene` (at least two, each with triangles)
/// against the others, by the OpenCL closest-primitive kernel. Throws
/// std::invalid_argument naming the mesh (its label) that cannot be
/// sampled, ClError on device failure. O(samples · log T).
SceneMaps sceneDistanceMaps(ocl::Runtime& runtime, const SurfaceScene& scene,
                            const SceneMapsOptions& options = {});

}  // namespace dfrecon
