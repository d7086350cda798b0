#include "io/images/LinePlot.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include <opencv2/imgproc.hpp>

#include "io/images/ImageFiles.hpp"

namespace dfrecon {

namespace {

// A round tick step (1, 2 or 5 × 10^k) giving about `count` ticks over span.
double tickStep(double span, int count) {
    const double raw = span / count;
    const double power = std::pow(10.0, std::floor(std::log10(raw)));
    for (double m : {1.0, 2.0, 5.0, 10.0})
        if (m * power >= raw) return m * power;
    return 10 * power;
}

std::string tickText(double v, double step) {
    char text[32];
    const int digits = step >= 1 ? 0 : int(std::ceil(-std::log10(step)));
    std::snprintf(text, sizeof text, "%.*f", digits, std::abs(v) < step * 1e-9 ? 0.0 : v);
    return text;
}

cv::Scalar colourOf(const Rgb& c) {
    return cv::Scalar(c[2], c[1], c[0]);
}

}  // namespace

void writeLinePlotPng(const std::string& path, const LinePlot& plot) {
    double xMin = INFINITY, xMax = -INFINITY, yMin = INFINITY, yMax = -INFINITY;
    for (const PlotCurve& c : plot.curves) {
        if (c.x.size() != c.y.size())
            throw std::invalid_argument("plot curve '" + c.label + "': x and y differ in length");
        for (std::size_t k = 0; k < c.x.size(); ++k)
            if (std::isfinite(c.x[k]) && std::isfinite(c.y[k])) {
                xMin = std::min(xMin, c.x[k]);
                xMax = std::max(xMax, c.x[k]);
                yMin = std::min(yMin, c.y[k]);
                yMax = std::max(yMax, c.y[k]);
            }
    }
    if (!(xMin <= xMax))
        throw std::invalid_argument("plot '" + plot.title + "' has no finite point");
    if (yMin >= 0) yMin = 0;
    if (xMax == xMin) xMax = xMin + 1;
    if (yMax == yMin) yMax = yMin + 1;

    const int w = plot.widthPx, h = plot.heightPx;
    const int left = 80, right = 30, top = 50, bottom = 70;
    cv::Mat image(h, w, CV_8UC3, cv::Scalar(255, 255, 255));
    const auto px = [&](double x) {
        return left + (x - xMin) / (xMax - xMin) * (w - left - right);
    };
    const auto py = [&](double y) {
        return h - bottom - (y - yMin) / (yMax - yMin) * (h - top - bottom);
    };
    const cv::Scalar grey(200, 200, 200), black(0, 0, 0);
    const int font = cv::FONT_HERSHEY_SIMPLEX;

    const double xs = tickStep(xMax - xMin, 10), ys = tickStep(yMax - yMin, 8);
    for (double x = std::ceil(xMin / xs) * xs; x <= xMax + xs * 1e-9; x += xs) {
        const int at = int(std::lround(px(x)));
        cv::line(image, {at, top}, {at, h - bottom}, grey, 1);
        cv::putText(image, tickText(x, xs), {at - 12, h - bottom + 20}, font, 0.45, black, 1,
                    cv::LINE_AA);
    }
    for (double y = std::ceil(yMin / ys) * ys; y <= yMax + ys * 1e-9; y += ys) {
        const int at = int(std::lround(py(y)));
        cv::line(image, {left, at}, {w - right, at}, grey, 1);
        cv::putText(image, tickText(y, ys), {8, at + 5}, font, 0.45, black, 1, cv::LINE_AA);
    }
    cv::rectangle(image, {left, top}, {w - right, h - bottom}, black, 1);
    cv::putText(image, plot.title, {left, 22}, font, 0.6, black, 1, cv::LINE_AA);
    cv::putText(image, plot.xLabel, {left + (w - left - right) / 2 - 60, h - 25}, font, 0.5, black,
                1, cv::LINE_AA);
    cv::putText(image, plot.yLabel, {8, top - 8}, font, 0.5, black, 1, cv::LINE_AA);

    // Bottom right: cumulative curves rise to the right, leaving it empty.
    int legend = h - bottom - 20 * int(plot.curves.size());
    for (const PlotCurve& c : plot.curves) {
        std::vector<cv::Point> points;
        for (std::size_t k = 0; k < c.x.size(); ++k)
            if (std::isfinite(c.x[k]) && std::isfinite(c.y[k]))
                points.push_back({int(std::lround(px(c.x[k]))), int(std::lround(py(c.y[k])))});
        cv::polylines(image, points, false, colourOf(c.colour), 2, cv::LINE_AA);
        cv::line(image, {w - right - 230, legend - 5}, {w - right - 200, legend - 5},
                 colourOf(c.colour), 2);
        cv::putText(image, c.label, {w - right - 190, legend}, font, 0.45, black, 1, cv::LINE_AA);
        legend += 20;
    }
    writePng(path, image);
}

}  // namespace dfrecon
