#include "io/files/JsonText.hpp"

#include <algorithm>
#include <set>
#include <vector>

#include "contours/InputError.hpp"
#include "io/files/RegularFile.hpp"
#include "io/files/TextEncoding.hpp"

namespace dfrecon {

namespace {

using Json = nlohmann::json;

// The first pass: nlohmann's SAX events, checked for depth and repeated
// keys, building nothing. Stops at the first problem.
class JsonChecker : public nlohmann::json_sax<Json> {
  public:
    explicit JsonChecker(int maxDepth) : maxDepth_(maxDepth) {}

    const std::string& problem() const { return problem_; }
    std::size_t errorByte() const { return errorByte_; }

    bool null() override { return value(); }
    bool boolean(bool) override { return value(); }
    bool number_integer(number_integer_t) override { return value(); }
    bool number_unsigned(number_unsigned_t) override { return value(); }
    bool number_float(number_float_t, const string_t&) override { return value(); }
    bool string(string_t&) override { return value(); }
    bool binary(binary_t&) override { return value(); }

    bool start_object(std::size_t) override { return open(true); }
    bool key(string_t& key) override {
        Level& level = levels_.back();
        level.key = key;
        if (!level.keys.insert(key).second) {
            problem_ = "the key '" + key + "' a second time in one object, at " + pointer() +
                       " (each key at most once)";
            return false;
        }
        return true;
    }
    bool end_object() override { return close(); }
    bool start_array(std::size_t) override { return open(false); }
    bool end_array() override { return close(); }

    bool parse_error(std::size_t position, const std::string&,
                     const nlohmann::detail::exception& e) override {
        problem_ = std::string("not valid JSON: ") + e.what();
        errorByte_ = position;
        return false;
    }

  private:
    struct Level {
        bool object = false;
        std::set<std::string> keys;  // an object's keys so far
        std::string key;             // the current one
        std::size_t items = 0;       // a list's items so far
    };

    // A value (scalar, list or object) completes an item of a list.
    bool value() {
        if (!levels_.empty() && !levels_.back().object) ++levels_.back().items;
        return true;
    }
    bool open(bool object) {
        if (int(levels_.size()) == maxDepth_) {
            problem_ = "lists or objects nested more than " + std::to_string(maxDepth_) +
                       " deep, at " + pointer();
            return false;
        }
        levels_.push_back({object, {}, {}, 0});
        return true;
    }
    bool close() {
        levels_.pop_back();
        return value();
    }

    // Where the parser is, as a JSON pointer (RFC 6901).
    std::string pointer() const {
        std::string where;
        for (const Level& level : levels_) {
            where += '/';
            if (!level.object) {
                where += std::to_string(level.items);
                continue;
            }
            for (const char c : level.key)
                where += c == '~'   ? std::string("~0")
                         : c == '/' ? std::string("~1")
                                    : std::string(1, c);
        }
        return where.empty() ? "/" : where;
    }

    int maxDepth_;
    std::vector<Level> levels_;
    std::string problem_;
    std::size_t errorByte_ = 0;
};

int lineOfByte(const std::string& text, std::size_t byte) {
    return 1 + int(std::count(text.begin(), text.begin() + std::min(byte, text.size()), '\n'));
}

}  // namespace

Json parseJsonText(const std::string& rawText, const std::string& file, const JsonLimits& limits) {
    const std::string text = utf8FromLegacyLines(rawText);
    JsonChecker checker(limits.maxDepth);
    if (!Json::sax_parse(text, &checker)) {
        const int line = checker.errorByte() > 0 ? lineOfByte(text, checker.errorByte()) : 0;
        throw InputError(file, line, checker.problem());
    }
    return Json::parse(text);
}

Json readJsonFile(const std::string& path, const JsonLimits& limits, const std::string& what) {
    return parseJsonText(readRegularFile(path, limits.maxBytes, what), path, limits);
}

std::string jsonText(const nlohmann::ordered_json& value, int indent) {
    return value.dump(indent, ' ', false, nlohmann::ordered_json::error_handler_t::replace);
}

std::string jsonText(const nlohmann::json& value, int indent) {
    return value.dump(indent, ' ', false, Json::error_handler_t::replace);
}

}  // namespace dfrecon
