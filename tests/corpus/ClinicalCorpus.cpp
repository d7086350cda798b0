#include "tests/corpus/ClinicalCorpus.hpp"

#include <algorithm>
#include <cmath>
#include <random>

namespace dfrecon::testing {

namespace {

constexpr double kPi = 3.14159265358979323846;

using Random = std::mt19937;

double uniform(Random& random, double lo, double hi) {
    return std::uniform_real_distribution<double>(lo, hi)(random);
}

int integer(Random& random, int lo, int hi) {
    return std::uniform_int_distribution<int>(lo, hi)(random);
}

// A smooth star-shaped outline: a radius that wobbles with a few low
// harmonics (never self-crossing), `points` points counter-clockwise.
struct Wobble {
    double amplitude[3], phase[3];
};

Wobble randomWobble(Random& random, double strength) {
    Wobble w;
    for (int k = 0; k < 3; ++k) {
        w.amplitude[k] = uniform(random, 0, strength / double(k + 1));
        w.phase[k] = uniform(random, 0, 2 * kPi);
    }
    return w;
}

Polygon outline(Point2 centre, double rx, double ry, int points, const Wobble& w) {
    Polygon p;
    for (int i = 0; i < points; ++i) {
        const double t = 2 * kPi * i / points;
        double scale = 1;
        for (int k = 0; k < 3; ++k) scale += w.amplitude[k] * std::cos((k + 2) * t + w.phase[k]);
        p.push_back({centre.x + rx * scale * std::cos(t), centre.y + ry * scale * std::sin(t)});
    }
    return p;
}

// Plane positions as a planning CT has them: a start and a spacing, the
// values rounded to 0.01 mm as exports write them.
std::vector<double> planes(double startMm, double spacingMm, int count) {
    std::vector<double> z;
    for (int k = 0; k < count; ++k) z.push_back(std::round((startMm + k * spacingMm) * 100) / 100);
    return z;
}

Roi roiOn(const std::string& name, const PlaneFrame& frame) {
    Roi roi;
    roi.name = name;
    roi.frame = frame;
    return roi;
}

// The body outline on every plane: the image planes of the set.
Roi body(const std::vector<double>& z, const PlaneFrame& frame, Random& random) {
    Roi roi = roiOn("Body", frame);
    const Wobble w = randomWobble(random, 0.05);
    for (double zMm : z) roi.slices.push_back({zMm, {outline({0, 0}, 90, 70, 72, w)}});
    return roi;
}

// Radius of a rounded structure at height `t` in [-1, 1] of its extent.
double profile(double t) {
    return std::sqrt(std::max(0.05, 1 - t * t));
}

ContourSet vesselHoles(Random& random) {
    const double spacing = std::vector<double>{1.5, 2, 2.5, 3}[integer(random, 0, 3)];
    const int n = integer(random, 8, 16);
    const std::vector<double> z = planes(uniform(random, -50, 50), spacing, n);
    ContourSet set;
    set.rois.push_back(body(z, {}, random));
    Roi lung = roiOn("Lung", {});
    const Wobble w = randomWobble(random, 0.08);
    std::vector<std::vector<Polygon>> planeContours(z.size());
    for (std::size_t k = 1; k + 1 < z.size(); ++k) {
        const double t = 2.0 * double(k) / double(z.size() - 1) - 1;
        planeContours[k].push_back(outline({-20, 0}, 45 * profile(t), 35 * profile(t), 80, w));
    }
    // Vessels: a few points each, on one to three neighbouring planes, a
    // fraction of a square millimetre to a few.
    const int vessels = integer(random, 20, 60);
    for (int v = 0; v < vessels; ++v) {
        const std::size_t first = std::size_t(integer(random, 2, int(z.size()) - 3));
        const std::size_t count = std::size_t(integer(random, 1, 3));
        // Some reach the outline, where even-odd makes notches of them.
        const double angle = uniform(random, 0, 2 * kPi), reach = uniform(random, 0, 1.05);
        const Point2 centre{-20 + reach * 35 * std::cos(angle), reach * 25 * std::sin(angle)};
        const int points = integer(random, 4, 8);
        const double radius = uniform(random, 0.25, 1.5);
        for (std::size_t k = first; k < std::min(first + count, z.size() - 1); ++k) {
            Polygon hole = outline(centre, radius, radius * uniform(random, 0.6, 1.0), points,
                                   Wobble{{0, 0, 0}, {0, 0, 0}});
            std::reverse(hole.begin(), hole.end());
            planeContours[k].push_back(std::move(hole));
        }
    }
    // Half the lungs come from a segmentation: every point on a 0.25 mm
    // lattice, so neighbouring planes share many points.
    const bool lattice = integer(random, 0, 1) == 1;
    for (std::size_t k = 0; k < z.size(); ++k) {
        if (planeContours[k].empty()) continue;
        if (lattice)
            for (Polygon& contour : planeContours[k])
                for (Point2& p : contour) p = {std::round(p.x * 4) / 4, std::round(p.y * 4) / 4};
        lung.slices.push_back({z[k], planeContours[k]});
    }
    set.rois.push_back(std::move(lung));
    return set;
}

// What drawing tools leave in an outline: a loop that crosses itself, a
// spike out and back along one line, repeated points, a path that runs on
// past its start.
Polygon spoil(Polygon p, Random& random) {
    const std::size_t n = p.size();
    switch (integer(random, 0, 4)) {
        case 0: {  // a small loop: out, across the path, back
            const std::size_t at = std::size_t(integer(random, 1, int(n) - 3));
            const Point2 a = p[at], b = p[at + 1];
            const Point2 d = b - a;
            const Point2 normal{-d.y, d.x};
            p.insert(p.begin() + std::ptrdiff_t(at) + 1,
                     {b + 0.8 * normal, a + 0.8 * normal + 0.3 * d});
            break;
        }
        case 1: {  // a fold over several points
            const std::size_t at = std::size_t(integer(random, 0, int(n) - 1));
            const Point2 base = p[at];
            const Point2 direction{uniform(random, -1, 1), uniform(random, -1, 1)};
            const double length = uniform(random, 1, 6);
            p.insert(p.begin() + std::ptrdiff_t(at) + 1,
                     {base + 0.5 * length * direction, base + length * direction,
                      base + 0.5 * length * direction, base});
            break;
        }
        case 2:  // repeated points
            for (int r = 0; r < 3; ++r) {
                const std::size_t at = std::size_t(integer(random, 0, int(p.size()) - 1));
                p.insert(p.begin() + std::ptrdiff_t(at), p[at]);
            }
            break;
        case 3: {  // the path runs on past its start over a few points
            const std::size_t extra = std::size_t(integer(random, 2, 6));
            for (std::size_t k = 0; k < extra; ++k) p.push_back(p[k]);
            break;
        }
        default: {  // a figure eight: the far half of the outline turned over
            const std::size_t half = n / 2;
            std::reverse(p.begin() + std::ptrdiff_t(half / 2),
                         p.begin() + std::ptrdiff_t(half / 2 + half / 3));
            break;
        }
    }
    return p;
}

ContourSet crossingOutlines(Random& random) {
    const double spacing = std::vector<double>{2, 2.5, 3, 5}[integer(random, 0, 3)];
    const std::vector<double> z = planes(uniform(random, -40, 40), spacing, integer(random, 8, 14));
    ContourSet set;
    set.rois.push_back(body(z, {}, random));
    for (const char* name : {"GTV", "Cord"}) {
        Roi roi = roiOn(name, {});
        const bool cord = std::string(name) == "Cord";
        const Wobble w = randomWobble(random, cord ? 0.05 : 0.15);
        const Point2 centre = cord ? Point2{0, -40} : Point2{uniform(random, -20, 20), 10};
        for (std::size_t k = 1; k + 1 < z.size(); ++k) {
            const double t = 2.0 * double(k) / double(z.size() - 1) - 1;
            const double r = cord ? 5 : 22 * profile(t);
            Polygon p = outline(centre, r, r * 0.8, integer(random, 24, 90), w);
            if (uniform(random, 0, 1) < 0.5) p = spoil(std::move(p), random);
            roi.slices.push_back({z[k], {p}});
        }
        set.rois.push_back(std::move(roi));
    }
    return set;
}

ContourSet storedTwice(Random& random) {
    const double spacing = std::vector<double>{2, 2.5, 3}[integer(random, 0, 2)];
    const std::vector<double> z = planes(uniform(random, -40, 40), spacing, integer(random, 8, 20));
    ContourSet set;
    set.rois.push_back(body(z, {}, random));
    Roi roi = roiOn("Oesophagus", {});
    const Wobble w = randomWobble(random, 0.1);
    for (std::size_t k = 0; k < z.size(); ++k) {
        const Point2 centre{5 * std::sin(0.3 * double(k)), -25 + 3 * std::cos(0.2 * double(k))};
        Polygon p = outline(centre, 7, 5, 40, w);
        Polygon again = p;
        if (integer(random, 0, 1)) std::reverse(again.begin(), again.end());
        std::rotate(again.begin(), again.begin() + integer(random, 0, 39), again.end());
        roi.slices.push_back({z[k], {p, again}});
    }
    set.rois.push_back(std::move(roi));
    return set;
}

ContourSet srsSlabs(Random& random) {
    const std::vector<double> z = planes(uniform(random, -30, 30), 1, 40);
    ContourSet set;
    set.rois.push_back(body(z, {}, random));
    const int targets = integer(random, 1, 3);
    for (int t = 0; t < targets; ++t) {
        Roi roi = roiOn("PTV" + std::to_string(t + 1), {});
        const Wobble w = randomWobble(random, 0.12);
        const Point2 centre{uniform(random, -40, 40), uniform(random, -30, 30)};
        const int extent = integer(random, 1, 14);  // planes; 1: a single-plane slab
        const int first = integer(random, 1, 39 - extent);
        const double radius = uniform(random, 2, 10);
        for (int k = 0; k < extent; ++k) {
            const double h = extent == 1 ? 0 : 2.0 * k / (extent - 1) - 1;
            roi.slices.push_back({z[std::size_t(first + k)],
                                  {outline(centre, radius * profile(h), radius * profile(h),
                                           integer(random, 12, 48), w)}});
        }
        set.rois.push_back(std::move(roi));
    }
    return set;
}

ContourSet obliquePlanes(Random& random) {
    const double tilt = uniform(random, 3, 35) * kPi / 180, turn = uniform(random, 0, 2 * kPi);
    const Vec3 normal{std::sin(tilt) * std::cos(turn), std::sin(tilt) * std::sin(turn),
                      std::cos(tilt)};
    const PlaneFrame frame = frameWithNormal(normal);
    const double spacing = uniform(random, 3, 6);
    const std::vector<double> z = planes(uniform(random, -60, 60), spacing, integer(random, 8, 16));
    ContourSet set;
    set.rois.push_back(body(z, frame, random));
    for (const char* name : {"GTV", "Oedema"}) {
        Roi roi = roiOn(name, frame);
        const bool oedema = std::string(name) == "Oedema";
        const Wobble w = randomWobble(random, oedema ? 0.25 : 0.12);
        for (std::size_t k = 1; k + 1 < z.size(); ++k) {
            const double t = 2.0 * double(k) / double(z.size() - 1) - 1;
            const double r = (oedema ? 35 : 20) * profile(t);
            roi.slices.push_back(
                {z[k], {outline({uniform(random, -2, 2), 0}, r, 0.8 * r, 120, w)}});
        }
        set.rois.push_back(std::move(roi));
    }
    return set;
}

ContourSet touchingNeighbours(Random& random) {
    const double spacing = std::vector<double>{2, 3}[integer(random, 0, 1)];
    const std::vector<double> z = planes(uniform(random, -40, 40), spacing, integer(random, 6, 12));
    ContourSet set;
    set.rois.push_back(body(z, {}, random));
    Roi left = roiOn("Lobe L", {}), right = roiOn("Lobe R", {}), pair = roiOn("Nodes", {});
    const double wave = uniform(random, 1, 5);
    for (std::size_t k = 0; k < z.size(); ++k) {
        // A disc cut along a wavy line: the two halves share every point of it.
        const double r = 30;
        Polygon border;
        for (int i = 0; i <= 12; ++i) {
            const double y = -r + 2 * r * i / 12.0;
            border.push_back({wave * std::sin(0.3 * y + 0.5 * double(k)), y});
        }
        Polygon l = border, rr;
        for (int i = 1; i < 24; ++i) {  // the left arc, from top to bottom
            const double a = kPi / 2 + kPi * i / 24.0;
            l.push_back({r * std::cos(a), r * std::sin(a)});
        }
        std::reverse(border.begin(), border.end());
        rr = border;
        for (int i = 1; i < 24; ++i) {  // the right arc, from bottom to top
            const double a = -kPi / 2 + kPi * i / 24.0;
            rr.push_back({r * std::cos(a), r * std::sin(a)});
        }
        left.slices.push_back({z[k], {l}});
        right.slices.push_back({z[k], {rr}});
        // Two lobes of one ROI touching at one point.
        const Point2 touch{50, 0};
        Polygon a = outline({50 - 6, 0}, 6, 4, 16, Wobble{{0, 0, 0}, {0, 0, 0}});
        Polygon b = outline({50 + 5, 0}, 5, 3, 16, Wobble{{0, 0, 0}, {0, 0, 0}});
        a[0] = touch;  // the lobes' rightmost and leftmost points
        b[8] = touch;
        pair.slices.push_back({z[k], {a, b}});
    }
    set.rois.push_back(std::move(left));
    set.rois.push_back(std::move(right));
    set.rois.push_back(std::move(pair));
    return set;
}

ContourSet planesLeftEmpty(Random& random) {
    const double spacing = std::vector<double>{1, 2, 2.5, 3}[integer(random, 0, 3)];
    const std::vector<double> z = planes(uniform(random, -40, 40), spacing, 24);
    ContourSet set;
    set.rois.push_back(body(z, {}, random));
    Roi roi = roiOn("Node", {});
    const Wobble w = randomWobble(random, 0.1);
    const double radius = uniform(random, 2, 12);
    std::size_t k = std::size_t(integer(random, 0, 3));
    while (k < z.size()) {
        const std::size_t run = std::size_t(integer(random, 1, 5));
        for (std::size_t j = 0; j < run && k < z.size(); ++j, ++k)
            roi.slices.push_back({z[k], {outline({10, 5}, radius, 0.8 * radius, 32, w)}});
        k += std::size_t(integer(random, 1, 4));  // planes left empty
    }
    set.rois.push_back(std::move(roi));
    return set;
}

}  // namespace

ContourSet clinicalCase(CorpusKind kind, std::uint32_t seed) {
    Random random(seed * 7919u + std::uint32_t(kind));
    switch (kind) {
        case CorpusKind::VesselHoles:
            return vesselHoles(random);
        case CorpusKind::CrossingOutlines:
            return crossingOutlines(random);
        case CorpusKind::StoredTwice:
            return storedTwice(random);
        case CorpusKind::SrsSlabs:
            return srsSlabs(random);
        case CorpusKind::ObliquePlanes:
            return obliquePlanes(random);
        case CorpusKind::TouchingNeighbours:
            return touchingNeighbours(random);
        case CorpusKind::PlanesLeftEmpty:
            return planesLeftEmpty(random);
    }
    return {};
}

}  // namespace dfrecon::testing
