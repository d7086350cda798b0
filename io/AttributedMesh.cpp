#include "io/AttributedMesh.hpp"

#include <OpenMesh/Core/IO/MeshIO.hh>
#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <ostream>
#include <sstream>
#include <stdexcept>

#include "io/AtomicWrite.hpp"
#include "io/MeshIO.hpp"

namespace dfrecon {

namespace {

template <class Values>
void checkSize(const std::string& what, const std::string& name, const Values& values,
               std::size_t count) {
    if (values.size() != count)
        throw std::invalid_argument(what + " data '" + name + "' has " +
                                    std::to_string(values.size()) + " values for " +
                                    std::to_string(count) + " " + what + "s");
}

void checkSizes(const MeshAttributes& a, std::size_t vertices, std::size_t faces) {
    for (const auto& [name, v] : a.vertexScalars) checkSize("vertex", name, v, vertices);
    for (const auto& [name, v] : a.vertexLabels) checkSize("vertex", name, v, vertices);
    for (const auto& [name, v] : a.vertexVectors) checkSize("vertex", name, v, vertices);
    if (!a.vertexColours.empty()) checkSize("vertex", "colours", a.vertexColours, vertices);
    for (const auto& [name, v] : a.faceLabels) checkSize("face", name, v, faces);
    if (!a.faceColours.empty()) checkSize("face", "colours", a.faceColours, faces);
}

bool hasFaceData(const MeshAttributes& a) {
    return !a.faceLabels.empty() || !a.faceColours.empty();
}

// Persistent properties are what OpenMesh's PLY writer emits as custom
// properties, under their names.
template <class Handle, class Range, class Values>
void addProperty(TriMesh& mesh, const std::string& name, Range elements, const Values& values) {
    Handle handle;
    mesh.add_property(handle, name);
    mesh.property(handle).set_persistent(true);
    for (auto e : elements) mesh.property(handle, e) = values[std::size_t(e.idx())];
}

}  // namespace

void writeAttributedPly(TriMesh mesh, const MeshAttributes& attributes, const std::string& path,
                        bool binary) {
    checkSizes(attributes, mesh.n_vertices(), mesh.n_faces());
    OpenMesh::IO::Options flags = OpenMesh::IO::Options::Custom;
    if (binary) flags += OpenMesh::IO::Options::Binary;
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
    writeAtomically(path, [&](const std::string& temporary) {
        return OpenMesh::IO::write_mesh(mesh, temporary, flags, kAsciiMeshDigits);
    });
}

void writeAttributedPly(const TriangleSoup& soup, const MeshAttributes& attributes,
                        const std::string& path, bool binary) {
    checkSizes(attributes, soup.points.size(), soup.triangles.size());
    // toTriMesh keeps the points in order, so vertex arrays line up.
    std::size_t refused = 0;
    TriMesh mesh = toTriMesh(soup, &refused);
    if (refused > 0 && hasFaceData(attributes))
        throw std::invalid_argument(std::to_string(refused) +
                                    " non-manifold triangles cannot go into a PLY with face data");
    writeAttributedPly(std::move(mesh), attributes, path, binary);
}

void writeAttributedVtk(const TriangleSoup& soup, const MeshAttributes& attributes,
                        const std::string& path) {
    checkSizes(attributes, soup.points.size(), soup.triangles.size());
    writeStreamAtomically(path, [&](std::ostream& out) {
        out << "# vtk DataFile Version 3.0\ndfrecon mesh with per-vertex and per-face data\n"
               "ASCII\nDATASET POLYDATA\nPOINTS "
            << soup.points.size() << " double\n"
            << std::setprecision(17);
        for (const Vec3& p : soup.points) out << p.x << ' ' << p.y << ' ' << p.z << '\n';
        out << "POLYGONS " << soup.triangles.size() << ' ' << 4 * soup.triangles.size() << '\n';
        for (const auto& t : soup.triangles)
            out << "3 " << t[0] << ' ' << t[1] << ' ' << t[2] << '\n';
        // VTK's legacy reader takes "nan" and "inf" spelled this way.
        auto number = [&](float v) {
            if (std::isnan(v)) return std::string("nan");
            if (std::isinf(v)) return std::string(v > 0 ? "inf" : "-inf");
            std::ostringstream s;
            s << std::setprecision(9) << v;
            return s.str();
        };
        auto labels = [&](const std::vector<NamedArray<std::int32_t>>& arrays) {
            for (const auto& [name, values] : arrays) {
                out << "SCALARS " << name << " int 1\nLOOKUP_TABLE default\n";
                for (std::int32_t v : values) out << v << '\n';
            }
        };
        auto colours = [&](const std::vector<Rgb>& values) {
            if (values.empty()) return;
            out << "COLOR_SCALARS colour 3\n" << std::setprecision(4);
            for (const Rgb& c : values)
                out << c[0] / 255.0 << ' ' << c[1] / 255.0 << ' ' << c[2] / 255.0 << '\n';
        };
        out << "POINT_DATA " << soup.points.size() << '\n';
        for (const auto& [name, values] : attributes.vertexScalars) {
            out << "SCALARS " << name << " float 1\nLOOKUP_TABLE default\n";
            for (float v : values) out << number(v) << '\n';
        }
        labels(attributes.vertexLabels);
        for (const auto& [name, values] : attributes.vertexVectors) {
            out << "VECTORS " << name << " float\n";
            for (const Vec3& v : values)
                out << number(float(v.x)) << ' ' << number(float(v.y)) << ' ' << number(float(v.z))
                    << '\n';
        }
        colours(attributes.vertexColours);
        if (!hasFaceData(attributes)) return;
        out << "CELL_DATA " << soup.triangles.size() << '\n';
        labels(attributes.faceLabels);
        colours(attributes.faceColours);
    });
}

void writeAttributedVtk(const TriMesh& mesh, const MeshAttributes& attributes,
                        const std::string& path) {
    writeAttributedVtk(toTriangleSoup(mesh), attributes, path);
}

bool isAttributedMeshPath(const std::string& path) {
    const std::string ext = lowerExtension(path);
    return ext == ".ply" || ext == ".vtk";
}

void writeAttributedMesh(TriMesh mesh, const MeshAttributes& attributes, const std::string& path,
                         bool binary) {
    const std::string ext = lowerExtension(path);
    if (ext == ".ply")
        writeAttributedPly(std::move(mesh), attributes, path, binary);
    else if (ext == ".vtk")
        writeAttributedVtk(mesh, attributes, path);
    else
        throw std::invalid_argument("'" + path + "': meshes with attributes are .ply or .vtk");
}

}  // namespace dfrecon
