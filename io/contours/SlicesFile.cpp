#include "io/contours/SlicesFile.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <istream>
#include <ostream>
#include <sstream>

#include "geometry/ContourValidation.hpp"
#include "geometry/PlaneReading.hpp"
#include "geometry/PolygonXor.hpp"
#include "io/files/AtomicWrite.hpp"
#include "io/files/InputLimits.hpp"
#include "io/files/InputsInUse.hpp"
#include "io/files/RegularFile.hpp"
#include "io/files/TextEncoding.hpp"

namespace dfrecon {

namespace {

// A contour as read, with the line of each point so later checks can point
// at the file.
struct SlicesContour {
    int keywordLine = 0;
    Polygon points;
    std::vector<int> pointLines;
};
struct SourceSlice {
    double zMm = 0;
    int line = 0;
    std::vector<SlicesContour> contours;
};
struct SourceRoi {
    Roi roi;  // name and colour; slices are filled from `slices` at the end
    int line = 0;
    std::vector<SourceSlice> slices;
};

// Splits one line into tokens: whitespace separated, "double quoted" tokens
// may hold spaces and '#', and '#' elsewhere starts a comment.
struct Tokenizer {
    std::vector<std::string> tokens;
    std::vector<bool> quoted;

    // Returns an error message, or empty on success.
    std::string split(const std::string& line) {
        tokens.clear();
        quoted.clear();
        std::size_t i = 0;
        while (i < line.size()) {
            const char c = line[i];
            if (c == '#') break;
            if (c == ' ' || c == '\t' || c == '\r') {
                ++i;
                continue;
            }
            if (c == '"') {
                // "" inside quotes is one quote: GTV "left" is "GTV ""left""".
                std::string token;
                std::size_t close = line.find('"', i + 1);
                for (std::size_t from = i + 1;; close = line.find('"', from)) {
                    if (close == std::string::npos) return "unterminated quoted name";
                    token.append(line, from, close - from);
                    if (close + 1 >= line.size() || line[close + 1] != '"') break;
                    token += '"';
                    from = close + 2;
                }
                tokens.push_back(std::move(token));
                quoted.push_back(true);
                i = close + 1;
                continue;
            }
            std::size_t j = i;
            while (j < line.size() && line[j] != ' ' && line[j] != '\t' && line[j] != '\r' &&
                   line[j] != '#' && line[j] != '"')
                ++j;
            tokens.push_back(line.substr(i, j - i));
            quoted.push_back(false);
            i = j;
        }
        for (const std::string& t : tokens)
            for (char ch : t)
                if (static_cast<unsigned char>(ch) < 0x20 && ch != '\t')
                    return "control character in line";
        return {};
    }
};

bool isSlicesKeyword(const std::string& token) {
    return token == "roi" || token == "slice" || token == "contour" || token == "units" ||
           token == "dfrecon-slices";
}

bool looksNumeric(const std::string& token) {
    const char c = token.empty() ? ' ' : token[0];
    return (c >= '0' && c <= '9') || c == '-' || c == '+' || c == '.';
}

class Parser {
  public:
    Parser(std::istream& in, std::string fileName, const SlicesLimits& limits,
           const SlicesProgress& progress)
        : in_(in), file_(std::move(fileName)), limits_(limits), progress_(progress) {}

    SlicesLoad run() {
        readAll();
        SlicesLoad result;
        for (SourceRoi& source : rois_) {
            // A geometric defect (a crossing, too few points) is one ROI's:
            // the file's other ROIs still load, as from a clinical export.
            Roi header = source.roi;
            finishing_ = source.roi.name;
            try {
                result.contours.rois.push_back(finish(source));
            } catch (const InputError& e) {
                header.slices.clear();
                header.defect = e;
                result.contours.rois.push_back(std::move(header));
            }
        }
        result.warnings = std::move(warnings_);
        return result;
    }

  private:
    [[noreturn]] void fail(int line, const std::string& problem) const {
        throw InputError(file_, line, problem);
    }
    // Warnings made while an ROI is finished carry its name (InputWarning::roi).
    void warn(int line, const std::string& message) {
        warnings_.push_back({file_, line, message, finishing_});
    }

    // Reads one line with a hard length limit; false at end of input. Reads
    // the stream in chunks: per-character istream calls would dominate.
    bool nextLine(std::string& line) {
        line.clear();
        bool any = false;
        for (;;) {
            if (chunkPos_ == chunk_.size()) {
                chunk_.resize(kChunkBytes);
                in_.read(chunk_.data(), std::streamsize(chunk_.size()));
                chunk_.resize(std::size_t(in_.gcount()));
                chunkPos_ = 0;
                bytesRead_ += chunk_.size();
                if (bytesRead_ > limits_.maxBytes)
                    fail(lineNo_ + 1, "more than " + std::to_string(limits_.maxBytes >> 20) +
                                          " MiB of text, the limit of a .slices file");
                if (progress_) progress_(bytesRead_);
                if (chunk_.empty()) break;
            }
            any = true;
            const char* begin = chunk_.data() + chunkPos_;
            const char* end = chunk_.data() + chunk_.size();
            const char* newline = std::find(begin, end, '\n');
            if (line.size() + std::size_t(newline - begin) > limits_.maxLineBytes)
                fail(lineNo_ + 1,
                     "line longer than " + std::to_string(limits_.maxLineBytes) + " bytes");
            line.append(begin, newline);
            chunkPos_ += std::size_t(newline - begin);
            if (newline != end) {
                ++chunkPos_;  // past the newline
                break;
            }
        }
        if (!any) return false;
        ++lineNo_;
        if (line.find('\0') != std::string::npos) fail(lineNo_, "NUL byte in text file");
        // A name typed on Windows may be Latin-1: each line made UTF-8.
        line = utf8FromLegacyText(line);
        return true;
    }

    double number(const std::string& token, const char* what) const {
        const char* begin = token.data();
        const char* end = token.data() + token.size();
        if (begin != end && *begin == '+') ++begin;
        double value = 0;
        const auto [ptr, ec] = std::from_chars(begin, end, value);
        if (ec == std::errc::result_out_of_range)
            fail(lineNo_, std::string(what) + " '" + token + "' is out of range");
        if (ec != std::errc() || ptr != end || begin == end)
            fail(lineNo_, std::string(what) + ": '" + token + "' is not a number");
        if (!std::isfinite(value))
            fail(lineNo_, std::string(what) + " is NaN or Inf ('" + token + "')");
        if (std::abs(value) > limits_.maxAbsCoordinateMm)
            fail(lineNo_, std::string(what) + " " + token + " exceeds the limit of " +
                              std::to_string(int64_t(limits_.maxAbsCoordinateMm)) + " mm");
        return value;
    }

    long long integer(const std::string& token, const char* what, long long lo,
                      long long hi) const {
        long long value = 0;
        const auto [ptr, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
        if (ec != std::errc() || ptr != token.data() + token.size() || token.empty())
            fail(lineNo_, std::string(what) + ": '" + token + "' is not an integer");
        if (value < lo || value > hi)
            fail(lineNo_, std::string(what) + " " + token + " outside " + std::to_string(lo) +
                              ".." + std::to_string(hi));
        return value;
    }

    void expectTokens(std::size_t count, const std::string& usage) const {
        if (tok_.tokens.size() != count) fail(lineNo_, "expected '" + usage + "'");
    }

    void readAll() {
        std::string line;
        enum class Stage { Header, Units, Body } stage = Stage::Header;
        while (nextLine(line)) {
            if (const std::string err = tok_.split(line); !err.empty()) fail(lineNo_, err);
            if (tok_.tokens.empty()) continue;
            const std::string& key = tok_.tokens[0];

            if (pendingPoints_ > 0) {
                if (isSlicesKeyword(key) && !tok_.quoted[0]) contourCountMismatch();
                readPoint();
                continue;
            }
            if (stage == Stage::Header) {
                if (key != "dfrecon-slices")
                    fail(lineNo_,
                         "bad header: expected 'dfrecon-slices 1' as the first line, got '" + key +
                             "'");
                expectTokens(2, "dfrecon-slices 1");
                if (tok_.tokens[1] != "1")
                    fail(lineNo_, "unsupported version '" + tok_.tokens[1] +
                                      "' (this build reads version 1)");
                stage = Stage::Units;
            } else if (stage == Stage::Units) {
                if (key != "units") fail(lineNo_, "expected 'units mm' after the header");
                expectTokens(2, "units mm");
                if (tok_.tokens[1] != "mm")
                    fail(lineNo_, "unsupported units '" + tok_.tokens[1] + "' (only mm)");
                stage = Stage::Body;
            } else if (key == "roi" && !tok_.quoted[0]) {
                readRoi();
            } else if (key == "slice" && !tok_.quoted[0]) {
                readSlice();
            } else if (key == "contour" && !tok_.quoted[0]) {
                readContourHeader();
            } else if (key == "units" || key == "dfrecon-slices") {
                fail(lineNo_, "'" + key + "' may appear only once, at the top");
            } else if (looksNumeric(key) && !rois_.empty() && !rois_.back().slices.empty() &&
                       !rois_.back().slices.back().contours.empty()) {
                const SlicesContour& c = rois_.back().slices.back().contours.back();
                fail(lineNo_, "contour at line " + std::to_string(c.keywordLine) + " declares " +
                                  std::to_string(c.points.size()) +
                                  " points but more follow (point count does not match)");
            } else {
                fail(lineNo_, "unknown keyword '" + key + "'");
            }
        }
        if (stage == Stage::Header) fail(lineNo_, "empty file: expected header 'dfrecon-slices 1'");
        if (stage == Stage::Units) fail(lineNo_, "missing 'units mm' line");
        if (pendingPoints_ > 0) contourCountMismatch();
    }

    [[noreturn]] void contourCountMismatch() const {
        const SlicesContour& c = rois_.back().slices.back().contours.back();
        fail(c.keywordLine, "contour declares " + std::to_string(c.points.size() + pendingPoints_) +
                                " points but " + std::to_string(c.points.size()) +
                                " follow (point count does not match)");
    }

    void readRoi() {
        if (tok_.tokens.size() != 2 && tok_.tokens.size() != 5)
            fail(lineNo_, "expected 'roi NAME' or 'roi NAME R G B'");
        if (rois_.size() >= limits_.maxRois)
            fail(lineNo_, "more than " + std::to_string(limits_.maxRois) + " ROIs");
        SourceRoi source;
        source.line = lineNo_;
        source.roi.name = tok_.tokens[1];
        if (source.roi.name.empty()) fail(lineNo_, "empty ROI name");
        if (source.roi.name.size() > kMaxRoiNameBytes)
            fail(lineNo_, "an ROI name of " + std::to_string(source.roi.name.size()) +
                              " bytes, over the " + std::to_string(kMaxRoiNameBytes) +
                              " a name may have");
        for (const SourceRoi& other : rois_)
            if (other.roi.name == source.roi.name)
                fail(lineNo_, "duplicate ROI name '" + source.roi.name + "' (first at line " +
                                  std::to_string(other.line) + ")");
        if (tok_.tokens.size() == 5)
            source.roi.colour = Rgb{std::uint8_t(integer(tok_.tokens[2], "red", 0, 255)),
                                    std::uint8_t(integer(tok_.tokens[3], "green", 0, 255)),
                                    std::uint8_t(integer(tok_.tokens[4], "blue", 0, 255))};
        rois_.push_back(std::move(source));
    }

    void readSlice() {
        if (rois_.empty()) fail(lineNo_, "'slice' before any 'roi'");
        expectTokens(2, "slice Z");
        SourceRoi& roi = rois_.back();
        if (roi.slices.size() >= limits_.maxSlicesPerRoi)
            fail(lineNo_, "more than " + std::to_string(limits_.maxSlicesPerRoi) +
                              " slices in ROI '" + roi.roi.name + "'");
        roi.slices.push_back({number(tok_.tokens[1], "slice z"), lineNo_, {}});
    }

    void readContourHeader() {
        if (rois_.empty() || rois_.back().slices.empty())
            fail(lineNo_, "'contour' before any 'slice'");
        expectTokens(2, "contour N");
        SourceSlice& slice = rois_.back().slices.back();
        if (slice.contours.size() >= limits_.maxContoursPerSlice)
            fail(lineNo_, "more than " + std::to_string(limits_.maxContoursPerSlice) +
                              " contours on one slice");
        const long long count = integer(tok_.tokens[1], "point count", 1,
                                        static_cast<long long>(limits_.maxPointsPerContour));
        if (totalPoints_ + std::size_t(count) > limits_.maxPointsTotal)
            fail(lineNo_,
                 "file holds more than " + std::to_string(limits_.maxPointsTotal) + " points");
        SlicesContour contour;
        contour.keywordLine = lineNo_;
        slice.contours.push_back(std::move(contour));
        pendingPoints_ = std::size_t(count);
        totalPoints_ += pendingPoints_;
    }

    void readPoint() {
        if (tok_.tokens.size() != 2)
            fail(lineNo_,
                 "expected a point 'x y', got " + std::to_string(tok_.tokens.size()) + " tokens");
        SlicesContour& c = rois_.back().slices.back().contours.back();
        c.points.push_back({number(tok_.tokens[0], "x"), number(tok_.tokens[1], "y")});
        c.pointLines.push_back(lineNo_);
        --pendingPoints_;
    }

    // ---- repair, validation and orientation of one ROI ----------------------

    Roi finish(SourceRoi& source) {
        std::vector<SourceSlice>& slices = source.slices;
        const std::string name = source.roi.name;

        std::size_t repeated = 0;
        for (SourceSlice& slice : slices)
            for (SlicesContour& c : slice.contours) repeated += dropRepeatedPoints(c);

        if (!std::is_sorted(
                slices.begin(), slices.end(),
                [](const SourceSlice& a, const SourceSlice& b) { return a.zMm < b.zMm; })) {
            warn(source.line, "slices of ROI '" + name + "' are not in increasing z; sorted");
            std::stable_sort(
                slices.begin(), slices.end(),
                [](const SourceSlice& a, const SourceSlice& b) { return a.zMm < b.zMm; });
        }
        mergeDuplicateZ(slices, name);

        Roi roi = std::move(source.roi);
        roi.reading.repeatedPoints += repeated;
        for (SourceSlice& slice : slices) {
            if (slice.contours.empty()) {
                warn(slice.line, "slice z=" + formatNumber(slice.zMm) + " of ROI '" + name +
                                     "' has no contours; ignored");
                continue;
            }
            readPlane(slice, name, roi.reading);
            validate(slice, name);
            Slice out;
            out.zMm = slice.zMm;
            for (SlicesContour& c : slice.contours) out.contours.push_back(std::move(c.points));
            // Every contour of the plane had no area, or cancelled another.
            if (out.contours.empty()) continue;
            normaliseOrientation(out);
            roi.slices.push_back(std::move(out));
        }
        if (roi.reading.changedShape())
            warn(source.line,
                 "ROI '" + name + "' read as planning systems read it: " + roi.reading.summary());
        return roi;
    }

    // Returns how many points were dropped (the ROI's reading counts them).
    std::size_t dropRepeatedPoints(SlicesContour& c) {
        std::size_t kept = 0;
        for (std::size_t i = 0; i < c.points.size(); ++i) {
            if (kept > 0 && c.points[i] == c.points[kept - 1]) continue;
            c.points[kept] = c.points[i];
            c.pointLines[kept] = c.pointLines[i];
            ++kept;
        }
        // The polygon closes itself, so a last point equal to the first repeats it.
        while (kept > 1 && c.points[kept - 1] == c.points[0]) --kept;
        const std::size_t dropped = c.points.size() - kept;
        c.points.resize(kept);
        c.pointLines.resize(kept);
        if (dropped > 0)
            warn(c.keywordLine,
                 "dropped " + std::to_string(dropped) + " repeated consecutive point(s)");
        return dropped;
    }

    void mergeDuplicateZ(std::vector<SourceSlice>& slices, const std::string& name) {
        std::vector<SourceSlice> merged;
        for (SourceSlice& slice : slices) {
            if (!merged.empty() && std::abs(slice.zMm - merged.back().zMm) <= kSameZToleranceMm) {
                warn(slice.line, "ROI '" + name + "' has slice z=" + formatNumber(slice.zMm) +
                                     " twice (also line " + std::to_string(merged.back().line) +
                                     "); contours merged");
                for (SlicesContour& c : slice.contours)
                    merged.back().contours.push_back(std::move(c));
                continue;
            }
            merged.push_back(std::move(slice));
        }
        slices = std::move(merged);
    }

    // The plane read as planning systems read it (geometry/PlaneReading):
    // contours kept whole keep their lines; those of a filled region, or
    // with points dropped, carry their contour's line (or the slice's).
    void readPlane(SourceSlice& slice, const std::string& name, PlaneReadingCounts& counts) {
        std::vector<Polygon> drawn;
        for (const SlicesContour& c : slice.contours) drawn.push_back(c.points);
        PlaneReading reading;
        try {
            reading = readPlaneContours(std::move(drawn), kMaxXorCrossingsPerPlane);
        } catch (const TooManyCrossings& e) {
            fail(slice.line,
                 "slice z=" + formatNumber(slice.zMm) + " of ROI '" + name + "': " + e.what());
        }
        counts += reading.counts;
        std::vector<SlicesContour> out;
        for (std::size_t k = 0; k < reading.contours.size(); ++k) {
            const std::size_t source = reading.sourceOf[k];
            Polygon& points = reading.contours[k];
            if (source != kResolvedContour && points == slice.contours[source].points) {
                out.push_back(std::move(slice.contours[source]));
                continue;
            }
            const int line =
                source == kResolvedContour ? slice.line : slice.contours[source].keywordLine;
            out.push_back({line, std::move(points), std::vector<int>(points.size(), line)});
        }
        slice.contours = std::move(out);
    }

    void validate(const SourceSlice& slice, const std::string& name) const {
        std::vector<Polygon> polygons;
        for (const SlicesContour& c : slice.contours) polygons.push_back(c.points);
        const std::optional<ContourDefect> defect = findContourDefect(polygons);
        if (!defect) return;
        if (defect->kind == ContourDefect::Kind::TooComplex)
            fail(slice.line, "slice z=" + formatNumber(slice.zMm) +
                                 " is too complex to validate (pathological segment layout)");
        const SlicesContour& a = slice.contours[defect->contourA];
        const SlicesContour& b = slice.contours[defect->contourB];
        const std::string segA = describeSegment(a, defect->segmentA);
        const std::string segB = describeSegment(b, defect->segmentB);
        const std::string how = defect->contact == SegmentContact::Overlap ? " overlaps "
                                : defect->contact == SegmentContact::Touch ? " touches "
                                                                           : " crosses ";
        const int line = a.pointLines[defect->segmentA];
        if (defect->kind == ContourDefect::Kind::SelfIntersection)
            fail(line, "self-intersecting contour (line " + std::to_string(a.keywordLine) +
                           "): " + segA + how + segB);
        fail(line, "contours of ROI '" + name + "' cross on slice z=" + formatNumber(slice.zMm) +
                       ": contour at line " + std::to_string(a.keywordLine) + " " + segA + how +
                       "contour at line " + std::to_string(b.keywordLine) + " " + segB);
    }

    static std::string describeSegment(const SlicesContour& c, std::size_t k) {
        const std::size_t next = (k + 1) % c.points.size();
        return "segment " + std::to_string(k + 1) + " (lines " + std::to_string(c.pointLines[k]) +
               "-" + std::to_string(c.pointLines[next]) + ")";
    }

    static std::string formatNumber(double v) {
        std::ostringstream s;
        s << v;
        return s.str();
    }

    static constexpr double kSameZToleranceMm = 1e-6;
    static constexpr std::size_t kChunkBytes = 1 << 16;

    std::istream& in_;
    std::string file_;
    SlicesLimits limits_;
    SlicesProgress progress_;
    std::vector<char> chunk_;
    std::size_t chunkPos_ = 0;
    std::uint64_t bytesRead_ = 0;
    Tokenizer tok_;
    int lineNo_ = 0;
    std::size_t pendingPoints_ = 0;
    std::size_t totalPoints_ = 0;
    std::vector<SourceRoi> rois_;
    std::vector<InputWarning> warnings_;
    std::string finishing_;  // the ROI being finished, for its warnings
};

// Shortest text that parses back to exactly `v`.
std::string exactNumber(double v) {
    char buffer[32];
    const auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, v);
    (void)ec;  // 32 bytes always fit a double's shortest form
    return std::string(buffer, end);
}

std::string quotedName(const std::string& name) {
    if (name.empty()) throw std::invalid_argument("ROI name is empty");
    bool needsQuotes = false;
    std::string quoted;
    for (char c : name) {
        if (c == '\n' || (static_cast<unsigned char>(c) < 0x20 && c != '\t'))
            throw std::invalid_argument("ROI name '" + name + "' holds a control character");
        if (c == ' ' || c == '\t' || c == '#' || c == '"') needsQuotes = true;
        quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
    }
    if (isSlicesKeyword(name)) needsQuotes = true;
    return needsQuotes ? "\"" + quoted + "\"" : name;
}

}  // namespace

SlicesLoad parseSlices(std::istream& in, const std::string& fileName, const SlicesLimits& limits,
                       const SlicesProgress& progress) {
    return Parser(in, fileName, limits, progress).run();
}

SlicesLoad readSlicesFile(const std::string& path, const SlicesLimits& limits,
                          const std::function<void(double)>& progress) {
    const ReadingInput reading(path);
    const std::uint64_t size = checkRegularFile(path, limits.maxBytes, "a .slices file");
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError(path, 0, "cannot open file");
    SlicesProgress bytes;
    if (progress && size > 0)
        bytes = [&](std::uint64_t read) { progress(std::min(1.0, double(read) / double(size))); };
    return parseSlices(in, path, limits, bytes);
}

void formatSlices(const ContourSet& contours, std::ostream& out) {
    out << "dfrecon-slices 1\nunits mm\n";
    for (const Roi& roi : contours.rois) {
        out << "roi " << quotedName(roi.name);
        if (roi.colour)
            out << ' ' << int((*roi.colour)[0]) << ' ' << int((*roi.colour)[1]) << ' '
                << int((*roi.colour)[2]);
        out << '\n';
        for (const Slice& slice : roi.slices) {
            out << "slice " << exactNumber(slice.zMm) << '\n';
            for (const Polygon& contour : slice.contours) {
                out << "contour " << contour.size() << '\n';
                for (Point2 p : contour) out << exactNumber(p.x) << ' ' << exactNumber(p.y) << '\n';
            }
        }
    }
}

void writeSlicesFile(const ContourSet& contours, const std::string& path) {
    writeStreamAtomically(path, [&](std::ostream& out) { formatSlices(contours, out); });
}

}  // namespace dfrecon
