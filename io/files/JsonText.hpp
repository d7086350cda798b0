#pragma once
// JSON in and out, for every file dfrecon reads as JSON (batch manifests and
// records, mask-stack sidecars) and every report it prints. Reading holds a
// file to what a hostile one could abuse in nlohmann::json: nesting (a
// record nested 10^5 deep crashed the report), repeated keys (silently the
// last one won) and bytes that are not UTF-8 (a raw library message, no file
// named). Writing never throws on a name that is not UTF-8.
#include <cstdint>
#include <string>

#include <nlohmann/json.hpp>

namespace dfrecon {

struct JsonLimits {
    /// Most levels of lists and objects (the top value is level 1).
    int maxDepth = 16;
    /// Largest file readJsonFile reads.
    std::uint64_t maxBytes = std::uint64_t(256) << 20;
};

/// Parses `text`, read from `file` (which only labels messages): valid JSON,
/// at most limits.maxDepth levels deep, no key twice in one object. Lines
/// that are not UTF-8 are read as Windows-1252 (io/files/TextEncoding). Throws
/// InputError(file, line, problem) — the line where the parser stopped, or
/// for a repeated key or a level too deep the place as a JSON pointer
/// ("/3/input"). Linear in the text: a first pass checks, nlohmann's own
/// parser (iterative, no callback: its callback parser is quadratic on long
/// lists) builds the value.
nlohmann::json parseJsonText(const std::string& text, const std::string& file,
                             const JsonLimits& limits);

/// parseJsonText on the bytes of `path`, a regular file of at most
/// limits.maxBytes (io/files/RegularFile). `what` names the kind of file for the
/// size message ("a batch record").
nlohmann::json readJsonFile(const std::string& path, const JsonLimits& limits,
                            const std::string& what);

/// `value` as JSON text (indented by `indent`, or on one line when
/// negative). Bytes that are not UTF-8 in a string (a file name given on
/// the command line) become U+FFFD instead of an exception: a report is
/// never lost to a name. O(size).
std::string jsonText(const nlohmann::ordered_json& value, int indent = -1);
std::string jsonText(const nlohmann::json& value, int indent = -1);

}  // namespace dfrecon
