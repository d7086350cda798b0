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
#include "recon/HermiteTangents.hpp"
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

// The field of the slice on the other side of the end (below when the cap
// goes `up`) at the vertices of contours `which` of `end` (slice `slice` of
// `fields`): how far outside (> 0) or inside (< 0) that slice's solid each
// lies. Empty when there is no such slice or it has no contours there.
std::vector<double> fieldBeyond(const LayerPart& end, const std::vector<std::uint32_t>& which,
                                bool up, const SliceFields& fields, std::size_t slice,
                                std::size_t planesAway = 1) {
    if (up ? slice < planesAway : slice + planesAway >= fields.sliceCount()) return {};
    const std::size_t other = up ? slice - planesAway : slice + planesAway;
    const SliceGrid& grid = fields.grid;
    std::vector<double> values;
    for (std::uint32_t c : which)
        for (Point2 p : end.layer->contours[c]) {
            const int i =
                std::clamp(int((p.x - grid.originMm.x) / grid.pixelMm), 0, grid.width - 1);
            const int j =
                std::clamp(int((p.y - grid.originMm.y) / grid.pixelMm), 0, grid.height - 1);
            const double d = fields.distanceMm[fields.index(other, i, j)];
            if (!std::isfinite(d)) return {};
            values.push_back(d);
        }
    return values;
}

// How far the region of `end` (slice `slice` of `fields`) lies inside the
// solid of the slice `planesAway` planes on the other side: the mean of
// that slice's field at end's vertices, negated for outer contours (their
// solid lies under them where the region narrows toward its end) and kept
// for a cavity's own end (its outermost contour a hole: that slice's
// cavity lies under it). Empty when there is no such slice.
std::optional<double> meanDepthBeyond(const LayerPart& end, bool up, const SliceFields& fields,
                                      std::size_t slice, std::size_t planesAway) {
    const std::vector<double> beyond =
        fieldBeyond(end, end.contours, up, fields, slice, planesAway);
    if (beyond.empty()) return std::nullopt;
    double sum = 0;
    for (double d : beyond) sum += d;
    const double mean = sum / double(beyond.size());
    return outermostIsHole(end) ? mean : -mean;
}

// How fast the region of `end` (slice `slice` of `fields`) shrinks per mm
// of z toward its end, in either mode: the slope smooth mode's
// interpolation has at an end plane (recon/HermiteTangents). From the slice
// on the other side alone, the end slab's secant; with the one beyond it
// too, the parabola through the end slab with that slice's tangent, steeper
// at a rounded end (a ball's pole, a tube's rounded tip), so the lid's rim
// follows the rounding instead of running straight on. 0 when there is no
// such slice or the region grows. O(points).
double inwardSlope(const LayerPart& end, bool up, const SliceFields& fields, std::size_t slice) {
    const std::optional<double> depth = meanDepthBeyond(end, up, fields, slice, 1);
    if (!depth) return 0;
    const auto zAway = [&](std::size_t k) { return fields.zMm[up ? slice - k : slice + k]; };
    const double gap = std::fabs(fields.zMm[slice] - zAway(1));
    if (!(gap > 0)) return 0;
    const double secant = std::max(0.0, *depth / gap);
    const std::optional<double> deeper = meanDepthBeyond(end, up, fields, slice, 2);
    if (secant <= 0 || !deeper) return secant;
    const double gapBeyond = std::fabs(zAway(1) - zAway(2));
    const double beyondTangent =
        parabolaTangent(gap, secant, gapBeyond, (*deeper - *depth) / gapBeyond);
    return endTangent(secant, beyondTangent);
}

// An end's contours where a cavity closes before the end does. A hole of
// the end plane whose cavity narrows toward the end (the slice on the other
// side holds more of it: most of its vertices lie outside that slice's
// solid, inside the same wall; cavityCloses) is a cavity's last section, as
// a ball's cavity near its pole is:
// capping it with the rest would run it through the lid as a tunnel from
// the cavity to the outside. Such a hole gets a lid of its own, nearer the
// plane than the rest's, and what it holds (an island) a cap nearer still.
// A hole that widens toward the end (a torus's or a bowl's opening) stays
// open, as before.
struct CavitySplit {
    LayerPart rest;                   // what is capped as before
    std::vector<LayerPart> holes;     // closing holes, one contour each
    std::vector<LayerPart> holdings;  // what each closing hole holds (maybe nothing)
};

// Fraction of the cap offset a closing hole's lid reaches, and then what it
// holds, of the hole's: each level halves, so nested lids never meet.
constexpr double kCavityLidFraction = 0.5;

// The contours of `end` that contain contour `inner`'s first vertex, by
// index into end.contours, innermost first. Contours of a plane do not
// cross, so one vertex decides. O(n · points) per contour.
std::vector<std::size_t> enclosing(const LayerPart& end, std::size_t inner) {
    const Point2 p = end.layer->contours[end.contours[inner]].front();
    std::vector<std::pair<double, std::size_t>> around;
    for (std::size_t k = 0; k < end.contours.size(); ++k) {
        if (k == inner) continue;
        const Polygon& contour = end.layer->contours[end.contours[k]];
        if (boundingBox(contour).contains(p) && windingNumber(p, contour) != 0)
            around.push_back({std::fabs(signedArea(contour)), k});
    }
    std::sort(around.begin(), around.end());
    std::vector<std::size_t> out;
    for (const auto& [area, k] : around) out.push_back(k);
    return out;
}

// The value below which the fraction `q` of `values` lies (the element at
// that rank; `values` non-empty, reordered). O(n).
double quantile(std::vector<double>& values, double q) {
    const auto rank =
        values.begin() +
        std::ptrdiff_t(std::min(values.size() - 1, std::size_t(q * double(values.size()))));
    std::nth_element(values.begin(), rank, values.end());
    return *rank;
}

// Does the cavity of hole `contour` narrow toward the end fast enough to
// close soon beyond it? Its vertices (`beyondMm`: the field beyond at each)
// mostly lie outside the solid of the slice beyond, and a quarter of them
// by at least half its radius (2 · area / perimeter: at that rate it closes
// within two gaps) and two pixels (the field is read at the pixel a vertex
// falls in). Quantiles, not the mean, as an island in the cavity beyond
// lies under some of them or near. A torus's bore, which narrows a little
// toward its middle, a straight tube's, and one that noise makes wobble
// stay open. O(n).
bool cavityCloses(const Polygon& contour, std::vector<double> beyondMm, const SliceGrid& grid) {
    if (beyondMm.empty()) return false;
    const double median = quantile(beyondMm, 0.5), upperQuartile = quantile(beyondMm, 0.75);
    const double radiusMm =
        2 * std::fabs(signedArea(contour)) / std::max(perimeterMm(contour), 1e-12);
    return median > 0 && upperQuartile > std::max(0.5 * radiusMm, 2 * grid.pixelMm);
}

CavitySplit splitClosingCavities(const LayerPart& end, bool up, const SliceFields& fields,
                                 std::size_t slice) {
    CavitySplit split;
    split.rest.layer = end.layer;
    const std::size_t n = end.contours.size();
    // A hole with something around it in this part (a part whose outermost
    // contour is a hole is a cavity's own end, capped as it is).
    std::vector<bool> closing(n, false);
    bool any = false;
    for (std::size_t k = 0; k < n; ++k) {
        const std::uint32_t c = end.contours[k];
        if (signedArea(end.layer->contours[c]) >= 0) continue;
        const std::vector<std::size_t> around = enclosing(end, k);
        if (around.empty()) continue;
        // The wall around it goes on beyond (its outline lies mostly inside
        // the solid there), so the hole beyond is this cavity's, not the
        // open space around a part that starts or ends here.
        std::vector<double> wall =
            fieldBeyond(end, {end.contours[around.front()]}, up, fields, slice);
        if (wall.empty() || !(quantile(wall, 0.5) < 0)) continue;
        closing[k] = cavityCloses(end.layer->contours[c], fieldBeyond(end, {c}, up, fields, slice),
                                  fields.grid);
        any = any || closing[k];
    }
    if (!any) {
        split.rest = end;
        return split;
    }
    // Each contour goes with the outermost closing hole around it, if any.
    std::vector<std::size_t> owner(n, n);
    for (std::size_t k = 0; k < n; ++k) {
        for (std::size_t around : enclosing(end, k))
            if (closing[around]) owner[k] = around;           // the last is the outermost
        if (closing[k] && owner[k] != n) closing[k] = false;  // inside another: its holding
    }
    std::vector<std::size_t> slot(n, n);
    for (std::size_t k = 0; k < n; ++k)
        if (closing[k] && owner[k] == n) {
            slot[k] = split.holes.size();
            split.holes.push_back({end.layer, {end.contours[k]}});
            split.holdings.push_back({end.layer, {}});
        }
    for (std::size_t k = 0; k < n; ++k) {
        if (slot[k] != n) continue;
        if (owner[k] != n)
            split.holdings[slot[owner[k]]].contours.push_back(end.contours[k]);
        else
            split.rest.contours.push_back(end.contours[k]);
    }
    return split;
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
void flat(CapSite& site, const LayerPart& end, CapReach reach, const SliceFields& fields,
          std::size_t slice) {
    const bool up = reach.up;
    const double offsetMm = reach.offsetMm;
    const double z = end.layer->zMm + (up ? offsetMm : -offsetMm);
    const double slope = inwardSlope(end, up, fields, slice);
    const double insetMm = slope * offsetMm;
    // Voxels end in a prism: the slope of their staircase says nothing about
    // the last voxel layer, which the contour volume counts whole.
    if (reach.voxelEnds || insetMm < fields.grid.pixelMm) {
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
        // The end would narrow to nothing before the lid: round it off
        // where it closes at this slope (its deepest point gone), not at the
        // full offset, which would leave a blunt end hanging past it.
        const float deepestMm = -*std::min_element(
            own.distanceMm.begin(), own.distanceMm.begin() + std::ptrdiff_t(own.grid.pixelCount()));
        const double closesMm = std::clamp(double(deepestMm) / slope, 0.25 * offsetMm, offsetMm);
        dome(site.builder(), end, {up, closesMm, INFINITY}, fields, slice);
        return;
    }
    const Layer& top = site.addIsolineLayer(z, std::move(lid), end);
    LayerPart lidPart{&top, {}};
    for (std::uint32_t c = 0; c < top.contours.size(); ++c) lidPart.contours.push_back(c);
    const SliceFields lidField = site.fieldsOf({lidPart}, own.grid);
    const std::size_t joinFrom = site.builder().triangleCount();
    if (up)
        site.joinLayers(end, own, lidPart, lidField);
    else
        site.joinLayers(lidPart, lidField, end, own);
    // A cavity's end keeps the shape of its trend: the slab's interpolant
    // there (the cavity's field against the solid plane beyond) closes it
    // far sooner than the lid, so bending its wall onto it would pinch the
    // cavity and volume matching would take that back from the outer wall.
    if (outermostIsHole(end)) site.builder().markLoftSince(joinFrom, false);
    roundedCap(site.builder(), lidPart, {up, 0.0, 0.0}, {}, [](Point2) { return 0.0; });
}

}  // namespace

void capEnds(CapSite& site, CapMode mode, const LayerPart& end, CapReach reach,
             const SliceFields& fields, std::size_t slice) {
    if (end.contours.empty() || mode == CapMode::None) return;
    const CavitySplit split = splitClosingCavities(end, reach.up, fields, slice);
    const bool up = reach.up;
    const double offsetMm = reach.offsetMm;
    if (mode == CapMode::Flat)
        flat(site, split.rest, reach, fields, slice);
    else
        dome(site.builder(), split.rest, {up, offsetMm, INFINITY}, fields, slice);
    const double lidMm = kCavityLidFraction * offsetMm;
    for (std::size_t h = 0; h < split.holes.size(); ++h) {
        prismCap(site.builder(), split.holes[h], up, lidMm);
        capEnds(site, mode, split.holdings[h], {up, kCavityLidFraction * lidMm, reach.voxelEnds},
                fields, slice);
    }
}

void guaranteedCap(SurfaceBuilder& builder, const LayerPart& end, CapReach reach,
                   const SliceFields& fields, std::size_t slice) {
    if (end.contours.empty()) return;
    const CavitySplit split = splitClosingCavities(end, reach.up, fields, slice);
    prismCap(builder, split.rest, reach.up, reach.offsetMm);
    const double lidMm = kCavityLidFraction * reach.offsetMm;
    for (std::size_t h = 0; h < split.holes.size(); ++h) {
        prismCap(builder, split.holes[h], reach.up, lidMm);
        guaranteedCap(builder, split.holdings[h], {reach.up, kCavityLidFraction * lidMm}, fields,
                      slice);
    }
}

void capEndsAsPiece(CapSite& site, CapMode mode, const LayerPart& end, CapReach reach,
                    const SliceFields& fields, std::size_t slice) {
    const std::size_t before = site.builder().triangleCount();
    capEnds(site, mode, end, reach, fields, slice);
    if (mode != CapMode::None && !site.isCleanCap(before, end)) {
        site.builder().truncateTriangles(before);
        guaranteedCap(site.builder(), end, reach, fields, slice);
    }
}

}  // namespace dfrecon
