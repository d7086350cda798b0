#pragma once
// The report of one reconstructed ROI: the keys `reconstruct --json` and
// `batch` give per ROI (docs/cli.md lists every key) and the Python module's
// reconstruct() returns.
#include <cstddef>
#include <string>

#include <nlohmann/json.hpp>

#include "contours/ContourSet.hpp"
#include "dfrecon/Reconstruct.hpp"
#include "io/dicom/RtStruct.hpp"
#include "io/mesh/StructureTag.hpp"
#include "report/ReconstructSettings.hpp"

namespace dfrecon {

/// The name and colour of `roi` as mesh files carry them (io/mesh/StructureTag).
/// O(name length).
StructureTag structureTagOf(const Roi& roi);

/// Where a reconstructed ROI went: its file (when written), the faces
/// OpenMesh refused on the way, the seconds writing took.
struct RoiWriting {
    std::string path;
    bool written = false;
    std::size_t refusedFaces = 0;
    double seconds = 0;
};

/// The report `reconstruct --json` gives per ROI for `result` of `roi`
/// (docs/cli.md lists every key); `dicom` what DICOM reading found about it
/// (or nullptr), `simplification` simplificationJson's report or null. The
/// Python module's reconstruct() returns it too. O(broken pieces).
nlohmann::ordered_json roiReport(const Roi& roi, const RoiSurface& result,
                                 const RtStructRoiInfo* dicom, const ReconstructSettings& settings,
                                 const RoiWriting& writing,
                                 const nlohmann::ordered_json& simplification);

}  // namespace dfrecon
