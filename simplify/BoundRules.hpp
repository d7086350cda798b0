#pragma once
// The settling rules shared with kernels/collapse_bound.cl, compiled as
// C++ (REAL = double, REAL4 = Vec3) in namespace dfrecon::shared, so the
// batch and its reference take the same steps with the same roundings:
// clip_polygon, straddle_plane and straddle_distance
// (kernels/straddle_bound.cl), fan_distance (kernels/fan_bound.cl).
#include <cmath>

#include "geometry/ClosestPoint.hpp"
#include "geometry/VertexFans.hpp"

namespace dfrecon::shared {
using closest::dot3;
using closest::point_triangle_distance;
using std::sqrt;
#define REAL double
#define REAL4 Vec3
#define STRADDLE_FN inline
#define FAN_FN inline
#define FAN_MAX 16
// In this order: the fan rule clips with straddle_bound.cl's clip_polygon.
#include "kernels/straddle_bound.cl"
// (a separate block, so that include sorting keeps the order)
#include "kernels/fan_bound.cl"
#undef FAN_MAX
#undef FAN_FN
#undef STRADDLE_FN
#undef REAL4
#undef REAL

static_assert(VertexFans::kMaxNeighbours == 16, "FAN_MAX above and in kernels/fan_bound.cl");
}  // namespace dfrecon::shared
