#include "shapes/AnalyticShapes.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <stdexcept>

#include "geometry/ContourValidation.hpp"
#include "shapes/BetweenPlanesShapes.hpp"
#include "shapes/EllipsoidDistance.hpp"

namespace dfrecon {

namespace {

int atLeast3(int points) {
    return std::max(points, 3);
}

// --- sphere ---------------------------------------------------------------

class Sphere : public AnalyticShape {
  public:
    Sphere(double radius, Vec3 centre = {}, std::string name = "sphere")
        : r_(radius), c_(centre), name_(std::move(name)) {}
    std::string name() const override { return name_; }
    double volumeMm3() const override { return 4.0 / 3.0 * kPi * r_ * r_ * r_; }
    double signedDistance(Vec3 p) const override {
        return length(Vec3{p.x - c_.x, p.y - c_.y, p.z - c_.z}) - r_;
    }
    double zMinMm() const override { return c_.z - r_; }
    double zMaxMm() const override { return c_.z + r_; }
    std::vector<Polygon> section(double z, int points) const override {
        const double h = z - c_.z;
        if (std::abs(h) >= r_) return {};
        return {circlePolygon({c_.x, c_.y}, std::sqrt(r_ * r_ - h * h), atLeast3(points))};
    }

  private:
    double r_;
    Vec3 c_;
    std::string name_;
};

// --- ellipsoid (exact distance: shapes/EllipsoidDistance) --------------------------

class Ellipsoid : public AnalyticShape {
  public:
    Ellipsoid(double a, double b, double c) : axes_{a, b, c} {}
    std::string name() const override { return "ellipsoid"; }
    double volumeMm3() const override { return 4.0 / 3.0 * kPi * axes_[0] * axes_[1] * axes_[2]; }
    double signedDistance(Vec3 p) const override {
        return ellipsoidSignedDistance(axes_[0], axes_[1], axes_[2], p);
    }
    double zMinMm() const override { return -axes_[2]; }
    double zMaxMm() const override { return axes_[2]; }
    std::vector<Polygon> section(double z, int points) const override {
        const double t = 1 - (z / axes_[2]) * (z / axes_[2]);
        if (t <= 0) return {};
        const double a = axes_[0] * std::sqrt(t), b = axes_[1] * std::sqrt(t);
        Polygon polygon;
        points = atLeast3(points);
        for (int i = 0; i < points; ++i) {
            const double u = 2 * kPi * i / points;
            polygon.push_back({a * std::cos(u), b * std::sin(u)});
        }
        return {polygon};
    }

  private:
    std::array<double, 3> axes_;
};

// --- torus around the z axis ----------------------------------------------------

class Torus : public AnalyticShape {
  public:
    Torus(double major, double minor) : R_(major), r_(minor) {}
    std::string name() const override { return "torus"; }
    double volumeMm3() const override { return 2 * kPi * kPi * R_ * r_ * r_; }
    double signedDistance(Vec3 p) const override {
        return std::hypot(std::hypot(p.x, p.y) - R_, p.z) - r_;
    }
    double zMinMm() const override { return -r_; }
    double zMaxMm() const override { return r_; }
    std::vector<Polygon> section(double z, int points) const override {
        if (std::abs(z) >= r_) return {};
        const double w = std::sqrt(r_ * r_ - z * z);
        // An annulus: the outer contour and its hole.
        return {circlePolygon({0, 0}, R_ + w, atLeast3(points)),
                circlePolygon({0, 0}, R_ - w, atLeast3(points))};
    }

  private:
    double R_, r_;
};

// --- capsule lying along x, so sections are stadiums ------------------------------

class Capsule : public AnalyticShape {
  public:
    Capsule(double halfLength, double radius) : h_(halfLength), r_(radius) {}
    std::string name() const override { return "capsule"; }
    double volumeMm3() const override {
        return kPi * r_ * r_ * 2 * h_ + 4.0 / 3.0 * kPi * r_ * r_ * r_;
    }
    double signedDistance(Vec3 p) const override {
        return length(Vec3{p.x - std::clamp(p.x, -h_, h_), p.y, p.z}) - r_;
    }
    double zMinMm() const override { return -r_; }
    double zMaxMm() const override { return r_; }
    std::vector<Polygon> section(double z, int points) const override {
        if (std::abs(z) >= r_) return {};
        const double w = std::sqrt(r_ * r_ - z * z);
        // Vertices spread by arc length over two straight sides and two half circles.
        const double straight = 2 * h_, arc = kPi * w, perimeter = 2 * straight + 2 * arc;
        const int nStraight = std::max(1, int(std::lround(points * straight / perimeter)));
        const int nArc = std::max(2, int(std::lround(points * arc / perimeter)));
        Polygon polygon;
        for (int i = 0; i < nStraight; ++i) polygon.push_back({-h_ + straight * i / nStraight, -w});
        for (int i = 0; i < nArc; ++i) {
            const double t = -kPi / 2 + kPi * i / nArc;
            polygon.push_back({h_ + w * std::cos(t), w * std::sin(t)});
        }
        for (int i = 0; i < nStraight; ++i) polygon.push_back({h_ - straight * i / nStraight, w});
        for (int i = 0; i < nArc; ++i) {
            const double t = kPi / 2 + kPi * i / nArc;
            polygon.push_back({-h_ + w * std::cos(t), w * std::sin(t)});
        }
        return {polygon};
    }

  private:
    double h_, r_;
};

// --- "Y": a stem cylinder that splits into two branch cylinders at z = 0 -----------

// Distance from p to the side surface of the vertical cylinder (centre c,
// radius r, z in [z0, z1]) and to its flat caps.
double distanceToCylinderSide(Vec3 p, Point2 c, double r, double z0, double z1) {
    const double radial = std::hypot(p.x - c.x, p.y - c.y) - r;
    const double axial = std::max({0.0, z0 - p.z, p.z - z1});
    return std::hypot(radial, axial);
}
double distanceToDisc(Vec3 p, Point2 c, double r, double zc) {
    const double outside = std::max(0.0, std::hypot(p.x - c.x, p.y - c.y) - r);
    return std::hypot(outside, p.z - zc);
}

class YShape : public AnalyticShape {
  public:
    // Stem: disc(0, r) × [-length, 0]; branches: disc((±offset, 0), r) × [0, length].
    // offset in (r, 2r): branches overlap the stem's disc but not each other.
    YShape(double radius, double offset, double length) : r_(radius), d_(offset), L_(length) {}
    std::string name() const override { return "y"; }
    double volumeMm3() const override { return kPi * r_ * r_ * 3 * L_; }
    double zMinMm() const override { return -L_; }
    double zMaxMm() const override { return L_; }
    std::vector<Polygon> section(double z, int points) const override {
        if (z <= -L_ || z >= L_ || z == 0) return {};
        if (z < 0) return {circlePolygon({0, 0}, r_, atLeast3(points))};
        return {circlePolygon({-d_, 0}, r_, atLeast3(points)),
                circlePolygon({d_, 0}, r_, atLeast3(points))};
    }
    double signedDistance(Vec3 p) const override {
        // Boundary = stem side and bottom, branch sides and tops, and the part
        // of the plane z = 0 covered by exactly one of stem and branches. All
        // three circles bound that planar part, so its distance is the
        // in-plane distance to the circles unless p projects into it.
        const Point2 stem{0, 0}, left{-d_, 0}, right{d_, 0};
        double d =
            std::min({distanceToCylinderSide(p, stem, r_, -L_, 0), distanceToDisc(p, stem, r_, -L_),
                      distanceToCylinderSide(p, left, r_, 0, L_),
                      distanceToCylinderSide(p, right, r_, 0, L_), distanceToDisc(p, left, r_, L_),
                      distanceToDisc(p, right, r_, L_)});
        const Point2 q{p.x, p.y};
        auto inDisc = [&](Point2 c) { return length(q - c) <= r_; };
        const bool inStem = inDisc(stem), inBranch = inDisc(left) || inDisc(right);
        double inPlane = 0;
        if (inStem == inBranch)
            inPlane = std::min({std::abs(length(q - stem) - r_), std::abs(length(q - left) - r_),
                                std::abs(length(q - right) - r_)});
        d = std::min(d, std::hypot(inPlane, p.z));
        const bool inside =
            (p.z >= -L_ && p.z <= 0 && inStem) || (p.z >= 0 && p.z <= L_ && inBranch);
        return inside ? -d : d;
    }

  private:
    double r_, d_, L_;
};

// --- union of disjoint solids: min of exact distances is exact ----------------------

class DisjointUnion : public AnalyticShape {
  public:
    DisjointUnion(std::string name, std::vector<std::unique_ptr<AnalyticShape>> parts)
        : name_(std::move(name)), parts_(std::move(parts)) {}
    std::string name() const override { return name_; }
    double volumeMm3() const override {
        double v = 0;
        for (const auto& part : parts_) v += part->volumeMm3();
        return v;
    }
    double signedDistance(Vec3 p) const override {
        double d = INFINITY;
        for (const auto& part : parts_) d = std::min(d, part->signedDistance(p));
        return d;
    }
    double zMinMm() const override {
        double z = INFINITY;
        for (const auto& part : parts_) z = std::min(z, part->zMinMm());
        return z;
    }
    double zMaxMm() const override {
        double z = -INFINITY;
        for (const auto& part : parts_) z = std::max(z, part->zMaxMm());
        return z;
    }
    std::vector<Polygon> section(double z, int points) const override {
        std::vector<Polygon> all;
        for (const auto& part : parts_)
            for (Polygon& polygon : part->section(z, points)) all.push_back(std::move(polygon));
        return all;
    }

  private:
    std::string name_;
    std::vector<std::unique_ptr<AnalyticShape>> parts_;
};

// --- hollow sphere: a ball with a concentric spherical cavity ------------------------

class HollowSphere : public AnalyticShape {
  public:
    HollowSphere(double outer, double inner) : R_(outer), r_(inner) {}
    /// With a ball of radius `island` centred at `islandCentre` floating in
    /// the cavity (it must lie inside it, clear of its wall).
    HollowSphere(double outer, double inner, double island, Vec3 islandCentre)
        : R_(outer), r_(inner), island_(island), islandCentre_(islandCentre) {}
    /// With the cavity centred at `cavityCentre` (it must lie inside the
    /// ball, clear of its surface), named `name`.
    HollowSphere(std::string name, double outer, double inner, Vec3 cavityCentre, double island,
                 Vec3 islandCentre)
        : name_(std::move(name)),
          R_(outer),
          r_(inner),
          cavityCentre_(cavityCentre),
          island_(island),
          islandCentre_(islandCentre) {}
    std::string name() const override {
        if (!name_.empty()) return name_;
        return island_ > 0 ? "shell-island" : "hollow-sphere";
    }
    double volumeMm3() const override {
        return 4.0 / 3.0 * kPi * (R_ * R_ * R_ - r_ * r_ * r_ + island_ * island_ * island_);
    }
    double signedDistance(Vec3 p) const override {
        const double shell = std::max(length(p) - R_, r_ - length(p - cavityCentre_));
        // Two disjoint solids: the nearer surface is the point's own or,
        // outside both, the nearer one.
        return island_ > 0 ? std::min(shell, length(p - islandCentre_) - island_) : shell;
    }
    double zMinMm() const override { return -R_; }
    double zMaxMm() const override { return R_; }
    std::vector<Polygon> section(double z, int points) const override {
        if (std::abs(z) >= R_) return {};
        std::vector<Polygon> polygons{
            circlePolygon({0, 0}, std::sqrt(R_ * R_ - z * z), atLeast3(points))};
        const double cz = z - cavityCentre_.z;
        if (std::abs(cz) < r_)
            polygons.push_back(circlePolygon({cavityCentre_.x, cavityCentre_.y},
                                             std::sqrt(r_ * r_ - cz * cz), atLeast3(points)));
        const double dz = z - islandCentre_.z;
        if (island_ > 0 && std::abs(dz) < island_)
            polygons.push_back(circlePolygon({islandCentre_.x, islandCentre_.y},
                                             std::sqrt(island_ * island_ - dz * dz),
                                             atLeast3(points)));
        return polygons;
    }

  private:
    std::string name_;
    double R_, r_;
    Vec3 cavityCentre_{};
    double island_ = 0;
    Vec3 islandCentre_{};
};

}  // namespace

std::vector<Vec3> sampleSurface(const AnalyticShape& shape, std::size_t count, unsigned seed) {
    // The x/y extent from a few sections; z from the shape.
    Box2 box;
    const double z0 = shape.zMinMm(), z1 = shape.zMaxMm();
    for (int k = 1; k < 64; ++k)
        for (const Polygon& c : shape.section(z0 + (z1 - z0) * k / 64, 64))
            for (Point2 p : c) box.add(p);
    const double grow = 0.1 * std::max({box.max.x - box.min.x, box.max.y - box.min.y, z1 - z0});
    std::mt19937 random(seed);
    std::uniform_real_distribution<double> ux(box.min.x - grow, box.max.x + grow),
        uy(box.min.y - grow, box.max.y + grow), uz(z0 - grow, z1 + grow);
    std::vector<Vec3> samples;
    const double step = 1e-5 * (1 + grow);
    for (std::size_t attempt = 0; samples.size() < count && attempt < 20 * count; ++attempt) {
        Vec3 p{ux(random), uy(random), uz(random)};
        // Newton steps on d(p) = 0 along the (unit) gradient of the distance.
        for (int iteration = 0; iteration < 8; ++iteration) {
            const double d = shape.signedDistance(p);
            if (std::abs(d) < 1e-9) break;
            const Vec3 g{shape.signedDistance({p.x + step, p.y, p.z}) -
                             shape.signedDistance({p.x - step, p.y, p.z}),
                         shape.signedDistance({p.x, p.y + step, p.z}) -
                             shape.signedDistance({p.x, p.y - step, p.z}),
                         shape.signedDistance({p.x, p.y, p.z + step}) -
                             shape.signedDistance({p.x, p.y, p.z - step})};
            const double norm = length(g);
            if (norm == 0) break;  // on a medial point: no direction
            p = p - (d / norm) * g;
        }
        if (std::abs(shape.signedDistance(p)) < 1e-9) samples.push_back(p);
    }
    return samples;
}

const std::vector<std::string>& shapeNames() {
    static const std::vector<std::string> names = {
        "sphere",    "ellipsoid",     "torus",        "capsule",   "y",
        "two-blobs", "hollow-sphere", "shell-island", "shell-pole"};
    return names;
}

const std::vector<std::string>& allShapeNames() {
    static const std::vector<std::string> names = [] {
        std::vector<std::string> all = shapeNames();
        for (const std::string& name : betweenPlanesShapeNames()) all.push_back(name);
        return all;
    }();
    return names;
}

std::string shapeDescription(const std::string& name) {
    if (name == "sphere") return "ball of radius 20 mm";
    if (name == "ellipsoid") return "semi-axes 30 x 20 x 15 mm (z smallest)";
    if (name == "torus")
        return "major radius 20 mm, minor 8 mm, axis z (annulus slices with a hole)";
    if (name == "capsule") return "radius 10 mm, 30 mm straight part along x (stadium slices)";
    if (name == "y") return "cylinder r 8 mm below z=0 splitting into two at x=+-10 mm above";
    if (name == "two-blobs") return "balls r 12 mm at x=-18 and r 9 mm at x=+18, z=+3";
    if (name == "hollow-sphere") return "ball r 20 mm with a concentric cavity r 10 mm";
    if (name == "shell-island")
        return "ball r 20 mm with a cavity r 12 mm and a ball r 6 mm floating off-centre in it "
               "(three nested contours per plane)";
    if (name == "shell-pole")
        return "ball r 20 mm with a cavity r 8 mm centred 11.2 mm above its centre (0.8 mm of "
               "wall at the top pole, so the top plane cuts the cavity) and a ball r 3 mm "
               "floating in it";
    if (std::string d = betweenPlanesShapeDescription(name); !d.empty()) return d;
    throw std::invalid_argument("unknown shape '" + name + "'");
}

std::unique_ptr<AnalyticShape> makeShape(const std::string& name, double scale) {
    if (!(scale > 0) || !std::isfinite(scale))
        throw std::invalid_argument("shape scale must be positive");
    const double s = scale;
    if (name == "sphere") return std::make_unique<Sphere>(20 * s);
    if (name == "ellipsoid") return std::make_unique<Ellipsoid>(30 * s, 20 * s, 15 * s);
    if (name == "torus") return std::make_unique<Torus>(20 * s, 8 * s);
    if (name == "capsule") return std::make_unique<Capsule>(15 * s, 10 * s);
    if (name == "y") return std::make_unique<YShape>(8 * s, 10 * s, 20 * s);
    if (name == "two-blobs") {
        std::vector<std::unique_ptr<AnalyticShape>> parts;
        parts.push_back(std::make_unique<Sphere>(12 * s, Vec3{-18 * s, 0, 0}, "blob-a"));
        parts.push_back(std::make_unique<Sphere>(9 * s, Vec3{18 * s, 0, 3 * s}, "blob-b"));
        return std::make_unique<DisjointUnion>("two-blobs", std::move(parts));
    }
    if (name == "hollow-sphere") return std::make_unique<HollowSphere>(20 * s, 10 * s);
    if (name == "shell-island")
        return std::make_unique<HollowSphere>(20 * s, 12 * s, 6 * s, Vec3{2 * s, 1 * s, 1.5 * s});
    if (name == "shell-pole")
        return std::make_unique<HollowSphere>(name, 20 * s, 8 * s, Vec3{0, 0, 11.2 * s}, 3 * s,
                                              Vec3{1 * s, 0.5 * s, 10.5 * s});
    if (auto shape = makeBetweenPlanesShape(name, s)) return shape;
    std::string known;
    for (const std::string& n : allShapeNames()) known += (known.empty() ? "" : ", ") + n;
    throw std::invalid_argument("unknown shape '" + name + "' (known: " + known + ")");
}

ContourSet sliceShape(const AnalyticShape& shape, const SynthOptions& options) {
    if (!(options.spacingMm > 0) || !std::isfinite(options.spacingMm))
        throw std::invalid_argument("slice spacing must be a positive number of mm");
    if (options.pointsPerContour < 3 || options.pointsPerContour > 1'000'000)
        throw std::invalid_argument("points per contour must be in 3..1000000");
    if (!(options.noiseMm >= 0) || !std::isfinite(options.noiseMm))
        throw std::invalid_argument("noise must be a non-negative number of mm");
    const double zMin = shape.zMinMm(), zMax = shape.zMaxMm();
    if ((zMax - zMin) / options.spacingMm > 100'000)
        throw std::invalid_argument("slice spacing too small: over 100000 slices");

    std::mt19937 random(options.seed);
    std::normal_distribution<double> gauss(0.0, options.noiseMm);
    auto jitter = [&] {
        return std::clamp(gauss(random), -3 * options.noiseMm, 3 * options.noiseMm);
    };

    Roi roi;
    roi.name = shape.name();
    for (int k = 0;; ++k) {
        const double z = zMin + options.spacingMm * (k + 0.5);
        if (z >= zMax) break;
        Slice slice;
        slice.zMm = z;
        slice.contours = shape.section(z, options.pointsPerContour);
        if (slice.contours.empty()) continue;
        if (options.noiseMm > 0) {
            for (Polygon& polygon : slice.contours)
                for (Point2& p : polygon) p = p + Point2{jitter(), jitter()};
            if (findContourDefect(slice.contours))
                throw std::invalid_argument("noise of " + std::to_string(options.noiseMm) +
                                            " mm makes contours intersect at z=" +
                                            std::to_string(z) + "; use less noise or fewer points");
        }
        normaliseOrientation(slice);
        roi.slices.push_back(std::move(slice));
    }
    ContourSet set;
    set.rois.push_back(std::move(roi));
    return set;
}

}  // namespace dfrecon
