// The .slices v1 parser: one case per error class (line and message), the
// repairs it makes, orientation by nesting, and exact round trips.
#include <gtest/gtest.h>

#include <sstream>

#include "io/contours/SlicesFile.hpp"
#include "shapes/AnalyticShapes.hpp"
#include "tests/BadSlicesInputs.hpp"

using namespace dfrecon;

namespace {

using namespace dfrecon::testing;

SlicesLoad parseText(const std::string& text, const SlicesLimits& limits = {}) {
    std::istringstream in(text);
    return parseSlices(in, "test.slices", limits);
}

class SlicesParserError : public ::testing::TestWithParam<BadInput> {};

TEST_P(SlicesParserError, ReportsLineAndProblem) {
    const BadInput& input = GetParam();
    try {
        // A defect of one ROI's geometry is kept on that ROI (the others
        // load); it must carry the same place and message.
        for (const Roi& roi : parseText(input.text).contours.rois)
            if (roi.defect) throw *roi.defect;
        FAIL() << "no error for " << input.name;
    } catch (const InputError& e) {
        EXPECT_EQ(e.file(), "test.slices");
        EXPECT_EQ(e.line(), input.line) << e.what();
        EXPECT_NE(e.problem().find(input.message), std::string::npos) << e.what();
        if (input.line > 0) {
            const std::string prefix = "test.slices:" + std::to_string(input.line) + ": ";
            EXPECT_EQ(std::string(e.what()).rfind(prefix, 0), 0u) << e.what();
        }
    }
}

INSTANTIATE_TEST_SUITE_P(AllClasses, SlicesParserError, ::testing::ValuesIn(badInputs()),
                         [](const auto& testInfo) { return std::string(testInfo.param.name); });

TEST(SlicesParser, ReadsNamesColoursCommentsAndSeveralRois) {
    const SlicesLoad load = parseText(
        "# exported by hand\n"
        "dfrecon-slices 1   # version\n"
        "units mm\n"
        "roi \"Left Lung #2\" 10 20 30\n"
        "slice -2.5\n" +
        kSquare + "\n\nroi body\nslice 0\n" + kSquare);
    ASSERT_EQ(load.contours.rois.size(), 2u);
    const Roi& lung = load.contours.rois[0];
    EXPECT_EQ(lung.name, "Left Lung #2");
    ASSERT_TRUE(lung.colour.has_value());
    EXPECT_EQ((*lung.colour)[2], 30);
    ASSERT_EQ(lung.slices.size(), 1u);
    EXPECT_EQ(lung.slices[0].zMm, -2.5);
    EXPECT_EQ(lung.slices[0].contours[0].size(), 4u);
    EXPECT_FALSE(load.contours.rois[1].colour.has_value());
    EXPECT_TRUE(load.warnings.empty());
}

TEST(SlicesParser, RepairsRepeatedPointsWithWarning) {
    const SlicesLoad load =
        parseText(kHeader + "roi a\nslice 0\ncontour 7\n0 0\n0 0\n10 0\n10 10\n10 10\n0 10\n0 0\n");
    const Polygon& c = load.contours.rois[0].slices[0].contours[0];
    EXPECT_EQ(c.size(), 4u);
    ASSERT_EQ(load.warnings.size(), 1u);
    EXPECT_EQ(load.warnings[0].line, 5);
    EXPECT_NE(load.warnings[0].message.find("dropped 3 repeated"), std::string::npos);
}

// Drawings a planning system exports and a voxel tool fills: each is read
// by the even-odd rule (geometry/PlaneReading), counted, warned about once
// per ROI, and leaves the region the rule gives.
struct Drawing {
    const char* name;
    std::string slice;  // the contours of one plane
    double areaMm2;     // the even-odd region's area
    std::size_t PlaneReadingCounts::*counted;
};

TEST(SlicesParser, PlanningSystemDrawingsAreReadByTheEvenOddRule) {
    const std::vector<Drawing> drawings{
        {"BowTie", "contour 4\n0 0\n10 10\n10 0\n0 10\n", 50,
         &PlaneReadingCounts::resolvedContours},
        {"SelfCrossing", "contour 4\n0 0\n10 10\n10 0\n0 5\n", 125.0 / 3,
         &PlaneReadingCounts::resolvedContours},
        {"SelfTouching", "contour 6\n0 0\n10 0\n5 5\n10 10\n0 10\n5 5\n", 50,
         &PlaneReadingCounts::keyholeCuts},
        {"Spike", "contour 5\n0 0\n10 0\n20 0\n10 0.0\n0 10\n", 50,
         &PlaneReadingCounts::foldPoints},
        {"ContoursCross", kSquare + "contour 4\n5 5\n15 5\n15 15\n5 15\n", 150,
         &PlaneReadingCounts::resolvedContours},
        {"StoredTwice", kSquare + kSquare, 100, &PlaneReadingCounts::duplicateContours},
        {"TwoPointsBeside", kSquare + "contour 2\n20 0\n21 1\n", 100,
         &PlaneReadingCounts::zeroAreaContours},
        {"LineBeside", kSquare + "contour 3\n20 0\n21 1\n22 2\n", 100,
         &PlaneReadingCounts::zeroAreaContours},
    };
    for (const Drawing& drawing : drawings) {
        const SlicesLoad load = parseText(kHeader + "roi a\nslice 0\n" + drawing.slice);
        const Roi& roi = load.contours.rois[0];
        ASSERT_FALSE(roi.defect.has_value()) << drawing.name << ": " << roi.defect->what();
        ASSERT_EQ(roi.slices.size(), 1u) << drawing.name;
        double area = 0;
        for (const Polygon& c : roi.slices[0].contours) area += signedArea(c);
        EXPECT_NEAR(area, drawing.areaMm2, 1e-9) << drawing.name;
        EXPECT_GT(roi.reading.*drawing.counted, 0u) << drawing.name;
    }
}

TEST(SlicesParser, AnRoiOfNothingButLinesIsEmptyNotBroken) {
    const SlicesLoad load = parseText(
        kHeader + "roi a\nslice 0\ncontour 3\n0 0\n1 1\n2 2\nslice 1\ncontour 2\n0 0\n1 1\n");
    const Roi& roi = load.contours.rois[0];
    EXPECT_FALSE(roi.defect.has_value());
    EXPECT_TRUE(roi.slices.empty());
    EXPECT_EQ(roi.reading.zeroAreaContours, 2u);
    ASSERT_EQ(load.warnings.size(), 1u);
    EXPECT_NE(
        load.warnings[0].message.find("read as planning systems read it: 2 contours of no area"),
        std::string::npos)
        << load.warnings[0].message;
}

TEST(SlicesParser, SortsSlicesAndMergesDuplicateZWithWarnings) {
    const SlicesLoad load = parseText(kHeader + "roi a\nslice 5\n" + kSquare + "slice 1\n" +
                                      kSquare + "slice 5\ncontour 3\n20 0\n30 0\n25 5\n");
    const Roi& roi = load.contours.rois[0];
    ASSERT_EQ(roi.slices.size(), 2u);
    EXPECT_EQ(roi.slices[0].zMm, 1);
    EXPECT_EQ(roi.slices[1].zMm, 5);
    EXPECT_EQ(roi.slices[1].contours.size(), 2u);
    ASSERT_EQ(load.warnings.size(), 2u);
    EXPECT_NE(load.warnings[0].message.find("sorted"), std::string::npos);
    EXPECT_NE(load.warnings[1].message.find("twice"), std::string::npos);
    EXPECT_EQ(load.warnings[1].line, 16);
}

TEST(SlicesParser, OrientsByNestingDepth) {
    // Outer clockwise, hole counter-clockwise, island clockwise: all wrong.
    const SlicesLoad load = parseText(kHeader +
                                      "roi a\nslice 0\n"
                                      "contour 4\n0 0\n0 30\n30 30\n30 0\n"
                                      "contour 4\n5 5\n25 5\n25 25\n5 25\n"
                                      "contour 4\n10 10\n10 20\n20 20\n20 10\n");
    const Slice& slice = load.contours.rois[0].slices[0];
    EXPECT_GT(signedArea(slice.contours[0]), 0);
    EXPECT_LT(signedArea(slice.contours[1]), 0);
    EXPECT_GT(signedArea(slice.contours[2]), 0);
}

TEST(SlicesParser, AcceptsContoursThatTouchAtAPoint) {
    const SlicesLoad load =
        parseText(kHeader + "roi a\nslice 0\n" + kSquare + "contour 3\n10 10\n20 10\n20 20\n");
    EXPECT_EQ(load.contours.rois[0].slices[0].contours.size(), 2u);
}

TEST(SlicesParser, EnforcesSizeLimits) {
    SlicesLimits limits;
    limits.maxPointsPerContour = 10;
    EXPECT_THROW(parseText(kHeader + "roi a\nslice 0\ncontour 11\n", limits), InputError);
    limits = {};
    limits.maxPointsTotal = 7;
    EXPECT_THROW(parseText(kHeader + "roi a\nslice 0\n" + kSquare + kSquare, limits), InputError);
    limits = {};
    limits.maxSlicesPerRoi = 1;
    EXPECT_THROW(parseText(kHeader + "roi a\nslice 0\nslice 1\n", limits), InputError);
    limits = {};
    limits.maxLineBytes = 16;
    try {
        parseText(kHeader + "roi " + std::string(100, 'x') + "\n", limits);
        FAIL();
    } catch (const InputError& e) {
        EXPECT_EQ(e.line(), 3);
        EXPECT_NE(e.problem().find("line longer than 16 bytes"), std::string::npos);
    }
}

TEST(SlicesParser, DeclaredCountDoesNotAllocateUpFront) {
    // A huge declared count with no points must fail on the count, not on memory.
    EXPECT_THROW(parseText(kHeader + "roi a\nslice 0\ncontour 999999999999\n"), InputError);
}

TEST(SlicesFile, MissingFileIsInputError) {
    EXPECT_THROW(readSlicesFile("/nonexistent/x.slices"), InputError);
}

TEST(SlicesWriter, RoundTripsExactly) {
    for (const std::string& name : shapeNames()) {
        SynthOptions options;
        options.noiseMm = 0.05;
        options.pointsPerContour = 40;
        ContourSet original = sliceShape(*makeShape(name, 1.37), options);
        original.rois[0].colour = Rgb{1, 2, 3};
        original.rois[0].name = "with space #" + name;

        std::ostringstream out;
        formatSlices(original, out);
        std::istringstream in(out.str());
        const SlicesLoad back = parseSlices(in, name);
        EXPECT_TRUE(back.warnings.empty());
        ASSERT_EQ(back.contours.rois.size(), 1u);
        const Roi &a = original.rois[0], &b = back.contours.rois[0];
        EXPECT_EQ(a.name, b.name);
        EXPECT_EQ((*b.colour)[1], 2);
        ASSERT_EQ(a.slices.size(), b.slices.size()) << name;
        for (std::size_t s = 0; s < a.slices.size(); ++s) {
            EXPECT_EQ(a.slices[s].zMm, b.slices[s].zMm);
            ASSERT_EQ(a.slices[s].contours.size(), b.slices[s].contours.size());
            for (std::size_t c = 0; c < a.slices[s].contours.size(); ++c)
                EXPECT_EQ(a.slices[s].contours[c], b.slices[s].contours[c]) << name;
        }
    }
}

TEST(SlicesWriter, RejectsNamesTheFormatCannotHold) {
    ContourSet set;
    set.rois.emplace_back();
    set.rois.back().name = "bad\nname";
    std::ostringstream out;
    EXPECT_THROW(formatSlices(set, out), std::invalid_argument);
}

TEST(SlicesWriter, QuotesAQuoteByDoublingIt) {
    // GTV "left" is valid DICOM; converting it to .slices was a usage error.
    ContourSet set;
    set.rois.emplace_back();
    set.rois.back().name = "GTV \"left\"";
    std::ostringstream out;
    formatSlices(set, out);
    EXPECT_NE(out.str().find("roi \"GTV \"\"left\"\"\"\n"), std::string::npos) << out.str();
    std::istringstream in(out.str());
    EXPECT_EQ(parseSlices(in, "q.slices").contours.rois.at(0).name, "GTV \"left\"");
}

}  // namespace
