#include "segment/FarthestPointSampling.hpp"

#include <stdexcept>
#include <string>

namespace dfrecon {

void addFarthestPoints(const FastMarching& marching, FarthestPoints& samples, int more) {
    for (int k = 0; k < more; ++k) {
        const int next = farthestVertex(samples.field);
        if (next < 0 || !(samples.field.time[std::size_t(next)] > 0)) return;
        const int label = int(samples.vertices.size());
        samples.vertices.push_back(next);
        marching.march(samples.field, {{next, 0.0, label}});
        const int far = farthestVertex(samples.field);
        samples.coveringRadius.push_back(far < 0 ? 0.0 : samples.field.time[std::size_t(far)]);
    }
}

FarthestPoints farthestPointSampling(const FastMarching& marching, int count, int start) {
    if (count < 1) throw std::invalid_argument("farthest-point sampling needs count ≥ 1");
    if (start < 0 || start >= marching.vertexCount())
        throw std::invalid_argument("start vertex " + std::to_string(start) + " out of range");
    FarthestPoints samples;
    // The march from `start` only finds the first sample; it is not one.
    samples.field = marching.solve({{start, 0.0, -1}});
    const int first = farthestVertex(samples.field);
    samples.field = GeodesicField{std::size_t(marching.vertexCount())};
    samples.vertices.push_back(first);
    marching.march(samples.field, {{first, 0.0, 0}});
    const int far = farthestVertex(samples.field);
    samples.coveringRadius.push_back(far < 0 ? 0.0 : samples.field.time[std::size_t(far)]);
    addFarthestPoints(marching, samples, count - 1);
    return samples;
}

}  // namespace dfrecon
