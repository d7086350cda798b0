#include "simplify/CollapseBound.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace dfrecon {

bool trianglesAfterCollapse(const TriMesh& mesh, TriMesh::HalfedgeHandle v0v1,
                            std::vector<NewTriangle>& out) {
    out.clear();
    const auto v0 = mesh.from_vertex_handle(v0v1), v1 = mesh.to_vertex_handle(v0v1);
    const TriMesh::FaceHandle fl = mesh.face_handle(v0v1), fr = mesh.opposite_face_handle(v0v1);
    for (auto f : mesh.vf_range(v0)) {
        if (f == fl || f == fr) continue;
        NewTriangle t;
        int k = 0;
        for (auto v : mesh.fv_range(f)) {
            const auto moved = v == v0 ? v1 : v;
            t.ids[std::size_t(k)] = std::uint32_t(moved.idx());
            t.p[k++] = toVec3(mesh.point(moved));
        }
        const Vec3 e0 = t.p[1] - t.p[0], e1 = t.p[2] - t.p[0], e2 = t.p[2] - t.p[1];
        const double longest2 = std::max({dot(e0, e0), dot(e1, e1), dot(e2, e2)});
        if (length(cross(e0, e1)) <= kSliverAreaRatio * longest2) return false;
        out.push_back(t);
    }
    return true;
}

namespace {

constexpr std::uint32_t kIdLimit = 1u << 21;

bool cacheable(const NewTriangle& t) {
    return t.ids[0] < kIdLimit && t.ids[1] < kIdLimit && t.ids[2] < kIdLimit;
}

// The first slot to probe for `key` in a table of `size` (a power of two)
// slots: Fibonacci hashing, as the keys' low bits are one vertex id.
std::size_t slotOf(std::uint64_t key, std::size_t size) {
    return std::size_t((key * 0x9E3779B97F4A7C15ull) >> 32) & (size - 1);
}

std::uint64_t keyOf(const NewTriangle& t) {
    std::array<std::uint32_t, 3> ids = t.ids;
    std::sort(ids.begin(), ids.end());
    return std::uint64_t(ids[0]) | std::uint64_t(ids[1]) << 21 | std::uint64_t(ids[2]) << 42;
}

}  // namespace

double DeviationCache::bound(const NewTriangle& t, const DeviationSurface& original,
                             const DeviationLimits& limits) {
    return estimate(t, original, limits, SIZE_MAX);
}

double DeviationCache::estimate(const NewTriangle& t, const DeviationSurface& original,
                                const DeviationLimits& limits, std::size_t maxPieces,
                                double enough) {
    return estimate(entryOf(t), t, original, limits, maxPieces, enough);
}

void DeviationCache::reserve(std::size_t more) {
    if (2 * (used_ + more) <= slots_.size()) return;
    std::size_t size = std::max<std::size_t>(1024, slots_.size());
    while (2 * (used_ + more) > size) size *= 2;
    std::vector<Slot> old(size);
    old.swap(slots_);
    for (const Slot& slot : old) {
        if (slot.key == 0) continue;
        std::size_t i = slotOf(slot.key, slots_.size());
        while (slots_[i].key != 0) i = (i + 1) & (slots_.size() - 1);
        slots_[i] = slot;
    }
}

DeviationCache::Known* DeviationCache::entryOf(const NewTriangle& t) {
    if (!cacheable(t)) return nullptr;
    reserve(1);
    const std::uint64_t key = keyOf(t);
    std::size_t i = slotOf(key, slots_.size());
    while (slots_[i].key != key && slots_[i].key != 0) i = (i + 1) & (slots_.size() - 1);
    if (slots_[i].key == 0) {
        slots_[i].key = key;
        ++used_;
    }
    return &slots_[i].known;
}

double DeviationCache::estimate(Known* entry, const NewTriangle& t,
                                const DeviationSurface& original, const DeviationLimits& limits,
                                std::size_t maxPieces, double enough) {
    const auto compute = [&] {
        return deviationBoundWithin(original, t.p[0], t.p[1], t.p[2], limits, {maxPieces, enough});
    };
    if (!entry) return compute().value;
    Known& known = *entry;
    if (known.pieces >= maxPieces || (known.pieces > 0 && known.value > enough)) return known.value;
    const DeviationEstimate e = compute();
    // Kept as computed, so a cached bound is the bound itself, compared with
    // the limit as the batch's are. Pieces come in the same order in every
    // run, so the run that took more pieces has the larger lower bound.
    if (e.complete)
        known = {e.value, SIZE_MAX};
    else if (e.piecesTaken >= known.pieces)
        known = {e.value, e.piecesTaken};
    return known.value;
}

float DeviationCache::largestEstimate(const std::vector<NewTriangle>& created,
                                      const DeviationSurface& original,
                                      const DeviationLimits& limits, std::size_t maxPieces,
                                      double enough) {
    // Worst known first: the first estimate is then the likeliest to pass
    // `enough`, and what is known may pass it already.
    struct Triangle {
        Known* entry;
        double known;
        std::size_t index;
    };
    std::array<Triangle, 32> order;
    const std::size_t n = std::min(created.size(), order.size());
    reserve(n);  // the entries below stay put
    for (std::size_t i = 0; i < n; ++i) {
        Known* entry = entryOf(created[i]);
        order[i] = {entry, entry ? entry->value : 0.0, i};
    }
    std::sort(order.begin(), order.begin() + std::ptrdiff_t(n), [](const auto& x, const auto& y) {
        return x.known != y.known ? x.known > y.known : x.index < y.index;
    });
    double largest = 0;
    for (std::size_t k = 0; k < created.size(); ++k) {
        const NewTriangle& t = created[k < n ? order[k].index : k];
        Known* entry = k < n ? order[k].entry : entryOf(t);
        const double d = estimate(entry, t, original, limits, maxPieces, enough);
        if (d > limits.limitMm) return -1;
        largest = std::max(largest, d);
        if (largest > enough) break;
    }
    return float(largest);
}

float surfaceDeviation(const std::vector<NewTriangle>& created, const DeviationSurface& original,
                       const DeviationLimits& limits, DeviationCache* cache) {
    double largest = 0;
    for (const NewTriangle& t : created) {
        const double d = cache ? cache->bound(t, original, limits)
                               : deviationBound(original, t.p[0], t.p[1], t.p[2], limits);
        if (d > limits.limitMm) return -1;
        largest = std::max(largest, d);
    }
    return float(largest);
}

float surfaceDeviationLowerBound(const std::vector<NewTriangle>& created,
                                 const DeviationSurface& original, const DeviationLimits& limits,
                                 DeviationCache& cache, std::size_t maxPieces, double enough) {
    return cache.largestEstimate(created, original, limits, maxPieces, enough);
}

}  // namespace dfrecon
