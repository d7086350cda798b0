#pragma once
// Surface distance maps of a scene (paper §4, Algorithm 1): for every
// object, at every texel of its atlas and at every vertex, the signed
// distance to the nearest other object, which object that is, its closest
// primitive and point. Any of the closest-primitive implementations can
// compute them (the OpenCL kernel, its C++ reference, brute force).
#include <functional>
#include <vector>

#include "field/ClosestPrimitives.hpp"
#include "sdm/Atlas.hpp"

namespace dfrecon {

using ClosestPrimitivesFn = std::function<std::vector<ClosestPrimitive>(
    const std::vector<SurfaceSample>&, const DistanceQuery&)>;

/// Where an object is sampled: its atlas texels first, then its vertices.
struct ObjectSamples {
    Atlas atlas;
    std::vector<std::uint32_t> texel;    // atlas texel of samples[k], k < texel.size()
    std::vector<SurfaceSample> samples;  // texel samples, then one per used vertex
    std::vector<std::uint32_t> vertex;   // soup point of samples[texel.size() + k]

    std::size_t texelCount() const { return texel.size(); }
    /// The largest distance from any point of the surface to a sample of
    /// its own triangle (the atlas's Lemma 2 bound).
    double samplingBoundMm() const { return atlas.samplingBoundMm(); }
};

/// Builds the atlas of object `object` and its samples. O(T log T + texels).
ObjectSamples sampleObject(const SurfaceScene& scene, std::size_t object,
                           const AtlasOptions& options);

struct ObjectDistanceMap {
    std::vector<ClosestPrimitive> texels;    // per texel sample
    std::vector<ClosestPrimitive> vertices;  // per soup point (object -1 if unused)
};

/// The maps of every object against all others (query.target must be -1)
/// from `samples` (one per object), in one closest-primitive call per
/// object. O(samples · log T) typically.
std::vector<ObjectDistanceMap> surfaceDistanceMaps(const SurfaceScene& scene,
                                                   const std::vector<ObjectSamples>& samples,
                                                   const ClosestPrimitivesFn& closest,
                                                   const DistanceQuery& query = {});

/// The map as a row-major image: distance in mm at used texels, NaN at
/// unused ones (and +inf beyond the band).
std::vector<float> distanceImage(const ObjectSamples& samples, const ObjectDistanceMap& map);
/// Nearest object per texel: -1 where unused or none within the band.
std::vector<float> nearestObjectImage(const ObjectSamples& samples, const ObjectDistanceMap& map);
/// Unit direction to the closest point per texel (x, y, z interleaved), 0
/// where unused; the paper's distance vector divided by its length.
std::vector<float> directionImage(const ObjectSamples& samples, const ObjectDistanceMap& map);

}  // namespace dfrecon
