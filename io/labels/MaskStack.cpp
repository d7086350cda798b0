#include "io/labels/MaskStack.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>

#include "contours/InputError.hpp"
#include "io/files/InputLimits.hpp"
#include "io/files/InputsInUse.hpp"
#include "io/files/JsonText.hpp"
#include "io/images/ImageFiles.hpp"
#include "io/labels/LabelVolumeDetail.hpp"

namespace dfrecon {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

bool endsWithJson(const std::string& path) {
    if (path.size() < 5) return false;
    std::string end = path.substr(path.size() - 5);
    for (char& c : end) c = char(std::tolower(static_cast<unsigned char>(c)));
    return end == ".json";
}

// Shell-style match of `name` against `pattern` with * and ?, no classes.
// Iterative with one backtrack point: O(|name| · |pattern|) worst case.
bool wildcardMatch(const std::string& pattern, const std::string& name) {
    std::size_t p = 0, n = 0, star = std::string::npos, resume = 0;
    while (n < name.size()) {
        if (p < pattern.size() && (pattern[p] == '?' || pattern[p] == name[n])) {
            ++p, ++n;
        } else if (p < pattern.size() && pattern[p] == '*') {
            star = p++, resume = n;
        } else if (star != std::string::npos) {
            p = star + 1, n = ++resume;
        } else {
            return false;
        }
    }
    while (p < pattern.size() && pattern[p] == '*') ++p;
    return p == pattern.size();
}

// Natural order: digit runs compare as numbers, so slice_2 < slice_10.
bool naturalLess(const std::string& a, const std::string& b) {
    std::size_t i = 0, j = 0;
    while (i < a.size() && j < b.size()) {
        if (std::isdigit(static_cast<unsigned char>(a[i])) &&
            std::isdigit(static_cast<unsigned char>(b[j]))) {
            std::size_t i2 = i, j2 = j;
            while (i2 < a.size() && std::isdigit(static_cast<unsigned char>(a[i2]))) ++i2;
            while (j2 < b.size() && std::isdigit(static_cast<unsigned char>(b[j2]))) ++j2;
            std::string x = a.substr(i, i2 - i), y = b.substr(j, j2 - j);
            x.erase(0, std::min(x.find_first_not_of('0'), x.size()));
            y.erase(0, std::min(y.find_first_not_of('0'), y.size()));
            if (x.size() != y.size()) return x.size() < y.size();
            if (x != y) return x < y;
            i = i2, j = j2;
        } else {
            if (a[i] != b[j]) return a[i] < b[j];
            ++i, ++j;
        }
    }
    return a.size() - i < b.size() - j;
}

// A spacing from the sidecar: finite, at least kMinVoxelSpacingMm, and no
// longer than the coordinate limit; or InputError naming the key.
double spacing(const json& value, const std::string& sidecar, const std::string& key) {
    if (!value.is_number() || !std::isfinite(value.get<double>()) ||
        !(value.get<double>() >= kMinVoxelSpacingMm) ||
        !(value.get<double>() <= kMaxAbsCoordinateMm))
        throw InputError(
            sidecar, 0, key + " must be a length from 1e-6 to 1e6 mm (found " + value.dump() + ")");
    return value.get<double>();
}

// Coordinates from the sidecar: finite and within kMaxAbsCoordinateMm.
std::vector<double> numbers(const json& value, const std::string& sidecar, const std::string& key) {
    if (!value.is_array()) throw InputError(sidecar, 0, key + " must be an array of numbers");
    std::vector<double> out;
    for (const json& v : value) {
        if (!v.is_number() || !std::isfinite(v.get<double>()))
            throw InputError(sidecar, 0, key + " must hold finite numbers only");
        if (std::fabs(v.get<double>()) > kMaxAbsCoordinateMm)
            throw InputError(sidecar, 0,
                             key + " holds " + v.dump() + ", beyond the limit of ±1000000 mm");
        out.push_back(v.get<double>());
    }
    return out;
}

std::vector<fs::path> imagePaths(const json& doc, const fs::path& folder,
                                 const std::string& sidecar) {
    std::vector<fs::path> paths;
    if (doc.contains("files") == doc.contains("pattern"))
        throw InputError(sidecar, 0, "give exactly one of \"files\" and \"pattern\"");
    if (doc.contains("files")) {
        const json& files = doc["files"];
        if (!files.is_array()) throw InputError(sidecar, 0, "files must be an array of names");
        for (const json& f : files) {
            if (!f.is_string() || f.get<std::string>().empty())
                throw InputError(sidecar, 0, "files must hold non-empty file names");
            paths.push_back(folder / f.get<std::string>());
        }
    } else {
        if (!doc["pattern"].is_string())
            throw InputError(sidecar, 0, "pattern must be a file name pattern (* and ?)");
        const std::string pattern = doc["pattern"].get<std::string>();
        if (pattern.find('/') != std::string::npos)
            throw InputError(sidecar, 0, "pattern must match names in the sidecar's folder");
        std::vector<std::string> names;
        std::error_code error;
        for (const fs::directory_entry& entry : fs::directory_iterator(folder, error)) {
            const std::string name = entry.path().filename().string();
            if (entry.is_regular_file(error) && wildcardMatch(pattern, name)) names.push_back(name);
            if (names.size() > kMaxMaskStackImages) break;
        }
        std::sort(names.begin(), names.end(), naturalLess);
        for (const std::string& name : names) paths.push_back(folder / name);
    }
    if (paths.empty()) throw InputError(sidecar, 0, "the stack lists no images");
    if (paths.size() > kMaxMaskStackImages)
        throw InputError(sidecar, 0,
                         "more than " + std::to_string(kMaxMaskStackImages) + " images");
    return paths;
}

// Slice z positions: "slicePositionsMm", or "sliceSpacingMm" from originMm's z.
std::vector<double> slicePositions(const json& doc, std::size_t count, double zStartMm,
                                   const std::string& sidecar) {
    if (doc.contains("slicePositionsMm") == doc.contains("sliceSpacingMm"))
        throw InputError(sidecar, 0,
                         "give exactly one of \"slicePositionsMm\" and \"sliceSpacingMm\"");
    std::vector<double> positions;
    if (doc.contains("slicePositionsMm")) {
        positions = numbers(doc["slicePositionsMm"], sidecar, "slicePositionsMm");
        if (positions.size() != count)
            throw InputError(sidecar, 0,
                             "slicePositionsMm has " + std::to_string(positions.size()) +
                                 " positions for " + std::to_string(count) + " images");
        for (std::size_t k = 1; k < positions.size(); ++k)
            if (!(positions[k] > positions[k - 1]))
                throw InputError(sidecar, 0, "slicePositionsMm are not strictly increasing");
    } else {
        const double spacingMm = spacing(doc["sliceSpacingMm"], sidecar, "sliceSpacingMm");
        for (std::size_t k = 0; k < count; ++k)
            positions.push_back(zStartMm + double(k) * spacingMm);
        if (!(std::fabs(positions.back()) <= kMaxAbsCoordinateMm))
            throw InputError(sidecar, 0,
                             "the slices reach z = " + std::to_string(positions.back()) +
                                 " mm, beyond the limit of ±1000000 mm");
    }
    return positions;
}

std::map<std::int32_t, std::string> labelNames(const json& doc, const std::string& sidecar) {
    std::map<std::int32_t, std::string> names;
    if (!doc.contains("labels")) return names;
    const json& labels = doc["labels"];
    if (!labels.is_object()) throw InputError(sidecar, 0, "labels must map label numbers to names");
    for (const auto& [key, value] : labels.items()) {
        std::size_t used = 0;
        long long label = 0;
        try {
            label = std::stoll(key, &used);
        } catch (const std::exception&) {
            used = 0;
        }
        if (used == 0 || used != key.size() || label < INT32_MIN || label > INT32_MAX)
            throw InputError(sidecar, 0, "labels: '" + key + "' is not an integer label");
        if (!value.is_string() || value.get<std::string>().empty())
            throw InputError(sidecar, 0, "labels: the name of label " + key + " must be a string");
        names[std::int32_t(label)] = value.get<std::string>();
    }
    return names;
}

cv::Mat readImage(const fs::path& path) {
    const std::string name = path.string();
    std::error_code error;
    if (!fs::is_regular_file(path, error)) throw InputError(name, 0, "image file not found");
    ImageSamples found;
    cv::Mat image = readGreyImage(name, found);
    if (image.empty())
        throw InputError(name, 0,
                         "label images must be 8- or 16-bit single channel (found " +
                             std::to_string(found.samplesPerPixel) + " channel(s) of depth " +
                             std::to_string(found.bitsPerSample) + " bits)");
    return image;
}

}  // namespace

bool isMaskStackPath(const std::string& path) {
    std::error_code error;
    if (fs::is_directory(path, error))
        return fs::is_regular_file(fs::path(path) / kMaskStackSidecar, error);
    return endsWithJson(path);
}

MaskStack readMaskStack(const std::string& path) {
    const ReadingInput reading(path);
    std::error_code error;
    const fs::path sidecarPath =
        fs::is_directory(path, error) ? fs::path(path) / kMaskStackSidecar : fs::path(path);
    const std::string sidecar = sidecarPath.string();
    JsonLimits limits;
    limits.maxDepth = 4;  // the object, its lists of numbers and of images
    limits.maxBytes = std::uint64_t(64) << 20;
    const json doc = readJsonFile(sidecar, limits, "a mask stack sidecar");
    if (!doc.is_object()) throw InputError(sidecar, 0, "the sidecar must be a JSON object");

    MaskStack stack;
    VolumeGeometry& geometry = stack.volume.geometry;
    if (!doc.contains("pixelSpacingMm"))
        throw InputError(sidecar, 0, "pixelSpacingMm [column, row] is missing");
    if (!doc["pixelSpacingMm"].is_array() || doc["pixelSpacingMm"].size() != 2)
        throw InputError(sidecar, 0, "pixelSpacingMm must be two numbers > 0");
    const std::vector<double> pixel = {
        spacing(doc["pixelSpacingMm"][0], sidecar, "pixelSpacingMm"),
        spacing(doc["pixelSpacingMm"][1], sidecar, "pixelSpacingMm")};
    std::vector<double> origin{0, 0, 0};
    if (doc.contains("originMm")) {
        origin = numbers(doc["originMm"], sidecar, "originMm");
        if (origin.size() != 2 && origin.size() != 3)
            throw InputError(sidecar, 0, "originMm must be [x, y] or [x, y, z]");
        origin.resize(3, 0.0);
    }
    const std::vector<fs::path> images = imagePaths(doc, sidecarPath.parent_path(), sidecar);
    stack.slicePositionsMm = slicePositions(doc, images.size(), origin[2], sidecar);
    stack.labelNames = labelNames(doc, sidecar);

    const std::size_t count = images.size();
    const double firstZ = stack.slicePositionsMm.front(), lastZ = stack.slicePositionsMm.back();
    geometry.spacingMm = {pixel[0], pixel[1],
                          count > 1                        ? (lastZ - firstZ) / double(count - 1)
                          : doc.contains("sliceSpacingMm") ? doc["sliceSpacingMm"].get<double>()
                                                           : 1.0};
    geometry.originMm = {origin[0], origin[1], firstZ};

    for (std::size_t k = 0; k < count; ++k) {
        const cv::Mat image = readImage(images[k]);
        if (k == 0) {
            // The first image fixes the size: refuse absurd stacks before
            // allocating the whole volume.
            const std::uint64_t voxels =
                std::uint64_t(image.cols) * std::uint64_t(image.rows) * std::uint64_t(count);
            if (voxels > kMaxLabelVolumeVoxels)
                throw InputError(sidecar, 0,
                                 std::to_string(count) + " images of " +
                                     std::to_string(image.cols) + "x" + std::to_string(image.rows) +
                                     " pixels exceed the 2^31 voxel limit");
            // Images are decoded one at a time: only the labels grow.
            const std::string memory = labelvolume::memoryProblem(voxels, 0);
            if (!memory.empty()) throw InputError(sidecar, 0, memory);
            geometry.size = {image.cols, image.rows, int(count)};
            const std::string problem = labelvolume::geometryProblem(geometry);
            if (!problem.empty()) throw InputError(sidecar, 0, problem);
            stack.volume.labels.resize(geometry.voxelCount());
        } else if (image.cols != geometry.size[0] || image.rows != geometry.size[1]) {
            throw InputError(images[k].string(), 0,
                             "image is " + std::to_string(image.cols) + "x" +
                                 std::to_string(image.rows) + " pixels, the first image " +
                                 std::to_string(geometry.size[0]) + "x" +
                                 std::to_string(geometry.size[1]));
        }
        std::int32_t* out =
            stack.volume.labels.data() + k * std::size_t(image.cols) * std::size_t(image.rows);
        for (int row = 0; row < image.rows; ++row)
            for (int col = 0; col < image.cols; ++col)
                *out++ = image.depth() == CV_8U ? std::int32_t(image.at<std::uint8_t>(row, col))
                                                : std::int32_t(image.at<std::uint16_t>(row, col));
    }
    return stack;
}

}  // namespace dfrecon
