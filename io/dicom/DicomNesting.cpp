#include "io/dicom/DicomNesting.hpp"

#include <zlib.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "contours/InputError.hpp"
#include "io/files/FileScanner.hpp"
#include "io/files/RegularFile.hpp"

namespace dfrecon {

namespace {

constexpr std::uint32_t kUndefined = 0xffffffffu;
constexpr std::uint64_t kNoEnd = std::numeric_limits<std::uint64_t>::max();

// The data set's bytes: the file itself after the meta header, or its
// inflated stream (Deflated Explicit VR Little Endian).
class Source {
  public:
    virtual ~Source() = default;
    virtual bool read(void* out, std::size_t n) = 0;
    virtual bool skip(std::uint64_t n) = 0;
    virtual std::uint64_t offset() const = 0;
};

class PlainSource : public Source {
  public:
    PlainSource(const std::string& path, std::uint64_t start) : file_(path), start_(start) {
        file_.skipBytes(start);
    }
    bool read(void* out, std::size_t n) override { return file_.readBytes(out, n); }
    bool skip(std::uint64_t n) override { return file_.skipBytes(n); }
    std::uint64_t offset() const override { return file_.offset() - start_; }

  private:
    FileScanner file_;
    std::uint64_t start_;
};

class InflatingSource : public Source {
  public:
    InflatingSource(const std::string& path, std::uint64_t start)
        : file_(path), in_(std::size_t(1) << 16), out_(std::size_t(1) << 16) {
        file_.skipBytes(start);
        // Raw deflate, no zlib or gzip wrapper (PS3.5 A.5).
        if (inflateInit2(&stream_, -MAX_WBITS) != Z_OK)
            throw InputError(path, 0, "cannot start inflating the data set");
    }
    ~InflatingSource() override { inflateEnd(&stream_); }
    InflatingSource(const InflatingSource&) = delete;
    InflatingSource& operator=(const InflatingSource&) = delete;

    bool read(void* out, std::size_t n) override {
        auto* target = static_cast<unsigned char*>(out);
        while (n > 0) {
            if (begin_ == end_ && !refill()) return false;
            const std::size_t take = std::min(n, end_ - begin_);
            if (target) std::memcpy(target, out_.data() + begin_, take), target += take;
            begin_ += take, offset_ += take, n -= take;
        }
        return true;
    }
    bool skip(std::uint64_t n) override {
        while (n > 0) {
            const std::size_t step = std::size_t(std::min<std::uint64_t>(n, out_.size()));
            if (!read(nullptr, step)) return false;
            n -= step;
        }
        return true;
    }
    std::uint64_t offset() const override { return offset_; }

  private:
    bool refill() {
        if (finished_) return false;
        begin_ = end_ = 0;
        while (end_ == 0) {
            if (stream_.avail_in == 0) {
                const std::size_t n =
                    std::size_t(std::min<std::uint64_t>(file_.remaining(), in_.size()));
                if (n == 0 || !file_.readBytes(in_.data(), n)) return false;
                stream_.next_in = in_.data();
                stream_.avail_in = uInt(n);
            }
            stream_.next_out = out_.data();
            stream_.avail_out = uInt(out_.size());
            const int status = inflate(&stream_, Z_NO_FLUSH);
            end_ = out_.size() - stream_.avail_out;
            if (status == Z_STREAM_END) {
                finished_ = true;
                return end_ > 0;
            }
            if (status != Z_OK && status != Z_BUF_ERROR) return false;
        }
        return true;
    }

    FileScanner file_;
    z_stream stream_{};
    std::vector<unsigned char> in_, out_;
    std::size_t begin_ = 0, end_ = 0;
    std::uint64_t offset_ = 0;
    bool finished_ = false;
};

struct Syntax {
    bool explicitVr = true, bigEndian = false;
};

enum class FrameKind { Items, Elements, Fragments };

struct Frame {
    FrameKind kind;
    std::uint64_t end;  // kNoEnd: undefined length, ended by a delimiter
    Syntax syntax;
    bool speculative;                     // a value of another VR walked as a sequence
    std::uint32_t lastTag = 0xffffffffu;  // of Elements: the element before
};

std::uint16_t u16(const unsigned char* b, bool big) {
    return big ? std::uint16_t(b[0] << 8 | b[1]) : std::uint16_t(b[1] << 8 | b[0]);
}

std::uint32_t u32(const unsigned char* b, bool big) {
    return big ? std::uint32_t(b[0]) << 24 | std::uint32_t(b[1]) << 16 | std::uint32_t(b[2]) << 8 |
                     b[3]
               : std::uint32_t(b[3]) << 24 | std::uint32_t(b[2]) << 16 | std::uint32_t(b[1]) << 8 |
                     b[0];
}

// VRs whose explicit form has two reserved bytes and a 32-bit length; an
// unknown VR is read the same way, as DICOM prescribes for new ones.
bool longLength(const char vr[2]) {
    static const char* const shortVrs[] = {"AE", "AS", "AT", "CS", "DA", "DS", "DT",
                                           "FL", "FD", "IS", "LO", "LT", "PN", "SH",
                                           "SL", "SS", "ST", "TM", "UI", "UL", "US"};
    for (const char* s : shortVrs)
        if (vr[0] == s[0] && vr[1] == s[1]) return false;
    return true;
}

class Walker {
  public:
    Walker(std::string path, std::size_t maxDepth) : path_(std::move(path)), maxDepth_(maxDepth) {}

    void walk(Source& source, Syntax syntax) {
        stack_.push_back({FrameKind::Elements, kNoEnd, syntax, false});
        while (!stack_.empty()) {
            const std::uint64_t end = stack_.back().end;
            if (end != kNoEnd && source.offset() >= end) {
                if (source.offset() == end)
                    pop();
                else if (!abandon(source))
                    return;
                continue;
            }
            if (!step(source) && !abandon(source)) return;
        }
    }

  private:
    // One element, item or delimiter. False when the stream is malformed.
    bool step(Source& source) {
        const Frame top = stack_.back();
        const bool big = top.syntax.bigEndian;
        unsigned char b[8];
        if (!source.read(b, 4)) return stack_.size() == 1 ? (stack_.clear(), true) : false;
        const std::uint16_t group = u16(b, big), element = u16(b + 2, big);
        if (group == 0xfffe) {
            if (!source.read(b, 4)) return false;
            const std::uint32_t length = u32(b, big);
            if (element == 0xe000 && top.kind != FrameKind::Elements) {  // an item
                if (top.kind == FrameKind::Fragments)
                    return length != kUndefined && source.skip(length);
                return push(source, FrameKind::Elements, length, top.syntax);
            }
            if (element == 0xe00d && top.kind == FrameKind::Elements && top.end == kNoEnd &&
                stack_.size() > 1) {
                pop();
                return true;
            }
            if (element == 0xe0dd && top.kind != FrameKind::Elements && top.end == kNoEnd) {
                pop();
                return true;
            }
            return false;
        }
        if (top.kind != FrameKind::Elements) return false;
        checkGarbage(source, group, element);
        char vr[2] = {0, 0};
        std::uint32_t length = 0;
        if (top.syntax.explicitVr) {
            if (!source.read(vr, 2)) return false;
            if (longLength(vr)) {
                if (!source.read(b, 6)) return false;
                length = u32(b + 2, big);
            } else {
                if (!source.read(b, 2)) return false;
                length = u16(b, big);
            }
        } else {
            if (!source.read(b, 4)) return false;
            length = u32(b, big);
        }
        const bool sq = vr[0] == 'S' && vr[1] == 'Q';
        if (length == kUndefined) {
            if (group == 0x7fe0 && element == 0x0010 && !sq)
                return push(source, FrameKind::Fragments, length, top.syntax);
            // A sequence; an undefined-length UN holds implicit little endian.
            Syntax inner = top.syntax;
            if (vr[0] == 'U' && vr[1] == 'N') inner = {false, false};
            return push(source, FrameKind::Items, length, inner);
        }
        if (top.end != kNoEnd && source.offset() + length > top.end) return false;
        if (sq) return push(source, FrameKind::Items, length, top.syntax);
        // Any other value: walked as a sequence when it starts with an item
        // tag, since a reader may take it for one.
        if (length < 8) return source.skip(length);
        if (!source.read(b, 4)) return false;
        if (u16(b, big) == 0xfffe && u16(b + 2, big) == 0xe000) {
            stack_.push_back({FrameKind::Items, source.offset() - 4 + length, top.syntax, true});
            checkDepth(source);
            if (!source.read(b, 4)) return false;
            return push(source, FrameKind::Elements, u32(b, big), top.syntax);
        }
        return source.skip(length - 4);
    }

    // Enters a value of `length` bytes from here; false when it would end
    // after the value that holds it.
    bool push(const Source& source, FrameKind kind, std::uint32_t length, Syntax syntax) {
        const std::uint64_t end = length == kUndefined ? kNoEnd : source.offset() + length;
        const std::uint64_t outer = stack_.back().end;
        if (end != kNoEnd && outer != kNoEnd && end > outer) return false;
        stack_.push_back({kind, end, syntax, false});
        if (kind == FrameKind::Items) checkDepth(source);
        return true;
    }

    void pop() { stack_.pop_back(); }

    // Zeros or one empty element over and over after the magic: DCMTK
    // parses such a file at some 4 µs an element, a minute a gigabyte.
    // Neither occurs in a DICOM file — command elements (group 0000)
    // belong to network messages (PS3.7), and an element occurs once in its
    // data set (PS3.5 7.1) — so the file is refused at the first. Not within
    // a value walked on speculation, which may be anything.
    void checkGarbage(const Source& source, std::uint16_t group, std::uint16_t element) {
        const std::uint32_t tag = std::uint32_t(group) << 16 | element;
        Frame& top = stack_.back();
        const std::uint32_t previous = top.lastTag;
        top.lastTag = tag;
        for (const Frame& f : stack_)
            if (f.speculative) return;
        char name[16];
        std::snprintf(name, sizeof name, "(%04X,%04X)", unsigned(group), unsigned(element));
        const std::string at =
            " at byte " + std::to_string(source.offset() - 4) + " of the data set";
        if (group == 0)
            throw InputError(path_, 0,
                             std::string("a command element ") + name + at +
                                 ", which no DICOM file holds: not a DICOM file's data");
        if (tag == previous)
            throw InputError(path_, 0,
                             std::string("the element ") + name + " twice in a row" + at +
                                 ": not a DICOM file's data");
    }

    void checkDepth(const Source& source) {
        std::size_t depth = 0;
        for (const Frame& f : stack_) depth += f.kind == FrameKind::Items;
        if (depth > maxDepth_)
            throw InputError(path_, 0,
                             "sequences nested more than " + std::to_string(maxDepth_) +
                                 " deep (at byte " + std::to_string(source.offset()) +
                                 " of the data set); refused before parsing, whose recursion "
                                 "they would exhaust");
    }

    // Malformed here: gives up the innermost value walked on speculation
    // (skipping to its end) and goes on; false when there is none.
    bool abandon(Source& source) {
        for (std::size_t k = stack_.size(); k-- > 0;) {
            if (!stack_[k].speculative) continue;
            const std::uint64_t end = stack_[k].end;
            stack_.resize(k);
            return source.offset() <= end && source.skip(end - source.offset());
        }
        stack_.clear();
        return false;
    }

    std::string path_;
    std::size_t maxDepth_;
    std::vector<Frame> stack_;
};

// The File Meta Information (explicit VR little endian, group 0002) read
// into memory: where the data set starts and its transfer syntax UID.
struct Meta {
    std::uint64_t datasetStart = 0;
    std::string transferSyntax;
    bool found = false;
};

Meta readMeta(const std::string& path) {
    FileScanner file(path);
    const std::size_t size = std::size_t(std::min<std::uint64_t>(file.size(), 1 << 20));
    std::vector<unsigned char> head(size);
    file.readBytes(head.data(), size);
    Meta meta;
    if (size < 132 || std::memcmp(head.data() + 128, "DICM", 4) != 0) return meta;
    meta.found = true;
    std::size_t at = 132;
    while (at + 8 <= size && u16(head.data() + at, false) == 0x0002) {
        const std::uint16_t element = u16(head.data() + at + 2, false);
        const char vr[2] = {char(head[at + 4]), char(head[at + 5])};
        std::uint64_t length = 0, value = 0;
        if (longLength(vr)) {
            if (at + 12 > size) break;
            length = u32(head.data() + at + 8, false);
            value = at + 12;
        } else {
            length = u16(head.data() + at + 6, false);
            value = at + 8;
        }
        if (length == kUndefined || value + length > size) break;
        if (element == 0x0010) {
            meta.transferSyntax.assign(reinterpret_cast<const char*>(head.data() + value),
                                       std::size_t(length));
            while (!meta.transferSyntax.empty() &&
                   (meta.transferSyntax.back() == '\0' || meta.transferSyntax.back() == ' '))
                meta.transferSyntax.pop_back();
        }
        at = std::size_t(value + length);
    }
    meta.datasetStart = at;
    return meta;
}

// Without File Meta Information DCMTK guesses the syntax from the first
// element: explicit when two letters follow the tag, big endian when the
// group only makes sense read that way.
Syntax guessSyntax(const std::string& path) {
    FileScanner file(path);
    unsigned char b[6] = {};
    if (!file.readBytes(b, 6)) return {};
    Syntax s;
    s.explicitVr = b[4] >= 'A' && b[4] <= 'Z' && b[5] >= 'A' && b[5] <= 'Z';
    s.bigEndian = u16(b, false) > 0x00ff && u16(b, true) <= 0x00ff;
    return s;
}

}  // namespace

void checkDicomNesting(const std::string& path, std::size_t maxDepth) {
    // A missing file is DCMTK's to report; a FIFO or device would block it.
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) return;
    checkRegularFile(path, kMaxInputFileBytes, "a DICOM file");
    const Meta meta = readMeta(path);
    Walker walker(path, maxDepth);
    if (!meta.found) {
        PlainSource source(path, 0);
        walker.walk(source, guessSyntax(path));
        return;
    }
    const std::string& ts = meta.transferSyntax;
    if (ts == "1.2.840.10008.1.2.1.99") {
        InflatingSource source(path, meta.datasetStart);
        walker.walk(source, {true, false});
        return;
    }
    PlainSource source(path, meta.datasetStart);
    walker.walk(source, {ts != "1.2.840.10008.1.2", ts == "1.2.840.10008.1.2.2"});
}

}  // namespace dfrecon
