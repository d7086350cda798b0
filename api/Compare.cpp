#include "dfrecon/Compare.hpp"

#include <stdexcept>

#include "api/Stopwatch.hpp"
#include "geometry/SurfaceMeasures.hpp"

namespace dfrecon {

Comparison compareSolids(ocl::Runtime& runtime, const ComparedSolid& a, const ComparedSolid& b,
                         const CompareOptions& options) {
    if (!a.check.validSolid() || !b.check.validSolid())
        throw std::invalid_argument(std::string("compare: surface ") +
                                    (a.check.validSolid() ? "B" : "A") +
                                    " is not a valid closed solid");
    Stopwatch watch;
    Comparison r;
    r.overlap = overlapOf(a.surface, b.surface, a.check, b.check);
    r.overlapSeconds = watch.lap();
    r.distances =
        surfaceDistances(runtime, a.surface, b.surface, options.spacingMm, options.toleranceMm);
    r.centroidDistanceMm =
        length(measureSurface(b.surface).centroidMm - measureSurface(a.surface).centroidMm);
    r.distanceSeconds = watch.lap();
    if (a.contours && b.contours) {
        PlaneComparisonOptions planes;
        planes.toleranceMm = options.toleranceMm;
        r.planes = comparePlanes(*a.contours, *b.contours, planes);
        r.planeSeconds = watch.lap();
    }
    return r;
}

}  // namespace dfrecon
