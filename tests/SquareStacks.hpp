#pragma once
// ROIs of 10 mm squares on chosen planes: the smallest stacks that show
// where an ROI ends and starts again (contours/PlaneGaps), with volumes
// (100 mm² a plane) summed by hand.
#include <string>
#include <vector>

#include "contours/ContourSet.hpp"

namespace dfrecon::testing {

/// An ROI named `name` of 10 mm squares (100 mm²) on the planes `z`.
inline Roi squareStack(const std::string& name, const std::vector<double>& z) {
    Roi roi;
    roi.name = name;
    for (double zMm : z) roi.slices.push_back({zMm, {{{0, 0}, {10, 0}, {10, 10}, {0, 10}}}});
    return roi;
}

/// The planes from `from` to `to` mm, `step` apart.
inline std::vector<double> planesFrom(double from, double to, double step) {
    std::vector<double> z;
    for (double v = from; v <= to + 1e-9; v += step) z.push_back(v);
    return z;
}

}  // namespace dfrecon::testing
