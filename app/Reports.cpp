#include "app/Reports.hpp"

namespace dfrecon::app {

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
            {"selfIntersectingExamples", examples}};
}

void appendItems(nlohmann::ordered_json& into, const nlohmann::ordered_json& items) {
    for (const auto& [key, value] : items.items()) into[key] = value;
}

nlohmann::ordered_json xyzJson(const Vec3& p) {
    return {p.x, p.y, p.z};
}

}  // namespace dfrecon::app
