#pragma once
// The one CSV form of dfrecon's tables (batch-report, compare of structure
// sets): RFC 4180, numbers as JSON writes them.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace dfrecon::app {

/// `rows` (objects) as CSV: a header line of `columns`, then one line per
/// row with each column's value; numbers as JSON writes them (shortest text
/// that reads back exactly), booleans true or false, null or a missing key
/// as an empty cell, text quoted where it must be (a comma, quote, line
/// break or edge space). O(cells).
std::string csvTable(const nlohmann::ordered_json& rows, const std::vector<std::string>& columns);

}  // namespace dfrecon::app
