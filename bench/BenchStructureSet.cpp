// dfrecon-bench structure-set: whole structure sets, every ROI, as
// `dfrecon reconstruct --all` makes them (the surface reconstructed and
// checked as a file holds it), against the route users take today, timed in
// the same run: rasterise each ROI onto a grid of 0.5 mm pixels and the
// planes' spacing (even-odd fill at pixel centres), then marching cubes
// (OpenVDB's volumeToMesh at the half level). Lines per set: dfrecon
// (seconds, valid solids, worst deviation from the contour-implied volume)
// and rasterise+mc (seconds, valid solids, the same deviation); the
// dfrecon line carries the speed ratio.
#include <openvdb/openvdb.h>
#include <openvdb/tools/VolumeToMesh.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <mutex>

#include <nlohmann/json.hpp>

#include "bench/Benchmarks.hpp"
#include "geometry/MeshCheck.hpp"
#include "io/MaskContours.hpp"
#include "io/RtStruct.hpp"
#include "recon/Reconstruction.hpp"
#include "shapes/RandomLabelVolumes.hpp"

namespace dfrecon::bench {

namespace {

constexpr double kRasterPixelMm = 0.5;

struct SetResult {
    double seconds = 0;
    std::size_t rois = 0, valid = 0, triangles = 0;
    double worstVolumeDeviation = 0;  // |volume / contour volume - 1|, worst ROI
};

void addRoi(SetResult& set, const MeshCheckReport& check, double contourVolume) {
    ++set.rois;
    set.valid += check.validSolid();
    set.triangles += check.triangles;
    if (contourVolume > 0)
        set.worstVolumeDeviation =
            std::max(set.worstVolumeDeviation, std::abs(check.volumeMm3 / contourVolume - 1));
}

// The baseline's surface of one ROI: its planes filled even-odd at the
// centres of 0.5 mm pixels, stacked at the mean plane spacing, iso-surfaced
// at the half level.
TriangleSoup rasteriseAndMarch(const Roi& roi) {
    static std::once_flag initialised;
    std::call_once(initialised, [] { openvdb::initialize(); });
    Box2 box;
    for (const Slice& s : roi.slices)
        for (const Polygon& c : s.contours)
            for (Point2 p : c) box.add(p);
    const double h = kRasterPixelMm;
    const int width = int(std::ceil((box.max.x - box.min.x) / h)) + 1;
    const double spacing = roi.slices.size() > 1 ? spacingOf(roi).meanMm : 1.0;
    openvdb::FloatGrid::Ptr volume = openvdb::FloatGrid::create(0.0f);
    openvdb::math::Mat4d scale = openvdb::math::Mat4d::identity();
    scale.preScale(openvdb::Vec3d(h, h, spacing));
    scale.postTranslate(openvdb::Vec3d(box.min.x, box.min.y, roi.slices.front().zMm));
    volume->setTransform(openvdb::math::Transform::createLinearTransform(scale));
    auto access = volume->getAccessor();
    std::vector<double> crossings;
    for (std::size_t k = 0; k < roi.slices.size(); ++k) {
        const int plane = int(std::lround((roi.slices[k].zMm - roi.slices.front().zMm) / spacing));
        for (int j = 0; box.min.y + j * h <= box.max.y; ++j) {
            const double y = box.min.y + j * h;
            crossings.clear();
            for (const Polygon& c : roi.slices[k].contours)
                for (std::size_t e = 0; e < c.size(); ++e) {
                    const Point2 a = c[e], b = c[(e + 1) % c.size()];
                    if ((a.y <= y) != (b.y <= y))
                        crossings.push_back(a.x + (y - a.y) / (b.y - a.y) * (b.x - a.x));
                }
            std::sort(crossings.begin(), crossings.end());
            for (std::size_t c = 0; c + 1 < crossings.size(); c += 2)
                for (int i = std::max(0, int(std::ceil((crossings[c] - box.min.x) / h)));
                     i < width && box.min.x + i * h <= crossings[c + 1]; ++i)
                    access.setValue(openvdb::Coord(i, j, plane), 1.0f);
        }
    }
    std::vector<openvdb::Vec3s> points;
    std::vector<openvdb::Vec3I> triangles;
    std::vector<openvdb::Vec4I> quads;
    openvdb::tools::volumeToMesh(*volume, points, triangles, quads, 0.5);
    TriangleSoup soup;
    for (const openvdb::Vec3s& p : points) soup.points.push_back({p[0], p[1], p[2]});
    // OpenVDB winds faces clockwise seen from outside; flipped to outward.
    for (const openvdb::Vec3I& t : triangles) soup.triangles.push_back({t[2], t[1], t[0]});
    for (const openvdb::Vec4I& q : quads) {
        soup.triangles.push_back({q[3], q[2], q[1]});
        soup.triangles.push_back({q[3], q[1], q[0]});
    }
    return soup;
}

void benchSet(ocl::Runtime& runtime, const std::string& name, const ContourSet& set) {
    SetResult ours, baseline;
    for (const Roi& roi : set.rois) {
        if (roi.slices.empty()) continue;
        const double contourVolume = contourVolumeMm3(roi);
        Reconstruction result;
        ours.seconds += bestSeconds(1, [&] { result = reconstructSurface(runtime, roi); });
        addRoi(ours, result.check, contourVolume);
        TriangleSoup marched;
        baseline.seconds += bestSeconds(1, [&] { marched = rasteriseAndMarch(roi); });
        addRoi(baseline, checkMesh(marched), contourVolume);
    }
    auto line = [&](const char* system, const SetResult& r) {
        nlohmann::ordered_json j{
            {"bench", "structure-set"}, {"case", name},
            {"system", system},         {"size", r.rois},
            {"seconds", r.seconds},     {"validSolids", r.valid},
            {"triangles", r.triangles}, {"worstVolumeDeviationPct", 100 * r.worstVolumeDeviation}};
        if (&r == &ours) j["speedupOverBaseline"] = baseline.seconds / ours.seconds;
        std::cout << j.dump() << std::endl;
    };
    line("dfrecon", ours);
    line("rasterise+mc", baseline);
}

}  // namespace

int benchStructureSet(const std::string& device) {
    ocl::Runtime runtime(device);
    const std::filesystem::path brodmann =
        std::filesystem::path(DFRECON_SHARED_DATA) / "brodmann-rtstruct.dcm";
    const std::filesystem::path kmeans =
        std::filesystem::path(DFRECON_FIXTURES) / "kmeans_axial" / "rtstruct.dcm";
    for (const auto& [name, path] : {std::pair{"brodmann 41 ROIs, 2 mm", brodmann},
                                     std::pair{"kmeans_axial 7 ROIs", kmeans}}) {
        if (!std::filesystem::exists(path)) {
            std::cout << nlohmann::ordered_json{{"bench", "structure-set"},
                                                {"case", name},
                                                {"skipped", path.string() + " not found"}}
                             .dump()
                      << std::endl;
            continue;
        }
        benchSet(runtime, name, readRtStruct(path.string()).contours);
    }
    // Many contours per plane, as a CT bone structure has.
    benchSet(runtime, "200 blobs, 240x240x40 voxels of 0.5x0.5x2 mm",
             contoursFromLabels(manyBlobLabelVolume(7, 200, 240, 40)));
    return 0;
}

}  // namespace dfrecon::bench
