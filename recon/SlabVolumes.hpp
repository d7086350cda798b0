#pragma once
// How much volume each slab between two contour planes should hold, and how
// much a surface holds there. Straight lofting loses volume between planes:
// half-way, the band between two differing contours encloses less than
// their mean area (and a convex bulge lies outside every chord), so a
// reconstruction comes out smaller than the anatomy it was cut from.
// Measured against known truth (dfrecon-bench truth), the integral of a C1
// interpolation in z of the planes' section areas is close to the true
// volume between the planes; smooth mode bulges each slab until its volume
// is that (recon/LoftSmoothing) — per nested part of a slab (SlabParts) and
// per connected component of the surface (SurfaceComponents), each to the
// integral of its own sections.
#include <cstdint>
#include <utility>
#include <vector>

#include "contours/ContourSet.hpp"
#include "geometry/TriangleSoup.hpp"

namespace dfrecon {

/// The contour planes' sections: net area (holes subtract) and perimeter.
struct PlaneSections {
    std::vector<double> zMm, areaMm2, perimeterMm;
};

/// Of `slices` (increasing z, each with contours). O(points).
PlaneSections sectionsOf(const std::vector<Slice>& slices);

/// Each slab's target volume: the integral of the cubic Hermite
/// interpolation of the section areas in z, h/2 (A0 + A1) + h²/12 (m0 − m1),
/// with the tangents of recon/SliceInterpolant inside the stack
/// (recon/HermiteTangents: the slope of the parabola through a plane and
/// its neighbours, 0 beside a straight stretch) and the end slab's secant
/// at its ends. One value per slab. O(slices).
std::vector<double> slabVolumeTargets(const PlaneSections& planes);

/// The cubic Hermite interpolation of the planes' net areas at z (the
/// tangents of slabVolumeTargets) over the straight one, within
/// [kMinAreaRatio, kMaxAreaRatio]; 1 outside the stack, with fewer than two
/// planes, or where either is not positive. What the sections' trend says
/// about the area between two planes relative to the straight mean: below 1
/// at a waist, above 1 where a small section meets a large one that keeps
/// growing. O(log planes).
inline constexpr double kMinAreaRatio = 0.5, kMaxAreaRatio = 2;
double hermiteAreaRatio(const PlaneSections& planes, double zMm);

/// The volume of a closed, outward-oriented surface between each pair of
/// neighbouring planes, where triangle t lies in slab pieceOf[t] − 1
/// (pieces 0 and slices are the end caps and are skipped) and every slab
/// piece lies between its planes, meeting them only in their contours: by
/// the divergence theorem with the field (0, 0, z − z_s), the integral of
/// (z − z_s)·n_z over the slab's triangles plus h·A(z_s+1) for the section
/// at the top plane. O(T).
std::vector<double> slabVolumes(const TriangleSoup& surface,
                                const std::vector<std::uint32_t>& pieceOf,
                                const PlaneSections& planes);

/// The connected parts of each slab: its triangles joined where they share
/// a vertex (two blobs side by side, a cavity's wall inside the outer wall,
/// are parts of their own). A nested part gets its own volume target and
/// bulge: one bulge for the whole slab moved a cavity's wall into the
/// cavity where the cavity widens.
struct SlabParts {
    static constexpr std::uint32_t kNone = UINT32_MAX;
    std::vector<std::uint32_t> partOfVertex;    // kNone: on a plane, or in a cap
    std::vector<std::uint32_t> partOfTriangle;  // kNone: in a cap
    std::vector<std::size_t> slabOf;            // per part
    /// Per part: the sections it closes on its slab's lower and upper
    /// planes (net area, perimeter), from its boundary edges there.
    std::vector<double> areaBelowMm2, areaAboveMm2, perimeterBelowMm, perimeterAboveMm;
    /// Parts of neighbouring slabs that share contour points on the plane
    /// between them: (the part below, the part above), each pair once.
    std::vector<std::pair<std::uint32_t, std::uint32_t>> meetings;
    /// Per part: whether it lies inside another part of its slab (a
    /// cavity's wall, whose sections are holes, or an island in a cavity).
    /// Such a part is bent by its own profile: the solid's bulge around it
    /// would move a cavity's wall the wrong way.
    std::vector<bool> nested;

    std::size_t count() const { return slabOf.size(); }
};

/// The parts of `surface`'s slabs (triangle t in slab pieceOf[t] − 1, as
/// slabVolumes reads it). Points whose z lies within 1e-4 mm of a plane are
/// on it. O(T α(T)), plus O(n · e) to find the n parts inside the cavities
/// (e: the cavities' edges on the planes).
SlabParts slabPartsOf(const TriangleSoup& surface, const std::vector<std::uint32_t>& pieceOf,
                      const PlaneSections& planes);

/// Each part's volume target: the integral of the cubic Hermite
/// interpolation of its own section areas, as slabVolumeTargets does for
/// whole planes, the tangent at a plane from the part's secant and that of
/// the parts it meets across the plane (its own secant where it meets
/// none: a stack's or a part's end). A cavity's wall is bent by the
/// cavity's own profile, not the solid's around it. O(parts + meetings).
std::vector<double> partVolumeTargets(const SlabParts& parts, const PlaneSections& planes);

/// Each part's volume between its slab's planes, as slabVolumes measures a
/// slab's (its upper section from its own boundary edges). O(T).
std::vector<double> partVolumes(const TriangleSoup& surface, const SlabParts& parts,
                                const PlaneSections& planes);

/// The connected components of a surface (vertices joined by its
/// triangles): each vertex's (kNone for a vertex on no triangle) and their
/// count. Separate objects of one ROI (two nodes, a structure and a speck
/// beside it) bulge each by its own sections. O(T α(T)).
struct SurfaceComponents {
    static constexpr std::uint32_t kNone = UINT32_MAX;
    std::vector<std::uint32_t> ofVertex;
    std::size_t count = 0;
};
SurfaceComponents surfaceComponents(const TriangleSoup& surface);

/// Each component's sections on the planes `planeZMm`: the net area and
/// perimeter of its loops there (`planeLoops`, per plane the contours as
/// vertex ids of `surface`, the solid on their left, as
/// geometry/StackedMeshCheck's PieceStack holds them). One PlaneSections per
/// component. O(loop points).
std::vector<PlaneSections> componentSections(
    const TriangleSoup& surface, const std::vector<double>& planeZMm,
    const std::vector<std::vector<std::vector<std::uint32_t>>>& planeLoops,
    const SurfaceComponents& components);

/// slabVolumeTargets of one component's sections (componentSections) over
/// the planes that hold them, so the component's first and last plane are
/// the ends of its stack (the end slab's secant as tangent, as for a whole
/// ROI): one that begins mid-stack does not bulge toward the empty plane
/// below, which its cap closes already. 0 for the other slabs. O(slices).
std::vector<double> ownVolumeTargets(const PlaneSections& sections);

/// Per slab s and component c (index s · components.count + c), the volume
/// the component's triangles in the slab's piece bound with its section on
/// the slab's upper plane, as slabVolumes measures a whole slab (for one
/// component, slabVolumes itself). O(T).
std::vector<double> componentSlabVolumes(const TriangleSoup& surface,
                                         const std::vector<std::uint32_t>& pieceOf,
                                         const std::vector<PlaneSections>& sections,
                                         const SurfaceComponents& components);

}  // namespace dfrecon
