#pragma once
// Pictures of sampled 2D fields for people: PNG files drawn with OpenCV, with
// the contours drawn on top at sub-pixel precision. Image row 0 is the top,
// so the grid's +y points up as in a plot.
#include <cstdint>
#include <string>
#include <vector>

#include "geometry/Polygon.hpp"

namespace dfrecon {

/// Where a W×H pixel grid lies: pixel (i, j) centred at
/// originMm + ((i + ½)·pixelMm, (j + ½)·pixelMm).
struct ImageFrame {
    Point2 originMm;
    double pixelMm = 1;
    int width = 0, height = 0;
};

/// A grid pixel (i, j) to highlight.
struct PixelMark {
    int i = 0, j = 0;
};

/// A signed distance field (row-major, mm, negative inside) as a colour
/// picture (io/images/Colours' diverging scheme: blue inside, red outside,
/// brighter near zero, scaled to the largest |d|), thin iso-lines
/// every `isoStepMm`, `marked` pixels in yellow, contours in white. Written
/// atomically.
void writeSignedFieldPng(const std::string& path, const float* distanceMm, const ImageFrame& frame,
                         const std::vector<Polygon>& contours, double isoStepMm,
                         const std::vector<PixelMark>& marked = {});

/// Integer labels (row-major; 0xffffffff = none, black) in io/images/Colours'
/// categorical colours, neighbouring labels spread apart, and the contours
/// in white.
void writeLabelPng(const std::string& path, const std::uint32_t* labels, const ImageFrame& frame,
                   const std::vector<Polygon>& contours);

}  // namespace dfrecon
