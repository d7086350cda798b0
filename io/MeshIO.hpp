#pragma once
// Triangle meshes (OpenMesh half-edge structure, double precision in mm) and
// their files: PLY (binary or ASCII), OBJ, OFF, STL, chosen by extension.
#include <iosfwd>
#include <string>

#include "geometry/TriMesh.hpp"
#include "geometry/TriangleSoup.hpp"

namespace dfrecon {

/// Significant digits of coordinates in ASCII mesh files: enough to give
/// back every double (and so every float) exactly. OpenMesh's default of 6
/// moves points by up to a micrometre at patient coordinates, which can
/// make a checked valid surface intersect itself in the file.
inline constexpr int kAsciiMeshDigits = 17;

struct MeshWriteOptions {
    bool binary = true;         // PLY and STL: binary (smaller, exact floats)
    bool vertexNormals = true;  // PLY, OBJ, OFF: per-vertex normals
};

/// The file name's extension in lower case, dot included ("" for none).
std::string lowerExtension(const std::string& path);

/// True for .ply .obj .off .stl (any letter case).
bool isMeshExtension(const std::string& path);

/// Reads a mesh; throws InputError naming the file when it cannot be read,
/// has an unsupported extension, or holds no triangles.
TriMesh readMesh(const std::string& path);

/// Reads any mesh file OpenMesh reads (.ply .obj .off .stl) as a soup:
/// polygons are split into triangle fans, nothing is dropped or merged
/// (STL's corners are merged by position, as OpenMesh's STL reader does).
/// Throws InputError naming the file when it cannot be read.
TriangleSoup readTriangleSoup(const std::string& path);

/// Writes `mesh` by extension through a temporary file and a rename, so a
/// failure leaves no partial file. Throws std::runtime_error on failure,
/// std::invalid_argument for an unsupported extension.
void writeMesh(const TriMesh& mesh, const std::string& path, const MeshWriteOptions& options = {});

/// Writes `mesh` to a stream (standard output: `-o -`) in the format of
/// `extension` (".ply" .obj .off .stl), the same bytes writeMesh would put in
/// a file. Throws std::runtime_error when the stream fails (checked after a
/// flush), std::invalid_argument for an unsupported extension.
void writeMesh(const TriMesh& mesh, std::ostream& out, const std::string& extension,
               const MeshWriteOptions& options = {});

}  // namespace dfrecon
