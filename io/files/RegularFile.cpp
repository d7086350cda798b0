#include "io/files/RegularFile.hpp"

#include <sys/stat.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>

#include "contours/InputError.hpp"

namespace dfrecon {

namespace {

// What a file that is not a regular one is, in the words of `ls -l`.
std::string kindOf(mode_t mode) {
    if (S_ISDIR(mode)) return "a folder";
    if (S_ISFIFO(mode)) return "a named pipe";
    if (S_ISCHR(mode)) return "a character device";
    if (S_ISBLK(mode)) return "a block device";
    if (S_ISSOCK(mode)) return "a socket";
    return "not a plain file";
}

std::string mebibytes(std::uint64_t bytes) {
    return bytes >= (std::uint64_t(1) << 20) ? std::to_string(bytes >> 20) + " MiB"
                                             : std::to_string(bytes) + " bytes";
}

[[noreturn]] void tooLarge(const std::string& path, std::uint64_t maxBytes,
                           const std::string& what) {
    throw InputError(path, 0, "larger than " + mebibytes(maxBytes) + ", the limit of " + what);
}

}  // namespace

std::uint64_t checkRegularFile(const std::string& path, std::uint64_t maxBytes,
                               const std::string& what) {
    struct stat info {};
    if (::stat(path.c_str(), &info) != 0)
        throw InputError(
            path, 0,
            errno == ENOENT ? "no such file" : "cannot open: " + std::string(std::strerror(errno)));
    if (!S_ISREG(info.st_mode))
        throw InputError(path, 0, kindOf(info.st_mode) + ", not a regular file");
    const std::uint64_t bytes = std::uint64_t(info.st_size);
    if (bytes > maxBytes) tooLarge(path, maxBytes, what);
    return bytes;
}

std::string readRegularFile(const std::string& path, std::uint64_t maxBytes,
                            const std::string& what) {
    const std::uint64_t bytes = checkRegularFile(path, maxBytes, what);
    std::unique_ptr<std::FILE, int (*)(std::FILE*)> file(std::fopen(path.c_str(), "rb"),
                                                         &std::fclose);
    if (!file) throw InputError(path, 0, "cannot open: " + std::string(std::strerror(errno)));
    std::string text(std::size_t(bytes), '\0');
    std::size_t read = std::fread(text.data(), 1, text.size(), file.get());
    text.resize(read);
    // A file still being written may have grown since: read on, to the limit.
    char more[1 << 16];
    while (std::size_t n = std::fread(more, 1, sizeof more, file.get())) {
        if (text.size() + n > maxBytes) tooLarge(path, maxBytes, what);
        text.append(more, n);
    }
    if (std::ferror(file.get())) throw InputError(path, 0, "read error");
    return text;
}

bool isRegularFile(const std::string& path) {
    struct stat info {};
    return ::stat(path.c_str(), &info) == 0 && S_ISREG(info.st_mode);
}

}  // namespace dfrecon
