#include "shapes/EllipsoidDistance.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>
#include <vector>

namespace dfrecon {

namespace {

// Largest root s of Σ (rᵢ zᵢ / (s + rᵢ))² = 1, found by bisection; `g` is the
// sign of the implicit function at the point (outside > 0).
double ellipseRoot(const std::vector<double>& r, const std::vector<double>& z, double g) {
    std::vector<double> n(r.size());
    double lengthN = 0;
    for (std::size_t i = 0; i < r.size(); ++i) {
        n[i] = r[i] * z[i];
        lengthN += n[i] * n[i];
    }
    double s0 = z.back() - 1;
    double s1 = g < 0 ? 0 : std::sqrt(lengthN) - 1;
    double s = 0;
    for (int iteration = 0; iteration < 2100; ++iteration) {
        s = 0.5 * (s0 + s1);
        if (s == s0 || s == s1) break;
        double value = -1;
        for (std::size_t i = 0; i < r.size(); ++i) {
            const double ratio = n[i] / (s + r[i]);
            value += ratio * ratio;
        }
        if (value > 0)
            s0 = s;
        else if (value < 0)
            s1 = s;
        else
            break;
    }
    return s;
}

// Distance from (y0, y1), both >= 0, to the ellipse with semi-axes e0 >= e1.
double distanceToEllipse(double e0, double e1, double y0, double y1) {
    if (y1 > 0) {
        if (y0 > 0) {
            const double z0 = y0 / e0, z1 = y1 / e1, g = z0 * z0 + z1 * z1 - 1;
            if (g == 0) return 0;
            const double r0 = (e0 / e1) * (e0 / e1);
            const double s = ellipseRoot({r0, 1}, {z0, z1}, g);
            const double x0 = r0 * y0 / (s + r0), x1 = y1 / (s + 1);
            return std::hypot(x0 - y0, x1 - y1);
        }
        return std::abs(y1 - e1);
    }
    const double numer0 = e0 * y0, denom0 = e0 * e0 - e1 * e1;
    if (numer0 < denom0) {
        const double xde0 = numer0 / denom0;
        const double x0 = e0 * xde0, x1 = e1 * std::sqrt(1 - xde0 * xde0);
        return std::hypot(x0 - y0, x1);
    }
    return std::abs(y0 - e0);
}

// Distance from y (all >= 0) to the ellipsoid with semi-axes e0 >= e1 >= e2.
double distanceToEllipsoid(double e0, double e1, double e2, double y0, double y1, double y2) {
    if (y2 > 0) {
        if (y1 > 0) {
            if (y0 > 0) {
                const double z0 = y0 / e0, z1 = y1 / e1, z2 = y2 / e2;
                const double g = z0 * z0 + z1 * z1 + z2 * z2 - 1;
                if (g == 0) return 0;
                const double r0 = (e0 / e2) * (e0 / e2), r1 = (e1 / e2) * (e1 / e2);
                const double s = ellipseRoot({r0, r1, 1}, {z0, z1, z2}, g);
                const double x0 = r0 * y0 / (s + r0), x1 = r1 * y1 / (s + r1), x2 = y2 / (s + 1);
                return length(Vec3{x0 - y0, x1 - y1, x2 - y2});
            }
            return distanceToEllipse(e1, e2, y1, y2);
        }
        if (y0 > 0) return distanceToEllipse(e0, e2, y0, y2);
        return std::abs(y2 - e2);
    }
    const double denom0 = e0 * e0 - e2 * e2, denom1 = e1 * e1 - e2 * e2;
    const double numer0 = e0 * y0, numer1 = e1 * y1;
    if (numer0 < denom0 && numer1 < denom1) {
        const double xde0 = numer0 / denom0, xde1 = numer1 / denom1;
        const double discr = 1 - xde0 * xde0 - xde1 * xde1;
        if (discr > 0) {
            const double x0 = e0 * xde0, x1 = e1 * xde1, x2 = e2 * std::sqrt(discr);
            return length(Vec3{x0 - y0, x1 - y1, x2});
        }
    }
    return distanceToEllipse(e0, e1, y0, y1);
}

}  // namespace

double ellipsoidSignedDistance(double a, double b, double c, Vec3 p) {
    // Sort axes descending (carrying coordinates along) as the solver expects.
    std::array<std::pair<double, double>, 3> ax = {
        {{a, std::abs(p.x)}, {b, std::abs(p.y)}, {c, std::abs(p.z)}}};
    std::sort(ax.begin(), ax.end(), [](auto& l, auto& r) { return l.first > r.first; });
    const double d = distanceToEllipsoid(ax[0].first, ax[1].first, ax[2].first, ax[0].second,
                                         ax[1].second, ax[2].second);
    const double g = (p.x / a) * (p.x / a) + (p.y / b) * (p.y / b) + (p.z / c) * (p.z / c);
    return g < 1 ? -d : d;
}

}  // namespace dfrecon
