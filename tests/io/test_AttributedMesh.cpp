// Meshes with per-vertex and per-face data: every array reaches the PLY
// header or the VTK and VTP files under its name (read back by VTK's own
// readers), and a wrong size or format is refused before anything is
// written.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "io/mesh/AttributedMesh.hpp"
#include "io/mesh/MeshIO.hpp"
#include "tests/TempDir.hpp"
#include "tests/VtkRead.hpp"

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

TEST(AttributedMesh, PlyNamesItsStructureInTheHeader) {
    TempDir dir("attributed-structure");
    MeshAttributes a = everything();
    a.structure = {"Left\nlung", std::array<std::uint8_t, 3>{200, 100, 7}};
    writeAttributedPly(toTriMesh(square()), a, dir / "m.ply", true);
    const std::string ply = slurp(dir / "m.ply");
    // Right after the format line; a line break in the name is a space.
    EXPECT_EQ(ply.find("comment roi_name Left lung\ncomment roi_colour 200 100 7\n"),
              ply.find("format binary_little_endian 1.0\n") + 32)
        << ply.substr(0, 200);
    const TriangleSoup back = readTriangleSoup(dir / "m.ply");  // through io/mesh/PlyFileCheck
    EXPECT_EQ(back.points, square().points);
}

TEST(AttributedMesh, VtkAndVtpCarryPointAndCellData) {
    TempDir dir("attributed-vtk");
    writeAttributedMesh(square(), everything(), dir / "m.vtk");
    writeAttributedMesh(toTriMesh(square()), everything(), dir / "m.VTP");
    MeshAttributes vertexOnly = everything();
    vertexOnly.faceLabels.clear();
    vertexOnly.faceColours.clear();
    writeAttributedMesh(toTriMesh(square()), vertexOnly, dir / "v.vtk");
    DFRECON_READ_WITH_VTK(read, {dir / "m.vtk", dir / "m.VTP", dir / "v.vtk"});
    for (int k = 0; k < 2; ++k) {
        const nlohmann::json& file = read.files[std::size_t(k)];
        EXPECT_EQ(file["points"].size(), 4u);
        for (const char* name : {"distance", "source", "to_nearest", "colour"})
            EXPECT_TRUE(file["pointData"].contains(name)) << name;
        EXPECT_EQ(file["cellData"]["region"]["values"], nlohmann::json::parse("[7, 8]"));
    }
    EXPECT_TRUE(read.files[2]["cellData"].empty());
}

TEST(AttributedMesh, ExtensionChoosesTheFormat) {
    TempDir dir("attributed-ext");
    EXPECT_TRUE(isAttributedMeshPath("a.PLY"));
    EXPECT_TRUE(isAttributedMeshPath("a.vtk"));
    EXPECT_TRUE(isAttributedMeshPath("a.vtp"));
    EXPECT_FALSE(isAttributedMeshPath("a.obj"));
    writeAttributedMesh(toTriMesh(square()), everything(), dir / "m.vtk");
    EXPECT_TRUE(contains(slurp(dir / "m.vtk"), "DATASET POLYDATA"));
    writeAttributedMesh(toTriMesh(square()), everything(), dir / "m.vtp");
    EXPECT_TRUE(contains(slurp(dir / "m.vtp"), "<VTKFile type=\"PolyData\""));
    EXPECT_THROW(writeAttributedMesh(toTriMesh(square()), everything(), dir / "m.obj"),
                 std::invalid_argument);
    EXPECT_FALSE(fs::exists(dir / "m.obj"));
}

TEST(AttributedMesh, WrongSizesAndDroppedFacesAreRefused) {
    TempDir dir("attributed-bad");
    MeshAttributes shortLabels = everything();
    shortLabels.faceLabels[0].values.pop_back();
    EXPECT_THROW(writeAttributedPly(square(), shortLabels, dir / "m.ply"), std::invalid_argument);
    EXPECT_THROW(writeAttributedMesh(square(), shortLabels, dir / "m.vtk"), std::invalid_argument);
    EXPECT_THROW(writeAttributedMesh(square(), shortLabels, dir / "m.vtp"), std::invalid_argument);
    EXPECT_FALSE(fs::exists(dir / "m.ply"));
    EXPECT_FALSE(fs::exists(dir / "m.vtk"));
    EXPECT_FALSE(fs::exists(dir / "m.vtp"));

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
