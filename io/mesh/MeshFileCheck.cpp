#include "io/mesh/MeshFileCheck.hpp"

#include <cfloat>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <sstream>
#include <vector>

#include "contours/InputError.hpp"
#include "io/files/FileScanner.hpp"
#include "io/files/InputLimits.hpp"
#include "io/mesh/MeshFormat.hpp"

namespace dfrecon {

namespace {

const std::string kLimit = std::to_string(std::int64_t(kMaxAbsCoordinateMm));

// A coordinate as OpenMesh's streams read it into a float, and within the
// limit; "" when it is one, else what is wrong.
std::string coordinateProblem(const std::string& token) {
    double value = 0;
    if (!parseDecimal(token, value)) return "'" + token + "' is not a finite number";
    if (std::fabs(value) > kMaxAbsCoordinateMm)
        return token + " is beyond the limit of ±" + kLimit + " mm";
    return "";
}

// A number OpenMesh's streams read into a float.
bool isFloatNumber(const std::string& token) {
    double value = 0;
    return parseDecimal(token, value) && std::fabs(value) <= FLT_MAX;
}

// ---- OFF (OpenMesh's OFFReader) ----------------------------------------------
//
// The first line is [ST][C][N]OFF [BINARY]; OpenMesh reads it with getline
// and the counts with >> after it. ASCII: each vertex is 3 numbers (6 with
// N) then the rest of its line (colours, texture coordinates: parsed apart);
// each face a corner count and the corners, then, with C, the rest of its
// line. Binary ("OFF BINARY", no prefix): little-endian uint32 counts, 3
// floats per vertex, a uint32 corner count and corners per face.

struct OffHeader {
    bool normals = false, colours = false, binary = false, prefixed = false;
};

OffHeader parseOffLine(const std::string& path, std::string line) {
    while (!line.empty() && std::isspace(static_cast<unsigned char>(line.back()))) line.pop_back();
    OffHeader h;
    std::size_t p = 0;
    if (line.compare(p, 2, "ST") == 0) p += 2, h.prefixed = true;
    if (line.compare(p, 1, "C") == 0) ++p, h.colours = true, h.prefixed = true;
    if (line.compare(p, 1, "N") == 0) ++p, h.normals = true, h.prefixed = true;
    if (line.compare(p, 3, "OFF") != 0)
        throw InputError(path, 1,
                         "not an OFF file OpenMesh reads (the first line is not "
                         "[ST][C][N]OFF [BINARY])");
    const std::string rest = line.substr(p + 3);
    if (rest == " BINARY") {
        h.binary = true;
    } else if (!rest.empty()) {
        throw InputError(path, 1,
                         "the first line must hold only the OFF keyword (OpenMesh skips anything "
                         "after it, counts included; put the counts on the next line)");
    }
    if (h.binary && h.prefixed)
        throw InputError(path, 1,
                         "binary OFF with normals, colours or texture coordinates is not "
                         "supported");
    return h;
}

/// An OFF header's counts and the fewest bytes each vertex and face takes
/// in its encoding.
struct OffCounts {
    std::uint64_t vertices = 0, faces = 0;
    std::uint64_t vertexBytes = 0, faceBytes = 0;
};

/// Throws InputError (at `line` of `path`) when the counts cannot fit in the
/// `bytes` left after them: a header declaring billions of vertices is
/// refused before anything is allocated for them.
void checkOffCounts(const std::string& path, const OffCounts& counts, std::uint64_t bytes,
                    int line) {
    const std::uint64_t vertices = counts.vertices, faces = counts.faces;
    const std::uint64_t vertexBytes = counts.vertexBytes, faceBytes = counts.faceBytes;
    const long double least = static_cast<long double>(vertices) * vertexBytes +
                              static_cast<long double>(faces) * faceBytes;
    if (least > static_cast<long double>(bytes))
        throw InputError(path, line,
                         "the header declares " + std::to_string(vertices) + " vertices and " +
                             std::to_string(faces) + (faces == 1 ? " face" : " faces") +
                             ", which take at least " +
                             std::to_string(std::uint64_t(std::min<long double>(least, 1e19L))) +
                             " bytes; the file has " + std::to_string(bytes) + " after the counts");
}

void checkAsciiOff(FileScanner& in, const OffHeader& h) {
    std::string token;
    std::uint64_t counts[3] = {0, 0, 0};
    const char* names[3] = {"vertex", "face", "edge"};
    for (int k = 0; k < 3; ++k) {
        std::int64_t value = 0;
        if (!in.nextToken(token)) in.fail("the file ends before the counts", in.line());
        if (token[0] == '#')
            in.fail("comments are not supported in OFF files (OpenMesh reads them as numbers)",
                    in.tokenLine());
        if (!parseInteger(token, value) || value < 0 || value > std::int64_t(UINT32_MAX))
            in.fail(std::string(names[k]) + " count '" + token +
                        "' is not a whole number from 0 "
                        "to " +
                        std::to_string(UINT32_MAX),
                    in.tokenLine());
        counts[k] = std::uint64_t(value);
    }
    const std::uint64_t vertices = counts[0], faces = counts[1];
    checkOffCounts(in.path(), {vertices, faces, h.normals ? 12u : 6u, 8}, in.remaining(),
                   in.line());
    for (std::uint64_t v = 0; v < vertices; ++v) {
        for (int c = 0; c < (h.normals ? 6 : 3); ++c) {
            if (!in.nextToken(token))
                in.fail("the file ends in vertex " + std::to_string(v) + " of " +
                            std::to_string(vertices),
                        in.line());
            const std::string problem =
                c < 3 ? coordinateProblem(token)
                      : (isFloatNumber(token) ? "" : "'" + token + "' is not a finite float");
            if (!problem.empty())
                in.fail("vertex " + std::to_string(v) + ": " + problem, in.tokenLine());
        }
        in.skipLine();
    }
    for (std::uint64_t f = 0; f < faces; ++f) {
        const std::string face = "face " + std::to_string(f) + " of " + std::to_string(faces);
        std::int64_t corners = 0, corner = 0;
        if (!in.nextToken(token)) in.fail("the file ends before " + face, in.line());
        if (!parseInteger(token, corners) || corners < 3 ||
            corners > std::int64_t(kMaxMeshFaceCorners))
            in.fail(face + ": corner count '" + token + "' is not from 3 to " +
                        std::to_string(kMaxMeshFaceCorners),
                    in.tokenLine());
        for (std::int64_t c = 0; c < corners; ++c) {
            if (!in.nextToken(token))
                in.fail(
                    "the file ends inside " + face + " (" + std::to_string(corners) + " corners)",
                    in.line());
            if (!parseInteger(token, corner) || corner < 0 || std::uint64_t(corner) >= vertices)
                in.fail(face + ": corner '" + token + "' is not a vertex (0 to " +
                            std::to_string(std::int64_t(vertices) - 1) + ")",
                        in.tokenLine());
        }
        if (h.colours) in.skipLine();
    }
}

std::uint32_t littleEndian32(const unsigned char* b) {
    return std::uint32_t(b[0]) | std::uint32_t(b[1]) << 8 | std::uint32_t(b[2]) << 16 |
           std::uint32_t(b[3]) << 24;
}

void checkBinaryOff(FileScanner& in) {
    unsigned char bytes[12];
    if (!in.readBytes(bytes, 12)) in.fail("the file ends before the counts", 0);
    const std::uint64_t vertices = littleEndian32(bytes), faces = littleEndian32(bytes + 4);
    checkOffCounts(in.path(), {vertices, faces, 12, 16}, in.remaining(), 0);
    for (std::uint64_t v = 0; v < vertices; ++v) {
        float xyz[3];
        in.readBytes(bytes, 12);
        std::memcpy(xyz, bytes, 12);
        for (float c : xyz)
            if (!std::isfinite(c) || std::fabs(c) > kMaxAbsCoordinateMm)
                in.fail("vertex " + std::to_string(v) +
                            " has a coordinate that is not finite or "
                            "beyond ±" +
                            kLimit + " mm",
                        0);
    }
    std::vector<unsigned char> corners(4 * kMaxMeshFaceCorners);
    for (std::uint64_t f = 0; f < faces; ++f) {
        const std::string face = "face " + std::to_string(f) + " of " + std::to_string(faces);
        if (!in.readBytes(bytes, 4)) in.fail("the file ends before " + face, 0);
        const std::uint32_t n = littleEndian32(bytes);
        if (n < 3 || n > kMaxMeshFaceCorners)
            in.fail(face + ": corner count " + std::to_string(n) + " is not from 3 to " +
                        std::to_string(kMaxMeshFaceCorners),
                    0);
        if (!in.readBytes(corners.data(), 4 * std::size_t(n)))
            in.fail("the file ends inside " + face, 0);
        for (std::uint32_t c = 0; c < n; ++c)
            if (littleEndian32(corners.data() + 4 * c) >= vertices)
                in.fail(face + ": corner " +
                            std::to_string(littleEndian32(corners.data() + 4 * c)) +
                            " is not a vertex",
                        0);
    }
}

void checkOffFile(const std::string& path) {
    FileScanner in(path);
    std::string first;
    if (!in.readLine(first, FileScanner::kMaxTokenBytes)) in.fail("empty file", 0);
    const OffHeader h = parseOffLine(path, first);
    if (h.binary)
        checkBinaryOff(in);
    else
        checkAsciiOff(in, h);
}

// ---- OBJ (OpenMesh's OBJReader) ----------------------------------------------
//
// Line by line. OpenMesh drops a "v" line whose numbers do not parse (every
// later face then points at the wrong vertex), reads the material library a
// "mtllib" line names whatever it is (a FIFO blocks, /dev/zero never ends a
// line), and takes any integer as a corner.

std::vector<std::string> wordsOf(const std::string& line) {
    std::istringstream in(line);
    std::vector<std::string> out;
    for (std::string w; in >> w;) out.push_back(w);
    return out;
}

void checkObjFile(const std::string& path) {
    FileScanner in(path);
    std::string line;
    std::uint64_t vertices = 0, highest = 0;
    int highestLine = 0;
    const std::size_t maxLine = std::size_t(1) << 20;
    while (true) {
        const int number = in.line();
        if (!in.readLine(line, maxLine)) break;
        const std::vector<std::string> w = wordsOf(line);
        if (w.empty() || w[0][0] == '#') continue;
        auto fail = [&](const std::string& problem) { in.fail(problem, number); };
        if (w[0] == "v") {
            if (w.size() < 4) fail("a vertex needs x, y and z");
            for (int c = 1; c <= 3; ++c) {
                const std::string problem = coordinateProblem(w[std::size_t(c)]);
                if (!problem.empty()) fail("vertex " + std::to_string(vertices) + ": " + problem);
            }
            ++vertices;
        } else if (w[0] == "f") {
            std::size_t corners = 0;
            for (std::size_t k = 1; k < w.size() && w[k][0] != '#'; ++k) {
                const std::string index = w[k].substr(0, w[k].find('/'));
                std::int64_t value = 0;
                if (!parseInteger(index, value) || value == 0)
                    fail("face corner '" + w[k] + "' does not start with a vertex number");
                // Negative numbers count back from the last vertex so far.
                if (value < 0 && std::uint64_t(-value) > vertices)
                    fail("face corner " + index + " reaches before the first vertex");
                if (value > 0 && std::uint64_t(value) > highest) {
                    highest = std::uint64_t(value);
                    highestLine = number;
                }
                ++corners;
            }
            if (corners < 3 || corners > kMaxMeshFaceCorners)
                fail("a face has " + std::to_string(corners) + " corners, not 3 to " +
                     std::to_string(kMaxMeshFaceCorners));
        } else if (w[0] == "mtllib") {
            // OpenMesh opens the folder of the file plus the rest of the line.
            std::string name = line.substr(line.find("mtllib") + 6);
            name.erase(0, name.find_first_not_of(" \t\r"));
            name.erase(name.find_last_not_of(" \t\r") + 1);
            const std::string slash =
                path.rfind('/') == std::string::npos ? "./" : path.substr(0, path.rfind('/') + 1);
            std::error_code ec;
            const std::filesystem::path library(slash + name);
            if (std::filesystem::exists(library, ec) &&
                !std::filesystem::is_regular_file(library, ec))
                fail("material library '" + name + "' is not a regular file");
        }
    }
    if (highest > vertices)
        in.fail("a face refers to vertex " + std::to_string(highest) + " of " +
                    std::to_string(vertices),
                highestLine);
}

// ---- STL (OpenMesh's STLReader) ----------------------------------------------
//
// Binary when the size is exactly 84 + 50 per triangle counted at byte 80,
// else ASCII: every line holding "outer" is followed by three vertex lines
// read as a word and three numbers (a number that does not parse leaves 0,
// or the largest float, silently).

void checkBinaryStl(FileScanner& in, std::uint32_t triangles) {
    in.skipBytes(84);
    unsigned char record[50];
    for (std::uint32_t t = 0; t < triangles; ++t) {
        in.readBytes(record, 50);
        for (int c = 3; c < 12; ++c) {
            float value;
            std::memcpy(&value, record + 4 * c, 4);
            if (!std::isfinite(value) || std::fabs(value) > kMaxAbsCoordinateMm)
                in.fail("triangle " + std::to_string(t) +
                            " has a coordinate that is not finite "
                            "or beyond ±" +
                            kLimit + " mm",
                        0);
        }
    }
}

void checkAsciiStl(FileScanner& in) {
    std::string line;
    const std::size_t maxLine = std::size_t(1) << 20;
    while (in.readLine(line, maxLine)) {
        if (line.find("outer") == std::string::npos && line.find("OUTER") == std::string::npos)
            continue;
        for (int corner = 0; corner < 3; ++corner) {
            const int number = in.line();
            if (!in.readLine(line, maxLine)) in.fail("the file ends inside a facet", number);
            const std::vector<std::string> w = wordsOf(line);
            if (w.size() < 4) in.fail("a vertex line needs 'vertex x y z'", number);
            for (int c = 1; c <= 3; ++c) {
                const std::string problem = coordinateProblem(w[std::size_t(c)]);
                if (!problem.empty()) in.fail("vertex " + problem, number);
            }
        }
    }
}

void checkStlFile(const std::string& path) {
    FileScanner in(path);
    unsigned char head[84] = {};
    const std::size_t headBytes = std::size_t(std::min<std::uint64_t>(in.size(), 84));
    FileScanner(path).readBytes(head, headBytes);
    std::string binary = "shorter than its 84-byte header";
    if (headBytes == 84) {
        const std::uint32_t triangles = littleEndian32(head + 80);
        const std::uint64_t size = 84 + 50 * std::uint64_t(triangles);
        if (size == in.size()) return checkBinaryStl(in, triangles);
        binary = std::to_string(triangles) + " triangles take " + std::to_string(size) +
                 " bytes, the file has " + std::to_string(in.size());
    }
    const std::string text(reinterpret_cast<const char*>(head), headBytes);
    const std::size_t start = text.find_first_not_of(" \t\r\n");
    if (start == std::string::npos || text.compare(start, 5, "solid") != 0)
        in.fail("neither an ASCII STL (no 'solid' at the start) nor a binary one (" + binary + ")",
                0);
    checkAsciiStl(in);
}

}  // namespace

void checkMeshFileBeforeReading(const std::string& path) {
    const std::string ext = lowerExtension(path);
    if (ext == ".ply")
        checkPlyFile(path);
    else if (ext == ".off")
        checkOffFile(path);
    else if (ext == ".obj")
        checkObjFile(path);
    else if (ext == ".stl")
        checkStlFile(path);
}

void requireSanePoint(const std::string& path, std::size_t vertex, const Vec3& p) {
    for (int a = 0; a < 3; ++a) {
        if (std::isfinite(p[a]) && std::fabs(p[a]) <= kMaxAbsCoordinateMm) continue;
        std::ostringstream s;
        s.precision(17);
        s << "vertex " << vertex << " has coordinate " << p[a] << ", "
          << (std::isfinite(p[a]) ? "beyond the limit of ±" + kLimit + " mm" : "not finite");
        throw InputError(path, 0, s.str());
    }
}

}  // namespace dfrecon
