// The shared triangle update (kernels/eikonal_update.cl through
// segment/LocalUpdate.hpp) against plane waves, whose arrival times a
// linear update must reproduce exactly.
#include "segment/LocalUpdate.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

using namespace dfrecon;

namespace {

struct Triangle2 {
    double ax, ay, bx, by;  // A and B relative to C = (0, 0)
    double la() const { return std::hypot(ax, ay); }
    double lb() const { return std::hypot(bx, by); }
    double cosC() const { return (ax * bx + ay * by) / (la() * lb()); }
};

}  // namespace

TEST(LocalUpdate, PlaneWaveThroughTheTriangleIsExact) {
    std::mt19937 random(7);
    std::uniform_real_distribution<double> length(0.2, 3.0), unit(0, 1);
    int across = 0;
    for (int trial = 0; trial < 2000; ++trial) {
        // An acute corner at C: A on the x axis, B at angle θ ≤ 90°.
        const double theta = 0.1 + (M_PI / 2 - 0.1) * unit(random);
        const double la = length(random), lb = length(random);
        const Triangle2 t{la, 0, lb * std::cos(theta), lb * std::sin(theta)};
        // A wave arriving at C from a direction inside the angle ACB.
        const double phi = theta * unit(random);
        const double slowness = 0.5 + unit(random);
        const double nx = -std::cos(phi) * slowness, ny = -std::sin(phi) * slowness;
        const double t0 = 10 * unit(random);  // T(C)
        const double ta = t0 + nx * t.ax + ny * t.ay, tb = t0 + nx * t.bx + ny * t.by;
        const TriangleUpdate u = triangleUpdate(ta, tb, {t.la(), t.lb(), t.cosC()}, slowness, true);
        EXPECT_NEAR(u.time, t0, 1e-12 * (1 + t0));
        if (u.upwind == Upwind::AcrossFace) {
            ++across;
            // The characteristic crosses AB at A + w(B − A), on the ray from C along −n.
            const double px = t.ax + u.weightB * (t.bx - t.ax),
                         py = t.ay + u.weightB * (t.by - t.ay);
            EXPECT_NEAR(std::atan2(py, px), phi, 1e-9);
        }
        EXPECT_LE(u.time, ta + t.la() * slowness + 1e-12);
    }
    EXPECT_GT(across, 1900);  // all but directions grazing an edge
}

TEST(LocalUpdate, WaveFromOutsideTheAngleTravelsAlongAnEdge) {
    // Right angle at C; a wave moving along +x+y... arriving from below the x axis.
    const double la = 1, lb = 1, cosC = 0;
    const double nx = -std::cos(-0.5), ny = -std::sin(-0.5);  // from direction −0.5 rad
    const double ta = nx * la, tb = ny * lb;                  // T(C) = 0
    const TriangleUpdate u = triangleUpdate(ta, tb, {la, lb, cosC}, 1.0, true);
    EXPECT_EQ(u.upwind, Upwind::AlongA);
    EXPECT_NEAR(u.time, ta + la, 1e-15);
}

TEST(LocalUpdate, UnknownCornerOnlyGivesItsEdge) {
    const double inf = std::numeric_limits<double>::infinity();
    const TriangleUpdate u = triangleUpdate(inf, 2.0, {1.0, 0.5, 0.3}, 2.0, false);
    EXPECT_EQ(u.upwind, Upwind::AlongB);
    EXPECT_DOUBLE_EQ(u.time, 3.0);
    EXPECT_DOUBLE_EQ(u.weightB, 1.0);
}

TEST(LocalUpdate, EquilateralTriangleFromTwoEqualTimes) {
    const TriangleUpdate u = triangleUpdate(0, 0, {1, 1, 0.5}, 1, true);
    EXPECT_EQ(u.upwind, Upwind::AcrossFace);
    EXPECT_NEAR(u.time, std::sqrt(0.75), 1e-15);
    EXPECT_NEAR(u.weightB, 0.5, 1e-15);
}

TEST(LocalUpdate, LabelsFollowTheUpwindCorner) {
    TriangleUpdate u;
    u.upwind = Upwind::AlongB;
    EXPECT_EQ(upwindLabel(u, 3, 4), 4);
    u.upwind = Upwind::AlongA;
    EXPECT_EQ(upwindLabel(u, 3, 4), 3);
    u.upwind = Upwind::AcrossFace;  // only ever asked with equal labels
    EXPECT_EQ(upwindLabel(u, 5, 5), 5);
}
