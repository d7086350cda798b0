#include "sdm/ProximityQueries.hpp"

#include <algorithm>
#include <cmath>

#include "geometry/MeshCheck.hpp"

namespace dfrecon {

bool surfacesIntersect(const TriangleSoup& a, const TriangleSoup& b) {
    // One hierarchy over both; only pairs across the two count.
    TriangleSoup both = a;
    appendSoup(both, b);
    const std::size_t firstOfB = a.triangles.size();
    const TriangleBvh bvh(both);
    bool found = false;
    bvh.selfPairs([&](std::size_t i, std::size_t j) {
        if (found || (i < firstOfB) == (j < firstOfB)) return;
        Vec3 s[3], t[3];
        for (int k = 0; k < 3; ++k) {
            s[k] = both.points[both.triangles[i][std::size_t(k)]];
            t[k] = both.points[both.triangles[j][std::size_t(k)]];
        }
        found = trianglesIntersect(s, t);
    });
    return found;
}

namespace {

// What one object's samples say about another: the nearest sample pair and
// the deepest sample inside it.
struct OneWay {
    double nearestMm = INFINITY;
    Vec3 from, to;
    double deepestMm = 0;
    bool anyInside = false, anyOutside = false;
};

OneWay oneWay(const SurfaceScene& scene, const ObjectSamples& from, std::size_t to,
              const ClosestPrimitivesFn& closest) {
    DistanceQuery query;
    query.target = int(to);
    const std::vector<ClosestPrimitive> answers = closest(from.samples, query);
    OneWay w;
    for (std::size_t k = 0; k < answers.size(); ++k) {
        const ClosestPrimitive& c = answers[k];
        if (c.object < 0) continue;
        if (std::abs(c.distanceMm) < w.nearestMm) {
            w.nearestMm = std::abs(c.distanceMm);
            w.from = from.samples[k].point;
            w.to = c.point;
        }
        if (c.distanceMm < 0) {
            w.anyInside = true;
            w.deepestMm = std::max(w.deepestMm, -c.distanceMm);
        } else if (c.distanceMm > 0 || !scene.closed(to)) {
            w.anyOutside = true;
        }
    }
    return w;
}

}  // namespace

std::vector<PairProximity> proximityQueries(const SurfaceScene& scene,
                                            const std::vector<ObjectSamples>& samples,
                                            const ClosestPrimitivesFn& closest) {
    std::vector<PairProximity> pairs;
    for (std::size_t i = 0; i < scene.objectCount(); ++i)
        for (std::size_t j = i + 1; j < scene.objectCount(); ++j) {
            const OneWay ij = oneWay(scene, samples[i], j, closest);
            const OneWay ji = oneWay(scene, samples[j], i, closest);
            PairProximity p;
            p.first = i;
            p.second = j;
            p.surfacesIntersect = surfacesIntersect(scene.object(i), scene.object(j));
            // Without crossing surfaces, one object is inside the other
            // wholly or not at all, so any sample decides.
            p.firstInsideSecond = !p.surfacesIntersect && ij.anyInside && !ij.anyOutside;
            p.secondInsideFirst = !p.surfacesIntersect && ji.anyInside && !ji.anyOutside;
            // Both directions were sampled, so the finer bound holds.
            p.boundMm = std::min(samples[i].samplingBoundMm(), samples[j].samplingBoundMm());
            if (ij.nearestMm <= ji.nearestMm) {
                p.separationMm = ij.nearestMm;
                p.pointOnFirst = ij.from;
                p.pointOnSecond = ij.to;
            } else {
                p.separationMm = ji.nearestMm;
                p.pointOnFirst = ji.to;
                p.pointOnSecond = ji.from;
            }
            if (p.colliding()) p.separationMm = 0;
            p.deepestPointMm = std::max(ij.deepestMm, ji.deepestMm);
            p.depthBoundMm = std::max(samples[i].samplingBoundMm(), samples[j].samplingBoundMm());
            pairs.push_back(p);
        }
    return pairs;
}

}  // namespace dfrecon
