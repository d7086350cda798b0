#include "segment/GeodesicDistances.hpp"

#include <gtest/gtest.h>

#include "shapes/MeshShapes.hpp"

using namespace dfrecon;

TEST(GeodesicDistances, FastMarchingOnCpuDevicesAndWithoutOpenCL) {
    EXPECT_EQ(chooseGeodesicSolver(10, nullptr), GeodesicSolver::FastMarching);
    EXPECT_EQ(chooseGeodesicSolver(10'000'000, nullptr), GeodesicSolver::FastMarching);
    ocl::Runtime runtime;
    const GeodesicSolver big = chooseGeodesicSolver(10'000'000, &runtime);
    if (runtime.device().kind == ocl::DeviceKind::Gpu)
        EXPECT_EQ(big, GeodesicSolver::FastIterative);
    else
        EXPECT_EQ(big, GeodesicSolver::FastMarching);
    EXPECT_EQ(chooseGeodesicSolver(1000, &runtime), GeodesicSolver::FastMarching);
}

TEST(GeodesicDistances, BothSolversGiveTheSameField) {
    const MeshGraph graph = MeshGraph::fromSoup(geodesicSphere(12));
    const UpdateStencils stencils(graph);
    ocl::Runtime runtime;
    GeodesicSolver used = GeodesicSolver::Automatic;
    const GeodesicField marched =
        geodesicDistances(stencils, {{0, 0, 0}}, {}, &runtime, GeodesicSolver::FastMarching, &used);
    EXPECT_EQ(used, GeodesicSolver::FastMarching);
    const GeodesicField iterated = geodesicDistances(stencils, {{0, 0, 0}}, {}, &runtime,
                                                     GeodesicSolver::FastIterative, &used);
    EXPECT_EQ(used, GeodesicSolver::FastIterative);
    for (int v = 0; v < graph.vertexCount(); ++v)
        EXPECT_NEAR(marched.time[std::size_t(v)], iterated.time[std::size_t(v)], 1e-6);
    EXPECT_THROW(
        geodesicDistances(stencils, {{0, 0, 0}}, {}, nullptr, GeodesicSolver::FastIterative),
        std::invalid_argument);
    EXPECT_STREQ(toString(GeodesicSolver::FastMarching), "fast-marching");
}
