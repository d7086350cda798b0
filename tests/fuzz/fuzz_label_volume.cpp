// libFuzzer target for the label-volume readers (docs/fuzzing.md). teem and
// niftilib read files, not memory, and the format follows the name, so each
// input goes through a temporary file whose extension the first byte
// chooses (.nrrd .nhdr .nii .nii.gz): one corpus covers both libraries and
// all four ways in. A .nhdr names a detached data file, which may be any
// file the header points at; for those the oracle is only "no crash", as
// for everything else. Oracle: any input either loads or raises InputError;
// whatever loads has as many labels as its grid has voxels and a geometry
// that readLabelVolume promises: positive sizes, finite spacing of at least
// kMinVoxelSpacingMm, finite origin and unit directions, and a grid within
// kMaxAbsCoordinateMm.

#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>

#include "contours/InputError.hpp"
#include "io/files/InputLimits.hpp"
#include "io/labels/LabelVolume.hpp"
#include "tests/fuzz/ScratchInput.hpp"

using namespace dfrecon;

namespace {

constexpr std::array<const char*, 4> kExtensions{{".nrrd", ".nhdr", ".nii", ".nii.gz"}};

void expectSane(const LabelVolume& volume) {
    const VolumeGeometry& g = volume.geometry;
    std::uint64_t voxels = 1;
    for (int a = 0; a < 3; ++a) {
        if (g.size[a] <= 0) __builtin_trap();
        voxels *= std::uint64_t(g.size[a]);
        if (!std::isfinite(g.spacingMm[a]) || g.spacingMm[a] < kMinVoxelSpacingMm) __builtin_trap();
        if (!std::isfinite(g.originMm[a])) __builtin_trap();
        double norm = 0;
        for (double c : g.direction[a]) {
            if (!std::isfinite(c)) __builtin_trap();
            norm += c * c;
        }
        if (std::abs(std::sqrt(norm) - 1) > 1e-3) __builtin_trap();
    }
    if (voxels > kMaxLabelVolumeVoxels || volume.labels.size() != voxels) __builtin_trap();
    if (g.voxelCount() != voxels) __builtin_trap();
    // The outer corners of the grid (a parallelepiped) bound all of it.
    for (int corner = 0; corner < 8; ++corner) {
        auto at = [&](int a) { return (corner >> a & 1) ? g.size[a] - 0.5 : -0.5; };
        const Vec3 p = g.worldOfIndex(at(0), at(1), at(2));
        for (double c : {p.x, p.y, p.z})
            if (!std::isfinite(c) || std::abs(c) > kMaxAbsCoordinateMm) __builtin_trap();
    }
}

}  // namespace

// The project's suppressions travel with the binary, so the fuzzing run and
// a replay by hand judge an input as `make sanitize-test` does: teem leaks
// its gzip stream on corrupt data (tests/lsan.supp says why), a third-party
// leak per refused file that no fix in io/ can reach.
extern "C" const char* __lsan_default_options() {
    return "suppressions=" DFRECON_LSAN_SUPPRESSIONS;
}
extern "C" const char* __ubsan_default_options() {
    return "print_stacktrace=1:suppressions=" DFRECON_UBSAN_SUPPRESSIONS;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    if (size == 0) return 0;
    const std::string& path = fuzz::writeScratchInput("label", kExtensions, data, size);
    LabelVolume volume;
    try {
        volume = readLabelVolume(path);
    } catch (const InputError&) {
        return 0;
    }
    expectSane(volume);
    return 0;
}
