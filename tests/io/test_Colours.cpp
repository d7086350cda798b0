// The colour schemes: the ramp's ends, the sign of the diverging scheme,
// distinct categorical colours, and the no-value colour wherever there is
// no value.
#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "io/images/Colours.hpp"

using namespace dfrecon;

TEST(Colours, SequentialRunsFromBlueToRedAndClamps) {
    EXPECT_EQ(sequentialColour(0, 10), (Rgb{0, 0, 255}));
    EXPECT_EQ(sequentialColour(10, 10), (Rgb{255, 0, 0}));
    EXPECT_EQ(sequentialColour(25, 10), sequentialColour(10, 10));
    EXPECT_EQ(sequentialColour(-1, 10), sequentialColour(0, 10));
    EXPECT_EQ(sequentialColour(5, 0), sequentialColour(0, 10));  // nothing to scale by
    EXPECT_EQ(sequentialColour(NAN, 10), kNoValueColour);
    EXPECT_EQ(sequentialColour(INFINITY, 10), kNoValueColour);
}

TEST(Colours, DivergingShowsTheSignAndIsBrightestAtZero) {
    const Rgb inside = divergingColour(-1, 10), outside = divergingColour(1, 10);
    EXPECT_GT(inside[2], inside[0]);
    EXPECT_GT(outside[0], outside[2]);
    EXPECT_GT(divergingColour(0.1, 10)[0], divergingColour(5, 10)[0]);
    EXPECT_EQ(divergingColour(50, 10), divergingColour(10, 10));
    EXPECT_EQ(divergingColour(INFINITY, 10), kNoValueColour);
}

TEST(Colours, CategoricalColoursDifferAndNegativeIdsHaveNone) {
    std::set<Rgb> seen;
    for (int id = 0; id < 32; ++id) seen.insert(categoricalColour(id));
    EXPECT_EQ(seen.size(), 32u);
    EXPECT_EQ(categoricalColour(-1), kNoValueColour);
    EXPECT_NE(categoricalColour(0), kNoValueColour);
    EXPECT_EQ(categoricalColour(7), categoricalColour(7));
}
