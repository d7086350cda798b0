#pragma once
// What a mesh file must be before OpenMesh reads it, and what its points
// must be after. OpenMesh's readers trust their input: a PLY header without
// end_header loops forever, a declared count allocates before anything is
// read, a face of 2^31 corners or a value its streams cannot parse (nan,
// 1e308) sends them through garbage into unbounded loops and allocations.
// These checks read the file once, with a fixed buffer, exactly as
// OpenMesh's readers will take it (PLYReader, OFFReader, OBJReader and
// STLReader of OpenMesh 9), and refuse what would not be read as written:
// declared counts the file cannot hold (an ASCII vertex takes at least 6
// bytes, a face 8; binary records their exact size), values that are not
// numbers of their type, faces of fewer than 3 or more than
// kMaxMeshFaceCorners corners or with corners that are not vertices,
// coordinates beyond kMaxAbsCoordinateMm, and layouts OpenMesh misreads.
// Every refusal is an InputError naming the file (and the line, for text).
#include <cstddef>
#include <string>

#include "geometry/Vec3.hpp"

namespace dfrecon {

/// Checks the file at `path` (.ply, .off, .obj or .stl, by extension, any
/// case) as described above. Throws InputError naming the file and what is
/// wrong. O(file size), memory O(1).
void checkMeshFileBeforeReading(const std::string& path);

/// The PLY part of checkMeshFileBeforeReading (io/mesh/PlyFileCheck.cpp).
void checkPlyFile(const std::string& path);

/// Throws InputError naming `path` and the 0-based `vertex` unless every
/// coordinate of `point` is finite and within kMaxAbsCoordinateMm. O(1).
void requireSanePoint(const std::string& path, std::size_t vertex, const Vec3& point);

}  // namespace dfrecon
