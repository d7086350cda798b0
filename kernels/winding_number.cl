// Winding number of a slice's closed contours around every pixel centre.
//
// segments[k] = (ax, ay, bx, by): one directed contour edge in mm, relative to
// the grid origin (small magnitudes keep float32 error far below a pixel).
// Pixel (i, j) has its centre at ((i + 0.5) * pixelMm, (j + 0.5) * pixelMm).
// Sum over edges of Sunday's crossing rule: +1 for an upward edge with the
// point on its left, -1 for a downward edge with the point on its right.
// Cost: O(width * height * segmentCount); no culling.
__kernel void winding_number_grid(__global const float4* segments, const uint segmentCount,
                                  const float pixelMm, const uint width, const uint height,
                                  __global int* winding) {
    const uint i = get_global_id(0);
    const uint j = get_global_id(1);
    if (i >= width || j >= height) return;
    const float2 p = (float2)((i + 0.5f) * pixelMm, (j + 0.5f) * pixelMm);
    int w = 0;
    for (uint k = 0; k < segmentCount; ++k) {
        const float4 s = segments[k];
        const float side = (s.z - s.x) * (p.y - s.y) - (s.w - s.y) * (p.x - s.x);
        if (s.y <= p.y) {
            if (s.w > p.y && side > 0.0f) ++w;
        } else if (s.w <= p.y && side < 0.0f) {
            --w;
        }
    }
    winding[j * width + i] = w;
}
