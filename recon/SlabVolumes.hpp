#pragma once
// How much volume each slab between two contour planes should hold, and how
// much a surface holds there. Straight lofting loses volume between planes:
// half-way, the band between two differing contours encloses less than
// their mean area (and a convex bulge lies outside every chord), so a
// reconstruction comes out smaller than the anatomy it was cut from.
// Measured against known truth (dfrecon-bench truth), the integral of a C1
// interpolation in z of the planes' section areas is close to the true
// volume between the planes; smooth mode bulges each slab until its volume
// is that (recon/LoftSmoothing).
#include <cstdint>
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
/// with the tangents of recon/SliceInterpolant (the slope of the parabola
/// through a plane and its neighbours; the end slab's secant at the ends of
/// the stack). One value per slab. O(slices).
std::vector<double> slabVolumeTargets(const PlaneSections& planes);

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

}  // namespace dfrecon
