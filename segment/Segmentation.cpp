#include "segment/Segmentation.hpp"

#include <algorithm>
#include <chrono>
#include <stdexcept>
#include <string>

#include "segment/FarthestPointSampling.hpp"

namespace dfrecon {

Segmentation segmentMesh(const MeshGraph& graph, const SegmentOptions& options) {
    const auto start = std::chrono::steady_clock::now();
    if (options.regions < 1) throw std::invalid_argument("need at least one region");
    if (options.regions > graph.vertexCount())
        throw std::invalid_argument("more regions (" + std::to_string(options.regions) +
                                    ") than vertices (" + std::to_string(graph.vertexCount()) +
                                    ")");
    Segmentation result;
    const double weight = options.curvatureWeightMm > 0
                              ? options.curvatureWeightMm
                              : defaultCurvatureWeight(graph, options.regions);
    result.curvatureWeightMm = options.speed == SpeedKind::Uniform ? 0.0 : weight;
    const SpeedKind samplingKind =
        options.speed == SpeedKind::EdgeAttractive ? SpeedKind::EdgeRepulsive : options.speed;
    const UpdateStencils stencils(graph, options.unfold);
    {
        const FastMarching sampling(stencils, curvatureSpeed(graph, samplingKind, weight));
        FarthestPoints samples = farthestPointSampling(sampling, options.regions);
        // Sampling only reaches the first sample's component: every other
        // component gets a seed of its own (the disk constraint and the
        // iterations refine it from there).
        for (int v = 0; v < graph.vertexCount(); ++v) {
            if (samples.field.time[std::size_t(v)] != kUnreached ||
                graph.trianglesAround(v).size() == 0)
                continue;
            sampling.march(samples.field, {{v, 0.0, int(samples.vertices.size())}});
            samples.vertices.push_back(v);
            ++result.componentSeeds;
        }
        result.initialSeeds = samples.vertices;
    }
    if (options.progress) options.progress(0.1);
    const FastMarching regionMetric(stencils, curvatureSpeed(graph, options.speed, weight));
    LloydOptions lloydOptions = options.lloyd;
    if (options.progress)
        lloydOptions.onIteration = [&](int iteration, int most) {
            options.progress(0.1 + 0.9 * iteration / std::max(most, 1));
        };
    LloydResult lloyd = geodesicLloyd(graph, regionMetric, result.initialSeeds, lloydOptions);
    const std::vector<RegionTopology> topology =
        regionTopology(graph, lloyd.regions.faceRegion, int(lloyd.seeds.size()));
    for (std::size_t i = 0; i < lloyd.seeds.size(); ++i) {
        RegionReport r;
        r.seed = lloyd.seeds[i];
        r.areaMm2 = lloyd.regions.area[i];
        r.perimeterMm = lloyd.regions.perimeter[i];
        r.compactness = lloyd.regions.compactness(int(i));
        r.faces = topology[i].faces;
        r.disk = topology[i].isDisk();
        result.regions.push_back(r);
    }
    result.seeds = std::move(lloyd.seeds);
    result.vertexRegion = std::move(lloyd.field.label);
    result.faceRegion = std::move(lloyd.regions.faceRegion);
    result.energy = std::move(lloyd.energy);
    result.iterations = lloyd.iterations;
    result.converged = lloyd.converged;
    result.seedsAdded = lloyd.seedsAdded;
    result.seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return result;
}

}  // namespace dfrecon
