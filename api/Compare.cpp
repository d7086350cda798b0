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
    // The overlap and the distances take most of the time, about alike.
    auto report = [&](double fraction) {
        if (options.progress) options.progress(fraction);
    };
    Stopwatch watch;
    Comparison r;
    r.overlap = overlapOf(a.surface, b.surface, a.check, b.check);
    r.overlapSeconds = watch.lap();
    report(0.5);
    r.distances =
        surfaceDistances(runtime, a.surface, b.surface, options.spacingMm, options.toleranceMm);
    r.centroidDistanceMm =
        length(measureSurface(b.surface).centroidMm - measureSurface(a.surface).centroidMm);
    r.distanceSeconds = watch.lap();
    report(0.95);
    if (a.contours && b.contours) {
        PlaneComparisonOptions planes;
        planes.toleranceMm = options.toleranceMm;
        r.planes = comparePlanes(*a.contours, *b.contours, planes);
        r.planeSeconds = watch.lap();
    }
    report(1.0);
    return r;
}

}  // namespace dfrecon
