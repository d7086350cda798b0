// Reconstruction quality on every synth shape at 2 mm and 5 mm spacing: the
// closed-form shapes and the between-planes family (tilted, bent, thin,
// necked, branching; shapes/BetweenPlanesShapes).
// Distances by dense sampling against the analytic surface, both directions:
// reconstruction → surface with the exact signed distance (the bounded
// smooth union through shapes/SurfaceReference), surface → reconstruction
// with exact point–triangle distances over a BVH. Each row also splits the
// errors by where they lie between the contour planes (bench/SlabErrors),
// because that is where interpolation sags.
// Systems: levin-mc (the baseline: fields interpolated in z, marching cubes
// at 0.5 mm voxels), dfrecon at default settings (smooth), dfrecon with
// --contour-error 0.1 (fields at their default pixel size) and dfrecon with
// --interpolation linear. Then the end-to-end
// time of 100 slices x 500 points per contour (fields, axes, triangulation,
// writing a PLY).
#include <cstdio>
#include <filesystem>
#include <iostream>

#include <nlohmann/json.hpp>

#include "baselines/MarchingCubesBaselines.hpp"
#include "bench/Benchmarks.hpp"
#include "bench/SlabErrors.hpp"
#include "geometry/MeshCheck.hpp"
#include "geometry/TriangleBvh.hpp"
#include "io/mesh/MeshIO.hpp"
#include "recon/Reconstruction.hpp"
#include "shapes/AnalyticShapes.hpp"
#include "shapes/SurfaceReference.hpp"
#include "simplify/SimplificationVerifier.hpp"

namespace dfrecon::bench {

namespace {

constexpr std::size_t kSamples = 20000;

// What a case measures against: the true surface, points on it, and the
// contour planes.
struct Truth {
    const AnalyticShape& shape;
    const SurfaceReference& reference;
    const std::vector<Vec3>& surfaceSamples;
    std::vector<double> planesMm;
};

struct TruthDistance {
    double hausdorffMm = 0, meanMm = 0;
    std::vector<ErrorSample> errors;  // both directions, with their z
};

TruthDistance measure(const Truth& truth, const TriangleSoup& soup) {
    TruthDistance d;
    double sum = 0;
    for (const Vec3& p : sampleTriangles(soup, kSamples, 7)) {
        const double e = truth.reference.distance(p);
        d.errors.push_back({p.z, e});
        d.hausdorffMm = std::max(d.hausdorffMm, e);
        sum += e;
    }
    const TriangleBvh bvh(soup);
    for (const Vec3& p : truth.surfaceSamples) {
        const double e = bvh.nearest(p).distance;
        d.errors.push_back({p.z, e});
        d.hausdorffMm = std::max(d.hausdorffMm, e);
        sum += e;
    }
    d.meanMm = sum / double(d.errors.size());
    return d;
}

void printRow(const std::string& caseName, const std::string& system, double seconds,
              const Truth& truth, const TriangleSoup& soup) {
    const MeshCheckReport check = checkMesh(soup);
    const TruthDistance distance = measure(truth, soup);
    const SlabErrors split = splitBySlabPosition(distance.errors, truth.planesMm);
    std::cout
        << nlohmann::ordered_json{{"bench", "recon"},
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
                                   100 * (check.volumeMm3 / truth.shape.volumeMm3() - 1)},
                                  {"planes", truth.planesMm.size()},
                                  {"slab_mean_mm", orNull(split.slab, &ErrorStats::meanMm)},
                                  {"near_plane_mean_mm",
                                   orNull(split.nearPlane, &ErrorStats::meanMm)},
                                  {"near_plane_p95_mm",
                                   orNull(split.nearPlane, &ErrorStats::p95Mm)},
                                  {"near_plane_max_mm",
                                   orNull(split.nearPlane, &ErrorStats::maxMm)},
                                  {"mid_slab_mean_mm", orNull(split.midSlab, &ErrorStats::meanMm)},
                                  {"mid_slab_p95_mm", orNull(split.midSlab, &ErrorStats::p95Mm)},
                                  {"mid_slab_max_mm", orNull(split.midSlab, &ErrorStats::maxMm)}}
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
    for (const std::string& name : allShapeNames())
        for (double spacing : {2.0, 5.0}) {
            const auto shape = makeShape(name);
            SynthOptions options;
            options.spacingMm = spacing;
            options.pointsPerContour = 128;
            const ContourSet set = sliceShape(*shape, options);
            const Roi& roi = set.rois[0];
            const std::string caseName = name + " " + std::to_string(int(spacing)) + " mm";
            const SurfaceReference reference(*shape);
            const std::vector<Vec3> surface = sampleSurface(*shape, kSamples, 11);
            Truth truth{*shape, reference, surface, {}};
            for (const Slice& slice : roi.slices) truth.planesMm.push_back(slice.zMm);
            TriMesh mesh;
            double seconds = bestSeconds(1, [&] {
                const SliceFields fields =
                    computeSliceFields(runtime, roi.slices, gridForSlices(roi.slices, 0.5));
                mesh = levinBaseline(fields);
            });
            printRow(caseName, "levin-mc", seconds, truth, toTriangleSoup(mesh));
            // The default (smooth), the same with contours simplified, and linear.
            for (double contourError : {0.0, 0.1}) {
                ReconstructionOptions recon;
                recon.contourErrorMm = contourError;
                Reconstruction result;
                seconds = bestSeconds(1, [&] { result = reconstructSurface(runtime, roi, recon); });
                printRow(caseName, contourError > 0 ? "dfrecon-ce0.1" : "dfrecon", seconds, truth,
                         result.surface);
            }
            ReconstructionOptions linear;
            linear.interpolation = Interpolation::Linear;
            Reconstruction result;
            seconds = bestSeconds(1, [&] { result = reconstructSurface(runtime, roi, linear); });
            printRow(caseName, "dfrecon-linear", seconds, truth, result.surface);
        }
    benchEndToEnd(runtime);
    return 0;
}

}  // namespace dfrecon::bench
