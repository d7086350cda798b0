#include "recon/MedialAxis.hpp"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <stdexcept>

namespace dfrecon {

namespace {

void checkSlices(const SliceFields& fields, std::size_t lower, std::size_t upper) {
    if (lower >= fields.sliceCount() || upper >= fields.sliceCount())
        throw std::out_of_range("sumSlices: slice index out of range");
}

}  // namespace

SliceSum sumSlices(const SliceFields& fields, std::size_t lower, std::size_t upper) {
    checkSlices(fields, lower, upper);
    const std::size_t pixels = fields.grid.pixelCount();
    SliceSum result;
    result.sumMm.resize(pixels);
    result.negative.resize(pixels);
    for (std::size_t k = 0; k < pixels; ++k) {
        const float s =
            fields.distanceMm[lower * pixels + k] + fields.distanceMm[upper * pixels + k];
        result.sumMm[k] = s;
        result.negative[k] = s < 0 ? 1 : 0;
    }
    return result;
}

std::vector<MedialAxis> traceMedialAxes(const SliceFields& fields, std::size_t lower,
                                        std::size_t upper, const SliceSum& sum) {
    checkSlices(fields, lower, upper);
    const SliceGrid& grid = fields.grid;
    const std::size_t pixels = grid.pixelCount();
    if (sum.negative.size() != pixels)
        throw std::invalid_argument("traceMedialAxes: size mismatch");

    // findContours wants a mutable 8-bit image; grid row j is image row j.
    cv::Mat mask(grid.height, grid.width, CV_8U);
    std::copy(sum.negative.begin(), sum.negative.end(), mask.data);
    std::vector<std::vector<cv::Point>> borders;
    std::vector<cv::Vec4i> hierarchy;
    cv::findContours(mask, borders, hierarchy, cv::RETR_CCOMP, cv::CHAIN_APPROX_NONE);

    std::vector<MedialAxis> axes(borders.size());
    for (std::size_t b = 0; b < borders.size(); ++b) {
        MedialAxis& axis = axes[b];
        // RETR_CCOMP: top-level borders are outer ones, their children holes.
        axis.parent = hierarchy[b][3];
        axis.bordersHole = axis.parent >= 0;
        double twiceArea = 0;  // shoelace in grid coordinates (+y up)
        for (std::size_t k = 0; k < borders[b].size(); ++k) {
            const cv::Point& p = borders[b][k];
            const cv::Point& q = borders[b][(k + 1) % borders[b].size()];
            twiceArea += double(p.x) * q.y - double(q.x) * p.y;
            const std::size_t at = std::size_t(p.y) * std::size_t(grid.width) + std::size_t(p.x);
            axis.pixels.push_back({p.x, p.y, sum.sumMm[at], fields.nearestId[lower * pixels + at],
                                   fields.nearestId[upper * pixels + at]});
        }
        // Like contours: outer borders counter-clockwise, hole borders clockwise.
        if ((twiceArea > 0) == axis.bordersHole)
            std::reverse(axis.pixels.begin(), axis.pixels.end());
    }
    return axes;
}

}  // namespace dfrecon
