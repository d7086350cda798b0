// Reconstructs a sliced sphere with the installed dfrecon library on the
// default OpenCL device, through the public API alone (include/dfrecon/), as
// a user's project would, and prints its volume beside the exact one, for
// tests/install/test_consumer.sh to compare.
#include <cmath>
#include <cstdio>
#include <exception>
#include <vector>

#include "dfrecon/dfrecon.hpp"

int main() {
    try {
        // A sphere of radius 20 mm cut at the centres of 2 mm slabs (z = -19,
        // -17, ... 19 mm), 64 points a contour.
        const double radiusMm = 20, spacingMm = 2, pi = std::acos(-1.0);
        dfrecon::RoiPoints sphere;
        sphere.name = "sphere";
        for (double z = -radiusMm + 0.5 * spacingMm; z < radiusMm; z += spacingMm) {
            const double r = std::sqrt(radiusMm * radiusMm - z * z);
            std::vector<dfrecon::Vec3> contour;
            for (int k = 0; k < 64; ++k)
                contour.push_back(
                    {r * std::cos(2 * pi * k / 64), r * std::sin(2 * pi * k / 64), z});
            sphere.contours.push_back(contour);
        }
        const dfrecon::ContoursRead read = dfrecon::structureSetFromPoints({sphere});
        dfrecon::ocl::Runtime runtime;
        const dfrecon::RoiSurface result =
            dfrecon::reconstructRoi(runtime, read.contours.rois.front());
        std::printf("volumeMm3 %.6f exactMm3 %.6f validSolid %d\n", result.check.volumeMm3,
                    4.0 / 3.0 * pi * radiusMm * radiusMm * radiusMm,
                    result.check.validSolid() ? 1 : 0);
        return 0;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "consumer: %s\n", e.what());
        return 1;
    }
}
