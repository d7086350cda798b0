#include "dfrecon/Compare.hpp"

#include <chrono>
#include <stdexcept>

#include "geometry/SurfaceMeasures.hpp"

namespace dfrecon {

namespace {

class Lap {
  public:
    double next() {
        const auto now = std::chrono::steady_clock::now();
        const double seconds = std::chrono::duration<double>(now - last_).count();
        last_ = now;
        return seconds;
    }

  private:
    std::chrono::steady_clock::time_point last_ = std::chrono::steady_clock::now();
};

}  // namespace

Comparison compareSolids(ocl::Runtime& runtime, const ComparedSolid& a, const ComparedSolid& b,
                         const CompareOptions& options) {
    if (!a.check.validSolid() || !b.check.validSolid())
        throw std::invalid_argument(std::string("compare: surface ") +
                                    (a.check.validSolid() ? "B" : "A") +
                                    " is not a valid closed solid");
    Lap lap;
    Comparison r;
    r.overlap = overlapOf(a.surface, b.surface, a.check, b.check);
    r.overlapSeconds = lap.next();
    r.distances =
        surfaceDistances(runtime, a.surface, b.surface, options.spacingMm, options.toleranceMm);
    r.centroidDistanceMm =
        length(measureSurface(b.surface).centroidMm - measureSurface(a.surface).centroidMm);
    r.distanceSeconds = lap.next();
    if (a.contours && b.contours) {
        PlaneComparisonOptions planes;
        planes.toleranceMm = options.toleranceMm;
        r.planes = comparePlanes(*a.contours, *b.contours, planes);
        r.planeSeconds = lap.next();
    }
    return r;
}

}  // namespace dfrecon
