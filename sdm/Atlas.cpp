#include "sdm/Atlas.hpp"

#include <algorithm>
#include <climits>
#include <cmath>
#include <numeric>
#include <sstream>
#include <stdexcept>
#include <string>

#include "geometry/TriangleBvh.hpp"

namespace dfrecon {

namespace {

// A triangle in its own plane, in mm: the longest edge from `origin` along
// `along` to (length, 0), the third corner above it at (apexX, heightMm)
// with 0 <= apexX <= length (the foot of the altitude onto the longest edge
// lies on it). `first` is the soup corner at the origin.
struct ChartFrame {
    Vec3 origin, along, up;
    double length = 0, apexX = 0, heightMm = 0;
    int first = 0;
};

ChartFrame chartFrame(const TriangleSoup& soup, std::size_t t) {
    const auto& tri = soup.triangles[t];
    Vec3 p[3];
    for (int k = 0; k < 3; ++k) p[k] = soup.points[tri[std::size_t(k)]];
    ChartFrame f;
    double longest = -1;
    for (int k = 0; k < 3; ++k) {
        const double l = length(p[(k + 1) % 3] - p[k]);
        if (l > longest) longest = l, f.first = k;
    }
    const Vec3 a = p[f.first], b = p[(f.first + 1) % 3], c = p[(f.first + 2) % 3];
    f.origin = a;
    f.length = longest;
    f.along = longest > 0 ? (1 / longest) * (b - a) : Vec3{1, 0, 0};
    // In-plane perpendicular towards the apex; any perpendicular when the
    // triangle is degenerate (then its points are all on the line).
    const Vec3 ac = c - a;
    Vec3 up = ac - dot(ac, f.along) * f.along;
    if (length(up) <= 1e-12 * std::max(longest, 1e-300)) {
        const Vec3 helper = std::abs(f.along.x) < 0.9 ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
        up = cross(f.along, helper);
    }
    f.up = (1 / length(up)) * up;
    f.apexX = std::clamp(dot(ac, f.along), 0.0, longest);
    f.heightMm = std::max(0.0, dot(ac, f.up));
    return f;
}

struct ChartSize {
    int width = 1, height = 1;
};

// Texels along `lengthMm`, at least 1; a count past int's range (a texel
// far smaller than the triangle, as a search for the texel size may try) is
// clamped, not converted: that conversion is undefined.
int texelsAlong(double lengthMm, double texelMm) {
    const double texels = std::ceil(lengthMm / texelMm);
    return texels < double(INT_MAX) ? std::max(1, int(texels)) : INT_MAX;
}

ChartSize chartSize(const ChartFrame& f, double texelMm) {
    return {texelsAlong(f.length, texelMm), texelsAlong(f.heightMm, texelMm)};
}

// Shelf packing: charts in `order` (tallest first) left to right in rows of
// `width` texels. Returns the total height, or INT_MAX when a chart is
// wider than the atlas; fills positions when given.
long packRows(const std::vector<ChartSize>& sizes, const std::vector<std::size_t>& order, int width,
              std::vector<TriangleChart>* charts) {
    long x = 0, y = 0, rowHeight = 0;
    for (std::size_t t : order) {
        const ChartSize s = sizes[t];
        if (s.width > width) return INT32_MAX;
        if (x + s.width > width) {
            y += rowHeight;
            x = 0;
            rowHeight = 0;
        }
        if (rowHeight == 0) rowHeight = s.height;
        if (charts) {
            (*charts)[t].x = int(x);
            (*charts)[t].y = int(y);
            (*charts)[t].width = s.width;
            (*charts)[t].height = s.height;
        }
        x += s.width;
    }
    return y + rowHeight;
}

std::vector<ChartSize> chartSizes(const std::vector<ChartFrame>& frames, double texelMm) {
    std::vector<ChartSize> sizes(frames.size());
    for (std::size_t t = 0; t < frames.size(); ++t) sizes[t] = chartSize(frames[t], texelMm);
    return sizes;
}

// Does the closed texel square [i, i+1] × [j, j+1] meet the closed
// counter-clockwise triangle abc? Separating axes: the rectangle holds the
// triangle's bounding box, so only the three edge normals can separate.
bool texelMeetsTriangle(int i, int j, Point2 a, Point2 b, Point2 c) {
    const Point2 corners[3] = {a, b, c};
    for (int k = 0; k < 3; ++k) {
        const Point2 p = corners[k], q = corners[(k + 1) % 3];
        const double nx = q.y - p.y, ny = p.x - q.x;  // outward for CCW
        const double limit = nx * p.x + ny * p.y;
        // The square's corner least far along the normal.
        const double least = nx * (nx > 0 ? i : i + 1) + ny * (ny > 0 ? j : j + 1);
        if (least > limit + 1e-9 * (std::abs(limit) + 1)) return false;
    }
    return true;
}

}  // namespace

double Atlas::samplingBoundMm() const {
    return std::sqrt(2.0) * texelMm;
}

std::size_t Atlas::usedTexels() const {
    return std::size_t(std::count_if(texelTriangle.begin(), texelTriangle.end(),
                                     [](std::int32_t t) { return t >= 0; }));
}

Atlas buildAtlas(const TriangleSoup& soup, const AtlasOptions& options) {
    const std::size_t count = soup.triangles.size();
    if (count == 0) throw std::invalid_argument("atlas: the mesh has no triangles");
    std::vector<ChartFrame> frames(count);
    double areaMm2 = 0, largestSide = 0;
    for (std::size_t t = 0; t < count; ++t) {
        frames[t] = chartFrame(soup, t);
        areaMm2 += frames[t].length * frames[t].heightMm;  // the chart's box
        largestSide = std::max({largestSide, frames[t].length, frames[t].heightMm});
    }
    // Tallest first: heights are monotone in the real height for any texel
    // size, so one order serves every packing below.
    std::vector<std::size_t> order(count);
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
        return frames[a].heightMm > frames[b].heightMm;
    });

    Atlas atlas;
    if (options.maxErrorMm > 0) {
        atlas.texelMm = options.maxErrorMm / std::sqrt(2.0);
        const std::vector<ChartSize> sizes = chartSizes(frames, atlas.texelMm);
        double texels = 0;
        int widest = 1;
        for (const ChartSize& s : sizes) {
            texels += double(s.width) * s.height;
            widest = std::max(widest, s.width);
        }
        // Square-ish, with room for the rows' ragged ends.
        const double side = std::ceil(std::sqrt(1.15 * texels));
        if (side * side > double(options.maxTexels)) {
            // Streams write numbers as %g: 1e-09, not 0.000000; 2.8e+21, not
            // a wrapped long.
            std::ostringstream problem;
            problem << "atlas: a sampling bound of " << options.maxErrorMm << " mm needs about "
                    << side * side << " texels, more than " << options.maxTexels
                    << "; ask for a larger bound";
            throw std::invalid_argument(problem.str());
        }
        atlas.width = std::max(widest, int(side));
        atlas.height = int(packRows(sizes, order, atlas.width, nullptr));
    } else {
        const int size = options.sizeTexels;
        if (size <= 0 || double(size) * size > double(options.maxTexels))
            throw std::invalid_argument("atlas: size " + std::to_string(size) + " is out of range");
        if (count > std::size_t(size) * std::size_t(size))
            throw std::invalid_argument("atlas: " + std::to_string(count) +
                                        " triangles need more than " + std::to_string(size) + "x" +
                                        std::to_string(size) + " texels");
        auto fits = [&](double texelMm) {
            return packRows(chartSizes(frames, texelMm), order, size, nullptr) <= size;
        };
        // Below the area bound nothing fits; at the largest side every chart
        // is one texel, which fits as count <= size².
        // (A surface of no area has no area bound: lo then starts just above
        // 0, where the search cannot reach a texel of 0 mm.)
        double hi = std::max(largestSide, 1e-9) * 1.0001;
        double lo = std::max(std::sqrt(areaMm2) / size, hi * 1e-12);
        for (int step = 0; step < 50 && hi > lo * (1 + 1e-6); ++step) {
            const double mid = std::sqrt(lo * hi);
            (fits(mid) ? hi : lo) = mid;
        }
        atlas.texelMm = hi;
        atlas.width = atlas.height = size;
    }

    atlas.charts.resize(count);
    packRows(chartSizes(frames, atlas.texelMm), order, atlas.width, &atlas.charts);
    atlas.texelTriangle.assign(std::size_t(atlas.width) * std::size_t(atlas.height), -1);
    for (std::size_t t = 0; t < count; ++t) {
        TriangleChart& chart = atlas.charts[t];
        const ChartFrame& f = frames[t];
        const double s = 1 / atlas.texelMm;
        // Local corners (counter-clockwise: origin, along, apex) in texels.
        const Point2 a{chart.x + 0.0, chart.y + 0.0}, b{chart.x + f.length * s, chart.y + 0.0},
            c{chart.x + f.apexX * s, chart.y + f.heightMm * s};
        chart.corners[std::size_t(f.first)] = a;
        chart.corners[std::size_t((f.first + 1) % 3)] = b;
        chart.corners[std::size_t((f.first + 2) % 3)] = c;
        for (int j = chart.y; j < chart.y + chart.height; ++j)
            for (int i = chart.x; i < chart.x + chart.width; ++i)
                if (texelMeetsTriangle(i, j, a, b, c))
                    atlas
                        .texelTriangle[std::size_t(j) * std::size_t(atlas.width) + std::size_t(i)] =
                        std::int32_t(t);
    }
    return atlas;
}

AtlasSamples atlasSamples(const Atlas& atlas, const TriangleSoup& soup) {
    AtlasSamples samples;
    // Chart by chart, so that neighbouring samples (work-items) share a
    // triangle and its list of candidates.
    for (std::size_t t = 0; t < atlas.charts.size(); ++t) {
        const TriangleChart& chart = atlas.charts[t];
        const ChartFrame f = chartFrame(soup, t);
        const auto& tri = soup.triangles[t];
        for (int j = chart.y; j < chart.y + chart.height; ++j)
            for (int i = chart.x; i < chart.x + chart.width; ++i) {
                const std::size_t texel =
                    std::size_t(j) * std::size_t(atlas.width) + std::size_t(i);
                if (atlas.texelTriangle[texel] != std::int32_t(t)) continue;
                const double u = (i + 0.5 - chart.x) * atlas.texelMm,
                             v = (j + 0.5 - chart.y) * atlas.texelMm;
                const Vec3 preimage = f.origin + u * f.along + v * f.up;
                samples.texel.push_back(std::uint32_t(texel));
                samples.triangle.push_back(std::uint32_t(t));
                samples.point.push_back(closestPointOnTriangle(
                    preimage, soup.points[tri[0]], soup.points[tri[1]], soup.points[tri[2]]));
            }
    }
    return samples;
}

}  // namespace dfrecon
