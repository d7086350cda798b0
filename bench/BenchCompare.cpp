// dfrecon-bench compare: Dice and Hausdorff of two offset balls of radius R
// (distance d between centres), whose exact values are known — Dice =
// (4R + d)(2R − d)² / (16 R³), Hausdorff = d — computed three ways in the
// same run: dfrecon compare's surface route on fine geodesic spheres
// (compare/), and the voxel route of label-map tools (plastimatch dice,
// Slicer's Segment Comparison) at 1 mm and 0.5 mm voxels: voxels whose
// centre is inside each ball's polyhedron, Dice from voxel counts, Hausdorff
// between the centres of boundary voxels (inside, with a 6-neighbour
// outside): voxelRouteOf below, the same route as for real structures.
//
// Then real structures (mricron-data's Brodmann atlas, contoured per label
// at its 1 mm planes): touching neighbours and one area against itself
// moved as a second observer might draw it. Each pair compared our way
// (exact overlap, kernel distances at 0.2 mm, the per-plane comparison;
// pairs per second) and the voxel way at 1 and 0.5 mm on the same two
// surfaces (voxels whose centre is inside, Dice by counts, Hausdorff and
// HD95 between boundary voxel centres by an exact distance transform), in
// the same run: the speed line, and how far the voxels' figures fall from
// the exact ones. Each pair's Dice is checked against corefinement with
// exact constructions (the route before the flux), with both bounds. Then a large organ against its
// +1 mm margin (the IBSI phantom's 358 cc GTV from ../shared/data/clinical, grown by dfrecon
// margin's route), the third kind of pair issue 62 names. Our lines give the
// overlap's and the distances' seconds apart and the time against the 0.5 mm
// voxel route's.
#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <optional>
#include <vector>

#include <nlohmann/json.hpp>

#include "bench/Benchmarks.hpp"
#include "compare/OverlapVolume.hpp"
#include "compare/PlaneComparison.hpp"
#include "dfrecon/Algebra.hpp"
#include "dfrecon/Contours.hpp"
#include "field/Rasterization.hpp"
#include "field/SurfaceDistances.hpp"
#include "geometry/Box3.hpp"
#include "geometry/MeshCheck.hpp"
#include "io/labels/LabelInput.hpp"
#include "recon/Reconstruction.hpp"
#include "shapes/MeshShapes.hpp"

namespace dfrecon::bench {

namespace {

struct Figures {
    double dice = 0, hausdorffMm = 0;
};

// A box grid of cubic voxels covering both surfaces with a margin.
struct VoxelGrid {
    Vec3 origin;  // centre of voxel (0, 0, 0)
    double voxelMm = 1;
    int n[3] = {0, 0, 0};
    std::size_t index(int i, int j, int k) const { return (std::size_t(k) * n[1] + j) * n[0] + i; }
    std::size_t size() const { return std::size_t(n[0]) * n[1] * n[2]; }
};

VoxelGrid gridAround(const TriangleSoup& a, const TriangleSoup& b, double voxelMm) {
    Box3 box;
    for (const TriangleSoup* soup : {&a, &b})
        for (const Vec3& p : soup->points) box.add(p);
    VoxelGrid grid;
    grid.voxelMm = voxelMm;
    const Vec3 margin{2 * voxelMm, 2 * voxelMm, 2 * voxelMm};
    grid.origin = box.lo - margin;
    const Vec3 extent = box.hi - box.lo + 2.0 * margin;
    grid.n[0] = int(std::ceil(extent.x / voxelMm));
    grid.n[1] = int(std::ceil(extent.y / voxelMm));
    grid.n[2] = int(std::ceil(extent.z / voxelMm));
    return grid;
}

// Voxels whose centre is inside the closed surface, as label-map tools fill
// them: field/Rasterization's ray parity (exact where a row of centres runs
// through a mesh edge or vertex, as contours on voxel planes put many).
std::vector<std::uint8_t> voxelise(const TriangleSoup& soup, const VoxelGrid& g) {
    VolumeGeometry grid;  // the same box, LPS axes
    grid.size = {g.n[0], g.n[1], g.n[2]};
    grid.spacingMm = {g.voxelMm, g.voxelMm, g.voxelMm};
    grid.originMm = {g.origin.x, g.origin.y, g.origin.z};
    std::vector<std::uint8_t> inside(g.size(), 0);
    for (const std::size_t v : voxelsInsideSolid(soup, PlaneFrame{}, grid)) inside[v] = 1;
    return inside;
}

// Inside voxels with a 6-neighbour outside.
std::vector<std::uint8_t> boundaryOf(const std::vector<std::uint8_t>& inside, const VoxelGrid& g) {
    std::vector<std::uint8_t> boundary(g.size(), 0);
    for (int k = 1; k + 1 < g.n[2]; ++k)
        for (int j = 1; j + 1 < g.n[1]; ++j)
            for (int i = 1; i + 1 < g.n[0]; ++i) {
                const std::size_t c = g.index(i, j, k);
                if (!inside[c]) continue;
                boundary[c] = !inside[g.index(i - 1, j, k)] || !inside[g.index(i + 1, j, k)] ||
                              !inside[g.index(i, j - 1, k)] || !inside[g.index(i, j + 1, k)] ||
                              !inside[g.index(i, j, k - 1)] || !inside[g.index(i, j, k + 1)];
            }
    return boundary;
}

// Squared distances (in voxels) from every voxel to the nearest marked one:
// Felzenszwalb and Huttenlocher's exact transform, one axis at a time.
std::vector<double> squaredDistanceTransform(const std::vector<std::uint8_t>& marked,
                                             const VoxelGrid& g) {
    const double far = 1e20;
    std::vector<double> d(g.size());
    for (std::size_t c = 0; c < d.size(); ++c) d[c] = marked[c] ? 0 : far;
    const int longest = std::max({g.n[0], g.n[1], g.n[2]});
    std::vector<double> f(longest), out(longest), z(longest + 1);
    std::vector<int> v(longest);
    auto pass = [&](int n) {
        int k = 0;
        v[0] = 0;
        z[0] = -far;
        z[1] = far;
        for (int q = 1; q < n; ++q) {
            double s;
            for (;;) {
                s = ((f[q] + q * q) - (f[v[k]] + v[k] * v[k])) / (2.0 * q - 2.0 * v[k]);
                if (s > z[k] || k == 0) break;
                --k;
            }
            if (s <= z[k]) s = z[k];  // k == 0 reached
            ++k;
            v[k] = q;
            z[k] = s;
            z[k + 1] = far;
        }
        k = 0;
        for (int q = 0; q < n; ++q) {
            while (z[k + 1] < q) ++k;
            out[q] = (q - v[k]) * double(q - v[k]) + f[v[k]];
        }
    };
    for (int axis = 0; axis < 3; ++axis) {
        const int a1 = (axis + 1) % 3, a2 = (axis + 2) % 3;
        for (int y = 0; y < g.n[a2]; ++y)
            for (int x = 0; x < g.n[a1]; ++x) {
                auto at = [&](int t) {
                    int ijk[3];
                    ijk[axis] = t, ijk[a1] = x, ijk[a2] = y;
                    return g.index(ijk[0], ijk[1], ijk[2]);
                };
                for (int t = 0; t < g.n[axis]; ++t) f[t] = std::min(d[at(t)], far);
                pass(g.n[axis]);
                for (int t = 0; t < g.n[axis]; ++t) d[at(t)] = out[t];
            }
    }
    return d;
}

struct VoxelFigures {
    double dice = 0, hausdorffMm = 0, hd95Mm = 0;
    std::size_t voxels = 0;
};

// The voxel route on two closed surfaces: plastimatch's Dice, Hausdorff and
// HD95 (the larger of the two directions' 95th percentiles over boundary
// voxels).
VoxelFigures voxelRouteOf(const TriangleSoup& a, const TriangleSoup& b, double voxelMm) {
    const VoxelGrid g = gridAround(a, b, voxelMm);
    const std::vector<std::uint8_t> inA = voxelise(a, g), inB = voxelise(b, g);
    std::size_t countA = 0, countB = 0, both = 0;
    for (std::size_t c = 0; c < g.size(); ++c)
        countA += inA[c], countB += inB[c], both += inA[c] && inB[c];
    const std::vector<std::uint8_t> edgeA = boundaryOf(inA, g), edgeB = boundaryOf(inB, g);
    const std::vector<double> toA = squaredDistanceTransform(edgeA, g),
                              toB = squaredDistanceTransform(edgeB, g);
    auto directed = [&](const std::vector<std::uint8_t>& from, const std::vector<double>& to,
                        double& p95) {
        std::vector<double> distances;
        for (std::size_t c = 0; c < g.size(); ++c)
            if (from[c]) distances.push_back(std::sqrt(to[c]) * voxelMm);
        if (distances.empty()) return p95 = 0.0;
        std::sort(distances.begin(), distances.end());
        p95 = distances[std::size_t(0.95 * double(distances.size() - 1))];
        return distances.back();
    };
    VoxelFigures f;
    double p95AB = 0, p95BA = 0;
    f.hausdorffMm = std::max(directed(edgeA, toB, p95AB), directed(edgeB, toA, p95BA));
    f.hd95Mm = std::max(p95AB, p95BA);
    f.dice = countA + countB > 0 ? 2.0 * double(both) / double(countA + countB) : 1;
    f.voxels = g.size();
    return f;
}

TriangleSoup moved(TriangleSoup soup, const Vec3& by) {
    for (Vec3& p : soup.points) p = p + by;
    return soup;
}

// Real structures, each pair our way and the voxel way (see the top).
int benchCompareStructures(ocl::Runtime& runtime) {
    const std::string atlas = "/usr/share/mricron/templates/brodmann.nii.gz";
    if (!std::filesystem::exists(atlas)) {
        std::cerr << "bench compare: " << atlas << " missing (make setup installs mricron-data)\n";
        return 1;
    }
    const ContourSet set = readLabelContours(atlas);
    struct Structure {
        const Roi* roi;
        TriangleSoup surface;
    };
    auto structure = [&](const std::string& name) {
        const Roi* roi = set.findRoi(name);
        Reconstruction r = reconstructSurface(runtime, *roi);
        toPatient(r.surface, roi->frame);
        return Structure{roi, std::move(r.surface)};
    };
    const Structure ba6 = structure("label_6"), ba17 = structure("label_17"),
                    ba18 = structure("label_18"), ba44 = structure("label_44"),
                    ba45 = structure("label_45");
    // A second observer: the same area drawn 0.6 mm to the right and 0.4 mm
    // forward (no plane comparison: its contours were not moved).
    const Structure ba6moved{nullptr, moved(ba6.surface, {0.6, 0.4, 0})};
    struct Pair {
        const char* name;
        const Structure *a, *b;
    };
    std::vector<Pair> pairs{{"BA44 / BA45 (touching)", &ba44, &ba45},
                            {"BA17 / BA18 (touching)", &ba17, &ba18},
                            {"BA6 / BA6 moved 0.72 mm", &ba6, &ba6moved}};
    // A large organ and its +1 mm margin.
    const std::filesystem::path gtvFile =
        std::filesystem::path(DFRECON_SHARED_DATA) / "clinical" / "ibsi-phantom-gtv-rtstruct.dcm";
    std::optional<ContoursRead> gtvSet;
    std::optional<Structure> gtv, gtvGrown;
    std::optional<Roi> grownRoi;
    if (std::filesystem::exists(gtvFile)) {
        gtvSet = readContours(gtvFile.string());
        const Roi& roi = gtvSet->contours.rois.front();
        Reconstruction r = reconstructSurface(runtime, roi);
        toPatient(r.surface, roi.frame);
        gtv = Structure{&roi, std::move(r.surface)};
        StructureAlgebraResult grown = marginRoi(runtime, gtvSet->contours, roi.name,
                                                 DirectionalMargin::uniform(1.0), "GTV+1");
        grownRoi = std::move(grown.roi);
        Reconstruction g = reconstructSurface(runtime, *grownRoi);
        toPatient(g.surface, grownRoi->frame);
        gtvGrown = Structure{&*grownRoi, std::move(g.surface)};
        pairs.push_back({"IBSI GTV 358 cc / its +1 mm margin", &*gtv, &*gtvGrown});
    } else {
        std::cerr << "bench compare: " << gtvFile << " missing, its pair skipped\n";
    }
    double oursSeconds = 0;
    for (const Pair& pair : pairs) {
        Overlap overlap;
        SurfaceDistances distances;
        std::optional<PlaneComparison> planes;
        double overlapSeconds = 0, distancesSeconds = 0;
        const double seconds = bestSeconds(1, [&] {
            overlapSeconds =
                bestSeconds(1, [&] { overlap = overlapOf(pair.a->surface, pair.b->surface); });
            distancesSeconds = bestSeconds(1, [&] {
                distances = surfaceDistances(runtime, pair.a->surface, pair.b->surface, 0.2);
            });
            if (pair.a->roi && pair.b->roi) planes = comparePlanes(*pair.a->roi, *pair.b->roi, {});
        });
        oursSeconds += seconds;
        // Today's reference: corefinement with exact constructions, B moved
        // 1e-6 mm where the surfaces coincide in part (within area(B)·1e-6).
        double corefinementBoundMm3 = 0;
        std::optional<double> corefined;
        const double corefinementSeconds = bestSeconds(1, [&] {
            corefined = intersectionVolume(pair.a->surface, pair.b->surface, {0, 0, 0});
            if (corefined) return;
            const double shiftMm = 1e-6;
            corefined = intersectionVolume(pair.a->surface, pair.b->surface,
                                           shiftMm * overlapShiftDirection());
            corefinementBoundMm3 = checkMesh(pair.b->surface).areaMm2 * shiftMm;
        });
        const double volumes = overlap.volumeAMm3 + overlap.volumeBMm3;
        const std::size_t triangles =
            pair.a->surface.triangles.size() + pair.b->surface.triangles.size();
        std::cout
            << nlohmann::ordered_json{{"bench", "compare"},
                                      {"case", pair.name},
                                      {"system", "dfrecon-surfaces"},
                                      {"size", triangles},
                                      {"seconds", seconds},
                                      {"overlap_s", overlapSeconds},
                                      {"distances_s", distancesSeconds},
                                      {"dice", overlap.dice()},
                                      {"overlapMethod", overlap.method},
                                      {"diceBound", 2 * overlap.intersectionBoundMm3 / volumes},
                                      {"corefinement_s", corefinementSeconds},
                                      {"diceMinusCorefinement",
                                       corefined ? nlohmann::ordered_json(overlap.dice() -
                                                                          2 * *corefined / volumes)
                                                 : nlohmann::ordered_json()},
                                      {"corefinementDiceBound", 2 * corefinementBoundMm3 / volumes},
                                      {"hausdorffMm", distances.hausdorffMm()},
                                      {"hd95Mm", distances.hd95Mm()},
                                      {"distanceBoundMm", distances.spacingMm},
                                      {"planeDice", planes && planes->samePlanes
                                                        ? nlohmann::ordered_json(planes->dice())
                                                        : nlohmann::ordered_json()}}
                   .dump()
            << std::endl;
        // The same pair with distances sampled at 0.5 mm, the voxels' size:
        // every figure within 0.5 mm, where the voxels' Hausdorff is off by
        // up to a voxel diagonal.
        SurfaceDistances coarse;
        const double coarseSeconds =
            overlapSeconds + bestSeconds(1, [&] {
                coarse = surfaceDistances(runtime, pair.a->surface, pair.b->surface, 0.5);
            });
        std::cout << nlohmann::ordered_json{{"bench", "compare"},
                                            {"case", pair.name},
                                            {"system", "dfrecon-surfaces-0.5mm"},
                                            {"seconds", coarseSeconds},
                                            {"dice", overlap.dice()},
                                            {"hausdorffMm", coarse.hausdorffMm()},
                                            {"hd95Mm", coarse.hd95Mm()},
                                            {"hd95MinusFineMm",
                                             coarse.hd95Mm() - distances.hd95Mm()},
                                            {"distanceBoundMm", coarse.spacingMm}}
                         .dump()
                  << std::endl;
        for (const double voxel : {1.0, 0.5}) {
            VoxelFigures v;
            const double s =
                bestSeconds(1, [&] { v = voxelRouteOf(pair.a->surface, pair.b->surface, voxel); });
            std::cout << nlohmann::ordered_json{{"bench", "compare"},
                                                {"case", pair.name},
                                                {"system",
                                                 voxel == 1.0 ? "voxels-1mm" : "voxels-0.5mm"},
                                                {"size", v.voxels},
                                                {"seconds", s},
                                                {"oursOverThese", seconds / s},
                                                {"dice", v.dice},
                                                {"diceError", v.dice - overlap.dice()},
                                                {"hausdorffMm", v.hausdorffMm},
                                                {"hd95Mm", v.hd95Mm},
                                                {"hd95ErrorMm", v.hd95Mm - distances.hd95Mm()}}
                             .dump()
                      << std::endl;
        }
    }
    std::cout << nlohmann::ordered_json{{"bench", "compare"},
                                        {"case", "real pairs"},
                                        {"system", "dfrecon-surfaces"},
                                        {"pairsPerSecond", double(pairs.size()) / oursSeconds}}
                     .dump()
              << std::endl;
    return 0;
}

}  // namespace

int benchCompare(const std::string& device) {
    ocl::Runtime runtime(device);
    const double radius = 10;
    for (double offset : {1.0, 5.0, 12.0}) {
        const double exactDice = (4 * radius + offset) * (2 * radius - offset) *
                                 (2 * radius - offset) / (16 * radius * radius * radius);
        const std::string name = "balls R 10 mm, offset " + std::to_string(int(offset)) + " mm";
        auto line = [&](const std::string& system, double seconds, const Figures& f,
                        std::size_t size) {
            std::cout << nlohmann::ordered_json{{"bench", "compare"},
                                                {"case", name},
                                                {"system", system},
                                                {"size", size},
                                                {"seconds", seconds},
                                                {"dice", f.dice},
                                                {"diceError", f.dice - exactDice},
                                                {"hausdorffMm", f.hausdorffMm},
                                                {"hausdorffErrorMm", f.hausdorffMm - offset}}
                             .dump()
                      << std::endl;
        };
        const TriangleSoup a = geodesicSphere(48, radius),
                           b = geodesicSphere(48, radius,
                                              (offset / std::sqrt(3.0)) * Vec3{1, 1, 1});
        Figures ours;
        double overlapSeconds = 0;
        const double seconds = bestSeconds(1, [&] {
            overlapSeconds = bestSeconds(1, [&] { ours.dice = overlapOf(a, b).dice(); });
            ours.hausdorffMm = surfaceDistances(runtime, a, b, 0.1).hausdorffMm();
        });
        line("dfrecon-surfaces", seconds, ours, a.triangles.size());
        std::cout << nlohmann::ordered_json{{"bench", "compare"},
                                            {"case", name},
                                            {"system", "dfrecon-surfaces"},
                                            {"overlap_s", overlapSeconds},
                                            {"distances_s", seconds - overlapSeconds}}
                         .dump()
                  << std::endl;
        for (double voxel : {1.0, 0.5}) {
            VoxelFigures voxels;
            const double s = bestSeconds(1, [&] { voxels = voxelRouteOf(a, b, voxel); });
            line("voxels-" + std::string(voxel == 1.0 ? "1mm" : "0.5mm"), s,
                 {voxels.dice, voxels.hausdorffMm}, voxels.voxels);
        }
    }
    return benchCompareStructures(runtime);
}

}  // namespace dfrecon::bench
