// Slab volumes: the targets against exact integrals of section areas, the
// measured volumes against solids whose slab volumes are known.
#include <gtest/gtest.h>

#include <cmath>

#include "recon/SlabVolumes.hpp"

namespace dfrecon {
namespace {

Polygon square(double side, Point2 at) {
    return {{at.x, at.y}, {at.x + side, at.y}, {at.x + side, at.y + side}, {at.x, at.y + side}};
}

}  // namespace

TEST(SlabVolumes, TargetsIntegrateQuadraticAreasExactlyInside) {
    // A ball's sections: A(z) = π (R² − z²), quadratic in z. Slabs whose two
    // planes both have neighbours get the exact integral; unevenly spaced.
    const double r = 10;
    PlaneSections planes;
    for (double z : {-9.0, -6.0, -2.5, 0.0, 1.5, 5.0, 8.0}) {
        planes.zMm.push_back(z);
        planes.areaMm2.push_back(M_PI * (r * r - z * z));
        planes.perimeterMm.push_back(2 * M_PI * std::sqrt(r * r - z * z));
    }
    const std::vector<double> targets = slabVolumeTargets(planes);
    ASSERT_EQ(targets.size(), 6u);
    auto exact = [&](double a, double b) {
        auto f = [&](double z) { return M_PI * (r * r * z - z * z * z / 3); };
        return f(b) - f(a);
    };
    for (std::size_t s = 1; s + 1 < targets.size(); ++s)
        EXPECT_NEAR(targets[s], exact(planes.zMm[s], planes.zMm[s + 1]), 1e-9 * targets[s]) << s;
    // End slabs: the end tangent is the secant, so they lie between the
    // trapezoid and the exact value.
    for (std::size_t s : {std::size_t(0), targets.size() - 1}) {
        const double h = planes.zMm[s + 1] - planes.zMm[s];
        const double trapezoid = 0.5 * h * (planes.areaMm2[s] + planes.areaMm2[s + 1]);
        EXPECT_GT(targets[s], trapezoid);
        EXPECT_LT(targets[s], exact(planes.zMm[s], planes.zMm[s + 1]));
    }
}

TEST(SlabVolumes, AStraightStretchLendsNoSlopeToTheSlabWhereItEnds) {
    // Three equal sections (a tube), then a larger one: the tangent at the
    // tube's last plane is 0, as the field's is there (recon/HermiteTangents),
    // so the last slab's target is h/2 (A2 + A3) + h²/12 (0 − 60), not the
    // parabola's h²/12 (30 − 60).
    const PlaneSections planes{{0, 1, 2, 3}, {100, 100, 100, 160}, {40, 40, 40, 50}};
    const std::vector<double> targets = slabVolumeTargets(planes);
    ASSERT_EQ(targets.size(), 3u);
    EXPECT_NEAR(targets[0], 100, 1e-9);
    EXPECT_NEAR(targets[1], 100, 1e-9);
    EXPECT_NEAR(targets[2], 130 - 60.0 / 12, 1e-9);
}

TEST(SlabVolumes, SectionsAreNetAreasAndPerimeters) {
    Slice slice{2, {square(4, {0, 0}), square(1, {1, 1})}};
    std::reverse(slice.contours[1].begin(), slice.contours[1].end());  // a hole
    const PlaneSections planes = sectionsOf({slice});
    EXPECT_DOUBLE_EQ(planes.zMm[0], 2);
    EXPECT_DOUBLE_EQ(planes.areaMm2[0], 15);
    EXPECT_DOUBLE_EQ(planes.perimeterMm[0], 20);
}

TEST(SlabVolumes, MeasuredVolumesOfAShearedPrism) {
    // A unit square extruded through planes z = 0, 1, 3 and sheared (x moves
    // with z): every slab holds area × height (Cavalieri), whatever the shear.
    TriangleSoup soup;
    const std::vector<double> z{0, 1, 3};
    for (double h : z) {
        const double dx = 0.7 * h;
        for (Point2 p : square(1, {dx, 0})) soup.points.push_back({p.x, p.y, h});
    }
    std::vector<std::uint32_t> pieceOf;
    auto add = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t piece) {
        soup.triangles.push_back({a, b, c});
        pieceOf.push_back(piece);
    };
    // Walls of slab s between rings s and s + 1 (outward: the square is
    // counter-clockwise seen from above).
    for (std::uint32_t s = 0; s < 2; ++s)
        for (std::uint32_t k = 0; k < 4; ++k) {
            const std::uint32_t a = 4 * s + k, b = 4 * s + (k + 1) % 4;
            add(a, b, b + 4, s + 1);
            add(a, b + 4, a + 4, s + 1);
        }
    add(0, 2, 1, 0);  // bottom lid, piece 0
    add(0, 3, 2, 0);
    add(8, 9, 10, 3);  // top lid, piece 3
    add(8, 10, 11, 3);
    PlaneSections planes;
    planes.zMm = z;
    planes.areaMm2 = {1, 1, 1};
    planes.perimeterMm = {4, 4, 4};
    const std::vector<double> volumes = slabVolumes(soup, pieceOf, planes);
    ASSERT_EQ(volumes.size(), 2u);
    EXPECT_NEAR(volumes[0], 1, 1e-12);
    EXPECT_NEAR(volumes[1], 2, 1e-12);
}

}  // namespace dfrecon
