#pragma once
// Triangle meshes (OpenMesh half-edge structure, double precision in mm) and
// their files, the format chosen by extension (io/mesh/MeshFormat): PLY (binary
// or ASCII), OBJ, OFF, STL read and written through OpenMesh; legacy VTK and
// VTK XML PolyData written (io/mesh/VtkPolyData). docs/formats.md says what each
// file carries.
#include <iosfwd>
#include <string>

#include "geometry/TriMesh.hpp"
#include "geometry/TriangleSoup.hpp"
#include "io/mesh/MeshFormat.hpp"
#include "io/mesh/StructureTag.hpp"

namespace dfrecon {

struct MeshWriteOptions {
    bool binary = true;         // PLY and STL: binary (smaller, exact floats)
    bool vertexNormals = true;  // PLY, OBJ, OFF: per-vertex normals
    /// The ROI the mesh is the surface of, where the format has a place for
    /// it: PLY header comments and vertex colours; OBJ "o"/"g" names and,
    /// with a colour, a material in NAME.mtl beside the file (not on a
    /// stream); VTK and VTP field data and a vertex colour array; the binary
    /// STL header and ASCII STL's solid name (no colour); nothing in OFF.
    /// Without a colour no colour is written.
    StructureTag structure;
};

/// True for the formats dfrecon reads: .ply .obj .off .stl (any letter case).
bool isMeshExtension(const std::string& path);

/// True for the formats writeMesh writes: those and .vtk .vtp.
bool isMeshOutputPath(const std::string& path);

/// The material library writeMesh puts beside an OBJ file with a coloured
/// structure: the same path with the extension .mtl.
std::string materialLibraryPath(const std::string& objPath);

/// Reads a mesh; throws InputError naming the file when it cannot be read,
/// has an unsupported extension, or holds no triangles.
TriMesh readMesh(const std::string& path);

/// Reads any mesh file OpenMesh reads (.ply .obj .off .stl) as a soup:
/// polygons are split into triangle fans, nothing is dropped or merged
/// (STL's corners are merged by position, as OpenMesh's STL reader does).
/// Throws InputError naming the file when it cannot be read.
TriangleSoup readTriangleSoup(const std::string& path);

/// Writes `mesh` by extension (any of isMeshOutputPath) through a temporary
/// file and a rename, so a failure leaves no partial file; an OBJ with a
/// coloured structure gets its material library first, the same way.
/// PLY, OBJ, OFF and STL hold floats (OpenMesh's writers; ASCII with
/// kAsciiMeshDigits, so each float exactly), VTK and VTP doubles. Throws
/// std::runtime_error on failure, std::invalid_argument for an unsupported
/// extension. O(vertices + faces). The writers add what they write
/// (normals, colours) to the mesh as properties: a const mesh is copied
/// first, a mesh passed as an rvalue (std::move: OpenMesh's meshes have no
/// move constructor, so by-value would copy it too) gains them in place,
/// which saves the copy (150 MB for a 2.8 M-triangle surface).
void writeMesh(const TriMesh& mesh, const std::string& path, const MeshWriteOptions& options = {});
void writeMesh(TriMesh&& mesh, const std::string& path, const MeshWriteOptions& options = {});

/// Writes `mesh` to a stream (standard output: `-o -`) in `format`, the same
/// bytes writeMesh would put in a file, except that an OBJ names no material
/// library (there is no file beside a stream to hold it). Throws
/// std::runtime_error when the stream fails (checked after a flush).
void writeMesh(const TriMesh& mesh, std::ostream& out, MeshFormat format,
               const MeshWriteOptions& options = {});
void writeMesh(TriMesh&& mesh, std::ostream& out, MeshFormat format,
               const MeshWriteOptions& options = {});

}  // namespace dfrecon
