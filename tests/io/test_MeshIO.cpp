// Mesh files through OpenMesh: every format round-trips a closed mesh, and a
// failed write leaves nothing behind.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "io/InputError.hpp"
#include "io/MeshIO.hpp"

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

}  // namespace

class MeshRoundTrip : public ::testing::TestWithParam<std::pair<std::string, bool>> {};

TEST_P(MeshRoundTrip, KeepsTopologyAndPositions) {
    const auto [extension, binary] = GetParam();
    const fs::path dir = scratchDir("mesh-" + extension.substr(1) + (binary ? "b" : "a"));
    const std::string path = (dir / ("octa" + extension)).string();
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

INSTANTIATE_TEST_SUITE_P(AllFormats, MeshRoundTrip,
                         ::testing::Values(std::pair{".ply", true}, std::pair{".ply", false},
                                           std::pair{".obj", false}, std::pair{".off", false},
                                           std::pair{".stl", true}, std::pair{".stl", false}),
                         [](const auto& testInfo) {
                             return testInfo.param.first.substr(1) +
                                    (testInfo.param.second ? "_binary" : "_ascii");
                         });

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
