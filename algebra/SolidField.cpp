#include "algebra/SolidField.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <thread>
#include <utility>

#include "algebra/OctantGauge.hpp"
#include "field/ClosestPrimitives.hpp"
#include "field/SurfaceScene.hpp"

namespace dfrecon {

// One margin shape: the ROIs' surfaces in space scaled by 1/axes (axes 1:
// unscaled, an isotropic margin or none), ready for distance queries.
struct ExpressionField::Shape {
    Vec3 axes{1, 1, 1};
    std::vector<std::string> rois;  // object i of the scene
    std::unique_ptr<SurfaceScene> scene;
    std::unique_ptr<ClosestPrimitiveKernel> kernel;        // DistanceBackend::Device
    std::map<std::size_t, std::vector<double>> distances;  // per object, of the last values()
    std::map<std::size_t, std::vector<Vec3>> closest;      // their closest points (octant leaves)

    Vec3 scaled(Vec3 p) const { return {p.x / axes.x, p.y / axes.y, p.z / axes.z}; }
};

// A leaf of the expression: ROI `object` of shape `shape`; its value is
// (distance − level) · norm.
struct ExpressionField::Leaf {
    std::size_t shape = 0, object = 0;
    double level = 0, norm = 1;
    double spaceLipschitz = 1;  // of the leaf's value, along any direction
    /// A margin that differs between the senses of an axis: the gauge of
    /// this body replaces the distance (algebra/OctantGauge).
    std::optional<OctantBody> octants;
    bool shrink = false;
};

namespace {

using Kind = ExpressionNode::Kind;

// The largest stretch of a vector in the plane of (u, v) under diag(1/axes):
// the Lipschitz constant, within the planes, of a distance in scaled space.
double inPlaneStretch(Vec3 axes, const PlaneFrame& frame) {
    const Vec3 d{1 / (axes.x * axes.x), 1 / (axes.y * axes.y), 1 / (axes.z * axes.z)};
    const auto form = [&](Vec3 a, Vec3 b) {
        return a.x * d.x * b.x + a.y * d.y * b.y + a.z * d.z * b.z;
    };
    const double uu = form(frame.u, frame.u), vv = form(frame.v, frame.v),
                 uv = form(frame.u, frame.v);
    const double mean = 0.5 * (uu + vv), half = 0.5 * (uu - vv);
    return std::sqrt(mean + std::sqrt(half * half + uv * uv));
}

Box3 boxOf(const TriangleSoup& soup) {
    Box3 box;
    for (const Vec3& p : soup.points) box.add(p);
    return box;
}

bool emptyBox(const Box3& b) {
    return b.lo.x > b.hi.x || b.lo.y > b.hi.y || b.lo.z > b.hi.z;
}

}  // namespace

ExpressionField::ExpressionField(const RoiExpression& lowered,
                                 const std::map<std::string, TriangleSoup>& surfaces,
                                 const PlaneFrame& planes, DistanceBackend backend,
                                 ocl::Runtime* runtime)
    : expression_(lowered), leafOfNode_(lowered.nodes.size(), SIZE_MAX) {
    if (backend == DistanceBackend::Device && !runtime)
        throw std::invalid_argument("ExpressionField: the device backend needs a runtime");
    // Leaves: ROIs, and margins of ROIs; each finds or adds its shape.
    std::vector<std::size_t> leafNodes;
    for (std::size_t i = 0; i < lowered.nodes.size(); ++i) {
        const ExpressionNode& n = lowered.nodes[i];
        if (n.kind == Kind::Margin && lowered.nodes[n.left].kind != Kind::Roi)
            throw std::invalid_argument(
                "ExpressionField: a margin of more than an ROI (lower the "
                "expression with marginsOnRois first)");
        const bool leaf =
            n.kind == Kind::Margin ||
            (n.kind == Kind::Roi &&
             std::none_of(lowered.nodes.begin(), lowered.nodes.end(), [&](const ExpressionNode& m) {
                 return m.kind == Kind::Margin && m.left == i;
             }));
        if (leaf) leafNodes.push_back(i);
    }
    std::vector<std::vector<TriangleSoup>> shapeSurfaces;
    for (std::size_t i : leafNodes) {
        const ExpressionNode& n = lowered.nodes[i];
        const std::string& roi = n.kind == Kind::Margin ? lowered.nodes[n.left].roi : n.roi;
        const auto surface = surfaces.find(roi);
        if (surface == surfaces.end())
            throw std::invalid_argument("ExpressionField: no surface for ROI '" + roi + "'");
        Leaf leaf;
        Vec3 axes{1, 1, 1};
        const auto axis = [](double mm) { return std::max(std::abs(mm), kFlatMarginAxisMm); };
        if (n.kind == Kind::Margin && !n.margin.isSymmetric()) {
            // Eight octants: distances in the unscaled scene, then gauges.
            OctantBody body;
            for (std::size_t k = 0; k < 6; ++k) body.mm[k] = axis(n.margin.mm[k]);
            leaf.shrink = n.margin.shrinks();
            leaf.norm = 1 / body.largestInPlane(planes.u, planes.v);
            leaf.spaceLipschitz = leaf.norm / body.smallest();
            leaf.octants = body;
        } else if (n.kind == Kind::Margin && !n.margin.isUniform()) {
            axes = {axis(n.margin.mm[0]), axis(n.margin.mm[2]), axis(n.margin.mm[4])};
            leaf.level = n.margin.grows() ? 1 : -1;
            leaf.norm = 1 / inPlaneStretch(axes, planes);
            leaf.spaceLipschitz = leaf.norm / std::min({axes.x, axes.y, axes.z});
        } else if (n.kind == Kind::Margin) {
            leaf.level = n.margin.mm[0];
        }
        std::size_t s = 0;
        while (s < shapes_.size() && !(shapes_[s]->axes == axes)) ++s;
        if (s == shapes_.size()) {
            shapes_.push_back(std::make_unique<Shape>());
            shapes_.back()->axes = axes;
            shapeSurfaces.emplace_back();
        }
        Shape& shape = *shapes_[s];
        auto known = std::find(shape.rois.begin(), shape.rois.end(), roi);
        if (known == shape.rois.end()) {
            shape.rois.push_back(roi);
            TriangleSoup scaled = surface->second;
            for (Vec3& p : scaled.points) p = shape.scaled(p);
            shapeSurfaces[s].push_back(std::move(scaled));
            known = shape.rois.end() - 1;
        }
        leaf.shape = s;
        leaf.object = std::size_t(known - shape.rois.begin());
        leafOfNode_[i] = leaves_.size();
        leaves_.push_back(leaf);
    }
    for (std::size_t s = 0; s < shapes_.size(); ++s) {
        Shape& shape = *shapes_[s];
        shape.scene = std::make_unique<SurfaceScene>(std::move(shapeSurfaces[s]), shape.rois);
        for (std::size_t o = 0; o < shape.rois.size(); ++o)
            if (!shape.scene->closed(o))
                throw std::invalid_argument("the surface of ROI '" + shape.rois[o] +
                                            "' is not closed, so inside and outside are not "
                                            "defined");
        if (backend == DistanceBackend::Device)
            shape.kernel = std::make_unique<ClosestPrimitiveKernel>(*runtime, *shape.scene);
    }
}

ExpressionField::~ExpressionField() = default;

std::vector<double> ExpressionField::values(const std::vector<Vec3>& patientPoints) {
    const std::size_t count = patientPoints.size();
    // The distances every leaf needs, once per shape and ROI.
    for (auto& shape : shapes_) {
        shape->distances.clear();
        shape->closest.clear();
    }
    for (const Leaf& leaf : leaves_) {
        Shape& shape = *shapes_[leaf.shape];
        if (shape.distances.count(leaf.object)) continue;
        std::vector<Vec3> points(count);
        for (std::size_t k = 0; k < count; ++k) points[k] = shape.scaled(patientPoints[k]);
        DistanceQuery query;
        query.target = int(leaf.object);
        const std::vector<ClosestPrimitive> found =
            shape.kernel ? shape.kernel->runAt(points, query)
                         : closestPrimitivesAtReference(*shape.scene, points, query);
        std::vector<double>& d = shape.distances[leaf.object];
        d.resize(count);
        for (std::size_t k = 0; k < count; ++k) d[k] = found[k].distanceMm;
        if (std::any_of(leaves_.begin(), leaves_.end(), [&](const Leaf& l) {
                return l.octants && l.shape == leaf.shape && l.object == leaf.object;
            })) {
            std::vector<Vec3>& c = shape.closest[leaf.object];
            c.resize(count);
            for (std::size_t k = 0; k < count; ++k) c[k] = found[k].point;
        }
        queries_ += count;
    }
    // The tree, bottom-up over all points at once (children precede
    // parents in nodes, as the parser and the lowering add them).
    std::vector<std::vector<double>> at(expression_.nodes.size());
    for (std::size_t i = 0; i < expression_.nodes.size(); ++i) {
        const ExpressionNode& n = expression_.nodes[i];
        std::vector<double>& v = at[i];
        if (leafOfNode_[i] != SIZE_MAX) {
            const Leaf& leaf = leaves_[leafOfNode_[i]];
            const std::vector<double>& d = shapes_[leaf.shape]->distances.at(leaf.object);
            v.resize(count);
            if (leaf.octants)
                octantValues(leaf, d, patientPoints, v);
            else
                for (std::size_t k = 0; k < count; ++k) v[k] = (d[k] - leaf.level) * leaf.norm;
            continue;
        }
        if (n.kind == Kind::Roi) continue;  // under a margin: the margin is the leaf
        if (n.kind == Kind::Margin) continue;
        const std::vector<double>&a = at[n.left], &b = at[n.right];
        v.resize(count);
        for (std::size_t k = 0; k < count; ++k) {
            switch (n.kind) {
                case Kind::Union:
                    v[k] = std::min(a[k], b[k]);
                    break;
                case Kind::Intersection:
                    v[k] = std::max(a[k], b[k]);
                    break;
                case Kind::Difference:
                    v[k] = std::max(a[k], -b[k]);
                    break;
                case Kind::Xor:
                    v[k] = std::min(std::max(a[k], -b[k]), std::max(b[k], -a[k]));
                    break;
                default:
                    break;
            }
        }
    }
    return std::move(at[expression_.root]);
}

double ExpressionField::toleranceMm() const {
    double tolerance = 1e-9;
    for (const Leaf& leaf : leaves_) {
        const Shape& shape = *shapes_[leaf.shape];
        Box3 box;
        for (std::size_t o = 0; o < shape.scene->objectCount(); ++o)
            for (const Vec3& p : shape.scene->object(o).points) box.add(p);
        const double extent = length(box.hi - box.lo);
        const double distance = shape.kernel ? shape.kernel->toleranceMm() : 1e-12 * extent;
        tolerance = std::max(tolerance, 4 * distance * leaf.norm);
    }
    return tolerance;
}

bool ExpressionField::hasOctantMargins() const {
    return std::any_of(leaves_.begin(), leaves_.end(),
                       [](const Leaf& l) { return bool(l.octants); });
}

double ExpressionField::lipschitzInSpace() const {
    double most = 0;
    for (const Leaf& leaf : leaves_) most = std::max(most, leaf.spaceLipschitz);
    return most;
}

void ExpressionField::octantValues(const Leaf& leaf, const std::vector<double>& distance,
                                   const std::vector<Vec3>& points,
                                   std::vector<double>& out) const {
    // Beyond twice the largest semi-axis from the surface the gauge is at
    // least 2: a bound (its distance over the largest axis) serves there,
    // as it errs towards zero, which is all the sampling's cell test needs.
    constexpr double kCap = 2;
    const OctantBody& body = *leaf.octants;
    const double largest = body.largest();
    const TriangleBvh& bvh = shapes_[leaf.shape]->scene->bvh(leaf.object);
    const std::vector<Vec3>& closest = shapes_[leaf.shape]->closest.at(leaf.object);
    const auto valueAt = [&](std::size_t k) {
        const double d = distance[k];
        double f;
        if (!leaf.shrink) {
            // Inside the ROI: in the growth, at least 1 + depth / largest deep.
            if (d < 0)
                f = -(1 + -d / largest);
            else if (d >= kCap * largest)
                f = d / largest - 1;
            else  // the gauge to the nearest point bounds the search
                f = smallestGauge(
                        bvh, points[k], body, false,
                        std::min(kCap, body.gauge(points[k] - closest[k]) * (1 + 1e-12))) -
                    1;
        } else {
            if (d >= 0)
                f = 1 + d / largest;
            else if (-d >= kCap * largest)
                f = 1 - -d / largest;
            else
                f = 1 -
                    smallestGauge(bvh, points[k], body, true,
                                  std::min(kCap, body.gauge(closest[k] - points[k]) * (1 + 1e-12)));
        }
        return f * leaf.norm;
    };
    // The gauges are the host's work: every core takes a share of points.
    const std::size_t threads = std::max<std::size_t>(
        1, std::min<std::size_t>(std::thread::hardware_concurrency(), points.size() / 256));
    std::vector<std::thread> workers;
    for (std::size_t t = 0; t < threads; ++t)
        workers.emplace_back([&, t] {
            for (std::size_t k = t; k < points.size(); k += threads) out[k] = valueAt(k);
        });
    for (std::thread& w : workers) w.join();
}

Box3 ExpressionField::support() const {
    std::vector<Box3> box(expression_.nodes.size());
    for (std::size_t i = 0; i < expression_.nodes.size(); ++i) {
        const ExpressionNode& n = expression_.nodes[i];
        if (leafOfNode_[i] != SIZE_MAX) {
            const Leaf& leaf = leaves_[leafOfNode_[i]];
            const Shape& shape = *shapes_[leaf.shape];
            Box3 b = boxOf(shape.scene->object(leaf.object));
            b.lo = {b.lo.x * shape.axes.x, b.lo.y * shape.axes.y, b.lo.z * shape.axes.z};
            b.hi = {b.hi.x * shape.axes.x, b.hi.y * shape.axes.y, b.hi.z * shape.axes.z};
            if (n.kind == Kind::Margin && n.margin.grows()) {
                // R is −x, L +x, A −y, P +y, S +z, I −z (patient LPS).
                const auto& m = n.margin.mm;
                b.lo = b.lo - Vec3{m[0], m[2], m[5]};
                b.hi = b.hi + Vec3{m[1], m[3], m[4]};
            }
            box[i] = b;
            continue;
        }
        if (n.kind == Kind::Roi || n.kind == Kind::Margin) continue;
        const Box3 &a = box[n.left], &b = box[n.right];
        Box3 r;
        switch (n.kind) {
            case Kind::Union:
            case Kind::Xor:
                if (!emptyBox(a)) r.add(a);
                if (!emptyBox(b)) r.add(b);
                break;
            case Kind::Intersection:
                r.lo = {std::max(a.lo.x, b.lo.x), std::max(a.lo.y, b.lo.y),
                        std::max(a.lo.z, b.lo.z)};
                r.hi = {std::min(a.hi.x, b.hi.x), std::min(a.hi.y, b.hi.y),
                        std::min(a.hi.z, b.hi.z)};
                break;
            case Kind::Difference:
                r = a;
                break;
            default:
                break;
        }
        box[i] = r;
    }
    return box[expression_.root];
}

}  // namespace dfrecon
