#pragma once
// How much two solids overlap, from their surfaces: the volume of their
// intersection by the flux through each surface's part inside the other
// (compare/IntersectionFlux: exact predicates, crossing points in double
// with a stated bound far below any Dice digit that matters), with CGAL's
// corefinement (exact constructions) kept as the independent route. Dice and
// Jaccard carry no voxelisation error (what plastimatch and Slicer's Segment
// Comparison compute on label maps is off by the partial voxels along both
// surfaces).
#include <optional>

#include "geometry/MeshCheck.hpp"
#include "geometry/TriangleSoup.hpp"

namespace dfrecon {

struct Overlap {
    double volumeAMm3 = 0, volumeBMm3 = 0;
    double intersectionMm3 = 0;
    /// How intersectionMm3 was found: "surface flux" (A and B in general
    /// position), or "surface flux, B shifted" where the surfaces coincide in
    /// part (shared faces, edges or vertices, where no general position
    /// exists): then B is moved by shiftMm along a fixed generic direction,
    /// which changes the intersection by at most area(B)·shift (the volume B
    /// sweeps moving that far). "exact" and "exact, B shifted" name the same
    /// two cases decided by corefinement, the fallback where the flux finds
    /// no general position even with B moved. Either way |intersectionMm3 −
    /// the true intersection| ≤ intersectionBoundMm3: the flux's rounding
    /// bound plus area(B)·shift.
    const char* method = "exact";
    double shiftMm = 0, intersectionBoundMm3 = 0;
    double unionMm3() const { return volumeAMm3 + volumeBMm3 - intersectionMm3; }
    /// 2|A ∩ B| / (|A| + |B|); 1 for two empty solids.
    double dice() const;
    /// |A ∩ B| / |A ∪ B|; 1 for two empty solids.
    double jaccard() const;
};

/// The unit direction overlapOf moves B along where the surfaces coincide
/// in part: along no face, edge or axis of anatomy.
Vec3 overlapShiftDirection();

/// The volume of the intersection of the solids bounded by `a` and by `b`
/// moved by `shiftOfB`, exactly (corefinement), or none where corefinement
/// cannot build it (the surfaces coincide in part). Both must be valid
/// closed solids (not checked here). The building block of overlapOf.
std::optional<double> intersectionVolume(const TriangleSoup& a, const TriangleSoup& b,
                                         const Vec3& shiftOfB);

/// The overlap of the solids bounded by `a` and `b`, which must be valid
/// closed solids (dfrecon check): throws std::invalid_argument otherwise.
/// Any two valid solids get an answer — touching, nested, identical,
/// disjoint: by the flux where the surfaces are in general position (one
/// surface given twice is the solid itself), else with B moved (method says
/// which; surfaces sharing many points — at least 16 and 1 % of the
/// smaller's — are moved at once). A's and B's volumes are the mesh check's.
/// Work: O((n + k) log n) for n triangles and k pairs of triangles whose
/// boxes overlap, in double with exact predicates, up to four times over;
/// corefinement's exact arithmetic only where all of those fail.
Overlap overlapOf(const TriangleSoup& a, const TriangleSoup& b);

/// overlapOf by the flux alone (with B moved where the surfaces coincide in
/// part), none where no shift gives it general position: for callers that
/// would rather report "not measured" than wait for corefinement, whose
/// exact constructions take minutes on surfaces of 10⁵ triangles. Both
/// must have been checked (checkA = checkMesh(a), ...). O(overlapOf's flux).
std::optional<Overlap> overlapByFlux(const TriangleSoup& a, const TriangleSoup& b,
                                     const MeshCheckReport& checkA, const MeshCheckReport& checkB);

/// The same where the caller has checked both solids already (checkA =
/// checkMesh(a), checkB = checkMesh(b)): they are not checked again.
Overlap overlapOf(const TriangleSoup& a, const TriangleSoup& b, const MeshCheckReport& checkA,
                  const MeshCheckReport& checkB);

}  // namespace dfrecon
