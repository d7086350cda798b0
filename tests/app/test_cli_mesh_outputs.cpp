// Mesh outputs as viewers read them (docs/formats.md): reconstruct, batch
// and simplify write every format, name the ROI in each and carry its
// colour where the format can, and segment, geodesic and sdm write VTK XML
// with their arrays; VTK's own readers check the .vtk and .vtp files.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "io/mesh/MeshIO.hpp"
#include "shapes/MeshShapes.hpp"
#include "tests/CliRun.hpp"
#include "tests/TempDir.hpp"
#include "tests/VtkRead.hpp"

namespace fs = std::filesystem;
using dfrecon::testing::slurp;
using dfrecon::testing::TempDir;

namespace {

using Result = dfrecon::testing::CliResult;

Result run(const TempDir& dir, const std::string& args) {
    return dfrecon::testing::runCli(dir.str(), "-q " + args);
}

bool contains(const std::string& text, const std::string& part) {
    return text.find(part) != std::string::npos;
}

// "Left Kidney" has the colour 230 120 40; PTV has none.
const std::string kTwoRois = std::string(DFRECON_EXAMPLES) + "/two-rois.slices";

void expectKidneyField(const nlohmann::json& file) {
    EXPECT_EQ(file["fieldData"]["roi_name"]["values"][0], "Left Kidney");
    EXPECT_EQ(file["fieldData"]["roi_colour"]["values"], nlohmann::json::parse("[230,120,40]"));
    const nlohmann::json& colour = file["pointData"]["colour"]["values"];
    ASSERT_EQ(colour.size(), 3 * file["points"].size());
    for (std::size_t k = 0; k < colour.size(); k += 3)
        ASSERT_EQ(colour[k].get<int>() * 65536 + colour[k + 1].get<int>() * 256 +
                      colour[k + 2].get<int>(),
                  230 * 65536 + 120 * 256 + 40);
}

}  // namespace

TEST(CliMeshOutputs, ReconstructNamesAndColoursTheRoiInEveryFormat) {
    const TempDir dir("cli-mesh-outputs");
    for (const char* ext : {"ply", "obj", "stl", "off", "vtk", "vtp"}) {
        const Result r = run(dir, "reconstruct " + kTwoRois + " --roi 'Left Kidney' -o " +
                                      (dir / (std::string("k.") + ext)));
        ASSERT_EQ(r.exitCode, 0) << ext << ": " << r.err;
        // -q: nothing on stderr, not even OpenMesh's "[PLYWriter] : write file".
        EXPECT_EQ(r.err, "") << ext;
        EXPECT_FALSE(contains(r.out, "Writer")) << r.out;
    }
    const std::string ply = slurp(dir / "k.ply");
    EXPECT_TRUE(contains(ply, "comment roi_name Left Kidney\ncomment roi_colour 230 120 40\n"));
    EXPECT_TRUE(contains(ply, "property uchar red"));
    EXPECT_EQ(slurp(dir / "k.obj")
                  .rfind("mtllib k.mtl\no Left_Kidney\ng Left_Kidney\n"
                         "usemtl Left_Kidney\n",
                         0),
              0u);
    EXPECT_TRUE(
        contains(slurp(dir / "k.mtl"), "newmtl Left_Kidney\nKd 0.901961 0.470588 0.156863\n"));
    EXPECT_EQ(slurp(dir / "k.stl").substr(0, 23), "dfrecon ROI Left Kidney");

    // Every readable file holds the same surface, to the bit.
    const dfrecon::TriangleSoup fromPly = dfrecon::readTriangleSoup(dir / "k.ply");
    for (const char* ext : {"obj", "off"})
        EXPECT_EQ(dfrecon::readTriangleSoup(dir / (std::string("k.") + ext)).points, fromPly.points)
            << ext;
    DFRECON_READ_WITH_VTK(read, {dir / "k.vtk", dir / "k.vtp"});
    for (const nlohmann::json& file : read.files) {
        SCOPED_TRACE(file["file"].get<std::string>());
        ASSERT_EQ(file["points"].size(), fromPly.points.size());
        for (std::size_t v = 0; v < fromPly.points.size(); ++v)
            ASSERT_EQ((dfrecon::Vec3{file["points"][v][0].get<double>(),
                                     file["points"][v][1].get<double>(),
                                     file["points"][v][2].get<double>()}),
                      fromPly.points[v])
                << v;
        EXPECT_EQ(file["polys"].size(), fromPly.triangles.size());
        expectKidneyField(file);
    }
}

TEST(CliMeshOutputs, FolderFormatStreamsAndBatch) {
    const TempDir dir("cli-mesh-folder");
    // --all into a folder: --format picks the files' format.
    const Result all =
        run(dir, "reconstruct " + kTwoRois + " --all --format vtp -o " + (dir / "all"));
    ASSERT_EQ(all.exitCode, 0) << all.err;
    EXPECT_TRUE(fs::exists(dir / "all/Left_Kidney.vtp"));
    EXPECT_TRUE(fs::exists(dir / "all/PTV.vtp"));
    // Standard output streams VTK too.
    const Result piped = dfrecon::testing::runShell(
        dir.str(), std::string(DFRECON_BINARY) + " -q reconstruct " + kTwoRois +
                       " --roi PTV -o - --format vtk > " + (dir / "piped.vtk"));
    ASSERT_EQ(piped.exitCode, 0) << piped.err;
    // batch: per entry, as a manifest column.
    std::ofstream(dir / "manifest.csv") << "input,id,roi,format\n"
                                        << kTwoRois << ",kidney,Left Kidney,obj\n"
                                        << kTwoRois << ",ptv,PTV,vtp\n";
    const Result batch = run(dir, "batch " + (dir / "manifest.csv") + " -o " + (dir / "batch"));
    ASSERT_EQ(batch.exitCode, 0) << batch.err;
    EXPECT_TRUE(contains(slurp(dir / "batch/kidney/Left_Kidney.mtl"), "Kd 0.901961"));
    const nlohmann::json record = nlohmann::json::parse(slurp(dir / "batch/ptv/record.json"));
    EXPECT_EQ(record["rois"][0]["mesh"], "PTV.vtp") << record.dump();

    DFRECON_READ_WITH_VTK(read, {dir / "all/Left_Kidney.vtp", dir / "all/PTV.vtp",
                                 dir / "piped.vtk", dir / "batch/ptv/PTV.vtp"});
    expectKidneyField(read.files[0]);
    for (std::size_t k = 1; k < 4; ++k) {
        const nlohmann::json& file = read.files[k];
        // No colour in the contours: none in the file.
        EXPECT_EQ(file["fieldData"]["roi_name"]["values"][0], "PTV") << file["file"];
        EXPECT_FALSE(file["fieldData"].contains("roi_colour")) << file["file"];
        EXPECT_TRUE(file["pointData"].empty()) << file["file"];
    }
    EXPECT_EQ(read.files[1]["points"], read.files[2]["points"]);
    EXPECT_EQ(read.files[1]["points"], read.files[3]["points"]);
}

TEST(CliMeshOutputs, SegmentGeodesicAndSdmWriteVtkXmlWithTheirArrays) {
    const TempDir dir("cli-mesh-arrays");
    dfrecon::writeMesh(dfrecon::toTriMesh(dfrecon::geodesicSphere(4, 5.0)), dir / "a.ply");
    dfrecon::TriangleSoup moved = dfrecon::geodesicSphere(4, 5.0);
    for (dfrecon::Vec3& p : moved.points) p.x += 12;
    dfrecon::writeMesh(dfrecon::toTriMesh(moved), dir / "b.ply");
    const std::string mesh = dir / "a.ply";
    ASSERT_EQ(run(dir, "geodesic " + mesh + " --from 0 -o " + (dir / "d.vtp")).exitCode, 0);
    ASSERT_EQ(run(dir, "segment " + mesh + " -k 3 --iterations 1 -o " + (dir / "r.vtp")).exitCode,
              0);
    const Result sdm =
        run(dir, "sdm " + mesh + " " + (dir / "b.ply") +
                     " --no-images --size 64 --mesh-formats vtp,ply -o " + (dir / "sdm"));
    ASSERT_EQ(sdm.exitCode, 0) << sdm.err;
    EXPECT_TRUE(fs::exists(dir / "sdm/a.ply"));
    EXPECT_FALSE(fs::exists(dir / "sdm/a.vtk"));
    EXPECT_EQ(
        run(dir, "sdm " + mesh + " " + (dir / "b.ply") + " --mesh-formats obj -o " + (dir / "sdm2"))
            .exitCode,
        1);
    DFRECON_READ_WITH_VTK(read, {dir / "d.vtp", dir / "r.vtp", dir / "sdm/a.vtp"});
    const nlohmann::json& distances = read.files[0]["pointData"];
    EXPECT_EQ(distances["distance"]["type"], "float");
    EXPECT_EQ(distances["distance"]["values"][0], 0.0);
    EXPECT_EQ(distances["source"]["type"], "int");
    EXPECT_EQ(distances["colour"]["components"], 3);
    const nlohmann::json& regions = read.files[1]["cellData"];
    EXPECT_EQ(regions["region"]["values"].size(), read.files[1]["cells"].get<std::size_t>());
    EXPECT_EQ(regions["colour"]["components"], 3);
    const nlohmann::json& clearance = read.files[2]["pointData"];
    for (const char* name : {"distance", "nearest_object", "to_nearest", "colour"})
        EXPECT_TRUE(clearance.contains(name)) << name;
    // a's vertices lie on a sphere 2 mm from b's, whose facets lie inside it.
    double nearest = 1e9;
    for (const auto& d : clearance["distance"]["values"])
        nearest = std::min(nearest, d.get<double>());
    EXPECT_GE(nearest, 2.0 - 1e-6);
    EXPECT_LT(nearest, 2.3);
}
