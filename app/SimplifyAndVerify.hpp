#pragma once
// The simplification step shared by `dfrecon simplify` and `dfrecon
// reconstruct --max-error`: run simplifySurface, verify the result
// independently (dense samples, exact distances; the contours and a .vdb
// field when given) and describe it all as JSON (report/SimplifyReport).
#include <optional>

#include <nlohmann/json.hpp>

#include "app/Commands.hpp"
#include "contours/ContourSet.hpp"
#include "dfrecon/Simplify.hpp"
#include "io/volumes/LevelSetVdb.hpp"
#include "report/SimplifyReport.hpp"

namespace dfrecon::app {

struct SimplifyRequest {
    SimplifyOptions options;
    const Roi* contours = nullptr;           // verify against these too
    const LevelSetSampler* field = nullptr;  // report |field| on the result
    std::string label;                       // progress text
};

/// Simplifies `surface` (replaced by the result) and returns the report:
/// sizes, the certified bounds, the verified distances, seconds.
nlohmann::ordered_json simplifyAndVerify(ocl::Runtime& runtime, TriangleSoup& surface,
                                         const SimplifyRequest& request,
                                         const GlobalOptions& global);

}  // namespace dfrecon::app
