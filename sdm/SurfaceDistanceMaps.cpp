#include "sdm/SurfaceDistanceMaps.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>

namespace dfrecon {

ObjectSamples sampleObject(const SurfaceScene& scene, std::size_t object,
                           const AtlasOptions& options) {
    const TriangleSoup& soup = scene.object(object);
    ObjectSamples s;
    s.atlas = buildAtlas(soup, options);
    AtlasSamples texels = atlasSamples(s.atlas, soup);
    s.texel = std::move(texels.texel);
    s.samples.reserve(s.texel.size() + soup.points.size());
    for (std::size_t k = 0; k < s.texel.size(); ++k)
        s.samples.push_back({texels.point[k], std::uint32_t(object), texels.triangle[k]});
    // Each vertex with one of its triangles, whose candidates serve it.
    std::vector<std::uint32_t> triangleOf(soup.points.size(), UINT32_MAX);
    for (std::size_t t = 0; t < soup.triangles.size(); ++t)
        for (std::uint32_t v : soup.triangles[t])
            if (triangleOf[v] == UINT32_MAX) triangleOf[v] = std::uint32_t(t);
    for (std::size_t v = 0; v < soup.points.size(); ++v) {
        if (triangleOf[v] == UINT32_MAX) continue;
        s.vertex.push_back(std::uint32_t(v));
        s.samples.push_back({soup.points[v], std::uint32_t(object), triangleOf[v]});
    }
    return s;
}

std::vector<ObjectDistanceMap> surfaceDistanceMaps(const SurfaceScene& scene,
                                                   const std::vector<ObjectSamples>& samples,
                                                   const ClosestPrimitivesFn& closest,
                                                   const DistanceQuery& query) {
    if (query.target >= 0) throw std::invalid_argument("surfaceDistanceMaps: target must be -1");
    std::vector<ObjectDistanceMap> maps(samples.size());
    for (std::size_t o = 0; o < samples.size(); ++o) {
        std::vector<ClosestPrimitive> all = closest(samples[o].samples, query);
        const std::size_t texels = samples[o].texelCount();
        maps[o].texels.assign(all.begin(), all.begin() + std::ptrdiff_t(texels));
        maps[o].vertices.resize(scene.object(o).points.size());
        for (std::size_t k = 0; k < samples[o].vertex.size(); ++k)
            maps[o].vertices[samples[o].vertex[k]] = all[texels + k];
    }
    return maps;
}

namespace {

template <class Value>
std::vector<float> texelImage(const ObjectSamples& samples, const ObjectDistanceMap& map,
                              int channels, float unused, Value&& value) {
    std::vector<float> image(std::size_t(samples.atlas.width) * std::size_t(samples.atlas.height) *
                                 std::size_t(channels),
                             unused);
    for (std::size_t k = 0; k < samples.texelCount(); ++k)
        value(map.texels[k], samples.samples[k], &image[samples.texel[k] * std::size_t(channels)]);
    return image;
}

}  // namespace

std::vector<float> distanceImage(const ObjectSamples& samples, const ObjectDistanceMap& map) {
    return texelImage(samples, map, 1, std::numeric_limits<float>::quiet_NaN(),
                      [](const ClosestPrimitive& c, const SurfaceSample&, float* out) {
                          *out = float(c.distanceMm);
                      });
}

std::vector<float> nearestObjectImage(const ObjectSamples& samples, const ObjectDistanceMap& map) {
    return texelImage(samples, map, 1, -1.0f,
                      [](const ClosestPrimitive& c, const SurfaceSample&, float* out) {
                          *out = float(c.object);
                      });
}

std::vector<float> directionImage(const ObjectSamples& samples, const ObjectDistanceMap& map) {
    return texelImage(samples, map, 3, 0.0f,
                      [](const ClosestPrimitive& c, const SurfaceSample& s, float* out) {
                          if (c.object < 0) return;
                          const Vec3 d = c.point - s.point;
                          const double l = length(d);
                          if (l <= 0) return;
                          out[0] = float(d.x / l);
                          out[1] = float(d.y / l);
                          out[2] = float(d.z / l);
                      });
}

}  // namespace dfrecon
