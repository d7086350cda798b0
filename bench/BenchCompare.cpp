// dfrecon-bench compare: Dice and Hausdorff of two offset balls of radius R
// (distance d between centres), whose exact values are known — Dice =
// (4R + d)(2R − d)² / (16 R³), Hausdorff = d — computed three ways in the
// same run: dfrecon compare's surface route on fine geodesic spheres
// (compare/), and the voxel route of label-map tools (plastimatch dice,
// Slicer's Segment Comparison) at 1 mm and 0.5 mm voxels: voxels whose
// centre is inside each ball, Dice from voxel counts, Hausdorff between the
// centres of boundary voxels (inside, with a 6-neighbour outside).
#include <algorithm>
#include <cmath>
#include <iostream>
#include <vector>

#include <nlohmann/json.hpp>

#include "bench/Benchmarks.hpp"
#include "compare/OverlapVolume.hpp"
#include "compare/SurfaceDistances.hpp"
#include "shapes/MeshShapes.hpp"

namespace dfrecon::bench {

namespace {

struct Figures {
    double dice = 0, hausdorffMm = 0;
};

// The voxel route, on a grid covering both balls.
Figures voxelRoute(double radius, double offset, double voxelMm) {
    // A grid whose axes the offset does not follow (a diagonal), as
    // anatomy does not follow the scanner's.
    const double lo = -radius - 2 * voxelMm, hi = radius + offset + 2 * voxelMm;
    const int n = int(std::ceil((hi - lo) / voxelMm));
    auto centre = [&](int i, int j, int k) {
        return Vec3{lo + (i + 0.5) * voxelMm, lo + (j + 0.5) * voxelMm, lo + (k + 0.5) * voxelMm};
    };
    auto inA = [&](Vec3 p) { return dot(p, p) <= radius * radius; };
    const Vec3 shift = (offset / std::sqrt(3.0)) * Vec3{1, 1, 1};
    auto inB = [&](Vec3 p) {
        const Vec3 q = p - shift;
        return dot(q, q) <= radius * radius;
    };
    std::size_t a = 0, b = 0, both = 0;
    std::vector<Vec3> borderA, borderB;
    auto border = [&](auto inside, int i, int j, int k) {
        for (const auto& [di, dj, dk] :
             {std::array{1, 0, 0}, std::array{-1, 0, 0}, std::array{0, 1, 0}, std::array{0, -1, 0},
              std::array{0, 0, 1}, std::array{0, 0, -1}})
            if (!inside(centre(i + di, j + dj, k + dk))) return true;
        return false;
    };
    for (int k = 0; k < n; ++k)
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i) {
                const Vec3 p = centre(i, j, k);
                const bool x = inA(p), y = inB(p);
                a += x, b += y, both += x && y;
                if (x && border(inA, i, j, k)) borderA.push_back(p);
                if (y && border(inB, i, j, k)) borderB.push_back(p);
            }
    auto directed = [](const std::vector<Vec3>& from, const std::vector<Vec3>& to) {
        double worst = 0;
        for (const Vec3& p : from) {
            double best = INFINITY;
            for (const Vec3& q : to) best = std::min(best, dot(p - q, p - q));
            worst = std::max(worst, best);
        }
        return std::sqrt(worst);
    };
    return {2.0 * double(both) / double(a + b),
            std::max(directed(borderA, borderB), directed(borderB, borderA))};
}

}  // namespace

int benchCompare() {
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
            ours.hausdorffMm = surfaceDistances(a, b, 0.1).hausdorffMm();
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
            Figures voxels;
            const double s = bestSeconds(1, [&] { voxels = voxelRoute(radius, offset, voxel); });
            line("voxels-" + std::string(voxel == 1.0 ? "1mm" : "0.5mm"), s, voxels,
                 std::size_t(std::pow((2 * radius + offset + 4 * voxel) / voxel, 3)));
        }
    }
    return 0;
}

}  // namespace dfrecon::bench
