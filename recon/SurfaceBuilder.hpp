#pragma once
// The growing triangle list of a reconstruction: vertices with their 3D
// positions, triangles by vertex index. Contour vertices are added once and
// shared by the pieces above and below them, which is what makes the
// result watertight.
#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

#include "geometry/MeshCheck.hpp"
#include "geometry/Polygon.hpp"
#include "geometry/TriangleSoup.hpp"

namespace dfrecon {

/// What a builder added on top of the points it started with: its new
/// points and its triangles with their pieces, loft marks and clean groups.
/// Parts built apart (the slabs, on several cores) and appended in order
/// make the same surface as one builder adding them one after the other.
struct SurfacePart {
    std::size_t sharedPoints = 0;  // the points it started with: ids below this
    std::vector<Vec3> points;      // the new points, ids sharedPoints, sharedPoints + 1, ...
    std::vector<std::array<std::uint32_t, 3>> triangles;
    std::vector<std::uint32_t> pieces;  // per triangle
    std::vector<bool> lofts;            // per triangle
    CleanGroups cleanGroups;            // per triangle, numbered from 1 within the part
    std::uint32_t cleanGroupCount = 0;
};

class SurfaceBuilder {
  public:
    SurfaceBuilder() = default;
    /// A builder whose first vertices are `sharedPoints` (a part built on
    /// it is appended to a builder that holds the same first points).
    explicit SurfaceBuilder(std::vector<Vec3> sharedPoints) {
        soup_.points = std::move(sharedPoints);
    }

    std::uint32_t addVertex(Point2 p, double zMm) {
        soup_.points.push_back({p.x, p.y, zMm});
        return std::uint32_t(soup_.points.size() - 1);
    }
    /// Counter-clockwise seen from outside the solid.
    void addTriangle(std::uint32_t a, std::uint32_t b, std::uint32_t c) {
        soup_.triangles.push_back({a, b, c});
        pieces_.push_back(piece_);
        lofts_.push_back(false);
        cleanGroups_.push_back(0);
    }
    const Vec3& point(std::uint32_t v) const { return soup_.points[v]; }
    std::size_t triangleCount() const { return soup_.triangles.size(); }
    /// Drops the triangles added after the first `count`.
    void truncateTriangles(std::size_t count) {
        soup_.triangles.resize(count);
        pieces_.resize(count);
        lofts_.resize(count);
        cleanGroups_.resize(count);
    }
    /// Marks the triangles added since `first` as a loft band (`loft`): a
    /// strip stitched between two layers, which smooth interpolation may
    /// bend; or, with `loft` false, as none, strips included, which it leaves
    /// as built.
    void markLoftSince(std::size_t first, bool loft = true) {
        std::fill(lofts_.begin() + std::ptrdiff_t(first), lofts_.end(), loft);
    }
    /// Records that the triangles added since `first` were searched for
    /// colliding pairs among themselves, clean, at float coordinates (a
    /// strip's own check): a check of their piece need not test those
    /// pairs again (geometry/MeshCheck CleanGroups).
    void markSearchedTogetherSince(std::size_t first) {
        const std::uint32_t group = ++lastCleanGroup_;
        std::fill(cleanGroups_.begin() + std::ptrdiff_t(first), cleanGroups_.end(), group);
    }
    /// Per triangle from `first` on, its clean group (0: none).
    CleanGroups cleanGroupsSince(std::size_t first) const {
        return CleanGroups(cleanGroups_.begin() + std::ptrdiff_t(first), cleanGroups_.end());
    }
    const std::vector<std::uint32_t>& pieces() const { return pieces_; }
    const std::vector<bool>& lofts() const { return lofts_; }
    /// Tags the triangles added from now on with `piece` (the slab or cap
    /// they close), so that a broken piece can be found and built again.
    void setPiece(std::uint32_t piece) { piece_ = piece; }
    /// The piece triangles added now are tagged with.
    std::uint32_t piece() const { return piece_; }
    std::uint32_t pieceOf(std::size_t triangle) const { return pieces_[triangle]; }
    /// Drops the triangles of every piece p with drop[p] set. O(triangles).
    void dropPieces(const std::vector<bool>& drop);
    /// Rounds every point to the nearest float, as mesh files store them, so
    /// that a check sees the surface a file will hold. O(points).
    void roundPointsToFloat() { dfrecon::roundPointsToFloat(soup_); }
    /// The triangles from `first` on, as a soup of just their vertices.
    TriangleSoup trianglesSince(std::size_t first) const;
    const TriangleSoup& soup() const { return soup_; }

    /// The finished surface and what smoothing reads of it per triangle.
    struct Released {
        TriangleSoup soup;
        std::vector<std::uint32_t> pieces;
        std::vector<bool> lofts;
    };
    /// Hands over the surface with its pieces and loft marks. The builder
    /// is empty afterwards: the clean groups, which only the checks before
    /// read, are freed with it rather than held through smoothing. O(1).
    Released release();

    /// Hands over everything added after the first `sharedPoints` points
    /// (which must be all the builder started with, and no triangle), and
    /// goes back to holding only those. New points no triangle uses are
    /// left out (the rest keep their order), and the arrays have no spare
    /// capacity. O(what was added).
    SurfacePart takePart(std::size_t sharedPoints);
    /// Appends a part built on a builder whose first points were this
    /// one's first part.sharedPoints: its new points get the next ids, its
    /// clean groups the next numbers. O(part).
    void appendPart(SurfacePart&& part);

  private:
    TriangleSoup soup_;
    std::vector<std::uint32_t> pieces_;  // per triangle
    std::vector<bool> lofts_;            // per triangle
    CleanGroups cleanGroups_;            // per triangle
    std::uint32_t lastCleanGroup_ = 0;
    std::uint32_t piece_ = 0;
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
