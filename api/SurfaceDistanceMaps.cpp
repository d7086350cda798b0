#include "dfrecon/SurfaceDistanceMaps.hpp"

#include <stdexcept>

#include "api/Stopwatch.hpp"
#include "field/ClosestPrimitives.hpp"

namespace dfrecon {

SceneMaps sceneDistanceMaps(ocl::Runtime& runtime, const SurfaceScene& scene,
                            const SceneMapsOptions& options) {
    if (scene.objectCount() < 2)
        throw std::invalid_argument(
            "surface distance maps need at least two meshes (distances are to the others)");
    auto label = [&](std::size_t o) {
        return o < options.labels.size() ? options.labels[o] : scene.name(o);
    };
    SceneMaps out;
    for (std::size_t o = 0; o < scene.objectCount(); ++o) {
        try {
            out.samples.push_back(sampleObject(scene, o, options.atlas));
        } catch (const std::invalid_argument& e) {
            throw std::invalid_argument(label(o) + ": " + e.what());
        }
    }
    ClosestPrimitiveKernel kernel(runtime, scene);
    const ClosestPrimitivesFn closest = [&](const std::vector<SurfaceSample>& s,
                                            const DistanceQuery& q) { return kernel.run(s, q); };
    Stopwatch watch;
    out.maps = surfaceDistanceMaps(scene, out.samples, closest, options.query);
    out.mapSeconds = watch.lap();
    if (options.proximity) {
        out.pairs = proximityQueries(scene, out.samples, closest);
        out.proximitySeconds = watch.lap();
    }
    return out;
}

}  // namespace dfrecon
