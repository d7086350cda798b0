#pragma once
// Per-vertex normals for writing a mesh, without a normal per face.
#include "geometry/TriMesh.hpp"

namespace dfrecon {

/// Requests `mesh`'s vertex normals and sets each to what OpenMesh's
/// update_normals() gives (the normalised sum of the unit normals of the
/// vertex's faces, summed in the same order, so the same bits) without
/// requesting face normals: those are 24 bytes a face held only for this
/// (66 MB on a 2.8 M-triangle surface). Each face's normal is computed once
/// per corner instead. O(faces).
void setVertexNormals(TriMesh& mesh);

}  // namespace dfrecon
