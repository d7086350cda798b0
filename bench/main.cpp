// dfrecon-bench SUITE [--device SPEC]: runs one benchmark suite (or `all`)
// and prints its JSON lines.
#include <exception>
#include <iostream>
#include <string>

#include "app/HeapArenas.hpp"
#include "bench/Benchmarks.hpp"

using namespace dfrecon::bench;

int main(int argc, char** argv) {
    // As the dfrecon program does: the structure-set routes measure its memory.
    dfrecon::app::oneHeapArenaPerCore();
    const std::string usage =
        "usage: dfrecon-bench "
        "fields|recon|truth|simplify|slices-io|rtstruct|sdm|segment|structure-set|compare|margin|"
        "label-maps|neighbours|atlases|"
        "all "
        "[--device SPEC] [--truth-sets DIR] [--truth-set NAME]\n"
        "  fields     2D signed distance fields: kernel vs brute force vs OpenCV "
        "distanceTransform\n"
        "  recon      reconstruction quality on the synth shapes (marching-cubes baseline)\n"
        "  truth      reconstruction against known truth: atlas surfaces cut by planes "
        "(scripts/truth_sets.sh; --truth-sets DIR, default build/truth-sets; --truth-set NAME "
        "for one), every ROI by dfrecon linear and smooth, shape-based interpolation, "
        "rasterise + marching cubes and the contour-implied volume\n"
        "  simplify   error-bounded simplification vs OpenMesh's ModQuadric+ModHausdorff\n"
        "  slices-io  .slices reading and writing vs a bare iostream read\n"
        "  rtstruct   RTSTRUCT reading and writing (plastimatch fixtures) vs DCMTK's dcmrt "
        "parse\n"
        "  sdm        surface distance maps, 512x512 per object, 6K-triangle scene, vs brute "
        "force and OpenVDB meshToVolume\n"
        "  segment    geodesic distances (fast marching, OpenCL fast iterative method) on spheres "
        "and libcgal-demo meshes; geodesic Lloyd segmentation\n"
        "  structure-set  whole structure sets (Brodmann atlas, kmeans, many blobs) through "
        "reconstruct --all vs rasterise + marching cubes, each route in a process of its own "
        "(its peak memory; --route CASE:dfrecon|CASE:raster runs one, as the suite does)\n"
        "  margin     exact margins of spheres and cubes vs the exact offset, voxel EDT margins "
        "(1, 0.5 mm) and plastimatch's distance map\n"
        "  compare    Dice and Hausdorff of offset balls: surfaces (exact overlap) vs voxels, "
        "against the exact values\n"
        "  label-maps label maps of the shared structure sets' ROIs (1 cc or more) from the "
        "reconstructed solid vs from the 3D distance field: volume against the surface's\n"
        "  neighbours touching ROIs (split ball, Brodmann atlas) reconstructed each on its own "
        "vs moved apart: the overlap left between pairs (exact) and the volumes\n"
        "  atlases    every area of AAL and AICHA cut by planes (scripts/truth_sets.sh --whole, "
        "into "
        "build/atlas-sets): those of 0.5 cc or more beyond 2 % of their contour volume, each "
        "against its true surface's volume\n";
    if (argc < 2) {
        std::cerr << usage;
        return 1;
    }
    const std::string suite = argv[1];
    std::string device, truthSets, truthSet, route;
    for (int a = 2; a + 1 < argc; ++a) {
        const std::string flag = argv[a];
        if (flag == "--device") device = argv[a + 1];
        if (flag == "--truth-sets") truthSets = argv[a + 1];
        if (flag == "--truth-set") truthSet = argv[a + 1];
        if (flag == "--route") route = argv[a + 1];
    }
    try {
        if (suite == "fields") return benchFields(device);
        if (suite == "slices-io") return benchSlicesIO();
        if (suite == "recon") return benchRecon(device);
        if (suite == "truth") return benchTruth(device, truthSets, truthSet);
        if (suite == "simplify") return benchSimplify(device);
        if (suite == "rtstruct") return benchRtStruct();
        if (suite == "sdm") return benchSdm(device);
        if (suite == "segment") return benchSegment(device);
        if (suite == "structure-set") return benchStructureSet(device, route);
        if (suite == "compare") return benchCompare(device);
        if (suite == "margin") return benchMargin(device);
        if (suite == "label-maps") return benchLabelMaps(device);
        if (suite == "neighbours") return benchNeighbours(device);
        if (suite == "atlases") return benchAtlases(device);
        if (suite == "all")
            return benchSlicesIO() | benchRtStruct() | benchFields(device) | benchRecon(device) |
                   benchTruth(device, truthSets, truthSet) | benchSimplify(device) |
                   benchSdm(device) | benchSegment(device) | benchStructureSet(device) |
                   benchCompare(device) | benchMargin(device) | benchLabelMaps(device) |
                   benchNeighbours(device) | benchAtlases(device);
    } catch (const std::exception& e) {
        std::cerr << "dfrecon-bench " << suite << ": " << e.what() << "\n";
        return 1;
    }
    std::cerr << usage;
    return 1;
}
