#pragma once
// The JSON form of a comparison of two structures, as `compare --json`
// reports each pair and the Python module's compare() returns it
// (docs/cli.md, "compare", lists every key).
#include <optional>

#include <nlohmann/json.hpp>

#include "dfrecon/Compare.hpp"

namespace dfrecon::app {

/// The per-plane comparison's keys, or null without one. O(1).
nlohmann::ordered_json planesJson(const std::optional<PlaneComparison>& planes);

/// Volumes, overlap, distances, centroid distance, onPlanes and seconds of
/// one comparison. O(1).
nlohmann::ordered_json comparisonJson(const Comparison& r);

}  // namespace dfrecon::app
