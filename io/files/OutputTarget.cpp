#include "io/files/OutputTarget.hpp"

#include <sys/stat.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <filesystem>
#include <mutex>
#include <stdexcept>
#include <string>
#include <vector>

#include "io/files/InputsInUse.hpp"

namespace dfrecon {

namespace fs = std::filesystem;

namespace {

std::atomic<bool> inputsGuarded{false};

// Files this process has written: reading one back (to verify it) does not
// make it an input that a second write may not replace.
std::mutex writtenMutex;
std::vector<std::string> writtenFiles;

bool writtenHere(const std::string& path) {
    std::lock_guard<std::mutex> lock(writtenMutex);
    for (const std::string& written : writtenFiles)
        if (sameFile(path, written)) return true;
    return false;
}

// The path made absolute and normal, without touching the file system
// beyond the current folder (a missing file has no canonical form).
fs::path normalPath(const std::string& path) {
    std::error_code error;
    fs::path absolute = fs::absolute(fs::path(path), error);
    if (error) absolute = fs::path(path);
    fs::path canonical = fs::weakly_canonical(absolute, error);
    return (error ? absolute : canonical).lexically_normal();
}

std::string lowerCase(std::string text) {
    for (char& c : text) c = char(std::tolower(static_cast<unsigned char>(c)));
    return text;
}

}  // namespace

std::string whyNotAFileTarget(const std::string& path) {
    struct stat info {};
    if (::lstat(path.c_str(), &info) != 0) return "";  // missing: created
    if (S_ISDIR(info.st_mode)) return "it is a folder";
    if (S_ISCHR(info.st_mode)) return "it is a character device";
    if (S_ISBLK(info.st_mode)) return "it is a block device";
    if (S_ISFIFO(info.st_mode)) return "it is a named pipe (FIFO)";
    if (S_ISSOCK(info.st_mode)) return "it is a socket";
    return "";
}

bool sameFile(const std::string& a, const std::string& b) {
    struct stat sa {
    }, sb{};
    if (::stat(a.c_str(), &sa) == 0 && ::stat(b.c_str(), &sb) == 0)
        return sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
    return normalPath(a) == normalPath(b);
}

bool sameFileIgnoringCase(const std::string& a, const std::string& b) {
    const fs::path pa = normalPath(a), pb = normalPath(b);
    return lowerCase(pa.filename().string()) == lowerCase(pb.filename().string()) &&
           (pa.parent_path() == pb.parent_path() ||
            sameFile(pa.parent_path().string(), pb.parent_path().string()));
}

void checkOutputTarget(const std::string& path) {
    const std::string why = whyNotAFileTarget(path);
    if (!why.empty())
        throw std::invalid_argument(path + ": refused as an output: " + why +
                                    " (give a file name)");
    if (!inputsGuarded) return;
    for (const std::string& input : inputsInUse().inputs)
        if (sameFile(path, input) && !writtenHere(input))
            throw std::invalid_argument(path + ": refused as an output: it is an input of " +
                                        "this command" +
                                        (input == path ? "" : " (read as " + input + ")") +
                                        "; writing it would replace what was read");
}

void guardInputsFromOutputs(bool on) {
    inputsGuarded = on;
}

void noteOutputWritten(const std::string& path) {
    std::lock_guard<std::mutex> lock(writtenMutex);
    writtenFiles.push_back(path);
}

}  // namespace dfrecon
