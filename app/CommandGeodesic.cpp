// dfrecon geodesic MESH --from V[,V...] -o OUT.ply: geodesic distance on a
// surface from source vertices (fast marching, or the OpenCL fast
// iterative method where that is faster), per vertex in the PLY.
#include <cmath>
#include <iostream>
#include <memory>
#include <sstream>

#include <nlohmann/json.hpp>

#include "api/Stopwatch.hpp"
#include "app/Commands.hpp"
#include "app/GeodesicOutput.hpp"
#include "app/OutputOptions.hpp"
#include "app/StandardStreams.hpp"
#include "io/files/JsonText.hpp"
#include "report/EnumNames.hpp"
#include "report/NumberChecks.hpp"
#include "report/Reports.hpp"
#include "segment/GeodesicDistances.hpp"
#include "segment/SpeedFunctions.hpp"

namespace dfrecon::app {

namespace {

// The --solver names. Reports print segment's toString(GeodesicSolver), the
// longer names a reader of the JSON needs no manual for.
constexpr EnumNames<GeodesicSolver, 3> kSolverOptionNames{{
    {"auto", GeodesicSolver::Automatic},
    {"fm", GeodesicSolver::FastMarching},
    {"fim", GeodesicSolver::FastIterative},
}};

struct GeodesicArgs {
    std::string input, output, from;
    std::string speed = nameOf(kSpeedKindNames, SpeedKind::Uniform);
    std::string solver = nameOf(kSolverOptionNames, GeodesicSolver::Automatic);
    double curvatureWeightMm = 0;
    bool json = false, ascii = false, noUnfold = false;
};

/// "3,17,42" → {3, 17, 42}; std::invalid_argument (exit 1) otherwise. A
/// string, not a CLI11 vector option, so that `--from 0 MESH` does not take
/// the mesh as a second vertex.
std::vector<int> parseVertexList(const std::string& text) {
    std::vector<int> vertices;
    std::stringstream list(text);
    for (std::string item; std::getline(list, item, ',');) {
        std::size_t used = 0;
        int v = -1;
        try {
            v = std::stoi(item, &used);
        } catch (const std::exception&) {
            used = 0;
        }
        if (used == 0 || used != item.size() || v < 0)
            throw std::invalid_argument("--from: '" + item + "' is not a vertex index");
        vertices.push_back(v);
    }
    if (vertices.empty()) throw std::invalid_argument("--from: no vertices given");
    return vertices;
}

void runGeodesic(const GeodesicArgs& args, const GlobalOptions& global) {
    Stopwatch watch;
    requireAttributedMeshOutput(args.output);
    GeodesicInput input = readGeodesicInput(args.input);
    const int n = input.graph.vertexCount();
    const std::vector<int> from = parseVertexList(args.from);
    std::vector<GeodesicSource> sources;
    for (int v : from) {
        if (v < 0 || v >= n)
            throw std::invalid_argument("--from vertex " + std::to_string(v) +
                                        " is not a vertex of " + args.input + " (it has " +
                                        std::to_string(n) + ")");
        sources.push_back({v, 0.0, int(sources.size())});
    }
    const SpeedKind kind = parseEnum(kSpeedKindNames, args.speed, "--speed");
    const double weight =
        args.curvatureWeightMm > 0 ? args.curvatureWeightMm : defaultCurvatureWeight(input.graph);
    UnfoldOptions unfold;
    unfold.unfoldObtuse = !args.noUnfold;
    const UpdateStencils stencils(input.graph, unfold);
    const std::vector<double> speed = curvatureSpeed(input.graph, kind, weight);
    // Only open a device when the FIM may run: fast marching needs none.
    std::unique_ptr<ocl::Runtime> runtime;
    const GeodesicSolver requested = parseEnum(kSolverOptionNames, args.solver, "--solver");
    if (requested != GeodesicSolver::FastMarching)
        runtime = std::make_unique<ocl::Runtime>(global.device);
    watch.restartLap();
    GeodesicSolver used = requested;
    const GeodesicField field =
        geodesicDistances(stencils, sources, speed, runtime.get(), requested, &used);
    const double solveSeconds = watch.lap();
    writeDistances(std::move(input.mesh), field.time, field.label, args.output, !args.ascii);

    double largest = 0, sum = 0;
    int reached = 0;
    for (double t : field.time)
        if (std::isfinite(t)) {
            largest = std::max(largest, t);
            sum += t;
            ++reached;
        }
    if (!args.json) {
        std::cout << args.input << ": distances from " << sources.size() << " vertices, largest "
                  << largest << (kind == SpeedKind::Uniform ? " mm" : " (weighted)") << ", "
                  << n - reached << " vertices unreached (" << toString(used) << ") -> "
                  << args.output << "\n";
        return;
    }
    const nlohmann::ordered_json out{
        {"command", "geodesic"},
        {"input", args.input},
        {"output", args.output},
        {"vertices", n},
        {"faces", input.graph.triangleCount()},
        {"sources", from},
        {"speed", nameOf(kSpeedKindNames, kind)},
        {"curvatureWeightMm", kind == SpeedKind::Uniform ? 0.0 : weight},
        {"solver", toString(used)},
        {"device", valueOrNull(runtime != nullptr, runtime ? runtime->device().deviceName : "")},
        {"obtuseCorners", stencils.obtuseCorners()},
        {"unfoldFailures", stencils.unfoldFailures()},
        {"maxDistance", largest},
        {"meanDistance", reached > 0 ? sum / reached : 0.0},
        {"unreachedVertices", n - reached},
        {"seconds", solveSeconds},
        {"totalSeconds", watch.total()}};
    std::cout << jsonText(out, 2) << "\n";
}

}  // namespace

void addGeodesicCommand(CLI::App& root, const GlobalOptions& global) {
    auto args = std::make_shared<GeodesicArgs>();
    CLI::App* cmd =
        root.add_subcommand("geodesic", "Geodesic distance on a surface from source vertices");
    cmd->footer(
        "Fast marching on the triangles with obtuse angles unfolded, or the OpenCL fast "
        "iterative method where it is faster (on a GPU, large meshes; both give the same "
        "distances). Writes a PLY with vertex properties 'distance' (mm; the weighted "
        "distance ∫ds/F for a non-uniform speed; -1 where unreached) and 'source' (index into "
        "--from), and colours, or a VTK (.vtk) or VTK XML (.vtp) file with the same as point "
        "arrays 'distance', 'source' and 'colour'. Exit codes: 0 done, 1 usage, 2 bad input, 3 "
        "runtime failure.");
    cmd->add_option("file", args->input, "Input triangle mesh (.ply .stl .obj .off), mm")
        ->required()
        ->check(kNotStandardStream);
    cmd->add_option("-o,--output", args->output, "Output mesh with distances (.ply, .vtk or .vtp)")
        ->required()
        ->check(kNotStandardStream);
    cmd->add_option("--from", args->from, "Source vertex indices (0-based), comma-separated")
        ->required();
    cmd->add_option("--speed", args->speed,
                    "Front speed F: uniform (distance in mm), repulsive (1+e·κ) or attractive "
                    "(1/(1+m·κ)), κ the total curvature")
        ->capture_default_str()
        ->check(CLI::IsMember(namesOf(kSpeedKindNames)));
    cmd->add_option("--curvature-weight", args->curvatureWeightMm,
                    "e or m of the curvature speeds, in mm (default: √(area/10))")
        ->check(kPositive);
    cmd->add_option("--solver", args->solver,
                    "auto (the faster for this mesh and device), fm (fast marching) or fim "
                    "(OpenCL fast iterative method)")
        ->capture_default_str()
        ->check(CLI::IsMember(namesOf(kSolverOptionNames)));
    cmd->add_flag("--no-unfold", args->noUnfold,
                  "Use obtuse triangles as they are (less accurate; for comparison)");
    cmd->add_flag("--ascii", args->ascii, "ASCII PLY instead of binary");
    cmd->add_flag("--json", args->json, "Print a JSON report instead of text");
    asOutput(cmd->get_option("--output"), OutputKind::File);
    cmd->callback([args, &global] { runGeodesic(*args, global); });
}

}  // namespace dfrecon::app
