#pragma once
// The JSON form of a comparison of two structures, as `compare --json`
// reports each pair and the Python module's compare() returns it
// (docs/cli.md, "compare", lists every key).
#include <optional>

#include <nlohmann/json.hpp>

#include "cl/Runtime.hpp"
#include "dfrecon/Compare.hpp"
#include "report/RoiMatching.hpp"

namespace dfrecon {

/// The per-plane comparison's keys, or null without one. O(1).
nlohmann::ordered_json planesJson(const std::optional<PlaneComparison>& planes);

/// Volumes, overlap, distances, centroid distance, onPlanes and seconds of
/// one comparison. O(1).
nlohmann::ordered_json comparisonJson(const Comparison& r);

/// The surface of ROI `roi` of contour file `file`, reconstructed with
/// reconstruct's defaults. Throws InvalidResult naming file and ROI when it
/// is not a valid closed solid.
ComparedSolid reconstructedSolid(ocl::Runtime& runtime, const std::string& file, const Roi& roi);

/// One pair of two structure sets as a row: roiA, roiB, matchedBy, the
/// comparison's keys (comparisonJson), seconds, exitCode 0 and error null;
/// or, where either ROI or the comparison failed, exitCode and error (the
/// program's exit code and message). Never throws for the pair's own
/// failures. `compare` and Python's compare_sets() alike.
nlohmann::ordered_json comparedPairRow(ocl::Runtime& runtime, const RoiPair& pair,
                                       const std::string& fileA, const std::string& fileB,
                                       const CompareOptions& options);

/// The ROIs of a matching that are in no pair, by list: unmatchedA/B,
/// duplicateA/B, emptyA/B, each a list of names. O(ROIs).
nlohmann::ordered_json unpairedJson(const RoiMatching& matching);

}  // namespace dfrecon
