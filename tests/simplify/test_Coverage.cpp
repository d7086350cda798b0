// Covering pieces of the original surface by faces of the simplified one.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "simplify/Coverage.hpp"

namespace dfrecon {
namespace {

double area(const OriginalPiece& t) {
    return 0.5 * length(cross(t.p[1] - t.p[0], t.p[2] - t.p[0]));
}

// Two faces folded along a shared edge (the y axis; A flat, B rising 0.3
// per mm) and a flat piece across the fold: neither face covers it alone,
// so halving alone would need parts down to the slack's size. Cut at the
// plane bisecting the fold it needs at most four, each within the limit of
// its face, together the whole piece, and the value bounds the distance of
// every point of the piece to the two faces.
TEST(Coverage, CutsAPieceAcrossTheEdgeBetweenTwoFaces) {
    const Vec3 o{0, 0, 0}, top{0, 10, 0}, left{-10, 5, 0}, right{10, 5, 3};
    const std::vector<CoverCandidate> faces{coverCandidate(o, top, left, {0, 1, 2}, 7),
                                            coverCandidate(top, o, right, {1, 0, 3}, 8)};
    const OriginalPiece piece{{{-4, 3, 0}, {4, 3, 1.2}, {-2, 7, 0}}};
    const DeviationLimits limits{0.75};
    for (const CoverCandidate& face : faces) EXPECT_GT(cornerDistance(piece, face), 0.75);

    std::vector<std::pair<OriginalPiece, int>> parts;
    const double d =
        coverPiece(piece, faces, {}, limits,
                   [&](const OriginalPiece& part, int k, double) { parts.emplace_back(part, k); });
    ASSERT_LE(d, 0.75);
    EXPECT_GE(parts.size(), 2u);
    EXPECT_LE(parts.size(), 4u);
    double total = 0;
    for (const auto& [part, k] : parts) {
        EXPECT_LE(cornerDistance(part, faces[std::size_t(k)]), d);
        total += area(part);
    }
    EXPECT_NEAR(total, area(piece), 1e-12 * area(piece));
    double sampled = 0;
    for (int i = 0; i <= 40; ++i)
        for (int j = 0; i + j <= 40; ++j) {
            const Vec3 q = piece.p[0] + (i / 40.0) * (piece.p[1] - piece.p[0]) +
                           (j / 40.0) * (piece.p[2] - piece.p[0]);
            sampled = std::max(sampled, std::min(pointTriangleDistance(q, o, top, left),
                                                 pointTriangleDistance(q, top, o, right)));
        }
    EXPECT_LE(sampled, d + 1e-12);
    EXPECT_GT(sampled, 0.5);  // the piece does rise off the fold
}

}  // namespace
}  // namespace dfrecon
