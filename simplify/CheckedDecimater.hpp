#pragma once
// OpenMesh's greedy decimation loop (DecimaterT::decimate), with one change:
// a collapse is evaluated again, by every module, at the moment it is taken.
// DecimaterT evaluates a vertex's collapses when the vertex enters the queue
// and again only when its own one-ring changes; a bound that also depends on
// the faces around that ring (ModErrorBound's coverage and collision test)
// can go stale in between. Here a stale entry is re-queued with its current
// priority instead of being collapsed. Modules, legality checks and the
// collapse itself are OpenMesh's (BaseDecimaterT).
#if defined(__GNUC__)
#pragma GCC system_header  // OpenMesh's headers are not -Wshadow clean
#endif
#include <OpenMesh/Tools/Decimater/BaseDecimaterT.hh>

#include "geometry/TriMesh.hpp"

namespace dfrecon {

class CheckedDecimater : public OpenMesh::Decimater::BaseDecimaterT<TriMesh> {
  public:
    explicit CheckedDecimater(TriMesh& mesh) : BaseDecimaterT<TriMesh>(mesh), mesh_(mesh) {}

    /// Collapses the cheapest legal halfedge until none is left; returns the
    /// number of collapses. Call initialize() first. O(collapses · (valence²
    /// evaluations + log V)).
    std::size_t decimate();

    /// Collapses found stale when taken (re-queued instead).
    std::size_t staleCollapses = 0;

  private:
    TriMesh& mesh_;
};

}  // namespace dfrecon
