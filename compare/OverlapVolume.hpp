#pragma once
// How much two solids overlap, exactly: the volume of their intersection by
// CGAL's corefinement with exact constructions, so Dice and Jaccard carry no
// voxelisation error (what plastimatch and Slicer's Segment Comparison
// compute on label maps is off by the partial voxels along both surfaces).
#include "geometry/TriangleSoup.hpp"

namespace dfrecon {

struct Overlap {
    double volumeAMm3 = 0, volumeBMm3 = 0;
    double intersectionMm3 = 0;
    double unionMm3() const { return volumeAMm3 + volumeBMm3 - intersectionMm3; }
    /// 2|A ∩ B| / (|A| + |B|); 1 for two empty solids.
    double dice() const;
    /// |A ∩ B| / |A ∪ B|; 1 for two empty solids.
    double jaccard() const;
};

/// The overlap of the solids bounded by `a` and `b`, which must be valid
/// closed solids (dfrecon check): throws std::invalid_argument otherwise.
/// Exact predicates and constructions; the volumes are summed in double
/// from exact points rounded once. Work: O((n + k) log n) for n triangles
/// and k intersecting pairs, with exact arithmetic's constant.
Overlap overlapOf(const TriangleSoup& a, const TriangleSoup& b);

}  // namespace dfrecon
