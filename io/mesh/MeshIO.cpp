#include "io/mesh/MeshIO.hpp"

#include <OpenMesh/Core/IO/IOManager.hh>
#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/IO/importer/BaseImporter.hh>
#include <OpenMesh/Core/System/omstream.hh>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "contours/InputError.hpp"
#include "geometry/VertexNormals.hpp"
#include "io/files/AtomicWrite.hpp"
#include "io/files/InputLimits.hpp"
#include "io/files/InputsInUse.hpp"
#include "io/mesh/AttributedMesh.hpp"
#include "io/mesh/MeshFileCheck.hpp"
#include "io/mesh/VtkPolyData.hpp"

namespace dfrecon {

// OpenMesh logs every file it reads or writes ("[OBJWriter] : write file") on
// streams of its own, past --quiet; dfrecon says what it wrote itself. Its
// error stream stays: a reader's complaint can say more than ours.
[[maybe_unused]] const bool openMeshLogsOff = [] {
    omlog().disable();
    omout().disable();
    return true;
}();

bool isMeshExtension(const std::string& path) {
    const std::optional<MeshFormat> format = meshFormatOfPath(path);
    return format && isReadableMeshFormat(*format);
}

bool isMeshOutputPath(const std::string& path) {
    return meshFormatOfPath(path).has_value();
}

std::string materialLibraryPath(const std::string& objPath) {
    return std::filesystem::path(objPath).replace_extension(".mtl").string();
}

namespace {

// What both readers refuse before parsing: an extension OpenMesh does not
// read, a path that is no regular file, or a file OpenMesh would not read
// as written (io/mesh/MeshFileCheck).
void requireMeshFile(const std::string& path) {
    if (!isMeshExtension(path))
        throw InputError(path, 0,
                         "unsupported mesh extension (use " + meshExtensionList(true) + ")");
    checkMeshFileBeforeReading(path);  // through io/files/RegularFile: no pipe or device is opened
}

}  // namespace

TriMesh readMesh(const std::string& path) {
    const ReadingInput reading(path);
    // As a plain list first (no topology: linear), so that a vertex of too
    // many triangles is refused before OpenMesh links them, and before the
    // checks that compare them pairwise.
    (void)readTriangleSoup(path);
    TriMesh mesh;
    OpenMesh::IO::Options options;
    if (!OpenMesh::IO::read_mesh(mesh, path, options))
        throw InputError(path, 0, "not a readable mesh (OpenMesh could not parse it)");
    for (auto v : mesh.vertices()) {
        const auto& p = mesh.point(v);
        requireSanePoint(path, std::size_t(v.idx()), {p[0], p[1], p[2]});
    }
    if (mesh.n_faces() == 0) throw InputError(path, 0, "mesh has no triangles");
    return mesh;
}

namespace {

// The structure's name as one word: OBJ and MTL names end at white space.
std::string objName(const StructureTag& structure) {
    std::string name = structure.name.empty() ? "surface" : structure.name;
    for (char& c : name)
        if (static_cast<unsigned char>(c) <= ' ') c = '_';
    return name;
}

// What OpenMesh writes for `format` (obj off stl), into memory: the
// structure goes into those bytes before they reach the stream.
std::string openMeshBytes(TriMesh& mesh, MeshFormat format, const MeshWriteOptions& options) {
    OpenMesh::IO::Options flags;
    if (options.binary && format == MeshFormat::Stl) flags += OpenMesh::IO::Options::Binary;
    if (options.vertexNormals && format != MeshFormat::Stl) {
        setVertexNormals(mesh);
        flags += OpenMesh::IO::Options::VertexNormal;
    }
    std::ostringstream bytes;
    if (!OpenMesh::IO::write_mesh(mesh, bytes, meshFormatExtension(format), flags,
                                  kAsciiMeshDigits))
        throw std::runtime_error(std::string("OpenMesh could not write the ") +
                                 meshFormatName(format) + " mesh");
    return bytes.str();
}

// OBJ: the object and group named after the structure, and its material
// where a library beside the file holds it.
std::string objWithStructure(const std::string& obj, const StructureTag& structure,
                             const std::string& materialLibrary) {
    if (structure.empty()) return obj;
    const std::string name = objName(structure);
    std::string head;
    if (!materialLibrary.empty()) head += "mtllib " + materialLibrary + "\n";
    head += "o " + name + "\ng " + name + "\n";
    if (!materialLibrary.empty()) head += "usemtl " + name + "\n";
    return head + obj;
}

// STL: a binary file's 80-byte header, or an ASCII file's solid name. A
// binary header must not start with "solid" (readers would take the file
// for ASCII), which "dfrecon ROI" never does.
std::string stlWithStructure(std::string stl, const StructureTag& structure, bool binary) {
    if (structure.name.empty()) return stl;
    if (binary) {
        std::string header = "dfrecon ROI " + structure.name;
        header.resize(80, ' ');
        if (stl.size() < 80) throw std::runtime_error("OpenMesh wrote an STL without a header");
        stl.replace(0, 80, header);
        return stl;
    }
    std::string name = structure.name;
    for (char& c : name)
        if (static_cast<unsigned char>(c) < ' ') c = ' ';
    const std::size_t firstLineEnd = stl.find('\n');
    if (stl.compare(0, 5, "solid") != 0 || firstLineEnd == std::string::npos)
        throw std::runtime_error("OpenMesh wrote an ASCII STL without 'solid'");
    std::string out = "solid " + name + stl.substr(firstLineEnd);
    const std::size_t end = out.rfind("endsolid");
    if (end != std::string::npos) {
        const std::size_t endLineEnd = out.find('\n', end);
        out.replace(end, endLineEnd == std::string::npos ? std::string::npos : endLineEnd - end,
                    "endsolid " + name);
    }
    return out;
}

// The vertex colours and field data a structure gives PLY and VTK files.
MeshAttributes structureAttributes(std::size_t vertices, const StructureTag& structure) {
    MeshAttributes attributes;
    attributes.structure = structure;
    if (structure.colour) attributes.vertexColours.assign(vertices, *structure.colour);
    return attributes;
}

// `mesh` gains the properties the format writes (normals, colours).
void writeMeshBytes(TriMesh& mesh, std::ostream& out, MeshFormat format,
                    const MeshWriteOptions& options, const std::string& materialLibrary) {
    const StructureTag& structure = options.structure;
    switch (format) {
        case MeshFormat::Ply: {
            // Before the move: argument order is unspecified.
            const MeshAttributes attributes = structureAttributes(mesh.n_vertices(), structure);
            writeAttributedPly(out, std::move(mesh), attributes, options.binary,
                               options.vertexNormals);  // in place: no copy
            return;
        }
        case MeshFormat::Obj:
            out << objWithStructure(openMeshBytes(mesh, format, options), structure,
                                    materialLibrary);
            return;
        case MeshFormat::Off:
            out << openMeshBytes(mesh, format, options);
            return;
        case MeshFormat::Stl:
            out << stlWithStructure(openMeshBytes(mesh, format, options), structure,
                                    options.binary);
            return;
        case MeshFormat::Vtk:
        case MeshFormat::Vtp: {
            const TriangleSoup soup = toTriangleSoup(mesh);
            const MeshAttributes attributes = structureAttributes(soup.points.size(), structure);
            if (format == MeshFormat::Vtk)
                writeVtkLegacy(out, soup, attributes);
            else
                writeVtkXml(out, soup, attributes);
            return;
        }
    }
}

// An MTL file with the structure's colour as the diffuse colour of one
// material named like it (Blender and MeshLab read Kd).
void writeMaterialLibrary(const std::string& path, const StructureTag& structure) {
    const auto& c = *structure.colour;
    writeStreamAtomically(path, [&](std::ostream& out) {
        out << "# dfrecon: the display colour of ROI " << objName(structure) << "\nnewmtl "
            << objName(structure) << "\nKd " << std::setprecision(6) << c[0] / 255.0 << ' '
            << c[1] / 255.0 << ' ' << c[2] / 255.0 << "\n";
    });
}

}  // namespace

void writeMesh(const TriMesh& mesh, const std::string& path, const MeshWriteOptions& options) {
    TriMesh copy = mesh;
    writeMesh(std::move(copy), path, options);
}

void writeMesh(TriMesh&& mesh, const std::string& path, const MeshWriteOptions& options) {
    const std::optional<MeshFormat> format = meshFormatOfPath(path);
    if (!format)
        throw std::invalid_argument(path + ": unsupported mesh extension (use " +
                                    meshExtensionList(false) + ")");
    std::string materialLibrary;
    if (*format == MeshFormat::Obj && options.structure.colour) {
        // First, so that an OBJ that names its library never lacks it.
        const std::string library = materialLibraryPath(path);
        writeMaterialLibrary(library, options.structure);
        materialLibrary = std::filesystem::path(library).filename().string();
    }
    writeStreamAtomically(path, [&](std::ostream& out) {
        writeMeshBytes(mesh, out, *format, options, materialLibrary);
    });
}

void writeMesh(const TriMesh& mesh, std::ostream& out, MeshFormat format,
               const MeshWriteOptions& options) {
    TriMesh copy = mesh;
    writeMesh(std::move(copy), out, format, options);
}

void writeMesh(TriMesh&& mesh, std::ostream& out, MeshFormat format,
               const MeshWriteOptions& options) {
    writeMeshBytes(mesh, out, format, options, "");
    if (!out.flush())
        throw std::runtime_error(std::string("cannot write the ") + meshFormatName(format) +
                                 " mesh to the stream");
}

// OpenMesh's names only here (a unity build compiles the files of this
// library together).
namespace openmesh_import {

using namespace OpenMesh;

// Receives what OpenMesh's readers parse and keeps vertices and faces as
// they come; everything else (colours, normals, texture data) is ignored.
class SoupImporter : public IO::BaseImporter {
  public:
    explicit SoupImporter(TriangleSoup& soup) : soup_(soup) {}

    VertexHandle add_vertex(const Vec3f& p) override { return add_vertex(Vec3d(p)); }
    VertexHandle add_vertex(const Vec3d& p) override {
        soup_.points.push_back({p[0], p[1], p[2]});
        return VertexHandle(int(soup_.points.size()) - 1);
    }
    VertexHandle add_vertex() override { return add_vertex(Vec3d(0, 0, 0)); }
    HalfedgeHandle add_edge(VertexHandle, VertexHandle) override { return HalfedgeHandle(); }
    FaceHandle add_face(const VHandles& indices) override {
        for (std::size_t k = 1; k + 1 < indices.size(); ++k)
            soup_.triangles.push_back({std::uint32_t(indices[0].idx()),
                                       std::uint32_t(indices[k].idx()),
                                       std::uint32_t(indices[k + 1].idx())});
        return FaceHandle(int(soup_.triangles.size()) - 1);
    }
    FaceHandle add_face(HalfedgeHandle) override { return FaceHandle(); }
    void set_point(VertexHandle v, const Vec3f& p) override {
        if (v.is_valid() && std::size_t(v.idx()) < soup_.points.size())
            soup_.points[std::size_t(v.idx())] = {p[0], p[1], p[2]};
    }
    size_t n_vertices() const override { return soup_.points.size(); }
    size_t n_faces() const override { return soup_.triangles.size(); }
    size_t n_edges() const override { return 0; }

    // Attributes dfrecon does not read.
    void add_face_texcoords(FaceHandle, VertexHandle, const std::vector<Vec2f>&) override {}
    void add_face_texcoords(FaceHandle, VertexHandle, const std::vector<Vec3f>&) override {}
    void set_face_texindex(FaceHandle, int) override {}
    void set_halfedge(VertexHandle, HalfedgeHandle) override {}
    void set_normal(VertexHandle, const Vec3f&) override {}
    void set_normal(VertexHandle, const Vec3d&) override {}
    void set_color(VertexHandle, const Vec3uc&) override {}
    void set_color(VertexHandle, const Vec4uc&) override {}
    void set_color(VertexHandle, const Vec3f&) override {}
    void set_color(VertexHandle, const Vec4f&) override {}
    void set_texcoord(VertexHandle, const Vec2f&) override {}
    void set_status(VertexHandle, const Attributes::StatusInfo&) override {}
    void set_next(HalfedgeHandle, HalfedgeHandle) override {}
    void set_face(HalfedgeHandle, FaceHandle) override {}
    void request_face_texcoords2D() override {}
    void set_texcoord(HalfedgeHandle, const Vec2f&) override {}
    void set_texcoord(VertexHandle, const Vec3f&) override {}
    void set_texcoord(HalfedgeHandle, const Vec3f&) override {}
    void set_status(HalfedgeHandle, const Attributes::StatusInfo&) override {}
    void set_color(EdgeHandle, const Vec3uc&) override {}
    void set_color(EdgeHandle, const Vec4uc&) override {}
    void set_color(EdgeHandle, const Vec3f&) override {}
    void set_color(EdgeHandle, const Vec4f&) override {}
    void set_status(EdgeHandle, const Attributes::StatusInfo&) override {}
    void set_normal(FaceHandle, const Vec3f&) override {}
    void set_normal(FaceHandle, const Vec3d&) override {}
    void set_color(FaceHandle, const Vec3uc&) override {}
    void set_color(FaceHandle, const Vec4uc&) override {}
    void set_color(FaceHandle, const Vec3f&) override {}
    void set_color(FaceHandle, const Vec4f&) override {}
    void set_status(FaceHandle, const Attributes::StatusInfo&) override {}
    void add_texture_information(int, std::string) override {}

  private:
    TriangleSoup& soup_;
};

}  // namespace openmesh_import

TriangleSoup readTriangleSoup(const std::string& path) {
    const ReadingInput reading(path);
    requireMeshFile(path);
    TriangleSoup soup;
    openmesh_import::SoupImporter importer(soup);
    OpenMesh::IO::Options options;
    if (!OpenMesh::IO::IOManager().read(path, importer, options))
        throw InputError(path, 0, "not a readable mesh (OpenMesh could not parse it)");
    for (const auto& t : soup.triangles)
        for (std::uint32_t v : t)
            if (v >= soup.points.size())
                throw InputError(path, 0,
                                 "a face refers to vertex " + std::to_string(v) + " of " +
                                     std::to_string(soup.points.size()));
    for (std::size_t v = 0; v < soup.points.size(); ++v) requireSanePoint(path, v, soup.points[v]);
    if (soup.triangles.empty()) throw InputError(path, 0, "mesh has no triangles");
    std::vector<std::uint32_t> trianglesAt(soup.points.size(), 0);
    for (const auto& t : soup.triangles)
        for (std::uint32_t v : t)
            if (++trianglesAt[v] > kMaxTrianglesAtVertex)
                throw InputError(path, 0,
                                 "vertex " + std::to_string(v) + " is a corner of more than " +
                                     std::to_string(kMaxTrianglesAtVertex) +
                                     " triangles, the most one vertex may have (checks compare "
                                     "a vertex's triangles pairwise)");
    return soup;
}

}  // namespace dfrecon
