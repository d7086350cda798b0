#pragma once
// Closed triangle meshes of simple solids, with outward normals, for tests,
// benchmarks and demos: geodesic spheres and subdivided boxes.
#include "io/TriangleSoup.hpp"

namespace dfrecon {

/// A sphere: the icosahedron with each face split into 4, `subdivisions`
/// times, its vertices pushed onto the sphere. 20·4^s triangles. O(T).
TriangleSoup icosphere(Vec3 centre, double radiusMm, int subdivisions);

/// An axis-aligned box [lo, hi] whose every face is an n×n grid of squares,
/// each split into two triangles: 12·n² triangles, closed. O(n²).
TriangleSoup boxMesh(Vec3 lo, Vec3 hi, int n);

}  // namespace dfrecon
