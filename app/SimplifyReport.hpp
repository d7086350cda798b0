#pragma once
// The simplification step shared by `dfrecon simplify` and `dfrecon
// reconstruct --max-error`: run simplifySurface, verify the result
// independently (dense samples, exact distances; the contours and a .vdb
// field when given) and describe it all as JSON.
#include <optional>

#include <nlohmann/json.hpp>

#include "app/Commands.hpp"
#include "contours/ContourSet.hpp"
#include "dfrecon/Simplify.hpp"
#include "io/LevelSetVdb.hpp"

namespace dfrecon::app {

struct SimplifyRequest {
    SimplifyOptions options;
    const Roi* contours = nullptr;           // verify against these too
    const LevelSetSampler* field = nullptr;  // report |field| on the result
    std::string label;                       // progress text
};

/// The report of a simplification: sizes, the certified bounds, the
/// verified distances (to the contours when `againstContours`; |field| at
/// the result's samples when given), seconds. O(1).
nlohmann::ordered_json simplificationJson(const VerifiedSimplification& simplified,
                                          const SimplifyOptions& options, bool againstContours,
                                          std::optional<double> fieldAbsMaxMm = std::nullopt);

/// Simplifies `surface` (replaced by the result) and returns the report:
/// sizes, the certified bounds, the verified distances, seconds.
nlohmann::ordered_json simplifyAndVerify(ocl::Runtime& runtime, TriangleSoup& surface,
                                         const SimplifyRequest& request,
                                         const GlobalOptions& global);

}  // namespace dfrecon::app
