#include "recon/SliceInterpolant.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>

#include "recon/HermiteTangents.hpp"

namespace dfrecon {

SliceInterpolant::SliceInterpolant(const SliceFields& fields) : fields_(fields) {
    if (fields.sliceCount() == 0 || fields.grid.pixelCount() == 0)
        throw std::invalid_argument("SliceInterpolant: no fields");
    for (std::size_t s = 1; s < fields.sliceCount(); ++s)
        if (!(fields.zMm[s] > fields.zMm[s - 1]))
            throw std::invalid_argument("SliceInterpolant: slices not in increasing z");
}

std::size_t SliceInterpolant::slabAt(double zMm) const {
    const std::vector<double>& z = fields_.zMm;
    if (z.size() < 2) return 0;
    const auto above = std::upper_bound(z.begin(), z.end(), zMm);
    const std::size_t s = std::size_t(std::max<std::ptrdiff_t>(1, above - z.begin())) - 1;
    return std::min(s, z.size() - 2);
}

double SliceInterpolant::slabHeightAt(double zMm) const {
    if (fields_.zMm.size() < 2) return 0;
    const std::size_t s = slabAt(zMm);
    return fields_.zMm[s + 1] - fields_.zMm[s];
}

double SliceInterpolant::neighbourPlanesValue(Vec3 p) const {
    const std::size_t s = slabAt(p.z);
    const Point2 xy{p.x, p.y};
    if (fields_.zMm.size() < 2) return planeValue(0, xy);
    return std::min(planeValue(s, xy), planeValue(s + 1, xy));
}

double SliceInterpolant::planeValue(std::size_t slice, Point2 p) const {
    return planeSample(slice, p).value;
}

SliceInterpolant::PlaneSample SliceInterpolant::planeSample(std::size_t slice, Point2 p) const {
    const SliceGrid& g = fields_.grid;
    // Bilinear between pixel centres, clamped to the grid (whose margin keeps
    // every contour well inside).
    const double u = std::clamp((p.x - g.originMm.x) / g.pixelMm - 0.5, 0.0, g.width - 1.0);
    const double v = std::clamp((p.y - g.originMm.y) / g.pixelMm - 0.5, 0.0, g.height - 1.0);
    const int i = std::min(int(u), std::max(0, g.width - 2));
    const int j = std::min(int(v), std::max(0, g.height - 2));
    const int i1 = std::min(i + 1, g.width - 1), j1 = std::min(j + 1, g.height - 1);
    const double fx = u - i, fy = v - j;
    auto at = [&](int a, int b) { return double(fields_.distanceMm[fields_.index(slice, a, b)]); };
    const double a00 = at(i, j), a10 = at(i1, j), a01 = at(i, j1), a11 = at(i1, j1);
    return {
        (1 - fy) * ((1 - fx) * a00 + fx * a10) + fy * ((1 - fx) * a01 + fx * a11),
        {((1 - fy) * (a10 - a00) + fy * (a11 - a01)), ((1 - fx) * (a01 - a00) + fx * (a11 - a10))}};
}

namespace {

// A secant between two planes whose fields' gradients at the point are at
// most 60 degrees apart is trusted whole; at 120 degrees or more (the point
// lies across a medial axis on one plane: the far face of a thin tilted
// plate, one plane away) it measures a different stretch of contour, yet
// bounds the one the tangent wants (a distance field is the least over the
// stretches), and keeps kAcrossMedialAxisWeight. Dropped whole, it mended a
// thin plate at 2 mm (0.80 -> 0.40 x shape-based) and cost nested shells at
// 5 mm (hollow sphere 0.27 -> 0.52); a step from whole to the floor within
// 15 degrees made the field steep enough across the axis that a thin arch
// at 5 mm folded and went straight (JHU tract 3: -8 -> -15 % of its
// volume). docs/reconstruction.md, "Across a thin shape's medial axis".
constexpr double kTrustedCosine = 0.5, kLeastTrustedCosine = -0.5;
constexpr double kAcrossMedialAxisWeight = 0.3;

// How far the secant between two planes' fields at one point is trusted for
// a tangent, from their gradients there (`a`, `b`): 1 where they agree,
// kAcrossMedialAxisWeight where they point apart, linear in the cosine
// between. A vanishing gradient (a pixel on a ridge) counts as agreeing.
// O(1).
double secantTrust(Point2 a, Point2 b) {
    const double na = std::hypot(a.x, a.y), nb = std::hypot(b.x, b.y);
    if (!(na > 0) || !(nb > 0)) return 1;
    const double cosine = (a.x * b.x + a.y * b.y) / (na * nb);
    const double w = std::clamp(
        (cosine - kLeastTrustedCosine) / (kTrustedCosine - kLeastTrustedCosine), 0.0, 1.0);
    return kAcrossMedialAxisWeight + (1 - kAcrossMedialAxisWeight) * w;
}

}  // namespace

double SliceInterpolant::tangent(std::size_t slice, Point2 xy, double below, double here,
                                 double above, double trustBelow, double trustAbove) const {
    const std::vector<double>& z = fields_.zMm;
    const std::size_t n = z.size();
    // Inside the stack, recon/HermiteTangents' innerTangent (the parabola
    // through the plane and its two neighbours, 0 beside a straight
    // stretch). At the ends, the end slab's secant (no extrapolation where a
    // shape ends).
    if (slice == 0) return (above - here) / (z[1] - z[0]);
    if (slice + 1 == n) return (here - below) / (z[n - 1] - z[n - 2]);
    const double hBelow = z[slice] - z[slice - 1], hAbove = z[slice + 1] - z[slice];
    // The planes two away are read only where a straight stretch may begin.
    const auto beyondBelow = [&]() -> std::optional<double> {
        if (slice < 2) return std::nullopt;
        return (below - planeValue(slice - 2, xy)) / (z[slice - 1] - z[slice - 2]);
    };
    const auto beyondAbove = [&]() -> std::optional<double> {
        if (slice + 2 >= n) return std::nullopt;
        return (planeValue(slice + 2, xy) - above) / (z[slice + 2] - z[slice + 1]);
    };
    return innerTangent(hBelow, (here - below) / hBelow, hAbove, (above - here) / hAbove,
                        beyondBelow, beyondAbove, trustBelow, trustAbove);
}

double SliceInterpolant::value(Vec3 p) const {
    const std::vector<double>& z = fields_.zMm;
    const Point2 xy{p.x, p.y};
    if (z.size() == 1) return planeValue(0, xy);
    const std::size_t s = slabAt(p.z);
    const double h = z[s + 1] - z[s];
    const PlaneSample at0 = planeSample(s, xy), at1 = planeSample(s + 1, xy);
    const double v0 = at0.value, v1 = at1.value;
    const double secant = (v1 - v0) / h;
    // Beyond the end planes (the caps), the end slab's trend continues.
    if (p.z < z.front()) return v0 + (p.z - z[s]) * secant;
    if (p.z > z.back()) return v1 + (p.z - z[s + 1]) * secant;
    const double t = (p.z - z[s]) / h;
    // The four planes around the slab, each read once.
    const PlaneSample below = s > 0 ? planeSample(s - 1, xy) : PlaneSample{};
    const PlaneSample above = s + 2 < z.size() ? planeSample(s + 2, xy) : PlaneSample{};
    const double trustBelow = s > 0 ? secantTrust(below.gradient, at0.gradient) : 1;
    const double trustAcross = secantTrust(at0.gradient, at1.gradient);
    const double trustAbove = s + 2 < z.size() ? secantTrust(at1.gradient, above.gradient) : 1;
    const double m0 = tangent(s, xy, below.value, v0, v1, trustBelow, trustAcross);
    const double m1 = tangent(s + 1, xy, v0, v1, above.value, trustAcross, trustAbove);
    const double t2 = t * t, t3 = t2 * t;
    return (2 * t3 - 3 * t2 + 1) * v0 + (t3 - 2 * t2 + t) * h * m0 + (-2 * t3 + 3 * t2) * v1 +
           (t3 - t2) * h * m1;
}

namespace {

// d/dx and d/dy of `f` at p by central differences `stepMm` apart.
template <class F>
Point2 centralGradientXy(F&& f, Vec3 p, double stepMm) {
    return {(f(Vec3{p.x + stepMm, p.y, p.z}) - f(Vec3{p.x - stepMm, p.y, p.z})) / (2 * stepMm),
            (f(Vec3{p.x, p.y + stepMm, p.z}) - f(Vec3{p.x, p.y - stepMm, p.z})) / (2 * stepMm)};
}

}  // namespace

Point2 SliceInterpolant::gradientXy(Vec3 p) const {
    return centralGradientXy([this](Vec3 q) { return value(q); }, p, 0.5 * fields_.grid.pixelMm);
}

Point2 SliceInterpolant::neighbourPlanesGradientXy(Vec3 p) const {
    return centralGradientXy([this](Vec3 q) { return neighbourPlanesValue(q); }, p,
                             0.5 * fields_.grid.pixelMm);
}

}  // namespace dfrecon
