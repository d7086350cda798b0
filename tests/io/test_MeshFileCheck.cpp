// Mesh files are checked before OpenMesh reads them: every hostile file is
// an InputError naming the file, within a second and without allocating
// what its header claims; every file OpenMesh reads as written still reads.
#include <gtest/gtest.h>

#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "contours/InputError.hpp"
#include "io/mesh/MeshFileCheck.hpp"
#include "io/mesh/MeshIO.hpp"
#include "tests/TempDir.hpp"

using namespace dfrecon;
namespace fs = std::filesystem;

namespace {

fs::path scratch() {
    return dfrecon::testing::processScratch("meshcheck");
}

std::string write(const std::string& name, const std::string& bytes) {
    const fs::path path = scratch() / name;
    std::ofstream(path, std::ios::binary) << bytes;
    return path.string();
}

const std::string kTetraVertices = "0 0 0\n1 0 0\n0 1 0\n0 0 1\n";
const std::string kTetraFaces = "3 0 2 1\n3 0 1 3\n3 1 2 3\n3 0 3 2\n";

std::string asciiPly(const std::string& vertices, const std::string& faces,
                     const std::string& counts = "4 4") {
    const std::size_t space = counts.find(' ');
    return "ply\nformat ascii 1.0\nelement vertex " + counts.substr(0, space) +
           "\nproperty float x\nproperty float y\nproperty float z\nelement face " +
           counts.substr(space + 1) + "\nproperty list uchar int vertex_indices\nend_header\n" +
           vertices + faces;
}

// Both readers refuse `path` with an InputError that starts with the path
// and says `fragment`, well within a second.
void expectRefused(const std::string& path, const std::string& fragment) {
    for (int reader = 0; reader < 2; ++reader) {
        const auto start = std::chrono::steady_clock::now();
        try {
            if (reader == 0)
                readTriangleSoup(path);
            else
                readMesh(path);
            ADD_FAILURE() << path << " was read";
        } catch (const InputError& e) {
            const std::string what = e.what();
            EXPECT_EQ(what.rfind(path, 0), 0u) << what;
            EXPECT_NE(what.find(fragment), std::string::npos) << what;
        }
        EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(),
                  1.0)
            << path;
    }
}

void expectTetrahedron(const std::string& path) {
    const TriangleSoup soup = readTriangleSoup(path);
    EXPECT_EQ(soup.triangles.size(), 4u) << path;
    EXPECT_EQ(readMesh(path).n_faces(), 4u) << path;
}

}  // namespace

TEST(MeshFileCheck, PlyHeadersOpenMeshCannotEndAreRefused) {
    // OpenMesh loops forever on these (and printed 300 MB of complaints).
    expectRefused(write("noend.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"),
                  "without end_header");
    expectRefused(write("bigcount.ply", "ply\nformat ascii 1.0\nelement vertex 5000000000\n"),
                  "count '5000000000' is not a whole number");
    expectRefused(write("keyword.ply", "ply\nformat ascii 1.0\nelemnt vertex 3\nend_header\n"),
                  "unknown header keyword 'elemnt'");
    expectRefused(write("noformat.ply", "ply\ncomment first\nformat ascii 1.0\nend_header\n"),
                  "must be 'format");
    expectRefused(write("orphan.ply", "ply\nformat ascii 1.0\nproperty float x\nend_header\n"),
                  "a property before any element");
}

TEST(MeshFileCheck, DeclaredCountsMustFitTheFile) {
    // An ASCII vertex takes at least 6 bytes, a face 8.
    expectRefused(write("huge.ply", asciiPly(kTetraVertices, kTetraFaces, "1000000000 4")),
                  "the header declares 1000000000 vertices and 4 faces, which take at least");
    expectRefused(write("cut.ply", asciiPly(kTetraVertices, "3 0 2 1\n")), "which take at least");
    expectRefused(write("short.ply",
                        asciiPly(kTetraVertices, kTetraFaces.substr(0, 16) + std::string(40, ' '))),
                  "the file ends in face 2 of 4");
    // Binary records have exact sizes.
    std::string binary =
        "ply\nformat binary_little_endian 1.0\nelement vertex 100000\nproperty float x\n"
        "property float y\nproperty float z\nend_header\n";
    binary += std::string(12 * 4, '\0');
    expectRefused(write("huge-binary.ply", binary), "take at least 1200000 bytes; the file has 48");
}

TEST(MeshFileCheck, FacesMustHaveFewCornersThatAreVertices) {
    // A list count of 2^31 - 1 made OpenMesh push that many corners.
    expectRefused(
        write("list.ply", asciiPly(kTetraVertices, "2147483647 0 1 2\n" + kTetraFaces.substr(8))),
        "corner count '2147483647' is not from 3 to 4096");
    expectRefused(write("two.ply", asciiPly(kTetraVertices, "2 0 1   \n" + kTetraFaces.substr(8))),
                  "corner count '2'");
    expectRefused(write("index.ply", asciiPly(kTetraVertices, "3 0 1 9\n" + kTetraFaces.substr(8))),
                  "corner '9' is not a vertex (0 to 3)");
    std::string binary =
        "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n"
        "property float y\nproperty float z\nelement face 1\n"
        "property list int int vertex_indices\nend_header\n";
    binary += std::string(36, '\0');
    const std::int32_t face[4] = {2147483647, 0, 1, 2};
    binary.append(reinterpret_cast<const char*>(face), sizeof face);
    expectRefused(write("list-binary.ply", binary), "corner count 2147483647");
    // An OFF face line declaring a million corners made OpenMesh hang.
    expectRefused(write("face.off", "OFF\n4 1 0\n" + kTetraVertices + "1000000 0 1 2\n"),
                  ":7: face 0 of 1: corner count '1000000' is not from 3 to 4096");
}

TEST(MeshFileCheck, CoordinatesMustBeFiniteNumbersWithinAKilometre) {
    for (const std::string value : {"nan", "inf", "1e308", "-2e6", "1e"}) {
        const std::string vertices = value + " 0 0\n" + kTetraVertices.substr(6);
        expectRefused(write("v.ply", asciiPly(vertices, kTetraFaces)), "vertex 0 of 4: x is");
        expectRefused(write("v.off", "OFF\n4 4 0\n" + vertices + kTetraFaces), "vertex 0: ");
        expectRefused(write("v.obj", "v " + value + " 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"),
                      "v.obj:1: vertex 0: ");
        expectRefused(write("v.stl", "solid s\nfacet normal 0 0 1\nouter loop\nvertex " + value +
                                         " 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\n"
                                         "endsolid s\n"),
                      "v.stl:4: vertex ");
    }
    // Binary files hold floats: checked after reading, or before for STL.
    std::string binary =
        "ply\nformat binary_little_endian 1.0\nelement vertex 4\nproperty double x\n"
        "property double y\nproperty double z\nelement face 4\n"
        "property list uchar int vertex_indices\nend_header\n";
    const double points[12] = {1e300, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
    binary.append(reinterpret_cast<const char*>(points), sizeof points);
    const std::int32_t faces[4][3] = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}};
    for (const auto& f : faces) {
        binary += char(3);
        binary.append(reinterpret_cast<const char*>(f), sizeof f);
    }
    expectRefused(write("far-binary.ply", binary), "vertex 0 has coordinate inf, not finite");
    std::string stl(80, ' ');
    const std::uint32_t one = 1;
    stl.append(reinterpret_cast<const char*>(&one), 4);
    const float triangle[12] = {0, 0, 1, NAN, 0, 0, 1, 0, 0, 0, 1, 0};
    stl.append(reinterpret_cast<const char*>(triangle), sizeof triangle);
    stl += std::string(2, '\0');
    expectRefused(write("nan-binary.stl", stl), "triangle 0 has a coordinate that is not finite");
}

TEST(MeshFileCheck, OtherFormsOpenMeshMisreadsAreRefused) {
    expectRefused(write("counts.off", "OFF 4 4 0\n" + kTetraVertices + kTetraFaces),
                  "the first line must hold only the OFF keyword");
    expectRefused(
        write("comment.off", "OFF\n# made by hand\n4 4 0\n" + kTetraVertices + kTetraFaces),
        "comments are not supported");
    expectRefused(write("missing.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n"),
                  "missing.obj:4: a face refers to vertex 7 of 3");
    fs::create_directories(scratch() / "library.mtl");
    expectRefused(write("mtl.obj", "mtllib library.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"),
                  "material library 'library.mtl' is not a regular file");
    expectRefused(write("short.stl", std::string(100, 'x')),
                  "neither an ASCII STL (no 'solid' at the start) nor a binary one");
    // A comment last in a binary header: OpenMesh reads from the wrong byte.
    expectRefused(write("comment-last.ply",
                        "ply\nformat binary_little_endian 1.0\nelement vertex 0\nproperty float x\n"
                        "property float y\nproperty float z\ncomment last\nend_header\n"),
                  "binary data must follow 'end_header'");
    expectRefused(write("list-elsewhere.ply",
                        "ply\nformat ascii 1.0\nelement vertex 0\nproperty list uchar float x\n"
                        "end_header\n"),
                  "list property 'x' of element 'vertex' is not supported");
}

TEST(MeshFileCheck, WhatOpenMeshReadsAsWrittenStillReads) {
    // CRLF line ends, comments, obj_info, colours, elements before and after.
    std::string crlf = asciiPly(kTetraVertices, kTetraFaces);
    for (std::size_t at = crlf.find('\n'); at != std::string::npos; at = crlf.find('\n', at + 2))
        crlf.insert(at, "\r");
    expectTetrahedron(write("crlf.ply", crlf));
    expectTetrahedron(
        write("extra.ply",
              "ply\nformat ascii 1.0\ncomment by hand\nobj_info plain words\nelement material 1\n"
              "property uchar ambient_red\nelement vertex 4\nproperty float x\nproperty float y\n"
              "property float z\nproperty uchar red\nelement face 4\n"
              "property list uchar int vertex_indices\nproperty float quality\nelement edge 1\n"
              "property int vertex1\nend_header\n7\n0 0 0 1\n1 0 0 2\n0 1 0 3\n0 0 1 4\n"
              "3 0 2 1 0.5\n3 0 1 3 0.5\n3 1 2 3 0.5\n3 0 3 2 0.5\n"));
    // Binary, both byte orders and line ends, double coordinates and a face property.
    for (const bool big : {false, true})
        for (const std::string nl : {"\n", "\r\n"}) {
            std::string ply = "ply" + nl + "format binary_" + (big ? "big" : "little") +
                              "_endian 1.0" + nl + "element vertex 4" + nl + "property double x" +
                              nl + "property double y" + nl + "property double z" + nl +
                              "element face 4" + nl + "property list uchar uint vertex_indices" +
                              nl + "property int region" + nl + "end_header" + nl;
            auto put = [&](const void* value, std::size_t n) {
                const char* bytes = static_cast<const char*>(value);
                for (std::size_t k = 0; k < n; ++k) ply += bytes[big ? n - 1 - k : k];
            };
            const double points[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
            for (const auto& p : points)
                for (double c : p) put(&c, 8);
            const std::uint32_t faces[4][3] = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}};
            for (const auto& f : faces) {
                ply += char(3);
                for (std::uint32_t c : f) put(&c, 4);
                const std::int32_t region = 5;
                put(&region, 4);
            }
            expectTetrahedron(write("binary.ply", ply));
        }
    expectTetrahedron(write("plain.off", "OFF\n4 4 0\n" + kTetraVertices + kTetraFaces));
    expectTetrahedron(write("colour.off",
                            "COFF\n4 4 0\n0 0 0 9 9 9 255\n1 0 0 9 9 9 255\n"
                            "0 1 0 9 9 9 255\n0 0 1 9 9 9 255\n3 0 2 1 1 2 3\n"
                            "3 0 1 3\n3 1 2 3 4 5 6\n3 0 3 2\n"));
    expectTetrahedron(write("negative.obj",
                            "# by hand\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n"
                            "f 1 3 2\nf 1//1 2//1 4//1\nf -3 -2 -1\nf 1 4 3\n"));
}
