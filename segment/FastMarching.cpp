#include "segment/FastMarching.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <stdexcept>
#include <string>
#include <utility>

#include "segment/LocalUpdate.hpp"

namespace dfrecon {

std::vector<double> slownessFromSpeed(const std::vector<double>& speed, int vertexCount) {
    std::vector<double> slowness(std::size_t(vertexCount), 1.0);
    if (speed.empty()) return slowness;
    if (speed.size() != slowness.size())
        throw std::invalid_argument("speed has " + std::to_string(speed.size()) + " values for " +
                                    std::to_string(vertexCount) + " vertices");
    for (std::size_t v = 0; v < speed.size(); ++v) {
        if (!(speed[v] > 0) || !std::isfinite(speed[v]))
            throw std::invalid_argument("speed at vertex " + std::to_string(v) +
                                        " is not a positive number");
        slowness[v] = 1.0 / speed[v];
    }
    return slowness;
}

FastMarching::FastMarching(const UpdateStencils& stencils, const std::vector<double>& speed)
    : stencils_(stencils), slowness_(slownessFromSpeed(speed, stencils.vertexCount())) {}

GeodesicField FastMarching::solve(const std::vector<GeodesicSource>& sources,
                                  const MarchOptions& options) const {
    GeodesicField field{std::size_t(vertexCount())};
    march(field, sources, options);
    return field;
}

void FastMarching::march(GeodesicField& field, const std::vector<GeodesicSource>& sources,
                         const MarchOptions& options) const {
    const std::size_t n = std::size_t(vertexCount());
    if (field.time.size() != n || field.label.size() != n)
        throw std::invalid_argument("field does not match the mesh");
    std::vector<double>& time = field.time;
    std::vector<int>& label = field.label;
    // Untouched: a time this march has not changed (unreached, or from an
    // older march); Improved: lowered by this march, in the heap; Revisit: an
    // untouched vertex next to an improved one, queued at its own time so
    // that the stencils joining it to the improved one are evaluated once
    // both are known (the march over an older field needs this; a fresh
    // field has no finite untouched times); Settled: final in this march.
    enum State : char { Untouched, Improved, Revisit, Settled };
    std::vector<char> state(n, Untouched);
    using Entry = std::pair<double, int>;
    std::vector<Entry> heap;
    heap.reserve(1024);
    const auto push = [&heap](double t, int v) {
        heap.emplace_back(t, v);
        std::push_heap(heap.begin(), heap.end(), std::greater<>());
    };
    if (options.upwind) options.upwind->resize(n);
    for (const GeodesicSource& s : sources) {
        if (s.vertex < 0 || std::size_t(s.vertex) >= n)
            throw std::invalid_argument("source vertex " + std::to_string(s.vertex) +
                                        " out of range");
        if (!(s.time < time[std::size_t(s.vertex)])) continue;
        time[std::size_t(s.vertex)] = s.time;
        label[std::size_t(s.vertex)] = s.label;
        if (options.upwind) (*options.upwind)[std::size_t(s.vertex)] = UpwindRecord{};
        state[std::size_t(s.vertex)] = Improved;
        push(s.time, s.vertex);
    }
    std::size_t stopRemaining = 0;
    if (options.stopWhenFinal)
        stopRemaining = std::size_t(
            std::count(options.stopWhenFinal->begin(), options.stopWhenFinal->end(), char(1)));

    const std::vector<UpdateStencil>& stencils = stencils_.stencils();
    const std::vector<int>& useFirst = stencils_.useFirst();
    const std::vector<StencilUse>& uses = stencils_.uses();
    while (!heap.empty()) {
        std::pop_heap(heap.begin(), heap.end(), std::greater<>());
        const auto [t, v] = heap.back();
        heap.pop_back();
        const std::size_t vi = std::size_t(v);
        if (state[vi] == Settled || t > time[vi]) continue;  // stale entry
        if (t > options.maxTime) break;
        const bool improved = state[vi] == Improved;
        state[vi] = Settled;
        if (options.finalOrder) options.finalOrder->push_back(v);
        if (options.stopWhenFinal && (*options.stopWhenFinal)[vi] && --stopRemaining == 0) break;
        for (int k = useFirst[vi]; k < useFirst[vi + 1]; ++k) {
            const StencilUse use = uses[std::size_t(k)];
            const std::size_t c = std::size_t(use.target);
            if (state[c] == Settled) continue;
            const UpdateStencil& s = stencils[std::size_t(use.stencil)];
            const std::size_t a = std::size_t(s.a), b = std::size_t(s.b);
            const std::size_t other = a == vi ? b : a;
            if (improved && state[other] == Untouched && time[other] > t &&
                time[other] < kUnreached) {
                state[other] = Revisit;
                push(time[other], int(other));
            }
            // Known: no later than v, so final (in a march over an older
            // field too, whose untouched times are final where they are
            // earlier than the front).
            const bool knownA = time[a] <= t, knownB = time[b] <= t;
            const TriangleUpdate u =
                triangleUpdate(knownA ? time[a] : kUnreached, knownB ? time[b] : kUnreached,
                               {s.lengthA, s.lengthB, s.cosAngle}, slowness_[c],
                               knownA && knownB && label[a] == label[b]);
            if (!(u.time < time[c])) continue;
            time[c] = u.time;
            label[c] = upwindLabel(u, label[a], label[b]);
            if (options.upwind) {
                UpwindRecord& r = (*options.upwind)[c];
                r.a = u.upwind == Upwind::AlongB ? s.b : s.a;
                r.b = u.upwind == Upwind::AlongA ? s.a : s.b;
                r.weightB = u.upwind == Upwind::AcrossFace ? u.weightB : 0.0;
            }
            state[c] = Improved;
            push(u.time, use.target);
        }
    }
}

int farthestVertex(const GeodesicField& field) {
    int best = -1;
    for (std::size_t v = 0; v < field.time.size(); ++v)
        if (std::isfinite(field.time[v]) &&
            (best < 0 || field.time[v] > field.time[std::size_t(best)]))
            best = int(v);
    return best;
}

}  // namespace dfrecon
