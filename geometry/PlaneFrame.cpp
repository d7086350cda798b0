#include "geometry/PlaneFrame.hpp"

#include <cmath>

namespace dfrecon {

namespace {
const Vec3 kAxes[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
}

const char* PlaneFrame::orientationName() const {
    if (n == kAxes[2] || n == -1.0 * kAxes[2]) return "axial";
    if (n == kAxes[0] || n == -1.0 * kAxes[0]) return "sagittal";
    if (n == kAxes[1] || n == -1.0 * kAxes[1]) return "coronal";
    return "oblique";
}

PlaneFrame frameWithNormal(Vec3 normal) {
    const Vec3 n = (1.0 / length(normal)) * normal;
    for (int axis = 0; axis < 3; ++axis)
        if (std::abs(n[axis]) == 1.0) {
            const double s = n[axis];
            return {kAxes[(axis + 1) % 3], s * kAxes[(axis + 2) % 3], s * kAxes[axis]};
        }
    int least = 0;
    for (int axis = 1; axis < 3; ++axis)
        if (std::abs(n[axis]) < std::abs(n[least])) least = axis;
    Vec3 u = kAxes[least] - dot(kAxes[least], n) * n;
    u = (1.0 / length(u)) * u;
    return {u, cross(n, u), n};
}

PlaneFrame canonicalFrame(const PlaneFrame& frame) {
    for (int axis = 0; axis < 3; ++axis)
        if (std::abs(std::abs(frame.n[axis]) - 1) < 1e-9) return frameWithNormal(kAxes[axis]);
    return frame;
}

}  // namespace dfrecon
