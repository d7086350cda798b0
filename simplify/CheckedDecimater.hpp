#pragma once
// OpenMesh's greedy decimation loop (DecimaterT::decimate), lazily
// evaluated and checked when taken. Every halfedge enters the queue with
// nothing known of its priority (0); each time an entry reaches the top its
// bound is tightened (the next, dearer lower bound, at last the judgement of
// every module), and it goes back unless the new value is still the
// smallest in the queue; a judged entry at the top is taken. So the
// collapse taken is the cheapest of those legal when judged, as in
// DecimaterT, but the expensive judgement runs for the few halfedges that
// reach the top instead of every halfedge around every changed vertex; and
// a verdict is never stale: a bound that also depends on the faces around a
// vertex's ring (ModErrorBound's coverage and collision test) is judged
// again unless nothing was collapsed since. As in DecimaterT, a collapse
// judged illegal is dropped until its vertex is queued again; as the moment
// it surfaces depends on the lower bounds, so, slightly, does the order.
// Modules, legality checks and the collapse itself are OpenMesh's
// (BaseDecimaterT).
#if defined(__GNUC__)
#pragma GCC system_header  // OpenMesh's headers are not -Wshadow clean
#endif
#include <functional>
#include <vector>

#include <OpenMesh/Tools/Decimater/BaseDecimaterT.hh>

#include "geometry/TriMesh.hpp"

namespace dfrecon {

class CheckedDecimater : public OpenMesh::Decimater::BaseDecimaterT<TriMesh> {
  public:
    explicit CheckedDecimater(TriMesh& mesh) : BaseDecimaterT<TriMesh>(mesh), mesh_(mesh) {}

    /// Lower bounds of the modules' priority of a collapse (what
    /// collapse_priority would return, if legal), cheapest and loosest
    /// first, each < 0 when the collapse is surely illegal. Each time a
    /// halfedge reaches the top it is judged by the next, and by
    /// collapse_priority (after is_collapse_legal) after the last. They
    /// may depend only on the from-vertex's faces (a changed ring re-queues
    /// the vertex). With none, every queued halfedge is judged in full.
    /// The second argument is the priority of the queue's next entry (∞
    /// when there is none): a lower bound may stop early at any value above
    /// it, since the halfedge is then surely not the cheapest and goes back
    /// into the queue.
    using LowerBound = std::function<float(const CollapseInfo&, float enough)>;
    void setLowerBounds(std::vector<LowerBound> lowerBounds) {
        lowerBounds_ = std::move(lowerBounds);
    }

    /// Collapses the cheapest legal halfedge until none is left; returns the
    /// number of collapses. Call initialize() first. O(collapses · valence²
    /// lower bounds + judged · judgement + pushes · log pushes).
    std::size_t decimate();

    /// Judgements in full repeated because other collapses came between
    /// (the first verdict might no longer hold).
    std::size_t staleCollapses = 0;

  private:
    TriMesh& mesh_;
    std::vector<LowerBound> lowerBounds_;
};

}  // namespace dfrecon
