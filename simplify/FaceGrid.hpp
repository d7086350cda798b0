#pragma once
// A uniform hash grid of a changing set of triangles, for "which faces are
// near this box" while a mesh is being decimated. Entries are never removed:
// callers re-insert a face whose geometry changed and filter the candidates
// (deleted faces, stale boxes) by an exact test, which they need anyway.
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "geometry/TriangleBvh.hpp"

namespace dfrecon {

class FaceGrid {
  public:
    /// `cellMm`: the cell side; about the typical face size works best.
    explicit FaceGrid(double cellMm = 1.0) : cellMm_(cellMm) {}

    /// Forgets every face and switches to cells of `cellMm`.
    void reset(double cellMm) {
        cellMm_ = cellMm;
        cells_.clear();
        seen_.clear();
    }

    /// Registers `face` in every cell `box` touches. O(cells touched).
    void insert(int face, const Box3& box);

    /// Calls visit(face) once for every face registered in a cell `box`
    /// touches (a superset of the faces whose boxes overlap it).
    template <class Visit>
    void query(const Box3& box, Visit&& visit);

  private:
    struct CellRange {
        std::int64_t lo[3], hi[3];
    };
    CellRange cellsOf(const Box3& box) const;
    static std::uint64_t key(std::int64_t i, std::int64_t j, std::int64_t k);

    double cellMm_;
    std::unordered_map<std::uint64_t, std::vector<int>> cells_;
    std::vector<std::uint32_t> seen_;  // per face: the query that last saw it
    std::uint32_t query_ = 0;
};

template <class Visit>
void FaceGrid::query(const Box3& box, Visit&& visit) {
    ++query_;
    const CellRange r = cellsOf(box);
    for (std::int64_t i = r.lo[0]; i <= r.hi[0]; ++i)
        for (std::int64_t j = r.lo[1]; j <= r.hi[1]; ++j)
            for (std::int64_t k = r.lo[2]; k <= r.hi[2]; ++k) {
                const auto cell = cells_.find(key(i, j, k));
                if (cell == cells_.end()) continue;
                for (int face : cell->second) {
                    if (seen_[std::size_t(face)] == query_) continue;
                    seen_[std::size_t(face)] = query_;
                    visit(face);
                }
            }
}

}  // namespace dfrecon
