// dfrecon sdm A.ply B.ply ... -o DIR: surface distance maps between meshes
// (paper surface-distance-maps): at every vertex and atlas texel of each
// mesh, the signed distance to the nearest other mesh and which one it is;
// plus pairwise separation, collision and penetration with their bounds.
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <set>

#include <nlohmann/json.hpp>

#include "api/Stopwatch.hpp"
#include "app/Commands.hpp"
#include "app/HtmlReport.hpp"
#include "app/OutputOptions.hpp"
#include "app/Progress.hpp"
#include "app/StandardStreams.hpp"
#include "contours/InputError.hpp"
#include "dfrecon/SurfaceDistanceMaps.hpp"
#include "io/files/AtomicWrite.hpp"
#include "io/files/JsonText.hpp"
#include "io/images/Colours.hpp"
#include "io/images/FieldImages.hpp"
#include "io/images/ImageFiles.hpp"
#include "io/mesh/AttributedMesh.hpp"
#include "io/mesh/MeshIO.hpp"
#include "report/NumberChecks.hpp"
#include "report/Reports.hpp"

namespace dfrecon::app {

namespace {

struct SdmArgs {
    std::vector<std::string> inputs;
    std::string outputDir;
    int sizeTexels = 512;
    double maxErrorMm = 0;
    double maxDistanceMm = 0;
    bool json = false, noImages = false, noPairs = false;
    std::string reportPath;
    std::vector<std::string> meshFormats{"ply", "vtk"};
};

// NAME.FORMAT for each of `formats`, in their order.
nlohmann::ordered_json meshFiles(const std::string& name, const std::vector<std::string>& formats) {
    nlohmann::ordered_json files = nlohmann::ordered_json::array();
    for (const std::string& format : formats) files.push_back(name + "." + format);
    return files;
}

// File stems of the inputs, unique even on file systems that ignore letter
// case (lung.ply and LUNG.ply would be one file there): a stem that repeats
// gets _2, _3... on its second and later uses, skipping names taken.
std::vector<std::string> objectNames(const std::vector<std::string>& inputs) {
    auto key = [](std::string stem) {
        for (char& c : stem) c = char(std::tolower(static_cast<unsigned char>(c)));
        return stem;
    };
    std::set<std::string> taken;
    std::vector<std::string> names;
    for (const std::string& input : inputs) {
        std::string stem = std::filesystem::path(input).stem().string();
        if (stem.empty()) stem = "mesh";
        std::string name = stem;
        for (int k = 2; taken.count(key(name)); ++k) name = stem + "_" + std::to_string(k);
        taken.insert(key(name));
        names.push_back(name);
    }
    return names;
}

/// Where and how every object's maps are written: the folder, the mesh
/// formats, whether the atlas images too, and the distance the colour ramps
/// reach their ends at.
struct MapOutputs {
    std::filesystem::path dir;
    std::vector<std::string> formats;
    bool images = true;
    double colourFarMm = 1;
};

/// Object `name`'s surface `soup` with its vertex map, in every format, and
/// its atlas images (TIFF and PNG) when asked.
void writeObjectOutputs(const MapOutputs& out, const std::string& name, const TriangleSoup& soup,
                        const ObjectSamples& samples, const ObjectDistanceMap& map) {
    const std::filesystem::path& dir = out.dir;
    const double colourFarMm = out.colourFarMm;
    MeshAttributes data;
    std::vector<float> distance(soup.points.size());
    std::vector<std::int32_t> nearest(soup.points.size());
    std::vector<Vec3> direction(soup.points.size());
    for (std::size_t v = 0; v < soup.points.size(); ++v) {
        const ClosestPrimitive& c = map.vertices[v];
        distance[v] = c.object < 0 ? std::numeric_limits<float>::infinity() : float(c.distanceMm);
        nearest[v] = c.object;
        direction[v] = c.object < 0 ? Vec3{} : c.point - soup.points[v];
        // Diverging: a clearance map is read first for its sign (inside
        // another mesh or not), which a sequential ramp cannot show.
        data.vertexColours.push_back(
            divergingColour(c.object < 0 ? INFINITY : c.distanceMm, colourFarMm));
    }
    data.vertexScalars = {{"distance", distance}};
    data.vertexLabels = {{"nearest_object", nearest}};
    for (const std::string& format : out.formats) {
        MeshAttributes file = data;
        if (format == "ply")
            file.vertexScalars.push_back({"quality", distance});  // what MeshLab colours by
        else
            file.vertexVectors = {{"to_nearest", direction}};  // PLY has no vectors
        writeAttributedMesh(soup, file, (dir / (name + "." + format)).string());
    }
    if (!out.images) return;
    const int w = samples.atlas.width, h = samples.atlas.height;
    const std::vector<float> d = distanceImage(samples, map);
    writeFloatTiff((dir / (name + "_distance.tif")).string(), d.data(), w, h, 1);
    const std::vector<float> n = nearestObjectImage(samples, map);
    writeFloatTiff((dir / (name + "_nearest.tif")).string(), n.data(), w, h, 1);
    const std::vector<float> dir3 = directionImage(samples, map);
    writeFloatTiff((dir / (name + "_direction.tif")).string(), dir3.data(), w, h, 3);
    ImageFrame frame;
    frame.pixelMm = samples.atlas.texelMm;
    frame.width = w;
    frame.height = h;
    writeSignedFieldPng((dir / (name + "_distance.png")).string(), d.data(), frame, {},
                        colourFarMm / 4);
    std::vector<std::uint32_t> labels(n.size());
    for (std::size_t k = 0; k < n.size(); ++k)
        labels[k] = n[k] < 0 ? 0xffffffffu : std::uint32_t(n[k]);
    writeLabelPng((dir / (name + "_nearest.png")).string(), labels.data(), frame, {});
}

// The HTML report: the objects' table beside the meshes coloured by their
// vertices' signed distance to the nearest other mesh.
void writeSdmPage(const std::string& path, const SurfaceScene& scene,
                  const std::vector<std::string>& names, const std::vector<ObjectDistanceMap>& maps,
                  const nlohmann::ordered_json& objects, double colourFarMm) {
    HtmlReport page;
    page.title = "dfrecon sdm";
    page.columns = {"name", "triangles", "closed", "minDistanceMm", "texelsInsideOthers"};
    page.rows = objects;
    page.valueName = "signed distance to the nearest other mesh, mm (negative inside it)";
    page.valueScaleMm = colourFarMm;
    std::string leftOut;
    for (std::size_t o = 0; o < scene.objectCount(); ++o) {
        ReportSurface s{names[o], categoricalColour(std::int64_t(o) + 1), scene.object(o), {}};
        for (const ClosestPrimitive& c : maps[o].vertices)
            s.valuesMm.push_back(c.object < 0 ? INFINITY : float(c.distanceMm));
        if (!addSurface(page, std::move(s))) leftOut += (leftOut.empty() ? "" : ", ") + names[o];
    }
    if (!leftOut.empty()) page.note = "Not drawn (too many triangles in all): " + leftOut + ".";
    writeHtmlReport(path, page);
}

void runSdm(const SdmArgs& args, const GlobalOptions& global) {
    Stopwatch watch;
    if (args.inputs.size() < 2)
        throw std::invalid_argument("sdm needs at least two meshes (distances are to the others)");
    const std::vector<std::string> names = objectNames(args.inputs);
    std::vector<TriangleSoup> soups;
    for (const std::string& input : args.inputs) {
        TriangleSoup soup = readTriangleSoup(input);
        if (soup.triangles.empty()) throw InputError(input, 0, "mesh has no triangles");
        soups.push_back(std::move(soup));
    }
    const SurfaceScene scene(std::move(soups), names);

    SceneMapsOptions options;
    options.atlas.sizeTexels = args.sizeTexels;
    options.atlas.maxErrorMm = args.maxErrorMm;
    if (args.maxDistanceMm > 0) options.query.maxDistanceMm = args.maxDistanceMm;
    options.proximity = !args.noPairs;
    options.labels = args.inputs;

    ocl::Runtime runtime(global.device);
    Progress progress("distance maps", !global.quiet);
    const SceneMaps computed = sceneDistanceMaps(runtime, scene, options);
    progress.finish();
    const std::vector<ObjectSamples>& samples = computed.samples;
    const std::vector<ObjectDistanceMap>& maps = computed.maps;
    const std::vector<PairProximity>& pairs = computed.pairs;
    const double mapSeconds = computed.mapSeconds;

    std::filesystem::create_directories(args.outputDir);
    MapOutputs outputs{args.outputDir, args.meshFormats, !args.noImages, args.maxDistanceMm};
    // Colours span the band, or the scene's largest vertex clearance.
    if (outputs.colourFarMm <= 0) {
        for (const ObjectDistanceMap& m : maps)
            for (const ClosestPrimitive& c : m.vertices)
                if (c.object >= 0)
                    outputs.colourFarMm = std::max(outputs.colourFarMm, c.distanceMm);
        outputs.colourFarMm = std::max(outputs.colourFarMm, 1.0);
    }
    nlohmann::ordered_json objects = nlohmann::ordered_json::array();
    for (std::size_t o = 0; o < scene.objectCount(); ++o) {
        writeObjectOutputs(outputs, names[o], scene.object(o), samples[o], maps[o]);
        double nearestMm = INFINITY;
        std::size_t inside = 0;
        for (const ClosestPrimitive& c : maps[o].texels) {
            if (c.object < 0) continue;
            nearestMm = std::min(nearestMm, c.distanceMm);
            inside += c.distanceMm < 0;
        }
        objects.push_back({{"name", names[o]},
                           {"input", args.inputs[o]},
                           {"triangles", scene.object(o).triangles.size()},
                           {"closed", scene.closed(o)},
                           {"atlas", {samples[o].atlas.width, samples[o].atlas.height}},
                           {"texelMm", samples[o].atlas.texelMm},
                           {"samplingBoundMm", samples[o].samplingBoundMm()},
                           {"usedTexels", samples[o].texelCount()},
                           {"minDistanceMm", valueOrNull(std::isfinite(nearestMm), nearestMm)},
                           {"texelsInsideOthers", inside},
                           {"outputs", meshFiles(names[o], args.meshFormats)}});
    }
    nlohmann::ordered_json pairReport = nlohmann::ordered_json::array();
    for (const PairProximity& p : pairs)
        pairReport.push_back({{"first", names[p.first]},
                              {"second", names[p.second]},
                              {"separationMm", p.separationMm},
                              {"separationBoundMm", p.boundMm},
                              {"colliding", p.colliding()},
                              {"surfacesIntersect", p.surfacesIntersect},
                              {"firstInsideSecond", p.firstInsideSecond},
                              {"secondInsideFirst", p.secondInsideFirst},
                              {"deepestPointMm", p.deepestPointMm},
                              {"depthBoundMm", p.depthBoundMm},
                              {"pointOnFirst", xyzJson(p.pointOnFirst)},
                              {"pointOnSecond", xyzJson(p.pointOnSecond)}});
    nlohmann::ordered_json report{
        {"command", "sdm"},
        {"device", runtime.device().deviceName},
        {"maxDistanceMm", valueOrNull(args.maxDistanceMm > 0, args.maxDistanceMm)},
        {"objects", objects},
        {"pairs", pairReport},
        {"mapSeconds", mapSeconds},
        {"totalSeconds", watch.total()}};
    writeStreamAtomically((outputs.dir / "report.json").string(),
                          [&](std::ostream& out) { out << jsonText(report, 2) << "\n"; });
    if (!args.reportPath.empty())
        writeSdmPage(args.reportPath, scene, names, maps, objects, outputs.colourFarMm);
    if (args.json) {
        std::cout << jsonText(report, 2) << "\n";
        return;
    }
    // Micrometres are the most any of these numbers means.
    auto mm = [](double value) {
        char text[32];
        std::snprintf(text, sizeof text, "%.3f", value);
        return std::string(text);
    };
    for (std::size_t o = 0; o < scene.objectCount(); ++o) {
        const auto& nearest = objects[o]["minDistanceMm"];
        std::cout << names[o] << ": " << samples[o].texelCount() << " texels of "
                  << mm(samples[o].atlas.texelMm) << " mm (sampling bound "
                  << mm(samples[o].samplingBoundMm()) << " mm), nearest other object at "
                  << (nearest.is_number() ? mm(nearest.get<double>()) + " mm" : nearest.dump())
                  << "\n";
    }
    for (const PairProximity& p : pairs)
        std::cout << names[p.first] << " - " << names[p.second] << ": "
                  << (p.colliding()
                          ? "COLLIDING, deepest point " + mm(p.deepestPointMm) + " mm inside"
                          : "separated by " + mm(p.separationMm) + " mm (exact to within " +
                                mm(p.boundMm) + " mm)")
                  << "\n";
    std::cout << "-> " << args.outputDir << "\n";
}

}  // namespace

void addSdmCommand(CLI::App& root, const GlobalOptions& global) {
    auto args = std::make_shared<SdmArgs>();
    CLI::App* cmd = root.add_subcommand(
        "sdm", "Surface distance maps: distance to and identity of the nearest other mesh");
    cmd->footer(
        "For every vertex and atlas texel of each mesh: the distance to the nearest OTHER mesh "
        "(negative inside a closed one), which mesh that is, and the direction to its closest "
        "point. Each mesh's atlas maps every triangle to its own texels; every point of the "
        "surface is within the sampling bound (sqrt(2) x texel size) of a sample, so the maps "
        "are exact at samples and within that bound everywhere. Writes into DIR, per "
        "--mesh-formats: NAME.ply (vertex properties distance, quality, nearest_object and "
        "colours: MeshLab, Blender), NAME.vtk and NAME.vtp (the same as point arrays plus "
        "to_nearest vectors: ParaView, 3D Slicer), "
        "NAME_distance.tif / NAME_nearest.tif / NAME_direction.tif (32-bit float atlas maps, NaN "
        "or -1 at unused texels) with PNG previews, and report.json (per mesh and per pair: "
        "separation with its bound, closest points, collision, deepest penetrating point). "
        "Exit codes: 0 done, 1 usage, 2 bad input, 3 runtime failure. See docs/cli.md.");
    cmd->add_option("meshes", args->inputs, "Two or more meshes (.ply .stl .obj .off), in mm")
        ->required()
        ->check(kNotStandardStream);
    cmd->add_option("-o,--output", args->outputDir, "Output folder (created if missing)")
        ->required()
        ->check(kNotStandardStream);
    cmd->add_option("--size", args->sizeTexels,
                    "Atlas width and height in texels per mesh; the texel size is the smallest "
                    "at which all triangles fit")
        ->capture_default_str()
        ->check(CLI::Range(16, 8192));
    cmd->add_option("--max-error", args->maxErrorMm,
                    "Instead of --size: the sampling bound in mm (texel = bound / sqrt(2)); the "
                    "atlas grows to fit")
        ->check(kPositive);
    cmd->add_option("--max-distance", args->maxDistanceMm,
                    "Clearance band in mm: look no farther (faster); points with nothing "
                    "closer get distance inf and nearest_object -1 (default: no limit)")
        ->check(kPositive);
    cmd->add_option("--mesh-formats", args->meshFormats,
                    "The mesh files written per input, comma-separated: ply, vtk (legacy VTK) "
                    "and/or vtp (VTK XML)")
        ->delimiter(',')
        ->capture_default_str()
        ->check(CLI::IsMember({"ply", "vtk", "vtp"}));
    cmd->add_flag("--no-images", args->noImages, "Skip the atlas TIFF and PNG maps");
    cmd->add_flag("--no-pairs", args->noPairs, "Skip the pairwise proximity queries");
    cmd->add_option("--report", args->reportPath,
                    "Also write FILE.html: one self-contained page (no network needed) with the "
                    "objects' table beside an interactive 3D view of the meshes coloured by each "
                    "vertex's signed distance to the nearest other mesh (blue inside it, white "
                    "touching, red away)");
    cmd->add_flag("--json", args->json, "Print the JSON report to stdout too");
    asOutput(cmd->get_option("--output"), OutputKind::Folder);
    asOutput(cmd->get_option("--report"), OutputKind::File);
    cmd->callback([args, &global] { runSdm(*args, global); });
}

}  // namespace dfrecon::app
