// libFuzzer target for the mesh readers (docs/fuzzing.md). OpenMesh reads
// files, not memory, and picks its reader by extension, so each input goes
// through a temporary file whose extension the first byte chooses: one
// corpus then covers PLY, OFF, OBJ and STL, and a mutation of that byte
// hands the same body to another reader. Oracle: any input either loads or
// raises InputError; whatever loads has only finite points within
// kMaxAbsCoordinateMm and triangles whose corners are points of the soup.
#include <unistd.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <string>

#include "io/InputError.hpp"
#include "io/InputLimits.hpp"
#include "io/MeshIO.hpp"

using namespace dfrecon;

namespace {

constexpr std::array<const char*, 4> kExtensions{{".ply", ".off", ".obj", ".stl"}};

std::string scratch(const char* extension) {
    // Per process, so that several fuzzers (or -fork) never share a file;
    // /dev/shm where there is one keeps the disk out of the loop.
    static const std::string dir = access("/dev/shm", W_OK) == 0 ? "/dev/shm" : "/tmp";
    return dir + "/dfrecon-fuzz-mesh-" + std::to_string(getpid()) + extension;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    if (size == 0) return 0;
    // One file per extension, removed at exit (-fork starts a process, so a
    // set per job).
    struct Scratch {
        std::array<std::string, kExtensions.size()> paths;
        Scratch() {
            for (std::size_t e = 0; e < kExtensions.size(); ++e) paths[e] = scratch(kExtensions[e]);
        }
        ~Scratch() {
            for (const std::string& path : paths) std::remove(path.c_str());
        }
    };
    static const Scratch files;
    const std::string& path = files.paths[data[0] % kExtensions.size()];
    {
        std::ofstream file(path, std::ios::binary | std::ios::trunc);
        file.write(reinterpret_cast<const char*>(data + 1), std::streamsize(size - 1));
        if (!file) __builtin_trap();  // scratch space full: not the reader's fault
    }
    TriangleSoup soup;
    try {
        soup = readTriangleSoup(path);
    } catch (const InputError&) {
        return 0;
    }
    for (const Vec3& p : soup.points)
        for (double c : {p.x, p.y, p.z})
            if (!std::isfinite(c) || std::abs(c) > kMaxAbsCoordinateMm) __builtin_trap();
    if (soup.triangles.empty()) __builtin_trap();  // readTriangleSoup promises some
    for (const auto& triangle : soup.triangles)
        for (std::uint32_t v : triangle)
            if (v >= soup.points.size()) __builtin_trap();
    return 0;
}
