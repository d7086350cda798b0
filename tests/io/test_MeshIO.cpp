// Mesh files: every format round-trips a closed mesh with the very same
// points and the ROI's name and colour where the format has a place for
// them, and a failed write leaves nothing behind.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "contours/InputError.hpp"
#include "io/mesh/MeshIO.hpp"
#include "tests/VtkRead.hpp"

using namespace dfrecon;
namespace fs = std::filesystem;

namespace {

TriMesh octahedron() {
    TriMesh mesh;
    const double r = 12.5;
    std::vector<TriMesh::VertexHandle> v = {
        mesh.add_vertex({r, 0, 0}),  mesh.add_vertex({-r, 0, 0}), mesh.add_vertex({0, r, 0}),
        mesh.add_vertex({0, -r, 0}), mesh.add_vertex({0, 0, r}),  mesh.add_vertex({0, 0, -r})};
    const int faces[8][3] = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4},
                             {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
    for (const auto& f : faces) mesh.add_face(v[f[0]], v[f[1]], v[f[2]]);
    return mesh;
}

fs::path scratchDir(const std::string& name) {
    const fs::path dir = fs::temp_directory_path() / ("dfrecon-test-" + name);
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

// Every format OpenMesh reads, binary and ASCII where it has both.
using FormatParam = std::pair<std::string, bool>;  // extension, binary
const auto kReadableFormats = ::testing::Values(
    FormatParam{".ply", true}, FormatParam{".ply", false}, FormatParam{".obj", false},
    FormatParam{".off", false}, FormatParam{".stl", true}, FormatParam{".stl", false});

std::string formatTestName(const ::testing::TestParamInfo<FormatParam>& info) {
    return info.param.first.substr(1) + (info.param.second ? "_binary" : "_ascii");
}

// A fresh folder for a format's test, and the file NAME.EXT in it.
std::pair<fs::path, std::string> formatFile(const std::string& prefix, const std::string& name,
                                            const FormatParam& format) {
    const fs::path dir = scratchDir(prefix + format.first.substr(1) + (format.second ? "b" : "a"));
    return {dir, (dir / (name + format.first)).string()};
}

}  // namespace

class MeshRoundTrip : public ::testing::TestWithParam<FormatParam> {};

TEST_P(MeshRoundTrip, KeepsTopologyAndPositions) {
    const auto [extension, binary] = GetParam();
    const auto [dir, path] = formatFile("mesh-", "octa", GetParam());
    const TriMesh original = octahedron();
    MeshWriteOptions options;
    options.binary = binary;
    writeMesh(original, path, options);

    const TriMesh back = readMesh(path);
    EXPECT_EQ(back.n_faces(), 8u);
    EXPECT_EQ(back.n_vertices(), 6u);  // STL's triangle soup is merged on read
    double volume = 0;
    for (auto f : back.faces()) {
        auto it = back.cfv_iter(f);
        const auto a = back.point(*it++), b = back.point(*it++), c = back.point(*it);
        volume += (a | (b % c)) / 6.0;  // signed: outward orientation must survive
    }
    EXPECT_NEAR(volume, 4.0 / 3.0 * 12.5 * 12.5 * 12.5, 1e-3);
    EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);
}

INSTANTIATE_TEST_SUITE_P(AllFormats, MeshRoundTrip, kReadableFormats, formatTestName);

TEST(MeshIO, FailedWriteLeavesNoFile) {
    const fs::path dir = scratchDir("mesh-fail");
    EXPECT_THROW(writeMesh(octahedron(), (dir / "missing-dir" / "x.ply").string()),
                 std::runtime_error);
    EXPECT_THROW(writeMesh(octahedron(), (dir / "x.xyz").string()), std::invalid_argument);
    EXPECT_TRUE(fs::is_empty(dir));
}

TEST(MeshIO, UnreadableInputsAreInputErrors) {
    const fs::path dir = scratchDir("mesh-bad");
    EXPECT_THROW(readMesh((dir / "none.ply").string()), InputError);
    EXPECT_THROW(readMesh((dir / "x.txt").string()), InputError);
    std::ofstream((dir / "garbage.ply").string()) << "ply\nformat nonsense\n";
    EXPECT_THROW(readMesh((dir / "garbage.ply").string()), InputError);
}

TEST(MeshIO, TruncatedOffIsAnInputErrorNotGarbage) {
    // OpenMesh's OFF reader would hand over uninitialised indices here.
    const fs::path dir = scratchDir("mesh-truncated");
    const std::string path = (dir / "cut.off").string();
    std::ofstream(path) << "OFF\n3 1 0\n0 0 0\n";
    try {
        readTriangleSoup(path);
        FAIL() << "a truncated OFF file was read";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("the header declares 3 vertices and 1 face"),
                  std::string::npos)
            << e.what();
    }
    // The complete file reads.
    std::ofstream(path) << "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
    EXPECT_EQ(readTriangleSoup(path).triangles.size(), 1u);
}

namespace {

// The octahedron moved to patient-like coordinates no short decimal gives
// back; floats, as reconstruct writes them (OpenMesh's writers write
// floats).
TriMesh patientOctahedron() {
    TriangleSoup soup = toTriangleSoup(octahedron());
    for (Vec3& p : soup.points) p = p + Vec3{-187.3 + 1.0 / 3.0, 91.7 / 7.0, -1234.56789};
    roundPointsToFloat(soup);
    return toTriMesh(soup);
}

MeshWriteOptions tagged(bool binary) {
    MeshWriteOptions options;
    options.binary = binary;
    options.structure = {"Left lung", std::array<std::uint8_t, 3>{200, 100, 7}};
    return options;
}

std::string slurp(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

bool contains(const std::string& text, const std::string& part) {
    return text.find(part) != std::string::npos;
}

void expectSamePoints(const TriMesh& written, const TriangleSoup& read) {
    ASSERT_EQ(read.points.size(), written.n_vertices());
    for (auto v : written.vertices()) {
        const auto& p = written.point(v);
        EXPECT_EQ(read.points[std::size_t(v.idx())], (Vec3{p[0], p[1], p[2]})) << v.idx();
    }
}

}  // namespace

class TaggedMesh : public ::testing::TestWithParam<FormatParam> {};

// Every readable format reads back with the very same points (STL: merged
// by position, in its own order) and the structure where the format keeps it.
TEST_P(TaggedMesh, CarriesTheStructureAndExactPoints) {
    const auto [extension, binary] = GetParam();
    const auto [dir, path] = formatFile("tagged-", "lung", GetParam());
    const TriMesh mesh = patientOctahedron();
    writeMesh(mesh, path, tagged(binary));
    const std::string text = slurp(path);
    const TriangleSoup back = readTriangleSoup(path);
    if (extension == ".ply") {
        EXPECT_TRUE(contains(text, "comment roi_name Left lung\ncomment roi_colour 200 100 7\n"));
        EXPECT_TRUE(contains(text, "property uchar red"));
        expectSamePoints(mesh, back);
    } else if (extension == ".obj") {
        EXPECT_EQ(text.rfind("mtllib lung.mtl\no Left_lung\ng Left_lung\nusemtl Left_lung\n", 0),
                  0u);
        EXPECT_EQ(slurp((dir / "lung.mtl").string()),
                  "# dfrecon: the display colour of ROI Left_lung\nnewmtl Left_lung\n"
                  "Kd 0.784314 0.392157 0.027451\n");
        expectSamePoints(mesh, back);
    } else if (extension == ".stl") {
        if (binary) {
            EXPECT_EQ(text.substr(0, 22), "dfrecon ROI Left lung ");
        } else {
            EXPECT_EQ(text.rfind("solid Left lung\n", 0), 0u);
            EXPECT_TRUE(contains(text, "endsolid Left lung"));
        }
        EXPECT_EQ(back.triangles.size(), 8u);
    } else {  // .off: no place for it
        expectSamePoints(mesh, back);
    }
    EXPECT_EQ(readMesh(path).n_faces(), 8u);
    EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()),
              extension == ".obj" ? 2 : 1);
}

INSTANTIATE_TEST_SUITE_P(ReadableFormats, TaggedMesh, kReadableFormats, formatTestName);

TEST(MeshIO, VtkAndVtpCarryTheStructureAndExactPoints) {
    const fs::path dir = scratchDir("tagged-vtk");
    const TriMesh mesh = patientOctahedron();
    // Doubles that are no floats: these formats keep doubles.
    TriMesh fine = mesh;
    for (auto v : fine.vertices()) fine.point(v) += TriMesh::Point(1e-9, -1.0 / 3.0, 0.1);
    const std::string vtk = (dir / "lung.vtk").string(), vtp = (dir / "lung.vtp").string();
    writeMesh(fine, vtk, tagged(true));
    writeMesh(fine, vtp, tagged(true));
    DFRECON_READ_WITH_VTK(read, {vtk, vtp});
    for (const nlohmann::json& file : read.files) {
        ASSERT_EQ(file["points"].size(), 6u);
        for (auto v : fine.vertices())
            for (int c = 0; c < 3; ++c)
                EXPECT_EQ(file["points"][v.idx()][c].get<double>(), fine.point(v)[c]);
        EXPECT_EQ(file["polys"].size(), 8u);
        EXPECT_EQ(file["fieldData"]["roi_name"]["values"][0], "Left lung");
        EXPECT_EQ(file["fieldData"]["roi_colour"]["values"], nlohmann::json::parse("[200,100,7]"));
        const nlohmann::json& colour = file["pointData"]["colour"];
        EXPECT_EQ(colour["components"], 3);
        for (std::size_t k = 0; k < 18; k += 3) EXPECT_EQ(colour["values"][k], 200);
    }
}

TEST(MeshIO, UntaggedAndUncolouredMeshesWriteNoColour) {
    const fs::path dir = scratchDir("untagged");
    writeMesh(octahedron(), (dir / "plain.ply").string());
    MeshWriteOptions named;
    named.structure.name = "GTV";
    writeMesh(octahedron(), (dir / "named.ply").string(), named);
    writeMesh(octahedron(), (dir / "named.obj").string(), named);
    const std::string plain = slurp((dir / "plain.ply").string());
    EXPECT_FALSE(contains(plain, "comment"));
    EXPECT_FALSE(contains(plain, "red"));
    const std::string ply = slurp((dir / "named.ply").string());
    EXPECT_TRUE(contains(ply, "comment roi_name GTV\n"));
    EXPECT_FALSE(contains(ply, "roi_colour"));
    EXPECT_FALSE(contains(ply, "red"));
    // No colour, no material library.
    EXPECT_EQ(slurp((dir / "named.obj").string()).rfind("o GTV\ng GTV\n#", 0), 0u);
    EXPECT_FALSE(fs::exists(dir / "named.mtl"));
}

TEST(MeshIO, StreamsCarryTheStructureButNoMaterialLibrary) {
    std::ostringstream obj, vtp;
    writeMesh(octahedron(), obj, MeshFormat::Obj, tagged(false));
    EXPECT_EQ(obj.str().rfind("o Left_lung\ng Left_lung\n", 0), 0u);
    EXPECT_FALSE(contains(obj.str(), "mtllib"));
    EXPECT_FALSE(contains(obj.str(), "usemtl"));
    writeMesh(octahedron(), vtp, MeshFormat::Vtp, tagged(true));
    EXPECT_TRUE(contains(vtp.str(), "Name=\"roi_name\""));
}
