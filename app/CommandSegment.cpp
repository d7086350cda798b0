// dfrecon segment MESH -k N -o OUT.ply: compact, near-equal-area regions
// whose borders follow sharp creases (geodesic centroidal Voronoi
// tessellation; docs/segmentation.md), with per-face region ids and colours
// in the PLY, a report of each region and, with --report, an HTML page
// that draws the regions in their colours.
#include <cmath>
#include <iostream>
#include <memory>
#include <numeric>
#include <unordered_map>

#include <nlohmann/json.hpp>

#include "api/Stopwatch.hpp"
#include "app/Commands.hpp"
#include "app/GeodesicOutput.hpp"
#include "app/HtmlReport.hpp"
#include "app/OutputOptions.hpp"
#include "app/Progress.hpp"
#include "app/StandardStreams.hpp"
#include "io/files/JsonText.hpp"
#include "io/images/Colours.hpp"
#include "report/EnumNames.hpp"
#include "report/NumberChecks.hpp"
#include "report/Reports.hpp"
#include "segment/Segmentation.hpp"

namespace dfrecon::app {

namespace {

struct SegmentArgs {
    std::string input, output, reportPath,
        speed = nameOf(kSpeedKindNames, SpeedKind::EdgeAttractive);
    int regions = 10;
    bool json = false, ascii = false, noDisks = false;
    SegmentOptions options;
};

// One row per region, and one surface per region in the colour the output
// mesh gives it (the same categorical colour), so the page shows what a
// viewer of the PLY shows and each region can be hidden on its own.
void writeSegmentPage(const std::string& path, const TriMesh& mesh,
                      const std::vector<int>& faceRegion, const nlohmann::ordered_json& regions) {
    HtmlReport page;
    page.title = "dfrecon segment";
    page.columns = {"region", "areaMm2", "perimeterMm", "compactness", "faces", "disk"};
    page.rows = regions;
    const TriangleSoup whole = toTriangleSoup(mesh);
    // Each region keeps its points shared between its triangles (a smaller
    // page, and smooth shading as in the other reports): one map per region
    // from the mesh's point to the region's, O(F) in all.
    std::vector<TriangleSoup> parts(regions.size());
    std::vector<std::unordered_map<std::uint32_t, std::uint32_t>> localPoint(regions.size());
    for (std::size_t f = 0; f < whole.triangles.size(); ++f) {
        // -1: a face no front reached (a component without a seed).
        if (faceRegion[f] < 0 || std::size_t(faceRegion[f]) >= parts.size()) continue;
        const std::size_t r = std::size_t(faceRegion[f]);
        std::array<std::uint32_t, 3> t{};
        for (std::size_t c = 0; c < 3; ++c) {
            const std::uint32_t p = whole.triangles[f][c];
            const auto [it, added] =
                localPoint[r].try_emplace(p, std::uint32_t(parts[r].points.size()));
            if (added) parts[r].points.push_back(whole.points[p]);
            t[c] = it->second;
        }
        parts[r].triangles.push_back(t);
    }
    std::size_t notDrawn = 0;
    for (std::size_t r = 0; r < parts.size(); ++r) {
        // Named as its row, so the table shows its swatch and a box to hide it.
        ReportSurface s{
            std::to_string(r), categoricalColour(std::int64_t(r)), std::move(parts[r]), {}};
        if (!addSurface(page, std::move(s))) ++notDrawn;
    }
    if (notDrawn > 0)
        page.note = std::to_string(notDrawn) + " regions not drawn (too many triangles in all).";
    writeHtmlReport(path, page);
}

void runSegment(SegmentArgs args, const GlobalOptions& global) {
    const Stopwatch watch;
    requireAttributedMeshOutput(args.output);
    args.options.speed = parseEnum(kSpeedKindNames, args.speed, "--speed");
    args.options.regions = args.regions;
    args.options.lloyd.diskConstraint = !args.noDisks;
    GeodesicInput input = readGeodesicInput(args.input);
    if (args.regions > input.graph.vertexCount())
        throw std::invalid_argument("-k " + std::to_string(args.regions) + " is more than the " +
                                    std::to_string(input.graph.vertexCount()) + " vertices of " +
                                    args.input);
    Progress progress("segmenting " + args.input, !global.quiet);
    args.options.progress = [&progress](double done) { progress.update(done); };
    const Segmentation s = segmentMesh(input.graph, args.options);
    progress.finish();

    std::vector<double> areas;
    for (const RegionReport& r : s.regions) areas.push_back(r.areaMm2);
    const double mean = std::accumulate(areas.begin(), areas.end(), 0.0) / double(areas.size());
    double variance = 0;
    for (double a : areas) variance += (a - mean) * (a - mean) / double(areas.size());
    const nlohmann::ordered_json regions = segmentRegionsJson(s.regions);
    if (!args.reportPath.empty())
        writeSegmentPage(args.reportPath, input.mesh, s.faceRegion, regions);
    writeRegions(std::move(input.mesh), s.faceRegion, args.output, !args.ascii);
    if (!args.json) {
        std::cout << args.input << ": " << s.regions.size() << " regions (" << s.seedsAdded
                  << " added for disks), area " << mean << " ± " << std::sqrt(variance) << " mm², "
                  << s.iterations << " Lloyd iterations" << (s.converged ? "" : " (not converged)")
                  << " -> " << args.output << "\n";
        return;
    }
    const nlohmann::ordered_json out{{"command", "segment"},
                                     {"input", args.input},
                                     {"output", args.output},
                                     {"vertices", input.graph.vertexCount()},
                                     {"faces", input.graph.triangleCount()},
                                     {"speed", nameOf(kSpeedKindNames, args.options.speed)},
                                     {"curvatureWeightMm", s.curvatureWeightMm},
                                     {"requestedRegions", args.regions},
                                     {"regionCount", s.regions.size()},
                                     {"seedsAddedForDisks", s.seedsAdded},
                                     {"seedsAddedForComponents", s.componentSeeds},
                                     {"iterations", s.iterations},
                                     {"converged", s.converged},
                                     {"lloydEnergy", s.energy},
                                     {"areaMeanMm2", mean},
                                     {"areaStdDevMm2", std::sqrt(variance)},
                                     {"areaVarianceMm4", variance},
                                     {"regions", regions},
                                     {"seconds", s.seconds},
                                     {"totalSeconds", watch.total()}};
    std::cout << jsonText(out, 2) << "\n";
}

}  // namespace

void addSegmentCommand(CLI::App& root, const GlobalOptions& global) {
    auto args = std::make_shared<SegmentArgs>();
    CLI::App* cmd = root.add_subcommand(
        "segment", "Cut a surface into compact, near-equal-area patches along its creases");
    cmd->footer(
        "Geodesic centroidal Voronoi tessellation (docs/segmentation.md): seeds by farthest-point "
        "sampling, then Lloyd iterations moving each seed to its region's intrinsic centre of "
        "mass; distances by fast marching with a curvature speed. With --speed attractive "
        "(default) seeds are sampled with the edge-repulsive speed and regions use the "
        "edge-attractive one, so borders settle on sharp creases; uniform and repulsive use that "
        "speed throughout. A region that is not a topological disk gets an extra seed. The PLY "
        "holds a face property 'region' and face colours (MeshLab, Blender); the VTK (.vtk) or "
        "VTK XML (.vtp) file holds them as cell arrays 'region' and 'colour' (ParaView, 3D "
        "Slicer). Exit codes: 0 done, 1 usage, 2 bad input, 3 runtime failure.");
    cmd->add_option("file", args->input, "Input triangle mesh (.ply .stl .obj .off), mm")
        ->required()
        ->check(kNotStandardStream);
    cmd->add_option("-o,--output", args->output, "Output mesh with region ids (.ply, .vtk or .vtp)")
        ->required()
        ->check(kNotStandardStream);
    cmd->add_option("-k,--regions", args->regions, "Number of regions (seeds) to start from")
        ->capture_default_str()
        ->check(kPositive);
    cmd->add_option("--speed", args->speed, "Front speed: uniform, repulsive or attractive")
        ->capture_default_str()
        ->check(CLI::IsMember(namesOf(kSpeedKindNames)));
    cmd->add_option("--iterations", args->options.lloyd.maxIterations,
                    "Most Lloyd iterations (they stop earlier once no vertex changes region)")
        ->capture_default_str()
        ->check(kNonNegative);
    cmd->add_option("--curvature-weight", args->options.curvatureWeightMm,
                    "e and m of the curvature speeds 1+e·κ and 1/(1+m·κ), in mm (default: "
                    "√(area/k), so crossing a 90° crease costs about one region's width)")
        ->check(kPositive);
    cmd->add_flag("--no-disk-constraint", args->noDisks,
                  "Do not add seeds where a region is not a topological disk");
    cmd->add_option("--report", args->reportPath,
                    "Also write FILE.html: one self-contained page (no network needed) with the "
                    "regions' table beside an interactive 3D view of the surface, each region in "
                    "its colour")
        ->check(kNotStandardStream);
    cmd->add_flag("--ascii", args->ascii, "ASCII PLY instead of binary");
    cmd->add_flag("--json", args->json, "Print a JSON report instead of text");
    asOutput(cmd->get_option("--output"), OutputKind::File);
    asOutput(cmd->get_option("--report"), OutputKind::File);
    cmd->callback([args, &global] { runSegment(*args, global); });
}

}  // namespace dfrecon::app
