#pragma once
// Disjoint sets over indices 0..n-1 (path halving), for grouping triangles
// into components and contours into connected pieces.
#include <cstddef>
#include <numeric>
#include <vector>

namespace dfrecon {

class UnionFind {
  public:
    explicit UnionFind(std::size_t n = 0) { reset(n); }
    /// n singletons again, keeping the storage (for one small set after
    /// another). O(n).
    void reset(std::size_t n) {
        parent_.resize(n);
        std::iota(parent_.begin(), parent_.end(), std::size_t(0));
    }
    /// The representative of x's set; amortised nearly O(1).
    std::size_t find(std::size_t x) {
        while (parent_[x] != x) x = parent_[x] = parent_[parent_[x]];
        return x;
    }
    void join(std::size_t a, std::size_t b) { parent_[find(a)] = find(b); }

  private:
    std::vector<std::size_t> parent_;
};

}  // namespace dfrecon
