// A user's file read as the program reads it (api readContours): which
// warnings reading gives, and which ROI each is about.
#include <dcmtk/config/osconfig.h>  // first, as DCMTK requires
#include <dcmtk/dcmdata/dctk.h>
#include <gtest/gtest.h>

#include <sstream>

#include "dfrecon/Contours.hpp"
#include "io/dicom/RtStruct.hpp"
#include "tests/SquareStacks.hpp"
#include "tests/TempDir.hpp"

namespace dfrecon {
namespace {

// Body on every plane 0..20 mm (the image planes); Gapped ends at 4 and
// starts again at 10; Uneven is 2 then 3 mm apart.
ContourSet gappedAndUneven() {
    ContourSet set;
    set.rois = {testing::squareStack("Body", testing::planesFrom(0, 20, 2)),
                testing::squareStack("Gapped", {0, 2, 4, 10, 12}),
                testing::squareStack("Uneven", {0, 2, 5})};
    return set;
}

// The ROIs warned of uneven spacing, in order.
std::vector<std::string> unevenlySpaced(const ContoursRead& read) {
    std::vector<std::string> rois;
    for (const InputWarning& w : read.warnings)
        if (w.message.find("uneven slice spacing") != std::string::npos) rois.push_back(w.roi);
    return rois;
}

}  // namespace

// The gap where an ROI ends and starts again is no uneven spacing (a
// 29-ROI coronal set said "uneven slice spacing, 3 to 6 mm" of an area
// that ends there); spacing uneven within a run still is. Both formats.
TEST(ReadingWarnings, UnevenSpacingIsJudgedWithinRuns) {
    std::ostringstream text;
    text << "dfrecon-slices 1\nunits mm\n";
    for (const Roi& roi : gappedAndUneven().rois) {
        text << "roi " << roi.name << "\n";
        for (const Slice& s : roi.slices)
            text << "slice " << s.zMm << "\ncontour 4\n0 0\n10 0\n10 10\n0 10\n";
    }
    std::istringstream in(text.str());
    const ContoursRead slices = readSlicesStream(in, "gaps.slices");
    EXPECT_EQ(unevenlySpaced(slices), std::vector<std::string>{"Uneven"});

    const testing::TempDir dir("reading-warnings");
    const std::string path = dir / "gaps.dcm";
    writeRtStruct(gappedAndUneven(), path);
    const ContoursRead dicom = readContours(path);
    EXPECT_EQ(unevenlySpaced(dicom), std::vector<std::string>{"Uneven"});
    // The gap is reported as one, about its ROI.
    bool gapWarned = false;
    for (const InputWarning& w : dicom.warnings)
        gapWarned = gapWarned ||
                    (w.roi == "Gapped" && w.message.find("planes left empty") != std::string::npos);
    EXPECT_TRUE(gapWarned);
}

// A name mended on reading (an RTSTRUCT's 300-byte name, cut to 256 after
// the reader has warned about its ROI) takes those warnings along:
// selecting the ROI by its new name still shows them.
TEST(ReadingWarnings, AMendedNameKeepsItsWarnings) {
    const testing::TempDir dir("reading-warnings");
    const std::string path = dir / "long.dcm";
    ContourSet set;
    set.rois = {testing::squareStack("Uneven", {0, 2, 5})};
    writeRtStruct(set, path);
    const std::string longName(300, 'x');
    {
        DcmFileFormat file;
        ASSERT_TRUE(file.loadFile(path.c_str()).good());
        DcmItem* item = nullptr;
        ASSERT_TRUE(
            file.getDataset()->findAndGetSequenceItem(DCM_StructureSetROISequence, item, 0).good());
        ASSERT_TRUE(item->putAndInsertString(DCM_ROIName, longName.c_str()).good());
        ASSERT_TRUE(file.saveFile(path.c_str()).good());
    }
    const ContoursRead read = readContours(path);
    ASSERT_EQ(read.contours.rois.size(), 1u);
    const std::string mended = read.contours.rois[0].name;
    ASSERT_LT(mended.size(), longName.size());
    EXPECT_EQ(unevenlySpaced(read), std::vector<std::string>{mended});
}

// An ROI alone on one plane in a file that says nothing of its thickness
// is warned of: its contour volume is 0, its surface a 1 mm slab.
TEST(ReadingWarnings, OnePlaneWithNoThicknessIsWarnedOf) {
    std::istringstream in(
        "dfrecon-slices 1\nunits mm\nroi Dot\nslice 4\ncontour 4\n"
        "0 0\n10 0\n10 10\n0 10\n");
    const ContoursRead read = readSlicesStream(in, "dot.slices");
    ASSERT_EQ(read.contours.rois.size(), 1u);
    EXPECT_EQ(contourVolumeMm3(read.contours.rois[0]), 0.0);
    bool warned = false;
    for (const InputWarning& w : read.warnings)
        warned = warned || (w.roi == "Dot" &&
                            w.message.find("nothing gives its thickness") != std::string::npos);
    EXPECT_TRUE(warned);
    // With a second ROI on other planes the image planes' spacing is its
    // thickness, and nothing is said.
    std::istringstream two(
        "dfrecon-slices 1\nunits mm\nroi Dot\nslice 4\ncontour 4\n"
        "0 0\n10 0\n10 10\n0 10\nroi Box\nslice 2\ncontour 4\n"
        "0 0\n10 0\n10 10\n0 10\nslice 4\ncontour 4\n0 0\n10 0\n10 10\n"
        "0 10\nslice 6\ncontour 4\n0 0\n10 0\n10 10\n0 10\n");
    const ContoursRead read2 = readSlicesStream(two, "two.slices");
    EXPECT_DOUBLE_EQ(contourVolumeMm3(read2.contours.rois[0]), 200.0);
    for (const InputWarning& w : read2.warnings)
        EXPECT_EQ(w.message.find("nothing gives its thickness"), std::string::npos) << w.message;
}

}  // namespace dfrecon
