#pragma once
// How much two solids overlap, exactly: the volume of their intersection by
// CGAL's corefinement with exact constructions, so Dice and Jaccard carry no
// voxelisation error (what plastimatch and Slicer's Segment Comparison
// compute on label maps is off by the partial voxels along both surfaces).
#include <optional>

#include "geometry/MeshCheck.hpp"
#include "geometry/TriangleSoup.hpp"

namespace dfrecon {

struct Overlap {
    double volumeAMm3 = 0, volumeBMm3 = 0;
    double intersectionMm3 = 0;
    /// How intersectionMm3 was found: "exact" (corefinement of A and B), or
    /// "exact, B shifted" where the surfaces coincide in part (shared faces,
    /// edges or vertices, which corefinement cannot build a solid of): then
    /// B is moved by shiftMm along a fixed generic direction and the result is
    /// within intersectionBoundMm3 = area(B)·shift of the true one (the
    /// volume B sweeps moving that far).
    const char* method = "exact";
    double shiftMm = 0, intersectionBoundMm3 = 0;
    double unionMm3() const { return volumeAMm3 + volumeBMm3 - intersectionMm3; }
    /// 2|A ∩ B| / (|A| + |B|); 1 for two empty solids.
    double dice() const;
    /// |A ∩ B| / |A ∪ B|; 1 for two empty solids.
    double jaccard() const;
};

/// The volume of the intersection of the solids bounded by `a` and by `b`
/// moved by `shiftOfB`, exactly (corefinement), or none where corefinement
/// cannot build it (the surfaces coincide in part). Both must be valid
/// closed solids (not checked here). The building block of overlapOf.
std::optional<double> intersectionVolume(const TriangleSoup& a, const TriangleSoup& b,
                                         const Vec3& shiftOfB);

/// The overlap of the solids bounded by `a` and `b`, which must be valid
/// closed solids (dfrecon check): throws std::invalid_argument otherwise.
/// Any two valid solids get an answer — touching, nested, identical,
/// disjoint: exact where the surfaces are in general position (and for
/// one surface given twice), else by the shift above (Overlap::method says
/// which); surfaces sharing many points (at least 16 and 1 % of the
/// smaller's) go to the shift at once, as corefinement of neighbours cut
/// from one label map fails only after most of its work. Exact predicates and
/// constructions; A's and B's volumes are summed in double from their
/// points (the mesh check's), the intersection's from exact points rounded
/// once. Work: O((n + k) log n) for n triangles and k intersecting
/// pairs, with exact arithmetic's constant, up to four times over.
Overlap overlapOf(const TriangleSoup& a, const TriangleSoup& b);

/// The same where the caller has checked both solids already (checkA =
/// checkMesh(a), checkB = checkMesh(b)): they are not checked again.
Overlap overlapOf(const TriangleSoup& a, const TriangleSoup& b, const MeshCheckReport& checkA,
                  const MeshCheckReport& checkB);

}  // namespace dfrecon
