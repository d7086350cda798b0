#include "report/Reports.hpp"

#include <algorithm>
#include <cmath>

namespace dfrecon {

nlohmann::ordered_json contourReadingJson(const PlaneReadingCounts& counts) {
    return {{"rule", "even-odd"},
            {"repeatedPoints", counts.repeatedPoints},
            {"foldPoints", counts.foldPoints},
            {"zeroAreaContours", counts.zeroAreaContours},
            {"duplicateContours", counts.duplicateContours},
            {"keyholeCuts", counts.keyholeCuts},
            {"resolvedContours", counts.resolvedContours},
            {"planesResolved", counts.planesResolved},
            {"changedShape", counts.changedShape()}};
}

nlohmann::ordered_json meshCheckJson(const MeshCheckReport& r) {
    nlohmann::ordered_json examples = nlohmann::ordered_json::array();
    for (const auto& [a, b] : r.intersectingExamples) examples.push_back({a, b});
    return {{"validSolid", r.validSolid()},
            {"watertight", r.watertight()},
            {"vertices", r.vertices},
            {"triangles", r.triangles},
            {"edges", r.edges},
            {"components", r.components},
            {"eulerCharacteristic", r.eulerCharacteristic},
            {"genus", valueOrNull(r.genus >= 0, r.genus)},
            {"volumeMm3", r.volumeMm3},
            {"volumeCc", r.volumeMm3 / 1000},
            {"areaMm2", r.areaMm2},
            {"boundaryEdges", r.boundaryEdges},
            {"nonManifoldEdges", r.nonManifoldEdges},
            {"nonManifoldVertices", r.nonManifoldVertices},
            {"misorientedEdges", r.misorientedEdges},
            {"degenerateTriangles", r.degenerateTriangles},
            {"selfIntersectingPairs", r.intersectingPairs},
            {"selfIntersectingPairsAtLeast", r.intersectingPairsCapped},
            {"selfIntersectingExamples", examples}};
}

nlohmann::ordered_json defectLocationsJson(const MeshCheckReport& report,
                                           const TriangleSoup& soup) {
    auto corners = [&](std::size_t t) {
        nlohmann::ordered_json out = nlohmann::ordered_json::array();
        for (std::uint32_t v : soup.triangles[t]) out.push_back(xyzJson(soup.points[v]));
        return out;
    };
    Vec3 lo{INFINITY, INFINITY, INFINITY}, hi{-INFINITY, -INFINITY, -INFINITY};
    for (std::size_t t : report.defectiveTriangles)
        for (std::uint32_t v : soup.triangles[t]) {
            const Vec3 p = soup.points[v];
            lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
            hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
        }
    nlohmann::ordered_json pairs = nlohmann::ordered_json::array();
    for (const auto& [a, b] : report.intersectingExamples)
        pairs.push_back({{"triangles", {a, b}}, {"cornersMm", {corners(a), corners(b)}}});
    const bool any = !report.defectiveTriangles.empty();
    return {{"defectiveTriangles", report.defectiveTriangles.size()},
            {"defectBoxMm", any ? nlohmann::ordered_json{{"min", xyzJson(lo)}, {"max", xyzJson(hi)}}
                                : nlohmann::ordered_json(nullptr)},
            {"selfIntersectingAt", pairs}};
}

void appendItems(nlohmann::ordered_json& into, const nlohmann::ordered_json& items) {
    for (const auto& [key, value] : items.items()) into[key] = value;
}

nlohmann::ordered_json xyzJson(const Vec3& p) {
    return {p.x, p.y, p.z};
}

nlohmann::ordered_json segmentRegionsJson(const std::vector<RegionReport>& regions) {
    nlohmann::ordered_json out = nlohmann::ordered_json::array();
    for (std::size_t i = 0; i < regions.size(); ++i) {
        const RegionReport& r = regions[i];
        out.push_back({{"region", i},
                       {"seedVertex", r.seed},
                       {"areaMm2", r.areaMm2},
                       {"perimeterMm", r.perimeterMm},
                       {"compactness", r.compactness},
                       {"faces", r.faces},
                       {"disk", r.disk}});
    }
    return out;
}

}  // namespace dfrecon
