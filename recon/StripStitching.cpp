#include "recon/StripStitching.hpp"

#include <algorithm>
#include <cmath>

namespace dfrecon {

namespace {

// The place on the contour a medial pixel corresponds to, as a vertex index
// plus the fraction along the following edge.
double contourParameter(PrimitiveId id, Point2 at, const Polygon& contour) {
    if (id.isVertex) return double(id.index);
    const std::size_t n = contour.size();
    const Point2 a = contour[id.index], b = contour[(id.index + 1) % n];
    return double(id.index) + nearestSegmentParameter(at, a, b);
}

// Shortest signed step from parameter a to b on a cycle of length n.
double cyclicStep(double a, double b, double n) {
    double d = std::fmod(b - a, n);
    if (d > n / 2) d -= n;
    if (d <= -n / 2) d += n;
    return d;
}

}  // namespace

std::optional<AxisPositions> positionsAlongAxis(const MedialAxis& axis, const SliceGrid& grid,
                                                const Polygon& contour, std::uint32_t contourIndex,
                                                bool lower) {
    const std::size_t n = contour.size(), m = axis.pixels.size();
    if (n < 3 || m < 3) return std::nullopt;
    const double period = double(n);

    // Samples (arc length along the axis, unwrapped contour parameter).
    std::vector<double> arc, param;
    double s = 0;
    for (std::size_t k = 0; k < m; ++k) {
        const MedialPixel& p = axis.pixels[k];
        if (k > 0) {
            const MedialPixel& q = axis.pixels[k - 1];
            s += std::hypot(double(p.i - q.i), double(p.j - q.j));
        }
        const std::uint32_t code = lower ? p.lowerId : p.upperId;
        if (code == kNoPrimitive) continue;
        const PrimitiveId id = PrimitiveId::decode(code);
        if (id.contour != contourIndex || id.index >= n) continue;
        const double t = contourParameter(id, grid.pixelCentre(p.i, p.j), contour);
        arc.push_back(s);
        param.push_back(param.empty() ? t : param.back() + cyclicStep(param.back(), t, period));
    }
    const MedialPixel& last = axis.pixels.back();
    const double length =
        s + std::hypot(double(axis.pixels[0].i - last.i), double(axis.pixels[0].j - last.j));
    const std::size_t count = param.size();
    if (count < 3) return std::nullopt;
    const double closing = param.back() + cyclicStep(param.back(), param[0], period);
    if (std::lround((closing - param[0]) / period) != 1) return std::nullopt;

    // Backtracking (the axis wiggles while the contour turns) is flattened so
    // vertices keep their contour order.
    for (std::size_t k = 1; k < count; ++k)
        param[k] = std::min(std::max(param[k], param[k - 1]), param[0] + period);

    AxisPositions result;
    result.axisLength = length;
    const double firstVertex = std::ceil(param[0]);
    result.first =
        std::size_t(((long long)firstVertex % (long long)n + (long long)n) % (long long)n);
    result.positions.reserve(n);
    std::size_t k = 0;
    for (std::size_t v = 0; v < n; ++v) {
        const double x = firstVertex + double(v);
        while (k < count && param[k] < x) ++k;
        double at;
        if (k == 0) {
            at = arc[0];
        } else {
            // Between sample k-1 and k, or across the axis' seam back to sample 0.
            const double s0 = arc[k - 1], t0 = param[k - 1];
            const double s1 = k < count ? arc[k] : length + arc[0];
            const double t1 = k < count ? param[k] : param[0] + period;
            at = t1 > t0 ? s0 + (x - t0) / (t1 - t0) * (s1 - s0) : s1;
        }
        result.positions.push_back(at);
    }
    return result;
}

void stitchStrip(SurfaceBuilder& builder, const std::vector<std::uint32_t>& lowerIds,
                 const AxisPositions& lowerAt, const std::vector<std::uint32_t>& upperIds,
                 const AxisPositions& upperAt) {
    const std::size_t n = lowerIds.size(), m = upperIds.size();
    const double period = lowerAt.axisLength;
    // Vertex i of the walk on each side, and its position (one period added
    // per lap so positions keep increasing).
    auto lower = [&](std::size_t i) { return lowerIds[(lowerAt.first + i) % n]; };
    auto lowerPos = [&](std::size_t i) {
        return lowerAt.positions[i % n] + period * double(i / n);
    };
    // The upper walk starts at the vertex whose position is nearest the lower
    // start, so the first edge is a short one.
    std::size_t shift = 0;
    double best = INFINITY;
    for (std::size_t r = 0; r < m; ++r) {
        double d = std::fabs(std::remainder(upperAt.positions[r] - lowerAt.positions[0], period));
        if (d < best) best = d, shift = r;
    }
    const double offset = lowerAt.positions[0] +
                          std::remainder(upperAt.positions[shift] - lowerAt.positions[0], period) -
                          upperAt.positions[shift];
    auto upper = [&](std::size_t k) { return upperIds[(upperAt.first + shift + k) % m]; };
    auto upperPos = [&](std::size_t k) {
        const std::size_t r = shift + k;
        return upperAt.positions[r % m] + period * double(r / m) + offset;
    };
    auto distance = [&](std::uint32_t a, std::uint32_t b) {
        return length(builder.point(a) - builder.point(b));
    };

    std::size_t i = 0, k = 0;
    while (i < n || k < m) {
        bool advanceLower;
        if (k == m) {
            advanceLower = true;
        } else if (i == n) {
            advanceLower = false;
        } else {
            const double pl = lowerPos(i + 1), pu = upperPos(k + 1);
            advanceLower = pl < pu || (pl == pu && distance(lower(i + 1), upper(k)) <=
                                                       distance(upper(k + 1), lower(i)));
        }
        if (advanceLower) {
            builder.addTriangle(lower(i), lower(i + 1), upper(k));
            ++i;
        } else {
            builder.addTriangle(lower(i), upper(k + 1), upper(k));
            ++k;
        }
    }
}

}  // namespace dfrecon
