#pragma once
// Closed and flat triangle meshes generated exactly, with outward normals,
// for tests, benchmarks and demos: geodesic spheres (great-circle
// distances), subdivided boxes (sharp edges, exact distances between them),
// and flat grids (Euclidean distances), one of them made of obtuse
// triangles.
#include "geometry/TriangleSoup.hpp"

namespace dfrecon {

/// The icosahedron with each face cut into frequency² triangles, vertices
/// pushed onto the sphere of `radius` centred at `centre`:
/// 10·frequency² + 2 vertices, 20·frequency² triangles, all near-equilateral
/// (no obtuse angles), consistently oriented outwards. frequency ≥ 1.
TriangleSoup geodesicSphere(int frequency, double radius = 1.0, Vec3 centre = {});

/// geodesicSphere with every vertex moved by a uniform random offset of up
/// to `jitter` × the mean edge length along each axis, then put back on the
/// sphere: irregular, with obtuse triangles (7.5 % of the corners for
/// jitter 0.35), like a scanned surface. Same `seed`, same mesh.
TriangleSoup jitteredGeodesicSphere(int frequency, double jitter, unsigned seed = 1,
                                    double radius = 1.0);

/// The axis-aligned box [lo, hi] whose every face is an n × n grid of
/// rectangles, each split into two triangles along the same diagonal:
/// 12·n² triangles, closed. n ≥ 1. O(n²).
TriangleSoup boxMesh(Vec3 lo, Vec3 hi, int n);

/// The surface of the cube [-size/2, size/2]³ with each face an n × n grid of
/// squares, each cut into two right triangles along the same diagonal:
/// 6n² + 2 vertices. n ≥ 1.
TriangleSoup tessellatedCube(int n, double size = 1.0);

/// A flat (z = 0) grid of (columns + 1) × (rows + 1) points spaced `dx` along
/// x and `dy` along y, every other row shifted by dx/2 and each strip between
/// rows cut into isosceles triangles with apex angle 2·atan(dx / (2·dy)):
/// obtuse (over 90°) whenever dy < dx/2. With dy = dx·√3/2 they are
/// equilateral.
TriangleSoup staggeredGrid(int columns, int rows, double dx, double dy);

/// A flat (z = 0) grid of squares of side `spacing`, each cut into two right
/// triangles along the same diagonal.
TriangleSoup squareGrid(int columns, int rows, double spacing);

}  // namespace dfrecon
