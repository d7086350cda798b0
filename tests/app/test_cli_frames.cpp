// Patient coordinates through every command: a label volume in RAS axes
// (NIfTI's usual ones), a sagittal one, and unevenly spaced planes. Each
// output's geometry is checked against the source's own voxels, placed in
// LPS by readLabelVolume, not against what another output says.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include <openvdb/openvdb.h>

#include "geometry/Box3.hpp"
#include "io/labels/LabelVolume.hpp"
#include "io/mesh/MeshIO.hpp"
#include "io/volumes/LevelSetVdb.hpp"
#include "tests/CliRun.hpp"
#include "tests/TempDir.hpp"

namespace {

using dfrecon::LabelVolume;
using dfrecon::Vec3;
using dfrecon::testing::CliResult;
using dfrecon::testing::runCli;
using dfrecon::testing::slurp;
using dfrecon::testing::TempDir;

// A NIfTI-1 file of uint8 labels whose voxel (i, j, k) lies at RAS
// sform · (i, j, k, 1): the layout niftilib and nibabel read.
void writeNifti(const std::string& path, std::array<int, 3> size, std::array<float, 3> spacing,
                const std::array<std::array<float, 4>, 3>& sform,
                const std::vector<std::uint8_t>& labels) {
    char header[352] = {};
    auto put = [&](std::size_t offset, const auto& value) {
        std::memcpy(header + offset, &value, sizeof value);
    };
    put(0, std::int32_t(348));
    const std::int16_t dim[8] = {
        3, std::int16_t(size[0]), std::int16_t(size[1]), std::int16_t(size[2]), 1, 1, 1, 1};
    put(40, dim);
    put(70, std::int16_t(2));  // DT_UINT8
    put(72, std::int16_t(8));
    const float pixdim[8] = {1, spacing[0], spacing[1], spacing[2], 0, 0, 0, 0};
    put(76, pixdim);
    put(108, 352.0f);  // vox_offset
    put(112, 1.0f);    // scl_slope
    put(252, std::int16_t(0));
    put(254, std::int16_t(1));  // sform_code: scanner
    put(280, sform[0]);
    put(296, sform[1]);
    put(312, sform[2]);
    std::memcpy(header + 344, "n+1\0", 4);
    std::ofstream out(path, std::ios::binary);
    out.write(header, sizeof header);
    out.write(reinterpret_cast<const char*>(labels.data()), std::streamsize(labels.size()));
}

// Label 1 is a box of voxels [lo, hi] (inclusive) in a volume of `size`.
std::vector<std::uint8_t> boxLabels(std::array<int, 3> size, std::array<int, 3> lo,
                                    std::array<int, 3> hi) {
    const std::size_t count = std::size_t(size[0]) * std::size_t(size[1]) * std::size_t(size[2]);
    std::vector<std::uint8_t> labels(count, 0);
    for (int k = lo[2]; k <= hi[2]; ++k)
        for (int j = lo[1]; j <= hi[1]; ++j)
            for (int i = lo[0]; i <= hi[0]; ++i)
                labels[(std::size_t(k) * size[1] + j) * size[0] + i] = 1;
    return labels;
}

using dfrecon::Box3;

// The LPS box the contours of label 1 span: in the plane, voxel centres
// ± half a voxel (contours pass through the midpoints between inside and
// outside centres); along the plane normal, the plane centres themselves.
// With `slabs`, the voxels' own box: also ± half a voxel along the normal.
Box3 labelBox(const LabelVolume& volume, bool slabs) {
    const dfrecon::VolumeGeometry& g = volume.geometry;
    Box3 box;
    for (int k = 0; k < g.size[2]; ++k)
        for (int j = 0; j < g.size[1]; ++j)
            for (int i = 0; i < g.size[0]; ++i)
                if (volume.labels[g.linearIndex(i, j, k)] == 1)
                    for (double di : {-0.5, 0.5})
                        for (double dj : {-0.5, 0.5})
                            for (double dk : {-0.5, 0.5})
                                box.add(g.worldOfIndex(i + di, j + dj, k + (slabs ? dk : 0)));
    return box;
}

// "space origin", "space directions" and "sizes" of a NRRD header.
struct NrrdGeometry {
    std::vector<int> sizes;
    Vec3 origin;
    std::vector<Vec3> directions;
    std::size_t byteSkip = 0;
    std::string dataFile;
};

NrrdGeometry readNrrdHeader(const std::string& path) {
    NrrdGeometry g;
    std::ifstream in(path);
    std::string line;
    const std::regex vector(R"(\(([^,]+),([^,]+),([^)]+)\))");
    auto vectors = [&](const std::string& text) {
        std::vector<Vec3> out;
        for (auto it = std::sregex_iterator(text.begin(), text.end(), vector);
             it != std::sregex_iterator(); ++it)
            out.push_back({std::stod((*it)[1]), std::stod((*it)[2]), std::stod((*it)[3])});
        return out;
    };
    while (std::getline(in, line)) {
        const auto colon = line.find(": ");
        if (colon == std::string::npos) continue;
        const std::string key = line.substr(0, colon), value = line.substr(colon + 2);
        if (key == "sizes") {
            std::istringstream s(value);
            for (int n; s >> n;) g.sizes.push_back(n);
        } else if (key == "space origin") {
            g.origin = vectors(value).at(0);
        } else if (key == "space directions") {
            g.directions = vectors(value);
        } else if (key == "byte skip") {
            g.byteSkip = std::stoul(value);
        } else if (key == "data file") {
            g.dataFile = value;
        }
    }
    return g;
}

std::vector<float> readFloats(const std::string& path, std::size_t skipBytes, std::size_t count) {
    std::ifstream in(path, std::ios::binary);
    in.seekg(std::streamoff(skipBytes));
    std::vector<float> values(count);
    in.read(reinterpret_cast<char*>(values.data()), std::streamsize(count * sizeof(float)));
    EXPECT_TRUE(in) << path;
    return values;
}

// Every sample of a 2D distance slice more than a voxel diagonal from the
// border is negative exactly where its LPS position falls in a label-1
// voxel: the NRRD geometry puts the field where the voxels are.
void expectFieldSliceOnVoxels(const NrrdGeometry& header, Vec3 sliceOrigin,
                              const std::vector<float>& distance, const LabelVolume& volume) {
    const dfrecon::VolumeGeometry& g = volume.geometry;
    const double margin =
        std::sqrt(g.spacingMm[0] * g.spacingMm[0] + g.spacingMm[1] * g.spacingMm[1] +
                  g.spacingMm[2] * g.spacingMm[2]);
    std::size_t checked = 0;
    for (int j = 0; j < header.sizes[1]; ++j)
        for (int i = 0; i < header.sizes[0]; ++i) {
            const float d = distance[std::size_t(j) * std::size_t(header.sizes[0]) + i];
            if (std::abs(d) < margin) continue;
            const Vec3 p =
                sliceOrigin + double(i) * header.directions[0] + double(j) * header.directions[1];
            const auto index = g.indexOfWorld(p);
            int ijk[3];
            bool inGrid = true;
            for (int a = 0; a < 3; ++a) {
                ijk[a] = int(std::lround(index[std::size_t(a)]));
                inGrid = inGrid && ijk[a] >= 0 && ijk[a] < g.size[std::size_t(a)];
            }
            const bool labelled =
                inGrid && volume.labels[g.linearIndex(ijk[0], ijk[1], ijk[2])] == 1;
            ASSERT_EQ(d < 0, labelled)
                << "sample " << i << ", " << j << " at " << p.x << ", " << p.y << ", " << p.z;
            ++checked;
        }
    EXPECT_GT(checked, 100u);
}

struct FrameCase {
    std::string name;
    std::array<int, 3> size;
    std::array<float, 3> spacing;
    std::array<std::array<float, 4>, 3> sform;  // RAS
    std::array<int, 3> lo, hi;                  // the label's voxel box
    std::string planes;
};

void PrintTo(const FrameCase& c, std::ostream* out) {
    *out << c.name;
}

class CliFrames : public ::testing::TestWithParam<FrameCase> {};

TEST_P(CliFrames, InfoFieldsFieldAndMeshAgreeWithTheVoxelsInLps) {
    const FrameCase& c = GetParam();
    const TempDir dir("frames");
    const std::string nifti = dir / (c.name + ".nii");
    writeNifti(nifti, c.size, c.spacing, c.sform, boxLabels(c.size, c.lo, c.hi));
    const LabelVolume volume = dfrecon::readLabelVolume(nifti);
    const Box3 expected = labelBox(volume, false);

    // info: the extent in LPS, to rounding (contour points are exact).
    const CliResult info = runCli(dir.str(), "info --json " + nifti);
    ASSERT_EQ(info.exitCode, 0) << info.err;
    const auto roi = nlohmann::json::parse(info.out)["rois"][0];
    EXPECT_EQ(roi["planes"], c.planes);
    for (std::size_t a = 0; a < 3; ++a) {
        EXPECT_NEAR(roi["extentMm"]["min"][a].get<double>(), expected.lo[int(a)], 1e-9) << a;
        EXPECT_NEAR(roi["extentMm"]["max"][a].get<double>(), expected.hi[int(a)], 1e-9) << a;
    }

    // fields: the NRRD's samples sit on the voxels they describe.
    const std::string fieldsDir = dir / "fields";
    const CliResult fields = runCli(dir.str(), "-q fields " + nifti + " -o " + fieldsDir);
    ASSERT_EQ(fields.exitCode, 0) << fields.err;
    const NrrdGeometry header = readNrrdHeader(fieldsDir + "/label_1-distance.nhdr");
    ASSERT_EQ(header.sizes.size(), 3u);
    ASSERT_EQ(header.directions.size(), 3u);
    const std::size_t sliceSamples = std::size_t(header.sizes[0]) * std::size_t(header.sizes[1]);
    for (int s = 0; s < header.sizes[2]; ++s)
        expectFieldSliceOnVoxels(header, header.origin + double(s) * header.directions[2],
                                 readFloats(fieldsDir + "/" + header.dataFile,
                                            std::size_t(s) * sliceSamples * 4, sliceSamples),
                                 volume);

    // field: the reported origin is the .vdb's voxel (0, 0, 0), and the
    // level set is negative inside the label and positive outside it.
    const std::string vdb = dir / "field.vdb";
    const CliResult field = runCli(dir.str(), "-q field --json " + nifti + " -o " + vdb);
    ASSERT_EQ(field.exitCode, 0) << field.err;
    const auto report = nlohmann::json::parse(field.out);
    openvdb::initialize();
    openvdb::io::File file(vdb);
    file.open();
    const openvdb::GridBase::Ptr grid = file.readGrid("label_1");
    file.close();
    const openvdb::Vec3d origin = grid->transform().indexToWorld(openvdb::Vec3d(0, 0, 0));
    for (int a = 0; a < 3; ++a)
        EXPECT_NEAR(report["originMm"][std::size_t(a)].get<double>(), origin[a], 1e-6) << a;
    const dfrecon::LevelSetSampler sampler(vdb);
    const dfrecon::VolumeGeometry& g = volume.geometry;
    const Vec3 centre = g.worldOfIndex(0.5 * (c.lo[0] + c.hi[0]), 0.5 * (c.lo[1] + c.hi[1]),
                                       0.5 * (c.lo[2] + c.hi[2]));
    EXPECT_LT(sampler(centre), 0.0);
    EXPECT_GT(sampler(g.worldOfIndex(c.hi[0] + 2.0, 0.5 * (c.lo[1] + c.hi[1]),
                                     0.5 * (c.lo[2] + c.hi[2]))),
              0.0);

    // reconstruct: the mesh spans the voxels' box (contours at the voxel
    // borders in the plane, flat caps half a plane spacing beyond the end
    // planes), to float rounding.
    const std::string mesh = dir / "mesh.ply";
    const CliResult recon = runCli(dir.str(), "-q reconstruct " + nifti + " -o " + mesh);
    ASSERT_EQ(recon.exitCode, 0) << recon.err;
    const Box3 voxels = labelBox(volume, true);
    Box3 meshBox;
    for (const Vec3& p : dfrecon::readTriangleSoup(mesh).points) meshBox.add(p);
    for (std::size_t a = 0; a < 3; ++a) {
        EXPECT_NEAR(meshBox.lo[int(a)], voxels.lo[int(a)], 1e-4) << a;
        EXPECT_NEAR(meshBox.hi[int(a)], voxels.hi[int(a)], 1e-4) << a;
    }
}

// RAS axes with identity directions: LPS x = −(i + 10), y = −(j − 20).
const FrameCase kRasAxial{
    "ras-axial", {40, 48, 20}, {1, 1, 2}, {{{{1, 0, 0, 10}}, {{0, 1, 0, -20}}, {{0, 0, 2, 5}}}},
    {2, 5, 3},   {14, 27, 12}, "axial"};
// Sagittal planes: i runs anterior → posterior, j inferior → superior, k
// right → left (RAS x falls with k), as a sagittal MR series is stored.
const FrameCase kSagittal{
    "sagittal",         {36, 30, 16},
    {0.8f, 1.2f, 2.5f}, {{{{0, 0, -2.5f, 30}}, {{-0.8f, 0, 0, 12}}, {{0, 1.2f, 0, -40}}}},
    {4, 6, 3},          {25, 21, 11},
    "sagittal"};

INSTANTIATE_TEST_SUITE_P(Volumes, CliFrames, ::testing::Values(kRasAxial, kSagittal),
                         [](const auto& instance) {
                             std::string name = instance.param.name;
                             for (char& ch : name)
                                 if (ch == '-') ch = '_';
                             return name;
                         });

// Planes 0, 2, 3, 7 mm apart no single NRRD spacing can place: one 2D
// header per slice, each at its own plane, and a warning saying so.
TEST(CliFramesUneven, FieldsOfUnevenPlanesGetOneHeaderPerSliceAtItsOwnPosition) {
    const TempDir dir("frames-uneven");
    const std::string slices = dir / "uneven.slices";
    {
        std::ofstream out(slices);
        out << "dfrecon-slices 1\nunits mm\nroi tube\n";
        for (double z : {0.0, 2.0, 3.0, 7.0}) {
            out << "slice " << z << "\ncontour 32\n";
            for (int i = 0; i < 32; ++i) {
                const double t = 2 * M_PI * i / 32;
                out << 5 * std::cos(t) << " " << 5 * std::sin(t) << "\n";
            }
        }
    }
    const std::string fieldsDir = dir / "fields";
    const CliResult run = runCli(dir.str(), "fields " + slices + " -o " + fieldsDir);
    ASSERT_EQ(run.exitCode, 0) << run.err;
    EXPECT_NE(run.err.find("unevenly spaced"), std::string::npos) << run.err;
    EXPECT_FALSE(std::filesystem::exists(fieldsDir + "/tube-distance.nhdr"));
    const double planes[] = {0.0, 2.0, 3.0, 7.0};
    for (int s = 0; s < 4; ++s) {
        char name[64];
        std::snprintf(name, sizeof name, "/tube-distance-%03d.nhdr", s);
        const NrrdGeometry header = readNrrdHeader(fieldsDir + name);
        ASSERT_EQ(header.sizes.size(), 2u) << name;
        EXPECT_EQ(header.origin.z, planes[s]) << name;
        // The sample nearest the centre of the 32-gon: its inradius inside,
        // to a pixel.
        const std::size_t count = std::size_t(header.sizes[0]) * std::size_t(header.sizes[1]);
        const std::vector<float> d =
            readFloats(fieldsDir + "/" + header.dataFile, header.byteSkip, count);
        const int i = int(std::lround(-header.origin.x / header.directions[0].x));
        const int j = int(std::lround(-header.origin.y / header.directions[1].y));
        EXPECT_NEAR(d[std::size_t(j) * std::size_t(header.sizes[0]) + i],
                    -5.0 * std::cos(M_PI / 32), header.directions[0].x)
            << name;
    }
}

}  // namespace
