#include "app/HtmlReport.hpp"

#include <zlib.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <vector>

#include "io/files/AtomicWrite.hpp"
#include "io/files/Base64.hpp"
#include "io/files/JsonText.hpp"
#include "io/images/Colours.hpp"

namespace dfrecon::app {

// cmake/EmbedReportAssets.cmake: the vendored three.js, its OrbitControls,
// and app/ReportViewer.js.
extern const char* const kThreeJs;
extern const char* const kOrbitControlsJs;
extern const char* const kReportViewerJs;

namespace {

// `size` bytes deflated in zlib's format, which the page inflates with the
// browser's own DecompressionStream("deflate") (no library, no network), as
// base64. The default level: level 9 saves a few per cent for several times
// the time.
std::string deflated64(const void* data, std::size_t size) {
    uLongf packed = compressBound(uLong(size));
    std::vector<Bytef> out(packed);
    if (compress2(out.data(), &packed, static_cast<const Bytef*>(data), uLong(size),
                  Z_DEFAULT_COMPRESSION) != Z_OK)
        throw std::runtime_error("report: cannot compress a surface");
    return base64(out.data(), packed);
}

// A surface as the page decodes it (app/ReportViewer.js, `surfaceGeometry`):
// positions as 16-bit steps across the surface's box (each within half a
// step of the float it stands for: `positionBoundMm`), corner indices as
// zigzag differences from the corner before (neighbouring triangles share
// corners, so most differences are small), each deflated. About a third of
// the floats and 32-bit indices in base64 that the page held before.
nlohmann::ordered_json surfaceJson(const ReportSurface& s, double valueScaleMm) {
    double lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
    for (std::size_t i = 0; i < s.surface.points.size(); ++i) {
        const Vec3& p = s.surface.points[i];
        for (int a = 0; a < 3; ++a) {
            lo[a] = i == 0 ? p[a] : std::min(lo[a], p[a]);
            hi[a] = i == 0 ? p[a] : std::max(hi[a], p[a]);
        }
    }
    double stepMm[3];
    for (int a = 0; a < 3; ++a) stepMm[a] = hi[a] > lo[a] ? (hi[a] - lo[a]) / 65535.0 : 1.0;
    std::vector<std::uint16_t> positions;
    positions.reserve(3 * s.surface.points.size());
    for (const Vec3& p : s.surface.points)
        for (int a = 0; a < 3; ++a)
            positions.push_back(std::uint16_t(std::lround((p[a] - lo[a]) / stepMm[a])));
    std::vector<std::int32_t> corners;
    corners.reserve(3 * s.surface.triangles.size());
    std::int64_t previous = 0;
    for (const auto& t : s.surface.triangles)
        for (int k = 0; k < 3; ++k) {
            const std::int64_t delta = std::int64_t(t[k]) - previous;
            previous = t[k];
            corners.push_back(std::int32_t(delta >= 0 ? 2 * delta : -2 * delta - 1));  // zigzag
        }
    nlohmann::ordered_json out{
        {"name", s.name},
        {"colour", {s.colour[0], s.colour[1], s.colour[2]}},
        {"boxMinMm", {lo[0], lo[1], lo[2]}},
        {"stepMm", {stepMm[0], stepMm[1], stepMm[2]}},
        {"positionBoundMm", 0.5 * std::max({stepMm[0], stepMm[1], stepMm[2]})},
        {"positions", deflated64(positions.data(), positions.size() * sizeof(std::uint16_t))},
        {"corners", deflated64(corners.data(), corners.size() * sizeof(std::int32_t))}};
    if (!s.valuesMm.empty()) {
        std::vector<std::uint8_t> colours;
        colours.reserve(3 * s.valuesMm.size());
        for (const float v : s.valuesMm)
            for (const std::uint8_t c : divergingColour(v, valueScaleMm)) colours.push_back(c);
        out["pointColours"] = deflated64(colours.data(), colours.size());
    }
    return out;
}

// JSON text made inert inside a <script> element. The HTML parser reads a
// script's content as raw text that ends at "</script" and changes state at
// "<!--" and "<script" (a name a planning system lets a user type can hold
// any of them), so no '<' may reach it; '>' and '&' go too, so nothing in
// the block reads as markup to any tool, and U+2028/U+2029, which older
// JavaScript engines took as line ends. JSON has these characters only
// inside strings, where \uXXXX is the same character to JSON.parse.
std::string scriptSafe(const std::string& json) {
    std::string out;
    out.reserve(json.size());
    for (std::size_t i = 0; i < json.size(); ++i) {
        const char c = json[i];
        if (c == '<')
            out += "\\u003c";
        else if (c == '>')
            out += "\\u003e";
        else if (c == '&')
            out += "\\u0026";
        else if (c == '\xE2' && i + 2 < json.size() && json[i + 1] == '\x80' &&
                 (json[i + 2] == '\xA8' || json[i + 2] == '\xA9')) {
            out += json[i + 2] == '\xA8' ? "\\u2028" : "\\u2029";
            i += 2;
        } else {
            out += c;
        }
    }
    return out;
}

}  // namespace

bool addSurface(HtmlReport& report, ReportSurface surface) {
    std::size_t triangles = surface.surface.triangles.size();
    for (const ReportSurface& s : report.surfaces) triangles += s.surface.triangles.size();
    if (triangles > kMaxReportTriangles) return false;
    report.surfaces.push_back(std::move(surface));
    return true;
}

void writeHtmlReport(const std::string& path, const HtmlReport& report) {
    nlohmann::ordered_json data{{"title", report.title},
                                {"columns", report.columns},
                                {"rows", report.rows},
                                {"valueName", report.valueName},
                                {"valueScaleMm", report.valueScaleMm},
                                {"note", report.note},
                                {"surfaces", nlohmann::ordered_json::array()}};
    for (const ReportSurface& s : report.surfaces)
        data["surfaces"].push_back(surfaceJson(s, report.valueScaleMm));
    writeStreamAtomically(path, [&](std::ostream& out) {
        out << "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
            << "<meta name=\"generator\" content=\"dfrecon\">\n<title>dfrecon report</title>\n"
            << "<style>\nbody{font:14px system-ui,sans-serif;margin:0;display:flex;"
               "height:100vh}\n#side{width:38%;display:flex;flex-direction:column;padding:8px "
               "12px;box-sizing:border-box;min-width:0}h1{font-size:18px;overflow-wrap:anywhere}\n"
               "#table{overflow:auto;flex:1;min-height:0}\n#view{flex:1;position:relative;"
               "background:#20242a;min-width:0}\n"
               "table{border-collapse:collapse}td,th{padding:2px 6px;border-bottom:1px solid "
               "#ddd;text-align:right;white-space:nowrap;background:#fff}"
               "td:first-child,th:first-child{text-align:left;position:sticky;left:0;z-index:1}\n"
               "th{position:sticky;top:0;cursor:pointer;z-index:2}th:first-child{z-index:3}"
               "th[data-sort=up]::after{content:' \\25B2'}th[data-sort=down]::after{content:' "
               "\\25BC'}\n.swatch{display:inline-block;width:10px;height:10px;margin-right:4px}"
               ".opacity{width:56px;vertical-align:middle;margin-left:6px}\n"
               "#note{color:#eee;position:absolute;left:8px;bottom:8px}\n"
               "#views{position:absolute;left:8px;top:8px;z-index:1}#views button{margin-right:"
               "4px}\n#marker{position:absolute;right:8px;bottom:8px;width:96px;height:96px;"
               "font-weight:bold;pointer-events:none}\n</style>\n"
            << "</head>\n<body>\n<div id=\"side\"><h1 id=\"title\"></h1><div "
               "id=\"table\"></div><p id=\"legend\"></p></div>\n<div id=\"view\"><div "
               "id=\"note\"></div></div>\n"
            << "<script id=\"dfrecon-data\" type=\"application/json\">"
            << scriptSafe(jsonText(data)) << "</script>\n"
            << "<script>\n"
            << kThreeJs << "\n</script>\n"
            << "<script>\n"
            << kOrbitControlsJs << "\n</script>\n"
            << "<script>\n"
            << kReportViewerJs << "\n</script>\n"
            << "</body>\n</html>\n";
    });
}

}  // namespace dfrecon::app
