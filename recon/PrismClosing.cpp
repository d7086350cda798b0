#include "recon/PrismClosing.hpp"

#include <cmath>
#include <cstdint>
#include <optional>
#include <vector>

#include "geometry/MeshCheck.hpp"
#include "recon/PlanarRegion.hpp"

namespace dfrecon {

namespace {

std::vector<WeightedContour> weighted(const LayerPart& part, int weight) {
    std::vector<WeightedContour> out;
    if (part.layer)
        for (std::uint32_t c : part.contours) out.push_back({&part.layer->contours[c], weight});
    return out;
}

std::size_t contourCount(const LayerPart& part) {
    return part.layer ? part.contours.size() : 0;
}

// Do the lower and upper contours meet other than by crossing: a vertex of
// one on the other (a shared corner, a corner on an edge, a shared run)?
// Then the lid's walls and lids would meet along a shared edge or point, and
// the closing would not be a manifold. Crossing points are new vertices of
// the triangulation, corners of neither side, so they do not count.
bool sidesCoincide(const PlanarRegion& region, std::size_t lowerCount) {
    std::vector<std::uint8_t> on(region.points.size(), 0);  // bit 1: on a lower chain, 2: upper
    for (std::size_t c = 0; c < region.edgeChains.size(); ++c)
        for (const std::vector<std::uint32_t>& chain : region.edgeChains[c])
            for (std::uint32_t p : chain) on[p] |= c < lowerCount ? 1 : 2;
    for (std::size_t c = 0; c < region.edgeChains.size(); ++c) {
        const std::uint8_t other = c < lowerCount ? 2 : 1;
        for (const std::vector<std::uint32_t>& chain : region.edgeChains[c])
            if (on[chain.front()] & other) return true;
    }
    return false;
}

// The shifts tried in turn for the upper contours' side of the lid: none
// first (unless the sides coincide), then a fraction of a micrometre, enough
// to survive float coordinates in the output, in directions no pixel grid
// shares, then larger ones. A shifted outline leans the upper walls by that
// much: the closing stays a valid solid (a shear of a prism), whatever the
// shift.
constexpr double kShiftMm = 5e-4;
constexpr Point2 kShiftDirections[] = {{0.6, 0.8}, {-0.8, 0.6}, {0.28, -0.96}, {-0.96, -0.28}};
constexpr double kShiftScales[] = {1, 8, 64};

std::vector<Point2> upperShifts() {
    std::vector<Point2> shifts{{0, 0}};
    for (const double scale : kShiftScales)
        for (const Point2 direction : kShiftDirections)
            shifts.push_back((scale * kShiftMm) * direction);
    return shifts;
}

// The walls and lid of a closing whose lid is `region` (lower contours'
// chains first, then the upper ones').
void addClosing(SurfaceBuilder& builder, const LayerPart& lower, const LayerPart& upper,
                const PlanarRegion& region, double middleZMm) {
    const std::size_t lowerCount = contourCount(lower);
    std::vector<std::uint32_t> lid;
    lid.reserve(region.points.size());
    for (Point2 p : region.points) lid.push_back(builder.addVertex(p, middleZMm));

    for (std::size_t q = 0; q < lowerCount; ++q) {
        const std::vector<std::uint32_t>& ids = lower.layer->vertexIds[lower.contours[q]];
        const std::size_t n = ids.size();
        for (std::size_t k = 0; k < n; ++k) {
            const std::vector<std::uint32_t>& top = region.edgeChains[q][k];
            const std::uint32_t a = ids[k], b = ids[(k + 1) % n];
            for (std::size_t j = 0; j + 1 < top.size(); ++j)
                builder.addTriangle(a, lid[top[j + 1]], lid[top[j]]);
            builder.addTriangle(a, b, lid[top.back()]);
        }
    }
    for (std::size_t q = 0; q < contourCount(upper); ++q) {
        const std::vector<std::uint32_t>& ids = upper.layer->vertexIds[upper.contours[q]];
        const std::size_t n = ids.size();
        for (std::size_t k = 0; k < n; ++k) {
            const std::vector<std::uint32_t>& bottom = region.edgeChains[lowerCount + q][k];
            const std::uint32_t a = ids[k], b = ids[(k + 1) % n];
            for (std::size_t j = 0; j + 1 < bottom.size(); ++j)
                builder.addTriangle(lid[bottom[j]], lid[bottom[j + 1]], b);
            builder.addTriangle(lid[bottom.front()], b, a);
        }
    }
    // Solid below the lid where only X is (sign +1): it faces up.
    for (std::size_t t = 0; t < region.triangles.size(); ++t) {
        const auto& tri = region.triangles[t];
        if (region.sign[t] > 0)
            builder.addTriangle(lid[tri[0]], lid[tri[1]], lid[tri[2]]);
        else
            builder.addTriangle(lid[tri[0]], lid[tri[2]], lid[tri[1]]);
    }
}

// Does the closing added since `before` hold as a mesh file stores it
// (floats): no triangle flat, no two meeting? Exact arithmetic makes it a
// valid solid; a crossing point or shifted corner a hair from another
// point makes slivers that rounding can fold through their neighbours or
// flatten (a lung's vessels, the same point on neighbouring planes). Its
// topology is by vertex index, which rounding cannot change, so only the
// geometry is tested. O(T log T) for its T triangles.
bool holdsAsFloats(const SurfaceBuilder& builder, std::size_t before) {
    TriangleSoup triangles = builder.trianglesSince(before);
    roundPointsToFloat(triangles);
    for (const auto& t : triangles.triangles)
        if (isDegenerate(triangles, t)) return false;
    return countSelfIntersections(triangles) == 0;
}

}  // namespace

bool outermostIsHole(const LayerPart& a, const LayerPart& b) {
    double largest = 0, sign = 1;
    for (const LayerPart* part : {&a, &b}) {
        if (!part->layer) continue;
        for (std::uint32_t c : part->contours) {
            const double area = signedArea(part->layer->contours[c]);
            if (std::abs(area) > largest) largest = std::abs(area), sign = area;
        }
    }
    return sign < 0;
}

bool closeByPrisms(SurfaceBuilder& builder, const LayerPart& lower, const LayerPart& upper,
                   double middleZMm) {
    std::vector<WeightedContour> contours = weighted(lower, +1);
    const std::size_t lowerCount = contours.size();
    for (const WeightedContour& c : weighted(upper, -1)) contours.push_back(c);
    if (contours.empty()) return true;
    // With one side only (a cap) there is nothing to shift.
    const bool twoSides = lowerCount > 0 && lowerCount < contours.size();
    const std::vector<Point2> shifts = twoSides ? upperShifts() : std::vector<Point2>{{0, 0}};
    const std::vector<WeightedContour> unshifted = contours;
    std::vector<Polygon> shifted(contours.size() - lowerCount);
    const std::size_t before = builder.triangleCount();
    std::optional<PlanarRegion> fallback;  // the last lid whose sides did not coincide
    for (std::size_t k = 0; k < shifts.size(); ++k) {
        // Where the sides coincide, the upper side's lid outline is shifted
        // sideways: what was a shared edge becomes two parallel ones
        // (symbolic perturbation, the same rule everywhere). Crossings are
        // fine as they are, as long as they hold as floats.
        for (std::size_t c = lowerCount; k > 0 && c < contours.size(); ++c) {
            Polygon& moved = shifted[c - lowerCount];
            moved = *unshifted[c].polygon;
            for (Point2& p : moved) p = p + shifts[k];
            contours[c].polygon = &moved;
        }
        PlanarRegion region = triangulateRegion(contours);
        if (twoSides && sidesCoincide(region, lowerCount)) continue;
        builder.truncateTriangles(before);
        addClosing(builder, lower, upper, region, middleZMm);
        if (holdsAsFloats(builder, before)) {
            builder.markSearchedTogetherSince(before);
            return true;
        }
        fallback = std::move(region);
    }
    // No candidate holds as floats (or every shift left the sides
    // coinciding): the last one stays, and the piece's check reports it.
    builder.truncateTriangles(before);
    addClosing(builder, lower, upper, fallback ? *fallback : triangulateRegion(contours),
               middleZMm);
    return false;
}

}  // namespace dfrecon
