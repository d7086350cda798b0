#pragma once
// One self-contained HTML file a user can open anywhere: a table of results
// beside an interactive 3D view of the surfaces in their ROI colours (or
// coloured by a value per point, such as a surface distance map). The 3D
// viewer is three.js from the npm registry at a pinned version
// (scripts/vendor_viewer.sh), embedded with the surfaces, so the file opens
// from file:// with no network.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "geometry/TriangleSoup.hpp"
#include "io/images/Colours.hpp"

namespace dfrecon::app {

struct ReportSurface {
    std::string name;
    Rgb colour{200, 200, 200};
    TriangleSoup surface;  // patient mm (LPS)
    /// Per point of `surface`, or empty: each point then takes
    /// divergingColour(value, valueScaleMm) instead of `colour`.
    std::vector<float> valuesMm;
};

struct HtmlReport {
    std::string title;
    /// Table columns, in order; each row is an object with these keys.
    std::vector<std::string> columns;
    nlohmann::ordered_json rows = nlohmann::ordered_json::array();
    std::vector<ReportSurface> surfaces;
    /// What the values are ("signed distance to the nearest other surface,
    /// mm") and the magnitude the colour scale saturates at.
    std::string valueName;
    double valueScaleMm = 1;
    /// A line under the table (e.g. which surfaces were left out).
    std::string note;
};

/// Most triangles a report shows in all (about 130 MB of page): a command
/// adds surfaces while addSurface() says there is room, and names the rest
/// in HtmlReport::note.
inline constexpr std::size_t kMaxReportTriangles = std::size_t(8) << 20;

/// Adds `surface` to `report` unless that would take it past
/// kMaxReportTriangles; returns whether it did. O(1) (the surface is moved).
bool addSurface(HtmlReport& report, ReportSurface surface);

/// Writes `report` as one HTML file, atomically (io/files/AtomicWrite). The page
/// builds the table and the 3D view from data embedded in it: positions as
/// base64 float32, triangles as uint32, colours per point as RGB bytes.
/// Size about 30 bytes per point and 16 per triangle, plus 640 kB of
/// viewer. Once drawn, the page removes the embedded data from its
/// document (it holds the meshes, not their text too), and its body
/// carries data-surfaces (how many it drew) and data-webgl ("1", or "0"
/// where the browser has no WebGL: the table is there all the same), for
/// tests and scripts. Throws
/// std::runtime_error naming the file when it cannot be written. O(size).
void writeHtmlReport(const std::string& path, const HtmlReport& report);

}  // namespace dfrecon::app
