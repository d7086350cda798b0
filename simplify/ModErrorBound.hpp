#pragma once
// The error-bounded edge collapse as an OpenMesh Decimater module: a
// collapse is legal only if, afterwards,
//   (a) every point of every new triangle is within maxError of the
//       original surface (deviationBound over the original's hierarchy and
//       vertex fans), and
//   (b) every point of the original surface is within maxError of the
//       simplified one: the original triangles are kept on faces that cover
//       them (Coverage.hpp), split where no single face does, and moved to
//       the faces that replace theirs as the judgement of the collapse
//       covered them — as OpenMesh's ModHausdorff keeps removed vertices,
//       but for whole triangles;
// and no new triangle collides with the rest of the surface. The priority
// is the larger of the two bounds, so the collapses that change the
// surface least go first (paper §6.2). Topology (link condition) and normal
// flips are left to the Decimater and ModNormalFlipping.
#if defined(__GNUC__)
#pragma GCC system_header  // OpenMesh's module macros are not -Wshadow clean
#endif
#include <utility>
#include <vector>

#include <OpenMesh/Tools/Decimater/ModBaseT.hh>

#include "geometry/TriMesh.hpp"
#include "simplify/CollapseBound.hpp"
#include "simplify/Coverage.hpp"
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
    void setOriginal(const DeviationSurface& original, double maxErrorMm);

    /// surfaceDeviation of every halfedge of the unchanged mesh (index =
    /// halfedge index; < 0 = illegal), e.g. from the OpenCL batch. Used
    /// until a collapse changes the halfedge's neighbourhood.
    void setInitialDeviations(std::vector<float> deviations);

    void initialize() override;
    float collapse_priority(const CollapseInfo& ci) override;
    /// Lower bounds of collapse_priority (or < 0 when it is surely
    /// illegal) for CheckedDecimater's lazy queue, direction (a) only:
    /// the batch's value, or surfaceDeviationLowerBound from the first
    /// maxPieces pieces of each created triangle (cached; SIZE_MAX for the
    /// deviation itself, which collapse_priority then looks up), stopping
    /// once above `enough`.
    float deviationLowerBound(const CollapseInfo& ci, std::size_t maxPieces,
                              double enough = INFINITY);
    void preprocess_collapse(const CollapseInfo& ci) override;
    void postprocess_collapse(const CollapseInfo& ci) override;

    /// The two bounds the current mesh meets: (a) over all faces (from the
    /// cache), and (b) over all original pieces and the faces covering them.
    struct Bounds {
        double surfaceToOriginalMm = 0, originalToSurfaceMm = 0;
        std::vector<Vec3> outOfBound;  // corners of faces or pieces over the bound
    };
    Bounds currentBounds();

    /// Deviations evaluated on the CPU / taken from the initial batch.
    std::size_t cpuEvaluations = 0, initialEvaluations = 0;
    /// Collapses whose pieces were covered again when made, not taken from
    /// their judgement (another judgement came between; rare).
    std::size_t coveredAgain = 0;
    /// The total area of the original pieces kept on the faces: the
    /// original surface's, whatever was collapsed. O(pieces).
    double piecesArea();

    /// Original pieces stored (grows as pieces are split between faces).
    std::size_t pieces = 0;

  private:
    /// Direction (a): the batch's value, or surfaceDeviation (cached).
    float deviation(const CollapseInfo& ci);
    bool batchValueHolds(const CollapseInfo& ci) const;
    /// Direction (b), also kept as judgedCover_ when every piece is covered:
    /// the pieces of the collapsed faces go there when the collapse is made.
    double coverage(const CollapseInfo& ci);
    void gatherRim(TriMesh::VertexHandle centre, TriMesh::VertexHandle skip);
    bool collides(const CollapseInfo& ci, const std::vector<NewTriangle>& created);
    Vec3 point(TriMesh::VertexHandle v) const;
    Box3 boxOf(TriMesh::FaceHandle f) const;
    CoverCandidate candidateOf(TriMesh::FaceHandle f) const;

    const DeviationSurface* original_ = nullptr;
    DeviationLimits limits_;
    OpenMesh::FPropHandleT<std::vector<OriginalPiece>> pieces_;
    std::vector<float> initial_;
    std::vector<char> touched_;  // per vertex: neighbourhood changed since initial_
    FaceGrid faces_;
    std::vector<NewTriangle> created_;
    std::vector<CoverCandidate> candidates_;
    // The last coverage that covered every piece: parts and the face
    // covering each (created triangles by the face they replace), valid for
    // that halfedge while no collapse is made.
    std::vector<std::pair<OriginalPiece, int>> judgedCover_;
    int judgedHalfedge_ = -1;
    std::size_t judgedAtCollapse_ = 0, collapses_ = 0;
    std::vector<int> rimSeen_;  // per face: the gatherRim call that last took it
    int rimCall_ = 0;
    DeviationCache cache_;
};

}  // namespace dfrecon
