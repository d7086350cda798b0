// dfrecon compare A B: how two structures agree, as contouring studies and QA
// checks report it — volumes, Dice, Jaccard, Hausdorff, HD95 and mean surface
// distance — computed on the surfaces (compare/), not on voxels, with the
// distances' error bound stated.
#include <iostream>
#include <memory>

#include <nlohmann/json.hpp>

#include "app/Commands.hpp"
#include "app/Inputs.hpp"
#include "app/NumberChecks.hpp"
#include "app/Stopwatch.hpp"
#include "compare/OverlapVolume.hpp"
#include "compare/SurfaceDistances.hpp"
#include "geometry/MeshCheck.hpp"
#include "geometry/SurfaceMeasures.hpp"
#include "io/InputError.hpp"
#include "io/JsonText.hpp"
#include "io/MeshIO.hpp"
#include "recon/Reconstruction.hpp"

namespace dfrecon::app {

namespace {

struct CompareArgs {
    std::string a, b, roiA, roiB;
    double spacingMm = 0.2;
    double toleranceMm = 1;
    bool json = false;
};

/// A mesh file as it is, or an ROI of a contour file reconstructed (linear,
/// flat caps: the surface whose volume is the contours' own).
TriangleSoup surfaceOf(const std::string& path, const std::string& roi, const GlobalOptions& global,
                       std::unique_ptr<ocl::Runtime>& runtime) {
    if (isMeshExtension(path)) {
        TriangleSoup soup = readTriangleSoup(path);
        if (!checkMesh(soup).validSolid())
            throw InputError(path, 0, "not a valid closed solid (dfrecon check says where)");
        return soup;
    }
    const ContourInput input = loadContours(path, global);
    const Roi& chosen = *selectRois(input.contours, roi, false).front();
    // One device and program cache for both inputs, made only if needed.
    if (!runtime) runtime = std::make_unique<ocl::Runtime>(global.device);
    Reconstruction result = reconstructSurface(*runtime, chosen);
    if (!result.check.validSolid())
        throw InputError(path, 0, "ROI '" + chosen.name + "' gives no valid closed solid");
    toPatient(result.surface, chosen.frame);
    return result.surface;
}

void runCompare(const CompareArgs& args, const GlobalOptions& global) {
    Stopwatch watch;
    std::unique_ptr<ocl::Runtime> runtime;
    const TriangleSoup a = surfaceOf(args.a, args.roiA, global, runtime);
    const TriangleSoup b = surfaceOf(args.b, args.roiB, global, runtime);
    const double loadSeconds = watch.lap();
    const Overlap overlap = overlapOf(a, b);
    const double overlapSeconds = watch.lap();
    const SurfaceDistances d = surfaceDistances(a, b, args.spacingMm, args.toleranceMm);
    const double centroidDistanceMm =
        length(measureSurface(b).centroidMm - measureSurface(a).centroidMm);
    const double distanceSeconds = watch.lap();
    if (d.spacingMm > args.spacingMm && !global.quiet)
        std::cerr << "dfrecon: warning: --spacing " << args.spacingMm << " mm would take more than "
                  << kMaxDistanceSamples << " samples on a surface; distances sampled every "
                  << d.spacingMm << " mm, each within that of its exact value\n";
    if (args.json) {
        auto directed = [](const DirectedDistances& x) {
            return nlohmann::ordered_json{{"hausdorffMm", x.maxMm},
                                          {"hd95Mm", x.p95Mm},
                                          {"meanMm", x.meanMm},
                                          {"areaWithinToleranceMm2", x.areaWithinToleranceMm2},
                                          {"samples", x.samples}};
        };
        std::cout << jsonText(
                         nlohmann::ordered_json{
                             {"command", "compare"},
                             {"a", args.a},
                             {"b", args.b},
                             {"volumeAMm3", overlap.volumeAMm3},
                             {"volumeBMm3", overlap.volumeBMm3},
                             {"volumeDifferenceMm3", overlap.volumeBMm3 - overlap.volumeAMm3},
                             {"intersectionMm3", overlap.intersectionMm3},
                             {"unionMm3", overlap.unionMm3()},
                             {"dice", overlap.dice()},
                             {"jaccard", overlap.jaccard()},
                             {"overlapMethod", overlap.method},
                             {"overlapShiftMm", overlap.shiftMm},
                             {"intersectionBoundMm3", overlap.intersectionBoundMm3},
                             {"hausdorffMm", d.hausdorffMm()},
                             {"hd95Mm", d.hd95Mm()},
                             {"hd95PooledMm", d.hd95PooledMm},
                             {"meanSurfaceDistanceMm", d.meanMm()},
                             {"surfaceDice", d.surfaceDice()},
                             {"toleranceMm", d.toleranceMm},
                             {"centroidDistanceMm", centroidDistanceMm},
                             {"distanceBoundMm", d.spacingMm},
                             {"aToB", directed(d.aToB)},
                             {"bToA", directed(d.bToA)},
                             {"seconds",
                              {{"load", loadSeconds},
                               {"overlap", overlapSeconds},
                               {"distances", distanceSeconds}}}},
                         2)
                  << "\n";
        return;
    }
    std::cout << "volume A " << overlap.volumeAMm3 / 1000 << " cc, B " << overlap.volumeBMm3 / 1000
              << " cc, both " << overlap.intersectionMm3 / 1000 << " cc\n"
              << "Dice " << overlap.dice() << ", Jaccard " << overlap.jaccard() << " ("
              << (overlap.shiftMm > 0 ? "exact with B shifted " + std::to_string(overlap.shiftMm) +
                                            " mm off the surfaces it shares with A: intersection "
                                            "within " +
                                            std::to_string(overlap.intersectionBoundMm3) + " mm3"
                                      : std::string("exact"))
              << ")\n"
              << "Hausdorff " << d.hausdorffMm() << " mm, HD95 " << d.hd95Mm() << " mm (pooled "
              << d.hd95PooledMm << " mm), mean surface distance " << d.meanMm()
              << " mm (each within " << d.spacingMm << " mm)\n"
              << "surface Dice at " << d.toleranceMm << " mm " << d.surfaceDice()
              << ", centroid distance " << centroidDistanceMm << " mm\n";
}

}  // namespace

void addCompareCommand(CLI::App& root, const GlobalOptions& global) {
    auto args = std::make_shared<CompareArgs>();
    CLI::App* cmd = root.add_subcommand(
        "compare",
        "Volumes, Dice, Jaccard, Hausdorff, HD95 and mean surface distance of two "
        "structures, on their surfaces");
    cmd->footer(
        "A and B are mesh files (.ply .stl .obj .off; valid closed solids) or contour files "
        "(.slices, DICOM RTSTRUCT, label volumes; the ROI is reconstructed with the defaults). "
        "Dice and Jaccard come from the exact volume of the intersection (CGAL corefinement, "
        "exact constructions), so they carry no voxelisation error. Distances: every triangle "
        "of each surface is sampled on a lattice no coarser than --spacing and each sample gets "
        "its exact distance to the other surface; Hausdorff is the larger directed maximum, "
        "HD95 the larger directed area-weighted 95th percentile (hd95PooledMm: of both "
        "directions pooled), the mean is area-weighted over both surfaces; surface Dice is the "
        "share of both surfaces' area within --tolerance of the other; the centroid distance is "
        "between the solids' centres of mass; each is within --spacing of its exact value (a "
        "spacing that would take "
        "more than 8 388 608 samples on a surface is coarsened until it does not, with a "
        "warning; the report's distanceBoundMm is the one used). Exit codes: 0 done, 1 "
        "usage, 2 bad input (a surface that is not a valid closed solid), 3 runtime failure.");
    cmd->add_option("a", args->a, "First structure: mesh or contour file")->required();
    cmd->add_option("b", args->b, "Second structure: mesh or contour file")->required();
    cmd->add_option("--roi-a", args->roiA, "ROI of A when A is a contour file with several");
    cmd->add_option("--roi-b", args->roiB, "ROI of B when B is a contour file with several");
    cmd->add_option("--spacing", args->spacingMm,
                    "Largest lattice step of the distance samples, mm: the bound on every "
                    "distance's error")
        ->capture_default_str()
        ->check(kPositive);
    cmd->add_option("--tolerance", args->toleranceMm,
                    "Surface Dice's tolerance, mm: the share of both surfaces within this "
                    "distance of the other (surfaceDice)")
        ->capture_default_str()
        ->check(kNonNegative);
    cmd->add_flag("--json", args->json, "Print a JSON report instead of text");
    cmd->callback([args, &global] { runCompare(*args, global); });
}

}  // namespace dfrecon::app
