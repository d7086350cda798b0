#include "io/labels/LabelVolume.hpp"

#include <algorithm>
#include <cctype>
#include <climits>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <type_traits>

#include "contours/InputError.hpp"
#include "io/files/FileNames.hpp"
#include "io/files/InputLimits.hpp"
#include "io/files/InputsInUse.hpp"
#include "io/files/RegularFile.hpp"
#include "io/labels/LabelVolumeDetail.hpp"

namespace dfrecon {

namespace {

// A direction read back from a file is normalised here, but one handed to
// a writer must already be a unit vector within this.
constexpr double kUnitTolerance = 1e-6;

}  // namespace

namespace labelvolume {

std::size_t sampleBytes(SampleType type) {
    switch (type) {
        case SampleType::Int8:
        case SampleType::UInt8:
            return 1;
        case SampleType::Int16:
        case SampleType::UInt16:
            return 2;
        case SampleType::Int32:
        case SampleType::UInt32:
        case SampleType::Float32:
            return 4;
        case SampleType::Int64:
        case SampleType::UInt64:
        case SampleType::Float64:
            return 8;
    }
    return 0;
}

std::array<int, 3> checkedSizes(const std::string& path, const std::vector<std::uint64_t>& sizes) {
    if (sizes.size() < 3)
        throw InputError(
            path, 0, std::to_string(sizes.size()) + "-D image; a label volume needs 3 dimensions");
    for (std::size_t a = 0; a < sizes.size(); ++a)
        if (sizes[a] == 0) throw InputError(path, 0, "axis " + std::to_string(a) + " has size 0");
    for (std::size_t a = 3; a < sizes.size(); ++a)
        if (sizes[a] != 1)
            throw InputError(path, 0,
                             std::to_string(sizes.size()) + "-D image (axis " + std::to_string(a) +
                                 " has size " + std::to_string(sizes[a]) +
                                 "); a label volume needs 3 dimensions");
    // Each factor is checked against the cap before multiplying, so the
    // product never overflows 64 bits.
    std::uint64_t voxels = 1;
    for (int a = 0; a < 3; ++a) {
        if (sizes[a] > kMaxLabelVolumeVoxels || voxels * sizes[a] > kMaxLabelVolumeVoxels)
            throw InputError(path, 0,
                             "claims " + std::to_string(sizes[0]) + " x " +
                                 std::to_string(sizes[1]) + " x " + std::to_string(sizes[2]) +
                                 " voxels, more than the limit of " +
                                 std::to_string(kMaxLabelVolumeVoxels));
        voxels *= sizes[a];
    }
    std::array<int, 3> result{};
    for (int a = 0; a < 3; ++a) {
        if (sizes[a] > std::uint64_t(INT_MAX))
            throw InputError(path, 0,
                             "axis " + std::to_string(a) + " has " + std::to_string(sizes[a]) +
                                 " voxels, more than " + std::to_string(INT_MAX));
        result[a] = int(sizes[a]);
    }
    return result;
}

void requireBytes(const std::string& path, std::uint64_t neededBytes, std::uint64_t availableBytes,
                  const char* what) {
    if (availableBytes < neededBytes)
        throw InputError(path, 0,
                         std::string("truncated: ") + what + " can hold at most " +
                             std::to_string(availableBytes) +
                             " bytes of samples, the header needs " + std::to_string(neededBytes));
}

std::string memoryProblem(std::uint64_t voxels, std::size_t sampleBytes) {
    // Both libraries decode into one buffer of samples, then every voxel
    // gets a 32-bit label; nothing else grows with the volume.
    const long double bytes = static_cast<long double>(voxels) * (sampleBytes + 4);
    if (bytes <= static_cast<long double>(kMaxLabelVolumeBytes)) return {};
    std::ostringstream s;
    s << voxels << " voxels of " << sampleBytes << " byte(s) need "
      << std::uint64_t(std::min<long double>(bytes, 1e19L)) / (1u << 20)
      << " MiB with their labels, over the " << kMaxLabelVolumeBytes / (1u << 20)
      << " MiB a label volume may take";
    return s.str();
}

std::string geometryProblem(const VolumeGeometry& g) {
    for (int a = 0; a < 3; ++a)
        if (g.size[a] <= 0) return "axis " + std::to_string(a) + " has no voxels";
    if (std::uint64_t(g.voxelCount()) > kMaxLabelVolumeVoxels)
        return "more than " + std::to_string(kMaxLabelVolumeVoxels) + " voxels";
    for (int a = 0; a < 3; ++a) {
        if (!std::isfinite(g.spacingMm[a]) || !(g.spacingMm[a] >= kMinVoxelSpacingMm)) {
            std::ostringstream s;
            s << "axis " << a << " has spacing " << g.spacingMm[a]
              << " mm; spacing must be a finite length of at least " << kMinVoxelSpacingMm << " mm";
            return s.str();
        }
        if (!std::isfinite(g.originMm[a])) return "the origin is not finite";
        const auto& d = g.direction[a];
        const double norm = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        if (!std::isfinite(norm) || std::fabs(norm - 1) > kUnitTolerance)
            return "the direction of axis " + std::to_string(a) + " is not a unit vector";
    }
    if (!(std::fabs(axesDeterminant(g.direction)) > kMinAxisDeterminant))
        return "the axis directions are (nearly) parallel";
    // The grid is a parallelepiped: within the limit when its 8 outer
    // corners are.
    for (int corner = 0; corner < 8; ++corner) {
        auto at = [&](int a) { return (corner >> a & 1) ? g.size[a] - 0.5 : -0.5; };
        const Vec3 p = g.worldOfIndex(at(0), at(1), at(2));
        for (int c = 0; c < 3; ++c)
            if (!(std::fabs(p[c]) <= kMaxAbsCoordinateMm)) {
                std::ostringstream s;
                s << "the volume reaches (" << p.x << ", " << p.y << ", " << p.z
                  << ") mm, beyond the limit of ±" << std::int64_t(kMaxAbsCoordinateMm)
                  << " mm (origin, spacing or directions are not a patient's)";
                return s.str();
            }
    }
    return {};
}

VolumeGeometry geometryFromSteps(const std::string& path, const std::array<int, 3>& size,
                                 const std::array<std::array<double, 3>, 3>& steps,
                                 const std::array<double, 3>& originMm) {
    VolumeGeometry g;
    g.size = size;
    for (int c = 0; c < 3; ++c) g.originMm[c] = originMm[c] + 0.0;
    for (int a = 0; a < 3; ++a) {
        const auto& v = steps[a];
        // hypot: a step of 1e200 is long, not infinite.
        const double length = std::hypot(v[0], v[1], v[2]);
        if (!std::isfinite(length))
            throw InputError(path, 0, "the step of axis " + std::to_string(a) + " is not finite");
        if (!(length > 0))
            throw InputError(
                path, 0,
                "axis " + std::to_string(a) + " has zero spacing; spacing must be positive");
        g.spacingMm[a] = length;
        // + 0.0 turns the −0 of a negated zero into 0, for tidy printing.
        for (int c = 0; c < 3; ++c) g.direction[a][c] = v[c] / length + 0.0;
    }
    const std::string problem = geometryProblem(g);
    if (!problem.empty()) throw InputError(path, 0, problem);
    return g;
}

namespace {

template <class T>
T loadSample(const unsigned char* bytes, std::size_t index) {
    // memcpy: the libraries' buffers are malloc-aligned, but this keeps the
    // read well-defined whatever buffer it is given.
    T value;
    std::memcpy(&value, bytes + index * sizeof(T), sizeof(T));
    return value;
}

[[noreturn]] void badLabel(const std::string& path, const VolumeGeometry& g, std::size_t index,
                           double value, const char* why) {
    const std::size_t nx = std::size_t(g.size[0]), ny = std::size_t(g.size[1]);
    std::ostringstream s;
    s.precision(17);
    s << "voxel (" << index % nx << ", " << (index / nx) % ny << ", " << index / (nx * ny)
      << ") holds " << value << ", " << why;
    throw InputError(path, 0, s.str());
}

// A double that must be an integral label in int32.
std::int32_t labelOf(const std::string& path, const VolumeGeometry& g, std::size_t index,
                     double value) {
    if (!std::isfinite(value)) badLabel(path, g, index, value, "not a finite label");
    if (std::floor(value) != value) badLabel(path, g, index, value, "not an integer label");
    if (value < double(std::numeric_limits<std::int32_t>::min()) ||
        value > double(std::numeric_limits<std::int32_t>::max()))
        badLabel(path, g, index, value, "outside the int32 label range");
    return std::int32_t(value);
}

template <class T>
void convert(const std::string& path, const unsigned char* bytes, const VolumeGeometry& g,
             LinearScale scale, std::vector<std::int32_t>& out) {
    const std::size_t count = out.size();
    constexpr bool exact = std::is_integral_v<T> && sizeof(T) <= 2;
    if (exact && scale.identity()) {
        // int8..uint16 always fit: no check per voxel.
        for (std::size_t n = 0; n < count; ++n) out[n] = std::int32_t(loadSample<T>(bytes, n));
        return;
    }
    for (std::size_t n = 0; n < count; ++n) {
        const T stored = loadSample<T>(bytes, n);
        if constexpr (std::is_integral_v<T>) {
            if (scale.identity()) {
                // 32- and 64-bit integers: compared as integers, since
                // doubles round beyond 2^53.
                bool fits;
                if constexpr (std::is_signed_v<T>)
                    fits = std::int64_t(stored) >= std::numeric_limits<std::int32_t>::min() &&
                           std::int64_t(stored) <= std::numeric_limits<std::int32_t>::max();
                else
                    fits = std::uint64_t(stored) <=
                           std::uint64_t(std::numeric_limits<std::int32_t>::max());
                if (!fits) badLabel(path, g, n, double(stored), "outside the int32 label range");
                out[n] = std::int32_t(stored);
                continue;
            }
        }
        out[n] = labelOf(path, g, n, scale.slope * double(stored) + scale.intercept);
    }
}

}  // namespace

std::vector<std::int32_t> labelsFromSamples(const std::string& path, const void* data,
                                            SampleType type, const VolumeGeometry& geometry,
                                            LinearScale scale) {
    std::vector<std::int32_t> labels(geometry.voxelCount());
    const auto* bytes = static_cast<const unsigned char*>(data);
    switch (type) {
        case SampleType::Int8:
            convert<std::int8_t>(path, bytes, geometry, scale, labels);
            break;
        case SampleType::UInt8:
            convert<std::uint8_t>(path, bytes, geometry, scale, labels);
            break;
        case SampleType::Int16:
            convert<std::int16_t>(path, bytes, geometry, scale, labels);
            break;
        case SampleType::UInt16:
            convert<std::uint16_t>(path, bytes, geometry, scale, labels);
            break;
        case SampleType::Int32:
            convert<std::int32_t>(path, bytes, geometry, scale, labels);
            break;
        case SampleType::UInt32:
            convert<std::uint32_t>(path, bytes, geometry, scale, labels);
            break;
        case SampleType::Int64:
            convert<std::int64_t>(path, bytes, geometry, scale, labels);
            break;
        case SampleType::UInt64:
            convert<std::uint64_t>(path, bytes, geometry, scale, labels);
            break;
        case SampleType::Float32:
            convert<float>(path, bytes, geometry, scale, labels);
            break;
        case SampleType::Float64:
            convert<double>(path, bytes, geometry, scale, labels);
            break;
    }
    return labels;
}

std::vector<std::int32_t> layersFromInterleaved(const std::vector<std::int32_t>& interleaved,
                                                std::uint64_t layerCount) {
    const std::size_t layers = std::size_t(layerCount), voxels = interleaved.size() / layers;
    std::vector<std::int32_t> out(interleaved.size());
    for (std::size_t v = 0; v < voxels; ++v)
        for (std::size_t l = 0; l < layers; ++l) out[l * voxels + v] = interleaved[v * layers + l];
    return out;
}

}  // namespace labelvolume

LabelVolume readLabelVolume(const std::string& path) {
    const ReadingInput reading(path);
    namespace fs = std::filesystem;
    const bool nrrd = endsWithIgnoringCase(path, ".nrrd") || endsWithIgnoringCase(path, ".nhdr");
    const bool nifti = endsWithIgnoringCase(path, ".nii") || endsWithIgnoringCase(path, ".nii.gz");
    if (!nrrd && !nifti)
        throw InputError(path, 0,
                         "unknown label volume format; expected .nrrd, .nhdr, .nii or .nii.gz");
    // Checked here because both libraries would otherwise try other names
    // (niftilib adds .gz) or block on a FIFO.
    checkRegularFile(path, kMaxInputFileBytes, "a label volume");
    return nrrd ? labelvolume::readNrrdLabelVolume(path) : labelvolume::readNiftiLabelVolume(path);
}

void writeMaskNrrd(const std::string& path, const VolumeGeometry& geometry,
                   const std::vector<std::uint8_t>& mask) {
    if (!endsWithIgnoringCase(path, ".nrrd"))
        throw std::invalid_argument("writeMaskNrrd: " + path + " does not end in .nrrd");
    const std::string problem = labelvolume::geometryProblem(geometry);
    if (!problem.empty()) throw std::invalid_argument("writeMaskNrrd: " + problem);
    if (mask.size() != geometry.voxelCount())
        throw std::invalid_argument("writeMaskNrrd: mask size does not match the geometry");
    labelvolume::writeNrrdSamples(path, geometry, mask.data(), labelvolume::SampleType::UInt8);
}

namespace {

// The samples a file holds, in type T (which holds every label): the labels
// as they are for one layer, else with a layer index fastest, as a NRRD list
// axis runs. One copy, made in the file's type (a large segmentation's
// layers are most of its memory).
template <class T>
std::vector<T> samplesOf(const LabelVolume& volume) {
    const std::vector<std::int32_t>& labels = volume.labels;
    if (volume.layerCount == 1) return std::vector<T>(labels.begin(), labels.end());
    const std::size_t layers = std::size_t(volume.layerCount), voxels = labels.size() / layers;
    std::vector<T> out(labels.size());
    for (std::size_t l = 0; l < layers; ++l)
        for (std::size_t v = 0; v < voxels; ++v) out[v * layers + l] = T(labels[l * voxels + v]);
    return out;
}

}  // namespace

namespace {

// Writes volume's labels in the narrowest type that holds them all, through
// `write(data, type)`. The narrowest type keeps files small and is what
// Slicer writes for label maps (unsigned char, short); the values never
// change.
// Layers are written with a layer index fastest, as a NRRD list axis runs.
template <class Write>
void writeNarrowest(const std::string& path, const char* function, const LabelVolume& volume,
                    Write write) {
    using labelvolume::SampleType;
    const std::string problem = labelvolume::geometryProblem(volume.geometry);
    if (!problem.empty()) throw std::invalid_argument(std::string(function) + ": " + problem);
    if (volume.layerCount < 1 || std::uint64_t(volume.layerCount) > kMaxLabelLayers ||
        volume.labels.size() != volume.geometry.voxelCount() * std::size_t(volume.layerCount))
        throw std::invalid_argument(std::string(function) + ": " + path +
                                    ": label count does not match the geometry and layers");
    const auto [low, high] = std::minmax_element(volume.labels.begin(), volume.labels.end());
    if (*low >= 0 && *high <= 255) {
        write(samplesOf<std::uint8_t>(volume).data(), SampleType::UInt8);
    } else if (*low >= 0 && *high <= 65535) {
        write(samplesOf<std::uint16_t>(volume).data(), SampleType::UInt16);
    } else if (*low >= -32768 && *high <= 32767) {
        write(samplesOf<std::int16_t>(volume).data(), SampleType::Int16);
    } else if (volume.layerCount == 1) {
        write(volume.labels.data(), SampleType::Int32);
    } else {
        write(samplesOf<std::int32_t>(volume).data(), SampleType::Int32);
    }
}

}  // namespace

void writeLabelNrrd(const std::string& path, const LabelVolume& volume) {
    if (!endsWithIgnoringCase(path, ".nrrd"))
        throw std::invalid_argument("writeLabelNrrd: " + path + " does not end in .nrrd");
    writeNarrowest(path, "writeLabelNrrd", volume,
                   [&](const void* data, labelvolume::SampleType type) {
                       labelvolume::writeNrrdSamples(path, volume.geometry, data, type,
                                                     volume.keyValues, volume.layerCount);
                   });
}

void writeLabelVolume(const std::string& path, const LabelVolume& volume) {
    if (endsWithIgnoringCase(path, ".nrrd")) return writeLabelNrrd(path, volume);
    if (!endsWithIgnoringCase(path, ".nii") && !endsWithIgnoringCase(path, ".nii.gz"))
        throw std::invalid_argument("label map '" + path +
                                    "' must end in .nrrd, .seg.nrrd, .nii or .nii.gz");
    if (volume.layerCount != 1)
        throw std::invalid_argument("label map '" + path + "': NIfTI holds one layer, not " +
                                    std::to_string(volume.layerCount));
    writeNarrowest(path, "writeLabelVolume", volume,
                   [&](const void* data, labelvolume::SampleType type) {
                       labelvolume::writeNiftiSamples(path, volume.geometry, data, type);
                   });
}

std::string labelGridProblem(const VolumeGeometry& grid, std::size_t bytesPerVoxel) {
    if (std::string problem = labelvolume::geometryProblem(grid); !problem.empty()) return problem;
    return labelvolume::memoryProblem(std::uint64_t(grid.voxelCount()), bytesPerVoxel);
}

}  // namespace dfrecon
