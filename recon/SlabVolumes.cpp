#include "recon/SlabVolumes.hpp"

#include <cmath>

namespace dfrecon {

PlaneSections sectionsOf(const std::vector<Slice>& slices) {
    PlaneSections planes;
    for (const Slice& slice : slices) {
        double area = 0, perimeter = 0;
        for (const Polygon& c : slice.contours) {
            area += signedArea(c);
            perimeter += perimeterMm(c);
        }
        planes.zMm.push_back(slice.zMm);
        planes.areaMm2.push_back(area);
        planes.perimeterMm.push_back(perimeter);
    }
    return planes;
}

std::vector<double> slabVolumeTargets(const PlaneSections& planes) {
    const std::vector<double>& z = planes.zMm;
    const std::vector<double>& a = planes.areaMm2;
    const std::size_t n = z.size();
    std::vector<double> targets;
    if (n < 2) return targets;
    auto secant = [&](std::size_t k) { return (a[k + 1] - a[k]) / (z[k + 1] - z[k]); };
    auto tangent = [&](std::size_t k) {
        if (k == 0) return secant(0);
        if (k + 1 == n) return secant(n - 2);
        const double below = z[k] - z[k - 1], above = z[k + 1] - z[k];
        return (above * secant(k - 1) + below * secant(k)) / (below + above);
    };
    for (std::size_t k = 0; k + 1 < n; ++k) {
        const double h = z[k + 1] - z[k];
        targets.push_back(0.5 * h * (a[k] + a[k + 1]) + h * h / 12 * (tangent(k) - tangent(k + 1)));
    }
    return targets;
}

std::vector<double> slabVolumes(const TriangleSoup& surface,
                                const std::vector<std::uint32_t>& pieceOf,
                                const PlaneSections& planes) {
    const std::size_t slabs = planes.zMm.size() > 1 ? planes.zMm.size() - 1 : 0;
    std::vector<double> volumes(slabs, 0);
    for (std::size_t s = 0; s < slabs; ++s)
        volumes[s] = (planes.zMm[s + 1] - planes.zMm[s]) * planes.areaMm2[s + 1];
    for (std::size_t t = 0; t < surface.triangles.size(); ++t) {
        if (pieceOf[t] == 0 || pieceOf[t] > slabs) continue;
        const std::size_t s = pieceOf[t] - 1;
        const auto& tri = surface.triangles[t];
        const Vec3 a = surface.points[tri[0]], b = surface.points[tri[1]],
                   c = surface.points[tri[2]];
        // ∫ (z − z_s) n_z dA over a flat triangle: its z-facing area times
        // its mean height above the slab's floor.
        const double areaZ = 0.5 * cross(b - a, c - a).z;
        volumes[s] += areaZ * ((a.z + b.z + c.z) / 3 - planes.zMm[s]);
    }
    return volumes;
}

}  // namespace dfrecon
