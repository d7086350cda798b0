// Legacy VTK and VTK XML PolyData as VTK's own readers see them: the same
// points to the last bit, the same triangles, every array under its name
// with its type, components and values (non-finite ones included), and the
// structure as field data.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>

#include "io/mesh/VtkPolyData.hpp"
#include "tests/TempDir.hpp"
#include "tests/VtkRead.hpp"

using namespace dfrecon;
using dfrecon::testing::TempDir;

namespace {

// Coordinates no short decimal gives back, and a far one.
TriangleSoup square() {
    return {{{0.1, 0, 0}, {1, 0, 1e-17}, {1, 1, 1.0 / 3.0}, {0, 1, 123456.789012345678}},
            {{0, 1, 2}, {0, 2, 3}}};
}

MeshAttributes everything() {
    MeshAttributes a;
    a.vertexScalars = {{"distance",
                        {0.25f, 1.0f / 3.0f, std::numeric_limits<float>::quiet_NaN(),
                         -std::numeric_limits<float>::infinity()}}};
    a.vertexLabels = {{"source", {0, 0, 1, -1}}};
    a.vertexVectors = {{"to_nearest", {{1, 0, 0}, {0, 0.1, 0}, {0, 0, 1}, {1, 1, 1.0 / 7.0}}}};
    a.vertexColours = {{255, 0, 0}, {0, 255, 0}, {0, 0, 255}, {1, 2, 3}};
    a.faceLabels = {{"region", {7, -8}}};
    a.faceColours = {{10, 20, 30}, {40, 50, 60}};
    a.structure = {"Left lung & <x> 100%", std::array<std::uint8_t, 3>{200, 100, 7}};
    return a;
}

void write(const std::string& path, const TriangleSoup& soup, const MeshAttributes& attributes) {
    std::ofstream out(path, std::ios::binary);
    if (path.substr(path.size() - 4) == ".vtp")
        writeVtkXml(out, soup, attributes);
    else
        writeVtkLegacy(out, soup, attributes);
}

// Values as the reader script gives them: numbers, or "nan"/"inf"/"-inf".
double valueOf(const nlohmann::json& v) {
    if (v.is_string()) {
        const std::string s = v.get<std::string>();
        return s == "nan" ? std::nan("") : s == "inf" ? INFINITY : -INFINITY;
    }
    return v.get<double>();
}

template <class T>
void expectValues(const nlohmann::json& array, const std::vector<T>& values) {
    ASSERT_EQ(array["values"].size(), values.size());
    for (std::size_t k = 0; k < values.size(); ++k) {
        const double read = valueOf(array["values"][k]);
        if (std::isnan(double(values[k])))
            EXPECT_TRUE(std::isnan(read)) << k;
        else
            EXPECT_EQ(read, double(values[k])) << k;
    }
}

std::vector<double> flat(const std::vector<Vec3>& v) {
    std::vector<double> out;
    for (const Vec3& p : v) out.insert(out.end(), {p.x, p.y, p.z});
    return out;
}

std::vector<int> flat(const std::vector<Rgb>& v) {
    std::vector<int> out;
    for (const Rgb& c : v) out.insert(out.end(), c.begin(), c.end());
    return out;
}

}  // namespace

TEST(VtkPolyData, VtkReadsBackEveryArrayExactly) {
    TempDir dir("vtk-everything");
    const TriangleSoup soup = square();
    const MeshAttributes a = everything();
    write(dir / "m.vtk", soup, a);
    write(dir / "m.vtp", soup, a);
    DFRECON_READ_WITH_VTK(read, {dir / "m.vtk", dir / "m.vtp"});
    for (const nlohmann::json& file : read.files) {
        SCOPED_TRACE(file["file"].get<std::string>());
        EXPECT_EQ(file["pointType"], "double");
        ASSERT_EQ(file["points"].size(), soup.points.size());
        for (std::size_t v = 0; v < soup.points.size(); ++v) {
            EXPECT_EQ(file["points"][v][0].get<double>(), soup.points[v].x);
            EXPECT_EQ(file["points"][v][1].get<double>(), soup.points[v].y);
            EXPECT_EQ(file["points"][v][2].get<double>(), soup.points[v].z);
        }
        EXPECT_EQ(file["polys"], nlohmann::json::parse("[[0, 1, 2], [0, 2, 3]]"));
        const nlohmann::json& points = file["pointData"];
        EXPECT_EQ(points.size(), 4u);
        EXPECT_EQ(points["distance"]["type"], "float");
        expectValues(points["distance"], a.vertexScalars[0].values);
        EXPECT_EQ(points["source"]["type"], "int");
        expectValues(points["source"], a.vertexLabels[0].values);
        EXPECT_EQ(points["to_nearest"]["type"], "double");
        EXPECT_EQ(points["to_nearest"]["components"], 3);
        expectValues(points["to_nearest"], flat(a.vertexVectors[0].values));
        EXPECT_EQ(points["colour"]["type"], "unsigned char");
        EXPECT_EQ(points["colour"]["components"], 3);
        expectValues(points["colour"], flat(a.vertexColours));
        const nlohmann::json& cells = file["cellData"];
        EXPECT_EQ(cells.size(), 2u);
        expectValues(cells["region"], a.faceLabels[0].values);
        expectValues(cells["colour"], flat(a.faceColours));
        const nlohmann::json& field = file["fieldData"];
        EXPECT_EQ(field["roi_name"]["type"], "string");
        EXPECT_EQ(field["roi_name"]["values"], nlohmann::json::array({a.structure.name}));
        EXPECT_EQ(field["roi_colour"]["type"], "unsigned char");
        EXPECT_EQ(field["roi_colour"]["values"], nlohmann::json::parse("[200, 100, 7]"));
    }
}

TEST(VtkPolyData, LongAndUnicodeNamesAndBareMeshes) {
    TempDir dir("vtk-bare");
    MeshAttributes named;
    // Past the one-byte length of a legacy binary string (63 bytes).
    named.structure.name = std::string(100, 'A') + " Lunge rechts \xc3\xa9";
    write(dir / "named.vtk", square(), named);
    write(dir / "named.vtp", square(), named);
    write(dir / "bare.vtk", square(), {});
    write(dir / "bare.vtp", square(), {});
    DFRECON_READ_WITH_VTK(
        read, {dir / "named.vtk", dir / "named.vtp", dir / "bare.vtk", dir / "bare.vtp"});
    for (int k = 0; k < 2; ++k) {
        const nlohmann::json& file = read.files[std::size_t(k)];
        EXPECT_EQ(file["fieldData"]["roi_name"]["values"][0], named.structure.name);
        EXPECT_FALSE(file["fieldData"].contains("roi_colour"));
        EXPECT_TRUE(file["pointData"].empty());
    }
    for (int k = 2; k < 4; ++k) {
        const nlohmann::json& file = read.files[std::size_t(k)];
        EXPECT_EQ(file["points"].size(), 4u);
        EXPECT_EQ(file["cells"], 2);
        EXPECT_TRUE(file["fieldData"].empty());
        EXPECT_TRUE(file["pointData"].empty());
        EXPECT_TRUE(file["cellData"].empty());
    }
}

TEST(VtkPolyData, WrongSizesAreRefusedBeforeAnyByte) {
    MeshAttributes a = everything();
    a.faceLabels[0].values.pop_back();
    std::ostringstream legacy, xml;
    EXPECT_THROW(writeVtkLegacy(legacy, square(), a), std::invalid_argument);
    EXPECT_THROW(writeVtkXml(xml, square(), a), std::invalid_argument);
    EXPECT_TRUE(legacy.str().empty());
    EXPECT_TRUE(xml.str().empty());
}
