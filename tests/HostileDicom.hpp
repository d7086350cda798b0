#pragma once
// Hostile DICOM files built byte by byte (no DICOM library: a writer would
// recurse as a parser does): sequences nested far deeper than any parser's
// stack, and RT Structure Sets whose planes hold contours that all cross.
// Explicit VR little endian with File Meta Information.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>

namespace dfrecon::testing {

namespace hostiledicom {

inline void put16(std::string& out, std::uint16_t v) {
    out += char(v & 0xff);
    out += char(v >> 8);
}

inline void put32(std::string& out, std::uint32_t v) {
    for (int b = 0; b < 4; ++b) out += char((v >> (8 * b)) & 0xff);
}

inline std::string padded(std::string value, char pad = ' ') {
    if (value.size() % 2) value += pad;
    return value;
}

// An explicit VR element with a defined length.
inline std::string element(std::uint16_t group, std::uint16_t number, const char* vr,
                           const std::string& value) {
    std::string out;
    put16(out, group);
    put16(out, number);
    out += vr;
    const std::string v = vr[0] == 'U' && vr[1] == 'I' ? padded(value, '\0') : padded(value);
    const std::string name = vr;
    if (name == "OB" || name == "OW" || name == "SQ" || name == "UN" || name == "UT") {
        put16(out, 0);
        put32(out, std::uint32_t(v.size()));
    } else {
        put16(out, std::uint16_t(v.size()));
    }
    return out + v;
}

inline std::string item(const std::string& content) {
    std::string out;
    put16(out, 0xfffe);
    put16(out, 0xe000);
    put32(out, std::uint32_t(content.size()));
    return out + content;
}

inline std::string part10(const std::string& dataset) {
    const std::string sopClass = "1.2.840.10008.5.1.4.1.1.481.3";
    std::string meta = element(0x0002, 0x0001, "OB", std::string("\0\1", 2)) +
                       element(0x0002, 0x0002, "UI", sopClass) +
                       element(0x0002, 0x0003, "UI", "1.2.3.4") +
                       element(0x0002, 0x0010, "UI", "1.2.840.10008.1.2.1");
    std::string length;
    put32(length, std::uint32_t(meta.size()));
    meta = element(0x0002, 0x0000, "UL", length) + meta;
    return std::string(128, '\0') + "DICM" + meta + dataset;
}

inline std::string rtStructHeader() {
    return element(0x0008, 0x0016, "UI", "1.2.840.10008.5.1.4.1.1.481.3") +
           element(0x0008, 0x0060, "CS", "RTSTRUCT");
}

}  // namespace hostiledicom

/// An RTSTRUCT-looking file whose private tag (0009,1001) holds `depth`
/// sequences nested in one another, each of undefined length (36 bytes a
/// level: 100 000 levels are 3.6 MB).
inline std::string nestedSequencesDicom(std::size_t depth) {
    using namespace hostiledicom;
    std::string dataset = rtStructHeader() + element(0x0009, 0x0010, "LO", "HOSTILE");
    std::string open, close;
    for (std::size_t k = 0; k < depth; ++k) {
        put16(open, 0x0009);
        put16(open, 0x1001);
        open += "SQ";
        put16(open, 0);
        put32(open, 0xffffffffu);
        put16(open, 0xfffe);
        put16(open, 0xe000);
        put32(open, 0xffffffffu);
        put16(close, 0xfffe);
        put16(close, 0xe00d);
        put32(close, 0);
        put16(close, 0xfffe);
        put16(close, 0xe0dd);
        put32(close, 0);
    }
    return part10(dataset + open + close);
}

/// An RTSTRUCT with one ROI (number 1, "stars") whose `planes` planes, 2 mm
/// apart, each hold `contours` CLOSEDPLANAR_XOR stars of `spikes` spikes
/// (radii 50 and 20 mm) turned a little against each other: every two
/// stars cross in 2·spikes points.
inline std::string crossingStarsRtStruct(int contours, int spikes, int planes) {
    using namespace hostiledicom;
    std::string items;
    for (int p = 0; p < planes; ++p)
        for (int c = 0; c < contours; ++c) {
            const double turn = 2 * M_PI * c / contours / spikes * 0.97 + 0.001 * c;
            std::string data;
            for (int k = 0; k < 2 * spikes; ++k) {
                const double r = k % 2 == 0 ? 50 : 20, a = turn + M_PI * k / spikes;
                char text[96];
                std::snprintf(text, sizeof text, "%s%.4f\\%.4f\\%.4f", data.empty() ? "" : "\\",
                              r * std::cos(a), r * std::sin(a), 2.0 * p);
                data += text;
            }
            items += item(element(0x3006, 0x0042, "CS", "CLOSEDPLANAR_XOR") +
                          element(0x3006, 0x0046, "IS", std::to_string(2 * spikes)) +
                          element(0x3006, 0x0050, "DS", data));
        }
    const std::string roiList =
        item(element(0x3006, 0x0022, "IS", "1") + element(0x3006, 0x0026, "LO", "stars"));
    const std::string roiContours =
        item(element(0x3006, 0x0084, "IS", "1") + element(0x3006, 0x0040, "SQ", items));
    return part10(rtStructHeader() + element(0x3006, 0x0020, "SQ", roiList) +
                  element(0x3006, 0x0039, "SQ", roiContours));
}

}  // namespace dfrecon::testing
