#pragma once
// Medial axes between two neighbouring slices (reconstruction paper §2.1.3,
// §3.3): the border between the negative and non-negative regions of
// S = D_lower + D_upper, traced into closed chains of pixels. Each pixel
// carries the nearest-primitive ids of both slices, the correspondences the
// triangulation walks along.
#include <cstdint>
#include <vector>

#include "field/SliceFields.hpp"

namespace dfrecon {

/// S = D_lower + D_upper on the fields' grid and its negative mask (1 where
/// S < 0), row-major.
struct SliceSum {
    std::vector<float> sumMm;
    std::vector<std::uint8_t> negative;
};

/// The sum of slices `lower` and `upper` of `fields`. O(pixels), on the
/// host: one float addition per pixel is memory-bound, and a device launch
/// with its transfers cost several times the arithmetic (the reconstruction
/// calls this thousands of times on small windows).
SliceSum sumSlices(const SliceFields& fields, std::size_t lower, std::size_t upper);

struct MedialPixel {
    int i = 0, j = 0;           // grid pixel
    float sumMm = 0;            // S at the pixel (< 0: border pixels are on the negative side)
    std::uint32_t lowerId = 0;  // nearest primitive on the lower slice (PrimitiveId)
    std::uint32_t upperId = 0;  // ... and on the upper slice
};

/// One closed medial axis: consecutive pixels (and the last and first) are
/// 8-neighbours. Outer borders of negative regions run counter-clockwise
/// in grid coordinates (+x right, +y up), borders of holes clockwise.
struct MedialAxis {
    std::vector<MedialPixel> pixels;
    bool bordersHole = false;  // border of a non-negative hole in a negative region
    int parent = -1;           // for holes: the axis of the region it lies in
};

/// Traces every border of the negative region of `sum` (a pixel of the
/// region with a 4-neighbour outside it, or on the grid edge) with OpenCV's
/// findContours, and attaches both slices' ids. O(pixels).
std::vector<MedialAxis> traceMedialAxes(const SliceFields& fields, std::size_t lower,
                                        std::size_t upper, const SliceSum& sum);

}  // namespace dfrecon
