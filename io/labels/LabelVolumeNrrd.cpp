// NRRD label volumes through teem's nrrd library (Debian libteem-dev).
//
// teem parses the header and decodes the data, but it trusts its input, so
// this file screens what a hostile file could exploit before teem sees it:
//  - "data file: name%0999d 1 2 1" (numbered data files) goes to sprintf
//    as a format string with a buffer sized for 10 digits: a heap overflow
//    (and "%s" crashes). Only a single plain data file name is accepted,
//    and it must be a regular file (not standard input, a device or a FIFO
//    that would block).
//  - without an exact NRRD magic teem tries its other formats (PNM, PNG,
//    VTK, text tables) on the file; those are refused.
//  - the data are allocated from the header's sizes before reading. The
//    header is read first with skipData, sizes, the memory budget and the
//    file length checked, and only then the data.
//  - "nan" is how teem marks a value a header leaves out: a spacing or
//    origin written as nan would quietly become the default.
#include <teem/nrrd.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>
#include <mutex>
#include <stdexcept>

#include "contours/InputError.hpp"
#include "io/files/AtomicWrite.hpp"
#include "io/labels/LabelVolumeDetail.hpp"

namespace dfrecon::labelvolume {

namespace {

namespace fs = std::filesystem;

// teem keeps its error messages (biff) and settings in globals.
std::mutex& teemMutex() {
    static std::mutex mutex;
    return mutex;
}

struct NrrdNuke {  // frees the struct and its data
    void operator()(Nrrd* n) const { nrrdNuke(n); }
};
struct NrrdNix {  // frees the struct only: the data are wrapped, not owned
    void operator()(Nrrd* n) const { nrrdNix(n); }
};
struct IoStateNix {
    void operator()(NrrdIoState* s) const { nrrdIoStateNix(s); }
};
using OwnedNrrd = std::unique_ptr<Nrrd, NrrdNuke>;
using WrappingNrrd = std::unique_ptr<Nrrd, NrrdNix>;
using IoState = std::unique_ptr<NrrdIoState, IoStateNix>;

// teem's latest complaint, one line, without the "[nrrd] function:" prefix
// (the innermost message says what is wrong; the outer ones say where).
std::string teemError() {
    char* raw = biffGetDone(NRRD);
    std::string text = raw ? raw : "";
    free(raw);
    std::string last;
    std::size_t start = 0;
    while (start < text.size()) {
        std::size_t end = text.find('\n', start);
        if (end == std::string::npos) end = text.size();
        std::string line = text.substr(start, end - start);
        if (line.rfind("[nrrd] ", 0) == 0) line.erase(0, 7);
        const std::size_t colon = line.find(": ");
        if (colon != std::string::npos && line.find(' ') > colon) line.erase(0, colon + 2);
        if (!line.empty()) last = line;
        start = end + 1;
    }
    return last.empty() ? "teem reported no detail" : last;
}

// Where the data are: the header's own file after its blank line, or one
// detached data file.
struct DataLocation {
    std::string path;
    std::uint64_t offset = 0;  // bytes before the data (at least)
};

// Longest header screened; teem itself reads lines of any length.
constexpr std::size_t kMaxHeaderBytes = std::size_t(1) << 20;

std::string normalisedFieldName(const std::string& name) {
    std::string out;
    for (char c : name)
        if (c != ' ' && c != '_' && c != '-' && c != '\t')
            out += char(std::tolower(static_cast<unsigned char>(c)));
    return out;
}

// The line starting at `next` in `text`, ended as teem ends lines: by
// "\n", "\r\n" or a lone "\r". Advances `next` past the ending; returns
// false when the text ended first (the line is then what was left).
bool readLine(const std::string& text, std::size_t& next, std::string& line) {
    const std::size_t end = text.find_first_of("\r\n", next);
    if (end == std::string::npos) {
        line = text.substr(next);
        next = text.size();
        return false;
    }
    line = text.substr(next, end - next);
    next = end + 1;
    if (text[end] == '\r' && next < text.size() && text[next] == '\n') ++next;
    return true;
}

// Reads the header text (never the data) and finds the data, rejecting
// what teem would mishandle. Throws InputError. O(header).
DataLocation screenHeader(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError(path, 0, "cannot open");
    std::string text(kMaxHeaderBytes, '\0');
    in.read(text.data(), std::streamsize(text.size()));
    text.resize(std::size_t(in.gcount()));
    std::size_t next = 0;
    std::string line;
    readLine(text, next, line);
    // Exactly teem's NRRD magics: with anything else teem would try its
    // other formats (PNM, PNG, VTK, plain text tables) on the file.
    static const char* const magics[] = {"NRRD00.01", "NRRD0001", "NRRD0002", "NRRD0003",
                                         "NRRD0004",  "NRRD0005", "NRRD0006"};
    if (std::find(std::begin(magics), std::end(magics), line) == std::end(magics))
        throw InputError(path, 0, "not a NRRD file (it does not start with NRRD000x)");

    DataLocation location{path, 0};
    bool blankLine = false;
    std::string dataFile;
    while (next < text.size()) {
        if (!readLine(text, next, line)) {
            // The header runs to the end of what was read: fine for a
            // detached header that ends the file, not for one cut by the cap.
            if (text.size() == kMaxHeaderBytes)
                throw InputError(path, 0, "header longer than 1 MiB");
        } else if (line.empty()) {
            blankLine = true;
            location.offset = next;
            break;
        }
        if (line.empty() || line[0] == '#') continue;
        // Field lines are "name: value" (teem splits at the first ": ");
        // key/value pairs use ":=" and are not fields.
        const std::size_t colon = line.find(": ");
        if (colon == std::string::npos) continue;
        const std::string field = normalisedFieldName(line.substr(0, colon));
        // teem reads "nan" as it marks a value the header leaves out, so a
        // spacing of nan would quietly become the default 1 mm.
        if (field == "spacings" || field == "spaceorigin" || field == "spacedirections") {
            std::string value = line.substr(colon + 2);
            for (char& c : value) c = char(std::tolower(static_cast<unsigned char>(c)));
            if (value.find("nan") != std::string::npos)
                throw InputError(path, 0,
                                 line.substr(0, colon) + " holds nan; the geometry must be finite");
        }
        if (field != "datafile") continue;
        dataFile = line.substr(colon + 2);
        dataFile.erase(0, std::min(dataFile.size(), dataFile.find_first_not_of(" \t")));
        if (dataFile.empty()) throw InputError(path, 0, "empty data file name");
    }
    if (dataFile.empty()) {
        if (!blankLine) throw InputError(path, 0, "header has no blank line and no data file");
        return location;
    }
    if (dataFile.find('%') != std::string::npos || dataFile.rfind("LIST", 0) == 0 ||
        dataFile.rfind("SKIPLIST", 0) == 0)
        throw InputError(path, 0,
                         "data split over several files (data file: " + dataFile +
                             ") is not supported; use one data file");
    if (dataFile == "-") throw InputError(path, 0, "data file on standard input is not supported");
    // teem opens names with ':' as their second character as they are
    // (Windows drives); refuse them rather than guess which file it means.
    if (dataFile.size() > 1 && dataFile[1] == ':')
        throw InputError(path, 0, "data file name " + dataFile + " is not supported");
    const fs::path named(dataFile);
    location.path = (named.is_absolute() ? named : fs::path(path).parent_path() / named).string();
    location.offset = 0;
    std::error_code ec;
    if (!fs::is_regular_file(location.path, ec))
        throw InputError(path, 0,
                         "data file " + location.path + " is missing or not a regular file");
    return location;
}

SampleType nrrdSampleType(const std::string& path, int teemType) {
    switch (teemType) {
        case nrrdTypeChar:
            return SampleType::Int8;
        case nrrdTypeUChar:
            return SampleType::UInt8;
        case nrrdTypeShort:
            return SampleType::Int16;
        case nrrdTypeUShort:
            return SampleType::UInt16;
        case nrrdTypeInt:
            return SampleType::Int32;
        case nrrdTypeUInt:
            return SampleType::UInt32;
        case nrrdTypeLLong:
            return SampleType::Int64;
        case nrrdTypeULLong:
            return SampleType::UInt64;
        case nrrdTypeFloat:
            return SampleType::Float32;
        case nrrdTypeDouble:
            return SampleType::Float64;
        default:
            throw InputError(path, 0,
                             std::string("sample type ") + airEnumStr(nrrdType, teemType) +
                                 " is not a scalar number");
    }
}

int teemTypeOf(SampleType type) {
    switch (type) {
        case SampleType::UInt8:
            return nrrdTypeUChar;
        case SampleType::UInt16:
            return nrrdTypeUShort;
        case SampleType::Int16:
            return nrrdTypeShort;
        case SampleType::Int32:
            return nrrdTypeInt;
        default:
            throw std::invalid_argument("writeNrrdSamples: unsupported sample type");
    }
}

// Most bytes of samples that `fileBytes` bytes of `encoding` can decode to,
// a bound that holds for any content (a file of zeros compresses best).
std::uint64_t decodableBytes(const NrrdEncoding* encoding, std::uint64_t fileBytes,
                             std::size_t sampleSize) {
    if (encoding == nrrdEncodingRaw) return fileBytes;
    // Deflate codes at most 258 bytes in 2 bits (1032:1); the slack covers
    // gzip's headers of a tiny stream.
    if (encoding == nrrdEncodingGzip) return fileBytes * 1032 + 1024;
    // Two hex digits per byte.
    if (encoding == nrrdEncodingHex) return fileBytes / 2;
    // At least one digit and one separator per value.
    if (encoding == nrrdEncodingAscii) return (fileBytes + 1) / 2 * sampleSize;
    return 0;
}

// The geometry of the three spatial axes, nrrd.axis[first] on (first is 1
// past a segmentation's list axis of layers).
VolumeGeometry geometryOf(const std::string& path, const Nrrd& nrrd, unsigned first,
                          const std::array<int, 3>& size) {
    const NrrdAxisInfo* axis = nrrd.axis + first;
    for (int a = 0; a < 3; ++a) {
        const int kind = axis[a].kind;
        if (kind != nrrdKindUnknown && kind != nrrdKindDomain && kind != nrrdKindSpace)
            throw InputError(path, 0,
                             "axis " + std::to_string(a) + " is of kind " +
                                 airEnumStr(nrrdKind, kind) + ", not a spatial axis");
    }
    std::array<std::array<double, 3>, 3> steps{};
    std::array<double, 3> origin{0, 0, 0};
    if (nrrd.space == nrrdSpaceUnknown && nrrd.spaceDim == 0) {
        // No orientation at all: axes along LPS x, y, z with the
        // "spacings" field, or 1 mm.
        for (int a = 0; a < 3; ++a) {
            const double spacing = axis[a].spacing;
            steps[a][a] = std::isnan(spacing) ? 1.0 : spacing;
            if (!(steps[a][a] > 0) || !std::isfinite(steps[a][a]))
                throw InputError(path, 0,
                                 "axis " + std::to_string(a) + " has spacing " +
                                     std::to_string(spacing) + "; spacing must be positive");
        }
        return geometryFromSteps(path, size, steps, origin);
    }
    // Signs that take the file's space to LPS.
    std::array<double, 3> toLps{1, 1, 1};
    switch (nrrd.space) {
        case nrrdSpaceLeftPosteriorSuperior:
            break;
        case nrrdSpaceRightAnteriorSuperior:
            toLps = {-1, -1, 1};
            break;
        case nrrdSpaceLeftAnteriorSuperior:
            toLps = {1, -1, 1};
            break;
        case nrrdSpaceUnknown:
            throw InputError(path, 0,
                             "space dimension " + std::to_string(nrrd.spaceDim) +
                                 " without a named patient space (LPS, RAS or LAS)");
        default:
            throw InputError(path, 0,
                             std::string("space ") + airEnumStr(nrrdSpace, nrrd.space) +
                                 " is not a 3-D patient space (LPS, RAS or LAS)");
    }
    for (int a = 0; a < 3; ++a)
        for (int c = 0; c < 3; ++c) {
            const double v = axis[a].spaceDirection[c];
            if (std::isnan(v))
                throw InputError(path, 0, "axis " + std::to_string(a) + " has no space direction");
            steps[a][c] = toLps[c] * v;
        }
    // No "space origin" reads as NaN: the first voxel is then at 0.
    const bool noOrigin = std::isnan(nrrd.spaceOrigin[0]) && std::isnan(nrrd.spaceOrigin[1]) &&
                          std::isnan(nrrd.spaceOrigin[2]);
    if (!noOrigin)
        for (int c = 0; c < 3; ++c) origin[c] = toLps[c] * nrrd.spaceOrigin[c];
    return geometryFromSteps(path, size, steps, origin);
}

}  // namespace

LabelVolume readNrrdLabelVolume(const std::string& path) {
    const DataLocation location = screenHeader(path);
    std::lock_guard<std::mutex> lock(teemMutex());
    nrrdStateVerboseIO = 0;

    // Pass 1: the header only.
    OwnedNrrd header(nrrdNew());
    IoState headerIo(nrrdIoStateNew());
    if (!header || !headerIo) throw std::bad_alloc();
    headerIo->skipData = AIR_TRUE;
    if (nrrdLoad(header.get(), path.c_str(), headerIo.get()))
        throw InputError(path, 0, "not a readable NRRD header: " + teemError());
    // A 4-D file whose first axis is a list holds layers (3D Slicer's
    // segmentation with overlapping segments); the other three are space.
    const bool layered = header->dim == 4 && header->axis[0].kind == nrrdKindList;
    if (header->dim != 3 && !layered)
        throw InputError(path, 0,
                         std::to_string(header->dim) +
                             "-D image; a label volume needs 3 dimensions (or 4 with layers "
                             "first, kind list, as 3D Slicer segmentations have)");
    const unsigned first = layered ? 1 : 0;
    const std::uint64_t layerCount = layered ? header->axis[0].size : 1;
    if (layerCount == 0 || layerCount > kMaxLabelLayers)
        throw InputError(path, 0,
                         std::to_string(layerCount) + " layers; a segmentation may have 1 to " +
                             std::to_string(kMaxLabelLayers));
    std::vector<std::uint64_t> sizes;
    for (unsigned a = first; a < header->dim; ++a) sizes.push_back(header->axis[a].size);
    const std::array<int, 3> size = checkedSizes(path, sizes);
    const SampleType type = nrrdSampleType(path, header->type);
    // sizes are checked above, layers just now: no overflow
    const std::string memory =
        memoryProblem(sizes[0] * sizes[1] * sizes[2] * layerCount, sampleBytes(type));
    if (!memory.empty()) throw InputError(path, 0, memory);
    const NrrdEncoding* encoding = headerIo->encoding;
    if (encoding != nrrdEncodingRaw && encoding != nrrdEncodingGzip &&
        encoding != nrrdEncodingAscii && encoding != nrrdEncodingHex)
        throw InputError(path, 0,
                         std::string("encoding ") + encoding->name +
                             " is not supported (raw, gzip, ascii and hex are)");
    const VolumeGeometry geometry = geometryOf(path, *header, first, size);

    // The file must be able to hold the samples before they are allocated.
    std::error_code ec;
    const std::uint64_t fileBytes = fs::file_size(location.path, ec);
    if (ec) throw InputError(path, 0, "cannot measure " + location.path);
    const std::uint64_t dataFileBytes =
        fileBytes > location.offset ? fileBytes - location.offset : 0;
    std::uint64_t needed = std::uint64_t(geometry.voxelCount()) * layerCount * sampleBytes(type);
    if (encoding == nrrdEncodingRaw && headerIo->byteSkip > 0)
        needed += std::uint64_t(headerIo->byteSkip);
    requireBytes(path, needed, decodableBytes(encoding, dataFileBytes, sampleBytes(type)),
                 location.path == path ? "the file" : "the data file");

    // Pass 2: header and data.
    OwnedNrrd full(nrrdNew());
    IoState fullIo(nrrdIoStateNew());
    if (!full || !fullIo) throw std::bad_alloc();
    if (nrrdLoad(full.get(), path.c_str(), fullIo.get()))
        throw InputError(path, 0, "cannot read the data: " + teemError());
    // The same file read twice; a change in between is not trusted.
    if (full->dim != header->dim || full->type != header->type || !full->data ||
        full->axis[0].size != header->axis[0].size || full->axis[first].size != sizes[0] ||
        full->axis[first + 1].size != sizes[1] || full->axis[first + 2].size != sizes[2])
        throw InputError(path, 0, "changed while being read");
    LabelVolume volume;
    volume.geometry = geometry;
    volume.layerCount = int(layerCount);
    nrrdStateKeyValueReturnInternalPointers = AIR_FALSE;
    // The samples as one run (a layer index fastest where there are layers),
    // then layer after layer.
    VolumeGeometry samples = geometry;
    samples.size[0] *= int(layerCount);  // within the voxel limit, checked above
    volume.labels = labelsFromSamples(path, full->data, type, samples, LinearScale{});
    if (layered) volume.labels = layersFromInterleaved(volume.labels, layerCount);
    for (unsigned i = 0; i < nrrdKeyValueSize(full.get()); ++i) {
        char* key = nullptr;
        char* value = nullptr;
        nrrdKeyValueIndex(full.get(), &key, &value, i);  // copies: the state is set above
        if (key && value) volume.keyValues.emplace_back(key, value);
        std::free(key);
        std::free(value);
    }
    return volume;
}

void writeNrrdSamples(const std::string& path, const VolumeGeometry& geometry, const void* data,
                      SampleType type,
                      const std::vector<std::pair<std::string, std::string>>& keyValues,
                      int layerCount) {
    const int teemType = teemTypeOf(type);
    std::lock_guard<std::mutex> lock(teemMutex());
    nrrdStateVerboseIO = 0;
    if (!nrrdEncodingGzip->available())
        throw std::runtime_error("cannot write " + path + ": teem was built without zlib");
    writeAtomically(path, [&](const std::string& temporary) {
        WrappingNrrd nrrd(nrrdNew());
        IoState io(nrrdIoStateNew());
        if (!nrrd || !io) throw std::bad_alloc();
        // teem's wrap takes a non-const pointer but only reads on save.
        const bool layered = layerCount > 1;
        const int wrapped =
            layered ? nrrdWrap_va(nrrd.get(), const_cast<void*>(data), teemType, 4,
                                  std::size_t(layerCount), std::size_t(geometry.size[0]),
                                  std::size_t(geometry.size[1]), std::size_t(geometry.size[2]))
                    : nrrdWrap_va(nrrd.get(), const_cast<void*>(data), teemType, 3,
                                  std::size_t(geometry.size[0]), std::size_t(geometry.size[1]),
                                  std::size_t(geometry.size[2]));
        if (wrapped || nrrdSpaceSet(nrrd.get(), nrrdSpaceLeftPosteriorSuperior) ||
            nrrdSpaceOriginSet(nrrd.get(), geometry.originMm.data()))
            throw std::runtime_error("cannot write " + path + ": " + teemError());
        double steps[4][3];
        const int first = layered ? 1 : 0;
        // The list axis of layers has no space direction ("none").
        for (int c = 0; c < 3; ++c) steps[0][c] = AIR_NAN;
        for (int a = 0; a < 3; ++a)
            for (int c = 0; c < 3; ++c)
                steps[first + a][c] = geometry.spacingMm[a] * geometry.direction[a][c];
        // "domain" on every spatial axis is what Slicer writes for (label)
        // volumes, "list" for the layers of a segmentation.
        if (layered) {
            nrrdAxisInfoSet_va(nrrd.get(), nrrdAxisInfoSpaceDirection, steps[0], steps[1], steps[2],
                               steps[3]);
            nrrdAxisInfoSet_va(nrrd.get(), nrrdAxisInfoKind, nrrdKindList, nrrdKindDomain,
                               nrrdKindDomain, nrrdKindDomain);
        } else {
            nrrdAxisInfoSet_va(nrrd.get(), nrrdAxisInfoSpaceDirection, steps[0], steps[1],
                               steps[2]);
            nrrdAxisInfoSet_va(nrrd.get(), nrrdAxisInfoKind, nrrdKindDomain, nrrdKindDomain,
                               nrrdKindDomain);
        }
        for (int c = 0; c < 3; ++c) nrrd->spaceUnits[c] = airStrdup("mm");
        for (const auto& [key, value] : keyValues)
            if (nrrdKeyValueAdd(nrrd.get(), key.c_str(), value.c_str()))
                throw std::runtime_error("cannot write " + path + ": " + teemError());
        io->format = nrrdFormatNRRD;  // attached header whatever the name
        io->encoding = nrrdEncodingGzip;
        io->zlibLevel = 6;
        if (nrrdSave(temporary.c_str(), nrrd.get(), io.get()))
            throw std::runtime_error("cannot write " + path + ": " + teemError());
        return true;
    });
}

}  // namespace dfrecon::labelvolume
