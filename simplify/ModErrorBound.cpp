#include "simplify/ModErrorBound.hpp"

#include <algorithm>
#include <stdexcept>

#include "recon/MeshCheck.hpp"

namespace dfrecon {

ModErrorBound::ModErrorBound(TriMesh& mesh) : Base(mesh, false) {
    mesh.add_property(tracked_);
}

ModErrorBound::~ModErrorBound() {
    mesh().remove_property(tracked_);
}

const std::string& ModErrorBound::name() const {
    static const std::string name = "ErrorBound";
    return name;
}

void ModErrorBound::setOriginal(const TriangleBvh& original, double maxErrorMm) {
    if (!(maxErrorMm > 0)) throw std::invalid_argument("max error must be positive");
    original_ = &original;
    limits_.limitMm = maxErrorMm;
}

void ModErrorBound::setInitialPriorities(std::vector<float> priorities) {
    initial_ = std::move(priorities);
}

Vec3 ModErrorBound::point(TriMesh::VertexHandle v) const {
    return toVec3(const_cast<ModErrorBound*>(this)->mesh().point(v));
}

Box3 ModErrorBound::boxOf(TriMesh::FaceHandle f) const {
    Box3 box;
    for (auto v : const_cast<ModErrorBound*>(this)->mesh().fv_range(f)) box.add(point(v));
    return box;
}

void ModErrorBound::initialize() {
    if (!original_) throw std::logic_error("ModErrorBound: setOriginal before initialize");
    TriMesh& m = mesh();
    if (!initial_.empty() && initial_.size() != m.n_halfedges())
        throw std::invalid_argument("ModErrorBound: one initial priority per halfedge expected");
    touched_.assign(m.n_vertices(), 0);
    // Every original vertex starts on one of its faces (distance 0).
    double edgeSum = 0;
    for (auto f : m.faces()) m.property(tracked_, f).clear();
    for (auto v : m.vertices()) {
        for (auto f : m.vf_range(v)) {
            m.property(tracked_, f).push_back(point(v));
            break;
        }
    }
    for (auto e : m.edges()) edgeSum += m.calc_edge_length(e);
    faces_.reset(m.n_edges() ? 2 * edgeSum / double(m.n_edges()) : 1.0);
    for (auto f : m.faces()) faces_.insert(f.idx(), boxOf(f));
}

bool ModErrorBound::collides(const CollapseInfo& ci, const std::vector<NewTriangle>& created) {
    TriMesh& m = mesh();
    for (std::size_t i = 0; i < created.size(); ++i) {
        const NewTriangle& t = created[i];
        for (std::size_t j = i + 1; j < created.size(); ++j)
            if (trianglesCollide(t.ids, t.p, created[j].ids, created[j].p)) return true;
        Box3 box;
        for (const Vec3& p : t.p) box.add(p);
        bool hit = false;
        faces_.query(box, [&](int index) {
            if (hit) return;
            const TriMesh::FaceHandle f(index);
            if (m.status(f).deleted()) return;
            if (!boxOf(f).overlaps(box)) return;
            NewTriangle other;
            int k = 0;
            for (auto v : m.fv_range(f)) {
                if (v == ci.v0) return;  // replaced by this collapse
                other.ids[std::size_t(k)] = std::uint32_t(v.idx());
                other.p[k++] = point(v);
            }
            hit = trianglesCollide(t.ids, t.p, other.ids, other.p);
        });
        if (hit) return true;
    }
    return false;
}

float ModErrorBound::collapse_priority(const CollapseInfo& ci) {
    if (!trianglesAfterCollapse(mesh(), ci.v0v1, scratch_)) return ILLEGAL_COLLAPSE;
    float priority;
    if (!initial_.empty() && !touched_[std::size_t(ci.v0.idx())]) {
        priority = initial_[std::size_t(ci.v0v1.idx())];
        ++initialEvaluations;
    } else {
        trackedScratch_.clear();
        for (auto f : mesh().vf_range(ci.v0)) {
            const auto& points = mesh().property(tracked_, f);
            trackedScratch_.insert(trackedScratch_.end(), points.begin(), points.end());
        }
        priority = collapseBound(trackedScratch_, scratch_, *original_, limits_, &cache_);
        ++cpuEvaluations;
    }
    if (priority < 0) return ILLEGAL_COLLAPSE;
    if (collides(ci, scratch_)) return ILLEGAL_COLLAPSE;
    return priority;
}

void ModErrorBound::preprocess_collapse(const CollapseInfo& ci) {
    TriMesh& m = mesh();
    homeless_.clear();
    for (auto f : m.vf_range(ci.v0)) {
        auto& points = m.property(tracked_, f);
        homeless_.insert(homeless_.end(), points.begin(), points.end());
        points.clear();
    }
}

void ModErrorBound::postprocess_collapse(const CollapseInfo& ci) {
    TriMesh& m = mesh();
    for (const Vec3& q : homeless_) {
        TriMesh::FaceHandle home;
        double nearest = INFINITY;
        for (auto f : m.vf_range(ci.v1)) {
            Vec3 p[3];
            int k = 0;
            for (auto v : m.fv_range(f)) p[k++] = point(v);
            const double d = pointTriangleDistance(q, p[0], p[1], p[2]);
            if (d < nearest) {
                nearest = d;
                home = f;
            }
        }
        m.property(tracked_, home).push_back(q);
    }
    for (auto f : m.vf_range(ci.v1)) faces_.insert(f.idx(), boxOf(f));
    touched_[std::size_t(ci.v1.idx())] = 1;
    for (auto v : m.vv_range(ci.v1)) touched_[std::size_t(v.idx())] = 1;
}

ModErrorBound::Bounds ModErrorBound::currentBounds() {
    TriMesh& m = mesh();
    Bounds bounds;
    for (auto f : m.faces()) {
        Vec3 p[3];
        int k = 0;
        for (auto v : m.fv_range(f)) p[k++] = point(v);
        bounds.surfaceToOriginalMm = std::max(
            bounds.surfaceToOriginalMm, deviationBound(*original_, p[0], p[1], p[2], limits_));
        for (const Vec3& q : m.property(tracked_, f))
            bounds.originalToSurfaceMm =
                std::max(bounds.originalToSurfaceMm, pointTriangleDistance(q, p[0], p[1], p[2]));
    }
    return bounds;
}

}  // namespace dfrecon
