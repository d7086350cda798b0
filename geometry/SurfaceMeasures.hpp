#pragma once
// What a closed, outward-oriented triangle surface encloses, by the
// divergence theorem over its triangles: its volume, its area, and the part
// of its volume below a plane z = c. The mesh checker reports the first two;
// smooth reconstruction and the truth benchmark split volumes at planes.
#include "geometry/TriangleSoup.hpp"

namespace dfrecon {

struct SurfaceMeasures {
    double volumeMm3 = 0;  // signed: > 0 when normals point outward
    double areaMm2 = 0;
    /// The enclosed solid's centre of mass (uniform density): the tetrahedra
    /// from the origin to each triangle, weighted by signed volume. The
    /// origin when the volume is 0.
    Vec3 centroidMm;
};

/// Enclosed volume (Σ p0 · (p1 × p2) / 6), area and centroid. O(T).
SurfaceMeasures measureSurface(const TriangleSoup& soup);

/// The volume of the part with z ≤ `zMm`: the integral of (z − zMm)·n_z
/// over the surface below the plane (the field (0, 0, z − zMm) has unit
/// divergence and vanishes on the cutting plane), triangles crossing it
/// clipped. Exact for a closed surface. O(T).
double volumeBelowPlane(const TriangleSoup& soup, double zMm);

}  // namespace dfrecon
