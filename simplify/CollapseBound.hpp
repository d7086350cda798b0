#pragma once
// What one halfedge collapse would make, and how far its triangles stray
// from the original surface — shared by the Decimater module (any time)
// and the initial batch (unchanged mesh), so both compute the same bound.
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "geometry/TriMesh.hpp"
#include "simplify/DeviationBound.hpp"

namespace dfrecon {

struct NewTriangle {
    std::array<std::uint32_t, 3> ids;  // vertex indices after the collapse
    Vec3 p[3];
};

/// A created triangle whose doubled area is at most this fraction of its
/// longest edge squared is a sliver (the kernel batch gets the same number).
constexpr double kSliverAreaRatio = 1e-10;

/// The triangles collapsing `v0v1` (its from-vertex onto its to-vertex)
/// creates: the from-vertex's faces other than the two on the edge, the
/// from-vertex replaced. False if one would be a sliver, whose orientation
/// rounding can flip.
bool trianglesAfterCollapse(const TriMesh& mesh, TriMesh::HalfedgeHandle v0v1,
                            std::vector<NewTriangle>& out);

/// deviationBound of triangles by vertex ids, remembered: the Decimater
/// evaluates the same candidate triangle again and again as the queue is
/// updated around it, and with the original surface fixed its bound never
/// changes. Also a lower bound of it, much cheaper, for the lazy queue.
/// Values are kept as computed (a double costs no room: the entry is
/// padded to 16 bytes either way). Only for meshes of fewer than 2^21
/// vertices (else not used).
class DeviationCache {
  public:
    /// The cached bound of the triangle with these vertex ids, or computes it.
    double bound(const NewTriangle& t, const DeviationSurface& original,
                 const DeviationLimits& limits);

    /// deviationBoundWithin(t, maxPieces, enough), remembered: the bound
    /// when known or found within maxPieces pieces, else a lower bound of it
    /// (the stored one when it came from as many pieces or more, or is above
    /// `enough`). Above limits.limitMm only when the bound is. A look-up or
    /// O(maxPieces · log T).
    double estimate(const NewTriangle& t, const DeviationSurface& original,
                    const DeviationLimits& limits, std::size_t maxPieces, double enough = INFINITY);

    /// surfaceDeviationLowerBound (below) with this cache.
    float largestEstimate(const std::vector<NewTriangle>& created, const DeviationSurface& original,
                          const DeviationLimits& limits, std::size_t maxPieces, double enough);

  private:
    struct Known {
        double value;
        /// The pieces a lower bound came from (it grows with them); SIZE_MAX
        /// for the bound itself, 0 for nothing known yet.
        std::size_t pieces;
    };
    /// t's entry (created empty), or null when t's ids are too large to
    /// key. Entries move when the table grows: at most `reserve`d more
    /// entries may be created while one is held.
    Known* entryOf(const NewTriangle& t);
    void reserve(std::size_t more);
    double estimate(Known* known, const NewTriangle& t, const DeviationSurface& original,
                    const DeviationLimits& limits, std::size_t maxPieces, double enough);

    // Open addressing with linear probing, at most half full: one cache
    // line per look-up, where std::unordered_map's nodes cost two misses
    // (it was 5 % of simplification). Key 0 marks an empty slot; no
    // triangle has it (its three ids differ).
    struct Slot {
        std::uint64_t key = 0;
        Known known{0, 0};
    };
    std::vector<Slot> slots_;
    std::size_t used_ = 0;
};

/// Direction (a) of a collapse's error: the largest deviationBound of the
/// created triangles from the original, or -1 when one exceeds
/// limits.limitMm. With a cache, bounds of triangles seen before are reused.
/// O(created · pieces · log T).
float surfaceDeviation(const std::vector<NewTriangle>& created, const DeviationSurface& original,
                       const DeviationLimits& limits, DeviationCache* cache = nullptr);

/// A lower bound of surfaceDeviation(created, ..., cache): the largest
/// DeviationCache::estimate of the created triangles, or -1 when one shows
/// the deviation over limits.limitMm. Stops at the first value above
/// `enough`, the triangles known to be worst first: a caller that only asks
/// whether the deviation is at most `enough` needs no more. Equal to
/// surfaceDeviation when maxPieces is SIZE_MAX and nothing exceeds
/// `enough`. O(created) look-ups or O(created · maxPieces · log T).
float surfaceDeviationLowerBound(const std::vector<NewTriangle>& created,
                                 const DeviationSurface& original, const DeviationLimits& limits,
                                 DeviationCache& cache, std::size_t maxPieces,
                                 double enough = INFINITY);

inline Vec3 toVec3(const TriMesh::Point& p) {
    return {p[0], p[1], p[2]};
}

}  // namespace dfrecon
