#include "app/HtmlReport.hpp"

#include <cstdint>

#include "io/AtomicWrite.hpp"
#include "io/Base64.hpp"
#include "io/Colours.hpp"
#include "io/JsonText.hpp"

namespace dfrecon::app {

// cmake/EmbedReportAssets.cmake: the vendored three.js, its OrbitControls,
// and app/ReportViewer.js.
extern const char* const kThreeJs;
extern const char* const kOrbitControlsJs;
extern const char* const kReportViewerJs;

namespace {

nlohmann::ordered_json surfaceJson(const ReportSurface& s, double valueScaleMm) {
    std::vector<float> positions;
    positions.reserve(3 * s.surface.points.size());
    for (const Vec3& p : s.surface.points) {
        positions.push_back(float(p.x));
        positions.push_back(float(p.y));
        positions.push_back(float(p.z));
    }
    std::vector<std::uint32_t> triangles;
    triangles.reserve(3 * s.surface.triangles.size());
    for (const auto& t : s.surface.triangles)
        for (int k = 0; k < 3; ++k) triangles.push_back(std::uint32_t(t[k]));
    nlohmann::ordered_json out{
        {"name", s.name},
        {"colour", {s.colour[0], s.colour[1], s.colour[2]}},
        {"positions", base64(positions.data(), positions.size() * sizeof(float))},
        {"triangles", base64(triangles.data(), triangles.size() * sizeof(std::uint32_t))}};
    if (!s.valuesMm.empty()) {
        std::vector<std::uint8_t> colours;
        colours.reserve(3 * s.valuesMm.size());
        for (const float v : s.valuesMm)
            for (const std::uint8_t c : divergingColour(v, valueScaleMm)) colours.push_back(c);
        out["pointColours"] = base64(colours.data(), colours.size());
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
               "height:100vh}\n#side{width:38%;overflow:auto;padding:8px 12px;box-sizing:"
               "border-box}h1{font-size:18px;overflow-wrap:anywhere}\n#view{flex:1;position:"
               "relative;background:#20242a}\n"
               "table{border-collapse:collapse}td,th{padding:2px 6px;border-bottom:1px solid "
               "#ddd;text-align:right}td:first-child,th:first-child{text-align:left}\n"
               ".swatch{display:inline-block;width:10px;height:10px;margin-right:4px}\n"
               "#note{color:#eee;position:absolute;left:8px;bottom:8px}td{white-space:nowrap}\n</"
               "style>\n"
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
