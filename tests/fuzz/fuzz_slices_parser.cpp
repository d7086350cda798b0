// libFuzzer target for the .slices parser (docs/fuzzing.md). Oracle: any
// input either loads or raises InputError; whatever loads must write out and
// read back to the same contours (so the writer and parser agree on every
// name and number the parser accepts).
#include <cstdint>
#include <sstream>

#include "io/contours/SlicesFile.hpp"

using namespace dfrecon;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    // Small limits keep each run fast; the limit checks themselves are fuzzed.
    SlicesLimits limits;
    limits.maxPointsPerContour = 5000;
    limits.maxPointsTotal = 20000;
    limits.maxContoursPerSlice = 200;
    limits.maxSlicesPerRoi = 500;
    limits.maxRois = 50;
    limits.maxLineBytes = 4096;

    std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
    SlicesLoad load;
    try {
        load = parseSlices(in, "fuzz.slices", limits);
    } catch (const InputError&) {
        return 0;
    }
    std::ostringstream out;
    formatSlices(load.contours, out);
    std::istringstream again(out.str());
    const SlicesLoad back = parseSlices(again, "roundtrip.slices", limits);
    if (back.contours.rois.size() != load.contours.rois.size()) __builtin_trap();
    for (std::size_t r = 0; r < back.contours.rois.size(); ++r) {
        const Roi &a = load.contours.rois[r], &b = back.contours.rois[r];
        if (a.name != b.name || a.slices.size() != b.slices.size()) __builtin_trap();
        for (std::size_t s = 0; s < a.slices.size(); ++s)
            if (a.slices[s].zMm != b.slices[s].zMm || a.slices[s].contours != b.slices[s].contours)
                __builtin_trap();
    }
    return 0;
}
