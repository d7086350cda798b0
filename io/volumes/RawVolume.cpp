#include "io/volumes/RawVolume.hpp"

#include <cstdio>
#include <filesystem>
#include <ostream>
#include <stdexcept>

#include "io/files/AtomicWrite.hpp"

namespace dfrecon {

namespace {

std::ostream& operator<<(std::ostream& out, const Vec3& v) {
    return out << "(" << v.x << "," << v.y << "," << v.z << ")";
}

// The lines every header shares, after "dimension".
void writeCommon(std::ostream& out, const RawVolumeInfo& info, const char* nrrdType) {
    out << "# " << info.description << "\n"
        << "type: " << nrrdType << "\n";
}

void writeTail(std::ostream& out, Vec3 originMm, const std::string& dataFile) {
    out << "space origin: " << originMm << "\n"
        << "endian: little\n"
        << "encoding: raw\n"
        << "data file: " << dataFile << "\n";
}

template <class T>
std::vector<std::string> writeVolume(const std::string& nhdrPath, const std::string& rawPath,
                                     const std::vector<T>& values, const RawVolumeInfo& info,
                                     const char* nrrdType) {
    static_assert(sizeof(T) == 4, "4-byte samples");
    const std::size_t sliceSamples = std::size_t(info.width) * std::size_t(info.height);
    if (values.size() != sliceSamples * std::size_t(info.slices))
        throw std::invalid_argument("writeRawVolume: size mismatch");
    if (!info.sliceOriginsMm.empty() && info.sliceOriginsMm.size() != std::size_t(info.slices))
        throw std::invalid_argument("writeRawVolume: one origin per slice needed");
    // Samples are written little-endian, as this program only builds on such hosts.
    static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__, "little-endian host expected");
    writeStreamAtomically(rawPath, [&](std::ostream& out) {
        out.write(reinterpret_cast<const char*>(values.data()),
                  std::streamsize(values.size() * sizeof(T)));
    });
    const std::string dataFile = std::filesystem::path(rawPath).filename().string();
    if (info.sliceOriginsMm.empty()) {
        writeStreamAtomically(nhdrPath, [&](std::ostream& out) {
            out.precision(17);
            out << "NRRD0004\n";
            writeCommon(out, info, nrrdType);
            // Patient LPS, as DICOM and the meshes: 3D Slicer reads both alike.
            out << "dimension: 3\n"
                << "space: left-posterior-superior\n"
                << "sizes: " << info.width << " " << info.height << " " << info.slices << "\n"
                << "space directions: " << info.stepMm[0] << " " << info.stepMm[1] << " "
                << info.stepMm[2] << "\n"
                << "kinds: domain domain domain\n"
                << "space units: \"mm\" \"mm\" \"mm\"\n";
            writeTail(out, info.originMm, dataFile);
        });
        return {nhdrPath};
    }
    std::string stem = nhdrPath;
    if (stem.size() > 5 && stem.compare(stem.size() - 5, 5, ".nhdr") == 0)
        stem.resize(stem.size() - 5);
    std::vector<std::string> headers;
    for (int s = 0; s < info.slices; ++s) {
        char suffix[32];
        std::snprintf(suffix, sizeof suffix, "-%03d.nhdr", s);
        headers.push_back(stem + suffix);
        writeStreamAtomically(headers.back(), [&](std::ostream& out) {
            out.precision(17);
            out << "NRRD0004\n";
            writeCommon(out, info, nrrdType);
            out << "# slice " << s << " of " << info.slices
                << " (planes unevenly spaced: one header per slice)\n"
                << "dimension: 2\n"
                << "space: left-posterior-superior\n"
                << "sizes: " << info.width << " " << info.height << "\n"
                << "space directions: " << info.stepMm[0] << " " << info.stepMm[1] << "\n"
                << "kinds: domain domain\n"
                << "space units: \"mm\" \"mm\" \"mm\"\n"
                << "byte skip: " << std::size_t(s) * sliceSamples * sizeof(T) << "\n";
            writeTail(out, info.sliceOriginsMm[std::size_t(s)], dataFile);
        });
    }
    return headers;
}

}  // namespace

std::vector<std::string> writeRawVolume(const std::string& nhdrPath, const std::string& rawPath,
                                        const std::vector<float>& values,
                                        const RawVolumeInfo& info) {
    return writeVolume(nhdrPath, rawPath, values, info, "float");
}

std::vector<std::string> writeRawVolume(const std::string& nhdrPath, const std::string& rawPath,
                                        const std::vector<std::uint32_t>& values,
                                        const RawVolumeInfo& info) {
    return writeVolume(nhdrPath, rawPath, values, info, "uint32");
}

}  // namespace dfrecon
