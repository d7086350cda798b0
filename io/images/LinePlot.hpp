#pragma once
// Line plots for people, as PNG files through OpenCV: a few curves over
// one x axis (histograms of distances), with axes, ticks at round values,
// labels and a legend. Written atomically.
#include <string>
#include <vector>

#include "contours/Rgb.hpp"

namespace dfrecon {

struct PlotCurve {
    std::string label;
    Rgb colour{0, 0, 0};
    std::vector<double> x, y;  // equal lengths
};

struct LinePlot {
    std::string title, xLabel, yLabel;
    std::vector<PlotCurve> curves;
    int widthPx = 900, heightPx = 600;
};

/// Draws `plot` (axes spanning every curve's points; y from 0 when all y ≥
/// 0) and writes it to `path` atomically. Throws std::invalid_argument for
/// curves whose x and y differ in length or hold no finite point,
/// std::runtime_error when the file cannot be written. O(points).
void writeLinePlotPng(const std::string& path, const LinePlot& plot);

}  // namespace dfrecon
