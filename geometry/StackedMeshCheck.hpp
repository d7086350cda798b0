#pragma once
// The mesh check for a surface built in pieces stacked between parallel
// planes (a reconstruction: a cap, the slabs between neighbouring slices, a
// cap). Pieces of different slabs can only meet in the planes between them,
// and where a plane holds nothing of the surface but disjoint simple loops of
// vertices, which the pieces on both sides share, they do not meet at all.
// That is proved in O(T) plus a 2D check of each plane's loops, so the
// self-intersection search runs piece by piece: no pair across a plane is
// tested, no hierarchy spans the whole surface (the peak memory of a whole
// check), and pieces already searched at the same coordinates are skipped.
#include <cstdint>
#include <vector>

#include "geometry/MeshCheck.hpp"
#include "geometry/TriangleSoup.hpp"

namespace dfrecon {

/// How a surface's pieces are stacked. Piece p lies between plane p - 1 and
/// plane p: piece 0 below the first plane, piece planeZMm.size() above the
/// last.
struct PieceStack {
    /// The planes' heights as the soup holds them (z of their loops'
    /// vertices), strictly ascending.
    std::vector<double> planeZMm;
    /// Per plane, its loops: closed polylines of vertex ids (the slices'
    /// contours), the one place where pieces above and below may touch it.
    std::vector<std::vector<std::vector<std::uint32_t>>> planeLoops;
    /// Per piece (may be shorter: missing means false), whether its own
    /// pairs were already searched, clean, at the soup's present coordinates
    /// (as checkMesh judges pairs), so need not be searched again.
    std::vector<bool> searched;
    /// Per triangle (or empty), pairs within the other pieces known clean
    /// (geometry/MeshCheck CleanGroups): not tested again.
    CleanGroups cleanGroup;
    /// planeLoopsApart was found true at the loops' present coordinates
    /// (they do not move while a surface is checked again and again): not
    /// tested again.
    bool loopsKnownApart = false;
};

/// Are each plane's loops of `stack`, at the soup's coordinates, simple and
/// pairwise apart (no shared point at all)? The one part of
/// stackSeparatesPieces that does not depend on the pieces. O(n log n) per
/// plane for its n loop points.
bool planeLoopsApart(const TriangleSoup& soup, const PieceStack& stack);

/// Does the stack keep the pieces of `soup` (piece of triangle t:
/// pieceOf[t]) apart, except where they share vertices and edges in the
/// planes' loops? True when every piece's vertices lie between its planes
/// (inclusive), the planes ascend, every triangle meets a plane only in a
/// loop vertex or a loop edge, and each plane's loops are simple and
/// pairwise disjoint. Then no two triangles of different pieces collide as
/// checkMesh judges pairs (one exception: orientation tests within
/// checkMesh's tolerance of 1e-10 relative may call two triangles that are
/// apart "touching"; this says they are apart, which they are). O(T + V)
/// plus O(n) per plane for its n loop points.
bool stackSeparatesPieces(const TriangleSoup& soup, const std::vector<std::uint32_t>& pieceOf,
                          const PieceStack& stack);

/// checkMesh for a stacked surface: when stackSeparatesPieces, the pairs
/// are searched within each piece not yet searched (pieces on the free
/// cores at once), except pairs the stack's clean groups vouch for,
/// otherwise over the whole surface. The report is
/// checkMesh's (the intersecting pairs the same set unless the count is
/// capped, where it is a different first kMaxCountedIntersections).
/// O(T log T) for the topology plus O(S log S + overlapping pairs) for the
/// S triangles of the pieces searched; memory O(T) plus the largest
/// piece's hierarchy.
MeshCheckReport checkStackedMesh(const TriangleSoup& soup,
                                 const std::vector<std::uint32_t>& pieceOf,
                                 const PieceStack& stack);

}  // namespace dfrecon
