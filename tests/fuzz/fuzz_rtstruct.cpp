// libFuzzer target for the RTSTRUCT reader (docs/fuzzing.md). DCMTK reads
// files, not memory, so each input goes through a temporary file. Oracle: any
// input either loads or raises InputError; whatever loads must write out with
// writeRtStruct and read back to the same ROIs and contours, point by point.
//
// "The same" allows a tolerance: the writer rounds every coordinate to a
// DICOM DS value of at most 16 characters, and a non-axial ROI is written
// through its plane frame and gets a frame recomputed from the rounded points
// on reading, so only axial coordinates that were valid DS values come back
// bit for bit. Contours within a plane are matched as a set, since a
// recomputed frame may order contours of one plane differently.
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <string>

#include "io/dicom/RtStruct.hpp"

using namespace dfrecon;

namespace {

// Above the rounding to DS values of 16 characters (about 1e-8 mm at the
// 1e6 mm coordinate limit) and the error of a frame rotation and back; far
// below anything that matters in a contour.
constexpr double kToleranceMm = 1e-6;

// The reader flattens each contour onto its plane, which is only defined to
// kSamePlaneToleranceMm; when the frame changes on the round trip (a stack
// tilted just enough to read as oblique is written in exactly tilted planes,
// whose contours then each lie within the tolerance of an axial plane and
// read as axial), points may move by up to that tolerance along the normal.
bool sameFrame(const PlaneFrame& a, const PlaneFrame& b) {
    for (int axis = 0; axis < 3; ++axis)
        if (std::abs(a.u[axis] - b.u[axis]) > 1e-9 || std::abs(a.v[axis] - b.v[axis]) > 1e-9 ||
            std::abs(a.n[axis] - b.n[axis]) > 1e-9)
            return false;
    return true;
}

std::string scratch(const char* role) {
    // Per process, so that several fuzzers (or -fork) never share a file;
    // /dev/shm where there is one keeps the disk out of the loop.
    static const std::string dir = access("/dev/shm", W_OK) == 0 ? "/dev/shm" : "/tmp";
    return dir + "/dfrecon-fuzz-rtstruct-" + std::to_string(getpid()) + "-" + role + ".dcm";
}

bool near(Vec3 a, Vec3 b, double tolerance) {
    return std::abs(a.x - b.x) <= tolerance && std::abs(a.y - b.y) <= tolerance &&
           std::abs(a.z - b.z) <= tolerance;
}

// Same point sequence in patient coordinates. Where the frame changed, a
// flipped normal reverses the orientation that normaliseOrientation gives,
// so the sequence may also run backwards.
bool sameContour(const Roi& ra, const Polygon& a, double za, const Roi& rb, const Polygon& b,
                 double zb) {
    if (a.size() != b.size()) return false;
    const bool same = sameFrame(ra.frame, rb.frame);
    const double tolerance = same ? kToleranceMm : kSamePlaneToleranceMm;
    const std::size_t n = a.size();
    // Either direction from any start (std::reverse moves the first point).
    for (int direction : {1, -1})
        for (std::size_t start = 0; start < n; ++start) {
            if (same && (direction < 0 || start > 0)) return false;
            bool all = true;
            for (std::size_t i = 0; i < n && all; ++i) {
                const Point2 q = b[(start + (direction > 0 ? i : n - i)) % n];
                all = near(ra.frame.toPatient({a[i].x, a[i].y, za}),
                           rb.frame.toPatient({q.x, q.y, zb}), tolerance);
            }
            if (all) return true;
        }
    return false;
}

void expectSame(const RtStructLoad& a, const RtStructLoad& b) {
    if (a.contours.rois.size() != b.contours.rois.size()) __builtin_trap();
    for (std::size_t r = 0; r < a.contours.rois.size(); ++r) {
        const Roi &x = a.contours.rois[r], &y = b.contours.rois[r];
        if (x.name != y.name || x.number != y.number || x.slices.size() != y.slices.size())
            __builtin_trap();
        // A normal that flips with the frame (oblique -z read back as
        // axial +z) orders the same planes the other way.
        const bool flipped = dot(x.frame.n, y.frame.n) < 0;
        for (std::size_t s = 0; s < x.slices.size(); ++s) {
            const Slice &p = x.slices[s], &q = y.slices[flipped ? x.slices.size() - 1 - s : s];
            if (p.contours.size() != q.contours.size()) __builtin_trap();
            std::vector<bool> used(q.contours.size(), false);
            for (const Polygon& c : p.contours) {
                bool found = false;
                for (std::size_t k = 0; k < q.contours.size() && !found; ++k)
                    if (!used[k] && sameContour(x, c, p.zMm, y, q.contours[k], q.zMm))
                        used[k] = found = true;
                if (!found) __builtin_trap();
            }
        }
    }
}

}  // namespace

// The suppressions travel with the binary, so replaying one input by hand
// behaves as the fuzzing run did.
extern "C" const char* __ubsan_default_options() {
    return "print_stacktrace=1:suppressions=" DFRECON_UBSAN_SUPPRESSIONS;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    // Small limits keep each run fast and its memory bounded; the limit
    // checks themselves are fuzzed.
    RtStructLimits limits;
    limits.maxRois = 64;
    limits.maxContoursPerRoi = 2000;
    limits.maxPointsTotal = 50'000;

    // Removed at exit: -fork starts a process, so a pair of files, per job.
    struct Scratch {
        std::string in = scratch("in"), out = scratch("out");
        ~Scratch() {
            std::remove(in.c_str());
            std::remove(out.c_str());
        }
    };
    static const Scratch files;
    const std::string &input = files.in, &output = files.out;
    {
        std::ofstream file(input, std::ios::binary | std::ios::trunc);
        file.write(reinterpret_cast<const char*>(data), std::streamsize(size));
        if (!file) __builtin_trap();  // scratch space full: not the reader's fault
    }
    RtStructLoad load;
    try {
        load = readRtStruct(input, limits);
    } catch (const InputError&) {
        return 0;
    }
    // A file may declare no ROIs and read as an empty set, which no valid
    // RTSTRUCT can hold (writeRtStruct refuses it), so nothing to round-trip.
    if (load.contours.rois.empty()) return 0;
    writeRtStruct(load.contours, output);
    const RtStructLoad back = readRtStruct(output, limits);
    expectSame(load, back);
    std::remove(output.c_str());
    return 0;
}
