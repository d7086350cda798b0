#pragma once
// Reading a file's bytes, lines and whitespace-separated tokens in one
// forward pass with a fixed buffer, for the checks that run before a
// third-party parser sees the file (io/mesh/MeshFileCheck): memory stays bounded
// whatever the file holds, and every failure is an InputError naming the
// file (and, for text, the line).
#include <cstdint>
#include <cstdio>
#include <memory>
#include <string>
#include <string_view>

namespace dfrecon {

class FileScanner {
  public:
    /// Opens `path` (a regular file); throws InputError when it cannot.
    explicit FileScanner(const std::string& path);

    const std::string& path() const { return path_; }
    std::uint64_t size() const { return size_; }
    /// Bytes consumed so far.
    std::uint64_t offset() const { return offset_; }
    std::uint64_t remaining() const { return size_ - offset_; }
    /// 1-based line of the next byte (text), counting '\n'.
    int line() const { return line_; }
    /// Line on which the last token returned by nextToken started.
    int tokenLine() const { return tokenLine_; }

    /// The next token: a run of bytes other than the C locale's white space
    /// (as std::istream >> reads it). False at the end of the file. Throws
    /// InputError for a token longer than kMaxTokenBytes.
    bool nextToken(std::string& token);
    /// Consumes the rest of the current line and its '\n' (std::getline).
    void skipLine();
    /// The rest of the current line without its '\n' (std::getline); false
    /// at the end of the file. Throws InputError for a line longer than
    /// `maxBytes`.
    bool readLine(std::string& line, std::size_t maxBytes);
    /// Exactly `n` bytes into `out`; false (and nothing consumed) when fewer
    /// remain.
    bool readBytes(void* out, std::size_t n);
    /// Skips `n` bytes; false (and nothing skipped) when fewer remain.
    bool skipBytes(std::uint64_t n);
    /// The next byte without consuming it; -1 at the end.
    int peek();

    /// Throws InputError(path, line, problem); line 0 for binary data.
    [[noreturn]] void fail(const std::string& problem, int line) const;

    /// Longest token accepted: far more than any number is written with.
    static constexpr std::size_t kMaxTokenBytes = 4096;

  private:
    bool fill();  // refills the buffer; false at the end of the file

    std::string path_;
    std::unique_ptr<std::FILE, int (*)(std::FILE*)> file_;
    std::string buffer_;
    std::size_t begin_ = 0, end_ = 0;  // unread bytes of buffer_
    std::uint64_t size_ = 0, offset_ = 0;
    int line_ = 1, tokenLine_ = 1;
};

/// Whether `token` is a decimal number as std::istream reads one whole
/// ([+-] digits [. digits] [e [+-] digits], or starting with the point), and
/// its value. No "nan", "inf" or hexadecimal. O(token).
bool parseDecimal(std::string_view token, double& value);

/// Whether `token` is a whole decimal integer ([+-] digits) within int64,
/// and its value. O(token).
bool parseInteger(std::string_view token, std::int64_t& value);

}  // namespace dfrecon
