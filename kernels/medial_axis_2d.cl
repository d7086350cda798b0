// Medial axes between neighbouring slices (reconstruction paper §3.3): the
// sum S = D_lower + D_upper of two slices' signed fields, and the mask of its
// negative region, whose border the host traces into closed pixel chains.
// Zero counts as positive, as in the paper.
//
// distance: the fields of all slices, slice-major; `lower` and `upper` pick
// two of them. One work-item per pixel.
__kernel void sum_and_sign(__global const float* distance, const uint lower, const uint upper,
                           const uint width, const uint height, __global float* sum,
                           __global uchar* negative) {
    const uint i = get_global_id(0), j = get_global_id(1);
    if (i >= width || j >= height) return;
    const size_t pixels = (size_t)width * height, at = (size_t)j * width + i;
    const float s = distance[lower * pixels + at] + distance[upper * pixels + at];
    sum[at] = s;
    negative[at] = s < 0.0f ? 1 : 0;
}
