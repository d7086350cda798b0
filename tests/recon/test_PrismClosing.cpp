// Prism closings are the reconstruction's guaranteed pieces: whatever the
// two sides' contours, a slab closed by prisms between two capped ends is a
// valid closed solid. Checked with the independent mesh checker on the
// coincidences pixel contours make: shared edges (same side and opposite
// sides), shared corners, identical outlines, a corner on an edge.
#include <gtest/gtest.h>

#include <algorithm>

#include "geometry/MeshCheck.hpp"
#include "recon/PrismClosing.hpp"

namespace dfrecon {
namespace {

Polygon rectangle(double x0, double y0, double x1, double y1) {
    return {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
}

// The solid made of `lower` at z = 0 and `upper` at z = 2, closed between
// them by prisms and capped below and above (also by prisms).
MeshCheckReport closedSlab(std::vector<Polygon> lower, std::vector<Polygon> upper) {
    SurfaceBuilder builder;
    const Layer x = makeLayer(builder, 0, std::move(lower));
    const Layer y = makeLayer(builder, 2, std::move(upper));
    auto all = [](const Layer& layer) {
        LayerPart part{&layer, {}};
        for (std::uint32_t c = 0; c < layer.contours.size(); ++c) part.contours.push_back(c);
        return part;
    };
    closeByPrisms(builder, {}, all(x), -0.5);
    closeByPrisms(builder, all(x), all(y), 1);
    closeByPrisms(builder, all(y), {}, 2.5);
    return checkMesh(builder.soup());
}

void expectValid(const MeshCheckReport& r, double volume) {
    EXPECT_TRUE(r.validSolid()) << "boundary " << r.boundaryEdges << ", non-manifold edges "
                                << r.nonManifoldEdges << ", vertices " << r.nonManifoldVertices
                                << ", misoriented " << r.misorientedEdges << ", intersecting "
                                << r.intersectingPairs;
    EXPECT_NEAR(r.volumeMm3, volume, 1e-2);
}

TEST(PrismClosing, CrossingOutlinesCloseAsBefore) {
    expectValid(closedSlab({rectangle(0, 0, 2, 2)}, {rectangle(1, 1, 3, 3)}), 4 * 1.5 + 4 * 1.5);
}

TEST(PrismClosing, IdenticalOutlines) {
    expectValid(closedSlab({rectangle(0, 0, 2, 2)}, {rectangle(0, 0, 2, 2)}), 4 * 3);
}

TEST(PrismClosing, OutlinesSharingAnEdgeOnOppositeSides) {
    // Two boxes that would touch along an edge at the lid: a non-manifold
    // solid unless the closing keeps them apart.
    expectValid(closedSlab({rectangle(0, 0, 1, 1)}, {rectangle(1, 0, 2, 1)}), 1.5 + 1.5);
}

TEST(PrismClosing, OutlinesSharingAnEdgeOnTheSameSide) {
    expectValid(closedSlab({rectangle(0, 0, 2, 1)}, {rectangle(0, 0, 1, 1)}), 2 * 1.5 + 1.5);
}

TEST(PrismClosing, OutlinesSharingACorner) {
    expectValid(closedSlab({rectangle(0, 0, 1, 1)}, {rectangle(1, 1, 2, 2)}), 1.5 + 1.5);
}

TEST(PrismClosing, ACornerOnAnEdgeAndAStaircase) {
    const Polygon stairs{{0, 0}, {3, 0}, {3, 1}, {2, 1}, {2, 2}, {1, 2}, {1, 3}, {0, 3}};
    expectValid(closedSlab({stairs}, {rectangle(1, 1, 4, 2), rectangle(0, 2.5, 0.5, 3)}),
                6 * 1.5 + (3 + 0.25) * 1.5);
}

TEST(PrismClosing, BranchingWithHolesOnBothSides) {
    Polygon hole = rectangle(1, 1, 2, 2);
    std::reverse(hole.begin(), hole.end());
    expectValid(
        closedSlab({rectangle(0, 0, 3, 3), hole}, {rectangle(0, 0, 1, 3), rectangle(2, 0, 3, 3)}),
        8 * 1.5 + 6 * 1.5);
}

}  // namespace
}  // namespace dfrecon
