// Label volumes as contour input: names and colours from label tables, and
// intensity images (scans) told apart from label maps.
#include "io/labels/LabelInput.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <random>

#include "contours/InputError.hpp"
#include "io/images/Colours.hpp"
#include "io/labels/LabelTable.hpp"
#include "shapes/RandomLabelVolumes.hpp"
#include "tests/TempDir.hpp"

namespace dfrecon {
namespace {

using testing::TempDir;

LabelVolume emptyVolume(int nx, int ny, int nz) {
    LabelVolume v;
    v.geometry.size = {nx, ny, nz};
    v.labels.assign(v.geometry.voxelCount(), 0);
    return v;
}

// A smooth head-like intensity pattern with scanner noise, as an 8-bit MR.
LabelVolume scan(std::uint32_t seed) {
    LabelVolume v = emptyVolume(48, 48, 4);
    std::mt19937 random(seed);
    std::normal_distribution<double> noise(0, 4);
    for (int k = 0; k < 4; ++k)
        for (int j = 0; j < 48; ++j)
            for (int i = 0; i < 48; ++i) {
                const double r = std::hypot(i - 24, j - 24);
                if (r < 20)
                    v.labels[v.geometry.linearIndex(i, j, k)] =
                        std::int32_t(std::lround(90 + 40 * std::cos(r / 4) + noise(random)));
            }
    return v;
}

// `blocks`³ cubes of `side` voxels, each its own label: an atlas of many
// small regions.
LabelVolume blockAtlas(int blocks, int side) {
    LabelVolume v = emptyVolume(blocks * side, blocks * side, blocks * side);
    for (int k = 0; k < blocks * side; ++k)
        for (int j = 0; j < blocks * side; ++j)
            for (int i = 0; i < blocks * side; ++i)
                v.labels[v.geometry.linearIndex(i, j, k)] =
                    1 + (k / side * blocks + j / side) * blocks + i / side;
    return v;
}

TEST(LabelInput, ScansAreToldApartFromLabelMaps) {
    for (std::uint32_t seed : {1u, 2u, 3u}) EXPECT_TRUE(intensityImageEvidence(scan(seed))) << seed;
    // 343 labels in cubes 5 voxels a side: borders on a fifth of the pairs.
    EXPECT_FALSE(intensityImageEvidence(blockAtlas(7, 5)));
    for (std::uint32_t seed = 0; seed < 10; ++seed) {
        EXPECT_FALSE(intensityImageEvidence(hostileLabelVolume(seed))) << seed;
        EXPECT_FALSE(intensityImageEvidence(manyBlobLabelVolume(seed, 40, 60, 4))) << seed;
    }
}

TEST(LabelInput, RefusesAScanUnlessAccepted) {
    const TempDir dir("labelinput");
    writeLabelNrrd(dir / "t1.nrrd", scan(7));
    try {
        readLabelContours(dir / "t1.nrrd");
        FAIL() << "a scan was read as labels";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("intensity image"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("--accept-intensity"), std::string::npos);
    }
    LabelInputOptions accept;
    accept.acceptIntensityImages = true;
    EXPECT_GT(readLabelContours(dir / "t1.nrrd", accept).rois.size(), kIntensityMinValues);
}

TEST(LabelInput, NamesAndColoursComeFromTheLabelTable) {
    const TempDir dir("labelinput");
    LabelVolume v = emptyVolume(12, 12, 3);
    for (int k = 0; k < 3; ++k)
        for (int j = 2; j < 10; ++j) {
            v.labels[v.geometry.linearIndex(3, j, k)] = 4;
            v.labels[v.geometry.linearIndex(7, j, k)] = 9;
        }
    writeLabelNrrd(dir / "v.nrrd", v);
    const auto namesOf = [](const ContourSet& set) {
        std::vector<std::string> names;
        for (const Roi& roi : set.rois) names.push_back(roi.name);
        return names;
    };
    EXPECT_EQ(namesOf(readLabelContours(dir / "v.nrrd")),
              (std::vector<std::string>{"label_4", "label_9"}));
    EXPECT_EQ(readLabelContours(contourSourceOf(dir / "v.nrrd")).namesFrom, "");

    // Beside the volume.
    writeLabelTable(dir / "v.txt", {{4, {"Left kidney", Rgb{1, 2, 3}}}, {9, {"Cord", {}}}});
    ContourSet beside = readLabelContours(dir / "v.nrrd");
    EXPECT_EQ(namesOf(beside), (std::vector<std::string>{"Left kidney", "Cord"}));
    EXPECT_EQ(beside.rois[0].colour, (Rgb{1, 2, 3}));
    EXPECT_EQ(contourSourceOf(dir / "v.nrrd").labelTablePath, dir / "v.txt");
    EXPECT_EQ(readLabelContours(contourSourceOf(dir / "v.nrrd")).namesFrom, dir / "v.txt");

    // Named on the command line: wins over the one beside.
    std::ofstream(dir / "other.lut") << "4 Liver 9 8 7 255\n";
    LabelInputOptions options;
    options.labelTablePath = dir / "other.lut";
    ContourSet given = readLabelContours(dir / "v.nrrd", options);
    EXPECT_EQ(namesOf(given), (std::vector<std::string>{"Liver", "label_9"}));
    EXPECT_EQ(given.rois[0].colour, (Rgb{9, 8, 7}));

    // A Slicer segmentation carries its own.
    v.keyValues =
        segmentationKeys({{4, {"Spleen", Rgb{0, 255, 0}}}, {9, {"Aorta", {}}}}, v.geometry.size);
    writeLabelNrrd(dir / "s.seg.nrrd", v);
    // Its own names win over a table beside it (none given).
    writeLabelTable(dir / "s.txt", {{4, {"Not this", {}}}});
    const LabelContours read = readLabelContours(contourSourceOf(dir / "s.seg.nrrd"));
    EXPECT_EQ(read.namesFrom, "segmentation header");
    const ContourSet& segments = read.contours;
    EXPECT_EQ(namesOf(segments), (std::vector<std::string>{"Spleen", "Aorta"}));
    EXPECT_EQ(segments.rois[0].colour, (Rgb{0, 255, 0}));
    EXPECT_EQ(segments.rois[1].colour, categoricalColour(9));

    std::ofstream(dir / "broken.txt") << "4 a\n4 b\n";
    options.labelTablePath = dir / "broken.txt";
    EXPECT_THROW(readLabelContours(dir / "v.nrrd", options), InputError);
}

}  // namespace
}  // namespace dfrecon
