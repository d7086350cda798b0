#pragma once
// The mesh file formats dfrecon reads and writes, and the one table that
// maps them to extensions and names: every command picks a mesh format
// here, from a file's extension or from --format.
//   ply  PLY (binary or ASCII)            read and written
//   obj  Wavefront OBJ (+ MTL colour)     read and written
//   off  OFF                              read and written
//   stl  STL (binary or ASCII)            read and written
//   vtk  legacy VTK polydata (ASCII)      written only
//   vtp  VTK XML PolyData (binary base64) written only
// What each carries and which viewer reads it: docs/formats.md.
#include <optional>
#include <string>
#include <vector>

namespace dfrecon {

/// Significant digits of coordinates in ASCII mesh files: enough to give
/// back every double (and so every float) exactly. OpenMesh's default of 6
/// moves points by up to a micrometre at patient coordinates, which can
/// make a checked valid surface intersect itself in the file.
inline constexpr int kAsciiMeshDigits = 17;

enum class MeshFormat { Ply, Obj, Off, Stl, Vtk, Vtp };

/// The file name's extension in lower case, dot included ("" for none).
std::string lowerExtension(const std::string& path);

/// The format of `path` by its extension (any letter case); nullopt for
/// another. O(length).
std::optional<MeshFormat> meshFormatOfPath(const std::string& path);

/// The format named `name` ("ply" ... "vtp", lower case, as --format takes
/// it); nullopt for another. O(1).
std::optional<MeshFormat> meshFormatNamed(const std::string& name);

/// "ply" ... "vtp". O(1).
const char* meshFormatName(MeshFormat format);

/// ".ply" ... ".vtp". O(1).
std::string meshFormatExtension(MeshFormat format);

/// Whether dfrecon reads this format (OpenMesh's readers: ply obj off stl).
bool isReadableMeshFormat(MeshFormat format);

/// The names of every format, or of the readable ones ("ply" ...), in the
/// order above. O(1).
std::vector<std::string> meshFormatNames(bool readableOnly);

/// The names of every format, or of the readable ones, as a list for
/// messages and --help: "ply, obj, off, stl, vtk or vtp". O(1).
std::string meshFormatList(bool readableOnly);

/// The extensions likewise: ".ply .obj .off .stl .vtk .vtp". O(1).
std::string meshExtensionList(bool readableOnly);

}  // namespace dfrecon
