// 2D signed distance fields on a 512×512 grid for a contour with a hole, at
// 100, 1 000 and 10 000 segments. Systems, same run and machine:
//   dfrecon     the OpenCL kernel (field/SliceFields); x_opencv is its time
//               over OpenCV's
//   bruteforce  its C++ reference: every segment at every pixel
//   opencv      cv::distanceTransform(DIST_L2, DIST_MASK_PRECISE) on the
//               rasterised mask, inside and outside, giving a signed field
// Errors are against the brute-force field (exact to double rounding), in
// pixels.
#include <cmath>
#include <iostream>

#include <nlohmann/json.hpp>
#include <opencv2/imgproc.hpp>

#include "bench/Benchmarks.hpp"
#include "field/SliceFields.hpp"

namespace dfrecon::bench {

namespace {

constexpr int kGridPixels = 512;
// Timed runs of the kernel and of OpenCV, best kept: both take a few
// milliseconds, where one run in three can lose a millisecond to the
// machine (thread wake-ups), so ten runs were not always enough, and a busy
// spell can outlast thirty. (One of each in turn was tried: each then
// starts with the other's data in the caches, which slows both, OpenCV by
// a fifth.)
constexpr int kTimedRuns = 100;

// A wavy outer contour and a circular hole, `segments` edges in all, in a
// 512 px square with 1 mm pixels.
Slice contourWithHole(int segments) {
    const int outer = segments * 7 / 10, hole = segments - outer;
    Slice slice;
    Polygon a, b;
    for (int k = 0; k < outer; ++k) {
        const double t = 2 * kPi * k / outer;
        const double r = 200 * (1 + 0.08 * std::sin(5 * t));
        a.push_back({256 + r * std::cos(t), 256 + r * std::sin(t)});
    }
    for (int k = 0; k < hole; ++k) {
        const double t = -2 * kPi * k / hole;
        b.push_back({230 + 70 * std::cos(t), 270 + 70 * std::sin(t)});
    }
    slice.contours = {a, b};
    return slice;
}

struct Errors {
    double maxPx = 0, meanPx = 0;
};

Errors compare(const std::vector<float>& field, const std::vector<float>& exact, double pixelMm) {
    Errors e;
    for (std::size_t k = 0; k < field.size(); ++k) {
        const double d = std::abs(double(field[k]) - double(exact[k])) / pixelMm;
        e.maxPx = std::max(e.maxPx, d);
        e.meanPx += d;
    }
    e.meanPx /= double(field.size());
    return e;
}

// The usual image-space answer: rasterise, then two Euclidean distance
// transforms (distance to the nearest pixel of the other side).
std::vector<float> opencvSignedField(const Slice& slice, const SliceGrid& grid) {
    constexpr int kShift = 8;  // fillPoly sub-pixel bits
    cv::Mat mask = cv::Mat::zeros(grid.height, grid.width, CV_8U);
    std::vector<std::vector<cv::Point>> polygons;
    for (const Polygon& contour : slice.contours) {
        std::vector<cv::Point> points;
        for (Point2 p : contour) {
            // Pixel (i, j) covers [i, i+1) in image coordinates; centres at +0.5.
            const double x = (p.x - grid.originMm.x) / grid.pixelMm - 0.5;
            const double y = (p.y - grid.originMm.y) / grid.pixelMm - 0.5;
            points.emplace_back(int(std::lround(x * (1 << kShift))),
                                int(std::lround(y * (1 << kShift))));
        }
        polygons.push_back(points);
    }
    cv::fillPoly(mask, polygons, cv::Scalar(255), cv::LINE_8, kShift);  // even-odd: holes stay 0
    cv::Mat outside, inside, inverted;
    cv::distanceTransform(mask == 0, outside, cv::DIST_L2, cv::DIST_MASK_PRECISE);
    cv::bitwise_not(mask, inverted);
    cv::distanceTransform(inverted == 0, inside, cv::DIST_L2, cv::DIST_MASK_PRECISE);
    // Each transform measures to the nearest pixel centre of the other side.
    // (Shifting by half a pixel towards the contour was tried: it biases the
    // result by -0.34 px instead of +0.16 px, so the plain values are used.)
    std::vector<float> field(grid.pixelCount());
    for (int j = 0; j < grid.height; ++j)
        for (int i = 0; i < grid.width; ++i)
            field[std::size_t(j) * std::size_t(grid.width) + std::size_t(i)] =
                float((outside.at<float>(j, i) - inside.at<float>(j, i)) * grid.pixelMm);
    return field;
}

nlohmann::ordered_json line(const std::string& caseName, const std::string& system, double seconds,
                            const Errors& errors) {
    return {{"bench", "fields"},  {"case", caseName},           {"system", system},
            {"seconds", seconds}, {"max_err_px", errors.maxPx}, {"mean_err_px", errors.meanPx}};
}

}  // namespace

int benchFields(const std::string& device) {
    ocl::Runtime runtime(device);
    for (int segments : {100, 1000, 10000}) {
        const std::vector<Slice> slices{contourWithHole(segments)};
        SliceGrid grid;
        grid.originMm = {0, 0};
        grid.pixelMm = 1;
        grid.width = grid.height = kGridPixels;
        const std::string caseName = "512x512, " + std::to_string(segments) + " segments, hole";

        SliceFields exact;
        const double bruteSeconds =
            bestSeconds(1, [&] { exact = computeSliceFieldsReference(slices, grid); });

        // Warm-up (kernel build), untimed, so it also says what the tile lists
        // held: the counts' download is not part of the field.
        FieldKernelStats stats;
        FieldKernelOptions withStats;
        withStats.stats = &stats;
        computeSliceFields(runtime, slices, grid, {}, withStats);
        SliceFields kernel;
        const double kernelSeconds =
            bestSeconds(kTimedRuns, [&] { kernel = computeSliceFields(runtime, slices, grid); });

        std::vector<float> opencv;
        const double opencvSeconds =
            bestSeconds(kTimedRuns, [&] { opencv = opencvSignedField(slices[0], grid); });

        nlohmann::ordered_json ours =
            line(caseName, "dfrecon", kernelSeconds,
                 compare(kernel.distanceMm, exact.distanceMm, grid.pixelMm));
        ours["x_opencv"] = kernelSeconds / opencvSeconds;
        ours["device"] = runtime.device().deviceName;
        ours["tile_pixels"] = stats.tilePixels;
        ours["tiles"] = stats.tiles;
        ours["overflowing_tiles"] = stats.overflowingTiles;
        ours["leaf_listing_tiles"] = stats.leafListingTiles;
        ours["column_tiles"] = stats.columnTiles;
        ours["mean_listed"] = stats.meanListed();
        std::cout << ours.dump() << std::endl;
        std::cout << line(caseName, "bruteforce", bruteSeconds, Errors{}).dump() << std::endl;
        std::cout << line(caseName, "opencv", opencvSeconds,
                          compare(opencv, exact.distanceMm, grid.pixelMm))
                         .dump()
                  << std::endl;
    }
    return 0;
}

}  // namespace dfrecon::bench
