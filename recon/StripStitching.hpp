#pragma once
// Triangulation by tracing a medial axis (reconstruction paper §4): walking
// the medial axis between a contour P on one slice and Q on the next, each
// medial pixel names the nearest point of P and of Q. That gives every vertex
// of P and of Q a position along the axis; merging the two vertex sequences
// by position connects them with a strip of triangles, vertices of one side
// fanned to the vertex of the other side that shares their place on the
// axis (the paper's Fig. 5).
#include <cstdint>
#include <optional>
#include <vector>

#include "recon/MedialAxis.hpp"
#include "recon/SurfaceBuilder.hpp"

namespace dfrecon {

/// Where the vertices of one contour fall along a closed medial axis.
struct AxisPositions {
    double axisLength = 0;          // in pixels; positions are cyclic with this period
    std::size_t first = 0;          // the contour vertex with the smallest position
    std::vector<double> positions;  // positions[i] for vertex (first + i) mod n, non-decreasing
};

/// Positions of the vertices of `contour` (contour number `contourIndex` of
/// its slice) along `axis`, from the axis pixels' ids on that slice (`lower`
/// picks lowerId or upperId). Backtracking of the correspondence is removed
/// (a vertex never precedes the one before it), skipped vertices share the
/// place of the jump. Returns nothing unless the correspondence goes around
/// the contour exactly once in the contour's direction, which is what a
/// strip needs. O(axis pixels + contour points).
std::optional<AxisPositions> positionsAlongAxis(const MedialAxis& axis, const SliceGrid& grid,
                                                const Polygon& contour, std::uint32_t contourIndex,
                                                bool lower);

/// Closes the band between a lower contour (vertices `lowerIds`, one plane)
/// and an upper one (`upperIds`, the plane above), both in the slice
/// orientation (outer counter-clockwise, holes clockwise), with one triangle
/// per vertex of either, oriented outward. Ties in position go to the
/// shorter diagonal. O(n + m).
void stitchStrip(SurfaceBuilder& builder, const std::vector<std::uint32_t>& lowerIds,
                 const AxisPositions& lowerAt, const std::vector<std::uint32_t>& upperIds,
                 const AxisPositions& upperAt);

}  // namespace dfrecon
