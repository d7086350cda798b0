#include "app/GeodesicOutput.hpp"

#include <OpenMesh/Core/IO/MeshIO.hh>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <stdexcept>

#include "io/AtomicWrite.hpp"
#include "io/InputError.hpp"
#include "io/MeshIO.hpp"

namespace dfrecon::app {

namespace {

// OpenMesh 9 writes persistent custom properties into PLY headers under
// their names (Options::Custom), so no PLY writer of our own is needed.
void writePly(const TriMesh& mesh, const std::string& path, OpenMesh::IO::Options options,
              bool binary) {
    options += OpenMesh::IO::Options::Custom;
    if (binary) options += OpenMesh::IO::Options::Binary;
    writeAtomically(path, [&](const std::string& temporary) {
        return OpenMesh::IO::write_mesh(mesh, temporary, options);
    });
}

/// Well-separated colours for region ids: hues by the golden angle.
TriMesh::Color regionColour(int region) {
    if (region < 0) return {128, 128, 128};
    const double hue = std::fmod(region * 137.50776, 360.0) / 60;
    const double saturation = region % 2 ? 0.55 : 0.8, value = region % 3 ? 0.95 : 0.75;
    const double c = value * saturation, x = c * (1 - std::abs(std::fmod(hue, 2) - 1));
    double r = 0, g = 0, b = 0;
    switch (int(hue)) {
        case 0:
            r = c, g = x;
            break;
        case 1:
            r = x, g = c;
            break;
        case 2:
            g = c, b = x;
            break;
        case 3:
            g = x, b = c;
            break;
        case 4:
            r = x, b = c;
            break;
        default:
            r = c, b = x;
            break;
    }
    const double m = value - c;
    return {static_cast<unsigned char>(255 * (r + m)), static_cast<unsigned char>(255 * (g + m)),
            static_cast<unsigned char>(255 * (b + m))};
}

}  // namespace

GeodesicInput readGeodesicInput(const std::string& path) {
    GeodesicInput input{readMesh(path), {}};
    try {
        input.graph = MeshGraph::fromMesh(input.mesh);
    } catch (const std::invalid_argument& e) {
        throw InputError(path, 0, e.what());
    }
    return input;
}

void requirePlyOutput(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    if (ext != ".ply")
        throw std::invalid_argument("output '" + path +
                                    "' must be .ply (the only mesh format here that carries "
                                    "per-face and per-vertex values)");
}

void writeRegionsPly(TriMesh mesh, const std::vector<int>& faceRegion, const std::string& path,
                     bool binary) {
    mesh.request_face_colors();
    OpenMesh::FPropHandleT<int> region;
    mesh.add_property(region, "region");
    mesh.property(region).set_persistent(true);
    for (auto f : mesh.faces()) {
        const int r = faceRegion[std::size_t(f.idx())];
        mesh.property(region, f) = r;
        mesh.set_color(f, regionColour(r));
    }
    writePly(mesh, path, OpenMesh::IO::Options::FaceColor, binary);
}

void writeDistancePly(TriMesh mesh, const std::vector<double>& distance,
                      const std::vector<int>& source, const std::string& path, bool binary) {
    mesh.request_vertex_colors();
    OpenMesh::VPropHandleT<float> distanceProperty;
    OpenMesh::VPropHandleT<int> sourceProperty;
    mesh.add_property(distanceProperty, "distance");
    mesh.add_property(sourceProperty, "source");
    mesh.property(distanceProperty).set_persistent(true);
    mesh.property(sourceProperty).set_persistent(true);
    double largest = 0;
    for (double d : distance)
        if (std::isfinite(d)) largest = std::max(largest, d);
    for (auto v : mesh.vertices()) {
        const double d = distance[std::size_t(v.idx())];
        mesh.property(distanceProperty, v) = std::isfinite(d) ? float(d) : -1.0f;
        mesh.property(sourceProperty, v) = source[std::size_t(v.idx())];
        if (!std::isfinite(d)) {
            mesh.set_color(v, {128, 128, 128});
            continue;
        }
        const double s = largest > 0 ? d / largest : 0;  // blue → cyan → yellow → red
        const double r = std::clamp(2 * s - 0.5, 0.0, 1.0),
                     g = std::clamp(1.5 - std::abs(4 * s - 2), 0.0, 1.0),
                     b = std::clamp(1.5 - 2 * s, 0.0, 1.0);
        mesh.set_color(v, {static_cast<unsigned char>(255 * r), static_cast<unsigned char>(255 * g),
                           static_cast<unsigned char>(255 * b)});
    }
    writePly(mesh, path, OpenMesh::IO::Options::VertexColor, binary);
}

}  // namespace dfrecon::app
