// libFuzzer target for the mesh readers (docs/fuzzing.md). OpenMesh reads
// files, not memory, and picks its reader by extension, so each input goes
// through a temporary file whose extension the first byte chooses: one
// corpus then covers PLY, OFF, OBJ and STL, and a mutation of that byte
// hands the same body to another reader. Oracle: any input either loads or
// raises InputError; whatever loads has only finite points within
// kMaxAbsCoordinateMm and triangles whose corners are points of the soup.

#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>

#include "contours/InputError.hpp"
#include "io/files/InputLimits.hpp"
#include "io/mesh/MeshIO.hpp"
#include "tests/fuzz/ScratchInput.hpp"

using namespace dfrecon;

namespace {

constexpr std::array<const char*, 4> kExtensions{{".ply", ".off", ".obj", ".stl"}};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    if (size == 0) return 0;
    const std::string& path = fuzz::writeScratchInput("mesh", kExtensions, data, size);
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
