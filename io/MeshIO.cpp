#include "io/MeshIO.hpp"

#include <OpenMesh/Core/IO/IOManager.hh>
#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/IO/importer/BaseImporter.hh>
#include <OpenMesh/Core/System/omstream.hh>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "io/AtomicWrite.hpp"
#include "io/InputError.hpp"
#include "io/InputsInUse.hpp"
#include "io/MeshFileCheck.hpp"

namespace dfrecon {

// OpenMesh logs every file it reads or writes ("[OBJWriter] : write file") on
// streams of its own, past --quiet; dfrecon says what it wrote itself. Its
// error stream stays: a reader's complaint can say more than ours.
[[maybe_unused]] const bool openMeshLogsOff = [] {
    omlog().disable();
    omout().disable();
    return true;
}();

std::string lowerExtension(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return ext;
}

bool isMeshExtension(const std::string& path) {
    const std::string ext = lowerExtension(path);
    return ext == ".ply" || ext == ".obj" || ext == ".off" || ext == ".stl";
}

namespace {

// What both readers refuse before parsing: an extension OpenMesh does not
// read, a path that is no regular file, or a file OpenMesh would not read
// as written (io/MeshFileCheck).
void requireMeshFile(const std::string& path) {
    if (!isMeshExtension(path))
        throw InputError(path, 0, "unsupported mesh extension (use .ply .obj .off .stl)");
    if (!std::filesystem::is_regular_file(path)) throw InputError(path, 0, "cannot open file");
    checkMeshFileBeforeReading(path);
}

}  // namespace

TriMesh readMesh(const std::string& path) {
    const ReadingInput reading(path);
    requireMeshFile(path);
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

// What a mesh file of extension `ext` holds: a copy of `mesh` with its
// normals where the format keeps them (the caller's mesh stays const), and
// OpenMesh's flags for it.
struct MeshToWrite {
    TriMesh mesh;
    OpenMesh::IO::Options flags;
};

MeshToWrite prepareMesh(const TriMesh& mesh, const std::string& ext,
                        const MeshWriteOptions& options) {
    if (ext != ".ply" && ext != ".obj" && ext != ".off" && ext != ".stl")
        throw std::invalid_argument("unsupported mesh format '" + ext +
                                    "' (use .ply .obj .off .stl)");
    MeshToWrite out{mesh, {}};
    if (options.binary && (ext == ".ply" || ext == ".stl"))
        out.flags += OpenMesh::IO::Options::Binary;
    if (options.vertexNormals && ext != ".stl") {
        out.mesh.request_face_normals();
        out.mesh.request_vertex_normals();
        out.mesh.update_normals();
        out.flags += OpenMesh::IO::Options::VertexNormal;
    }
    return out;
}

}  // namespace

void writeMesh(const TriMesh& mesh, const std::string& path, const MeshWriteOptions& options) {
    if (!isMeshExtension(path))
        throw std::invalid_argument(path +
                                    ": unsupported mesh extension (use .ply .obj .off .stl)");
    const MeshToWrite prepared = prepareMesh(mesh, lowerExtension(path), options);
    writeAtomically(path, [&](const std::string& temporary) {
        return OpenMesh::IO::write_mesh(prepared.mesh, temporary, prepared.flags, kAsciiMeshDigits);
    });
}

void writeMesh(const TriMesh& mesh, std::ostream& out, const std::string& extension,
               const MeshWriteOptions& options) {
    const MeshToWrite prepared = prepareMesh(mesh, extension, options);
    if (!OpenMesh::IO::write_mesh(prepared.mesh, out, extension, prepared.flags,
                                  kAsciiMeshDigits) ||
        !out.flush())
        throw std::runtime_error("cannot write the " + extension.substr(1) + " mesh to the stream");
}

namespace {

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

}  // namespace

TriangleSoup readTriangleSoup(const std::string& path) {
    const ReadingInput reading(path);
    requireMeshFile(path);
    TriangleSoup soup;
    SoupImporter importer(soup);
    IO::Options options;
    if (!IO::IOManager().read(path, importer, options))
        throw InputError(path, 0, "not a readable mesh (OpenMesh could not parse it)");
    for (const auto& t : soup.triangles)
        for (std::uint32_t v : t)
            if (v >= soup.points.size())
                throw InputError(path, 0,
                                 "a face refers to vertex " + std::to_string(v) + " of " +
                                     std::to_string(soup.points.size()));
    for (std::size_t v = 0; v < soup.points.size(); ++v) requireSanePoint(path, v, soup.points[v]);
    if (soup.triangles.empty()) throw InputError(path, 0, "mesh has no triangles");
    return soup;
}

}  // namespace dfrecon
