// Surface distance maps on a scene of about 6 000 triangles (CGAL's
// elephant, eight and sphere, scaled to organ sizes and placed a few mm
// apart), 512×512 maps per object. One frame = the maps of every object
// (texels and vertices) against all the others.
// Systems:
//   dfrecon             the OpenCL kernel (sdm/ClosestPrimitives); also its
//                       culling: source_triangles (those holding samples),
//                       overflowing_sources (lists too long: searched in
//                       full), mean_candidates (per listed source)
//   dfrecon-cpu         its C++ reference, one thread
//   bruteforce          every triangle for every sample; timed on a subset
//                       of the samples and scaled to the frame
//   openvdb-meshToVolume the volumetric way: OpenVDB narrow-band signed
//                       distance fields of the objects (voxel = dfrecon's
//                       sampling bound), sampled trilinearly at the same
//                       points; only in the clearance-band case, as a
//                       full-range field at that voxel size would need a
//                       dense grid of the whole scene
// max_err_mm: the largest |distance - brute force| at the subset's samples
// (for dfrecon: the kernel's error at its samples; the map's error between
// samples is at most bound_mm, the atlas's Lemma 2 bound). For the
// volumetric baseline also max_unsigned_err_mm (of |distance|) and
// wrong_sign_samples: OpenVDB's sign comes from flooding the band's
// topology, which can take an exterior pocket for interior.
#include <iostream>

#include <openvdb/tools/Interpolation.h>
#include <openvdb/tools/MeshToVolume.h>
#include <nlohmann/json.hpp>

#include "bench/Benchmarks.hpp"
#include "io/mesh/MeshIO.hpp"
#include "sdm/SurfaceDistanceMaps.hpp"

namespace dfrecon::bench {

namespace {

constexpr int kMapSize = 512;
constexpr std::size_t kBruteSamples = 3000;

std::string fixture(const std::string& name) {
    return std::string(DFRECON_FIXTURES) + "/meshes/" + name;
}

// Scales `soup` so its bounding box's longest side is `sizeMm`, and moves
// its box's low corner to `lo`.
TriangleSoup placed(TriangleSoup soup, double sizeMm, Vec3 lo) {
    Box3 box;
    for (const Vec3& p : soup.points) box.add(p);
    const Vec3 extent = box.hi - box.lo;
    const double scale = sizeMm / std::max({extent.x, extent.y, extent.z});
    for (Vec3& p : soup.points) p = lo + scale * (p - box.lo);
    return soup;
}

Box3 boxOf(const TriangleSoup& soup) {
    Box3 box;
    for (const Vec3& p : soup.points) box.add(p);
    return box;
}

SurfaceScene benchScene() {
    TriangleSoup elephant = placed(readTriangleSoup(fixture("elephant.off")), 90, {0, 0, 0});
    const Box3 e = boxOf(elephant);
    // The eight stands 3 mm beside the elephant's box, the sphere sinks
    // 4 mm into its top: clearances from 0 to tens of mm, and a collision.
    TriangleSoup eight =
        placed(readTriangleSoup(fixture("eight.off")), 45, {e.hi.x + 3, e.lo.y + 5, e.lo.z + 5});
    TriangleSoup sphere =
        placed(readTriangleSoup(fixture("sphere.off")), 24,
               {0.5 * (e.lo.x + e.hi.x) - 12, 0.5 * (e.lo.y + e.hi.y) - 12, e.hi.z - 4});
    return SurfaceScene({std::move(elephant), std::move(eight), std::move(sphere)},
                        {"elephant", "eight", "sphere"});
}

// Every k-th sample of every object, about kBruteSamples in all.
std::vector<std::vector<std::size_t>> subsetOf(const std::vector<ObjectSamples>& samples) {
    std::size_t total = 0;
    for (const ObjectSamples& s : samples) total += s.samples.size();
    const std::size_t step = std::max<std::size_t>(1, total / kBruteSamples);
    std::vector<std::vector<std::size_t>> subset(samples.size());
    for (std::size_t o = 0; o < samples.size(); ++o)
        for (std::size_t k = 0; k < samples[o].samples.size(); k += step) subset[o].push_back(k);
    return subset;
}

using Frame = std::vector<std::vector<ClosestPrimitive>>;  // per object, per sample

Frame computeFrame(const std::vector<ObjectSamples>& samples, const ClosestPrimitivesFn& closest,
                   const DistanceQuery& query) {
    Frame frame;
    for (const ObjectSamples& s : samples) frame.push_back(closest(s.samples, query));
    return frame;
}

// Largest |value - brute| over the subset, where the brute force found an
// object (within the band) and the system a finite value; `missed` counts
// those where the system found none.
struct Error {
    double maxMm = 0;
    double maxUnsignedMm = 0;  // of |distance|: leaves out sign errors
    std::size_t missed = 0, wrongSign = 0;
};

template <class Value>
Error errorAgainst(const std::vector<std::vector<std::size_t>>& subset, const Frame& brute,
                   Value&& value) {
    Error e;
    for (std::size_t o = 0; o < subset.size(); ++o)
        for (std::size_t i = 0; i < subset[o].size(); ++i) {
            if (brute[o][i].object < 0) continue;
            const double v = value(o, subset[o][i]);
            if (!std::isfinite(v)) {
                ++e.missed;
                continue;
            }
            e.maxMm = std::max(e.maxMm, std::abs(v - brute[o][i].distanceMm));
            e.maxUnsignedMm =
                std::max(e.maxUnsignedMm, std::abs(std::abs(v) - std::abs(brute[o][i].distanceMm)));
            e.wrongSign +=
                (v < 0) != (brute[o][i].distanceMm < 0) && std::abs(brute[o][i].distanceMm) > 1e-9;
        }
    return e;
}

// The volumetric baseline: one narrow-band level set per object.
struct Volumes {
    std::vector<openvdb::FloatGrid::Ptr> grids;
};

Volumes buildVolumes(const SurfaceScene& scene, double voxelMm, double bandMm) {
    openvdb::initialize();
    Volumes v;
    const auto xform = openvdb::math::Transform::createLinearTransform(voxelMm);
    const float band = float(bandMm / voxelMm + 1);
    for (std::size_t o = 0; o < scene.objectCount(); ++o) {
        const TriangleSoup& soup = scene.object(o);
        std::vector<openvdb::Vec3s> points;
        std::vector<openvdb::Vec3I> triangles;
        for (const Vec3& p : soup.points)
            points.push_back(xform->worldToIndex(openvdb::Vec3d(p.x, p.y, p.z)));
        for (const auto& t : soup.triangles) triangles.emplace_back(t[0], t[1], t[2]);
        v.grids.push_back(openvdb::tools::meshToSignedDistanceField<openvdb::FloatGrid>(
            *xform, points, triangles, {}, band, band));
    }
    return v;
}

// Per sample, the smallest |value| over the other objects' fields (signed
// like dfrecon's answer); +inf outside every band.
Frame sampleVolumes(const SurfaceScene& scene, const Volumes& volumes,
                    const std::vector<ObjectSamples>& samples, double bandMm) {
    Frame frame(samples.size());
    for (std::size_t o = 0; o < samples.size(); ++o) {
        frame[o].resize(samples[o].samples.size());
        for (std::size_t j = 0; j < scene.objectCount(); ++j) {
            if (j == o) continue;
            openvdb::tools::GridSampler<openvdb::FloatGrid, openvdb::tools::BoxSampler> sampler(
                *volumes.grids[j]);
            for (std::size_t k = 0; k < samples[o].samples.size(); ++k) {
                const Vec3 p = samples[o].samples[k].point;
                const double d = sampler.wsSample(openvdb::Vec3d(p.x, p.y, p.z));
                ClosestPrimitive& c = frame[o][k];
                if (std::abs(d) < bandMm && std::abs(d) < std::abs(c.distanceMm)) {
                    c.distanceMm = d;
                    c.object = int(j);
                }
            }
        }
    }
    return frame;
}

}  // namespace

int benchSdm(const std::string& device) {
    const SurfaceScene scene = benchScene();
    ocl::Runtime runtime(device);
    const auto setupStart = std::chrono::steady_clock::now();
    std::vector<ObjectSamples> samples;
    std::size_t texels = 0, sampleCount = 0;
    double boundMm = 0;
    for (std::size_t o = 0; o < scene.objectCount(); ++o) {
        samples.push_back(sampleObject(scene, o, {kMapSize}));
        texels += samples.back().texelCount();
        sampleCount += samples.back().samples.size();
        boundMm = std::max(boundMm, samples.back().samplingBoundMm());
    }
    ClosestPrimitiveKernel kernel(runtime, scene);
    const double setupSeconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - setupStart).count();
    const std::vector<std::vector<std::size_t>> subset = subsetOf(samples);
    std::size_t subsetCount = 0;
    for (const auto& s : subset) subsetCount += s.size();

    const ClosestPrimitivesFn onDevice = [&](const std::vector<SurfaceSample>& s,
                                             const DistanceQuery& q) { return kernel.run(s, q); };
    const ClosestPrimitivesFn reference = [&](const std::vector<SurfaceSample>& s,
                                              const DistanceQuery& q) {
        return closestPrimitivesReference(scene, s, q);
    };
    auto line = [&](const std::string& caseName, const std::string& system) {
        return nlohmann::json{{"bench", "sdm"},
                              {"case", caseName},
                              {"system", system},
                              {"triangles", scene.triangleCount()},
                              {"objects", scene.objectCount()},
                              {"map_size", kMapSize},
                              {"texels", texels},
                              {"samples", sampleCount}};
    };

    for (const double bandMm : std::vector<double>{INFINITY, 10.0}) {
        const bool full = !std::isfinite(bandMm);
        const std::string caseName = full ? "scene-6k" : "scene-6k/band-10mm";
        DistanceQuery query;
        query.maxDistanceMm = bandMm;
        // Brute force on the subset: the reference answers, and its time.
        Frame brute(samples.size());
        const double bruteSeconds = bestSeconds(1, [&] {
            for (std::size_t o = 0; o < samples.size(); ++o) {
                std::vector<SurfaceSample> some;
                for (std::size_t k : subset[o]) some.push_back(samples[o].samples[k]);
                brute[o] = closestPrimitivesBruteForce(scene, some, query);
            }
        });

        Frame frame;
        const double seconds =
            bestSeconds(3, [&] { frame = computeFrame(samples, onDevice, query); });
        const Error kernelError = errorAgainst(
            subset, brute, [&](std::size_t o, std::size_t k) { return frame[o][k].distanceMm; });
        // The culling of one more frame, object by object: how many sampled
        // triangles, how long their candidate lists, how many overflowed.
        CullStats cull;
        for (const ObjectSamples& s : samples) {
            kernel.run(s.samples, query);
            const CullStats object = kernel.lastCullStats();
            cull.sources += object.sources;
            cull.overflowing += object.overflowing;
            cull.candidates += object.candidates;
        }
        const std::size_t listed = cull.sources - cull.overflowing;
        double volumeSeconds = 0;
        nlohmann::json out = line(caseName, "dfrecon");
        out.update(nlohmann::json{
            {"seconds", seconds},
            {"setup_seconds", setupSeconds},
            {"max_err_mm", kernelError.maxMm},
            {"missed_samples", kernelError.missed},
            {"bound_mm", boundMm},
            {"source_triangles", cull.sources},
            {"overflowing_sources", cull.overflowing},
            {"mean_candidates", listed ? double(cull.candidates) / double(listed) : 0.0},
            {"device", runtime.device().deviceName}});
        std::vector<nlohmann::json> lines{out};

        if (full) {
            Frame cpu;
            const double cpuSeconds =
                bestSeconds(1, [&] { cpu = computeFrame(samples, reference, query); });
            out = line(caseName, "dfrecon-cpu");
            out.update(nlohmann::json{
                {"seconds", cpuSeconds},
                {"max_err_mm",
                 errorAgainst(subset, brute,
                              [&](std::size_t o, std::size_t k) { return cpu[o][k].distanceMm; })
                     .maxMm},
                {"bound_mm", boundMm}});
            lines.push_back(out);
        } else {
            // The volumetric baseline at dfrecon's accuracy: voxel = bound.
            Frame volumetric;
            double buildSeconds = 0, sampleSeconds = 0;
            volumeSeconds = bestSeconds(1, [&] {
                const auto start = std::chrono::steady_clock::now();
                const Volumes volumes = buildVolumes(scene, boundMm, bandMm);
                buildSeconds =
                    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
                volumetric = sampleVolumes(scene, volumes, samples, bandMm);
                sampleSeconds =
                    std::chrono::duration<double>(std::chrono::steady_clock::now() - start)
                        .count() -
                    buildSeconds;
            });
            const Error volumeError = errorAgainst(
                subset, brute,
                [&](std::size_t o, std::size_t k) { return volumetric[o][k].distanceMm; });
            out = line(caseName, "openvdb-meshToVolume");
            out.update(nlohmann::json{{"seconds", volumeSeconds},
                                      {"build_seconds", buildSeconds},
                                      {"sample_seconds", sampleSeconds},
                                      {"voxel_mm", boundMm},
                                      {"max_err_mm", volumeError.maxMm},
                                      {"max_unsigned_err_mm", volumeError.maxUnsignedMm},
                                      {"wrong_sign_samples", volumeError.wrongSign},
                                      {"missed_samples", volumeError.missed}});
            lines.push_back(out);
            lines[0]["speedup_vs_volumetric"] = volumeSeconds / seconds;
        }
        out = line(caseName, "bruteforce");
        out.update(
            nlohmann::json{{"seconds", bruteSeconds * double(sampleCount) / double(subsetCount)},
                           {"measured_samples", subsetCount},
                           {"measured_seconds", bruteSeconds},
                           {"max_err_mm", 0.0}});
        lines.push_back(out);
        lines[0]["speedup_vs_bruteforce"] = lines.back()["seconds"].get<double>() / seconds;
        for (const nlohmann::json& l : lines) std::cout << l.dump() << std::endl;
    }
    return 0;
}

}  // namespace dfrecon::bench
