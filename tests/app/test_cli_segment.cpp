// dfrecon segment and dfrecon geodesic as a user runs them.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "io/mesh/MeshIO.hpp"
#include "shapes/MeshShapes.hpp"
#include "tests/CliRun.hpp"
#include "tests/TempDir.hpp"

namespace fs = std::filesystem;
using dfrecon::testing::TempDir;

namespace {

using Result = dfrecon::testing::CliResult;
using dfrecon::testing::slurp;

Result run(const TempDir& dir, const std::string& args) {
    return dfrecon::testing::runCli(dir.str(), args);
}

/// An ASCII PLY: its header lines and, per element, its rows of numbers.
struct Ply {
    std::vector<std::string> header;
    std::vector<std::vector<double>> vertices, faces;
};

Ply readAsciiPly(const std::string& path) {
    std::ifstream in(path);
    Ply ply;
    std::string line;
    std::size_t vertexCount = 0, faceCount = 0;
    while (std::getline(in, line) && line != "end_header") {
        ply.header.push_back(line);
        std::istringstream s(line);
        std::string word, element;
        s >> word >> element;
        if (word == "element" && element == "vertex") s >> vertexCount;
        if (word == "element" && element == "face") s >> faceCount;
    }
    const auto rows = [&](std::size_t count, std::vector<std::vector<double>>& into) {
        for (std::size_t i = 0; i < count && std::getline(in, line); ++i) {
            std::istringstream s(line);
            std::vector<double> row;
            for (double x; s >> x;) row.push_back(x);
            into.push_back(row);
        }
    };
    rows(vertexCount, ply.vertices);
    rows(faceCount, ply.faces);
    return ply;
}

bool hasLine(const Ply& ply, const std::string& line) {
    return std::find(ply.header.begin(), ply.header.end(), line) != ply.header.end();
}

}  // namespace

TEST(CliSegment, WritesRegionIdsAndReportsEachRegion) {
    TempDir dir("cli-segment");
    dfrecon::writeMesh(dfrecon::toTriMesh(dfrecon::tessellatedCube(12, 10.0)), dir / "cube.ply");
    const Result r =
        run(dir, "segment " + (dir / "cube.ply") + " -k 6 --iterations 5 --json --ascii -o " +
                     (dir / "regions.ply"));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const auto report = nlohmann::json::parse(r.out);
    EXPECT_EQ(report["command"], "segment");
    EXPECT_EQ(report["speed"], "attractive");
    const int regions = report["regionCount"];
    EXPECT_GE(regions, 6);
    double area = 0;
    for (const auto& region : report["regions"]) {
        area += region["areaMm2"].get<double>();
        EXPECT_GT(region["compactness"].get<double>(), 0);
    }
    EXPECT_NEAR(area, 600.0, 1e-6);
    EXPECT_GE(report["lloydEnergy"].size(), 1u);
    EXPECT_LE(report["iterations"].get<int>(), 5);

    const Ply ply = readAsciiPly(dir / "regions.ply");
    EXPECT_TRUE(hasLine(ply, "property int region"));
    EXPECT_TRUE(hasLine(ply, "property uchar red"));
    ASSERT_EQ(ply.faces.size(), 6u * 12 * 12 * 2);
    std::vector<int> facesPerRegion(std::size_t(regions), 0);
    for (const auto& face : ply.faces) {
        const int region = int(face.back());  // count, 3 indices, r g b, region
        ASSERT_GE(region, 0);
        ASSERT_LT(region, regions);
        ++facesPerRegion[std::size_t(region)];
    }
    for (int count : facesPerRegion) EXPECT_GT(count, 0);
}

TEST(CliSegment, GeodesicWritesDistancesFromTheSources) {
    TempDir dir("cli-geodesic");
    dfrecon::writeMesh(dfrecon::toTriMesh(dfrecon::geodesicSphere(16, 5.0)), dir / "sphere.ply");
    const Result r = run(dir, "geodesic " + (dir / "sphere.ply") + " --from 0 --json --ascii -o " +
                                  (dir / "distance.ply"));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const auto report = nlohmann::json::parse(r.out);
    EXPECT_EQ(report["solver"], "fast-marching");
    EXPECT_NEAR(report["maxDistance"].get<double>(), M_PI * 5.0, 0.02 * M_PI * 5.0);
    EXPECT_EQ(report["unreachedVertices"], 0);
    const Ply ply = readAsciiPly(dir / "distance.ply");
    EXPECT_TRUE(hasLine(ply, "property float distance"));
    EXPECT_TRUE(hasLine(ply, "property int source"));
    ASSERT_EQ(ply.vertices.size(), 10u * 16 * 16 + 2);
    // x y z (nx ny nz)? r g b distance source: distance is next to last.
    const auto& first = ply.vertices[0];
    EXPECT_EQ(first[first.size() - 2], 0.0);
    // Two sources and the OpenCL solver give the same nearest-source labels.
    const Result fim = run(dir, "geodesic " + (dir / "sphere.ply") +
                                    " --from 0,100 --solver fim --json -o " + (dir / "fim.ply"));
    ASSERT_EQ(fim.exitCode, 0) << fim.err;
    EXPECT_EQ(nlohmann::json::parse(fim.out)["solver"], "fast-iterative-opencl");
}

TEST(CliSegment, VtkOutputCarriesTheSameArrays) {
    TempDir dir("cli-segment-vtk");
    dfrecon::writeMesh(dfrecon::toTriMesh(dfrecon::geodesicSphere(4)), dir / "s.ply");
    const std::string mesh = dir / "s.ply";
    ASSERT_EQ(run(dir, "geodesic " + mesh + " --from 0 -o " + (dir / "d.vtk")).exitCode, 0);
    const std::string distances = dfrecon::testing::slurp(dir / "d.vtk");
    EXPECT_NE(distances.find("SCALARS distance float 1"), std::string::npos);
    EXPECT_NE(distances.find("SCALARS source int 1"), std::string::npos);
    ASSERT_EQ(run(dir, "segment " + mesh + " -k 3 --iterations 1 -o " + (dir / "r.vtk")).exitCode,
              0);
    const std::string regions = dfrecon::testing::slurp(dir / "r.vtk");
    EXPECT_NE(regions.find("CELL_DATA"), std::string::npos);
    EXPECT_NE(regions.find("SCALARS region int 1"), std::string::npos);
}

TEST(CliSegment, BadInputExitsTwoNamingTheFile) {
    TempDir dir("cli-segment-bad");
    std::ofstream(dir / "broken.ply") << "ply\nthis is not a mesh\n";
    for (const std::string command : {"segment", "geodesic --from 0"}) {
        const Result missing = run(dir, command + " /nonexistent/mesh.off -o " + (dir / "o.ply"));
        EXPECT_EQ(missing.exitCode, 2) << command;
        EXPECT_NE(missing.err.find("/nonexistent/mesh.off"), std::string::npos) << missing.err;
        const Result broken =
            run(dir, command + " " + (dir / "broken.ply") + " -o " + (dir / "o.ply"));
        EXPECT_EQ(broken.exitCode, 2) << command << ": " << broken.err;
        EXPECT_NE(broken.err.find(dir / "broken.ply"), std::string::npos) << broken.err;
        EXPECT_FALSE(fs::exists(dir / "o.ply"));
    }
}

TEST(CliSegment, UsageErrorsExitOneAndWriteNothing) {
    TempDir dir("cli-segment-usage");
    dfrecon::writeMesh(dfrecon::toTriMesh(dfrecon::geodesicSphere(4)), dir / "s.ply");
    const std::string mesh = dir / "s.ply";
    EXPECT_EQ(run(dir, "segment " + mesh + " -o " + (dir / "o.obj")).exitCode, 1);
    EXPECT_EQ(run(dir, "segment " + mesh + " -k 0 -o " + (dir / "o.ply")).exitCode, 1);
    EXPECT_EQ(run(dir, "segment " + mesh + " -k 100000 -o " + (dir / "o.ply")).exitCode, 1);
    EXPECT_EQ(run(dir, "segment " + mesh + " --speed fast -o " + (dir / "o.ply")).exitCode, 1);
    const Result far = run(dir, "geodesic " + mesh + " --from 5,99999 -o " + (dir / "o.ply"));
    EXPECT_EQ(far.exitCode, 1);
    EXPECT_NE(far.err.find("99999"), std::string::npos) << far.err;
    EXPECT_EQ(run(dir, "geodesic " + mesh + " -o " + (dir / "o.ply")).exitCode, 1);  // no --from
    EXPECT_EQ(run(dir, "geodesic " + mesh + " --from 1,x -o " + (dir / "o.ply")).exitCode, 1);
    EXPECT_EQ(run(dir, "geodesic --from 1 " + mesh + " -o " + (dir / "o.ply")).exitCode, 0);
    fs::remove(dir / "o.ply");
    EXPECT_FALSE(fs::exists(dir / "o.ply"));
    EXPECT_FALSE(fs::exists(dir / "o.obj"));
}

TEST(CliSegment, HelpGivesDefaultsAndUnits) {
    TempDir dir("cli-segment-help");
    const Result segment = run(dir, "segment --help");
    EXPECT_EQ(segment.exitCode, 0);
    for (const std::string expected : {"--speed", "attractive", "--iterations", "mm", "10"})
        EXPECT_NE(segment.out.find(expected), std::string::npos) << expected;
    const Result geodesic = run(dir, "geodesic --help");
    EXPECT_EQ(geodesic.exitCode, 0);
    for (const std::string expected : {"--from", "--solver", "auto", "mm"})
        EXPECT_NE(geodesic.out.find(expected), std::string::npos) << expected;
}
