#pragma once
// Farthest-point sampling on a surface (the paper's §2.3): each new sample
// is the vertex farthest (in the weighted geodesic distance of the given
// speed) from all samples so far. The distance field is kept between steps
// and each new sample's front is marched over it (FastMarching::march), so
// a step only touches the vertices that the new sample is closest to; the
// whole sampling costs about O(N log N · log k) on a uniform surface rather
// than k full solves.
#include <vector>

#include "segment/FastMarching.hpp"

namespace dfrecon {

struct FarthestPoints {
    std::vector<int> vertices;  // the samples, in the order chosen
    /// coveringRadius[i]: the largest distance to samples 0..i, i.e. how far
    /// sample i+1 is from the others when chosen (non-increasing).
    std::vector<double> coveringRadius;
    GeodesicField field;  // distance to the nearest sample; label = its index
};

/// `count` samples. The first is the vertex farthest from `start` (a vertex
/// index; the result then does not depend much on where one starts). Stops
/// early when every reached vertex is a sample (a mesh with fewer vertices
/// than `count`); vertices in components no front reaches are never
/// sampled. Throws std::invalid_argument for a bad start or count < 1.
FarthestPoints farthestPointSampling(const FastMarching& marching, int count, int start = 0);

/// Continues an existing sampling with `more` samples.
void addFarthestPoints(const FastMarching& marching, FarthestPoints& samples, int more);

}  // namespace dfrecon
