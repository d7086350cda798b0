#pragma once
// Geodesic Voronoi regions from a labelled arrival-time field (the paper's
// §2.2): per-face region ids, per-region areas and border lengths with the
// borders interpolated inside the triangles, region adjacency, and each
// region's topology (for the topological-disk constraint of §3.1).
//
// Where an edge joins vertices of different regions a and b, the border
// crosses it where the two fronts meet: each front is let overlap by one
// vertex (its time at the other vertex is the local update from that
// vertex's neighbours of the same region only), both times are
// interpolated linearly along the edge and the crossing is where they are
// equal. A triangle with two regions is cut by the segment joining its two
// crossings; one with three is cut into three pieces meeting at the mean of
// its three crossings. A face's region id is the region owning the largest
// piece of it.
#include <vector>

#include "segment/FastMarching.hpp"
#include "segment/MeshGraph.hpp"

namespace dfrecon {

struct VoronoiRegions {
    int regionCount = 0;
    std::vector<int> faceRegion;  // per triangle; -1 where no corner was reached
    std::vector<double> area;     // per region, mm², borders interpolated
    /// Per region, mm: its interpolated borders with other regions plus the
    /// mesh-boundary edges (or parts of them) it owns.
    std::vector<double> perimeter;
    std::vector<std::vector<int>> neighbours;  // per region, sorted
    /// Total length of the interpolated borders between regions, mm.
    double borderLength = 0;

    /// 4π·area / perimeter²: 1 for a flat disk, smaller for elongated or
    /// ragged regions (on positively curved surfaces a cap exceeds 1 a
    /// little); 0 for a region with no perimeter (a closed surface in one
    /// region).
    double compactness(int region) const;
};

/// Regions 0 .. regionCount-1 from `field` (labels outside that range count
/// as unreached). `marching` supplies the stencils and slowness the field
/// was computed with (for the one-vertex overlap). O(T + S).
VoronoiRegions geodesicVoronoi(const MeshGraph& graph, const FastMarching& marching,
                               const GeodesicField& field, int regionCount);

/// The topology of one region's faces (by faceRegion).
struct RegionTopology {
    int faces = 0;
    int eulerCharacteristic = 0;  // V − E + F of the region's faces
    int boundaryLoops = 0;        // connected components of its boundary edges
    /// A topological disk: one piece with χ = 1 and one boundary loop.
    /// (Regions touching at a single vertex count as one piece here.)
    bool isDisk() const { return faces > 0 && eulerCharacteristic == 1 && boundaryLoops == 1; }
};

/// Per region. O(T α(T)).
std::vector<RegionTopology> regionTopology(const MeshGraph& graph,
                                           const std::vector<int>& faceRegion, int regionCount);

}  // namespace dfrecon
