#include "simplify/CheckedDecimater.hpp"

#include <algorithm>
#include <limits>
#include <queue>
#include <vector>

namespace dfrecon {

std::size_t CheckedDecimater::decimate() {
    if (!is_initialized()) return 0;
    constexpr std::size_t kNotJudged = std::numeric_limits<std::size_t>::max();
    constexpr float kNothingQueued = std::numeric_limits<float>::infinity();
    struct Entry {
        float priority;  // the largest lower bound applied, or the priority when judged
        int halfedge;
        std::uint32_t version;  // of the from-vertex when queued
        std::size_t stage;      // lower bounds applied; lowerBounds_.size() once judged
        std::size_t judgedAt;   // collapses done when judged, or kNotJudged
        bool operator<(const Entry& other) const {
            // Cheapest on top; among equals the lower halfedge index, so runs
            // are reproducible.
            if (priority != other.priority) return priority > other.priority;
            return halfedge > other.halfedge;
        }
    };
    std::priority_queue<Entry> queue;
    std::vector<std::uint32_t> version(mesh_.n_vertices(), 0);

    // A vertex's collapses enter the queue with nothing known (priority 0):
    // a vertex is often re-queued several times before its entries surface,
    // and each stage is evaluated only when an entry is at the top, where it
    // can stop as soon as it is above the next one. The topology test
    // (is_collapse_legal) waits for the judgement too; it fails rarely.
    // Older entries of the vertex are dropped when they surface (version
    // behind).
    auto enqueue = [&](TriMesh::VertexHandle v) {
        const std::uint32_t now = ++version[std::size_t(v.idx())];
        if (mesh_.status(v).locked()) return;
        for (auto h : mesh_.voh_range(v)) queue.push({0.0f, h.idx(), now, 0, kNotJudged});
    };
    for (auto v : mesh_.vertices())
        if (!mesh_.status(v).deleted()) enqueue(v);

    const bool updateNormals = mesh_.has_face_normals();
    std::vector<TriMesh::VertexHandle> support;
    std::size_t collapses = 0;
    while (!queue.empty()) {
        const Entry top = queue.top();
        queue.pop();
        const TriMesh::HalfedgeHandle h(top.halfedge);
        const auto v0 = mesh_.from_vertex_handle(h);
        if (mesh_.status(v0).deleted() || top.version != version[std::size_t(v0.idx())]) continue;
        CollapseInfo ci(mesh_, h);
        // Tightened until judged in full, while still the cheapest; a verdict
        // holds while nothing else is collapsed.
        Entry entry = top;
        while (entry.judgedAt != collapses) {
            if (entry.stage < lowerBounds_.size()) {
                const float next = queue.empty() ? kNothingQueued : queue.top().priority;
                const float bound = lowerBounds_[entry.stage++](ci, next);
                entry.priority = bound < 0 ? bound : std::max(entry.priority, bound);
            } else {
                if (entry.judgedAt != kNotJudged) ++staleCollapses;
                entry.stage = lowerBounds_.size();
                entry.judgedAt = collapses;
                entry.priority = is_collapse_legal(ci) ? collapse_priority(ci) : -1;
            }
            if (entry.priority < 0) break;
            if (!queue.empty() && entry < queue.top()) {  // no longer the cheapest
                queue.push(entry);
                break;
            }
        }
        // Illegal until the vertex's ring changes (as in DecimaterT).
        if (entry.priority < 0 || entry.judgedAt != collapses) continue;
        support.assign(mesh_.vv_begin(v0), mesh_.vv_end(v0));
        preprocess_collapse(ci);
        mesh_.collapse(h);
        ++collapses;
        if (updateNormals)
            for (auto f : mesh_.vf_range(ci.v1)) mesh_.set_normal(f, mesh_.calc_face_normal(f));
        postprocess_collapse(ci);
        for (auto v : support)
            if (!mesh_.status(v).deleted()) enqueue(v);
    }
    return collapses;
}

}  // namespace dfrecon
