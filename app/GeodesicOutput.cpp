#include "app/GeodesicOutput.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "contours/InputError.hpp"
#include "io/images/Colours.hpp"
#include "io/mesh/AttributedMesh.hpp"
#include "io/mesh/MeshIO.hpp"

namespace dfrecon::app {

GeodesicInput readGeodesicInput(const std::string& path) {
    GeodesicInput input{readMesh(path), {}};
    try {
        input.graph = MeshGraph::fromMesh(input.mesh);
    } catch (const std::invalid_argument& e) {
        throw InputError(path, 0, e.what());
    }
    return input;
}

void requireAttributedMeshOutput(const std::string& path) {
    if (!isAttributedMeshPath(path))
        throw std::invalid_argument("output '" + path +
                                    "' must be .ply, .vtk or .vtp (the mesh formats here that "
                                    "carry per-face and per-vertex values)");
}

void writeRegions(TriMesh mesh, const std::vector<int>& faceRegion, const std::string& path,
                  bool binary) {
    MeshAttributes attributes;
    attributes.faceLabels = {{"region", {faceRegion.begin(), faceRegion.end()}}};
    for (int region : faceRegion) attributes.faceColours.push_back(categoricalColour(region));
    writeAttributedMesh(std::move(mesh), attributes, path, binary);
}

void writeDistances(TriMesh mesh, const std::vector<double>& distance,
                    const std::vector<int>& source, const std::string& path, bool binary) {
    double largest = 0;
    for (double d : distance)
        if (std::isfinite(d)) largest = std::max(largest, d);
    std::vector<float> written;
    std::vector<Rgb> colours;
    for (double d : distance) {
        written.push_back(std::isfinite(d) ? float(d) : -1.0f);
        colours.push_back(sequentialColour(d, largest));
    }
    MeshAttributes attributes;
    attributes.vertexScalars = {{"distance", std::move(written)}};
    attributes.vertexLabels = {{"source", {source.begin(), source.end()}}};
    attributes.vertexColours = std::move(colours);
    writeAttributedMesh(std::move(mesh), attributes, path, binary);
}

}  // namespace dfrecon::app
