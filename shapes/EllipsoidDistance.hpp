#pragma once
// Exact Euclidean distance to an axis-aligned ellipsoid (Eberly, "Distance
// from a point to an ellipse, an ellipsoid, or a hyperellipsoid"): shared by
// the ellipsoid shape and the thin tilted one of the between-planes family.
#include "geometry/Vec3.hpp"

namespace dfrecon {

/// Signed distance from p to the ellipsoid x²/a² + y²/b² + z²/c² = 1 (any
/// order of the semi-axes), negative inside; exact to the bisection's
/// precision (about 1e-15 relative).
double ellipsoidSignedDistance(double a, double b, double c, Vec3 p);

}  // namespace dfrecon
