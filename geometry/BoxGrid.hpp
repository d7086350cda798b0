#pragma once
// Boxes bucketed on a uniform grid: which of them may overlap a query box.
// For repeated local queries on a mesh whose vertices move within known
// bounds (give each item a box that holds it wherever it may go), where
// rebuilding a hierarchy per query round would cost more than the queries.
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "geometry/Box3.hpp"

namespace dfrecon {

class BoxGrid {
  public:
    /// Buckets `boxes` (item i has boxes[i]) on cells of `cellMm` a side
    /// (> 0). O(Σ cells each box covers).
    BoxGrid(std::vector<Box3> boxes, double cellMm);

    /// A grid whose cells are about a box across (the median box's largest
    /// side), never so small that the boxes' scene spans more than 64 cells
    /// a side: each box covers a few cells, and a query visits few. O(n)
    /// plus the constructor's work.
    static BoxGrid sizedToBoxes(std::vector<Box3> boxes);

    /// Calls visit(i) once for every item whose box overlaps `query`.
    /// O(cells the query covers + items in them).
    template <class Visit>
    void overlapping(const Box3& query, Visit&& visit) const {
        ++stamp_;
        forEachCell(query, [&](std::uint64_t key) {
            const auto found = cells_.find(key);
            if (found == cells_.end()) return;
            for (std::uint32_t i : found->second) {
                if (seen_[i] == stamp_) continue;
                seen_[i] = stamp_;
                if (boxes_[i].overlaps(query)) visit(i);
            }
        });
    }

  private:
    template <class F>
    void forEachCell(const Box3& box, F&& f) const;

    std::vector<Box3> boxes_;
    double cellMm_;
    std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> cells_;
    mutable std::vector<std::uint32_t> seen_;  // per item: the last query that listed it
    mutable std::uint32_t stamp_ = 0;
};

template <class F>
void BoxGrid::forEachCell(const Box3& box, F&& f) const {
    auto cell = [&](double x) { return std::int64_t(std::floor(x / cellMm_)); };
    // 21 bits a coordinate: cells wrap past ±10⁶ cells, which only costs
    // spurious candidates (the box test drops them).
    auto key = [](std::int64_t i, std::int64_t j, std::int64_t k) {
        const std::uint64_t m = (1u << 21) - 1;
        return (std::uint64_t(i) & m) | ((std::uint64_t(j) & m) << 21) |
               ((std::uint64_t(k) & m) << 42);
    };
    for (std::int64_t k = cell(box.lo.z); k <= cell(box.hi.z); ++k)
        for (std::int64_t j = cell(box.lo.y); j <= cell(box.hi.y); ++j)
            for (std::int64_t i = cell(box.lo.x); i <= cell(box.hi.x); ++i) f(key(i, j, k));
}

}  // namespace dfrecon
