#include "app/CompareReport.hpp"

namespace dfrecon::app {

nlohmann::ordered_json planesJson(const std::optional<PlaneComparison>& planes) {
    if (!planes) return nullptr;
    if (!planes->samePlanes) return {{"compared", false}, {"why", planes->whyNot}};
    return {{"compared", true},
            {"planes", planes->planes},
            {"volumeAMm3", planes->volumeAMm3},
            {"volumeBMm3", planes->volumeBMm3},
            {"intersectionMm3", planes->intersectionMm3},
            {"dice", planes->dice()},
            {"jaccard", planes->jaccard()},
            {"pathLengthAMm", planes->pathLengthAMm},
            {"pathLengthBMm", planes->pathLengthBMm},
            {"addedPathLengthMm", planes->addedPathLengthMm},
            {"addedPathLengthAMm", planes->addedPathLengthAMm},
            {"toleranceMm", planes->toleranceMm}};
}

nlohmann::ordered_json comparisonJson(const Comparison& r) {
    const Overlap& o = r.overlap;
    const SurfaceDistances& d = r.distances;
    auto directed = [](const DirectedDistances& x) {
        return nlohmann::ordered_json{{"hausdorffMm", x.maxMm},
                                      {"hd95Mm", x.p95Mm},
                                      {"meanMm", x.meanMm},
                                      {"areaWithinToleranceMm2", x.areaWithinToleranceMm2},
                                      {"samples", x.samples}};
    };
    return {{"volumeAMm3", o.volumeAMm3},
            {"volumeBMm3", o.volumeBMm3},
            {"volumeDifferenceMm3", o.volumeBMm3 - o.volumeAMm3},
            {"intersectionMm3", o.intersectionMm3},
            {"unionMm3", o.unionMm3()},
            {"dice", o.dice()},
            {"jaccard", o.jaccard()},
            {"overlapMethod", o.method},
            {"overlapShiftMm", o.shiftMm},
            {"intersectionBoundMm3", o.intersectionBoundMm3},
            {"hausdorffMm", d.hausdorffMm()},
            {"hd95Mm", d.hd95Mm()},
            {"hd95PooledMm", d.hd95PooledMm},
            {"meanSurfaceDistanceMm", d.meanMm()},
            {"surfaceDice", d.surfaceDice()},
            {"toleranceMm", d.toleranceMm},
            {"centroidDistanceMm", r.centroidDistanceMm},
            {"distanceBoundMm", d.spacingMm},
            {"aToB", directed(d.aToB)},
            {"bToA", directed(d.bToA)},
            {"onPlanes", planesJson(r.planes)},
            {"seconds",
             {{"overlap", r.overlapSeconds},
              {"distances", r.distanceSeconds},
              {"planes", r.planeSeconds}}}};
}

}  // namespace dfrecon::app
