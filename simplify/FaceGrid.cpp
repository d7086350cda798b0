#include "simplify/FaceGrid.hpp"

#include <cmath>

namespace dfrecon {

FaceGrid::CellRange FaceGrid::cellsOf(const Box3& box) const {
    CellRange r{};
    for (int axis = 0; axis < 3; ++axis) {
        r.lo[axis] = std::int64_t(std::floor(box.lo[axis] / cellMm_));
        r.hi[axis] = std::int64_t(std::floor(box.hi[axis] / cellMm_));
    }
    return r;
}

std::uint64_t FaceGrid::key(std::int64_t i, std::int64_t j, std::int64_t k) {
    // 21 bits per axis: ±1e6 cells, far beyond any scanner's field of view.
    auto bits = [](std::int64_t v) { return std::uint64_t(v + (1 << 20)) & 0x1fffff; };
    return bits(i) | bits(j) << 21 | bits(k) << 42;
}

void FaceGrid::insert(int face, const Box3& box) {
    if (std::size_t(face) >= seen_.size()) seen_.resize(std::size_t(face) + 1, 0);
    const CellRange r = cellsOf(box);
    for (std::int64_t i = r.lo[0]; i <= r.hi[0]; ++i)
        for (std::int64_t j = r.lo[1]; j <= r.hi[1]; ++j)
            for (std::int64_t k = r.lo[2]; k <= r.hi[2]; ++k) cells_[key(i, j, k)].push_back(face);
}

}  // namespace dfrecon
