#include "io/MeshIO.hpp"

#include <OpenMesh/Core/IO/MeshIO.hh>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <stdexcept>

#include "io/AtomicWrite.hpp"
#include "io/InputError.hpp"

namespace dfrecon {

static std::string lowerExtension(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return ext;
}

bool isMeshExtension(const std::string& path) {
    const std::string ext = lowerExtension(path);
    return ext == ".ply" || ext == ".obj" || ext == ".off" || ext == ".stl";
}

TriMesh readMesh(const std::string& path) {
    if (!isMeshExtension(path))
        throw InputError(path, 0, "unsupported mesh extension (use .ply .obj .off .stl)");
    if (!std::filesystem::is_regular_file(path)) throw InputError(path, 0, "cannot open file");
    TriMesh mesh;
    OpenMesh::IO::Options options;
    if (!OpenMesh::IO::read_mesh(mesh, path, options))
        throw InputError(path, 0, "not a readable mesh (OpenMesh could not parse it)");
    if (mesh.n_faces() == 0) throw InputError(path, 0, "mesh has no triangles");
    return mesh;
}

void writeMesh(const TriMesh& mesh, const std::string& path, const MeshWriteOptions& options) {
    if (!isMeshExtension(path))
        throw std::invalid_argument(path +
                                    ": unsupported mesh extension (use .ply .obj .off .stl)");
    const std::string ext = lowerExtension(path);

    // Normals are computed on a copy so the caller's mesh stays const.
    TriMesh copy = mesh;
    OpenMesh::IO::Options flags;
    if (options.binary && (ext == ".ply" || ext == ".stl")) flags += OpenMesh::IO::Options::Binary;
    if (options.vertexNormals && ext != ".stl") {
        copy.request_face_normals();
        copy.request_vertex_normals();
        copy.update_normals();
        flags += OpenMesh::IO::Options::VertexNormal;
    }
    writeAtomically(path, [&](const std::string& temporary) {
        return OpenMesh::IO::write_mesh(copy, temporary, flags);
    });
}

}  // namespace dfrecon
