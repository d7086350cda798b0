#include "io/RawVolume.hpp"

#include <cstring>
#include <filesystem>
#include <ostream>
#include <stdexcept>

#include "io/AtomicWrite.hpp"

namespace dfrecon {

namespace {

template <class T>
void writeVolume(const std::string& nhdrPath, const std::string& rawPath,
                 const std::vector<T>& values, const RawVolumeInfo& info, const char* nrrdType) {
    static_assert(sizeof(T) == 4, "4-byte samples");
    const std::size_t count =
        std::size_t(info.width) * std::size_t(info.height) * std::size_t(info.slices);
    if (values.size() != count) throw std::invalid_argument("writeRawVolume: size mismatch");
    // Samples are written little-endian, as this program only builds on such hosts.
    static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__, "little-endian host expected");
    writeStreamAtomically(rawPath, [&](std::ostream& out) {
        out.write(reinterpret_cast<const char*>(values.data()),
                  std::streamsize(values.size() * sizeof(T)));
    });
    const std::string dataFile = std::filesystem::path(rawPath).filename().string();
    writeStreamAtomically(nhdrPath, [&](std::ostream& out) {
        out.precision(17);
        out << "NRRD0004\n"
            << "# " << info.description << "\n"
            << "type: " << nrrdType << "\n"
            << "dimension: 3\n"
            // Patient LPS, as DICOM and the meshes: 3D Slicer reads both alike.
            << "space: left-posterior-superior\n"
            << "sizes: " << info.width << " " << info.height << " " << info.slices << "\n"
            << "space directions: (" << info.spacingMm[0] << ",0,0) (0," << info.spacingMm[1]
            << ",0) (0,0," << info.spacingMm[2] << ")\n"
            << "space origin: (" << info.originMm[0] << "," << info.originMm[1] << ","
            << info.originMm[2] << ")\n"
            << "space units: \"mm\" \"mm\" \"mm\"\n"
            << "endian: little\n"
            << "encoding: raw\n"
            << "data file: " << dataFile << "\n";
    });
}

}  // namespace

void writeRawVolume(const std::string& nhdrPath, const std::string& rawPath,
                    const std::vector<float>& values, const RawVolumeInfo& info) {
    writeVolume(nhdrPath, rawPath, values, info, "float");
}

void writeRawVolume(const std::string& nhdrPath, const std::string& rawPath,
                    const std::vector<std::uint32_t>& values, const RawVolumeInfo& info) {
    writeVolume(nhdrPath, rawPath, values, info, "uint32");
}

}  // namespace dfrecon
