#pragma once
// The report of a simplification, as `dfrecon simplify --json`, `reconstruct
// --max-error` and the Python module give it.
#include <optional>

#include <nlohmann/json.hpp>

#include "dfrecon/Simplify.hpp"

namespace dfrecon {

/// The report of a simplification: sizes, the certified bounds, the
/// verified distances (to the contours when `againstContours`; |field| at
/// the result's samples when given), seconds. O(1).
nlohmann::ordered_json simplificationJson(const VerifiedSimplification& simplified,
                                          const SimplifyOptions& options, bool againstContours,
                                          std::optional<double> fieldAbsMaxMm = std::nullopt);

}  // namespace dfrecon
