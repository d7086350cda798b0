#include "simplify/CheckedDecimater.hpp"

#include <queue>
#include <vector>

namespace dfrecon {

std::size_t CheckedDecimater::decimate() {
    if (!is_initialized()) return 0;
    struct Entry {
        float priority;
        int halfedge;
        std::uint32_t version;  // of the from-vertex when queued
        bool operator<(const Entry& other) const { return priority > other.priority; }
    };
    std::priority_queue<Entry> queue;  // cheapest on top
    std::vector<std::uint32_t> version(mesh_.n_vertices(), 0);

    // A vertex's cheapest legal collapse enters the queue; older entries of
    // the vertex are dropped when they surface (their version is behind).
    auto enqueue = [&](TriMesh::VertexHandle v) {
        const std::uint32_t now = ++version[std::size_t(v.idx())];
        float best = -1;
        TriMesh::HalfedgeHandle bestHalfedge;
        for (auto h : mesh_.voh_range(v)) {
            const CollapseInfo ci(mesh_, h);
            if (!is_collapse_legal(ci)) continue;
            const float priority = collapse_priority(ci);
            if (priority >= 0 && (best < 0 || priority < best)) {
                best = priority;
                bestHalfedge = h;
            }
        }
        if (best >= 0) queue.push({best, bestHalfedge.idx(), now});
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
        // Taken now: every module judges it again against the mesh as it is.
        const float priority = is_collapse_legal(ci) ? collapse_priority(ci) : -1;
        if (priority < 0 || priority > top.priority) {
            ++staleCollapses;
            enqueue(v0);
            continue;
        }
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
