#include "geometry/SurfaceMeasures.hpp"

#include <vector>

namespace dfrecon {

SurfaceMeasures measureSurface(const TriangleSoup& soup) {
    SurfaceMeasures m;
    Vec3 moment;  // Σ volume · centroid of each tetrahedron (origin, p0, p1, p2)
    for (const auto& t : soup.triangles) {
        const Vec3 p0 = soup.points[t[0]], p1 = soup.points[t[1]], p2 = soup.points[t[2]];
        m.areaMm2 += 0.5 * length(cross(p1 - p0, p2 - p0));
        const double volume = dot(p0, cross(p1, p2)) / 6;
        m.volumeMm3 += volume;
        moment = moment + (volume / 4) * (p0 + p1 + p2);
    }
    if (m.volumeMm3 != 0) m.centroidMm = (1 / m.volumeMm3) * moment;
    return m;
}

double volumeBelowPlane(const TriangleSoup& soup, double zMm) {
    double volume = 0;
    std::vector<Vec3> below;
    for (const auto& t : soup.triangles) {
        below.clear();
        for (int k = 0; k < 3; ++k) {
            const Vec3 p = soup.points[t[std::size_t(k)]];
            const Vec3 q = soup.points[t[std::size_t((k + 1) % 3)]];
            if (p.z <= zMm) below.push_back(p);
            if ((p.z < zMm) != (q.z < zMm) && p.z != q.z)
                below.push_back(p + ((zMm - p.z) / (q.z - p.z)) * (q - p));
        }
        // Over a flat piece, ∫ (z − zMm) n_z dA is its z-facing area times
        // its mean height above the plane (negative below it).
        for (std::size_t k = 1; k + 1 < below.size(); ++k) {
            const Vec3 a = below[0], b = below[k], c = below[k + 1];
            volume += 0.5 * cross(b - a, c - a).z * ((a.z + b.z + c.z) / 3 - zMm);
        }
    }
    return volume;
}

}  // namespace dfrecon
