#include "geometry/BoxGrid.hpp"

#include <algorithm>
#include <stdexcept>
#include <utility>

namespace dfrecon {

namespace {

// Cell coordinates are clamped here, so that any box (infinite, NaN) has
// cells; real scenes are far inside.
constexpr double kFarthestCell = 4e18;
// Each coordinate of a sparse key; a dense scene keeps below it too.
constexpr std::int64_t kKeyCells = std::int64_t(1) << 21;
// A dense grid may have this many cells, or a few per box if more: the
// count per cell is then cheaper than sorting the boxes' cells.
constexpr std::int64_t kDenseCells = 1 << 16;
constexpr std::int64_t kDenseCellsPerBox = 8;

}  // namespace

std::int64_t BoxGrid::cellOf(double x) const {
    const double cell = std::floor(x / cellMm_);
    if (!(cell > -kFarthestCell)) return std::int64_t(-kFarthestCell);
    if (!(cell < kFarthestCell)) return std::int64_t(kFarthestCell);
    return std::int64_t(cell);
}

BoxGrid::BoxGrid(std::vector<Box3> boxes, double cellMm)
    : boxes_(std::move(boxes)), cellMm_(cellMm), seen_(boxes_.size(), 0) {
    if (!(cellMm > 0)) throw std::invalid_argument("BoxGrid: cell size must be > 0");
    Box3 scene;
    for (const Box3& box : boxes_) scene.add(box);
    const std::int64_t sceneLo[3] = {cellOf(scene.lo.x), cellOf(scene.lo.y), cellOf(scene.lo.z)};
    const std::int64_t sceneHi[3] = {cellOf(scene.hi.x), cellOf(scene.hi.y), cellOf(scene.hi.z)};
    const std::int64_t denseLimit =
        std::max(kDenseCells, kDenseCellsPerBox * std::int64_t(boxes_.size()));
    std::int64_t cells = 1;
    for (int a = 0; a < 3 && dense_; ++a) {
        lo_[a] = sceneLo[a];
        n_[a] = boxes_.empty() ? 0 : sceneHi[a] - sceneLo[a] + 1;
        dense_ = n_[a] < kKeyCells && (cells *= n_[a]) <= denseLimit;
    }
    if (dense_) {
        // Counted per cell, then listed cell by cell, items rising.
        starts_.assign(std::size_t(cells) + 1, 0);
        for (const Box3& box : boxes_)
            forEachCell(box, [&](std::uint64_t key) { ++starts_[key + 1]; });
        for (std::size_t c = 1; c < starts_.size(); ++c) starts_[c] += starts_[c - 1];
        items_.resize(starts_.back());
        std::vector<std::uint32_t> next(starts_.begin(), starts_.end() - 1);
        for (std::size_t i = 0; i < boxes_.size(); ++i)
            forEachCell(boxes_[i],
                        [&](std::uint64_t key) { items_[next[key]++] = std::uint32_t(i); });
        return;
    }
    // Sorted by cell, then item: each cell's items rising, as listed.
    std::vector<std::pair<std::uint64_t, std::uint32_t>> entries;
    for (std::size_t i = 0; i < boxes_.size(); ++i)
        forEachCell(boxes_[i], [&](std::uint64_t key) { entries.emplace_back(key, i); });
    std::sort(entries.begin(), entries.end());
    items_.reserve(entries.size());
    for (std::size_t e = 0; e < entries.size(); ++e) {
        if (e == 0 || entries[e].first != entries[e - 1].first) {
            keys_.push_back(entries[e].first);
            starts_.push_back(std::uint32_t(e));
        }
        items_.push_back(entries[e].second);
    }
    starts_.push_back(std::uint32_t(entries.size()));
}

std::pair<std::uint32_t, std::uint32_t> BoxGrid::itemsOf(std::uint64_t key) const {
    if (dense_) return {starts_[key], starts_[key + 1]};
    const auto found = std::lower_bound(keys_.begin(), keys_.end(), key);
    if (found == keys_.end() || *found != key) return {0, 0};
    const std::size_t k = std::size_t(found - keys_.begin());
    return {starts_[k], starts_[k + 1]};
}

BoxGrid BoxGrid::sizedToBoxes(std::vector<Box3> boxes) {
    std::vector<double> extents(boxes.size());
    Box3 scene;
    for (std::size_t i = 0; i < boxes.size(); ++i) {
        const Vec3 e = boxes[i].hi - boxes[i].lo;
        extents[i] = std::max({e.x, e.y, e.z});
        scene.add(boxes[i]);
    }
    double cellMm = 1e-9;
    if (!boxes.empty()) {
        const auto middle = extents.begin() + std::ptrdiff_t(extents.size() / 2);
        std::nth_element(extents.begin(), middle, extents.end());
        const Vec3 size = scene.hi - scene.lo;
        cellMm = std::max({cellMm, *middle, size.x / 64, size.y / 64, size.z / 64});
    }
    return BoxGrid(std::move(boxes), cellMm);
}

}  // namespace dfrecon
