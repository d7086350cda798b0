// Reconstructs a sliced sphere with the installed dfrecon libraries on the
// default OpenCL device and prints its volume beside the exact one, for
// tests/install/test_consumer.sh to compare.
#include <cstdio>
#include <exception>

#include "cl/Runtime.hpp"
#include "dfrecon/dfrecon.hpp"
#include "shapes/AnalyticShapes.hpp"

int main() {
    try {
        const auto sphere = dfrecon::makeShape("sphere");  // radius 20 mm
        dfrecon::SynthOptions slicing;
        slicing.spacingMm = 2.0;
        const dfrecon::ContourSet contours = dfrecon::sliceShape(*sphere, slicing);
        dfrecon::ocl::Runtime runtime;
        // The public API (include/dfrecon/), as the program and Python use it.
        const dfrecon::RoiSurface result = dfrecon::reconstructRoi(runtime, contours.rois.front());
        std::printf("volumeMm3 %.6f exactMm3 %.6f validSolid %d\n", result.check.volumeMm3,
                    sphere->volumeMm3(), result.check.validSolid() ? 1 : 0);
        return 0;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "consumer: %s\n", e.what());
        return 1;
    }
}
