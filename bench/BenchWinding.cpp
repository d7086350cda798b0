// Winding-number grid: the OpenCL kernel against its C++ reference on the
// same slices, with agreement. Prints JSON lines.
#include <iostream>

#include <nlohmann/json.hpp>

#include "bench/Benchmarks.hpp"
#include "io/AnalyticShapes.hpp"
#include "recon/WindingGrid.hpp"

namespace dfrecon::bench {

int benchWinding(const std::string& device) {
    ocl::Runtime runtime(device);
    for (int points : {64, 512}) {
        for (int pixels : {256, 512}) {
            SynthOptions options;
            options.pointsPerContour = points;
            const ContourSet set = sliceShape(*makeShape("torus"), options);
            const Slice& slice = set.rois[0].slices[set.rois[0].slices.size() / 2];
            Box2 box;
            for (const Polygon& c : slice.contours)
                for (Point2 p : c) box.add(p);
            const double pixelMm = (box.max.x - box.min.x) / (pixels - 8);
            const SliceGrid grid = gridAround(box, pixelMm, 4);

            std::vector<int> kernel, reference;
            windingGrid(runtime, slice.contours, grid);  // warm-up: program build
            const double kernelSeconds =
                bestSeconds(5, [&] { kernel = windingGrid(runtime, slice.contours, grid); });
            const double referenceSeconds =
                bestSeconds(2, [&] { reference = windingGridReference(slice.contours, grid); });
            std::size_t mismatches = 0;
            for (std::size_t k = 0; k < kernel.size(); ++k) mismatches += kernel[k] != reference[k];
            std::cout << nlohmann::ordered_json{{"bench", "winding"},
                                                {"case", std::to_string(pixels) + "px " +
                                                             std::to_string(2 * points) +
                                                             " segments"},
                                                {"system", "dfrecon"},
                                                {"size", grid.pixelCount()},
                                                {"segments", 2 * points},
                                                {"device", runtime.device().deviceName},
                                                {"seconds", kernelSeconds},
                                                {"baseline", "C++ reference, one thread"},
                                                {"baselineSeconds", referenceSeconds},
                                                {"speedup", referenceSeconds / kernelSeconds},
                                                {"mismatchedPixels", mismatches}}
                             .dump()
                      << "\n";
        }
    }
    return 0;
}

}  // namespace dfrecon::bench
