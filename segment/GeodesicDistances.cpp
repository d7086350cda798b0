#include "segment/GeodesicDistances.hpp"

#include <stdexcept>

#include "segment/EikonalFim.hpp"

namespace dfrecon {

const char* toString(GeodesicSolver solver) {
    switch (solver) {
        case GeodesicSolver::Automatic:
            return "automatic";
        case GeodesicSolver::FastMarching:
            return "fast-marching";
        case GeodesicSolver::FastIterative:
            return "fast-iterative-opencl";
    }
    return "?";
}

GeodesicSolver chooseGeodesicSolver(int vertexCount, const ocl::Runtime* runtime) {
    if (runtime && runtime->device().kind == ocl::DeviceKind::Gpu &&
        vertexCount >= kFimMinVerticesOnGpu)
        return GeodesicSolver::FastIterative;
    return GeodesicSolver::FastMarching;
}

GeodesicField geodesicDistances(const UpdateStencils& stencils,
                                const std::vector<GeodesicSource>& sources,
                                const std::vector<double>& speed, ocl::Runtime* runtime,
                                GeodesicSolver solver, GeodesicSolver* used) {
    if (solver == GeodesicSolver::Automatic)
        solver = chooseGeodesicSolver(stencils.vertexCount(), runtime);
    if (used) *used = solver;
    if (solver == GeodesicSolver::FastIterative) {
        if (!runtime)
            throw std::invalid_argument("the fast iterative method needs an OpenCL device");
        EikonalFim fim(*runtime, stencils, speed);
        return fim.solve(sources);
    }
    return FastMarching(stencils, speed).solve(sources);
}

}  // namespace dfrecon
