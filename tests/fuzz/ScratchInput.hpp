#pragma once
// The file a fuzz input goes through when its reader reads files, not
// memory, and picks the format by extension: the first byte chooses the
// extension (one corpus covers every format, and mutating that byte hands the
// same body to another reader), the rest is the file. One file per extension
// and process (several fuzzers, or -fork jobs, never share one), in /dev/shm
// where there is one to keep the disk out of the loop, removed at exit.
#include <unistd.h>

#include <array>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <string>

namespace dfrecon::fuzz {

/// Writes data[1..size) to the scratch file for extension data[0] % N and
/// returns its path. `name` tells the fuzz targets' files apart. size >= 1.
template <std::size_t N>
const std::string& writeScratchInput(const char* name, const std::array<const char*, N>& extensions,
                                     const std::uint8_t* data, std::size_t size) {
    struct Scratch {
        std::array<std::string, N> paths;
        Scratch(const char* name, const std::array<const char*, N>& extensions) {
            const std::string dir = access("/dev/shm", W_OK) == 0 ? "/dev/shm" : "/tmp";
            for (std::size_t e = 0; e < N; ++e)
                paths[e] =
                    dir + "/dfrecon-fuzz-" + name + "-" + std::to_string(getpid()) + extensions[e];
        }
        ~Scratch() {
            for (const std::string& path : paths) std::remove(path.c_str());
        }
    };
    static const Scratch files(name, extensions);
    const std::string& path = files.paths[data[0] % N];
    std::ofstream file(path, std::ios::binary | std::ios::trunc);
    file.write(reinterpret_cast<const char*>(data + 1), std::streamsize(size - 1));
    file.close();
    if (!file) __builtin_trap();  // scratch space full: not the reader's fault
    return path;
}

}  // namespace dfrecon::fuzz
