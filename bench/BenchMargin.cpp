// dfrecon-bench margin: exact margins (dfrecon/Algebra) against the exact
// offset of the true shape, beside the voxel margins planning systems use
// (baselines/VoxelMargins: an exact Euclidean distance transform of the
// rasterised contours at 1 and 0.5 mm, and plastimatch's distance map), in
// one run. Spheres and cubes of 0.5–50 cm³ drawn on planes 1–5 mm apart,
// grown and shrunk by 3–20 mm. Per case: the exact offset volume, ours as
// Σ area × spacing of the new contours (what a planning system reports)
// and as the volume of their reconstructed surface, each voxel method's
// volume, and how far our contours' vertices lie from the exact offset
// surface of the true shape (the margin's own error is 1e-6 mm against the
// solid it grows; the rest is how well the contours tell the shape); and
// the same for the exact surface in space (algebra/SolidSurface, 0.5 mm
// voxels) against the surface reconstructed from the new contours. Then
// real organs of a clinical set, from 1 cc to 2 L (benchOrganMargins; alone
// with DFRECON_BENCH_ORGANS_ONLY=1).
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <iostream>

#include <nlohmann/json.hpp>

#include "baselines/VoxelMargins.hpp"
#include "bench/Benchmarks.hpp"
#include "dfrecon/Algebra.hpp"
#include "dfrecon/Contours.hpp"
#include "dfrecon/Reconstruct.hpp"
#include "geometry/SurfaceMeasures.hpp"
#include "geometry/TriangleBvh.hpp"

namespace dfrecon::bench {

namespace {

struct Shape {
    const char* kind;  // "sphere" or "cube"
    double volumeCc;
    double size() const {  // radius or edge, mm
        const double mm3 = volumeCc * 1000;
        return std::string(kind) == "sphere" ? std::cbrt(mm3 * 3 / (4 * M_PI)) : std::cbrt(mm3);
    }
};

// The shape's contours on planes `spacing` apart, one through the centre
// (a sphere: circles of 360 points; a cube: squares on the planes inside it,
// the planes at the centres of slabs that tile it exactly).
Roi contoursOf(const Shape& shape, double spacing) {
    Roi roi;
    roi.name = shape.kind;
    const double s = shape.size();
    if (std::string(shape.kind) == "sphere") {
        for (int k = -int(std::floor(s / spacing)); k * spacing < s; ++k) {
            const double z = k * spacing, r = std::sqrt(s * s - z * z);
            if (r < 0.05) continue;
            Polygon circle;
            for (int i = 0; i < 360; ++i)
                circle.push_back(
                    {r * std::cos(2 * M_PI * i / 360), r * std::sin(2 * M_PI * i / 360)});
            roi.slices.push_back({z, {circle}});
        }
    } else {
        const int planes = std::max(1, int(std::lround(s / spacing)));
        const double slab = s / planes, h = s / 2;
        for (int k = 0; k < planes; ++k)
            roi.slices.push_back({-h + (k + 0.5) * slab, {{{-h, -h}, {h, -h}, {h, h}, {-h, h}}}});
        roi.slabThicknessMm = 0;
    }
    return roi;
}

// The exact offset of the true shape: its volume, and the signed distance
// of a point from its boundary.
double offsetVolume(const Shape& shape, double m) {
    const double s = shape.size();
    if (std::string(shape.kind) == "sphere") return 4.0 / 3 * M_PI * std::pow(s + m, 3);
    if (m < 0) return std::pow(s + 2 * m, 3);
    return s * s * s + 6 * m * s * s + 3 * M_PI * m * m * s + 4.0 / 3 * M_PI * m * m * m;
}

double offsetDistance(const Shape& shape, double m, Vec3 p) {
    const double s = shape.size();
    if (std::string(shape.kind) == "sphere") return length(p) - (s + m);
    const Vec3 q{std::abs(p.x) - s / 2, std::abs(p.y) - s / 2, std::abs(p.z) - s / 2};
    const Vec3 out{std::max(q.x, 0.0), std::max(q.y, 0.0), std::max(q.z, 0.0)};
    return length(out) + std::min(std::max(q.x, std::max(q.y, q.z)), 0.0) - m;
}

double percent(double value, double exact) {
    return 100 * (value / exact - 1);
}

// Real organs of a clinical structure set (the Pinnacle head-and-neck
// export: a 1 cc chiasm, a 20 cc GTV, the 1.3 L brain, the 2 L external
// outline) grown and shrunk by 1 and 5 mm: ours (marginRoi: the source's
// reconstruction and the plane sections; the program adds the check of the
// result and the writing) against the EDT voxel margins at 1 and 0.5 mm in
// the same run, and how far our contour vertices lie from the exact offset
// of the reconstructed source (its nearest triangle on a host hierarchy,
// independent of the kernel the margin used).
int benchOrganMargins(ocl::Runtime& runtime) {
    const std::filesystem::path file =
        std::filesystem::path(DFRECON_SHARED_DATA) / "clinical" / "pinnacle-hn-rtstruct.dcm";
    if (!std::filesystem::exists(file)) {
        std::cerr << "bench margin: " << file << " missing, organs skipped\n";
        return 0;
    }
    const ContoursRead read = readContours(file.string());
    int failures = 0;
    for (const char* organ : {"Chiasm", "GTV", "Brain", "External"}) {
        const Roi* roi = read.contours.findRoi(organ);
        if (!roi) continue;
        const RoiSurface source = reconstructRoi(runtime, *roi);
        const TriangleBvh nearest(source.surface);
        for (const double margin : {1.0, -1.0, 5.0, -5.0}) {
            nlohmann::ordered_json row{{"bench", "margin"},
                                       {"case", std::string(organ) + " " + (margin > 0 ? "+" : "") +
                                                    std::to_string(int(margin)) + " mm"},
                                       {"sourceCc", source.check.volumeMm3 / 1000},
                                       {"marginMm", margin}};
            double ours = 0;
            try {
                StructureAlgebraResult r;
                ours = bestSeconds(1, [&] {
                    r = marginRoi(runtime, read.contours, organ, DirectionalMargin::uniform(margin),
                                  "M");
                });
                double worst = 0;
                std::size_t vertices = 0;
                for (const Slice& slice : r.roi.slices)
                    for (const Polygon& polygon : slice.contours)
                        for (const Point2& v : polygon) {
                            const Vec3 p = r.roi.frame.toPatient({v.x, v.y, slice.zMm});
                            worst = std::max(
                                worst, std::abs(nearest.nearest(p).distance - std::abs(margin)));
                            ++vertices;
                        }
                row["dfrecon"] = {{"seconds", ours},
                                  {"sectionsSeconds", r.sectionsSeconds},
                                  {"contoursCc", contourVolumeMm3(r.roi) / 1000},
                                  {"vertices", vertices},
                                  {"maxVertexOffExactOffsetMm", worst}};
            } catch (const std::exception& e) {
                row["dfrecon"] = {{"error", e.what()}};
                ++failures;
            }
            for (const double voxel : {1.0, 0.5}) {
                const std::string key = "edtVoxel" + std::string(voxel == 1.0 ? "1mm" : "0.5mm");
                try {
                    const VoxelMarginResult v = edtVoxelMargin(*roi, voxel, margin);
                    row[key] = {{"seconds", v.seconds},
                                {"cc", v.volumeMm3 / 1000},
                                {"oursOverThese", ours / v.seconds}};
                } catch (const std::exception& e) {
                    row[key] = {{"error", e.what()}};
                }
            }
            std::cout << row.dump() << std::endl;
        }
    }
    return failures;
}

}  // namespace

int benchMargin(const std::string& device) {
    ocl::Runtime runtime(device);
    if (std::getenv("DFRECON_BENCH_ORGANS_ONLY")) return benchOrganMargins(runtime) ? 1 : 0;
    struct Case {
        Shape shape;
        double spacing, margin;
    };
    std::vector<Case> cases;
    // The headline: a 1 cm³ sphere grown by 5 mm at every spacing.
    for (double spacing : {1.0, 2.0, 3.0, 4.0, 5.0}) cases.push_back({{"sphere", 1}, spacing, 5});
    for (const Shape& shape : {Shape{"sphere", 0.5}, Shape{"sphere", 10}, Shape{"sphere", 50},
                               Shape{"cube", 1}, Shape{"cube", 50}})
        for (double spacing : {1.0, 3.0, 5.0})
            for (double margin : {3.0, 10.0, 20.0, -3.0}) {
                if (margin < 0 && shape.size() < 8) continue;  // nothing left
                cases.push_back({shape, spacing, margin});
            }
    int failures = 0;
    for (const Case& c : cases) {
        ContourSet set;
        set.rois.push_back(contoursOf(c.shape, c.spacing));
        const double exact = offsetVolume(c.shape, c.margin);
        nlohmann::ordered_json row{
            {"bench", "margin"},
            {"case", std::string(c.shape.kind) + " " +
                         std::to_string(c.shape.volumeCc).substr(0, 4) + " cc, spacing " +
                         std::to_string(int(c.spacing)) + " mm, margin " +
                         std::to_string(int(c.margin)) + " mm"},
            {"shape", c.shape.kind},
            {"volumeCc", c.shape.volumeCc},
            {"spacingMm", c.spacing},
            {"marginMm", c.margin},
            {"exactCc", exact / 1000}};
        try {
            StructureAlgebraResult r;
            StructureAlgebraOptions options;
            options.surfaceVoxelMm = 0.5;
            const double seconds = bestSeconds(1, [&] {
                r = marginRoi(runtime, set, c.shape.kind, DirectionalMargin::uniform(c.margin), "M",
                              options);
            });
            const double contours = contourVolumeMm3(r.roi);
            const RoiSurface mesh = reconstructRoi(runtime, r.roi);
            const auto farthest = [&](const std::vector<Vec3>& points) {
                double worst = 0;
                for (const Vec3& v : points)
                    worst = std::max(worst, std::abs(offsetDistance(c.shape, c.margin, v)));
                return worst;
            };
            std::vector<Vec3> vertices;
            for (const Slice& s : r.roi.slices)
                for (const Polygon& p : s.contours)
                    for (const Point2& v : p) vertices.push_back({v.x, v.y, s.zMm});
            const double source = r.surfaceVolumesMm3.begin()->second;
            const SurfaceMeasures exactSurface = measureSurface(*r.surface);
            row["dfrecon"] = {
                {"seconds", seconds},
                {"surfaceSeconds", r.surfaceSeconds},
                {"sourceSolidErrorPercent", percent(source, offsetVolume(c.shape, 0))},
                {"contoursCc", contours / 1000},
                {"contoursErrorPercent", percent(contours, exact)},
                {"contoursMeshCc", mesh.check.volumeMm3 / 1000},
                {"contoursMeshErrorPercent", percent(mesh.check.volumeMm3, exact)},
                {"contoursMeshValid", mesh.check.validSolid()},
                {"surfaceCc", exactSurface.volumeMm3 / 1000},
                {"surfaceErrorPercent", percent(exactSurface.volumeMm3, exact)},
                {"maxVertexOffMm", farthest(vertices)},
                {"maxContoursMeshOffMm", farthest(mesh.surface.points)},
                {"maxSurfaceOffMm", farthest(r.surface->points)}};
        } catch (const std::exception& e) {
            row["dfrecon"] = {{"error", e.what()}};
            ++failures;
        }
        for (double voxel : {1.0, 0.5}) {
            const std::string key = "edtVoxel" + std::string(voxel == 1.0 ? "1mm" : "0.5mm");
            try {
                const VoxelMarginResult v = edtVoxelMargin(set.rois[0], voxel, c.margin);
                row[key] = {{"seconds", v.seconds},
                            {"cc", v.volumeMm3 / 1000},
                            {"errorPercent", percent(v.volumeMm3, exact)}};
            } catch (const std::exception& e) {
                row[key] = {{"error", e.what()}};
            }
        }
        try {
            const VoxelMarginResult v = plastimatchVoxelMargin(set.rois[0], 1.0, c.margin);
            row["plastimatch1mm"] = {{"seconds", v.seconds},
                                     {"cc", v.volumeMm3 / 1000},
                                     {"errorPercent", percent(v.volumeMm3, exact)}};
        } catch (const std::exception& e) {
            row["plastimatch1mm"] = {{"error", e.what()}};
        }
        std::cout << row.dump() << std::endl;
    }
    failures += benchOrganMargins(runtime);
    return failures ? 1 : 0;
}

}  // namespace dfrecon::bench
