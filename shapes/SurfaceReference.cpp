#include "shapes/SurfaceReference.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace dfrecon {

namespace {

long long cellOf(double v, double cell) {
    return (long long)std::floor(v / cell);
}

}  // namespace

SurfaceReference::SurfaceReference(const AnalyticShape& shape, std::size_t samples, double cellMm)
    : shape_(shape), cell_(cellMm) {
    if (shape.distanceIsExact()) return;
    samples_ = sampleSurface(shape, samples, 29);
    for (int a = 0; a < 3; ++a) {
        lo_[a] = std::numeric_limits<long long>::max();
        hi_[a] = std::numeric_limits<long long>::min();
    }
    for (std::size_t s = 0; s < samples_.size(); ++s) {
        const long long c[3] = {cellOf(samples_[s].x, cell_), cellOf(samples_[s].y, cell_),
                                cellOf(samples_[s].z, cell_)};
        for (int a = 0; a < 3; ++a) {
            lo_[a] = std::min(lo_[a], c[a]);
            hi_[a] = std::max(hi_[a], c[a]);
        }
        grid_[key(c[0], c[1], c[2])].push_back(s);
    }
}

long long SurfaceReference::key(long long i, long long j, long long k) const {
    // Cells are within the samples' box: a dense mixed-radix index.
    const long long nx = hi_[0] - lo_[0] + 1, ny = hi_[1] - lo_[1] + 1;
    return ((k - lo_[2]) * ny + (j - lo_[1])) * nx + (i - lo_[0]);
}

std::size_t SurfaceReference::nearestSample(Vec3 p) const {
    const long long c[3] = {cellOf(p.x, cell_), cellOf(p.y, cell_), cellOf(p.z, cell_)};
    std::size_t best = 0;
    double best2 = INFINITY;
    // Shells of cells at growing Chebyshev radius; after shell r, every
    // sample not yet seen is at least r cells away.
    const long long reach =
        std::max({hi_[0] - lo_[0], hi_[1] - lo_[1], hi_[2] - lo_[2]}) +
        std::max({std::abs(c[0] - lo_[0]), std::abs(c[1] - lo_[1]), std::abs(c[2] - lo_[2])}) + 1;
    for (long long r = 0; r <= reach; ++r) {
        for (long long i = c[0] - r; i <= c[0] + r; ++i)
            for (long long j = c[1] - r; j <= c[1] + r; ++j)
                for (long long k = c[2] - r; k <= c[2] + r; ++k) {
                    if (std::max({std::abs(i - c[0]), std::abs(j - c[1]), std::abs(k - c[2])}) != r)
                        continue;
                    if (i < lo_[0] || i > hi_[0] || j < lo_[1] || j > hi_[1] || k < lo_[2] ||
                        k > hi_[2])
                        continue;
                    const auto it = grid_.find(key(i, j, k));
                    if (it == grid_.end()) continue;
                    for (std::size_t s : it->second) {
                        const Vec3 d = samples_[s] - p;
                        if (dot(d, d) < best2) {
                            best2 = dot(d, d);
                            best = s;
                        }
                    }
                }
        if (best2 <= double(r) * cell_ * double(r) * cell_) break;
    }
    return best;
}

Vec3 SurfaceReference::gradient(Vec3 p) const {
    const double h = 1e-6;
    auto f = [&](Vec3 q) { return shape_.signedDistance(q); };
    return (0.5 / h) * Vec3{f({p.x + h, p.y, p.z}) - f({p.x - h, p.y, p.z}),
                            f({p.x, p.y + h, p.z}) - f({p.x, p.y - h, p.z}),
                            f({p.x, p.y, p.z + h}) - f({p.x, p.y, p.z - h})};
}

// Newton steps along the gradient onto the zero set (from a point already
// within a small fraction of a millimetre of it).
Vec3 SurfaceReference::project(Vec3 p) const {
    for (int iteration = 0; iteration < 20; ++iteration) {
        const double d = shape_.signedDistance(p);
        if (std::abs(d) < 1e-13) break;
        const Vec3 g = gradient(p);
        const double norm2 = dot(g, g);
        if (norm2 == 0) break;
        p = p - (d / norm2) * g;
    }
    return p;
}

Vec3 SurfaceReference::nearestPoint(Vec3 p) const {
    if (shape_.distanceIsExact() || samples_.empty()) return p;
    const Vec3 start = samples_[nearestSample(p)];
    Vec3 x = start;
    for (int iteration = 0; iteration < 100; ++iteration) {
        const Vec3 g = gradient(x);
        const double norm = length(g);
        if (norm == 0) break;
        const Vec3 n = (1 / norm) * g;
        const Vec3 next = project(p - dot(p - x, n) * n);
        const double moved = length(next - x);
        x = next;
        if (moved < 1e-12) break;
    }
    const bool onSurface = std::abs(shape_.signedDistance(x)) < 1e-9;
    return onSurface && length(p - x) < length(p - start) ? x : start;
}

double SurfaceReference::distance(Vec3 p) const {
    if (shape_.distanceIsExact() || samples_.empty()) return std::abs(shape_.signedDistance(p));
    return length(p - nearestPoint(p));
}

}  // namespace dfrecon
