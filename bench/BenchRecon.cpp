// Reconstruction quality on every synth shape at 2 mm and 5 mm spacing.
// Distances by dense sampling against the analytic surface, both directions:
// reconstruction → surface with the exact signed distance, surface →
// reconstruction with exact point–triangle distances over a BVH.
// Systems: levin-mc (the baseline: fields interpolated in z, marching cubes
// at 0.5 mm voxels), dfrecon at default settings and dfrecon with
// --contour-error 0.1 (fields at their default pixel size). Then the end-to-end
// time of 100 slices x 500 points per contour (fields, axes, triangulation,
// writing a PLY).
#include <cstdio>
#include <filesystem>
#include <iostream>

#include <nlohmann/json.hpp>

#include "bench/Benchmarks.hpp"
#include "geometry/MeshCheck.hpp"
#include "geometry/TriangleBvh.hpp"
#include "io/MeshIO.hpp"
#include "recon/MarchingCubesBaselines.hpp"
#include "recon/Reconstruction.hpp"
#include "shapes/AnalyticShapes.hpp"
#include "simplify/SurfaceDistance.hpp"

namespace dfrecon::bench {

namespace {

struct SurfaceDistance {
    double hausdorffMm = 0, meanMm = 0;
};

SurfaceDistance measure(const AnalyticShape& shape, const TriangleSoup& soup) {
    constexpr std::size_t kSamples = 20000;
    SurfaceDistance d;
    double sum = 0;
    for (const Vec3& p : sampleTriangles(soup, kSamples, 7)) {
        const double e = std::abs(shape.signedDistance(p));
        d.hausdorffMm = std::max(d.hausdorffMm, e);
        sum += e;
    }
    const TriangleBvh bvh(soup);
    const std::vector<Vec3> surface = sampleSurface(shape, kSamples, 11);
    for (const Vec3& p : surface) {
        const double e = bvh.nearest(p).distance;
        d.hausdorffMm = std::max(d.hausdorffMm, e);
        sum += e;
    }
    d.meanMm = sum / double(kSamples + surface.size());
    return d;
}

void printRow(const std::string& caseName, const std::string& system, double seconds,
              const AnalyticShape& shape, const TriangleSoup& soup) {
    const MeshCheckReport check = checkMesh(soup);
    const SurfaceDistance distance = measure(shape, soup);
    std::cout << nlohmann::ordered_json{{"bench", "recon"},
                                        {"case", caseName},
                                        {"system", system},
                                        {"seconds", seconds},
                                        {"triangles", check.triangles},
                                        {"watertight", check.validSolid()},
                                        {"genus", check.genus},
                                        {"components", check.components},
                                        {"hausdorff_mm", distance.hausdorffMm},
                                        {"mean_dist_mm", distance.meanMm},
                                        {"volume_err_pct",
                                         100 * (check.volumeMm3 / shape.volumeMm3() - 1)}}
                     .dump()
              << std::endl;
}

// 100 slices of 500 points through the whole command path, the speed target
// of the reconstruction issue.
void benchEndToEnd(ocl::Runtime& runtime) {
    const auto shape = makeShape("ellipsoid");
    SynthOptions options;
    options.pointsPerContour = 500;
    // The synth slicer puts slices half a spacing in from each end.
    options.spacingMm = (shape->zMaxMm() - shape->zMinMm()) / 100.0;
    const ContourSet set = sliceShape(*shape, options);
    const std::string path =
        (std::filesystem::temp_directory_path() / "dfrecon-bench-recon.ply").string();
    Reconstruction result;
    const double seconds = bestSeconds(3, [&] {
        result = reconstructSurface(runtime, set.rois[0]);
        writeMesh(toTriMesh(result.surface), path);
    });
    std::remove(path.c_str());
    const ReconstructionStats& s = result.stats;
    std::cout << nlohmann::ordered_json{{"bench", "recon-speed"},
                                        {"case", "ellipsoid " + std::to_string(s.slices) +
                                                     " slices x 500 points"},
                                        {"system", "dfrecon"},
                                        {"seconds", seconds},
                                        {"pixel_mm", s.pixelMm},
                                        {"fields_s", s.fieldsSeconds},
                                        {"medial_s", s.medialSeconds},
                                        {"triangulation_s", s.triangulationSeconds},
                                        {"triangles", result.surface.triangles.size()}}
                     .dump()
              << std::endl;
}

}  // namespace

int benchRecon(const std::string& device) {
    ocl::Runtime runtime(device);
    {  // Warm-up: build the kernels outside the timed runs.
        const ContourSet warm = sliceShape(*makeShape("sphere"), {});
        reconstructSurface(runtime, warm.rois[0]);
    }
    for (const std::string& name : shapeNames())
        for (double spacing : {2.0, 5.0}) {
            const auto shape = makeShape(name);
            SynthOptions options;
            options.spacingMm = spacing;
            options.pointsPerContour = 128;
            const ContourSet set = sliceShape(*shape, options);
            const Roi& roi = set.rois[0];
            const std::string caseName = name + " " + std::to_string(int(spacing)) + " mm";
            TriMesh mesh;
            double seconds = bestSeconds(1, [&] {
                const SliceFields fields =
                    computeSliceFields(runtime, roi.slices, gridForSlices(roi.slices, 0.5));
                mesh = levinBaseline(fields);
            });
            printRow(caseName, "levin-mc", seconds, *shape, toTriangleSoup(mesh));
            for (double contourError : {0.0, 0.1}) {
                ReconstructionOptions recon;
                recon.contourErrorMm = contourError;
                Reconstruction result;
                seconds = bestSeconds(1, [&] { result = reconstructSurface(runtime, roi, recon); });
                printRow(caseName, contourError > 0 ? "dfrecon-ce0.1" : "dfrecon", seconds, *shape,
                         result.surface);
            }
            ReconstructionOptions smooth;
            smooth.interpolation = Interpolation::Smooth;
            Reconstruction result;
            seconds = bestSeconds(1, [&] { result = reconstructSurface(runtime, roi, smooth); });
            printRow(caseName, "dfrecon-smooth", seconds, *shape, result.surface);
        }
    benchEndToEnd(runtime);
    return 0;
}

}  // namespace dfrecon::bench
