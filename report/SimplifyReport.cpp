#include "report/SimplifyReport.hpp"

namespace dfrecon {

nlohmann::ordered_json simplificationJson(const VerifiedSimplification& simplified,
                                          const SimplifyOptions& options, bool againstContours,
                                          std::optional<double> fieldAbsMaxMm) {
    const TwoSidedDistance& both = simplified.verified.surfaces;
    nlohmann::ordered_json distances{{"inputToResultMaxMm", both.aToB.maxMm},
                                     {"resultToInputMaxMm", both.bToA.maxMm},
                                     {"meanMm", 0.5 * (both.aToB.meanMm + both.bToA.meanMm)}};
    if (againstContours) distances["contoursToResultMaxMm"] = simplified.verified.contours.maxMm;
    distances["maxMm"] = simplified.verified.maxMm();
    distances["samples"] = both.aToB.samples + both.bToA.samples;
    distances["spacingMm"] = both.spacingMm;
    if (fieldAbsMaxMm) distances["fieldAbsMaxMm"] = *fieldAbsMaxMm;
    const SimplifyStats& s = simplified.result.stats;
    return {
        {"maxErrorMm", options.maxErrorMm},
        {"trianglesBefore", s.trianglesBefore},
        {"triangles", s.triangles},
        {"vertices", s.vertices},
        {"collapses", s.collapses},
        {"boundMm",
         {{"resultToInput", s.surfaceToInputBoundMm}, {"inputToResult", s.inputToSurfaceBoundMm}}},
        {"verified", distances},
        {"withinBound", simplified.withinBound(options.maxErrorMm)},
        {"originalPieces", s.pieces},
        {"retries", s.retries},
        {"seconds",
         {{"initialBatch", s.initialSeconds},
          {"decimate", s.decimateSeconds},
          {"verify", simplified.verifySeconds}}}};
}

}  // namespace dfrecon
