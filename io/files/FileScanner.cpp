#include "io/files/FileScanner.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>

#include "contours/InputError.hpp"
#include "io/files/RegularFile.hpp"

namespace dfrecon {

namespace {

constexpr std::size_t kBufferBytes = std::size_t(1) << 20;

// The C locale's white space, as std::istream >> skips it.
bool isSpace(char c) {
    return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v' || c == '\f';
}

bool isDigit(char c) {
    return c >= '0' && c <= '9';
}

}  // namespace

FileScanner::FileScanner(const std::string& path)
    : path_(path), file_(nullptr, &std::fclose), buffer_(kBufferBytes, '\0') {
    size_ = checkRegularFile(path, kMaxInputFileBytes, "an input file");
    file_.reset(std::fopen(path.c_str(), "rb"));
    if (!file_) throw InputError(path, 0, "cannot open file");
}

bool FileScanner::fill() {
    if (begin_ < end_) return true;
    begin_ = 0;
    end_ = std::fread(buffer_.data(), 1, buffer_.size(), file_.get());
    if (end_ == 0 && std::ferror(file_.get())) fail("read error", 0);
    return end_ > 0;
}

int FileScanner::peek() {
    return fill() ? static_cast<unsigned char>(buffer_[begin_]) : -1;
}

bool FileScanner::nextToken(std::string& token) {
    token.clear();
    while (fill() && isSpace(buffer_[begin_])) {
        if (buffer_[begin_] == '\n') ++line_;
        ++begin_, ++offset_;
    }
    tokenLine_ = line_;
    while (fill() && !isSpace(buffer_[begin_])) {
        if (token.size() == kMaxTokenBytes)
            fail("a value longer than " + std::to_string(kMaxTokenBytes) + " characters",
                 tokenLine_);
        token += buffer_[begin_++];
        ++offset_;
    }
    return !token.empty();
}

void FileScanner::skipLine() {
    while (fill()) {
        const char* start = buffer_.data() + begin_;
        const void* newline = std::memchr(start, '\n', end_ - begin_);
        if (newline) {
            const std::size_t n = std::size_t(static_cast<const char*>(newline) - start) + 1;
            begin_ += n, offset_ += n;
            ++line_;
            return;
        }
        offset_ += end_ - begin_;
        begin_ = end_;
    }
}

bool FileScanner::readLine(std::string& line, std::size_t maxBytes) {
    line.clear();
    if (!fill()) return false;
    while (fill()) {
        const char c = buffer_[begin_++];
        ++offset_;
        if (c == '\n') {
            ++line_;
            return true;
        }
        if (line.size() == maxBytes)
            fail("a line longer than " + std::to_string(maxBytes) + " characters", line_);
        line += c;
    }
    return true;
}

bool FileScanner::readBytes(void* out, std::size_t n) {
    if (n > remaining()) return false;
    auto* target = static_cast<char*>(out);
    while (n > 0) {
        if (!fill()) fail("the file ended while being read", 0);
        const std::size_t take = std::min(n, end_ - begin_);
        std::memcpy(target, buffer_.data() + begin_, take);
        target += take, begin_ += take, offset_ += take, n -= take;
    }
    return true;
}

bool FileScanner::skipBytes(std::uint64_t n) {
    if (n > remaining()) return false;
    const std::uint64_t buffered = end_ - begin_;
    if (n <= buffered) {
        begin_ += std::size_t(n);
        offset_ += n;
        return true;
    }
    // Past the buffer: seek to the new offset and start afresh.
    offset_ += n;
    begin_ = end_ = 0;
    if (std::fseek(file_.get(), long(offset_), SEEK_SET) != 0) fail("cannot seek", 0);
    return true;
}

void FileScanner::fail(const std::string& problem, int line) const {
    throw InputError(path_, line, problem);
}

bool parseDecimal(std::string_view token, double& value) {
    std::size_t i = 0;
    if (i < token.size() && (token[i] == '+' || token[i] == '-')) ++i;
    std::size_t digits = 0;
    while (i < token.size() && isDigit(token[i])) ++i, ++digits;
    if (i < token.size() && token[i] == '.') {
        ++i;
        while (i < token.size() && isDigit(token[i])) ++i, ++digits;
    }
    if (digits == 0) return false;
    if (i < token.size() && (token[i] == 'e' || token[i] == 'E')) {
        ++i;
        if (i < token.size() && (token[i] == '+' || token[i] == '-')) ++i;
        std::size_t exponentDigits = 0;
        while (i < token.size() && isDigit(token[i])) ++i, ++exponentDigits;
        if (exponentDigits == 0) return false;
    }
    if (i != token.size()) return false;
    // strtod rounds underflow to zero or a subnormal, as the streams do;
    // overflow gives infinity, which the streams refuse as well.
    const std::string text(token);
    errno = 0;
    value = std::strtod(text.c_str(), nullptr);
    return std::isfinite(value);
}

bool parseInteger(std::string_view token, std::int64_t& value) {
    std::size_t i = 0;
    const bool negative = !token.empty() && token[0] == '-';
    if (!token.empty() && (token[0] == '+' || token[0] == '-')) ++i;
    if (i == token.size()) return false;
    std::uint64_t magnitude = 0;
    for (; i < token.size(); ++i) {
        if (!isDigit(token[i])) return false;
        const std::uint64_t digit = std::uint64_t(token[i] - '0');
        if (magnitude > (std::uint64_t(INT64_MAX) - digit) / 10) return false;
        magnitude = magnitude * 10 + digit;
    }
    value = negative ? -std::int64_t(magnitude) : std::int64_t(magnitude);
    return true;
}

}  // namespace dfrecon
