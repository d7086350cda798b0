#include "io/images/FieldImages.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <opencv2/imgproc.hpp>

#include "io/images/Colours.hpp"
#include "io/images/ImageFiles.hpp"

namespace dfrecon {

namespace {

constexpr int kShift = 4;  // sub-pixel bits for cv::polylines

// Flips rows so +y is up.
int imageRow(const ImageFrame& frame, int j) {
    return frame.height - 1 - j;
}

void drawContours(cv::Mat& image, const ImageFrame& frame, const std::vector<Polygon>& contours) {
    std::vector<std::vector<cv::Point>> lines;
    for (const Polygon& contour : contours) {
        std::vector<cv::Point> points;
        for (Point2 p : contour) {
            const double x = (p.x - frame.originMm.x) / frame.pixelMm - 0.5;
            const double y = frame.height - 1 - ((p.y - frame.originMm.y) / frame.pixelMm - 0.5);
            points.emplace_back(int(std::lround(x * (1 << kShift))),
                                int(std::lround(y * (1 << kShift))));
        }
        lines.push_back(std::move(points));
    }
    cv::polylines(image, lines, true, cv::Scalar(255, 255, 255), 1, cv::LINE_AA, kShift);
}

// OpenCV stores pixels blue first.
cv::Vec3b toBgr(Rgb colour) {
    return {colour[2], colour[1], colour[0]};
}

}  // namespace

void writeSignedFieldPng(const std::string& path, const float* distanceMm, const ImageFrame& frame,
                         const std::vector<Polygon>& contours, double isoStepMm,
                         const std::vector<PixelMark>& marked) {
    if (frame.width <= 0 || frame.height <= 0) throw std::invalid_argument("empty image frame");
    float maxAbs = 0;
    for (std::size_t k = 0; k < std::size_t(frame.width) * std::size_t(frame.height); ++k)
        if (std::isfinite(distanceMm[k])) maxAbs = std::max(maxAbs, std::abs(distanceMm[k]));
    if (maxAbs == 0) maxAbs = 1;
    cv::Mat image(frame.height, frame.width, CV_8UC3);
    for (int j = 0; j < frame.height; ++j)
        for (int i = 0; i < frame.width; ++i) {
            const float d = distanceMm[std::size_t(j) * std::size_t(frame.width) + std::size_t(i)];
            cv::Vec3b& bgr = image.at<cv::Vec3b>(imageRow(frame, j), i);
            if (!std::isfinite(d)) {
                bgr = {0, 0, 0};
                continue;
            }
            bgr = toBgr(divergingColour(d, maxAbs));
            if (isoStepMm > 0) {
                const double phase = std::abs(d) / isoStepMm;
                if (phase - std::floor(phase) < 0.5 * frame.pixelMm / isoStepMm)
                    bgr = cv::Vec3b(uchar(bgr[0] / 2), uchar(bgr[1] / 2), uchar(bgr[2] / 2));
            }
        }
    for (const PixelMark& m : marked)
        if (m.i >= 0 && m.j >= 0 && m.i < frame.width && m.j < frame.height)
            image.at<cv::Vec3b>(imageRow(frame, m.j), m.i) = cv::Vec3b(0, 255, 255);
    drawContours(image, frame, contours);
    writePng(path, image);
}

void writeLabelPng(const std::string& path, const std::uint32_t* labels, const ImageFrame& frame,
                   const std::vector<Polygon>& contours) {
    if (frame.width <= 0 || frame.height <= 0) throw std::invalid_argument("empty image frame");
    cv::Mat image(frame.height, frame.width, CV_8UC3);
    for (int j = 0; j < frame.height; ++j)
        for (int i = 0; i < frame.width; ++i) {
            const std::uint32_t label =
                labels[std::size_t(j) * std::size_t(frame.width) + std::size_t(i)];
            image.at<cv::Vec3b>(imageRow(frame, j), i) =
                label == 0xffffffffu ? cv::Vec3b(0, 0, 0) : toBgr(categoricalColour(label));
        }
    drawContours(image, frame, contours);
    writePng(path, image);
}

}  // namespace dfrecon
