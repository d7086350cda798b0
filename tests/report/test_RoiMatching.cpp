// Matching the ROIs of two structure sets: the map first, then equal names,
// then folded names where they are unambiguous.
#include <gtest/gtest.h>

#include <stdexcept>

#include "report/RoiMatching.hpp"

using namespace dfrecon;
using namespace dfrecon;

namespace {

ContourSet setOf(const std::vector<std::string>& names) {
    ContourSet set;
    for (const std::string& name : names) {
        Roi roi;
        roi.name = name;
        roi.slices.push_back({0, {{{0, 0}, {1, 0}, {0, 1}}}});
        set.rois.push_back(roi);
    }
    return set;
}

}  // namespace

TEST(RoiMatching, FoldedNamesIgnoreCaseSpacesAndPunctuation) {
    EXPECT_EQ(foldedRoiName("Parotid_L"), "parotidl");
    EXPECT_EQ(foldedRoiName(" parotid l "), "parotidl");
    EXPECT_EQ(foldedRoiName("PTV-1"), "ptv1");
}

TEST(RoiMatching, MapThenNameThenFoldedName) {
    const ContourSet a = setOf({"Cord", "PTV", "Parotid_L", "Lung", "Only A"});
    ContourSet b = setOf({"SpinalCord", "PTV", "parotid l", "lung", "LUNG", "Only B"});
    Roi empty;
    empty.name = "Empty";
    b.rois.push_back(empty);  // no slices: not a structure to match
    const RoiMatching m = matchRois(a, b, {"Cord=SpinalCord"});
    ASSERT_EQ(m.pairs.size(), 3u);
    EXPECT_EQ(m.pairs[0].a->name, "Cord");
    EXPECT_STREQ(m.pairs[0].matchedBy, "map");
    EXPECT_EQ(m.pairs[1].b->name, "PTV");
    EXPECT_STREQ(m.pairs[1].matchedBy, "name");
    EXPECT_EQ(m.pairs[2].b->name, "parotid l");
    EXPECT_STREQ(m.pairs[2].matchedBy, "folded name");
    // "lung" and "LUNG" fold alike: ambiguous, left to the map.
    ASSERT_EQ(m.onlyA.size(), 2u);
    EXPECT_EQ(m.onlyA[0]->name, "Lung");
    ASSERT_EQ(m.onlyB.size(), 3u);
    EXPECT_EQ(m.onlyB[2]->name, "Only B");
    ASSERT_EQ(m.emptyB.size(), 1u);  // listed, not lost
    EXPECT_EQ(m.emptyB[0]->name, "Empty");
}

TEST(RoiMatching, EveryRoiIsInExactlyOnePlace) {
    // Planning systems allow one name twice; neither copy can be paired by
    // name, and both are reported as such, not as "only in".
    ContourSet a = setOf({"GTV", "GTV", "Cord", "Brain"});
    ContourSet b = setOf({"GTV", "Cord", "Cord", "brain"});
    Roi empty;
    empty.name = "Nothing";
    a.rois.push_back(empty);
    const RoiMatching m = matchRois(a, b, {});
    ASSERT_EQ(m.pairs.size(), 1u);
    EXPECT_EQ(m.pairs[0].a->name, "Brain");
    ASSERT_EQ(m.duplicateA.size(), 2u);
    ASSERT_EQ(m.duplicateB.size(), 2u);
    EXPECT_EQ(m.duplicateB[0]->name, "Cord");
    ASSERT_EQ(m.emptyA.size(), 1u);
    // Every ROI of each set is in one list.
    for (const auto& [set, lists] :
         {std::pair{&a, std::vector{&m.onlyA, &m.duplicateA, &m.emptyA}},
          std::pair{&b, std::vector{&m.onlyB, &m.duplicateB, &m.emptyB}}}) {
        std::size_t placed = m.pairs.size();
        for (const auto* list : lists) placed += list->size();
        EXPECT_EQ(placed, set->rois.size());
    }
    EXPECT_EQ(m.onlyA.size(), 1u);  // Cord of A: B's two are duplicates
    EXPECT_EQ(m.onlyB.size(), 1u);  // GTV of B: A's two are duplicates
    // --match pairs the first of a repeated name; the other stays a duplicate.
    const RoiMatching mapped = matchRois(a, b, {"GTV=GTV"});
    EXPECT_EQ(mapped.pairs.size(), 2u);
    EXPECT_EQ(mapped.duplicateA.size(), 1u);
}

TEST(RoiMatching, BadMapsAreUsageErrors) {
    const ContourSet a = setOf({"A1", "A2"}), b = setOf({"B1", "B2"});
    EXPECT_THROW(matchRois(a, b, {"A1"}), std::invalid_argument);
    EXPECT_THROW(matchRois(a, b, {"A1=Nope"}), std::invalid_argument);
    EXPECT_THROW(matchRois(a, b, {"A1=B1", "A1=B2"}), std::invalid_argument);
    EXPECT_EQ(matchRois(a, b, {"A1=B2", "A2=B1"}).pairs.size(), 2u);
}
