#include "io/AtomicWrite.hpp"

#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <system_error>

namespace dfrecon {

namespace fs = std::filesystem;

static std::string temporaryPathFor(const std::string& path) {
    static std::atomic<unsigned> counter{0};
    const fs::path target(path);
    // Hidden, unique per process and call, same folder (rename stays atomic),
    // same extension (format detection by extension keeps working).
    const std::string name = "." + target.stem().string() + ".tmp-" + std::to_string(::getpid()) +
                             "-" + std::to_string(counter++) + target.extension().string();
    return (target.parent_path() / name).string();
}

void writeAtomically(const std::string& path,
                     const std::function<bool(const std::string&)>& write) {
    const std::string temporary = temporaryPathFor(path);
    try {
        if (!write(temporary)) throw std::runtime_error("cannot write " + path);
        std::error_code ec;
        fs::rename(temporary, path, ec);
        if (ec) throw std::runtime_error("cannot write " + path + ": " + ec.message());
    } catch (...) {
        std::error_code ignored;
        fs::remove(temporary, ignored);
        throw;
    }
}

void writeStreamAtomically(const std::string& path,
                           const std::function<void(std::ostream&)>& write) {
    writeAtomically(path, [&](const std::string& temporary) {
        std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
        if (!out) throw std::runtime_error("cannot write " + path + ": " + std::strerror(errno));
        write(out);
        out.flush();
        if (!out) throw std::runtime_error("cannot write " + path + ": write failed");
        return true;
    });
}

}  // namespace dfrecon
