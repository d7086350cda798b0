#include "geometry/VolumeGrid.hpp"

#include <cmath>
#include <stdexcept>

namespace dfrecon {

double axesDeterminant(const std::array<std::array<double, 3>, 3>& c) {
    return c[0][0] * (c[1][1] * c[2][2] - c[1][2] * c[2][1]) -
           c[1][0] * (c[0][1] * c[2][2] - c[0][2] * c[2][1]) +
           c[2][0] * (c[0][1] * c[1][2] - c[0][2] * c[1][1]);
}

std::size_t VolumeGeometry::voxelCount() const {
    if (size[0] <= 0 || size[1] <= 0 || size[2] <= 0) return 0;
    return std::size_t(size[0]) * std::size_t(size[1]) * std::size_t(size[2]);
}

std::size_t VolumeGeometry::linearIndex(int i, int j, int k) const {
    return (std::size_t(k) * std::size_t(size[1]) + std::size_t(j)) * std::size_t(size[0]) +
           std::size_t(i);
}

Vec3 VolumeGeometry::worldOfIndex(double i, double j, double k) const {
    const double index[3] = {i, j, k};
    double p[3] = {originMm[0], originMm[1], originMm[2]};
    for (int a = 0; a < 3; ++a)
        for (int c = 0; c < 3; ++c) p[c] += index[a] * spacingMm[a] * direction[a][c];
    return {p[0], p[1], p[2]};
}

std::array<double, 3> VolumeGeometry::indexOfWorld(Vec3 pointMm) const {
    // Columns of the index-to-world matrix M; the index is M⁻¹·(p − origin),
    // with M⁻¹ from the cofactors (rows of M⁻¹ are cross products of
    // columns over det M).
    std::array<std::array<double, 3>, 3> m;
    for (int a = 0; a < 3; ++a)
        for (int c = 0; c < 3; ++c) m[a][c] = spacingMm[a] * direction[a][c];
    const double det = axesDeterminant(m);
    const double scale = spacingMm[0] * spacingMm[1] * spacingMm[2];
    if (!std::isfinite(det) || !(std::fabs(det) > kMinAxisDeterminant * std::fabs(scale)))
        throw std::domain_error("indexOfWorld: degenerate volume axes");
    const Vec3 c0{m[0][0], m[0][1], m[0][2]}, c1{m[1][0], m[1][1], m[1][2]},
        c2{m[2][0], m[2][1], m[2][2]};
    const Vec3 d = pointMm - Vec3{originMm[0], originMm[1], originMm[2]};
    return {dot(cross(c1, c2), d) / det, dot(cross(c2, c0), d) / det, dot(cross(c0, c1), d) / det};
}

}  // namespace dfrecon
