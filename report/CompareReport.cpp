#include "report/CompareReport.hpp"

#include "api/Stopwatch.hpp"
#include "dfrecon/Reconstruct.hpp"
#include "report/ExitCodes.hpp"
#include "report/Failure.hpp"

namespace dfrecon {

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

ComparedSolid reconstructedSolid(ocl::Runtime& runtime, const std::string& file, const Roi& roi) {
    RoiSurface result = dfrecon::reconstructRoi(runtime, roi);
    if (!result.check.validSolid())
        throw InvalidResult(file + ": ROI '" + roi.name + "' gives no valid closed solid");
    return ComparedSolid{std::move(result.surface), result.check, &roi};
}

nlohmann::ordered_json comparedPairRow(ocl::Runtime& runtime, const RoiPair& pair,
                                       const std::string& fileA, const std::string& fileB,
                                       const CompareOptions& options) {
    nlohmann::ordered_json row{
        {"roiA", pair.a->name}, {"roiB", pair.b->name}, {"matchedBy", pair.matchedBy}};
    try {
        Stopwatch watch;
        const ComparedSolid a = reconstructedSolid(runtime, fileA, *pair.a);
        const ComparedSolid b = reconstructedSolid(runtime, fileB, *pair.b);
        const double loadSeconds = watch.lap();
        row.update(comparisonJson(compareSolids(runtime, a, b, options)));
        row["seconds"]["load"] = loadSeconds;
        row["exitCode"] = 0;
        row["error"] = nullptr;
    } catch (...) {
        const Failure failure = describeFailure(std::current_exception());
        row["exitCode"] = failure.exitCode;
        row["error"] = failure.message;
    }
    return row;
}

nlohmann::ordered_json unpairedJson(const RoiMatching& matching) {
    auto names = [](const std::vector<const Roi*>& rois) {
        nlohmann::ordered_json list = nlohmann::ordered_json::array();
        for (const Roi* roi : rois) list.push_back(roi->name);
        return list;
    };
    return {{"unmatchedA", names(matching.onlyA)},      {"unmatchedB", names(matching.onlyB)},
            {"duplicateA", names(matching.duplicateA)}, {"duplicateB", names(matching.duplicateB)},
            {"emptyA", names(matching.emptyA)},         {"emptyB", names(matching.emptyB)}};
}

}  // namespace dfrecon
