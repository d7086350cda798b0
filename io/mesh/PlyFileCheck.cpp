// The PLY half of io/mesh/MeshFileCheck: the header parsed line by line as
// OpenMesh's PLYReader parses it token by token (so a header both read the
// same way is the only one accepted), then every record OpenMesh will read
// (the elements up to and including "face") walked once: ASCII token by
// token with each value parsed as OpenMesh's streams parse it, binary by
// record sizes with every face's corner list read.
#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <optional>
#include <sstream>
#include <vector>

#include "contours/InputError.hpp"
#include "io/files/FileScanner.hpp"
#include "io/files/InputLimits.hpp"
#include "io/mesh/MeshFileCheck.hpp"

namespace dfrecon {

namespace {

enum class PlyType { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };

std::optional<PlyType> plyType(const std::string& name) {
    static const std::pair<const char*, PlyType> names[] = {
        {"char", PlyType::Int8},      {"int8", PlyType::Int8},       {"uchar", PlyType::UInt8},
        {"uint8", PlyType::UInt8},    {"short", PlyType::Int16},     {"int16", PlyType::Int16},
        {"ushort", PlyType::UInt16},  {"uint16", PlyType::UInt16},   {"int", PlyType::Int32},
        {"int32", PlyType::Int32},    {"uint", PlyType::UInt32},     {"uint32", PlyType::UInt32},
        {"float", PlyType::Float32},  {"float32", PlyType::Float32}, {"double", PlyType::Float64},
        {"float64", PlyType::Float64}};
    for (const auto& [text, type] : names)
        if (name == text) return type;
    return std::nullopt;
}

std::size_t bytesOf(PlyType type) {
    switch (type) {
        case PlyType::Int8:
        case PlyType::UInt8:
            return 1;
        case PlyType::Int16:
        case PlyType::UInt16:
            return 2;
        case PlyType::Int32:
        case PlyType::UInt32:
        case PlyType::Float32:
            return 4;
        case PlyType::Float64:
            return 8;
    }
    return 0;
}

bool isReal(PlyType type) {
    return type == PlyType::Float32 || type == PlyType::Float64;
}

// How OpenMesh's reader takes a property's values.
enum class Target {
    Coordinate,  // vertex x, y, z: a float, within kMaxAbsCoordinateMm
    Real,        // read into a float: normals, texture coordinates, float colours
    Integer,     // read into an int: integer colours
    Skip,        // read as a string (ASCII) or skipped by its size (binary)
    Corners,     // the face's vertex_indices list
};

struct Property {
    std::string name;
    PlyType type = PlyType::Float32;  // of the value, or of a list's items
    PlyType countType = PlyType::UInt8;
    Target target = Target::Skip;
};

enum class Kind { Vertex, Face, Other };

struct Element {
    std::string name;
    Kind kind = Kind::Other;
    std::uint64_t count = 0;
    int line = 0;
    std::vector<Property> properties;
};

enum class Format { Ascii, BinaryLittleEndian, BinaryBigEndian };

struct Header {
    Format format = Format::Ascii;
    std::vector<Element> elements;  // those OpenMesh reads: up to and including "face"
    int lines = 0;                  // header lines, end_header included
    std::uint64_t dataOffset = 0;   // first byte after the end_header line
    std::uint64_t vertices = 0;
};

// The header is read whole into memory; OpenMesh reads headers of any size.
constexpr std::size_t kMaxHeaderBytes = std::size_t(1) << 20;

std::vector<std::string> words(const std::string& line) {
    std::istringstream in(line);
    std::vector<std::string> out;
    for (std::string w; in >> w;) out.push_back(w);
    return out;
}

bool isPlyKeyword(const std::string& w) {
    return w == "comment" || w == "element" || w == "property" || w == "end_header" ||
           w == "format" || w == "obj_info";
}

Target targetOf(Kind kind, const std::string& name) {
    if (kind == Kind::Vertex) {
        if (name == "x" || name == "y" || name == "z") return Target::Coordinate;
        for (const char* n : {"nx", "ny", "nz", "u", "s", "v", "t"})
            if (name == n) return Target::Real;
    }
    if (kind == Kind::Vertex || kind == Kind::Face) {
        for (const char* n : {"red", "green", "blue", "alpha"})
            if (name == n) return Target::Integer;  // Real for float types, below
        if (kind == Kind::Vertex)
            for (const char* n : {"diffuse_red", "diffuse_green", "diffuse_blue"})
                if (name == n) return Target::Integer;
    }
    return Target::Skip;
}

class HeaderParser {
  public:
    explicit HeaderParser(const std::string& path) : path_(path) {}

    Header parse() {
        FileScanner scanner(path_);
        std::string text(std::size_t(std::min<std::uint64_t>(scanner.size(), kMaxHeaderBytes)),
                         '\0');
        scanner.readBytes(text.data(), text.size());
        std::size_t next = 0;
        std::string line;
        if (!nextLine(text, next, line) || (trimmed(line) != "ply" && trimmed(line) != "PLY"))
            fail(1, "not a PLY file (the first line is not 'ply')");
        // OpenMesh reads the first line with getline, then tokens: where the
        // last token ended is where it looks for the binary data.
        std::uint64_t tokenEnd = next;
        bool formatSeen = false;
        for (int lineNumber = 2;; ++lineNumber) {
            const std::size_t lineStart = next;
            if (!nextLine(text, next, line)) {
                if (text.size() == kMaxHeaderBytes)
                    fail(0, "no end_header in the first " + std::to_string(kMaxHeaderBytes) +
                                " bytes");
                fail(0, "the header ends without end_header");
            }
            const std::vector<std::string> w = words(line);
            if (w.empty()) continue;
            const std::size_t lastToken = line.find_last_not_of(" \t\r\v\f");
            const std::uint64_t thisTokenEnd = lineStart + lastToken + 1;
            if (!formatSeen) {
                // OpenMesh takes the three words after "ply" as the format,
                // whatever they are.
                parseFormat(lineNumber, w);
                formatSeen = true;
            } else if (w[0] == "comment") {
                tokenEnd = next;  // OpenMesh takes the rest of the line with getline
                continue;
            } else if (w[0] == "end_header") {
                if (w.size() != 1) fail(lineNumber, "end_header must be alone on its line");
                header_.lines = lineNumber;
                header_.dataOffset = next;
                if (header_.format != Format::Ascii) checkBinaryStart(text, tokenEnd, next);
                finish();
                return header_;
            } else if (w[0] == "element") {
                parseElement(lineNumber, w);
            } else if (w[0] == "property") {
                parseProperty(lineNumber, w);
            } else if (w[0] == "obj_info") {
                // OpenMesh skips it word by word: a keyword among its words
                // would be taken as one.
                for (std::size_t k = 1; k < w.size(); ++k)
                    if (isPlyKeyword(w[k]))
                        fail(lineNumber, "obj_info holds the keyword '" + w[k] + "'");
            } else {
                fail(lineNumber, "unknown header keyword '" + w[0] + "'");
            }
            tokenEnd = thisTokenEnd;
        }
    }

  private:
    [[noreturn]] void fail(int line, const std::string& problem) const {
        throw InputError(path_, line, problem);
    }

    static std::string trimmed(const std::string& s) {
        const std::size_t a = s.find_first_not_of(" \t\r\v\f");
        if (a == std::string::npos) return "";
        return s.substr(a, s.find_last_not_of(" \t\r\v\f") - a + 1);
    }

    // The line at `next` without its '\n'; false when the text has no more
    // complete lines (a header line cut by the end of what was read).
    static bool nextLine(const std::string& text, std::size_t& next, std::string& line) {
        const std::size_t end = text.find('\n', next);
        if (end == std::string::npos) return false;
        line = text.substr(next, end - next);
        next = end + 1;
        return true;
    }

    void parseFormat(int line, const std::vector<std::string>& w) {
        double version = 0;
        if (w[0] != "format" || w.size() != 3 || !parseDecimal(w[2], version))
            fail(line,
                 "the line after 'ply' must be 'format ascii|binary_little_endian|"
                 "binary_big_endian 1.0'");
        if (w[1] == "ascii")
            header_.format = Format::Ascii;
        else if (w[1] == "binary_little_endian")
            header_.format = Format::BinaryLittleEndian;
        else if (w[1] == "binary_big_endian")
            header_.format = Format::BinaryBigEndian;
        else
            fail(line, "unknown PLY format '" + w[1] + "'");
    }

    void parseElement(int line, const std::vector<std::string>& w) {
        std::int64_t count = 0;
        if (w.size() != 3) fail(line, "an element line is 'element NAME COUNT'");
        // OpenMesh reads the count as an unsigned int.
        if (!parseInteger(w[2], count) || count < 0 || count > std::int64_t(UINT32_MAX))
            fail(line, "element " + w[1] + ": count '" + w[2] +
                           "' is not a whole number from 0 to " + std::to_string(UINT32_MAX));
        Element e;
        e.name = w[1];
        e.kind = w[1] == "vertex" ? Kind::Vertex : w[1] == "face" ? Kind::Face : Kind::Other;
        e.count = std::uint64_t(count);
        e.line = line;
        for (const Element& seen : all_)
            if (e.kind != Kind::Other && seen.kind == e.kind)
                fail(line, "a second '" + e.name + "' element");
        if (e.kind == Kind::Face && std::none_of(all_.begin(), all_.end(), [](const Element& s) {
                return s.kind == Kind::Vertex;
            }))
            fail(line, "the face element comes before the vertex element");
        all_.push_back(e);
    }

    void parseProperty(int line, const std::vector<std::string>& w) {
        if (all_.empty()) fail(line, "a property before any element");
        Element& e = all_.back();
        Property p;
        if (w.size() >= 2 && w[1] == "list") {
            if (w.size() != 5) fail(line, "a list property is 'property list COUNTTYPE TYPE NAME'");
            p.name = w[4];
            if (e.kind != Kind::Face || (p.name != "vertex_indices" && p.name != "vertex_index"))
                fail(line, "list property '" + p.name + "' of element '" + e.name +
                               "' is not supported (only the face's vertex_indices)");
            // The count types OpenMesh's reader knows.
            const std::string& c = w[2];
            if (c != "uchar" && c != "uint8" && c != "uint16" && c != "int")
                fail(line, "list count type '" + c +
                               "' is not supported (uchar, uint8, uint16 "
                               "or int)");
            p.countType = *plyType(c);
            const std::optional<PlyType> item = plyType(w[3]);
            if (!item || isReal(*item))
                fail(line, "vertex indices of type '" + w[3] + "'; they must be integers");
            p.type = *item;
            p.target = Target::Corners;
            for (const Property& q : e.properties)
                if (q.target == Target::Corners) fail(line, "a second vertex_indices list");
        } else {
            if (w.size() != 3) fail(line, "a property line is 'property TYPE NAME'");
            // OpenMesh accepts the type and the name in either order.
            std::optional<PlyType> type = plyType(w[1]);
            p.name = w[2];
            if (!type) {
                type = plyType(w[2]);
                p.name = w[1];
            }
            if (!type || plyType(p.name))
                fail(line, "property '" + w[1] + " " + w[2] + "' has no (single) known type");
            p.type = *type;
            p.target = targetOf(e.kind, p.name);
            const bool floatReal = p.type == PlyType::Float32;
            if (p.target == Target::Integer) {
                // OpenMesh reads float colours as floats, all others as
                // integers; a double colour it reads as neither.
                if (p.type == PlyType::Float64)
                    fail(line, "colour property '" + p.name + "' of type double is not supported");
                if (floatReal) p.target = Target::Real;
            }
            if (header_.format != Format::Ascii &&
                (p.target == Target::Coordinate || p.target == Target::Real) && !isReal(p.type))
                fail(line, "binary property '" + p.name + "' must be float or double");
            for (const Property& q : e.properties)
                if (q.name == p.name) fail(line, "property '" + p.name + "' given twice");
        }
        e.properties.push_back(p);
    }

    // OpenMesh finds binary data by seeking to where the token before
    // end_header ended plus 12 bytes ("\nend_header\n"), or 14 after "\r\n".
    // Anything else (spaces before the newline, a comment last) makes it
    // read from the wrong byte.
    void checkBinaryStart(const std::string& text, std::uint64_t tokenEnd, std::uint64_t next) {
        const bool crlf = tokenEnd + 1 < text.size() && text[std::size_t(tokenEnd)] == '\r' &&
                          text[std::size_t(tokenEnd) + 1] == '\n';
        if (tokenEnd + (crlf ? 14 : 12) != next)
            fail(header_.lines,
                 "binary data must follow 'end_header' and one line break directly after the "
                 "previous header line (OpenMesh reads from the wrong byte otherwise)");
    }

    void finish() {
        bool vertex = false;
        for (const Element& e : all_) {
            header_.elements.push_back(e);
            if (e.kind == Kind::Vertex) {
                vertex = true;
                header_.vertices = e.count;
                for (const char* axis : {"x", "y", "z"})
                    if (std::none_of(e.properties.begin(), e.properties.end(),
                                     [&](const Property& p) { return p.name == axis; }))
                        fail(e.line, std::string("the vertex element has no property ") + axis);
            }
            if (e.kind == Kind::Face) {
                if (std::none_of(e.properties.begin(), e.properties.end(),
                                 [](const Property& p) { return p.target == Target::Corners; }))
                    fail(e.line, "the face element has no vertex_indices list");
                break;  // OpenMesh stops reading after the faces
            }
        }
        if (!vertex) fail(0, "no vertex element");
    }

    std::string path_;
    Header header_;
    std::vector<Element> all_;
};

std::string plural(std::uint64_t n, const std::string& what) {
    if (n == 1) return "1 " + what;
    return std::to_string(n) + " " + (what == "vertex" ? "vertices" : what + "s");
}

// The fewest bytes the elements can take: ASCII a digit and a separator per
// value (a face at least "3 a b c"), binary their exact sizes (a face at
// least three corners).
std::uint64_t leastBytes(const Header& h) {
    const bool ascii = h.format == Format::Ascii;
    long double total = 0;
    for (const Element& e : h.elements) {
        std::uint64_t record = 0;
        for (const Property& p : e.properties) {
            if (p.target == Target::Corners)
                record += ascii ? 8 : bytesOf(p.countType) + 3 * bytesOf(p.type);
            else
                record += ascii ? 2 : bytesOf(p.type);
        }
        total += static_cast<long double>(record) * static_cast<long double>(e.count);
    }
    if (ascii && total > 0) total -= 1;  // the last value needs no separator
    return total > static_cast<long double>(UINT64_MAX) ? UINT64_MAX : std::uint64_t(total);
}

void checkCounts(const std::string& path, const Header& h, std::uint64_t dataBytes) {
    const std::uint64_t least = leastBytes(h);
    if (least <= dataBytes) return;
    std::string declared;
    for (const Element& e : h.elements)
        declared += (declared.empty() ? "" : " and ") + plural(e.count, e.name);
    throw InputError(path, 0,
                     "the header declares " + declared + ", which take at least " +
                         std::to_string(least) + " bytes; the file has " +
                         std::to_string(dataBytes) + " after the header");
}

std::string recordName(const Element& e, std::uint64_t index) {
    return e.name + " " + std::to_string(index) + " of " + std::to_string(e.count);
}

void checkAsciiBody(const std::string& path, const Header& h) {
    FileScanner in(path);
    for (int k = 0; k < h.lines; ++k) in.skipLine();
    std::string token;
    for (const Element& e : h.elements) {
        for (std::uint64_t r = 0; r < e.count; ++r) {
            auto next = [&](const std::string& what) {
                if (!in.nextToken(token))
                    in.fail("the file ends in " + recordName(e, r) + " (reading " + what + ")",
                            in.line());
            };
            auto bad = [&](const std::string& problem) {
                in.fail(recordName(e, r) + ": " + problem, in.tokenLine());
            };
            for (const Property& p : e.properties) {
                double real = 0;
                std::int64_t integer = 0;
                switch (p.target) {
                    case Target::Coordinate:
                        next(p.name);
                        if (!parseDecimal(token, real))
                            bad(p.name + " is '" + token + "', not a finite number");
                        if (std::fabs(real) > kMaxAbsCoordinateMm)
                            bad(p.name + " is " + token + ", beyond the limit of ±" +
                                std::to_string(std::int64_t(kMaxAbsCoordinateMm)) + " mm");
                        break;
                    case Target::Real:
                        next(p.name);
                        if (!parseDecimal(token, real) || std::fabs(real) > FLT_MAX)
                            bad(p.name + " is '" + token + "', not a finite float");
                        break;
                    case Target::Integer:
                        next(p.name);
                        if (!parseInteger(token, integer) || integer < INT32_MIN ||
                            integer > INT32_MAX)
                            bad(p.name + " is '" + token + "', not a 32-bit integer");
                        break;
                    case Target::Skip:
                        next(p.name);
                        break;
                    case Target::Corners: {
                        next("its corner count");
                        if (!parseInteger(token, integer) || integer < 3 ||
                            integer > std::int64_t(kMaxMeshFaceCorners))
                            bad("corner count '" + token + "' is not from 3 to " +
                                std::to_string(kMaxMeshFaceCorners));
                        const std::int64_t corners = integer;
                        for (std::int64_t c = 0; c < corners; ++c) {
                            next("corner " + std::to_string(c + 1) + " of " +
                                 std::to_string(corners));
                            if (!parseInteger(token, integer) || integer < 0 ||
                                std::uint64_t(integer) >= h.vertices)
                                bad("corner '" + token + "' is not a vertex (0 to " +
                                    std::to_string(std::int64_t(h.vertices) - 1) + ")");
                        }
                        break;
                    }
                }
            }
        }
    }
}

// A little- or big-endian integer of `type` from `bytes`.
std::int64_t integerAt(const unsigned char* bytes, PlyType type, bool bigEndian) {
    const std::size_t n = bytesOf(type);
    std::uint64_t u = 0;
    for (std::size_t k = 0; k < n; ++k)
        u |= std::uint64_t(bytes[bigEndian ? n - 1 - k : k]) << (8 * k);
    switch (type) {
        case PlyType::Int8:
            return std::int8_t(u);
        case PlyType::Int16:
            return std::int16_t(u);
        case PlyType::Int32:
            return std::int32_t(u);
        default:
            return std::int64_t(u);
    }
}

void checkBinaryBody(const std::string& path, const Header& h) {
    FileScanner in(path);
    in.skipBytes(h.dataOffset);
    const bool big = h.format == Format::BinaryBigEndian;
    std::vector<unsigned char> buffer(kMaxMeshFaceCorners * 8);
    for (const Element& e : h.elements) {
        const bool hasList =
            std::any_of(e.properties.begin(), e.properties.end(),
                        [](const Property& p) { return p.target == Target::Corners; });
        if (!hasList) {
            std::uint64_t record = 0;
            for (const Property& p : e.properties) record += bytesOf(p.type);
            // checkCounts made sure the records fit.
            in.skipBytes(record * e.count);
            continue;
        }
        for (std::uint64_t r = 0; r < e.count; ++r) {
            auto bad = [&](const std::string& problem) {
                in.fail(
                    recordName(e, r) + " (byte " + std::to_string(in.offset()) + "): " + problem,
                    0);
            };
            for (const Property& p : e.properties) {
                if (p.target != Target::Corners) {
                    if (!in.skipBytes(bytesOf(p.type))) bad("the file ends here");
                    continue;
                }
                if (!in.readBytes(buffer.data(), bytesOf(p.countType))) bad("the file ends here");
                const std::int64_t corners = integerAt(buffer.data(), p.countType, big);
                if (corners < 3 || corners > std::int64_t(kMaxMeshFaceCorners))
                    bad("corner count " + std::to_string(corners) + " is not from 3 to " +
                        std::to_string(kMaxMeshFaceCorners));
                const std::size_t size = bytesOf(p.type);
                if (!in.readBytes(buffer.data(), std::size_t(corners) * size))
                    bad("the file ends inside its " + std::to_string(corners) + " corners");
                for (std::int64_t c = 0; c < corners; ++c) {
                    const std::int64_t v = integerAt(buffer.data() + c * size, p.type, big);
                    if (v < 0 || std::uint64_t(v) >= h.vertices)
                        bad("corner " + std::to_string(v) + " is not a vertex (0 to " +
                            std::to_string(std::int64_t(h.vertices) - 1) + ")");
                }
            }
        }
    }
}

}  // namespace

void checkPlyFile(const std::string& path) {
    const Header header = HeaderParser(path).parse();
    std::error_code ec;
    const std::uint64_t size = std::filesystem::file_size(path, ec);
    const std::uint64_t dataBytes = size > header.dataOffset ? size - header.dataOffset : 0;
    checkCounts(path, header, dataBytes);
    if (header.format == Format::Ascii)
        checkAsciiBody(path, header);
    else
        checkBinaryBody(path, header);
}

}  // namespace dfrecon
