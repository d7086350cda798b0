#pragma once
// Is a triangle surface a valid closed solid? Closed, manifold, consistently
// oriented, no degenerate triangle, no two triangles crossing
// (geometry/MeshCheck: exact predicates); with its volume, area, genus and
// where its defects are. What `dfrecon check` reports.
#include "geometry/MeshCheck.hpp"
#include "geometry/TriangleSoup.hpp"

namespace dfrecon {

// checkMesh(const TriangleSoup&) -> MeshCheckReport: see geometry/MeshCheck.hpp.

}  // namespace dfrecon
