#include "recon/SlabVolumes.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

#include "geometry/Polygon.hpp"
#include "geometry/UnionFind.hpp"
#include "recon/HermiteTangents.hpp"

namespace dfrecon {

PlaneSections sectionsOf(const std::vector<Slice>& slices) {
    PlaneSections planes;
    for (const Slice& slice : slices) {
        double area = 0, perimeter = 0;
        for (const Polygon& c : slice.contours) {
            area += signedArea(c);
            perimeter += perimeterMm(c);
        }
        planes.zMm.push_back(slice.zMm);
        planes.areaMm2.push_back(area);
        planes.perimeterMm.push_back(perimeter);
    }
    return planes;
}

namespace {

/// dA/dz at plane k (at least two planes): recon/SliceInterpolant's
/// tangents applied to the areas inside the stack — the slope of the
/// parabola through it and its neighbours, 0 where the area has not changed
/// over the two slabs on one side (a straight stretch: a tube's sections
/// beyond a rounded end would otherwise lend that end slab half its
/// secant). At the ends of the stack the end slab's secant, as the field
/// takes: the end parabola (recon/HermiteTangents endTangent) was measured
/// on the areas too, and while it brought analytic balls' and capsules' end
/// slabs to their volume, it spread the atlases' small areas (3–7 planes)
/// from their contour volumes (24 beyond 2 % instead of 11) at no gain
/// against their truth (docs/reconstruction.md, "Caps that follow a rounded
/// end").
double areaTangent(const PlaneSections& planes, std::size_t k) {
    const std::vector<double>& z = planes.zMm;
    const std::vector<double>& a = planes.areaMm2;
    const std::size_t n = z.size();
    auto secant = [&](std::size_t i) { return (a[i + 1] - a[i]) / (z[i + 1] - z[i]); };
    if (k == 0) return secant(0);
    if (k + 1 == n) return secant(n - 2);
    const auto beyondBelow = [&]() -> std::optional<double> {
        if (k < 2) return std::nullopt;
        return secant(k - 2);
    };
    const auto beyondAbove = [&]() -> std::optional<double> {
        if (k + 2 >= n) return std::nullopt;
        return secant(k + 1);
    };
    return innerTangent(z[k] - z[k - 1], secant(k - 1), z[k + 1] - z[k], secant(k), beyondBelow,
                        beyondAbove);
}

}  // namespace

std::vector<double> slabVolumeTargets(const PlaneSections& planes) {
    const std::vector<double>& z = planes.zMm;
    const std::vector<double>& a = planes.areaMm2;
    std::vector<double> targets;
    for (std::size_t k = 0; k + 1 < z.size(); ++k) {
        const double h = z[k + 1] - z[k];
        targets.push_back(0.5 * h * (a[k] + a[k + 1]) +
                          h * h / 12 * (areaTangent(planes, k) - areaTangent(planes, k + 1)));
    }
    return targets;
}

double hermiteAreaRatio(const PlaneSections& planes, double zMm) {
    const std::vector<double>& z = planes.zMm;
    const std::vector<double>& a = planes.areaMm2;
    if (z.size() < 2 || !(zMm > z.front() && zMm < z.back())) return 1;
    const std::size_t k = std::size_t(std::upper_bound(z.begin(), z.end(), zMm) - z.begin()) - 1;
    const double h = z[k + 1] - z[k], t = (zMm - z[k]) / h;
    const double linear = (1 - t) * a[k] + t * a[k + 1];
    const double t2 = t * t, t3 = t2 * t;
    const double cubic = (2 * t3 - 3 * t2 + 1) * a[k] +
                         (t3 - 2 * t2 + t) * h * areaTangent(planes, k) +
                         (-2 * t3 + 3 * t2) * a[k + 1] + (t3 - t2) * h * areaTangent(planes, k + 1);
    if (!(linear > 0) || !(cubic > 0)) return 1;
    return std::clamp(cubic / linear, kMinAreaRatio, kMaxAreaRatio);
}

namespace {

/// ∫ (z − zFloor) n_z dA over the flat triangle abc: its z-facing area times
/// its mean height above the floor (the divergence theorem's share of a
/// triangle in the volume above zFloor). O(1).
double fluxAboveFloor(Vec3 a, Vec3 b, Vec3 c, double zFloorMm) {
    return 0.5 * cross(b - a, c - a).z * ((a.z + b.z + c.z) / 3 - zFloorMm);
}

/// Per slab s and group g (index s · groups + g), the volume between the
/// slab's planes `z` that the group's triangles in the slab's piece bound
/// with its section on the upper plane (`upperArea(s, g)`), by the
/// divergence theorem; `groupOf(triangle)` names each triangle's group.
/// O(T).
template <class UpperArea, class GroupOf>
std::vector<double> volumesBetweenPlanes(const TriangleSoup& surface,
                                         const std::vector<std::uint32_t>& pieceOf,
                                         const std::vector<double>& z, std::size_t groups,
                                         UpperArea upperArea, GroupOf groupOf) {
    const std::size_t slabs = z.size() > 1 ? z.size() - 1 : 0;
    std::vector<double> volumes(slabs * groups, 0);
    for (std::size_t s = 0; s < slabs; ++s)
        for (std::size_t g = 0; g < groups; ++g)
            volumes[s * groups + g] = (z[s + 1] - z[s]) * upperArea(s, g);
    for (std::size_t t = 0; t < surface.triangles.size(); ++t) {
        if (pieceOf[t] == 0 || pieceOf[t] > slabs) continue;
        const std::size_t s = pieceOf[t] - 1;
        const auto& tri = surface.triangles[t];
        volumes[s * groups + groupOf(tri)] += fluxAboveFloor(
            surface.points[tri[0]], surface.points[tri[1]], surface.points[tri[2]], z[s]);
    }
    return volumes;
}

}  // namespace

std::vector<double> slabVolumes(const TriangleSoup& surface,
                                const std::vector<std::uint32_t>& pieceOf,
                                const PlaneSections& planes) {
    return volumesBetweenPlanes(
        surface, pieceOf, planes.zMm, 1,
        [&](std::size_t s, std::size_t) { return planes.areaMm2[s + 1]; },
        [](const auto&) { return std::size_t(0); });
}

namespace {

// Points are rounded to float before smoothing (as a mesh file holds
// them): a contour point 83.31 mm up lies 5e-6 mm off its plane's double.
// Points between the planes lie at least a 32nd of a slab away.
constexpr double kOnPlaneMm = 1e-4;

/// Whether `p` (on the plane of `edges`) lies inside the region they bound:
/// their winding number around it is not 0 (geometry/Polygon's
/// windingCrossing; edges walked both ways, inside a part, cancel). O(edges).
bool enclosedBy(Vec3 p, const std::vector<std::pair<Vec3, Vec3>>& edges) {
    int winding = 0;
    for (const auto& [a, b] : edges) winding += windingCrossing({p.x, p.y}, {a.x, a.y}, {b.x, b.y});
    return winding != 0;
}

/// parts.nested: a part whose sections enclose less than nothing (holes: a
/// cavity's wall), or one whose section lies inside such a part's on the
/// same plane (an island in a cavity).
void markNestedParts(SlabParts& parts,
                     const std::vector<std::vector<std::pair<Vec3, Vec3>>>& sectionEdges) {
    const std::size_t count = parts.count();
    parts.nested.assign(count, false);
    std::vector<std::size_t> cavities;
    for (std::size_t p = 0; p < count; ++p)
        if (parts.areaBelowMm2[p] + parts.areaAboveMm2[p] < 0) {
            parts.nested[p] = true;
            cavities.push_back(p);
        }
    for (std::size_t p = 0; p < count && !cavities.empty(); ++p) {
        if (parts.nested[p]) continue;
        for (int side = 0; side < 2 && !parts.nested[p]; ++side) {
            const auto& own = sectionEdges[2 * p + std::size_t(side)];
            if (own.empty()) continue;
            for (std::size_t c : cavities)
                if (parts.slabOf[c] == parts.slabOf[p] &&
                    enclosedBy(own.front().first, sectionEdges[2 * c + std::size_t(side)])) {
                    parts.nested[p] = true;
                    break;
                }
        }
    }
}

}  // namespace

SlabParts slabPartsOf(const TriangleSoup& surface, const std::vector<std::uint32_t>& pieceOf,
                      const PlaneSections& planes) {
    const std::size_t slabs = planes.zMm.size() > 1 ? planes.zMm.size() - 1 : 0;
    const std::size_t triangles = surface.triangles.size();
    auto inSlab = [&](std::size_t t) { return pieceOf[t] >= 1 && pieceOf[t] <= slabs; };
    // Triangles of one slab that share a vertex are one part. A vertex on a
    // plane is shared by the slabs below and above: it joins within a slab
    // only, so the first triangle of each (vertex, slab) is remembered per
    // slab side (below: the slab under the vertex's plane).
    UnionFind sets(triangles);
    const std::size_t kUnseen = SIZE_MAX;
    std::vector<std::size_t> firstBelow(surface.points.size(), kUnseen),
        firstAbove(surface.points.size(), kUnseen);
    for (std::size_t t = 0; t < triangles; ++t) {
        if (!inSlab(t)) continue;
        const std::size_t slab = pieceOf[t] - 1;
        for (std::uint32_t v : surface.triangles[t]) {
            // A vertex on the slab's upper plane is seen from below, one on
            // its lower plane from above, one between the planes either way.
            const bool onUpper = std::abs(surface.points[v].z - planes.zMm[slab + 1]) <= kOnPlaneMm;
            std::size_t& first = onUpper ? firstBelow[v] : firstAbove[v];
            if (first == kUnseen)
                first = t;
            else
                sets.join(t, first);
        }
    }
    SlabParts parts;
    parts.partOfTriangle.assign(triangles, SlabParts::kNone);
    std::vector<std::uint32_t> partOfRoot(triangles, SlabParts::kNone);
    for (std::size_t t = 0; t < triangles; ++t) {
        if (!inSlab(t)) continue;
        std::uint32_t& part = partOfRoot[sets.find(t)];
        if (part == SlabParts::kNone) {
            part = std::uint32_t(parts.slabOf.size());
            parts.slabOf.push_back(pieceOf[t] - 1);
        }
        parts.partOfTriangle[t] = part;
    }
    const std::size_t count = parts.count();
    parts.areaBelowMm2.assign(count, 0);
    parts.areaAboveMm2.assign(count, 0);
    parts.perimeterBelowMm.assign(count, 0);
    parts.perimeterAboveMm.assign(count, 0);
    parts.partOfVertex.assign(surface.points.size(), SlabParts::kNone);
    // Per vertex on a plane: the part of the slab below it and of the slab
    // above it that reach it.
    std::vector<std::uint32_t> fromBelow(surface.points.size(), SlabParts::kNone),
        fromAbove(surface.points.size(), SlabParts::kNone);
    // Each part's edges on its planes (its sections' borders), per plane
    // side, for the nesting test below.
    std::vector<std::vector<std::pair<Vec3, Vec3>>> sectionEdges(2 * count);
    for (std::size_t t = 0; t < triangles; ++t) {
        const std::uint32_t part = parts.partOfTriangle[t];
        if (part == SlabParts::kNone) continue;
        const std::size_t slab = parts.slabOf[part];
        const auto& tri = surface.triangles[t];
        for (int k = 0; k < 3; ++k) {
            const Vec3 a = surface.points[tri[std::size_t(k)]],
                       b = surface.points[tri[std::size_t((k + 1) % 3)]];
            // Edges inside the part are walked once each way and cancel;
            // what is left is the part's boundary on the plane, walked
            // against the section that closes the part there (outward
            // surface): upward on the lower plane's section, downward on the
            // upper one's.
            const double twiceArea = a.x * b.y - a.y * b.x;
            for (const bool upper : {false, true}) {
                const double z = planes.zMm[slab + (upper ? 1 : 0)];
                if (std::abs(a.z - z) > kOnPlaneMm || std::abs(b.z - z) > kOnPlaneMm) continue;
                (upper ? parts.areaAboveMm2 : parts.areaBelowMm2)[part] +=
                    (upper ? -0.5 : 0.5) * twiceArea;
                (upper ? parts.perimeterAboveMm : parts.perimeterBelowMm)[part] +=
                    std::hypot(b.x - a.x, b.y - a.y);
                sectionEdges[2 * part + (upper ? 1 : 0)].emplace_back(a, b);
            }
        }
        for (std::uint32_t v : tri) {
            const Vec3 p = surface.points[v];
            const bool onLower = std::abs(p.z - planes.zMm[slab]) <= kOnPlaneMm,
                       onUpper = std::abs(p.z - planes.zMm[slab + 1]) <= kOnPlaneMm;
            if (onLower) fromAbove[v] = part;
            if (onUpper) fromBelow[v] = part;
            if (!onLower && !onUpper) parts.partOfVertex[v] = part;
        }
    }
    for (std::size_t v = 0; v < surface.points.size(); ++v)
        if (fromBelow[v] != SlabParts::kNone && fromAbove[v] != SlabParts::kNone)
            parts.meetings.emplace_back(fromBelow[v], fromAbove[v]);
    markNestedParts(parts, sectionEdges);
    std::sort(parts.meetings.begin(), parts.meetings.end());
    parts.meetings.erase(std::unique(parts.meetings.begin(), parts.meetings.end()),
                         parts.meetings.end());
    return parts;
}

std::vector<double> partVolumeTargets(const SlabParts& parts, const PlaneSections& planes) {
    const std::size_t count = parts.count();
    std::vector<double> height(count), secant(count);
    for (std::size_t p = 0; p < count; ++p) {
        const std::size_t slab = parts.slabOf[p];
        height[p] = planes.zMm[slab + 1] - planes.zMm[slab];
        secant[p] = (parts.areaAboveMm2[p] - parts.areaBelowMm2[p]) / height[p];
    }
    // Across each plane, the parts that meet there as one: their areas
    // summed on either side, so a branching's two arms count as the one
    // trunk they continue.
    std::vector<double> belowArea(count, 0), belowAreaUnder(count, 0), aboveArea(count, 0),
        aboveAreaOver(count, 0);
    std::vector<bool> hasBelow(count, false), hasAbove(count, false);
    for (const auto& [lower, upper] : parts.meetings) {
        hasBelow[upper] = hasAbove[lower] = true;
        belowArea[upper] += parts.areaAboveMm2[lower];
        belowAreaUnder[upper] += parts.areaBelowMm2[lower];
        aboveArea[lower] += parts.areaBelowMm2[upper];
        aboveAreaOver[lower] += parts.areaAboveMm2[upper];
    }
    std::vector<double> targets(count);
    for (std::size_t p = 0; p < count; ++p) {
        const double h = height[p];
        // The tangent at each plane: the parabola's slope through the
        // neighbours' secant and this part's (the slabs' heights weigh
        // them), or this part's own secant where it meets nothing there.
        double lower = secant[p], upper = secant[p];
        if (hasBelow[p]) {
            const std::size_t slab = parts.slabOf[p];
            const double hBelow = planes.zMm[slab] - planes.zMm[slab - 1];
            const double dBelow = (belowArea[p] - belowAreaUnder[p]) / hBelow;
            lower = (h * dBelow + hBelow * secant[p]) / (hBelow + h);
        }
        if (hasAbove[p]) {
            const std::size_t slab = parts.slabOf[p];
            const double hAbove = planes.zMm[slab + 2] - planes.zMm[slab + 1];
            const double dAbove = (aboveAreaOver[p] - aboveArea[p]) / hAbove;
            upper = (hAbove * secant[p] + h * dAbove) / (h + hAbove);
        }
        targets[p] = 0.5 * h * (parts.areaBelowMm2[p] + parts.areaAboveMm2[p]) +
                     h * h / 12 * (lower - upper);
    }
    return targets;
}

std::vector<double> partVolumes(const TriangleSoup& surface, const SlabParts& parts,
                                const PlaneSections& planes) {
    std::vector<double> volumes(parts.count(), 0);
    for (std::size_t part = 0; part < parts.count(); ++part) {
        const std::size_t slab = parts.slabOf[part];
        volumes[part] = (planes.zMm[slab + 1] - planes.zMm[slab]) * parts.areaAboveMm2[part];
    }
    for (std::size_t t = 0; t < surface.triangles.size(); ++t) {
        const std::uint32_t part = parts.partOfTriangle[t];
        if (part == SlabParts::kNone) continue;
        const auto& tri = surface.triangles[t];
        volumes[part] += fluxAboveFloor(surface.points[tri[0]], surface.points[tri[1]],
                                        surface.points[tri[2]], planes.zMm[parts.slabOf[part]]);
    }
    return volumes;
}

std::vector<double> ownVolumeTargets(const PlaneSections& sections) {
    const std::size_t n = sections.zMm.size();
    std::vector<double> targets(n > 1 ? n - 1 : 0, 0.0);
    std::size_t first = n, last = 0;
    for (std::size_t k = 0; k < n; ++k)
        if (sections.perimeterMm[k] > 0) first = std::min(first, k), last = k;
    if (first >= last) return targets;
    PlaneSections own;
    for (std::size_t k = first; k <= last; ++k) {
        own.zMm.push_back(sections.zMm[k]);
        own.areaMm2.push_back(sections.areaMm2[k]);
        own.perimeterMm.push_back(sections.perimeterMm[k]);
    }
    const std::vector<double> inner = slabVolumeTargets(own);
    std::copy(inner.begin(), inner.end(), targets.begin() + std::ptrdiff_t(first));
    return targets;
}

SurfaceComponents surfaceComponents(const TriangleSoup& surface) {
    UnionFind sets(surface.points.size());
    std::vector<bool> used(surface.points.size(), false);
    for (const auto& tri : surface.triangles) {
        sets.join(tri[0], tri[1]);
        sets.join(tri[1], tri[2]);
        used[tri[0]] = used[tri[1]] = used[tri[2]] = true;
    }
    SurfaceComponents components;
    components.ofVertex.assign(surface.points.size(), SurfaceComponents::kNone);
    std::vector<std::uint32_t> ofRoot(surface.points.size(), SurfaceComponents::kNone);
    for (std::size_t v = 0; v < surface.points.size(); ++v) {
        if (!used[v]) continue;
        std::uint32_t& c = ofRoot[sets.find(v)];
        if (c == SurfaceComponents::kNone) c = std::uint32_t(components.count++);
        components.ofVertex[v] = c;
    }
    return components;
}

std::vector<PlaneSections> componentSections(
    const TriangleSoup& surface, const std::vector<double>& planeZMm,
    const std::vector<std::vector<std::vector<std::uint32_t>>>& planeLoops,
    const SurfaceComponents& components) {
    std::vector<PlaneSections> sections(components.count);
    for (PlaneSections& c : sections) {
        c.zMm = planeZMm;
        c.areaMm2.assign(planeZMm.size(), 0);
        c.perimeterMm.assign(planeZMm.size(), 0);
    }
    for (std::size_t k = 0; k < planeLoops.size() && k < planeZMm.size(); ++k)
        for (const std::vector<std::uint32_t>& loop : planeLoops[k]) {
            if (loop.empty()) continue;
            const std::uint32_t c = components.ofVertex[loop[0]];
            if (c == SurfaceComponents::kNone) continue;
            Polygon contour;
            contour.reserve(loop.size());
            for (std::uint32_t v : loop)
                contour.push_back({surface.points[v].x, surface.points[v].y});
            sections[c].areaMm2[k] += signedArea(contour);
            sections[c].perimeterMm[k] += perimeterMm(contour);
        }
    return sections;
}

std::vector<double> componentSlabVolumes(const TriangleSoup& surface,
                                         const std::vector<std::uint32_t>& pieceOf,
                                         const std::vector<PlaneSections>& sections,
                                         const SurfaceComponents& components) {
    if (components.count == 0) return {};
    return volumesBetweenPlanes(
        surface, pieceOf, sections[0].zMm, components.count,
        [&](std::size_t s, std::size_t c) { return sections[c].areaMm2[s + 1]; },
        [&](const auto& tri) { return std::size_t(components.ofVertex[tri[0]]); });
}

}  // namespace dfrecon
