#pragma once
// The triangle mesh type every stage shares: OpenMesh's array kernel with
// double-precision points and normals (coordinates in mm).
#if defined(__GNUC__)
#pragma GCC system_header  // OpenMesh headers are not -Wshadow clean
#endif
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>

namespace dfrecon {

struct MeshTraits : public OpenMesh::DefaultTraits {
    using Point = OpenMesh::Vec3d;
    using Normal = OpenMesh::Vec3d;
    VertexAttributes(OpenMesh::Attributes::Status);
    FaceAttributes(OpenMesh::Attributes::Status);
    EdgeAttributes(OpenMesh::Attributes::Status);
};

using TriMesh = OpenMesh::TriMesh_ArrayKernelT<MeshTraits>;

}  // namespace dfrecon
