#include "recon/Caps.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <set>
#include <utility>
#include <vector>

#include "geometry/MeshCheck.hpp"
#include "recon/ContourSimplification.hpp"
#include "recon/IsoContours.hpp"
#include "recon/PlanarRegion.hpp"
#include "recon/PrismClosing.hpp"
#include "recon/SurfaceBuilder.hpp"

namespace dfrecon {

const char* capModeName(CapMode mode) {
    for (const auto& [name, value] : kCapModeNames)
        if (value == mode) return name;
    return "?";
}

double capOffsetMm(double requestedMm, double gapMm, bool betweenPlanes) {
    const double half = 0.5 * gapMm;
    if (requestedMm < 0) return half;
    return betweenPlanes ? std::min(requestedMm, half) : requestedMm;
}

void prismCap(SurfaceBuilder& builder, const LayerPart& end, bool up, double offsetMm) {
    if (up)
        closeByPrisms(builder, end, {}, end.layer->zMm + offsetMm);
    else
        closeByPrisms(builder, {}, end, end.layer->zMm - offsetMm);
}

namespace {

// The shape of a rounded cap: it rises from its contours' plane (upward when
// `up`, else downward) to `heightMm`, along a quarter circle that is
// vertical at the rim and flat once `roundingMm` inside (a plateau; with
// roundingMm at least the region's depth, a dome).
struct CapShape {
    bool up = true;
    double heightMm = 0, roundingMm = 0;
};

// A rounded cap of `shape` over the region of `part`'s contours, starting at
// the contours in their plane. `depthMm(p)` is the distance from p to the contours; the
// cap's inner vertices sit at `interiorPoints`, which must lie inside the
// region and off the contours. A height field over a planar triangulation,
// so it cannot fold onto itself.
void roundedCap(SurfaceBuilder& builder, const LayerPart& part, CapShape shape,
                const std::vector<Point2>& interiorPoints,
                const std::function<double(Point2)>& depthMm) {
    const bool up = shape.up;
    const double heightMm = shape.heightMm, roundingMm = shape.roundingMm;
    std::vector<WeightedContour> contours;
    if (part.layer)
        for (std::uint32_t c : part.contours) contours.push_back({&part.layer->contours[c], +1});
    if (contours.empty()) return;
    // An edge joining two contour points across the region (a chord) would
    // lie flat in the contour plane, where a cap from the other side may use
    // it too: chords get their midpoint as an inner vertex (a few rounds, as
    // the triangulation changes around new points).
    std::vector<Point2> inner = interiorPoints;
    PlanarRegion region = triangulateRegion(contours, inner);
    for (int round = 0; round < 4 && heightMm > 0; ++round) {
        std::vector<bool> onContour(region.points.size(), false);
        std::set<std::pair<std::uint32_t, std::uint32_t>> contourEdges;
        for (const auto& chains : region.edgeChains)
            for (const auto& chain : chains)
                for (std::size_t k = 0; k < chain.size(); ++k) {
                    onContour[chain[k]] = true;
                    if (k + 1 < chain.size())
                        contourEdges.insert(std::minmax(chain[k], chain[k + 1]));
                }
        std::set<std::pair<std::uint32_t, std::uint32_t>> chords;
        for (const auto& t : region.triangles)
            for (int k = 0; k < 3; ++k) {
                const auto edge = std::minmax(t[std::size_t(k)], t[std::size_t((k + 1) % 3)]);
                if (onContour[edge.first] && onContour[edge.second] && !contourEdges.count(edge))
                    chords.insert(edge);
            }
        if (chords.empty()) break;
        for (const auto& [a, b] : chords)
            inner.push_back(0.5 * (region.points[a] + region.points[b]));
        region = triangulateRegion(contours, inner);
    }
    const double z0 = part.layer->zMm;

    // Contour corners keep their layer vertices; everything else is lifted.
    constexpr std::uint32_t kUnset = 0xffffffffu;
    std::vector<std::uint32_t> vertex(region.points.size(), kUnset);
    std::vector<bool> onContour(region.points.size(), false);
    for (std::size_t q = 0; q < part.contours.size(); ++q) {
        const std::vector<std::uint32_t>& ids = part.layer->vertexIds[part.contours[q]];
        for (std::size_t k = 0; k < ids.size(); ++k) {
            vertex[region.edgeChains[q][k].front()] = ids[k];
            for (std::uint32_t p : region.edgeChains[q][k]) onContour[p] = true;
        }
    }
    double deepest = 0;
    std::vector<double> depth(region.points.size(), 0.0);
    for (std::size_t p = 0; p < region.points.size(); ++p) {
        if (onContour[p]) continue;
        depth[p] = std::max(0.0, depthMm(region.points[p]));
        deepest = std::max(deepest, depth[p]);
    }
    const double direction = up ? 1.0 : -1.0;
    const double radius = std::min(roundingMm, deepest);
    for (std::size_t p = 0; p < region.points.size(); ++p) {
        if (vertex[p] != kUnset) continue;
        const double r = radius > 0 ? std::min(1.0, depth[p] / radius) : 0.0;
        const double rise = heightMm * std::sqrt(std::max(0.0, 1 - (1 - r) * (1 - r)));
        vertex[p] = builder.addVertex(region.points[p], z0 + direction * rise);
    }
    for (std::size_t t = 0; t < region.triangles.size(); ++t) {
        const auto& tri = region.triangles[t];
        if ((region.sign[t] > 0) == up)
            builder.addTriangle(vertex[tri[0]], vertex[tri[1]], vertex[tri[2]]);
        else
            builder.addTriangle(vertex[tri[0]], vertex[tri[2]], vertex[tri[1]]);
    }
}

// How fast the contours of `end` (slice `slice` of `fields`) move inward
// per mm of z, judged from the slice on the other side: the mean of its
// field at their vertices over the gap. 0 when there is no such slice or
// the contours grow.
double inwardSlope(const LayerPart& end, bool up, const SliceFields& fields, std::size_t slice) {
    if (up ? slice == 0 : slice + 1 >= fields.sliceCount()) return 0;
    const std::size_t other = up ? slice - 1 : slice + 1;
    const SliceGrid& grid = fields.grid;
    double sum = 0;
    std::size_t count = 0;
    for (std::uint32_t c : end.contours)
        for (Point2 p : end.layer->contours[c]) {
            const int i =
                std::clamp(int((p.x - grid.originMm.x) / grid.pixelMm), 0, grid.width - 1);
            const int j =
                std::clamp(int((p.y - grid.originMm.y) / grid.pixelMm), 0, grid.height - 1);
            const double d = fields.distanceMm[fields.index(other, i, j)];
            if (!std::isfinite(d)) return 0;
            sum += d;
            ++count;
        }
    const double gap = std::fabs(fields.zMm[slice] - fields.zMm[other]);
    return count > 0 && gap > 0 ? std::max(0.0, -(sum / double(count)) / gap) : 0.0;
}

void dome(SurfaceBuilder& builder, const LayerPart& end, CapShape shape, const SliceFields& fields,
          std::size_t slice) {
    const bool up = shape.up;
    const double heightMm = shape.heightMm;
    // Inner vertices on a lattice a third of the cap height apart (so the
    // rounding gets a few steps), at least a pixel and a half inside,
    // where the slice's field is exact.
    const SliceGrid& grid = fields.grid;
    const double pixel = grid.pixelMm;
    const int step = std::max(2, int(std::lround(heightMm / 3 / pixel)));
    auto depthAt = [&](int i, int j) { return -fields.distanceMm[fields.index(slice, i, j)]; };
    std::vector<Point2> inner;
    for (int j = step / 2; j < grid.height; j += step) {
        for (int i = step / 2; i < grid.width; i += step) {
            if (depthAt(i, j) < 1.5 * pixel) continue;
            const Point2 p = grid.pixelCentre(i, j);
            int winding = 0;
            for (std::uint32_t c : end.contours)
                winding += windingNumber(p, end.layer->contours[c]);
            if (winding != 0) inner.push_back(p);
        }
    }
    // Every outer contour needs an inner vertex, or its dome would be
    // flat in the contour plane (and coincide with a cap from the other
    // side): the lattice can miss small ones, so take their deepest
    // pixel; contours too small for any get a flat cap instead.
    for (std::uint32_t c : end.contours) {
        const Polygon& contour = end.layer->contours[c];
        if (signedArea(contour) <= 0) continue;
        auto inside = [&](Point2 p) { return windingNumber(p, contour) != 0; };
        if (std::any_of(inner.begin(), inner.end(), inside)) continue;
        const Box2 box = boundingBox(contour);
        double best = 0.5 * pixel;
        std::optional<Point2> deepest;
        const int i0 = std::max(0, int((box.min.x - grid.originMm.x) / pixel));
        const int i1 = std::min(grid.width - 1, int((box.max.x - grid.originMm.x) / pixel));
        const int j0 = std::max(0, int((box.min.y - grid.originMm.y) / pixel));
        const int j1 = std::min(grid.height - 1, int((box.max.y - grid.originMm.y) / pixel));
        for (int j = j0; j <= j1; ++j)
            for (int i = i0; i <= i1; ++i)
                if (depthAt(i, j) > best && inside(grid.pixelCentre(i, j))) {
                    best = depthAt(i, j);
                    deepest = grid.pixelCentre(i, j);
                }
        if (!deepest) {
            prismCap(builder, end, up, heightMm);
            return;
        }
        inner.push_back(*deepest);
    }
    auto depthMm = [&](Point2 p) {
        double d = INFINITY;
        for (std::uint32_t c : end.contours)
            d = std::min(d, distanceToBoundary(p, end.layer->contours[c]));
        return d;
    };
    const std::size_t before = builder.triangleCount();
    roundedCap(builder, end, shape, inner, depthMm);
    // The cap alone must be a clean sheet whose only border is the end
    // contours; otherwise (contours touching inside it) a flat prism cap.
    const MeshCheckReport cap = checkMesh(builder.trianglesSince(before));
    std::size_t contourEdges = 0;
    for (std::uint32_t c : end.contours) contourEdges += end.layer->contours[c].size();
    if (cap.intersectingPairs > 0 || cap.nonManifoldEdges > 0 || cap.misorientedEdges > 0 ||
        cap.degenerateTriangles > 0 || cap.boundaryEdges != contourEdges) {
        builder.truncateTriangles(before);
        prismCap(builder, end, up, heightMm);
    }
}

// The flat cap: a lid at the offset. Its rim continues the side's slope
// from the last slab (a vertical wall where the side is vertical or
// widening), so ends that were narrowing keep narrowing to the lid
// instead of stepping; the lid is the end contours inset by that much
// (an isoline of their field), joined to them like any slab.
void flat(CapSite& site, const LayerPart& end, bool up, double offsetMm, const SliceFields& fields,
          std::size_t slice) {
    const double z = end.layer->zMm + (up ? offsetMm : -offsetMm);
    const double insetMm = inwardSlope(end, up, fields, slice) * offsetMm;
    if (insetMm < fields.grid.pixelMm) {
        prismCap(site.builder(), end, up, offsetMm);
        return;
    }
    const SliceFields own = site.fieldsOf({end}, std::nullopt);
    std::vector<float> shifted(own.distanceMm.begin(),
                               own.distanceMm.begin() + std::ptrdiff_t(own.grid.pixelCount()));
    for (float& d : shifted) d += float(insetMm);
    std::vector<Polygon> lid;
    for (SimplifiedContour& c :
         simplifySlice(zeroIsolines(shifted, own.grid), 0.25 * own.grid.pixelMm))
        if (c.points.size() >= 3) lid.push_back(std::move(c.points));
    if (lid.empty()) {
        // The end would narrow to nothing before the lid: round it off.
        dome(site.builder(), end, {up, offsetMm, INFINITY}, fields, slice);
        return;
    }
    const Layer& top = site.addIsolineLayer(z, std::move(lid), end);
    LayerPart lidPart{&top, {}};
    for (std::uint32_t c = 0; c < top.contours.size(); ++c) lidPart.contours.push_back(c);
    const SliceFields lidField = site.fieldsOf({lidPart}, own.grid);
    if (up)
        site.joinLayers(end, own, lidPart, lidField);
    else
        site.joinLayers(lidPart, lidField, end, own);
    roundedCap(site.builder(), lidPart, {up, 0.0, 0.0}, {}, [](Point2) { return 0.0; });
}

}  // namespace

void capEnds(CapSite& site, CapMode mode, const LayerPart& end, CapReach reach,
             const SliceFields& fields, std::size_t slice) {
    if (end.contours.empty()) return;
    const bool up = reach.up;
    const double offsetMm = reach.offsetMm;
    switch (mode) {
        case CapMode::None:
            return;
        case CapMode::Flat:
            flat(site, end, up, offsetMm, fields, slice);
            return;
        case CapMode::Dome:
            dome(site.builder(), end, {up, offsetMm, INFINITY}, fields, slice);
            return;
    }
}

void capEndsAsPiece(CapSite& site, CapMode mode, const LayerPart& end, CapReach reach,
                    const SliceFields& fields, std::size_t slice) {
    const std::size_t before = site.builder().triangleCount();
    capEnds(site, mode, end, reach, fields, slice);
    if (mode != CapMode::None && !site.isCleanCap(before, end)) {
        site.builder().truncateTriangles(before);
        prismCap(site.builder(), end, reach.up, reach.offsetMm);
    }
}

}  // namespace dfrecon
