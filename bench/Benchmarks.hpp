#pragma once
// The benchmarks of dfrecon-bench. Each prints JSON lines to stdout with at
// least {bench, case, system, seconds} and compares against its baseline in
// the same run; none asserts anything.
#include <algorithm>
#include <chrono>
#include <string>

namespace dfrecon::bench {

int benchFields(const std::string& device);
int benchSlicesIO();
int benchRecon(const std::string& device);
int benchSimplify(const std::string& device);
int benchRtStruct();
int benchSdm(const std::string& device);
int benchSegment(const std::string& device);
/// `route` empty: every case, each route in a process of its own; else
/// CASE:dfrecon or CASE:raster, one route of one case in this process (how
/// the suite starts those processes), printed as one JSON object.
int benchStructureSet(const std::string& device, const std::string& route = "");
int benchCompare(const std::string& device);
int benchMargin(const std::string& device);
int benchLabelMaps(const std::string& device);
int benchNeighbours(const std::string& device);
/// `setsDir` empty: build/truth-sets, made by scripts/truth_sets.sh where
/// missing; `onlySet` empty: every set there.
int benchTruth(const std::string& device, const std::string& setsDir, const std::string& onlySet);
/// Every area of whole atlases (build/atlas-sets, made by scripts/truth_sets.sh --whole
/// where missing): volume against contour volume and truth.
int benchAtlases(const std::string& device);

/// Wall-clock seconds of the fastest of `runs` calls of `work`.
template <class F>
double bestSeconds(int runs, F&& work) {
    double best = 1e300;
    for (int r = 0; r < runs; ++r) {
        const auto start = std::chrono::steady_clock::now();
        work();
        const std::chrono::duration<double> elapsed = std::chrono::steady_clock::now() - start;
        best = std::min(best, elapsed.count());
    }
    return best;
}

}  // namespace dfrecon::bench
