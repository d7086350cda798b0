// Meshes with per-vertex and per-face data: every array reaches the PLY
// header or the VTK sections under its name, and a wrong size or format is
// refused before anything is written.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "io/AttributedMesh.hpp"
#include "tests/TempDir.hpp"

using namespace dfrecon;
using dfrecon::testing::TempDir;
namespace fs = std::filesystem;

namespace {

// Two triangles sharing an edge: a square in z = 0.
TriangleSoup square() {
    return {{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, {{0, 1, 2}, {0, 2, 3}}};
}

MeshAttributes everything() {
    MeshAttributes a;
    a.vertexScalars = {{"distance", {0, 1, 2, 3}}};
    a.vertexLabels = {{"source", {0, 0, 1, 1}}};
    a.vertexVectors = {{"to_nearest", {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 1}}}};
    a.vertexColours = {{255, 0, 0}, {0, 255, 0}, {0, 0, 255}, {1, 2, 3}};
    a.faceLabels = {{"region", {7, 8}}};
    a.faceColours = {{10, 20, 30}, {40, 50, 60}};
    return a;
}

std::string slurp(const std::string& path) {
    std::ifstream in(path);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

bool contains(const std::string& text, const std::string& part) {
    return text.find(part) != std::string::npos;
}

}  // namespace

TEST(AttributedMesh, PlyCarriesVertexAndFaceProperties) {
    TempDir dir("attributed-ply");
    writeAttributedPly(toTriMesh(square()), everything(), dir / "m.ply", false);
    const std::string ply = slurp(dir / "m.ply");
    for (const char* line : {"element vertex 4", "property float distance", "property int source",
                             "property uchar red", "element face 2", "property int region"})
        EXPECT_TRUE(contains(ply, line)) << line;
    EXPECT_FALSE(contains(ply, "to_nearest"));  // vectors are VTK only
    // A face row: count, indices, colour, region.
    EXPECT_TRUE(contains(ply, " 40 50 60 8\n")) << ply;
}

TEST(AttributedMesh, VtkCarriesPointAndCellData) {
    TempDir dir("attributed-vtk");
    writeAttributedVtk(square(), everything(), dir / "m.vtk");
    const std::string vtk = slurp(dir / "m.vtk");
    for (const char* line :
         {"POINT_DATA 4\n", "SCALARS distance float 1\n", "SCALARS source int 1\n",
          "VECTORS to_nearest float\n", "CELL_DATA 2\n",
          "SCALARS region int 1\nLOOKUP_TABLE "
          "default\n7\n8\n"})
        EXPECT_TRUE(contains(vtk, line)) << line;
    // Without face data there is no CELL_DATA section.
    MeshAttributes vertexOnly = everything();
    vertexOnly.faceLabels.clear();
    vertexOnly.faceColours.clear();
    writeAttributedVtk(toTriMesh(square()), vertexOnly, dir / "v.vtk");
    EXPECT_FALSE(contains(slurp(dir / "v.vtk"), "CELL_DATA"));
}

TEST(AttributedMesh, ExtensionChoosesTheFormat) {
    TempDir dir("attributed-ext");
    EXPECT_TRUE(isAttributedMeshPath("a.PLY"));
    EXPECT_TRUE(isAttributedMeshPath("a.vtk"));
    EXPECT_FALSE(isAttributedMeshPath("a.obj"));
    writeAttributedMesh(toTriMesh(square()), everything(), dir / "m.vtk");
    EXPECT_TRUE(contains(slurp(dir / "m.vtk"), "DATASET POLYDATA"));
    EXPECT_THROW(writeAttributedMesh(toTriMesh(square()), everything(), dir / "m.obj"),
                 std::invalid_argument);
    EXPECT_FALSE(fs::exists(dir / "m.obj"));
}

TEST(AttributedMesh, WrongSizesAndDroppedFacesAreRefused) {
    TempDir dir("attributed-bad");
    MeshAttributes shortLabels = everything();
    shortLabels.faceLabels[0].values.pop_back();
    EXPECT_THROW(writeAttributedPly(square(), shortLabels, dir / "m.ply"), std::invalid_argument);
    EXPECT_THROW(writeAttributedVtk(square(), shortLabels, dir / "m.vtk"), std::invalid_argument);
    EXPECT_FALSE(fs::exists(dir / "m.ply"));
    EXPECT_FALSE(fs::exists(dir / "m.vtk"));

    // A third triangle on the shared edge is non-manifold: OpenMesh drops
    // it, so face values would no longer line up.
    TriangleSoup fin = square();
    fin.points.push_back({0.5, 0.5, 1});
    fin.triangles.push_back({0, 2, 4});
    MeshAttributes faces;
    faces.faceLabels = {{"region", {0, 1, 2}}};
    EXPECT_THROW(writeAttributedPly(fin, faces, dir / "f.ply"), std::invalid_argument);
    MeshAttributes vertices;
    vertices.vertexScalars = {{"distance", {0, 1, 2, 3, 4}}};
    writeAttributedPly(fin, vertices, dir / "f.ply");
    EXPECT_TRUE(fs::exists(dir / "f.ply"));
}
