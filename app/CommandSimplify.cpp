// dfrecon simplify IN -o OUT --max-error MM: error-bounded edge collapse of a
// closed surface (docs/simplification.md), with the bound it certifies and
// the distance an independent check measures.
#include <iostream>
#include <memory>

#include <nlohmann/json.hpp>

#include "api/Stopwatch.hpp"
#include "app/Commands.hpp"
#include "app/Inputs.hpp"
#include "app/OutputOptions.hpp"
#include "app/RoiReconstruction.hpp"
#include "app/SimplifyAndVerify.hpp"
#include "app/StandardStreams.hpp"
#include "contours/InputError.hpp"
#include "geometry/MeshCheck.hpp"
#include "io/files/JsonText.hpp"
#include "io/mesh/MeshIO.hpp"
#include "report/NumberChecks.hpp"
#include "report/Reports.hpp"

namespace dfrecon::app {

namespace {

struct SimplifyArgs {
    std::string input, output, field, contours, roi, format;
    bool json = false, ascii = false;
    SimplifyOptions options;
};

void runSimplify(const SimplifyArgs& args, const GlobalOptions& global) {
    const Stopwatch watch;
    const MeshOutput output = meshOutput(args.output, args.format, args.json);
    TriangleSoup surface = readTriangleSoup(args.input);
    // The same test as dfrecon check: the bounds and the collision test
    // assume a valid closed solid, and on a surface that already meets
    // itself (two faces back to back) the decimation ran for minutes.
    const MeshCheckReport before = checkMesh(surface);
    if (!before.validSolid())
        throw InputError(args.input, 0,
                         "not a valid closed solid (" + std::to_string(before.boundaryEdges) +
                             " boundary edges, " + std::to_string(before.nonManifoldEdges) +
                             " non-manifold edges, " + std::to_string(before.nonManifoldVertices) +
                             " non-manifold vertices, " + std::to_string(before.misorientedEdges) +
                             " misoriented edges, " + std::to_string(before.degenerateTriangles) +
                             " degenerate triangles, " + std::to_string(before.intersectingPairs) +
                             " self-intersecting triangle pairs, " +
                             (before.volumeMm3 > 0 ? "" : "no ") +
                             "positive volume); run dfrecon check");
    SimplifyRequest request;
    request.options = args.options;
    request.label = "simplifying " + args.input;
    std::unique_ptr<LevelSetSampler> field;
    if (!args.field.empty()) {
        field = std::make_unique<LevelSetSampler>(args.field);
        request.field = field.get();
    }
    ContourInput contours;
    if (!args.contours.empty()) {
        contours = loadContours(args.contours, global, onlyRoi(args.roi));
        request.contours = selectRois(contours.contours, args.roi, false).front();
    }
    ocl::Runtime runtime(global.device);
    nlohmann::ordered_json report = simplifyAndVerify(runtime, surface, request, global);
    const MeshCheckReport after = checkMesh(surface);
    MeshWriteOptions write;
    write.binary = !args.ascii;
    if (request.contours) write.structure = structureTagOf(*request.contours);
    writeMeshOutput(toTriMesh(surface), output, write);
    if (!args.json) {
        reportStream(output.toStandardOutput())
            << args.input << ": " << report["trianglesBefore"] << " -> " << report["triangles"]
            << " triangles within " << args.options.maxErrorMm << " mm (verified max "
            << report["verified"]["maxMm"].get<double>() << " mm), "
            << (after.validSolid() ? "closed valid solid" : "NOT a valid closed solid") << " -> "
            << output.label() << "\n";
        return;
    }
    nlohmann::ordered_json out{{"command", "simplify"},
                               {"input", args.input},
                               {"output", args.output},
                               {"device", runtime.device().deviceName}};
    appendItems(out, report);
    out["validSolid"] = after.validSolid();
    out["genusBefore"] = before.genus;
    out["genus"] = after.genus;
    out["totalSeconds"] = watch.total();
    std::cout << jsonText(out, 2) << "\n";
}

}  // namespace

void addSimplifyCommand(CLI::App& root, const GlobalOptions& global) {
    auto args = std::make_shared<SimplifyArgs>();
    CLI::App* cmd = root.add_subcommand(
        "simplify", "Simplify a closed surface with a guaranteed two-sided error bound");
    cmd->footer(
        "Edge collapses (OpenMesh Decimater) that keep every point of the result within "
        "--max-error of the input surface and every point of the input within --max-error of "
        "the result, with no self-intersections, flips or topology changes. The report gives the "
        "certified bound and the distance an independent check (dense samples, exact distances) "
        "measures. Exit codes: 0 done, 1 usage, 2 bad input, 3 runtime failure. See "
        "docs/simplification.md.");
    cmd->add_option("file", args->input, "Input closed mesh (.ply .stl .obj .off)")
        ->required()
        ->check(kNotStandardStream);
    cmd->add_option("-o,--output", args->output,
                    "Output mesh file (.ply .stl .obj .off .vtk .vtp), or - for standard output "
                    "(with --format); with --contours it is named after that ROI, and coloured "
                    "where the ROI has a colour")
        ->required();
    addMeshFormatOption(*cmd, args->format,
                        "Mesh format for -o - (standard output; with a file the extension "
                        "decides)");
    cmd->add_option("--max-error", args->options.maxErrorMm,
                    "The two-sided bound in mm (every point of either surface this close to the "
                    "other); at least 1e-6 mm, below which coordinates do not resolve it")
        ->required()
        ->check(maxErrorCheck(kMinMaxErrorMm, false));
    cmd->add_option("--field", args->field,
                    "A .vdb distance field (from dfrecon field): also report the largest |field| "
                    "on the result, i.e. how far it is from the contours' surface (measured, not "
                    "bounded)");
    cmd->add_option("--contours", args->contours,
                    "The .slices file the mesh was made from: also verify the distance from "
                    "every contour to the result");
    cmd->add_option("--roi", args->roi, "ROI of --contours (default: the only one)");
    cmd->add_option("--max-normal-turn", args->options.maxNormalTurnDeg,
                    "Largest angle in degrees a face normal may turn in one collapse")
        ->capture_default_str()
        ->check(CLI::Range(1.0, 90.0));
    cmd->add_flag("--ascii", args->ascii, "ASCII PLY/STL instead of binary");
    cmd->add_flag("--json", args->json, "Print a JSON report instead of text");
    asOutput(cmd->get_option("--output"), OutputKind::File);
    cmd->callback([args, &global] { runSimplify(*args, global); });
}

}  // namespace dfrecon::app
