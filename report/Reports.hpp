#pragma once
// The JSON form of each result that more than one command reports, written
// once so that a key means the same in every report (docs/cli.md).
#include <optional>
#include <vector>

#include <nlohmann/json.hpp>

#include "geometry/MeshCheck.hpp"
#include "geometry/PlaneReading.hpp"
#include "geometry/TriangleSoup.hpp"
#include "geometry/Vec3.hpp"
#include "segment/Segmentation.hpp"

namespace dfrecon {

/// Reports give volumes in cc (cm³), as planning systems do.
inline constexpr double kCubicMmPerCc = 1000;

/// The mesh checker's findings as a flat object: validSolid, watertight,
/// vertices, triangles, edges, components, eulerCharacteristic, genus (null
/// unless closed and manifold), volumeMm3, volumeCc, areaMm2, boundaryEdges,
/// nonManifoldEdges, nonManifoldVertices, misorientedEdges,
/// degenerateTriangles, selfIntersectingPairs and selfIntersectingExamples
/// (the first few pairs of triangle indices). O(examples).
nlohmann::ordered_json meshCheckJson(const MeshCheckReport& report);

/// Where `soup`'s defects are (its check `report`): `defectiveTriangles`
/// (how many take part in a defect), `defectBoxMm` (the box around them,
/// {min, max}, null when none) and `selfIntersectingAt` (the first few
/// intersecting pairs with their corners in mm, to find them in a viewer).
/// O(defective triangles).
nlohmann::ordered_json defectLocationsJson(const MeshCheckReport& report, const TriangleSoup& soup);

/// What reading changed in an ROI's contours (geometry/PlaneReading), as
/// {rule: "even-odd", repeatedPoints, foldPoints, zeroAreaContours,
/// duplicateContours, keyholeCuts, resolvedContours, planesResolved,
/// changedShape}. O(1).
nlohmann::ordered_json contourReadingJson(const PlaneReadingCounts& counts);

/// Copies every item of `items` into `into`, after the keys it has. O(items).
void appendItems(nlohmann::ordered_json& into, const nlohmann::ordered_json& items);

/// A point or vector as [x, y, z]. O(1).
nlohmann::ordered_json xyzJson(const Vec3& p);

/// Each region of a segmentation as `segment --json` lists it (region,
/// seedVertex, areaMm2, perimeterMm, compactness, faces, disk). O(regions).
nlohmann::ordered_json segmentRegionsJson(const std::vector<RegionReport>& regions);

/// Any three indexable values (sizes, spacings, an origin) as [a, b, c]. O(1).
template <class Triple>
nlohmann::ordered_json xyzJson(const Triple& t) {
    return {t[0], t[1], t[2]};
}

/// `value` when `present`, else null: the reports' one way of saying "not
/// given" or "not defined". Always builds a json value first, so that a
/// null `const char*` never reaches json's std::string constructor. O(1).
template <class T>
nlohmann::ordered_json valueOrNull(bool present, const T& value) {
    return present ? nlohmann::ordered_json(value) : nlohmann::ordered_json(nullptr);
}

/// The optional's value, else null. O(1).
template <class T>
nlohmann::ordered_json valueOrNull(const std::optional<T>& value) {
    return value ? nlohmann::ordered_json(*value) : nlohmann::ordered_json(nullptr);
}

}  // namespace dfrecon
