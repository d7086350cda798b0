#include "field/FieldVolume.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace dfrecon {

DenseDistanceVolume resampleAlongZ(const DistanceField3D& field, double zStepMm) {
    if (!(zStepMm > 0)) throw std::invalid_argument("z step must be positive");
    const std::vector<double>& z = field.zMm;
    const double range = z.back() - z.front();
    const long samples = std::lround(std::floor(range / zStepMm + 1e-9)) + 1;
    if (samples > 65536) throw std::invalid_argument("z step gives over 65536 samples");
    DenseDistanceVolume volume;
    volume.nx = field.grid.width;
    volume.ny = field.grid.height;
    volume.nz = int(samples);
    volume.originMm[0] = field.grid.originMm.x + 0.5 * field.grid.pixelMm;
    volume.originMm[1] = field.grid.originMm.y + 0.5 * field.grid.pixelMm;
    volume.originMm[2] = z.front();
    volume.voxelMm[0] = volume.voxelMm[1] = field.grid.pixelMm;
    volume.voxelMm[2] = zStepMm;
    const std::size_t pixels = field.grid.pixelCount();
    volume.valuesMm.resize(pixels * std::size_t(samples));
    std::size_t layer = 0;
    for (long k = 0; k < samples; ++k) {
        const double at = std::min(z.front() + double(k) * zStepMm, z.back());
        while (layer + 2 < z.size() && z[layer + 1] < at) ++layer;
        const double t = std::clamp((at - z[layer]) / (z[layer + 1] - z[layer]), 0.0, 1.0);
        const float* a = field.distanceMm.data() + layer * pixels;
        const float* b = a + pixels;
        float* out = volume.valuesMm.data() + std::size_t(k) * pixels;
        for (std::size_t p = 0; p < pixels; ++p) out[p] = float((1 - t) * a[p] + t * b[p]);
    }
    return volume;
}

}  // namespace dfrecon
