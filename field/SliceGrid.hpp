#pragma once
// The pixel grid on which a slice's fields are sampled: square pixels of
// pixelMm, pixel (i, j) centred at origin + ((i + ½)·pixelMm, (j + ½)·pixelMm).
#include <cstddef>

#include <vector>

#include "io/ContourSet.hpp"

namespace dfrecon {

struct SliceGrid {
    Point2 originMm;  // lower-left corner of pixel (0, 0)
    double pixelMm = 1;
    int width = 0, height = 0;

    std::size_t pixelCount() const { return std::size_t(width) * std::size_t(height); }
    Point2 pixelCentre(int i, int j) const {
        return {originMm.x + (i + 0.5) * pixelMm, originMm.y + (j + 0.5) * pixelMm};
    }
};

/// The grid with pixels of `pixelMm` covering `box` plus `marginPx` pixels on
/// every side.
SliceGrid gridAround(const Box2& box, double pixelMm, int marginPx);

/// The part of `grid` that covers `box` plus `marginPx` pixels on every
/// side, on the same lattice (its pixel centres are `grid`'s) and clipped to
/// it; an empty box gives an empty window. Fields sampled on a window equal
/// the whole grid's at the same points, so work on one part of an ROI costs
/// pixels of that part only. O(1).
SliceGrid windowOf(const SliceGrid& grid, const Box2& box, int marginPx);

/// Default grid side in pixels and margin (docs/fields.md).
inline constexpr int kDefaultGridPixels = 512;
inline constexpr int kGridMarginPx = 8;

/// The one grid shared by all slices of an ROI: covers the union of its
/// contours' bounding boxes plus kGridMarginPx pixels on each side. With
/// pixelMm <= 0 the pixel size is chosen so the longer side is about
/// `gridPixels`. Throws std::invalid_argument for an ROI without
/// contours or a grid over 16384 pixels a side.
SliceGrid gridForSlices(const std::vector<Slice>& slices, double pixelMm = 0,
                        int gridPixels = kDefaultGridPixels);

}  // namespace dfrecon
