#pragma once
// The growing triangle list of a reconstruction: vertices with their 3D
// positions, triangles by vertex index. Contour vertices are added once and
// shared by the pieces above and below them, which is what makes the
// result watertight.
#include <array>
#include <cstdint>
#include <vector>

#include "geometry/Polygon.hpp"
#include "geometry/TriangleSoup.hpp"

namespace dfrecon {

class SurfaceBuilder {
  public:
    std::uint32_t addVertex(Point2 p, double zMm) {
        soup_.points.push_back({p.x, p.y, zMm});
        return std::uint32_t(soup_.points.size() - 1);
    }
    /// Counter-clockwise seen from outside the solid.
    void addTriangle(std::uint32_t a, std::uint32_t b, std::uint32_t c) {
        soup_.triangles.push_back({a, b, c});
    }
    const Vec3& point(std::uint32_t v) const { return soup_.points[v]; }
    std::size_t triangleCount() const { return soup_.triangles.size(); }
    /// Drops the triangles added after the first `count`.
    void truncateTriangles(std::size_t count) { soup_.triangles.resize(count); }
    /// The triangles from `first` on, as a soup of just their vertices.
    TriangleSoup trianglesSince(std::size_t first) const;
    const TriangleSoup& soup() const { return soup_; }
    TriangleSoup release() { return std::move(soup_); }

  private:
    TriangleSoup soup_;
};

/// Contours on one plane and the mesh vertex of each contour point.
struct Layer {
    double zMm = 0;
    std::vector<Polygon> contours;
    std::vector<std::vector<std::uint32_t>> vertexIds;
};

/// A layer whose vertices have been added to `builder`.
Layer makeLayer(SurfaceBuilder& builder, double zMm, std::vector<Polygon> contours);

}  // namespace dfrecon
