#pragma once
// The error-bounded edge collapse as an OpenMesh Decimater module: a
// collapse is legal only if, afterwards,
//   (a) every point of every new triangle is within maxError of the
//       original surface (deviationBound over a BVH of the original), and
//   (b) every original vertex — contour points included — is within
//       maxError of the simplified surface: each is tracked on the face
//       nearest it, as OpenMesh's ModHausdorff tracks removed vertices, and
//       re-homed to the new faces when its face goes;
// and no new triangle collides with the rest of the surface. The priority
// is the larger of the two bounds, so the collapses that change the
// surface least go first (paper §6.2). Topology (link condition) and normal
// flips are left to the Decimater and ModNormalFlipping.
#if defined(__GNUC__)
#pragma GCC system_header  // OpenMesh's module macros are not -Wshadow clean
#endif
#include <vector>

#include <OpenMesh/Tools/Decimater/ModBaseT.hh>

#include "io/TriMesh.hpp"
#include "simplify/CollapseBound.hpp"
#include "simplify/FaceGrid.hpp"

namespace dfrecon {

class ModErrorBound : public OpenMesh::Decimater::ModBaseT<TriMesh> {
  public:
    using Base = OpenMesh::Decimater::ModBaseT<TriMesh>;
    using Self = ModErrorBound;
    using Handle = OpenMesh::Decimater::ModHandleT<ModErrorBound>;

    explicit ModErrorBound(TriMesh& mesh);
    ~ModErrorBound() override;

    const std::string& name() const override;

    /// The original surface and the bound; call before Decimater::initialize.
    /// `original` must outlive the module and be the mesh being decimated.
    void setOriginal(const TriangleBvh& original, double maxErrorMm);

    /// Priorities of the unchanged mesh for every halfedge (index =
    /// halfedge index; < 0 = illegal), e.g. from the OpenCL batch. Used
    /// until a collapse changes the halfedge's neighbourhood.
    void setInitialPriorities(std::vector<float> priorities);

    void initialize() override;
    float collapse_priority(const CollapseInfo& ci) override;
    void preprocess_collapse(const CollapseInfo& ci) override;
    void postprocess_collapse(const CollapseInfo& ci) override;

    /// The two bounds the current mesh meets: (a) over all faces, computed
    /// afresh, and (b) over all tracked original vertices.
    struct Bounds {
        double surfaceToOriginalMm = 0, originalToSurfaceMm = 0;
    };
    Bounds currentBounds();

    /// Collapses evaluated on the CPU / taken from the initial priorities.
    std::size_t cpuEvaluations = 0, initialEvaluations = 0;

  private:
    bool collides(const CollapseInfo& ci, const std::vector<NewTriangle>& created);
    Vec3 point(TriMesh::VertexHandle v) const;
    Box3 boxOf(TriMesh::FaceHandle f) const;

    const TriangleBvh* original_ = nullptr;
    DeviationLimits limits_;
    OpenMesh::FPropHandleT<std::vector<Vec3>> tracked_;
    std::vector<float> initial_;
    std::vector<char> touched_;  // per vertex: neighbourhood changed since initial_
    FaceGrid faces_;
    std::vector<Vec3> homeless_;  // tracked points of the faces being collapsed
    std::vector<NewTriangle> scratch_;
    std::vector<Vec3> trackedScratch_;
    DeviationCache cache_;
};

}  // namespace dfrecon
