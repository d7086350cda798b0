#pragma once
// Boxes bucketed on a uniform grid: which of them may overlap a query box.
// For repeated local queries on a mesh whose vertices move within known
// bounds (give each item a box that holds it wherever it may go), where
// rebuilding a hierarchy per query round would cost more than the queries.
#include <algorithm>
#include <cstdint>
#include <utility>
#include <vector>

#include "geometry/Box3.hpp"

namespace dfrecon {

class BoxGrid {
  public:
    /// Buckets `boxes` (item i has boxes[i]) on cells of `cellMm` a side
    /// (> 0). O(Σ cells each box covers), two passes and three arrays (a
    /// count per cell, then the items cell by cell): no allocation per cell.
    BoxGrid(std::vector<Box3> boxes, double cellMm);

    /// A grid whose cells are about a box across (the median box's largest
    /// side), never so small that the boxes' scene spans more than 64 cells
    /// a side: each box covers a few cells, and a query visits few. O(n)
    /// plus the constructor's work.
    static BoxGrid sizedToBoxes(std::vector<Box3> boxes);

    /// Calls visit(i) once for every item whose box overlaps `query`: cell
    /// by cell (z, then y, then x, each rising), within a cell by rising i,
    /// each item where it is first met. O(cells the query covers + items in
    /// them).
    template <class Visit>
    void overlapping(const Box3& query, Visit&& visit) const {
        ++stamp_;
        forEachCell(query, [&](std::uint64_t key) {
            const auto [from, to] = itemsOf(key);
            for (std::uint32_t k = from; k < to; ++k) {
                const std::uint32_t i = items_[k];
                if (seen_[i] == stamp_) continue;
                seen_[i] = stamp_;
                if (boxes_[i].overlaps(query)) visit(i);
            }
        });
    }

  private:
    /// Calls f(key) for every cell that `box` covers, in the order
    /// overlapping() promises. Dense grids skip cells outside the scene
    /// (they hold nothing).
    template <class F>
    void forEachCell(const Box3& box, F&& f) const;
    /// The range of items_ that lists the cell `key`.
    std::pair<std::uint32_t, std::uint32_t> itemsOf(std::uint64_t key) const;

    std::int64_t cellOf(double x) const;

    std::vector<Box3> boxes_;
    double cellMm_;
    // Dense (the usual case): the scene's cells, lowest cell lo_, n_ a
    // side, cell (i, j, k) at key i + n_x (j + n_y k), starts_ one per cell
    // and one more. Sparse (a scene of far more cells than boxes, or one
    // whose cells do not fit 21 bits a side): keys_ lists the cells that
    // hold items, ascending, and starts_ one per key; each coordinate wraps
    // at 2^21 cells, which only costs spurious candidates.
    bool dense_ = true;
    std::int64_t lo_[3] = {0, 0, 0}, n_[3] = {0, 0, 0};
    std::vector<std::uint64_t> keys_;
    std::vector<std::uint32_t> starts_;
    std::vector<std::uint32_t> items_;         // cell by cell, rising within one
    mutable std::vector<std::uint32_t> seen_;  // per item: the last query that listed it
    mutable std::uint32_t stamp_ = 0;
};

template <class F>
void BoxGrid::forEachCell(const Box3& box, F&& f) const {
    std::int64_t lo[3] = {cellOf(box.lo.x), cellOf(box.lo.y), cellOf(box.lo.z)};
    std::int64_t hi[3] = {cellOf(box.hi.x), cellOf(box.hi.y), cellOf(box.hi.z)};
    if (dense_) {
        for (int a = 0; a < 3; ++a) {
            lo[a] = std::max(lo[a] - lo_[a], std::int64_t(0));
            hi[a] = std::min(hi[a] - lo_[a], n_[a] - 1);
        }
        for (std::int64_t k = lo[2]; k <= hi[2]; ++k)
            for (std::int64_t j = lo[1]; j <= hi[1]; ++j)
                for (std::int64_t i = lo[0]; i <= hi[0]; ++i)
                    f(std::uint64_t(i + n_[0] * (j + n_[1] * k)));
        return;
    }
    const std::uint64_t m = (1u << 21) - 1;
    for (std::int64_t k = lo[2]; k <= hi[2]; ++k)
        for (std::int64_t j = lo[1]; j <= hi[1]; ++j)
            for (std::int64_t i = lo[0]; i <= hi[0]; ++i)
                f((std::uint64_t(i) & m) | ((std::uint64_t(j) & m) << 21) |
                  ((std::uint64_t(k) & m) << 42));
}

}  // namespace dfrecon
