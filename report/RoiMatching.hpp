#pragma once
// Which ROI of one structure set goes with which of another, for comparing
// two structure sets (two observers, a model against a clinician): by a map
// the user gives, then by name, then by name with case, spaces and
// punctuation ignored ("Parotid_L" and "parotid l").
#include <string>
#include <vector>

#include "contours/ContourSet.hpp"

namespace dfrecon {

struct RoiPair {
    const Roi* a = nullptr;
    const Roi* b = nullptr;
    /// "map" (--match), "name" (equal names) or "folded name" (equal with
    /// ASCII case folded and everything but letters and digits dropped).
    const char* matchedBy = "name";
};

/// Every ROI of both sets in exactly one place.
struct RoiMatching {
    std::vector<RoiPair> pairs;            // in A's order
    std::vector<const Roi*> onlyA, onlyB;  // unmatched, in their sets' order
    /// ROIs whose name another ROI of the same set also has: no name can say
    /// which is meant, so none of them is paired by name (--match pairs the
    /// first of a name); in their sets' order.
    std::vector<const Roi*> duplicateA, duplicateB;
    /// ROIs with neither contours nor a defect: nothing to compare.
    std::vector<const Roi*> emptyA, emptyB;
};

/// Whether `roi` takes part in a comparison: it has contours, or a defect
/// to report (what selectRois(all) takes). O(1).
bool isComparable(const Roi& roi);

/// `name` with ASCII letters lower-cased and every byte that is not an
/// ASCII letter or digit dropped. O(length).
std::string foldedRoiName(const std::string& name);

/// Matches `a`'s ROIs to `b`'s, each at most once: first the pairs of
/// `map` ("NAME_IN_A=NAME_IN_B", split at the first '='), then equal
/// names, then equal folded names where the folded name is one ROI's alone
/// on each side (an ambiguous one stays unmatched, to be mapped). ROIs
/// without slices or defect are listed as empty, ROIs sharing their exact
/// name with another of their set as duplicates (neither is paired). Throws std::invalid_argument
/// (a usage error) for a map entry without '=', naming an ROI its set
/// lacks, or naming an ROI twice. O(R log R) for R ROIs.
RoiMatching matchRois(const ContourSet& a, const ContourSet& b,
                      const std::vector<std::string>& map);

}  // namespace dfrecon
