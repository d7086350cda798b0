#include "simplify/ModErrorBound.hpp"

#include <algorithm>
#include <array>
#include <stdexcept>

#include "geometry/MeshCheck.hpp"

namespace dfrecon {

ModErrorBound::ModErrorBound(TriMesh& mesh) : Base(mesh, false) {
    mesh.add_property(pieces_);
}

ModErrorBound::~ModErrorBound() {
    mesh().remove_property(pieces_);
}

const std::string& ModErrorBound::name() const {
    static const std::string name = "ErrorBound";
    return name;
}

void ModErrorBound::setOriginal(const DeviationSurface& original, double maxErrorMm) {
    if (!(maxErrorMm > 0)) throw std::invalid_argument("max error must be positive");
    original_ = &original;
    limits_.limitMm = maxErrorMm;
}

void ModErrorBound::setInitialDeviations(std::vector<float> deviations) {
    initial_ = std::move(deviations);
}

Vec3 ModErrorBound::point(TriMesh::VertexHandle v) const {
    return toVec3(const_cast<ModErrorBound*>(this)->mesh().point(v));
}

CoverCandidate ModErrorBound::candidateOf(TriMesh::FaceHandle f) const {
    Vec3 p[3];
    std::array<std::uint32_t, 3> vertices;
    std::size_t k = 0;
    for (auto v : const_cast<ModErrorBound*>(this)->mesh().fv_range(f)) {
        vertices[k] = std::uint32_t(v.idx());
        p[k++] = point(v);
    }
    return coverCandidate(p[0], p[1], p[2], vertices, f.idx());
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
        throw std::invalid_argument("ModErrorBound: one initial deviation per halfedge expected");
    touched_.assign(m.n_vertices(), 0);
    rimSeen_.assign(m.n_faces(), 0);
    // Every original triangle starts on itself (distance 0).
    pieces = 0;
    for (auto f : m.faces()) {
        const CoverCandidate c = candidateOf(f);
        m.property(pieces_, f) = {OriginalPiece{{c.p[0], c.p[1], c.p[2]}}};
        ++pieces;
    }
    double edgeSum = 0;
    for (auto e : m.edges()) edgeSum += m.calc_edge_length(e);
    faces_.reset(m.n_edges() ? 2 * edgeSum / double(m.n_edges()) : 1.0);
    for (auto f : m.faces()) faces_.insert(f.idx(), boxOf(f));
}

// Appends to candidates_ the faces around the neighbours of `centre` that do
// not contain `centre` itself: the ring just outside centre's faces.
void ModErrorBound::gatherRim(TriMesh::VertexHandle centre, TriMesh::VertexHandle skip) {
    TriMesh& m = mesh();
    ++rimCall_;
    for (auto w : m.vv_range(centre))
        for (auto f : m.vf_range(w)) {
            int& seen = rimSeen_[std::size_t(f.idx())];
            if (seen == rimCall_) continue;
            seen = rimCall_;
            bool inner = false;
            for (auto u : m.fv_range(f)) inner = inner || u == centre || u == skip;
            if (!inner) candidates_.push_back(candidateOf(f));
        }
}

// Direction (b): can every piece on the faces being replaced be covered by
// the created triangles or the unchanged faces just around them?
double ModErrorBound::coverage(const CollapseInfo& ci) {
    TriMesh& m = mesh();
    candidates_.clear();
    // created_ follows the order of v0's faces, skipping the edge's two; each
    // created triangle is what its face becomes (the collapse keeps handles).
    for (auto f : m.vf_range(ci.v0)) {
        if (f == ci.fl || f == ci.fr) continue;
        const NewTriangle& t = created_[candidates_.size()];
        candidates_.push_back(coverCandidate(t.p[0], t.p[1], t.p[2], t.ids, f.idx()));
    }
    gatherRim(ci.v0, ci.v0);
    judgedCover_.clear();
    judgedHalfedge_ = -1;
    double worst = 0;
    int created = 0;
    for (auto f : m.vf_range(ci.v0)) {
        // Each piece goes to its nearest candidate: a face that merely fits
        // would leave pieces at the bound and block later collapses (6 % more
        // triangles on the ellipsoid at 1 mm). The face a piece is on, once
        // created, is the likely nearest.
        const int likely = (f == ci.fl || f == ci.fr) ? -1 : created++;
        for (const OriginalPiece& piece : m.property(pieces_, f)) {
            worst = std::max(worst, coverPiece(piece, candidates_, {-1, likely}, limits_,
                                               [&](const OriginalPiece& part, int k, double) {
                                                   judgedCover_.emplace_back(
                                                       part, candidates_[std::size_t(k)].id);
                                               }));
            if (worst > limits_.limitMm) return worst;
        }
    }
    judgedHalfedge_ = ci.v0v1.idx();
    judgedAtCollapse_ = collapses_;
    return worst;
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

float ModErrorBound::deviationLowerBound(const CollapseInfo& ci, std::size_t maxPieces,
                                         double enough) {
    if (!trianglesAfterCollapse(mesh(), ci.v0v1, created_)) return ILLEGAL_COLLAPSE;
    if (batchValueHolds(ci)) return initial_[std::size_t(ci.v0v1.idx())];
    return surfaceDeviationLowerBound(created_, *original_, limits_, cache_, maxPieces, enough);
}

bool ModErrorBound::batchValueHolds(const CollapseInfo& ci) const {
    return !initial_.empty() && !touched_[std::size_t(ci.v0.idx())];
}

float ModErrorBound::deviation(const CollapseInfo& ci) {
    if (!trianglesAfterCollapse(mesh(), ci.v0v1, created_)) return ILLEGAL_COLLAPSE;
    if (batchValueHolds(ci)) {
        ++initialEvaluations;
        return initial_[std::size_t(ci.v0v1.idx())];
    }
    ++cpuEvaluations;
    return surfaceDeviation(created_, *original_, limits_, &cache_);
}

float ModErrorBound::collapse_priority(const CollapseInfo& ci) {
    const float deviation = this->deviation(ci);  // also fills created_
    if (deviation < 0) return ILLEGAL_COLLAPSE;
    // Cheapest first: the deviation is mostly a look-up (batch, cache).
    const double covered = coverage(ci);
    if (covered > limits_.limitMm) return ILLEGAL_COLLAPSE;
    if (collides(ci, created_)) return ILLEGAL_COLLAPSE;
    return std::max(float(covered), deviation);
}

void ModErrorBound::preprocess_collapse(const CollapseInfo& ci) {
    TriMesh& m = mesh();
    // The judgement's cover holds when it was of this collapse with nothing
    // collapsed since. When another judgement came between, the same
    // coverage runs again on the same mesh, so it gives the same answer —
    // unless a Decimater collapses what was not judged on this mesh: then
    // the pieces stay whole on a face the collapse keeps, and the final
    // bounds show it (simplifySurface then runs again with vertices locked).
    if (judgedHalfedge_ != ci.v0v1.idx() || judgedAtCollapse_ != collapses_) {
        ++coveredAgain;
        if (!trianglesAfterCollapse(m, ci.v0v1, created_) || coverage(ci) > limits_.limitMm) {
            judgedCover_.clear();
            int kept = -1;
            for (auto f : m.vf_range(ci.v0))
                if (kept < 0 && f != ci.fl && f != ci.fr) kept = f.idx();
            for (auto f : m.vf_range(ci.v0))
                for (const OriginalPiece& piece : m.property(pieces_, f))
                    judgedCover_.emplace_back(piece, kept);
        }
    }
    for (auto f : m.vf_range(ci.v0)) {
        auto& stored = m.property(pieces_, f);
        pieces -= stored.size();
        stored.clear();
    }
}

void ModErrorBound::postprocess_collapse(const CollapseInfo& ci) {
    TriMesh& m = mesh();
    for (const auto& [part, face] : judgedCover_)
        m.property(pieces_, TriMesh::FaceHandle(face)).push_back(part);
    pieces += judgedCover_.size();
    for (auto f : m.vf_range(ci.v1)) faces_.insert(f.idx(), boxOf(f));
    touched_[std::size_t(ci.v1.idx())] = 1;
    for (auto v : m.vv_range(ci.v1)) touched_[std::size_t(v.idx())] = 1;
    ++collapses_;
}

double ModErrorBound::piecesArea() {
    TriMesh& m = mesh();
    double area = 0;
    for (auto f : m.faces())
        for (const OriginalPiece& piece : m.property(pieces_, f))
            area += 0.5 * length(cross(piece.p[1] - piece.p[0], piece.p[2] - piece.p[0]));
    return area;
}

ModErrorBound::Bounds ModErrorBound::currentBounds() {
    TriMesh& m = mesh();
    Bounds bounds;
    for (auto f : m.faces()) {
        const CoverCandidate c = candidateOf(f);
        const NewTriangle t{c.vertices, {c.p[0], c.p[1], c.p[2]}};
        // The cached value: the same function of the same three vertices.
        const double deviation = cache_.bound(t, *original_, limits_);
        bounds.surfaceToOriginalMm = std::max(bounds.surfaceToOriginalMm, deviation);
        if (deviation > limits_.limitMm)
            bounds.outOfBound.insert(bounds.outOfBound.end(), c.p, c.p + 3);
        for (const OriginalPiece& piece : m.property(pieces_, f)) {
            const double d = cornerDistance(piece, c);
            bounds.originalToSurfaceMm = std::max(bounds.originalToSurfaceMm, d);
            if (d > limits_.limitMm)
                bounds.outOfBound.insert(bounds.outOfBound.end(), piece.p, piece.p + 3);
        }
    }
    return bounds;
}

}  // namespace dfrecon
