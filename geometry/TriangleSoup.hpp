#pragma once
// Triangles as a plain indexed list, with no topological assumptions, so
// that non-manifold or inconsistently oriented input can be inspected
// (OpenMesh's half-edge mesh refuses such faces when reading).
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "geometry/PlaneFrame.hpp"
#include "geometry/TriMesh.hpp"
#include "geometry/Vec3.hpp"

namespace dfrecon {

struct TriangleSoup {
    std::vector<Vec3> points;
    std::vector<std::array<std::uint32_t, 3>> triangles;  // indices into points
};

/// The triangles of a half-edge mesh.
TriangleSoup toTriangleSoup(const TriMesh& mesh);

/// Triangles first..last-1 of `soup`, in order, as a soup of their own: the
/// points they use, in the order of their ids in `soup` (so shared corners
/// stay shared). For checks of one part of a surface. O(k log k) for k
/// triangles, nothing per point of `soup`.
TriangleSoup soupOfTriangles(const TriangleSoup& soup, std::size_t first, std::size_t last);
/// The same for the triangles `subset` (ids into soup.triangles), in order.
TriangleSoup soupOfTriangles(const TriangleSoup& soup, const std::vector<std::size_t>& subset);

/// Appends `part`'s points and triangles to `soup` (its triangles renumbered
/// to the appended points): two surfaces as one soup, nothing shared.
/// O(size of part).
void appendSoup(TriangleSoup& soup, const TriangleSoup& part);

/// Drops the points no triangle uses and renumbers the triangles. O(n).
void removeUnusedPoints(TriangleSoup& soup);

/// Drops the points from `first` on that no triangle uses; the points below
/// `first` keep their ids and the rest their order (so any comparison of
/// ids gives what it gave before), and both arrays are left with no spare
/// capacity. O(n).
void removeUnusedPointsFrom(TriangleSoup& soup, std::size_t first);

/// What removeUnusedPointsFrom(soup, first) renumbers: for point first + i,
/// its id once the unused points from `first` on are dropped, or
/// kUnusedPoint. Moves nothing. O(triangles + points from `first`).
inline constexpr std::uint32_t kUnusedPoint = 0xffffffffu;
std::vector<std::uint32_t> idsWithoutUnusedFrom(const TriangleSoup& soup, std::size_t first);

/// Rounds every point to the nearest float, as mesh files store them, so
/// that a check sees the surface a file will hold. O(n).
void roundPointsToFloat(TriangleSoup& soup);

/// Maps every point from `frame`'s plane coordinates to patient
/// coordinates; the frame is a rotation, so orientation is kept. O(n).
void toPatient(TriangleSoup& soup, const PlaneFrame& frame);

/// The half-edge mesh of a soup (writeMesh adds normals). OpenMesh refuses
/// faces that would make an edge non-manifold; how many it refused is
/// returned in `refusedFaces` (0 for any valid surface).
TriMesh toTriMesh(const TriangleSoup& soup, std::size_t* refusedFaces = nullptr);

}  // namespace dfrecon
