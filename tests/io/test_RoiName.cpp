// One rule for ROI names (io/contours/RoiName): what it refuses, and that what it
// mends passes it.
#include <gtest/gtest.h>

#include <string>

#include "contours/ContourSet.hpp"
#include "io/contours/RoiName.hpp"

using namespace dfrecon;

TEST(RoiName, RefusesWhatSomeFormatCannotHold) {
    EXPECT_EQ(roiNameProblem("PTV 70"), "");
    EXPECT_EQ(roiNameProblem("Läsion"), "");
    EXPECT_EQ(roiNameProblem(""), "is empty");
    EXPECT_EQ(roiNameProblem("caf\xe9"), "is not UTF-8");
    EXPECT_EQ(roiNameProblem("a\tb"), "holds a control character (U+0009)");
    EXPECT_EQ(roiNameProblem("a\x7f"), "holds a control character (U+007F)");
    EXPECT_NE(roiNameProblem(std::string(kMaxRoiNameBytes + 1, 'x')), "");
}

TEST(RoiName, MendedNamesPassTheRule) {
    EXPECT_EQ(mendedRoiName("PTV"), "PTV");
    EXPECT_EQ(mendedRoiName("caf\xe9"), "caf\xc3\xa9");  // Windows-1252 é
    EXPECT_EQ(mendedRoiName("a\nb"), "a_b");
    EXPECT_EQ(mendedRoiName(""), "_");
    // Cut at a character's start: 'é' is two bytes.
    std::string longName(kMaxRoiNameBytes - 1, 'x');
    longName += "\xc3\xa9";
    const std::string cut = mendedRoiName(longName);
    EXPECT_EQ(cut.size(), kMaxRoiNameBytes - 1);
    for (const std::string& name : {std::string("caf\xe9\x01"), longName, std::string("\x01\x02")})
        EXPECT_EQ(roiNameProblem(mendedRoiName(name)), "") << name;
}
