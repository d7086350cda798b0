#include "report/RoiMatching.hpp"

#include <algorithm>
#include <map>
#include <set>
#include <stdexcept>

namespace dfrecon {

namespace {

const Roi& namedRoi(const ContourSet& set, const std::string& name, const char* side) {
    const Roi* roi = set.findRoi(name);
    if (!roi || !isComparable(*roi))
        throw std::invalid_argument(std::string("--match: ") + side + " has no ROI '" + name +
                                    "' with contours");
    return *roi;
}

// Pairs the unmatched ROIs of both sides whose `key` is equal and one
// ROI's alone on each side.
template <class Key>
void pairByKey(std::vector<const Roi*>& onlyA, std::vector<const Roi*>& onlyB, Key key,
               const char* how, std::vector<RoiPair>& pairs) {
    std::map<std::string, std::vector<const Roi*>> byKeyA, byKeyB;
    for (const Roi* roi : onlyA) byKeyA[key(roi->name)].push_back(roi);
    for (const Roi* roi : onlyB) byKeyB[key(roi->name)].push_back(roi);
    std::set<const Roi*> matched;
    for (const auto& [k, rois] : byKeyA) {
        const auto other = byKeyB.find(k);
        if (k.empty() || rois.size() != 1 || other == byKeyB.end() || other->second.size() != 1)
            continue;
        pairs.push_back({rois.front(), other->second.front(), how});
        matched.insert(rois.front());
        matched.insert(other->second.front());
    }
    auto unmatched = [&](std::vector<const Roi*>& list) {
        std::vector<const Roi*> kept;
        for (const Roi* roi : list)
            if (!matched.count(roi)) kept.push_back(roi);
        list = std::move(kept);
    };
    unmatched(onlyA);
    unmatched(onlyB);
}

}  // namespace

bool isComparable(const Roi& roi) {
    return !roi.slices.empty() || roi.defect.has_value();
}

std::string foldedRoiName(const std::string& name) {
    std::string folded;
    for (char c : name) {
        if (c >= 'A' && c <= 'Z')
            folded += char(c - 'A' + 'a');
        else if ((c >= 'a' && c <= 'z') || (c >= '0' && c <= '9'))
            folded += c;
    }
    return folded;
}

RoiMatching matchRois(const ContourSet& a, const ContourSet& b,
                      const std::vector<std::string>& map) {
    RoiMatching matching;
    std::set<const Roi*> mapped;
    for (const std::string& entry : map) {
        const std::size_t equals = entry.find('=');
        if (equals == std::string::npos)
            throw std::invalid_argument("--match '" + entry + "': expected NAME_IN_A=NAME_IN_B");
        const Roi& roiA = namedRoi(a, entry.substr(0, equals), "A");
        const Roi& roiB = namedRoi(b, entry.substr(equals + 1), "B");
        if (!mapped.insert(&roiA).second || !mapped.insert(&roiB).second)
            throw std::invalid_argument("--match '" + entry + "': an ROI is matched twice");
        matching.pairs.push_back({&roiA, &roiB, "map"});
    }
    // Sorted into: mapped above, empty, duplicate name, or to be paired.
    auto place = [&](const ContourSet& set, std::vector<const Roi*>& only,
                     std::vector<const Roi*>& duplicates, std::vector<const Roi*>& empty) {
        std::map<std::string, int> uses;
        for (const Roi& roi : set.rois) ++uses[roi.name];
        for (const Roi& roi : set.rois) {
            if (mapped.count(&roi)) continue;
            if (!isComparable(roi))
                empty.push_back(&roi);
            else if (uses[roi.name] > 1)
                duplicates.push_back(&roi);
            else
                only.push_back(&roi);
        }
    };
    place(a, matching.onlyA, matching.duplicateA, matching.emptyA);
    place(b, matching.onlyB, matching.duplicateB, matching.emptyB);
    pairByKey(
        matching.onlyA, matching.onlyB, [](const std::string& n) { return n; }, "name",
        matching.pairs);
    pairByKey(matching.onlyA, matching.onlyB, foldedRoiName, "folded name", matching.pairs);
    // A's order: where each paired ROI of A stands in its set.
    auto position = [&](const Roi* roi) { return roi - a.rois.data(); };
    std::stable_sort(
        matching.pairs.begin(), matching.pairs.end(),
        [&](const RoiPair& x, const RoiPair& y) { return position(x.a) < position(y.a); });
    return matching;
}

}  // namespace dfrecon
