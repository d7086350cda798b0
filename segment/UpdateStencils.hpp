#pragma once
// The triangles each vertex is updated from, with obtuse angles unfolded
// (Kimmel & Sethian 1998; the paper's §2.1): both geodesic solvers iterate
// over these instead of over the mesh's triangles.
//
// Why: the triangle update is monotone (a vertex is only ever updated from
// smaller times) only when the angle at the updated vertex is at most 90°.
// For a triangle (C; A, B) obtuse at C, the walk crosses edge AB into the
// neighbouring triangles, unfolding each into the plane of (C, A, B), until
// it reaches a vertex W inside the cone at C where both angles ACW and WCB
// are acute; (C; A, W) and (C; W, B) — a "virtual" edge CW through the
// unfolded strip — then replace (C; A, B). If the walk meets the mesh
// boundary, comes back to C or takes more than maxUnfoldSteps triangles
// (counted in unfoldFailures), C is updated from A and B along the edges
// only: the stencil gets cosAngle = 1, an empty angle with no face update.
// With unfoldObtuse off, obtuse triangles are used as they are (for
// comparison: the scheme is then no longer monotone).
//
// The unfolding depends on geometry only, so it is done once per mesh; the
// solvers then need no mesh topology at all.
#include <vector>

#include "segment/MeshGraph.hpp"

namespace dfrecon {

/// Update C (the target) from A and B: |CA| = lengthA, |CB| = lengthB, the
/// angle ACB has cosine cosAngle (measured in the unfolded plane; 1 for
/// edge-only updates).
struct UpdateStencil {
    int a = 0, b = 0;
    double lengthA = 0, lengthB = 0, cosAngle = 0;
};

/// A stencil seen from one of its two corners: when `source` becomes known,
/// `target` may be updated through `stencil`.
struct StencilUse {
    int stencil = 0;
    int target = 0;
};

struct UnfoldOptions {
    bool unfoldObtuse = true;  // false: obtuse triangles are used as they are
    int maxUnfoldSteps = 20;   // triangles the walk may cross before it gives up
};

class UpdateStencils {
  public:
    /// O(T · s) for T triangles and s ≤ maxUnfoldSteps (obtuse corners only).
    UpdateStencils(const MeshGraph& graph, const UnfoldOptions& options = {});

    int vertexCount() const { return int(first_.size()) - 1; }
    /// The stencils that update vertex v: stencils()[first()[v] .. first()[v+1]).
    const std::vector<int>& first() const { return first_; }
    const std::vector<UpdateStencil>& stencils() const { return stencils_; }
    /// For each vertex s, the stencils in which it is a corner:
    /// uses()[useFirst()[s] .. useFirst()[s+1]).
    const std::vector<int>& useFirst() const { return useFirst_; }
    const std::vector<StencilUse>& uses() const { return uses_; }
    /// For each vertex s, the distinct vertices it may update (the targets
    /// of its uses): dependents()[dependentFirst()[s] .. dependentFirst()[s+1]).
    const std::vector<int>& dependentFirst() const { return dependentFirst_; }
    const std::vector<int>& dependents() const { return dependents_; }

    int obtuseCorners() const { return obtuseCorners_; }    // triangle corners over 90°
    int unfoldFailures() const { return unfoldFailures_; }  // of those, edges only
    double meanEdgeLength() const { return meanEdgeLength_; }

  private:
    std::vector<int> first_;
    std::vector<UpdateStencil> stencils_;
    std::vector<int> useFirst_;
    std::vector<StencilUse> uses_;
    std::vector<int> dependentFirst_;
    std::vector<int> dependents_;
    int obtuseCorners_ = 0;
    int unfoldFailures_ = 0;
    double meanEdgeLength_ = 0;
};

}  // namespace dfrecon
