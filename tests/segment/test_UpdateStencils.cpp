#include "segment/UpdateStencils.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "shapes/MeshShapes.hpp"

using namespace dfrecon;

TEST(UpdateStencils, AcuteMeshKeepsItsTriangles) {
    const MeshGraph graph = MeshGraph::fromSoup(geodesicSphere(4));
    const UpdateStencils stencils(graph);
    EXPECT_EQ(stencils.obtuseCorners(), 0);
    EXPECT_EQ(stencils.stencils().size(), graph.triangles().size() * 3);
    for (int c = 0; c < graph.vertexCount(); ++c)
        for (int k = stencils.first()[std::size_t(c)]; k < stencils.first()[std::size_t(c) + 1];
             ++k) {
            const UpdateStencil& s = stencils.stencils()[std::size_t(k)];
            EXPECT_NEAR(s.lengthA, length(graph.point(s.a) - graph.point(c)), 1e-12);
            EXPECT_NEAR(s.lengthB, length(graph.point(s.b) - graph.point(c)), 1e-12);
        }
}

TEST(UpdateStencils, UnfoldedStencilsAreAcuteAndExactOnAPlane) {
    // Flat, so an unfolded vertex lies where it really is: the virtual edge
    // and angle must match the true distance and angle.
    const MeshGraph graph = MeshGraph::fromSoup(staggeredGrid(12, 30, 1.0, 0.2));
    const UpdateStencils stencils(graph);
    EXPECT_GT(stencils.obtuseCorners(), 600);
    // Only corners at the grid's border may fail (the walk leaves the mesh).
    EXPECT_LT(stencils.unfoldFailures(), stencils.obtuseCorners() / 10);
    int virtualStencils = 0, edgeOnly = 0;
    for (int c = 0; c < graph.vertexCount(); ++c)
        for (int k = stencils.first()[std::size_t(c)]; k < stencils.first()[std::size_t(c) + 1];
             ++k) {
            const UpdateStencil& s = stencils.stencils()[std::size_t(k)];
            const Vec3 a = graph.point(s.a) - graph.point(c), b = graph.point(s.b) - graph.point(c);
            EXPECT_NEAR(s.lengthA, length(a), 1e-9);
            EXPECT_NEAR(s.lengthB, length(b), 1e-9);
            const double cosine = dot(a, b) / (length(a) * length(b));
            if (cosine < 0) {  // a failed unfolding: edges only
                EXPECT_EQ(s.cosAngle, 1.0);
                ++edgeOnly;
                continue;
            }
            EXPECT_NEAR(s.cosAngle, cosine, 1e-9);
            bool isTriangle = false;
            for (int t : graph.trianglesAround(c))
                isTriangle |= graph.cornerOf(t, s.a) >= 0 && graph.cornerOf(t, s.b) >= 0;
            if (!isTriangle) {
                ++virtualStencils;
                EXPECT_GE(s.cosAngle, 0.0);
            }
        }
    EXPECT_EQ(virtualStencils, 2 * (stencils.obtuseCorners() - stencils.unfoldFailures()));
    EXPECT_EQ(edgeOnly, stencils.unfoldFailures());
}

TEST(UpdateStencils, WithoutUnfoldingObtuseTrianglesStay) {
    const MeshGraph graph = MeshGraph::fromSoup(staggeredGrid(8, 8, 1.0, 0.2));
    UnfoldOptions options;
    options.unfoldObtuse = false;
    const UpdateStencils stencils(graph, options);
    EXPECT_GT(stencils.obtuseCorners(), 0);
    EXPECT_EQ(stencils.stencils().size(), graph.triangles().size() * 3);
}

TEST(UpdateStencils, UsesAndDependentsMirrorTheStencils) {
    const MeshGraph graph = MeshGraph::fromSoup(staggeredGrid(6, 8, 1.0, 0.25));
    const UpdateStencils stencils(graph);
    std::size_t uses = 0;
    for (int s = 0; s < graph.vertexCount(); ++s)
        for (int k = stencils.useFirst()[std::size_t(s)];
             k < stencils.useFirst()[std::size_t(s) + 1]; ++k) {
            const StencilUse use = stencils.uses()[std::size_t(k)];
            const UpdateStencil& st = stencils.stencils()[std::size_t(use.stencil)];
            EXPECT_TRUE(st.a == s || st.b == s);
            EXPECT_GE(use.stencil, stencils.first()[std::size_t(use.target)]);
            EXPECT_LT(use.stencil, stencils.first()[std::size_t(use.target) + 1]);
            const auto first =
                stencils.dependents().begin() + stencils.dependentFirst()[std::size_t(s)];
            const auto last =
                stencils.dependents().begin() + stencils.dependentFirst()[std::size_t(s) + 1];
            EXPECT_TRUE(std::binary_search(first, last, use.target));
            ++uses;
        }
    EXPECT_EQ(uses, 2 * stencils.stencils().size());
}
