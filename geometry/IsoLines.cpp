#include "geometry/IsoLines.hpp"

#include <algorithm>
#include <cstdint>
#include <stdexcept>

namespace dfrecon {

namespace {

// The padded lattice: cells (i, j) for i in [-1, W-1], j in [-1, H-1] join
// samples (i, j), (i+1, j), (i+1, j+1), (i, j+1); samples outside the image
// are positive, so every isoline closes.
class Lattice {
  public:
    Lattice(const std::vector<float>& values, int width, int height, const SampleLattice& placement,
            float minPositive)
        : values_(values),
          width_(width),
          height_(height),
          placement_(placement),
          minPositive_(minPositive) {}

    float at(int i, int j) const {
        if (i < 0 || j < 0 || i >= width_ || j >= height_) return 1.0f;
        const float v = values_[std::size_t(j) * std::size_t(width_) + std::size_t(i)];
        // A zero sample would put crossings of neighbouring edges on the same
        // point; nudging it to the positive side keeps polygons simple.
        return v < 0 ? v : std::max(v, minPositive_);
    }
    // Crossing points are named by the lattice edge they lie on: the edge from
    // sample (i, j) to (i+1, j) is 2·key(i, j), the one to (i, j+1) is 2·key + 1.
    std::uint32_t key(int i, int j) const {
        return std::uint32_t((j + 1) * (width_ + 2) + (i + 1));
    }
    std::size_t keyCount() const { return 2 * std::size_t(width_ + 2) * std::size_t(height_ + 2); }
    Point2 crossing(std::uint32_t edge) const {
        const int w = width_ + 2;
        const int i = int(edge / 2) % w - 1, j = int(edge / 2) / w - 1;
        const int i2 = (edge & 1) ? i : i + 1, j2 = (edge & 1) ? j + 1 : j;
        const double a = at(i, j), b = at(i2, j2);
        const double t = a / (a - b);
        const Point2 p = placement_.at(i, j), q = placement_.at(i2, j2);
        return p + t * (q - p);
    }

  private:
    const std::vector<float>& values_;
    int width_, height_;
    SampleLattice placement_;
    float minPositive_;
};

}  // namespace

std::vector<Polygon> negativeRegionBorders(const std::vector<float>& values, int width, int height,
                                           const SampleLattice& placement, float minPositive) {
    if (width < 0 || height < 0 || values.size() != std::size_t(width) * std::size_t(height))
        throw std::invalid_argument("negativeRegionBorders: image size does not match the values");
    if (!(placement.stepMm.x > 0) || !(placement.stepMm.y > 0))
        throw std::invalid_argument("negativeRegionBorders: sample steps must be positive");
    // Edge keys are 32-bit: refuse images whose padded lattice would overflow.
    if (2 * (std::uint64_t(width) + 2) * (std::uint64_t(height) + 2) >= 0xffffffffu)
        throw std::invalid_argument("negativeRegionBorders: image too large");
    const Lattice lattice(values, width, height, placement, minPositive);
    constexpr std::uint32_t kNone = 0xffffffffu;
    std::vector<std::uint32_t> next(lattice.keyCount(), kNone);
    std::vector<std::uint32_t> starts;

    for (int j = -1; j < height; ++j) {
        for (int i = -1; i < width; ++i) {
            // Corners and the edges after each, counter-clockwise from the
            // lower left: edge k runs from corner k to corner k+1.
            const float v[4] = {lattice.at(i, j), lattice.at(i + 1, j), lattice.at(i + 1, j + 1),
                                lattice.at(i, j + 1)};
            const std::uint32_t edge[4] = {2 * lattice.key(i, j), 2 * lattice.key(i + 1, j) + 1,
                                           2 * lattice.key(i, j + 1), 2 * lattice.key(i, j) + 1};
            int exits[2], entries[2], nExit = 0, nEntry = 0;
            for (int k = 0; k < 4; ++k) {
                const bool from = v[k] < 0, to = v[(k + 1) % 4] < 0;
                if (from && !to) exits[nExit++] = k;
                if (!from && to) entries[nEntry++] = k;
            }
            if (nExit == 0) continue;
            // A segment leaves where the walk exits the negative region and
            // rejoins where it re-enters, so negative stays on its left.
            // Saddles: joined negatives pair each exit with the next entry,
            // separated ones with the previous.
            const bool joined = nExit == 2 && (v[0] + v[1] + v[2] + v[3]) < 0;
            for (int e = 0; e < nExit; ++e) {
                int best = -1;
                for (int step = 1; step < 4 && best < 0; ++step) {
                    const int k =
                        joined || nExit == 1 ? (exits[e] + step) % 4 : (exits[e] - step + 4) % 4;
                    for (int f = 0; f < nEntry; ++f)
                        if (entries[f] == k) best = k;
                }
                const std::uint32_t from = edge[exits[e]], to = edge[best];
                next[from] = to;
                starts.push_back(from);
            }
        }
    }

    std::vector<Polygon> polygons;
    for (std::uint32_t start : starts) {
        if (next[start] == kNone) continue;  // already part of a traced loop
        Polygon polygon;
        std::uint32_t edge = start;
        while (next[edge] != kNone) {
            const Point2 p = lattice.crossing(edge);
            if (polygon.empty() || p != polygon.back()) polygon.push_back(p);
            const std::uint32_t following = next[edge];
            next[edge] = kNone;
            edge = following;
        }
        if (polygon.size() > 1 && polygon.front() == polygon.back()) polygon.pop_back();
        if (polygon.size() >= 3) polygons.push_back(std::move(polygon));
    }
    return polygons;
}

}  // namespace dfrecon
