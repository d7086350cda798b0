// A user's file read as the program reads it (api readContours): which
// warnings reading gives, and which ROI each is about.
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

}  // namespace dfrecon
