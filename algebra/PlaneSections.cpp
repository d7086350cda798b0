#include "algebra/PlaneSections.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "geometry/IsoLines.hpp"

namespace dfrecon {

namespace {

// Vertices nearer than this are one (0.1 µm: far below any contour's
// precision, far above rounding).
constexpr double kRepeatMm = 1e-4;
// Every vertex is rounded to this grid (plane mm). Where the section on two
// planes runs along one straight edge (a staircase ROI's pixel edges), its
// vertices on both planes agree to rounding, not bit for bit, and
// reconstruction folded on edges 1e-9 mm apart; on a grid they are equal.
constexpr double kSnapMm = 1e-4;
// A crossing stays this fraction of a step off the lattice samples, so
// parts of a section that pinch at a sample stay at least about 0.035 of a
// step apart (9 µm at 0.25 mm). Reconstruction opens exact touches, but
// pieces a few µm apart (3.5 µm: a staircase ROI's pixels that met at
// corners, cut from it by a difference) made it fold between the planes;
// 12 µm and more did not, on the shared Brodmann set.
constexpr double kKeepOffSample = 0.05;

// The lattice of one plane: fine samples (i, j), 0 ≤ i < width, at
// origin + (i, j)·step; coarse cells are `factor` samples wide.
struct SectionLattice {
    double originX = 0, originY = 0, step = 0;
    int factor = 1, cellsX = 0, cellsY = 0;
    int width() const { return cellsX * factor + 1; }
    int height() const { return cellsY * factor + 1; }
    std::size_t samples() const { return std::size_t(width()) * std::size_t(height()); }
    double x(double i) const { return originX + i * step; }
    double y(double j) const { return originY + j * step; }
};

// One plane's samples: exact where evaluated, else only a sign (the value
// then stands for "at least this far from zero").
struct PlaneSamples {
    double z = 0;
    std::vector<double> value;
    std::vector<unsigned char> exact;
};

// A polygon vertex on the lattice edge from sample a to sample b (t from
// a), with the field's values there.
struct EdgeVertex {
    std::size_t plane = 0, polygon = 0, vertex = 0;
    double ax = 0, ay = 0, bx = 0, by = 0;
    double t0 = 0, t1 = 1, f0 = 0, f1 = 0;
    int side = 0;  // Illinois: which end was kept last
    bool done = false;
};

SectionLattice latticeOver(const PlaneRect& region, const PlaneSectionOptions& o) {
    SectionLattice l;
    l.step = o.stepMm;
    l.factor = o.coarseFactor;
    const double cell = o.stepMm * o.coarseFactor;
    // One empty coarse cell all round, so every section closes inside.
    l.originX = region.xMin - cell - o.latticeShift * o.stepMm;
    l.originY = region.yMin - cell - o.latticeShift * o.stepMm;
    const double cellsX = std::ceil((region.xMax - region.xMin) / cell) + 2;
    const double cellsY = std::ceil((region.yMax - region.yMin) / cell) + 2;
    if (!(cellsX * o.coarseFactor < 46000 && cellsY * o.coarseFactor < 46000))
        throw std::invalid_argument(
            "planeSections: the region (" + std::to_string(region.xMax - region.xMin) + " × " +
            std::to_string(region.yMax - region.yMin) +
            " mm) needs more than 2^31 samples at a step of " + std::to_string(o.stepMm) + " mm");
    l.cellsX = int(std::max(1.0, cellsX));
    l.cellsY = int(std::max(1.0, cellsY));
    return l;
}

// A cell of the lattice, `size` samples wide, with its corner (i, j).
struct LatticeCell {
    std::size_t plane;
    int i, j, size;
};

// Samples the planes of one group: the coarse corners, then, level by
// level, the midpoints of the cells the Lipschitz bound cannot clear,
// halving them until they are one step wide (a quadtree over each coarse
// cell). A cleared cell's samples keep its corners' sign (no boundary can
// reach into it), so the samples evaluated are the ones within a few cells
// of the boundary at each level — about 4 per fine step of boundary, where
// sampling whole coarse cells took about 40 — and every sample marching
// squares reads on a cell the boundary crosses is exact.
std::vector<PlaneSamples> samplePlanes(const PlaneField& field, const std::vector<double>& zs,
                                       const SectionLattice& l, PlaneSectionStats& stats) {
    const int w = l.width(), k = l.factor;
    std::vector<PlaneSamples> planes(zs.size());
    std::vector<Vec3> points;
    std::vector<std::size_t> where;  // plane · samples + sample of each point
    auto mark = [&](std::size_t p, int i, int j) {
        PlaneSamples& s = planes[p];
        const std::size_t at = std::size_t(j) * std::size_t(w) + std::size_t(i);
        if (s.exact[at] != 0) return;
        s.exact[at] = 1;
        points.push_back({l.x(i), l.y(j), s.z});
        where.push_back(p * l.samples() + at);
    };
    auto evaluate = [&](std::size_t& counter) {
        if (points.empty()) return;
        const std::vector<double> values = field(points);
        counter += points.size();
        for (std::size_t n = 0; n < points.size(); ++n)
            planes[where[n] / l.samples()].value[where[n] % l.samples()] = values[n];
        points.clear();
        where.clear();
    };
    std::vector<LatticeCell> cells;
    for (std::size_t p = 0; p < zs.size(); ++p) {
        planes[p].z = zs[p];
        planes[p].value.assign(l.samples(), 0);
        planes[p].exact.assign(l.samples(), 0);
        for (int cj = 0; cj <= l.cellsY; ++cj)
            for (int ci = 0; ci <= l.cellsX; ++ci) mark(p, ci * k, cj * k);
        for (int cj = 0; cj < l.cellsY; ++cj)
            for (int ci = 0; ci < l.cellsX; ++ci) cells.push_back({p, ci * k, cj * k, k});
    }
    evaluate(stats.coarseSamples);

    std::vector<LatticeCell> near;
    while (!cells.empty()) {
        near.clear();
        for (const LatticeCell& c : cells) {
            // A boundary point inside a cell is within half its diagonal of
            // a corner.
            const int size = c.size;
            const double reach = 0.5 * std::sqrt(2.0) * size * l.step * (1 + 1e-9) + 1e-12;
            PlaneSamples& s = planes[c.plane];
            const auto at = [&](int i, int j) {
                return std::size_t(j) * std::size_t(w) + std::size_t(i);
            };
            const double f[4] = {s.value[at(c.i, c.j)], s.value[at(c.i + size, c.j)],
                                 s.value[at(c.i, c.j + size)], s.value[at(c.i + size, c.j + size)]};
            const bool mixed =
                std::any_of(f, f + 4, [&](double v) { return (v < 0) != (f[0] < 0); });
            double nearest = INFINITY;
            for (double v : f) nearest = std::min(nearest, std::abs(v));
            if (mixed || nearest <= reach) {
                if (size > 1) near.push_back(c);
                continue;
            }
            // No boundary in the cell: its corners' sign, at least
            // `nearest` from zero.
            for (int j = c.j; j <= c.j + size; ++j)
                for (int i = c.i; i <= c.i + size; ++i)
                    if (s.exact[at(i, j)] == 0) s.value[at(i, j)] = f[0] < 0 ? -nearest : nearest;
        }
        // The cells that may hold boundary, halved: their new corners.
        cells.clear();
        for (const LatticeCell& c : near) {
            const int half = c.size / 2;
            // A coarse factor that is not a power of two leaves odd sizes:
            // those are sampled whole, as one-step cells.
            if (c.size % 2 != 0) {
                for (int j = c.j; j <= c.j + c.size; ++j)
                    for (int i = c.i; i <= c.i + c.size; ++i) mark(c.plane, i, j);
                for (int j = c.j; j < c.j + c.size; ++j)
                    for (int i = c.i; i < c.i + c.size; ++i) cells.push_back({c.plane, i, j, 1});
                continue;
            }
            for (int dj = 0; dj <= 2; ++dj)
                for (int di = 0; di <= 2; ++di) mark(c.plane, c.i + di * half, c.j + dj * half);
            for (int dj = 0; dj < 2; ++dj)
                for (int di = 0; di < 2; ++di)
                    cells.push_back({c.plane, c.i + di * half, c.j + dj * half, half});
        }
        evaluate(stats.fineSamples);
    }
    return planes;
}

// The lattice edge a marching-squares vertex lies on: the one of the two
// candidate edges (horizontal or vertical through it) whose ends differ in
// sign. False when neither does (it then stays where it is).
bool edgeOf(Point2 v, const SectionLattice& l, const PlaneSamples& s, EdgeVertex& e) {
    const double fi = (v.x - l.originX) / l.step, fj = (v.y - l.originY) / l.step;
    const int w = l.width(), h = l.height();
    const auto valueAt = [&](int i, int j) {
        return s.value[std::size_t(j) * std::size_t(w) + std::size_t(i)];
    };
    const auto tryEdge = [&](int i0, int j0, int i1, int j1) {
        if (i0 < 0 || j0 < 0 || i1 >= w || j1 >= h) return false;
        const double a = valueAt(i0, j0), b = valueAt(i1, j1);
        if ((a < 0) == (b < 0)) return false;
        e.ax = l.x(i0);
        e.ay = l.y(j0);
        e.bx = l.x(i1);
        e.by = l.y(j1);
        e.f0 = a;
        e.f1 = b;
        return true;
    };
    const double ri = std::round(fi), rj = std::round(fj);
    if (std::abs(fj - rj) < 1e-4 &&
        tryEdge(int(std::floor(fi)), int(rj), int(std::floor(fi)) + 1, int(rj)))
        return true;
    if (std::abs(fi - ri) < 1e-4 &&
        tryEdge(int(ri), int(std::floor(fj)), int(ri), int(std::floor(fj)) + 1))
        return true;
    return false;
}

// Moves every vertex along its edge onto the zero set: regula falsi with
// the Illinois modification, all vertices of a group per field call.
void refine(const PlaneField& field, std::vector<EdgeVertex>& vertices,
            std::vector<std::vector<Polygon>>& polygons, const std::vector<PlaneSamples>& planes,
            const PlaneSectionOptions& o, PlaneSectionStats& stats) {
    std::vector<Vec3> points;
    std::vector<std::size_t> active;
    std::vector<double> tried;
    for (int iteration = 0; iteration < o.refineIterations; ++iteration) {
        points.clear();
        active.clear();
        tried.clear();
        for (std::size_t n = 0; n < vertices.size(); ++n) {
            EdgeVertex& e = vertices[n];
            if (e.done) continue;
            const double t = (e.t0 * e.f1 - e.t1 * e.f0) / (e.f1 - e.f0);
            // Never onto a lattice sample: where the boundary passes through
            // one, the crossings of its edges would meet there and the
            // polygons touch.
            const double tc =
                std::clamp(t, std::max(e.t0, kKeepOffSample), std::min(e.t1, 1 - kKeepOffSample));
            // The root lies between a sample and the point kept off it, which
            // was tried last time and is where the vertex stays: trying it
            // again would change nothing.
            if (tc == e.t0 || tc == e.t1) {
                e.done = true;
                continue;
            }
            points.push_back(
                {e.ax + tc * (e.bx - e.ax), e.ay + tc * (e.by - e.ay), planes[e.plane].z});
            active.push_back(n);
            tried.push_back(tc);
        }
        if (points.empty()) break;
        const std::vector<double> f = field(points);
        stats.refinementSamples += points.size();
        for (std::size_t m = 0; m < active.size(); ++m) {
            EdgeVertex& e = vertices[active[m]];
            const double t = tried[m], v = f[m];
            Polygon& polygon = polygons[e.plane][e.polygon];
            polygon[e.vertex] = {points[m].x, points[m].y};
            const double width = std::abs(e.bx - e.ax) + std::abs(e.by - e.ay);
            // Values within the zero tolerance read as +tolerance (outside):
            // such a point is on the boundary as far as the field can tell.
            if (std::abs(v) <= std::max(o.toleranceMm, o.zeroToleranceMm) ||
                (e.t1 - e.t0) * width <= o.toleranceMm) {
                e.done = true;
                continue;
            }
            if ((v < 0) == (e.f0 < 0)) {
                e.t0 = t;
                e.f0 = v;
                if (e.side == -1) e.f1 *= 0.5;
                e.side = -1;
            } else {
                e.t1 = t;
                e.f1 = v;
                if (e.side == 1) e.f0 *= 0.5;
                e.side = 1;
            }
        }
    }
}

// Drops vertices within `gap` of the one kept before them (two crossings
// beside a sample where the field is almost zero): points that near are one
// point to every reader, and the triangulations downstream need distinct
// points.
void dropNearRepeats(Polygon& polygon, double gap) {
    Polygon kept;
    for (const Point2& p : polygon)
        if (kept.empty() || length(p - kept.back()) > gap) kept.push_back(p);
    while (kept.size() > 1 && length(kept.back() - kept.front()) <= gap) kept.pop_back();
    polygon = std::move(kept);
}

}  // namespace

std::vector<Slice> planeSections(const PlaneField& exactField, const std::vector<double>& planeZMm,
                                 const PlaneRect& region, const PlaneSectionOptions& options,
                                 PlaneSectionStats* statsOut) {
    // Inside is below -tolerance: rounding on a face lying in a plane must
    // not scatter specks of section over it.
    const double tolerance = options.zeroToleranceMm;
    const PlaneField field = [&](const std::vector<Vec3>& points) {
        std::vector<double> values = exactField(points);
        for (double& v : values)
            if (v > -tolerance && v < tolerance) v = tolerance;
        return values;
    };
    if (!(options.stepMm > 0) || options.coarseFactor < 1)
        throw std::invalid_argument(
            "planeSections: the step must be > 0 mm and the coarse factor ≥ 1");
    PlaneSectionStats stats;
    stats.planes = planeZMm.size();
    std::vector<double> zs = planeZMm;
    std::sort(zs.begin(), zs.end());
    const SectionLattice l = latticeOver(region, options);
    const std::size_t perGroup = std::max<std::size_t>(1, options.maxSamplesPerBatch / l.samples());
    std::vector<Slice> out;
    for (std::size_t first = 0; first < zs.size(); first += perGroup) {
        const std::vector<double> group(
            zs.begin() + std::ptrdiff_t(first),
            zs.begin() + std::ptrdiff_t(std::min(zs.size(), first + perGroup)));
        const std::vector<PlaneSamples> planes = samplePlanes(field, group, l, stats);
        std::vector<std::vector<Polygon>> polygons(planes.size());
        std::vector<EdgeVertex> vertices;
        SampleLattice lattice;
        lattice.originMm = {l.originX, l.originY};
        lattice.stepMm = {l.step, l.step};
        for (std::size_t p = 0; p < planes.size(); ++p) {
            std::vector<float> image(planes[p].value.size());
            for (std::size_t n = 0; n < image.size(); ++n) image[n] = float(planes[p].value[n]);
            polygons[p] = negativeRegionBorders(image, l.width(), l.height(), lattice);
            for (std::size_t c = 0; c < polygons[p].size(); ++c)
                for (std::size_t v = 0; v < polygons[p][c].size(); ++v) {
                    EdgeVertex e;
                    e.plane = p;
                    e.polygon = c;
                    e.vertex = v;
                    if (edgeOf(polygons[p][c][v], l, planes[p], e)) vertices.push_back(e);
                }
        }
        refine(field, vertices, polygons, planes, options, stats);
        for (std::size_t p = 0; p < planes.size(); ++p) {
            Slice slice;
            slice.zMm = planes[p].z;
            for (Polygon& polygon : polygons[p]) {
                for (Point2& v : polygon)
                    v = {std::round(v.x / kSnapMm) * kSnapMm, std::round(v.y / kSnapMm) * kSnapMm};
                dropNearRepeats(polygon, kRepeatMm);
                if (polygon.size() >= 3 &&
                    std::abs(signedArea(polygon)) >= options.minContourAreaMm2)
                    slice.contours.push_back(std::move(polygon));
            }
            if (!slice.contours.empty()) out.push_back(std::move(slice));
        }
        if (options.progress)
            options.progress(double(std::min(zs.size(), first + perGroup)) / double(zs.size()));
    }
    stats.planesWithSection = out.size();
    if (statsOut) *statsOut = stats;
    return out;
}

}  // namespace dfrecon
