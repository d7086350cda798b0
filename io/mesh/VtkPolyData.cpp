#include "io/mesh/VtkPolyData.hpp"

#include <algorithm>
#include <cctype>
#include <cstring>
#include <ostream>

#include "io/files/Base64.hpp"

namespace dfrecon {

namespace {

bool littleEndian() {
    const std::uint16_t one = 1;
    unsigned char first;
    std::memcpy(&first, &one, 1);
    return first == 1;
}

std::vector<double> flatPoints(const std::vector<Vec3>& points) {
    std::vector<double> flat;
    flat.reserve(3 * points.size());
    for (const Vec3& p : points) flat.insert(flat.end(), {p.x, p.y, p.z});
    return flat;
}

std::vector<std::uint8_t> flatColours(const std::vector<Rgb>& colours) {
    std::vector<std::uint8_t> flat;
    flat.reserve(3 * colours.size());
    for (const Rgb& c : colours) flat.insert(flat.end(), c.begin(), c.end());
    return flat;
}

// ---- legacy VTK ---------------------------------------------------------------
//
// BINARY: VTK's legacy ASCII reader (9.1) refuses "nan" and "inf", which
// its own writer writes, and sdm's distances are infinite beyond the band.
// Binary values are big-endian, each array followed by a newline.

// VTK's legacy reader splits on white space and decodes %XX in names
// (vtkDataReader::DecodeString), as its writer encodes them.
std::string legacyEncoded(const std::string& text) {
    static const char* hex = "0123456789ABCDEF";
    std::string out;
    for (unsigned char c : text) {
        if (std::isalnum(c) || c == '_' || c == '-' || c == '.') {
            out += char(c);
        } else {
            out += '%';
            out += hex[c >> 4];
            out += hex[c & 15];
        }
    }
    return out;
}

template <class T>
void writeBigEndian(std::ostream& out, T value) {
    char bytes[sizeof(T)];
    std::memcpy(bytes, &value, sizeof(T));
    if (littleEndian()) std::reverse(bytes, bytes + sizeof(T));
    out.write(bytes, sizeof(T));
}

template <class T>
void writeBigEndian(std::ostream& out, const std::vector<T>& values) {
    std::string bytes(values.size() * sizeof(T), '\0');
    if (!values.empty()) std::memcpy(bytes.data(), values.data(), bytes.size());
    if (littleEndian())
        for (std::size_t k = 0; k < bytes.size(); k += sizeof(T))
            std::reverse(bytes.begin() + std::ptrdiff_t(k),
                         bytes.begin() + std::ptrdiff_t(k + sizeof(T)));
    out << bytes << '\n';
}

// A string of a binary string array: its length in 1, 2, 4 or 8 bytes, the
// two high bits saying which (3, 2, 1, 0), then its bytes.
void writeLegacyString(std::ostream& out, const std::string& text) {
    const std::uint64_t length = text.size();
    if (length < (1u << 6))
        writeBigEndian(out, std::uint8_t((3u << 6) | length));
    else if (length < (1u << 14))
        writeBigEndian(out, std::uint16_t((2u << 14) | length));
    else if (length < (1u << 30))
        writeBigEndian(out, std::uint32_t((1u << 30) | length));
    else
        writeBigEndian(out, length);
    out << text << '\n';
}

// The title is one line of at most 256 characters.
std::string legacyTitle(const StructureTag& structure) {
    if (structure.name.empty()) return "dfrecon mesh with per-vertex and per-face data";
    std::string title = "dfrecon surface of ROI " + structure.name;
    for (char& c : title)
        if (static_cast<unsigned char>(c) < ' ') c = ' ';
    return title.substr(0, 255);
}

void writeLegacyFieldData(std::ostream& out, const StructureTag& structure) {
    const int arrays = int(!structure.name.empty()) + int(structure.colour.has_value());
    if (arrays == 0) return;
    out << "FIELD FieldData " << arrays << '\n';
    if (!structure.name.empty()) {
        out << "roi_name 1 1 string\n";
        writeLegacyString(out, structure.name);
    }
    if (const auto& c = structure.colour) {
        out << "roi_colour 3 1 unsigned_char\n";
        writeBigEndian(out, std::vector<std::uint8_t>(c->begin(), c->end()));
    }
}

void writeLegacyLabels(std::ostream& out, const std::vector<NamedArray<std::int32_t>>& arrays) {
    for (const auto& [name, values] : arrays) {
        out << "SCALARS " << legacyEncoded(name) << " int 1\nLOOKUP_TABLE default\n";
        writeBigEndian(out, values);
    }
}

void writeLegacyColours(std::ostream& out, const std::vector<Rgb>& values) {
    if (values.empty()) return;
    out << "COLOR_SCALARS colour 3\n";
    writeBigEndian(out, flatColours(values));
}

// ---- VTK XML ------------------------------------------------------------------

std::string xmlEscaped(const std::string& text) {
    std::string out;
    for (char c : text) {
        switch (c) {
            case '&':
                out += "&amp;";
                break;
            case '<':
                out += "&lt;";
                break;
            case '>':
                out += "&gt;";
                break;
            case '"':
                out += "&quot;";
                break;
            default:
                out += c;
        }
    }
    return out;
}

// An inline binary DataArray: the byte count (UInt64) and the values, each
// base64-encoded on its own, as VTK's writer does (vtkXMLWriter).
template <class T>
void writeXmlArray(std::ostream& out, const char* type, const std::string& name, int components,
                   const std::vector<T>& values) {
    out << "        <DataArray type=\"" << type << "\" Name=\"" << xmlEscaped(name)
        << "\" NumberOfComponents=\"" << components << "\" format=\"binary\">\n          ";
    const std::uint64_t bytes = values.size() * sizeof(T);
    writeBase64(out, &bytes, sizeof bytes);
    writeBase64(out, values.data(), bytes);
    out << "\n        </DataArray>\n";
}

void writeXmlLabels(std::ostream& out, const std::vector<NamedArray<std::int32_t>>& arrays) {
    for (const auto& [name, values] : arrays) writeXmlArray(out, "Int32", name, 1, values);
}

// The array VTK takes as the active scalars (what ParaView colours by
// first), as the legacy reader takes the first SCALARS.
std::string activeScalars(const std::vector<NamedArray<float>>& scalars,
                          const std::vector<NamedArray<std::int32_t>>& labels,
                          const std::vector<Rgb>& colours) {
    if (!scalars.empty()) return scalars.front().name;
    if (!labels.empty()) return labels.front().name;
    return colours.empty() ? "" : "colour";
}

void writeXmlFieldData(std::ostream& out, const StructureTag& structure) {
    if (structure.empty()) return;
    out << "    <FieldData>\n";
    // ASCII string arrays hold each string's bytes as numbers, ended by 0.
    if (!structure.name.empty()) {
        out << "      <Array type=\"String\" Name=\"roi_name\" NumberOfTuples=\"1\" "
               "format=\"ascii\">\n        ";
        for (unsigned char c : structure.name) out << int(c) << ' ';
        out << "0\n      </Array>\n";
    }
    if (const auto& c = structure.colour)
        out << "      <DataArray type=\"UInt8\" Name=\"roi_colour\" NumberOfComponents=\"3\" "
               "NumberOfTuples=\"1\" format=\"ascii\">\n        "
            << int((*c)[0]) << ' ' << int((*c)[1]) << ' ' << int((*c)[2])
            << "\n      </DataArray>\n";
    out << "    </FieldData>\n";
}

}  // namespace

void writeVtkLegacy(std::ostream& out, const TriangleSoup& soup, const MeshAttributes& attributes) {
    checkAttributeSizes(attributes, soup.points.size(), soup.triangles.size());
    out << "# vtk DataFile Version 3.0\n"
        << legacyTitle(attributes.structure) << "\nBINARY\nDATASET POLYDATA\n";
    writeLegacyFieldData(out, attributes.structure);
    out << "POINTS " << soup.points.size() << " double\n";
    writeBigEndian(out, flatPoints(soup.points));
    out << "POLYGONS " << soup.triangles.size() << ' ' << 4 * soup.triangles.size() << '\n';
    std::vector<std::int32_t> polygons;
    polygons.reserve(4 * soup.triangles.size());
    for (const auto& t : soup.triangles)
        polygons.insert(polygons.end(),
                        {3, std::int32_t(t[0]), std::int32_t(t[1]), std::int32_t(t[2])});
    writeBigEndian(out, polygons);
    const bool vertexData = !attributes.vertexScalars.empty() || !attributes.vertexLabels.empty() ||
                            !attributes.vertexVectors.empty() || !attributes.vertexColours.empty();
    if (vertexData) {
        out << "POINT_DATA " << soup.points.size() << '\n';
        for (const auto& [name, values] : attributes.vertexScalars) {
            out << "SCALARS " << legacyEncoded(name) << " float 1\nLOOKUP_TABLE default\n";
            writeBigEndian(out, values);
        }
        writeLegacyLabels(out, attributes.vertexLabels);
        for (const auto& [name, values] : attributes.vertexVectors) {
            out << "VECTORS " << legacyEncoded(name) << " double\n";
            writeBigEndian(out, flatPoints(values));
        }
        writeLegacyColours(out, attributes.vertexColours);
    }
    if (attributes.hasFaceData()) {
        out << "CELL_DATA " << soup.triangles.size() << '\n';
        writeLegacyLabels(out, attributes.faceLabels);
        writeLegacyColours(out, attributes.faceColours);
    }
}

void writeVtkXml(std::ostream& out, const TriangleSoup& soup, const MeshAttributes& attributes) {
    checkAttributeSizes(attributes, soup.points.size(), soup.triangles.size());
    out << "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" version=\"1.0\" byte_order=\""
        << (littleEndian() ? "LittleEndian" : "BigEndian")
        << "\" header_type=\"UInt64\">\n  <PolyData>\n";
    writeXmlFieldData(out, attributes.structure);
    out << "    <Piece NumberOfPoints=\"" << soup.points.size()
        << "\" NumberOfVerts=\"0\" NumberOfLines=\"0\" NumberOfStrips=\"0\" NumberOfPolys=\""
        << soup.triangles.size() << "\">\n";

    const std::string pointScalars =
        activeScalars(attributes.vertexScalars, attributes.vertexLabels, attributes.vertexColours);
    out << "      <PointData";
    if (!pointScalars.empty()) out << " Scalars=\"" << xmlEscaped(pointScalars) << '"';
    if (!attributes.vertexVectors.empty())
        out << " Vectors=\"" << xmlEscaped(attributes.vertexVectors.front().name) << '"';
    out << ">\n";
    for (const auto& [name, values] : attributes.vertexScalars)
        writeXmlArray(out, "Float32", name, 1, values);
    writeXmlLabels(out, attributes.vertexLabels);
    for (const auto& [name, values] : attributes.vertexVectors)
        writeXmlArray(out, "Float64", name, 3, flatPoints(values));
    if (!attributes.vertexColours.empty())
        writeXmlArray(out, "UInt8", "colour", 3, flatColours(attributes.vertexColours));
    out << "      </PointData>\n";

    const std::string cellScalars =
        activeScalars({}, attributes.faceLabels, attributes.faceColours);
    out << "      <CellData";
    if (!cellScalars.empty()) out << " Scalars=\"" << xmlEscaped(cellScalars) << '"';
    out << ">\n";
    writeXmlLabels(out, attributes.faceLabels);
    if (!attributes.faceColours.empty())
        writeXmlArray(out, "UInt8", "colour", 3, flatColours(attributes.faceColours));
    out << "      </CellData>\n";

    out << "      <Points>\n";
    writeXmlArray(out, "Float64", "Points", 3, flatPoints(soup.points));
    out << "      </Points>\n";

    std::vector<std::int64_t> connectivity, offsets;
    connectivity.reserve(3 * soup.triangles.size());
    offsets.reserve(soup.triangles.size());
    for (const auto& t : soup.triangles) {
        connectivity.insert(connectivity.end(), t.begin(), t.end());
        offsets.push_back(std::int64_t(connectivity.size()));
    }
    out << "      <Polys>\n";
    writeXmlArray(out, "Int64", "connectivity", 1, connectivity);
    writeXmlArray(out, "Int64", "offsets", 1, offsets);
    out << "      </Polys>\n    </Piece>\n  </PolyData>\n</VTKFile>\n";
}

}  // namespace dfrecon
