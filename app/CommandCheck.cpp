// dfrecon check MESH: is a mesh a watertight, consistently oriented,
// self-intersection-free 2-manifold, and what is its topology? Exit code 0
// when it is a valid closed solid, 2 when it is not (or cannot be read).
#include <iostream>

#include <nlohmann/json.hpp>

#include "app/Commands.hpp"
#include "app/StandardStreams.hpp"
#include "contours/InputError.hpp"
#include "geometry/MeshCheck.hpp"
#include "io/files/JsonText.hpp"
#include "io/mesh/MeshIO.hpp"
#include "report/ExitCodes.hpp"
#include "report/Reports.hpp"

namespace dfrecon::app {

namespace {

void runCheck(const std::string& path, bool json) {
    const TriangleSoup soup = readTriangleSoup(path);
    const MeshCheckReport r = checkMesh(soup);
    const nlohmann::ordered_json where = defectLocationsJson(r, soup);
    if (json) {
        nlohmann::ordered_json report{{"command", "check"}, {"file", path}};
        appendItems(report, meshCheckJson(r));
        appendItems(report, where);
        std::cout << jsonText(report, 2) << "\n";
    } else {
        std::cout << path << ": " << r.vertices << " vertices, " << r.triangles << " triangles, "
                  << r.components << " component(s)\n"
                  << "  boundary edges " << r.boundaryEdges << ", non-manifold edges "
                  << r.nonManifoldEdges << ", non-manifold vertices " << r.nonManifoldVertices
                  << ", misoriented edges " << r.misorientedEdges << ", degenerate triangles "
                  << r.degenerateTriangles << "\n"
                  << "  self-intersecting triangle pairs "
                  << (r.intersectingPairsCapped ? "at least " : "") << r.intersectingPairs << "\n"
                  << "  Euler characteristic " << r.eulerCharacteristic;
        if (r.genus >= 0) std::cout << ", genus " << r.genus;
        std::cout << "\n  volume " << r.volumeMm3 / 1000 << " cc, area " << r.areaMm2 << " mm2\n";
        if (!where["defectBoxMm"].is_null())
            std::cout << "  " << r.defectiveTriangles.size() << " triangle(s) in defects, within "
                      << where["defectBoxMm"]["min"].dump() << " .. "
                      << where["defectBoxMm"]["max"].dump() << " mm\n";
        for (const auto& pair : where["selfIntersectingAt"])
            std::cout << "  triangles " << pair["triangles"].dump()
                      << " meet: " << pair["cornersMm"].dump() << "\n";
        std::cout << (r.validSolid() ? "valid closed solid\n" : "NOT a valid closed solid\n");
    }
    if (!r.validSolid())
        throw InputError(path, 0,
                         r.watertight() ? "self-intersecting or inside-out surface"
                                        : "not a watertight, oriented 2-manifold");
}

}  // namespace

void addCheckCommand(CLI::App& root, const GlobalOptions&) {
    struct Args {
        std::string path;
        bool json = false;
    };
    auto args = std::make_shared<Args>();
    CLI::App* cmd = root.add_subcommand(
        "check", "Check a mesh: watertight, manifold, oriented, no self-intersections; genus");
    cmd->footer("Exit code 0 for a valid closed solid (outward normals), 2 otherwise.");
    cmd->add_option("mesh", args->path, "Mesh file (.ply .obj .off .stl)")
        ->required()
        ->check(kNotStandardStream);
    cmd->add_flag("--json", args->json, "Print a JSON report instead of text");
    cmd->callback([args] { runCheck(args->path, args->json); });
}

}  // namespace dfrecon::app
