#include "field/DistanceField3D.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "cl/DeviceBuffer.hpp"

namespace dfrecon {

namespace {

// Stands in for +inf (slices without contours) so the sign-change rule's
// ratios stay finite; far beyond any grid.
constexpr float kFarMm = 1e7f;

std::vector<float> gapsOf(const DistanceField3D& field) {
    std::vector<float> gaps;
    for (std::size_t k = 0; k + 1 < field.layerCount(); ++k)
        gaps.push_back(float(field.zMm[k + 1] - field.zMm[k]));
    return gaps;
}

// The same rule as relax() in kernels/distance_3d.cl, in the same float
// arithmetic.
void relax(float& from, float& next, float gap) {
    const float a = from, b = next;
    if ((a < 0.0f) == (b < 0.0f)) {
        const float m = std::fabs(a) + gap;
        if (m < std::fabs(b)) next = b < 0.0f ? -m : m;
        return;
    }
    const float positive = a < 0.0f ? b : a, negative = a < 0.0f ? -a : -b;
    const float sum = positive + negative;
    const float p = std::fmin(positive, positive / sum * gap);
    const float n = std::fmin(negative, negative / sum * gap);
    if (a < 0.0f) {
        from = -n;
        next = p;
    } else {
        from = p;
        next = -n;
    }
}

}  // namespace

DistanceField3D layersFromSlices(const SliceFields& fields, double endSpacingMm) {
    const std::size_t slices = fields.sliceCount(), pixels = fields.grid.pixelCount();
    if (slices == 0) throw std::invalid_argument("3D field: no slices");
    DistanceField3D field;
    field.grid = fields.grid;
    const double first = slices > 1 ? fields.zMm[1] - fields.zMm[0] : endSpacingMm;
    const double last = slices > 1 ? fields.zMm[slices - 1] - fields.zMm[slices - 2] : endSpacingMm;
    field.zMm = {fields.zMm.front() - first, fields.zMm.front() - 0.5 * first};
    field.zMm.insert(field.zMm.end(), fields.zMm.begin(), fields.zMm.end());
    field.zMm.push_back(fields.zMm.back() + 0.5 * last);
    field.zMm.push_back(fields.zMm.back() + last);
    field.distanceMm.resize((slices + 4) * pixels);
    for (std::size_t p = 0; p < pixels; ++p) {
        for (std::size_t s = 0; s < slices; ++s) {
            const float d = fields.distanceMm[s * pixels + p];
            field.distanceMm[(s + 2) * pixels + p] = std::isfinite(d) ? d : kFarMm;
        }
        // The cap plane: zero over the end region, the in-slice distance to
        // it outside (exact there: the solid lies below the plane). Half a
        // spacing further every point is that plus the height, in the
        // field's metric.
        auto caps = [&](std::size_t endLayer, std::size_t capLayer, std::size_t outerLayer,
                        double halfGap) {
            const float d = std::max(field.distanceMm[endLayer * pixels + p], 0.0f);
            field.distanceMm[capLayer * pixels + p] = d;
            field.distanceMm[outerLayer * pixels + p] = std::min(kFarMm, d + float(halfGap));
        };
        caps(2, 1, 0, 0.5 * first);
        caps(slices + 1, slices + 2, slices + 3, 0.5 * last);
    }
    return field;
}

void propagateAlongZ(ocl::Runtime& runtime, DistanceField3D& field) {
    if (field.layerCount() < 2) return;
    const std::size_t pixels = field.grid.pixelCount();
    ocl::DeviceBuffer<cl_float> layers(runtime, field.distanceMm);
    ocl::DeviceBuffer<cl_float> gaps(runtime, gapsOf(field));
    cl::Kernel kernel = runtime.kernel({"distance_3d.cl"}, "propagate_z");
    try {
        kernel.setArg(0, layers.get());
        kernel.setArg(1, gaps.get());
        kernel.setArg(2, cl_uint(field.layerCount()));
        kernel.setArg(3, cl_uint(pixels));
        runtime.queue().enqueueNDRangeKernel(kernel, cl::NullRange,
                                             cl::NDRange(ocl::roundUp(pixels, ocl::kGroupSize1D)),
                                             cl::NDRange(ocl::kGroupSize1D));
    } catch (const cl::Error& e) {
        throw ocl::toClError(e, "distance_3d.cl");
    }
    field.distanceMm = layers.download(runtime);
}

void propagateAlongZReference(DistanceField3D& field) {
    const std::size_t pixels = field.grid.pixelCount(), layers = field.layerCount();
    const std::vector<float> gaps = gapsOf(field);
    float* d = field.distanceMm.data();
    for (std::size_t p = 0; p < pixels; ++p) {
        for (std::size_t k = 0; k + 1 < layers; ++k)
            relax(d[k * pixels + p], d[(k + 1) * pixels + p], gaps[k]);
        for (std::size_t k = layers - 1; k > 0; --k)
            relax(d[k * pixels + p], d[(k - 1) * pixels + p], gaps[k - 1]);
    }
}

double sampleField(const DistanceField3D& field, double xMm, double yMm, double zMm) {
    const SliceGrid& g = field.grid;
    // Continuous pixel coordinates of the pixel centres.
    const double u = std::clamp((xMm - g.originMm.x) / g.pixelMm - 0.5, 0.0, double(g.width - 1));
    const double v = std::clamp((yMm - g.originMm.y) / g.pixelMm - 0.5, 0.0, double(g.height - 1));
    // Grids are at least 2·margin + 1 pixels a side, so a 2×2 cell always fits.
    const int i0 = std::min(int(u), g.width - 2), j0 = std::min(int(v), g.height - 2);
    const int i1 = i0 + 1, j1 = j0 + 1;
    const double fu = u - i0, fv = v - j0;
    auto bilinear = [&](std::size_t layer) {
        auto at = [&](int i, int j) { return double(field.distanceMm[field.index(layer, i, j)]); };
        return (1 - fv) * ((1 - fu) * at(i0, j0) + fu * at(i1, j0)) +
               fv * ((1 - fu) * at(i0, j1) + fu * at(i1, j1));
    };
    const std::vector<double>& z = field.zMm;
    if (zMm <= z.front()) return bilinear(0);
    if (zMm >= z.back()) return bilinear(z.size() - 1);
    const std::size_t k = std::size_t(std::upper_bound(z.begin(), z.end(), zMm) - z.begin()) - 1;
    const double t = (zMm - z[k]) / (z[k + 1] - z[k]);
    return (1 - t) * bilinear(k) + t * bilinear(k + 1);
}

}  // namespace dfrecon
