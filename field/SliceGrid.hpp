#pragma once
// The pixel grid on which a slice's fields are sampled: square pixels of
// pixelMm, pixel (i, j) centred at origin + ((i + ½)·pixelMm, (j + ½)·pixelMm).
#include <cstddef>
#include <cstdint>

#include <vector>

#include "contours/ContourSet.hpp"

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

/// Most pixels of all slices of one ROI together, whose fields are held at
/// once (a distance and a nearest id, 8 bytes a pixel: 1 GiB): 2048 planes
/// at 256 pixels a side, 512 at 512.
inline constexpr std::uint64_t kMaxRoiFieldPixels = std::uint64_t(1) << 27;

/// The one grid shared by all slices of an ROI: covers the union of its
/// contours' bounding boxes plus kGridMarginPx pixels on each side. With
/// pixelMm <= 0 the pixel size is chosen so the longer side is about
/// `gridPixels`, or coarser where the slices would then take more than
/// kMaxRoiFieldPixels together (10 000 planes of a tiny contour). Throws
/// std::invalid_argument for an ROI without contours, or a pixelMm > 0 that
/// gives a grid over 16384 pixels a side or over kMaxRoiFieldPixels in
/// all (the message says the smallest pixel that fits).
SliceGrid gridForSlices(const std::vector<Slice>& slices, double pixelMm = 0,
                        int gridPixels = kDefaultGridPixels);

}  // namespace dfrecon
