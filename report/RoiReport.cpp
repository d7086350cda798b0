#include "report/RoiReport.hpp"

#include <optional>

#include "report/EnumNames.hpp"
#include "report/Reports.hpp"

namespace dfrecon {

StructureTag structureTagOf(const Roi& roi) {
    return StructureTag{roi.name, roi.colour};
}

namespace {

// Where the ROI ends and starts again (contours/PlaneGaps): [below, above]
// of each gap, in the plane frame's mm.
nlohmann::ordered_json planeGapsJson(const Roi& roi) {
    nlohmann::ordered_json gaps = nlohmann::ordered_json::array();
    for (std::size_t i : roi.restartsAt) gaps.push_back({roi.slices[i - 1].zMm, roi.slices[i].zMm});
    return gaps;
}

}  // namespace

nlohmann::ordered_json roiReport(const Roi& roi, const RoiSurface& result,
                                 const RtStructRoiInfo* dicom, const ReconstructSettings& settings,
                                 const RoiWriting& writing,
                                 const nlohmann::ordered_json& simplification) {
    const ReconstructionStats& s = result.stats;
    const MeshCheckReport& check = result.check;
    const double contourVolume = result.contourVolumeMm3;
    const std::optional<const char*> holes =
        dicom ? std::optional(nameOf(kHoleConventionNames, dicom->holes)) : std::nullopt;
    nlohmann::ordered_json broken = nlohmann::ordered_json::array();
    for (const auto& [below, above] : result.brokenPieces) broken.push_back({below, above});
    nlohmann::ordered_json report{{"roi", roi.name},
                                  {"roiNumber", valueOrNull(roi.number)},
                                  {"output", valueOrNull(writing.written, writing.path)},
                                  {"written", writing.written}};
    appendItems(report, meshCheckJson(check));
    appendItems(report,
                {{"contourVolumeMm3", contourVolume},
                 {"contourVolumeCc", contourVolume / 1000},
                 {"brokenSlabsMm", broken},
                 {"touchesOpened", s.touchesOpened},
                 {"piecesClosedAgain", s.repairedPieces},
                 {"facesRefusedByOpenMesh", writing.refusedFaces},
                 {"slices", s.slices},
                 {"pieces", s.runs},
                 {"planesLeftEmptyMm", planeGapsJson(roi)},
                 {"planes", roi.frame.orientationName()},
                 {"holeConvention", valueOrNull(holes)},
                 {"contourReading", contourReadingJson(roi.reading)},
                 {"slabThicknessMm", valueOrNull(roi.slabThicknessMm > 0, roi.slabThicknessMm)},
                 {"contourPoints", s.contourPoints},
                 {"pixelMm", s.pixelMm},
                 {"cap", nameOf(kCapModeNames, settings.options.cap)},
                 {"interpolation", nameOf(kInterpolationNames, settings.options.interpolation)},
                 {"smoothedVertices", s.smoothedVertices},
                 {"smoothUnbentVertices", s.smoothUnbentVertices},
                 {"smoothHalfUnbentVertices", s.smoothHalfUnbentVertices},
                 {"smoothCoarsenedVertices", s.smoothCoarsenedVertices},
                 {"smoothKeptLinearPieces", s.smoothRevertedPieces},
                 {"smoothFellBackToLinear", s.smoothFellBack},
                 {"strips", s.strips},
                 {"slidStrips", s.slidStrips},
                 {"rejectedStrips", s.rejectedStrips},
                 {"intermediateLayers", s.recursions},
                 {"deepestLevel", s.deepestLevel},
                 {"closedAtDepthLimit", s.limitClosings},
                 {"endContours", s.caps},
                 {"slabsClosedAsPrisms", s.fallbackSlabs},
                 {"stepSlabs", s.stepSlabs},
                 {"simplification", simplification},
                 {"seconds",
                  {{"simplify", s.simplifySeconds},
                   {"fields", s.fieldsSeconds},
                   {"medialAxes", s.medialSeconds},
                   {"triangulation", s.triangulationSeconds},
                   {"check", result.checkSeconds},
                   {"smooth", s.smoothSeconds},
                   {"write", writing.seconds}}}});
    return report;
}

}  // namespace dfrecon
