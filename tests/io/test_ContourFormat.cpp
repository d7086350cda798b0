// The one table of contour inputs: what a path holds, by its first bytes
// before its name, never blocking on a pipe, and the help text made from it.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

#include "io/contours/ContourFormat.hpp"
#include "tests/TempDir.hpp"

using namespace dfrecon;
using dfrecon::testing::TempDir;

namespace {

std::string write(const TempDir& dir, const std::string& name, const std::string& bytes) {
    const std::string path = dir / name;
    std::ofstream(path, std::ios::binary) << bytes;
    return path;
}

// A NIfTI-1 header's first four bytes: its size, 348, in either byte order.
std::string niftiStart(bool bigEndian) {
    std::string head(352, '\0');
    const std::uint32_t size = 348;
    for (int k = 0; k < 4; ++k)
        head[std::size_t(bigEndian ? 3 - k : k)] = char((size >> (8 * k)) & 0xff);
    return head;
}

}  // namespace

TEST(ContourFormat, ContentDecidesBeforeTheName) {
    const TempDir dir("contour-format-content");
    std::string dicom(200, '\0');
    dicom.replace(128, 4, "DICM");
    EXPECT_EQ(contourFormatOf(write(dir, "exported.txt", dicom)), ContourFormat::RtStruct);
    EXPECT_EQ(contourFormatOf(write(dir, "rs.slices", dicom)), ContourFormat::RtStruct);
    EXPECT_EQ(contourFormatOf(write(dir, "labels.dat", "NRRD0004\ntype: uint8\n")),
              ContourFormat::LabelVolume);
    EXPECT_EQ(contourFormatOf(write(dir, "little.img", niftiStart(false))),
              ContourFormat::LabelVolume);
    EXPECT_EQ(contourFormatOf(write(dir, "big.img", niftiStart(true))), ContourFormat::LabelVolume);
    EXPECT_EQ(contourFormatOf(write(dir, "a.slices", "dfrecon-slices 1\nunits mm\n")),
              ContourFormat::Slices);
    // A short DICOM-named file: the name decides.
    EXPECT_EQ(contourFormatOf(write(dir, "short.DCM", "x")), ContourFormat::RtStruct);
}

TEST(ContourFormat, NamesDecideWhatTheBytesDoNot) {
    const TempDir dir("contour-format-names");
    // Missing files: by name alone (their reader then names the file).
    EXPECT_EQ(contourFormatOf(dir / "rs.dcm"), ContourFormat::RtStruct);
    for (const std::string& extension : labelVolumeExtensions())
        EXPECT_EQ(contourFormatOf(dir / ("atlas" + extension)), ContourFormat::LabelVolume)
            << extension;
    EXPECT_EQ(contourFormatOf(dir / "ATLAS.NII.GZ"), ContourFormat::LabelVolume);
    EXPECT_EQ(contourFormatOf(dir / "masks.json"), ContourFormat::MaskStack);
    EXPECT_EQ(contourFormatOf(dir / "anything.txt"), ContourFormat::Slices);
    EXPECT_EQ(contourFormatOf("-"), ContourFormat::Slices);
    // A folder is a mask stack when it holds the sidecar.
    std::filesystem::create_directories(dir / "stack");
    EXPECT_EQ(contourFormatOf(dir / "stack"), ContourFormat::Slices);
    write(dir, "stack/stack.json", "{}");
    EXPECT_EQ(contourFormatOf(dir / "stack"), ContourFormat::MaskStack);
}

TEST(ContourFormat, APipeIsNeverOpenedToLookAtIt) {
    const TempDir dir("contour-format-fifo");
    const std::string fifo = dir / "pipe";
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    // Opening a FIFO with no writer would block forever.
    EXPECT_EQ(contourFormatOf(fifo), ContourFormat::Slices);
    EXPECT_FALSE(isDicomFile(fifo));
}

TEST(ContourFormat, NamesAndHelpComeFromTheTable) {
    EXPECT_STREQ(contourFormatName(ContourFormat::Slices), "dfrecon-slices 1");
    EXPECT_STREQ(contourFormatName(ContourFormat::RtStruct), "DICOM RTSTRUCT");
    EXPECT_STREQ(contourFormatName(ContourFormat::LabelVolume), "label volume");
    EXPECT_STREQ(contourFormatName(ContourFormat::MaskStack), "mask stack");
    const std::string help = contourInputHelp();
    for (const std::string& extension : labelVolumeExtensions())
        EXPECT_NE(help.find(extension), std::string::npos) << extension;
    for (const char* word : {".slices", ".dcm", "stack.json", "standard input"})
        EXPECT_NE(help.find(word), std::string::npos) << word;
}
