#include "io/contours/ContourFormat.hpp"

#include <array>
#include <cstdint>
#include <fstream>

#include "io/files/FileNames.hpp"
#include "io/files/RegularFile.hpp"
#include "io/labels/MaskStack.hpp"

namespace dfrecon {

namespace {

// The first bytes of `path` (up to 132: enough for DICOM's preamble and
// magic), or none when it is not a regular file or cannot be read.
std::string leadingBytes(const std::string& path) {
    if (!isRegularFile(path)) return {};  // never open a pipe or a device to sniff it
    std::ifstream in(path, std::ios::binary);
    std::array<char, 132> bytes{};
    in.read(bytes.data(), std::streamsize(bytes.size()));
    return std::string(bytes.data(), std::size_t(in.gcount()));
}

bool hasDicomMagic(const std::string& head) {
    return head.size() >= 132 && head.compare(128, 4, "DICM") == 0;
}

// NIfTI-1 and NIfTI-2 open with their header's size, 348 or 540, as a
// 32-bit integer in the file's byte order.
bool hasNiftiHeaderSize(const std::string& head) {
    if (head.size() < 4) return false;
    const auto byte = [&](int k) { return std::uint32_t(std::uint8_t(head[std::size_t(k)])); };
    const std::uint32_t little = byte(0) | byte(1) << 8 | byte(2) << 16 | byte(3) << 24;
    const std::uint32_t big = byte(3) | byte(2) << 8 | byte(1) << 16 | byte(0) << 24;
    for (std::uint32_t size : {348u, 540u})
        if (little == size || big == size) return true;
    return false;
}

}  // namespace

const std::vector<std::string>& labelVolumeExtensions() {
    static const std::vector<std::string> extensions{".nrrd", ".nhdr", ".nii", ".nii.gz"};
    return extensions;
}

bool hasLabelVolumeExtension(const std::string& path) {
    for (const std::string& end : labelVolumeExtensions())
        if (endsWithIgnoringCase(path, end)) return true;
    return false;
}

bool isDicomFile(const std::string& path) {
    return endsWithIgnoringCase(path, ".dcm") || hasDicomMagic(leadingBytes(path));
}

ContourFormat contourFormatOf(const std::string& path) {
    if (path == "-") return ContourFormat::Slices;
    const std::string head = leadingBytes(path);
    if (hasDicomMagic(head)) return ContourFormat::RtStruct;
    if (head.rfind("NRRD000", 0) == 0 || hasNiftiHeaderSize(head))
        return ContourFormat::LabelVolume;
    if (endsWithIgnoringCase(path, ".dcm")) return ContourFormat::RtStruct;
    if (hasLabelVolumeExtension(path)) return ContourFormat::LabelVolume;
    if (isMaskStackPath(path)) return ContourFormat::MaskStack;
    return ContourFormat::Slices;
}

const char* contourFormatName(ContourFormat format) {
    switch (format) {
        case ContourFormat::Slices:
            return "dfrecon-slices 1";
        case ContourFormat::RtStruct:
            return "DICOM RTSTRUCT";
        case ContourFormat::LabelVolume:
            return "label volume";
        case ContourFormat::MaskStack:
            return "mask stack";
    }
    return "?";
}

const std::string& contourInputHelp() {
    static const std::string help = [] {
        std::string extensions;
        for (const std::string& e : labelVolumeExtensions())
            extensions += (extensions.empty() ? "" : " ") + e;
        return "Input contours: .slices (- reads it from standard input), DICOM RTSTRUCT (.dcm "
               "or any DICOM file), a label volume (" +
               extensions + ": one ROI per label) or a mask stack (a folder with " +
               std::string(kMaskStackSidecar) + ")";
    }();
    return help;
}

}  // namespace dfrecon
