// ModErrorBound's homing of the original surface's pieces, driven one
// collapse at a time as CheckedDecimater drives it.
#include <gtest/gtest.h>

#include <cmath>
#include <utility>
#include <vector>

#include "recon/Reconstruction.hpp"
#include "shapes/AnalyticShapes.hpp"
#include "simplify/CheckedDecimater.hpp"
#include "simplify/InitialPriorities.hpp"
#include "simplify/ModErrorBound.hpp"

namespace dfrecon {
namespace {

// The torus reconstructed from 2 mm planes: slivers, as on real data.
TriangleSoup torusFromPlanes() {
    ocl::Runtime runtime("cpu");
    SynthOptions synth;
    synth.spacingMm = 2.0;
    return reconstructSurface(runtime, sliceShape(*makeShape("torus"), synth).rois[0]).surface;
}

// A CheckedDecimater over `mesh` with ModErrorBound alone, initialized (with
// the batch's values when given), for tests that drive collapses by hand.
struct Decimation {
    Decimation(TriMesh& mesh, const DeviationSurface& original, double limit,
               std::vector<float> initial = {})
        : decimater(mesh) {
        mesh.request_face_normals();
        mesh.update_face_normals();
        decimater.add(handle);
        module().setOriginal(original, limit);
        if (!initial.empty()) module().setInitialDeviations(std::move(initial));
        initialized = decimater.initialize();
    }
    ModErrorBound& module() { return decimater.module(handle); }
    CheckedDecimater decimater;
    ModErrorBound::Handle handle;
    bool initialized = false;
};

double area(const TriangleSoup& soup) {
    double total = 0;
    for (const auto& t : soup.triangles) {
        const Vec3 a = soup.points[t[0]], b = soup.points[t[1]], c = soup.points[t[2]];
        total += 0.5 * length(cross(b - a, c - a));
    }
    return total;
}

// A collapse is usually taken right after its judgement, and its pieces go
// where the judgement covered them; when another collapse was judged in
// between, they are covered afresh. Either way every piece stays on a face
// within the bound, and the pieces keep the original's area: none is lost
// or kept twice.
TEST(ModErrorBound, PiecesStayCoveredWhetherTakenAsJudgedOrNot) {
    const TriangleSoup input = torusFromPlanes();
    const DeviationSurface original(input);
    const double limit = 0.5;
    TriMesh mesh = toTriMesh(input);
    Decimation decimation(mesh, original, limit);
    ASSERT_TRUE(decimation.initialized);
    ModErrorBound& module = decimation.module();

    // The next legal collapse after halfedge `from`, and its priority.
    auto nextLegal = [&](int from) {
        for (int h = from + 1; h < int(mesh.n_halfedges()); ++h) {
            const TriMesh::HalfedgeHandle he(h);
            if (mesh.status(mesh.edge_handle(he)).deleted() || !mesh.is_collapse_ok(he)) continue;
            if (module.collapse_priority(ModErrorBound::CollapseInfo(mesh, he)) >= 0) return h;
        }
        return -1;
    };
    int taken = -1, collapses = 0;
    while (collapses < 300 && (taken = nextLegal(taken)) >= 0) {
        const ModErrorBound::CollapseInfo ci(mesh, TriMesh::HalfedgeHandle(taken));
        if (collapses % 2 == 1) nextLegal(taken);  // judges another one in between
        module.preprocess_collapse(ci);
        mesh.collapse(ci.v0v1);
        for (auto f : mesh.vf_range(ci.v1)) mesh.set_normal(f, mesh.calc_face_normal(f));
        module.postprocess_collapse(ci);
        ++collapses;
    }
    ASSERT_EQ(collapses, 300);
    EXPECT_GE(module.coveredAgain, 100u);  // both ways exercised
    EXPECT_LE(module.coveredAgain, 200u);
    const ModErrorBound::Bounds bounds = module.currentBounds();
    EXPECT_LE(bounds.originalToSurfaceMm, limit);
    EXPECT_LE(bounds.surfaceToOriginalMm, limit);
    EXPECT_NEAR(module.piecesArea(), area(input), 1e-9 * area(input));
}

// A collapse allowed by its batch value (compared in double) can create a
// triangle exactly at the limit. The final bounds, read from the cache, must
// still certify it: when the cache rounded bounds up to a float, such faces
// sent whole Brodmann ROIs into the locked-vertex retries.
TEST(ModErrorBound, FinalBoundsCertifyATriangleExactlyAtTheLimit) {
    const TriangleSoup input = torusFromPlanes();
    const DeviationSurface original(input);
    const TriMesh unchanged = toTriMesh(input);
    const std::vector<float> loose = initialPrioritiesReference(unchanged, original, 1.0);
    int tried = 0;
    for (std::size_t h = 0; h < loose.size() && tried < 10; ++h) {
        if (!(loose[h] > 0.05f)) continue;
        // The limit: this collapse's deviation itself, in double.
        TriMesh mesh = toTriMesh(input);
        const TriMesh::HalfedgeHandle he{int(h)};
        std::vector<NewTriangle> created;
        if (!mesh.is_collapse_ok(he) || !trianglesAfterCollapse(mesh, he, created)) continue;
        double limit = 0;
        for (const NewTriangle& t : created)
            limit = std::max(limit, deviationBound(original, t.p[0], t.p[1], t.p[2], {1.0}));
        Decimation decimation(mesh, original, limit,
                              initialPrioritiesReference(mesh, original, limit));
        ASSERT_TRUE(decimation.initialized);
        ModErrorBound& module = decimation.module();
        const ModErrorBound::CollapseInfo ci(mesh, he);
        if (module.collapse_priority(ci) < 0) continue;  // (b) over the limit
        ++tried;
        module.preprocess_collapse(ci);
        mesh.collapse(he);
        module.postprocess_collapse(ci);
        const ModErrorBound::Bounds bounds = module.currentBounds();
        EXPECT_LE(bounds.surfaceToOriginalMm, limit) << "halfedge " << h;
        EXPECT_LE(bounds.originalToSurfaceMm, limit) << "halfedge " << h;
    }
    EXPECT_EQ(tried, 10);
}

}  // namespace
}  // namespace dfrecon
