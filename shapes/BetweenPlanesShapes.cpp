#include "shapes/BetweenPlanesShapes.hpp"

#include <algorithm>
#include <cmath>
#include <mutex>
#include <stdexcept>

#include "shapes/EllipsoidDistance.hpp"
#include "shapes/ImplicitSection.hpp"

namespace dfrecon {

namespace {

double radians(double degrees) {
    return degrees * kPi / 180;
}

// Where a shape defined around the local origin lies: world = R·local + origin
// with R = Rz(azimuth)·Rx(tilt), so the local z axis leans `tilt` away from
// the planes' normal. Rigid, so exact distances stay exact.
class Placement {
  public:
    Placement(double tiltDegrees, double azimuthDegrees, Vec3 origin = {}) : origin_(origin) {
        const double ct = std::cos(radians(tiltDegrees)), st = std::sin(radians(tiltDegrees));
        const double ca = std::cos(radians(azimuthDegrees)), sa = std::sin(radians(azimuthDegrees));
        const double rx[3][3] = {{1, 0, 0}, {0, ct, -st}, {0, st, ct}};
        const double rz[3][3] = {{ca, -sa, 0}, {sa, ca, 0}, {0, 0, 1}};
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) {
                r_[i][j] = 0;
                for (int k = 0; k < 3; ++k) r_[i][j] += rz[i][k] * rx[k][j];
            }
    }
    Vec3 toLocal(Vec3 p) const {
        const Vec3 d = p - origin_;
        return {r_[0][0] * d.x + r_[1][0] * d.y + r_[2][0] * d.z,
                r_[0][1] * d.x + r_[1][1] * d.y + r_[2][1] * d.z,
                r_[0][2] * d.x + r_[1][2] * d.y + r_[2][2] * d.z};
    }
    Vec3 direction(Vec3 q) const {
        return {r_[0][0] * q.x + r_[0][1] * q.y + r_[0][2] * q.z,
                r_[1][0] * q.x + r_[1][1] * q.y + r_[1][2] * q.z,
                r_[2][0] * q.x + r_[2][1] * q.y + r_[2][2] * q.z};
    }
    Vec3 toWorld(Vec3 q) const { return direction(q) + origin_; }
    /// The world z axis in local coordinates: world z of q is origin.z + up·q.
    Vec3 up() const { return {r_[2][0], r_[2][1], r_[2][2]}; }
    double worldZ(Vec3 q) const { return origin_.z + dot(up(), q); }
    Point2 originXY() const { return {origin_.x, origin_.y}; }

  private:
    double r_[3][3];
    Vec3 origin_;
};

// A shape defined by an exact (or 1-Lipschitz) distance around the local
// origin and placed rigidly. Its z range is computed exactly by each shape
// (the slicer puts planes relative to it); sections are traced from the
// distance on cells of `cellMm`, within `boundRadius` of the origin.
class PlacedShape : public AnalyticShape {
  public:
    PlacedShape(std::string name, Placement placement, double boundRadius, double cellMm)
        : name_(std::move(name)), placement_(placement), bound_(boundRadius), cell_(cellMm) {}
    std::string name() const override { return name_; }
    double signedDistance(Vec3 p) const override { return localDistance(placement_.toLocal(p)); }
    double zMinMm() const override { return zMin_; }
    double zMaxMm() const override { return zMax_; }
    std::vector<Polygon> section(double z, int points) const override {
        if (!(z > zMin_ && z < zMax_)) return {};
        return implicitSection([this](Vec3 p) { return signedDistance(p); }, region(), z, cell_,
                               points);
    }
    /// Holds every section in x and y.
    Box2 region() const {
        Box2 box;
        const Point2 c = placement_.originXY();
        box.add(c - Point2{bound_, bound_});
        box.add(c + Point2{bound_, bound_});
        return box;
    }

  protected:
    virtual double localDistance(Vec3 q) const = 0;
    void setZRange(double zMin, double zMax) {
        zMin_ = zMin;
        zMax_ = zMax;
    }
    // z range of balls of radius r centred on a set of local points.
    void setZRangeOfBalls(const std::vector<Vec3>& centres, double r) {
        double lo = INFINITY, hi = -INFINITY;
        for (const Vec3& c : centres) {
            lo = std::min(lo, placement_.worldZ(c) - r);
            hi = std::max(hi, placement_.worldZ(c) + r);
        }
        setZRange(lo, hi);
    }
    SurfacePoint placed(Vec3 point, Vec3 normal) const {
        return {placement_.toWorld(point), placement_.direction(normal)};
    }
    double cellMm() const { return cell_; }

  private:
    std::string name_;
    Placement placement_;
    double bound_, cell_, zMin_ = 0, zMax_ = 0;
};

int stepsFor(double lengthMm, double stepMm, int least = 4) {
    return std::max(least, int(std::ceil(lengthMm / stepMm)));
}

// Unit vectors perpendicular to unit `axis` (any pair completing a frame).
void perpendiculars(Vec3 axis, Vec3& u, Vec3& v) {
    const Vec3 helper = std::abs(axis.x) < 0.9 ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
    u = cross(axis, helper);
    u = (1 / length(u)) * u;
    v = cross(axis, u);
}

// Points of the hemisphere of radius r around c facing `axis` (unit).
void addHemisphere(std::vector<SurfacePoint>& out, Vec3 c, Vec3 axis, double r, double step) {
    Vec3 u, v;
    perpendiculars(axis, u, v);
    const int rings = stepsFor(kPi / 2 * r, step);
    for (int i = 0; i <= rings; ++i) {
        const double polar = kPi / 2 * i / rings;  // 0 at the rim, pi/2 at the pole
        const int around = i == rings ? 1 : stepsFor(2 * kPi * r * std::cos(polar), step);
        for (int j = 0; j < around; ++j) {
            const double phi = 2 * kPi * j / around;
            const Vec3 n =
                std::cos(polar) * (std::cos(phi) * u + std::sin(phi) * v) + std::sin(polar) * axis;
            out.push_back({c + r * n, n});
        }
    }
}

// --- a torus lying at an angle -------------------------------------------------------

class TiltedTorus : public PlacedShape {
  public:
    TiltedTorus(std::string name, double major, double minor, Placement placement, double cell)
        : PlacedShape(std::move(name), placement, major + minor, cell), R_(major), r_(minor) {
        // The core circle spans R·|up projected on its plane| about the centre.
        const Vec3 up = placement.up();
        const double half = R_ * std::hypot(up.x, up.y) + r_;
        setZRange(placement.worldZ({}) - half, placement.worldZ({}) + half);
    }
    double volumeMm3() const override { return 2 * kPi * kPi * R_ * r_ * r_; }
    std::vector<SurfacePoint> parametricSurface(double step) const override {
        std::vector<SurfacePoint> out;
        const int nu = stepsFor(2 * kPi * (R_ + r_), step), nv = stepsFor(2 * kPi * r_, step);
        for (int i = 0; i < nu; ++i)
            for (int j = 0; j < nv; ++j) {
                const double u = 2 * kPi * i / nu, v = 2 * kPi * j / nv;
                const Vec3 n{std::cos(v) * std::cos(u), std::cos(v) * std::sin(u), std::sin(v)};
                out.push_back(placed(Vec3{R_ * std::cos(u), R_ * std::sin(u), 0} + r_ * n, n));
            }
        return out;
    }

  protected:
    double localDistance(Vec3 q) const override {
        return std::hypot(std::hypot(q.x, q.y) - R_, q.z) - r_;
    }

  private:
    double R_, r_;
};

// --- a cylinder with round ends (capsule) lying at an angle ---------------------------

class TiltedCylinder : public PlacedShape {
  public:
    TiltedCylinder(std::string name, double halfLength, double radius, Placement placement,
                   double cell)
        : PlacedShape(std::move(name), placement, halfLength + radius, cell),
          h_(halfLength),
          r_(radius) {
        setZRangeOfBalls({{0, 0, -h_}, {0, 0, h_}}, r_);
    }
    double volumeMm3() const override {
        return kPi * r_ * r_ * 2 * h_ + 4.0 / 3.0 * kPi * r_ * r_ * r_;
    }
    std::vector<SurfacePoint> parametricSurface(double step) const override {
        std::vector<SurfacePoint> local;
        const int around = stepsFor(2 * kPi * r_, step), along = stepsFor(2 * h_, step);
        for (int i = 0; i <= along; ++i)
            for (int j = 0; j < around; ++j) {
                const double phi = 2 * kPi * j / around;
                const Vec3 n{std::cos(phi), std::sin(phi), 0};
                local.push_back({Vec3{0, 0, -h_ + 2 * h_ * i / along} + r_ * n, n});
            }
        addHemisphere(local, {0, 0, h_}, {0, 0, 1}, r_, step);
        addHemisphere(local, {0, 0, -h_}, {0, 0, -1}, r_, step);
        std::vector<SurfacePoint> out;
        for (const SurfacePoint& s : local) out.push_back(placed(s.point, s.normal));
        return out;
    }

  protected:
    double localDistance(Vec3 q) const override {
        return length(Vec3{q.x, q.y, q.z - std::clamp(q.z, -h_, h_)}) - r_;
    }

  private:
    double h_, r_;
};

// --- a tube along a circular arc that bends through the planes -------------------------

// The arc: centre at the local origin, radius Ra in the local xz plane,
// angles in [-span, span] from the local x axis (so its middle runs along
// local z); the tube is every point within r of it (round ends).
class BentTube : public PlacedShape {
  public:
    BentTube(double arcRadius, double halfSpanDegrees, double radius, Placement placement,
             double cell)
        : PlacedShape("bent-tube", placement, arcRadius + radius, cell),
          Ra_(arcRadius),
          span_(radians(halfSpanDegrees)),
          r_(radius) {
        // World z of the arc point at angle a is origin.z + Ra (up.x cos a + up.z sin a):
        // its extremes on the span are at the ends or where the derivative vanishes.
        const Vec3 up = placement.up();
        std::vector<Vec3> extremes{arcPoint(-span_), arcPoint(span_)};
        for (double a : {std::atan2(up.z, up.x), std::atan2(up.z, up.x) + kPi}) {
            const double wrapped = std::remainder(a, 2 * kPi);
            if (std::abs(wrapped) <= span_) extremes.push_back(arcPoint(wrapped));
        }
        setZRangeOfBalls(extremes, r_);
    }
    double volumeMm3() const override {
        // Pappus for the swept disc, plus the two half balls at the ends (r < Ra
        // and a span well under a full turn: no part overlaps another).
        return kPi * r_ * r_ * Ra_ * 2 * span_ + 4.0 / 3.0 * kPi * r_ * r_ * r_;
    }
    std::vector<SurfacePoint> parametricSurface(double step) const override {
        std::vector<SurfacePoint> local;
        const int along = stepsFor(2 * span_ * (Ra_ + r_), step),
                  around = stepsFor(2 * kPi * r_, step);
        for (int i = 0; i <= along; ++i) {
            const double a = -span_ + 2 * span_ * i / along;
            const Vec3 radial{std::cos(a), 0, std::sin(a)};
            for (int j = 0; j < around; ++j) {
                const double phi = 2 * kPi * j / around;
                const Vec3 n = std::cos(phi) * radial + std::sin(phi) * Vec3{0, 1, 0};
                local.push_back({arcPoint(a) + r_ * n, n});
            }
        }
        addHemisphere(local, arcPoint(span_), tangent(span_), r_, step);
        addHemisphere(local, arcPoint(-span_), -1 * tangent(-span_), r_, step);
        std::vector<SurfacePoint> out;
        for (const SurfacePoint& s : local) out.push_back(placed(s.point, s.normal));
        return out;
    }

  protected:
    double localDistance(Vec3 q) const override {
        // The nearest point of the full circle is at q's own angle; off the
        // span, the nearest point of the arc is an end (distance grows with
        // the angle between).
        const double angle = std::atan2(q.z, q.x);
        if (std::abs(angle) <= span_) return std::hypot(std::hypot(q.x, q.z) - Ra_, q.y) - r_;
        return std::min(length(q - arcPoint(span_)), length(q - arcPoint(-span_))) - r_;
    }

  private:
    Vec3 arcPoint(double a) const { return {Ra_ * std::cos(a), 0, Ra_ * std::sin(a)}; }
    static Vec3 tangent(double a) { return {-std::sin(a), 0, std::cos(a)}; }
    double Ra_, span_, r_;
};

// --- a plate thinner than the spacing: a rounded rectangular slab --------------------------

// Every point within `rounding` of the rectangle [-a, a] x [-b, b] of the
// local xy plane: thickness 2·rounding, rounded edges.
class Plate : public PlacedShape {
  public:
    Plate(std::string name, double a, double b, double rounding, Placement placement, double cell)
        : PlacedShape(std::move(name), placement, std::hypot(a, b) + rounding, cell),
          a_(a),
          b_(b),
          t_(rounding) {
        setZRangeOfBalls({{-a, -b, 0}, {a, -b, 0}, {-a, b, 0}, {a, b, 0}}, t_);
    }
    double volumeMm3() const override {
        // Steiner: slab over the rectangle, half cylinders along its edges, a
        // ball's worth of corners.
        return 2 * t_ * 4 * a_ * b_ + kPi / 2 * t_ * t_ * 4 * (a_ + b_) +
               4.0 / 3.0 * kPi * t_ * t_ * t_;
    }
    std::vector<SurfacePoint> parametricSurface(double step) const override {
        std::vector<SurfacePoint> local;
        const int nx = stepsFor(2 * a_, step), ny = stepsFor(2 * b_, step);
        for (int i = 0; i <= nx; ++i)
            for (int j = 0; j <= ny; ++j) {
                const double x = -a_ + 2 * a_ * i / nx, y = -b_ + 2 * b_ * j / ny;
                local.push_back({{x, y, t_}, {0, 0, 1}});
                local.push_back({{x, y, -t_}, {0, 0, -1}});
            }
        const int around = stepsFor(2 * kPi * t_, step);
        auto edge = [&](Vec3 from, Vec3 to, Vec3 outward, int n) {
            for (int i = 0; i <= n; ++i)
                for (int j = 0; j < around; ++j) {
                    const double phi = -kPi / 2 + kPi * j / (around - 1);
                    const Vec3 normal = std::cos(phi) * outward + std::sin(phi) * Vec3{0, 0, 1};
                    local.push_back({from + (double(i) / n) * (to - from) + t_ * normal, normal});
                }
        };
        edge({-a_, -b_, 0}, {a_, -b_, 0}, {0, -1, 0}, nx);
        edge({-a_, b_, 0}, {a_, b_, 0}, {0, 1, 0}, nx);
        edge({-a_, -b_, 0}, {-a_, b_, 0}, {-1, 0, 0}, ny);
        edge({a_, -b_, 0}, {a_, b_, 0}, {1, 0, 0}, ny);
        // Corners: the quarter of a ball facing outward on both axes.
        const int rings = stepsFor(kPi * t_, step);
        for (double sx : {-1.0, 1.0})
            for (double sy : {-1.0, 1.0})
                for (int i = 0; i <= rings; ++i)
                    for (int j = 0; j <= around / 4 + 1; ++j) {
                        const double polar = -kPi / 2 + kPi * i / rings;
                        const double phi = (kPi / 2) * j / (around / 4 + 1);
                        const Vec3 n{sx * std::cos(polar) * std::cos(phi),
                                     sy * std::cos(polar) * std::sin(phi), std::sin(polar)};
                        local.push_back({Vec3{sx * a_, sy * b_, 0} + t_ * n, n});
                    }
        std::vector<SurfacePoint> out;
        for (const SurfacePoint& s : local) out.push_back(placed(s.point, s.normal));
        return out;
    }

  protected:
    double localDistance(Vec3 q) const override {
        return length(Vec3{std::max(std::abs(q.x) - a_, 0.0), std::max(std::abs(q.y) - b_, 0.0),
                           q.z}) -
               t_;
    }

  private:
    double a_, b_, t_;
};

// --- a thin ellipsoid lying at an angle ----------------------------------------------

class TiltedEllipsoid : public PlacedShape {
  public:
    TiltedEllipsoid(std::string name, double a, double b, double c, Placement placement,
                    double cell)
        : PlacedShape(std::move(name), placement, std::max({a, b, c}), cell), a_(a), b_(b), c_(c) {
        const Vec3 up = placement.up();
        const double half =
            std::sqrt((a * up.x) * (a * up.x) + (b * up.y) * (b * up.y) + (c * up.z) * (c * up.z));
        setZRange(placement.worldZ({}) - half, placement.worldZ({}) + half);
    }
    double volumeMm3() const override { return 4.0 / 3.0 * kPi * a_ * b_ * c_; }
    std::vector<SurfacePoint> parametricSurface(double step) const override {
        std::vector<SurfacePoint> out;
        const double longest = std::max({a_, b_, c_});
        const int nu = stepsFor(2 * kPi * longest, step), nv = stepsFor(kPi * longest, step);
        for (int i = 0; i < nu; ++i)
            for (int j = 0; j <= nv; ++j) {
                const double u = 2 * kPi * i / nu, v = -kPi / 2 + kPi * j / nv;
                const Vec3 p{a_ * std::cos(u) * std::cos(v), b_ * std::sin(u) * std::cos(v),
                             c_ * std::sin(v)};
                Vec3 n{p.x / (a_ * a_), p.y / (b_ * b_), p.z / (c_ * c_)};
                n = (1 / length(n)) * n;
                out.push_back(placed(p, n));
            }
        return out;
    }

  protected:
    double localDistance(Vec3 q) const override { return ellipsoidSignedDistance(a_, b_, c_, q); }

  private:
    double a_, b_, c_;
};

// --- a neck: two balls joined by a thin waist, as a solid of revolution --------------------

// Around the local z axis: ball A (radius rA, centre zA) and ball B (rB, zB)
// joined by the surface of revolution of a circle of radius f tangent to
// both (a circular fillet: what a smooth union approximates, but exact).
// The profile in the half plane (rho >= 0, z) is three arcs meeting with
// common tangents; the 3D distance is the 2D distance to that profile, since
// the nearest surface point lies in the point's own half plane.
class Neck : public PlacedShape {
  public:
    /// A ball's radius and its centre on the axis.
    struct Ball {
        double radius, z;
    };

    Neck(Ball a, Ball b, double fillet, Placement placement, double cell)
        : PlacedShape("neck", placement,
                      std::max(std::abs(a.z) + a.radius, std::abs(b.z) + b.radius), cell),
          rA_(a.radius),
          zA_(a.z),
          rB_(b.radius),
          zB_(b.z),
          f_(fillet) {
        const double rA = rA_, zA = zA_, rB = rB_, zB = zB_;
        // Fillet centre C: |C - A| = rA + f and |C - B| = rB + f.
        cz_ = ((rA + f_) * (rA + f_) - (rB + f_) * (rB + f_) + zB * zB - zA * zA) / (2 * (zB - zA));
        crho_ = std::sqrt((rA + f_) * (rA + f_) - (cz_ - zA) * (cz_ - zA));
        if (!(crho_ > f_)) throw std::invalid_argument("neck: fillet closes the waist");
        // Tangent points, on the segments from C to the ball centres.
        const double la = std::hypot(crho_, cz_ - zA), lb = std::hypot(crho_, cz_ - zB);
        ta_ = {crho_ - f_ * crho_ / la, cz_ + f_ * (zA - cz_) / la};
        tb_ = {crho_ - f_ * crho_ / lb, cz_ + f_ * (zB - cz_) / lb};
        angleA_ = std::atan2(ta_.y - zA, ta_.x);                       // arc A: [-pi/2, angleA]
        angleB_ = std::atan2(tb_.y - zB, tb_.x);                       // arc B: [angleB, pi/2]
        filletFrom_ = std::atan2(tb_.y - cz_, tb_.x - crho_);          // in (pi/2, pi)
        filletTo_ = std::atan2(ta_.y - cz_, ta_.x - crho_) + 2 * kPi;  // in (pi, 3pi/2)
        const double zlo =
            std::min(placement.worldZ({0, 0, zA}) - rA, placement.worldZ({0, 0, zB}) - rB);
        const double zhi =
            std::max(placement.worldZ({0, 0, zA}) + rA, placement.worldZ({0, 0, zB}) + rB);
        // The waist lies in the convex hull of the balls (its radius is convex
        // in z, below the chord between the tangent circles): the balls bound z.
        setZRange(zlo, zhi);
    }
    double volumeMm3() const override {
        auto cap = [](double r, double h) { return kPi * h * h * (3 * r - h) / 3; };
        // Waist: pi ∫ (crho - sqrt(f² - u²))² du over u = z - cz.
        const double u0 = ta_.y - cz_, u1 = tb_.y - cz_, f2 = f_ * f_;
        auto root = [&](double u) {
            return 0.5 * (u * std::sqrt(std::max(0.0, f2 - u * u)) +
                          f2 * std::asin(std::clamp(u / f_, -1.0, 1.0)));
        };
        const double waist =
            kPi * ((crho_ * crho_ + f2) * (u1 - u0) - (u1 * u1 * u1 - u0 * u0 * u0) / 3 -
                   2 * crho_ * (root(u1) - root(u0)));
        return cap(rA_, ta_.y - (zA_ - rA_)) + waist + cap(rB_, zB_ + rB_ - tb_.y);
    }
    std::vector<SurfacePoint> parametricSurface(double step) const override {
        // The profile's points and outward normals, then revolved.
        std::vector<std::pair<Point2, Point2>> profile;
        auto arc = [&](Point2 c, double r, double from, double to, double outward) {
            const int n = stepsFor(r * (to - from), step);
            for (int i = 0; i <= n; ++i) {
                const double a = from + (to - from) * i / n;
                const Point2 d{std::cos(a), std::sin(a)};
                profile.push_back({c + r * d, outward * d});
            }
        };
        arc({0, zA_}, rA_, -kPi / 2, angleA_, 1);
        arc({crho_, cz_}, f_, filletFrom_, filletTo_, -1);  // the solid is outside this circle
        arc({0, zB_}, rB_, angleB_, kPi / 2, 1);
        std::vector<SurfacePoint> out;
        for (const auto& [p, n] : profile) {
            const int around = std::max(1, stepsFor(2 * kPi * p.x, step, 1));
            for (int j = 0; j < around; ++j) {
                const double phi = 2 * kPi * j / around;
                out.push_back(placed({p.x * std::cos(phi), p.x * std::sin(phi), p.y},
                                     {n.x * std::cos(phi), n.x * std::sin(phi), n.y}));
            }
        }
        return out;
    }

  protected:
    double localDistance(Vec3 q) const override {
        const Point2 p{std::hypot(q.x, q.y), q.z};
        double d = std::min(arcDistance(p, {0, zA_}, rA_, -kPi / 2, angleA_, -kPi / 2 * 3),
                            arcDistance(p, {0, zB_}, rB_, angleB_, kPi / 2, -kPi / 2 * 3));
        d = std::min(d, arcDistance(p, {crho_, cz_}, f_, filletFrom_, filletTo_, 0));
        const bool inA = std::hypot(p.x, p.y - zA_) < rA_, inB = std::hypot(p.x, p.y - zB_) < rB_;
        bool inWaist = false;
        if (p.y >= ta_.y && p.y <= tb_.y) {
            const double u = p.y - cz_;
            inWaist = p.x < crho_ - std::sqrt(std::max(0.0, f_ * f_ - u * u));
        }
        return inA || inB || inWaist ? -d : d;
    }

  private:
    // Distance from p to the arc of circle (c, r) between angles from < to,
    // angles taken in [base, base + 2pi). Off the arc, the nearest arc point
    // is an end.
    static double arcDistance(Point2 p, Point2 c, double r, double from, double to, double base) {
        const Point2 d = p - c;
        double a = std::atan2(d.y, d.x);
        while (a < base) a += 2 * kPi;
        while (a >= base + 2 * kPi) a -= 2 * kPi;
        if (a >= from && a <= to) return std::abs(length(d) - r);
        const Point2 e0 = c + r * Point2{std::cos(from), std::sin(from)};
        const Point2 e1 = c + r * Point2{std::cos(to), std::sin(to)};
        return std::min(length(p - e0), length(p - e1));
    }

    double rA_, zA_, rB_, zB_, f_;
    double cz_ = 0, crho_ = 0;
    Point2 ta_, tb_;  // tangent points as (rho, z)
    double angleA_ = 0, angleB_ = 0, filletFrom_ = 0, filletTo_ = 0;
};

// --- a branch: a Y of capsules, smoothly joined ---------------------------------------

struct CapsulePart {
    Vec3 from, to;
    double radius;
};

double capsuleDistance(const CapsulePart& c, Vec3 q) {
    const Vec3 d = c.to - c.from;
    const double t = std::clamp(dot(q - c.from, d) / dot(d, d), 0.0, 1.0);
    return length(q - (c.from + t * d)) - c.radius;
}

// Quadratic smooth minimum: min(a, b) - max(k - |a - b|, 0)² / 4k. Its
// gradient is a convex combination of the two gradients, so it keeps them
// 1-Lipschitz; it equals min where |a - b| >= k and is at most k/4 below it.
double smoothMin(double a, double b, double k) {
    const double h = std::max(k - std::abs(a - b), 0.0) / k;
    return std::min(a, b) - h * h * k / 4;
}

// Stem and two branches meeting at the local origin, blended with radius k.
// Not an exact distance: the value is 1-Lipschitz with the right zero set and
// sign, so |value| <= the true distance, and value >= min of the capsules'
// exact distances - k/4. Its volume is integrated numerically.
class Branch : public PlacedShape {
  public:
    Branch(std::vector<CapsulePart> parts, double blend, Placement placement, double cell)
        : PlacedShape("branch", placement, boundOf(parts), cell),
          parts_(std::move(parts)),
          k_(blend) {
        // The blend only lowers the distance near the junction; the ends, far
        // from it, are plain capsule ends, so the capsules give the z range.
        double lo = INFINITY, hi = -INFINITY;
        for (const CapsulePart& c : parts_)
            for (Vec3 p : {c.from, c.to}) {
                lo = std::min(lo, placement.worldZ(p) - c.radius);
                hi = std::max(hi, placement.worldZ(p) + c.radius);
            }
        setZRange(lo, hi);
    }
    bool distanceIsExact() const override { return false; }
    double volumeMm3() const override {
        // Numerically (shapes/ImplicitSection), once: sections every 0.25 mm
        // traced on 0.1 mm cells (at scale 1) give 6104.11 mm³, 3e-5 below
        // the converged 6104.33; coarser cells cost more accuracy than
        // coarser sections (polygons inscribed in the 4 mm branches).
        std::call_once(volumeOnce_, [this] {
            volume_ = sectionedVolume([this](Vec3 p) { return signedDistance(p); }, region(),
                                      zMinMm(), zMaxMm(), 5 * cellMm(), 2 * cellMm());
        });
        return volume_;
    }
    std::vector<SurfacePoint> parametricSurface(double step) const override {
        // The capsules' own surfaces where the blend leaves them unchanged
        // (the value there is exactly zero); the blend itself has no
        // parametrisation.
        std::vector<SurfacePoint> out;
        for (const CapsulePart& c : parts_) {
            const Vec3 axis = (1 / length(c.to - c.from)) * (c.to - c.from);
            Vec3 u, v;
            perpendiculars(axis, u, v);
            std::vector<SurfacePoint> local;
            const int along = stepsFor(length(c.to - c.from), step),
                      around = stepsFor(2 * kPi * c.radius, step);
            for (int i = 0; i <= along; ++i)
                for (int j = 0; j < around; ++j) {
                    const double phi = 2 * kPi * j / around;
                    const Vec3 n = std::cos(phi) * u + std::sin(phi) * v;
                    local.push_back(
                        {c.from + (double(i) / along) * (c.to - c.from) + c.radius * n, n});
                }
            addHemisphere(local, c.to, axis, c.radius, step);
            addHemisphere(local, c.from, -1 * axis, c.radius, step);
            for (const SurfacePoint& s : local)
                if (std::abs(localDistance(s.point)) <= 1e-12 &&
                    std::abs(capsuleDistance(c, s.point)) <= 1e-12)
                    out.push_back(placed(s.point, s.normal));
        }
        return out;
    }

  protected:
    double localDistance(Vec3 q) const override {
        double d = capsuleDistance(parts_[0], q);
        for (std::size_t i = 1; i < parts_.size(); ++i)
            d = smoothMin(d, capsuleDistance(parts_[i], q), k_);
        return d;
    }

  private:
    static double boundOf(const std::vector<CapsulePart>& parts) {
        double bound = 0;
        for (const CapsulePart& c : parts)
            bound = std::max({bound, length(c.from) + c.radius, length(c.to) + c.radius});
        return bound;
    }
    std::vector<CapsulePart> parts_;
    double k_;
    mutable std::once_flag volumeOnce_;
    mutable double volume_ = 0;
};

}  // namespace

const std::vector<std::string>& betweenPlanesShapeNames() {
    static const std::vector<std::string> names = {"bent-tube",      "torus-30",    "torus-60",
                                                   "cylinder-30",    "cylinder-60", "plate-20",
                                                   "thin-ellipsoid", "neck",        "branch"};
    return names;
}

std::string betweenPlanesShapeDescription(const std::string& name) {
    if (name == "bent-tube")
        return "tube r 6 mm along a 120 deg arc of radius 30 mm, its plane 25 deg from vertical "
               "(axis 25-63 deg from z)";
    if (name == "torus-30") return "torus R 20 mm, r 6 mm, axis tilted 30 deg from z";
    if (name == "torus-60") return "torus R 20 mm, r 6 mm, axis tilted 60 deg from z";
    if (name == "cylinder-30")
        return "cylinder r 7 mm, 40 mm long with round ends, axis tilted 30 deg from z";
    if (name == "cylinder-60")
        return "cylinder r 7 mm, 40 mm long with round ends, axis tilted 60 deg from z";
    if (name == "plate-20") return "slab 40 x 28 mm, 3 mm thick with round edges, tilted 20 deg";
    if (name == "thin-ellipsoid") return "semi-axes 25 x 15 x 2 mm, tilted 25 deg";
    if (name == "neck")
        return "balls r 12 and 10 mm, 30 mm apart, joined by a waist of radius 2.9 mm "
               "(fillet r 7 mm), axis tilted 35 deg";
    if (name == "branch")
        return "capsule stem r 6 mm splitting into branches r 4.5 and 4 mm, smooth union "
               "(blend 3 mm), stem tilted 15 deg";
    return "";
}

std::unique_ptr<AnalyticShape> makeBetweenPlanesShape(const std::string& name, double scale) {
    const double s = scale;
    // Sections are traced on cells of 0.05 mm (at scale 1): well below the
    // thinnest part (the plate's 1.5 mm rounding) and the vertex spacing.
    const double cell = 0.05 * s;
    if (name == "bent-tube")
        return std::make_unique<BentTube>(30 * s, 60, 6 * s, Placement(25, 15), cell);
    if (name == "torus-30")
        return std::make_unique<TiltedTorus>(name, 20 * s, 6 * s, Placement(30, 10), cell);
    if (name == "torus-60")
        return std::make_unique<TiltedTorus>(name, 20 * s, 6 * s, Placement(60, 10), cell);
    if (name == "cylinder-30")
        return std::make_unique<TiltedCylinder>(name, 20 * s, 7 * s, Placement(30, 30), cell);
    if (name == "cylinder-60")
        return std::make_unique<TiltedCylinder>(name, 20 * s, 7 * s, Placement(60, 30), cell);
    if (name == "plate-20")
        return std::make_unique<Plate>(name, 20 * s, 14 * s, 1.5 * s, Placement(20, 40), cell);
    if (name == "thin-ellipsoid")
        return std::make_unique<TiltedEllipsoid>(name, 25 * s, 15 * s, 2 * s, Placement(25, 70),
                                                 cell);
    if (name == "neck")
        return std::make_unique<Neck>(Neck::Ball{12 * s, -15 * s}, Neck::Ball{10 * s, 15 * s},
                                      7 * s, Placement(35, 0), cell);
    if (name == "branch") {
        std::vector<CapsulePart> parts = {{{0, 0, -24 * s}, {0, 0, 0}, 6 * s},
                                          {{0, 0, 0}, {14 * s, 4 * s, 18 * s}, 4.5 * s},
                                          {{0, 0, 0}, {-11 * s, -5 * s, 19 * s}, 4 * s}};
        return std::make_unique<Branch>(std::move(parts), 3 * s, Placement(15, 30), cell);
    }
    return nullptr;
}

}  // namespace dfrecon
