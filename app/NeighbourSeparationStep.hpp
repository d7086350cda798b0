#pragma once
// reconstruct's step between reconstructing every ROI and writing them:
// neighbours kept apart (dfrecon/Reconstruct's keepNeighboursApart), and
// the overlap that remains between every pair that met, measured exactly
// (compare/OverlapVolume), for the report.
#include <optional>
#include <vector>

#include <nlohmann/json.hpp>

#include "cl/Runtime.hpp"
#include "contours/ContourSet.hpp"
#include "dfrecon/Reconstruct.hpp"

namespace dfrecon::app {

/// Moves the ROIs' surfaces apart (null entries: ROIs that failed), or with
/// `move` false only finds the pairs that meet, and
/// returns the report's "neighbours" object: seconds, and one entry per
/// pair that met (a vertex of one inside the other) with the vertices
/// inside and moved, and, for pairs whose contours overlap on no plane, the
/// intersection's volume after the move (mm³, with its bound). O(the
/// separation + one overlap per pair that met).
nlohmann::ordered_json neighbourSeparationJson(ocl::Runtime& runtime,
                                               const std::vector<const Roi*>& rois,
                                               std::vector<std::optional<RoiSurface>>& surfaces,
                                               bool move);

/// The one line `reconstruct` prints of that object (stdout, text mode).
std::string neighbourSeparationLine(const nlohmann::ordered_json& neighbours);

}  // namespace dfrecon::app
