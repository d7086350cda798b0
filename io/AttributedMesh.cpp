#include "io/AttributedMesh.hpp"

#include <OpenMesh/Core/IO/MeshIO.hh>
#include <ostream>
#include <sstream>
#include <stdexcept>

#include "io/AtomicWrite.hpp"
#include "io/MeshFormat.hpp"
#include "io/VtkPolyData.hpp"

namespace dfrecon {

namespace {

// Persistent properties are what OpenMesh's PLY writer emits as custom
// properties, under their names.
template <class Handle, class Range, class Values>
void addProperty(TriMesh& mesh, const std::string& name, Range elements, const Values& values) {
    Handle handle;
    mesh.add_property(handle, name);
    mesh.property(handle).set_persistent(true);
    for (auto e : elements) mesh.property(handle, e) = values[std::size_t(e.idx())];
}

// A header comment runs to the end of its line.
std::string oneLine(const std::string& text) {
    std::string line = text;
    for (char& c : line)
        if (static_cast<unsigned char>(c) < ' ') c = ' ';
    return line;
}

// The structure's comments go right after the format line: OpenMesh's
// reader finds binary data from the last token before end_header, which
// a comment there would move (io/PlyFileCheck).
std::string withStructureComments(const std::string& ply, const StructureTag& structure) {
    if (structure.empty()) return ply;
    std::string comments;
    if (!structure.name.empty()) comments += "comment roi_name " + oneLine(structure.name) + "\n";
    if (const auto& c = structure.colour)
        comments += "comment roi_colour " + std::to_string((*c)[0]) + " " +
                    std::to_string((*c)[1]) + " " + std::to_string((*c)[2]) + "\n";
    const std::size_t formatLine = ply.find('\n');
    const std::size_t afterFormat =
        formatLine == std::string::npos ? std::string::npos : ply.find('\n', formatLine + 1);
    if (afterFormat == std::string::npos)
        throw std::runtime_error("OpenMesh wrote a PLY without a format line");
    return ply.substr(0, afterFormat + 1) + comments + ply.substr(afterFormat + 1);
}

}  // namespace

void writeAttributedPly(std::ostream& out, TriMesh mesh, const MeshAttributes& attributes,
                        bool binary, bool vertexNormals) {
    checkAttributeSizes(attributes, mesh.n_vertices(), mesh.n_faces());
    OpenMesh::IO::Options flags = OpenMesh::IO::Options::Custom;
    if (binary) flags += OpenMesh::IO::Options::Binary;
    if (vertexNormals) {
        mesh.request_face_normals();
        mesh.request_vertex_normals();
        mesh.update_normals();
        flags += OpenMesh::IO::Options::VertexNormal;
    }
    if (!attributes.vertexColours.empty()) {
        mesh.request_vertex_colors();
        for (auto v : mesh.vertices()) {
            const Rgb& c = attributes.vertexColours[std::size_t(v.idx())];
            mesh.set_color(v, {c[0], c[1], c[2]});
        }
        flags += OpenMesh::IO::Options::VertexColor;
    }
    if (!attributes.faceColours.empty()) {
        mesh.request_face_colors();
        for (auto f : mesh.faces()) {
            const Rgb& c = attributes.faceColours[std::size_t(f.idx())];
            mesh.set_color(f, {c[0], c[1], c[2]});
        }
        flags += OpenMesh::IO::Options::FaceColor;
    }
    for (const auto& [name, values] : attributes.vertexScalars)
        addProperty<OpenMesh::VPropHandleT<float>>(mesh, name, mesh.vertices(), values);
    for (const auto& [name, values] : attributes.vertexLabels)
        addProperty<OpenMesh::VPropHandleT<int>>(mesh, name, mesh.vertices(), values);
    for (const auto& [name, values] : attributes.faceLabels)
        addProperty<OpenMesh::FPropHandleT<int>>(mesh, name, mesh.faces(), values);
    std::ostringstream ply;
    if (!OpenMesh::IO::write_mesh(mesh, ply, ".ply", flags, kAsciiMeshDigits))
        throw std::runtime_error("OpenMesh could not write the PLY");
    out << withStructureComments(ply.str(), attributes.structure);
}

void writeAttributedPly(TriMesh mesh, const MeshAttributes& attributes, const std::string& path,
                        bool binary) {
    checkAttributeSizes(attributes, mesh.n_vertices(), mesh.n_faces());
    writeStreamAtomically(path, [&](std::ostream& out) {
        writeAttributedPly(out, std::move(mesh), attributes, binary);
    });
}

void writeAttributedPly(const TriangleSoup& soup, const MeshAttributes& attributes,
                        const std::string& path, bool binary) {
    checkAttributeSizes(attributes, soup.points.size(), soup.triangles.size());
    // toTriMesh keeps the points in order, so vertex arrays line up.
    std::size_t refused = 0;
    TriMesh mesh = toTriMesh(soup, &refused);
    if (refused > 0 && attributes.hasFaceData())
        throw std::invalid_argument(std::to_string(refused) +
                                    " non-manifold triangles cannot go into a PLY with face data");
    writeAttributedPly(std::move(mesh), attributes, path, binary);
}

bool isAttributedMeshPath(const std::string& path) {
    const std::optional<MeshFormat> format = meshFormatOfPath(path);
    return format == MeshFormat::Ply || format == MeshFormat::Vtk || format == MeshFormat::Vtp;
}

namespace {

void requireAttributedMeshPath(const std::string& path) {
    if (!isAttributedMeshPath(path))
        throw std::invalid_argument("'" + path +
                                    "': meshes with attributes are .ply, .vtk or .vtp");
}

void writeVtkFile(const TriangleSoup& soup, const MeshAttributes& attributes,
                  const std::string& path) {
    checkAttributeSizes(attributes, soup.points.size(), soup.triangles.size());
    const bool xml = meshFormatOfPath(path) == MeshFormat::Vtp;
    writeStreamAtomically(path, [&](std::ostream& out) {
        if (xml)
            writeVtkXml(out, soup, attributes);
        else
            writeVtkLegacy(out, soup, attributes);
    });
}

}  // namespace

void writeAttributedMesh(const TriMesh& mesh, const MeshAttributes& attributes,
                         const std::string& path, bool binary) {
    requireAttributedMeshPath(path);
    if (meshFormatOfPath(path) == MeshFormat::Ply)
        writeAttributedPly(mesh, attributes, path, binary);
    else
        writeVtkFile(toTriangleSoup(mesh), attributes, path);
}

void writeAttributedMesh(const TriangleSoup& soup, const MeshAttributes& attributes,
                         const std::string& path, bool binary) {
    requireAttributedMeshPath(path);
    if (meshFormatOfPath(path) == MeshFormat::Ply)
        writeAttributedPly(soup, attributes, path, binary);
    else
        writeVtkFile(soup, attributes, path);
}

}  // namespace dfrecon
