// The reconstruction paper's 3D distance field (§6.1, Figs. 9–10): the
// slices' 2D signed fields propagated along z, once upwards and once
// downwards, with the distance D3D = in-slice distance + |Δz|. Where the sign
// changes between two layers, both values are rescaled so the interpolated
// zero stays where the 2D fields put it: a positive a and a negative -b
// become min(a, a/(a+b)·gap) and -min(b, b/(a+b)·gap).
//
// layers: layer-major fields (layer k, pixel p at k·pixels + p), updated in
// place; gapsMm[k]: z distance from layer k to k+1. One work-item per pixel
// column. The C++ reference is field/DistanceField3D.cpp.

// Relaxes `next` from `from` across `gap` (both values may change when the
// sign does).
inline void relax(__global float* from, __global float* next, const float gap) {
    const float a = *from, b = *next;
    if ((a < 0.0f) == (b < 0.0f)) {
        const float m = fabs(a) + gap;
        if (m < fabs(b)) *next = b < 0.0f ? -m : m;
        return;
    }
    const float positive = a < 0.0f ? b : a, negative = a < 0.0f ? -a : -b;
    const float sum = positive + negative;
    const float p = fmin(positive, positive / sum * gap);
    const float n = fmin(negative, negative / sum * gap);
    if (a < 0.0f) {
        *from = -n;
        *next = p;
    } else {
        *from = p;
        *next = -n;
    }
}

__kernel void propagate_z(__global float* layers, __global const float* gapsMm,
                          const uint layerCount, const uint pixels) {
    const size_t p = get_global_id(0);
    if (p >= pixels) return;
    for (uint k = 0; k + 1 < layerCount; ++k)
        relax(layers + (size_t)k * pixels + p, layers + (size_t)(k + 1) * pixels + p, gapsMm[k]);
    for (uint k = layerCount - 1; k > 0; --k)
        relax(layers + (size_t)k * pixels + p, layers + (size_t)(k - 1) * pixels + p,
              gapsMm[k - 1]);
}
