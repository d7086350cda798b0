#include "io/mesh/MeshFormat.hpp"

#include <array>
#include <cctype>
#include <filesystem>
#include <vector>

namespace dfrecon {

namespace {

struct FormatName {
    MeshFormat format;
    const char* name;
    bool readable;
};

constexpr std::array<FormatName, 6> kFormats{{{MeshFormat::Ply, "ply", true},
                                              {MeshFormat::Obj, "obj", true},
                                              {MeshFormat::Off, "off", true},
                                              {MeshFormat::Stl, "stl", true},
                                              {MeshFormat::Vtk, "vtk", false},
                                              {MeshFormat::Vtp, "vtp", false}}};

const FormatName& entryOf(MeshFormat format) {
    for (const FormatName& f : kFormats)
        if (f.format == format) return f;
    return kFormats[0];  // unreachable: every enumerator is in the table
}

}  // namespace

std::string lowerExtension(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return ext;
}

std::optional<MeshFormat> meshFormatOfPath(const std::string& path) {
    const std::string ext = lowerExtension(path);
    return ext.empty() ? std::nullopt : meshFormatNamed(ext.substr(1));
}

std::optional<MeshFormat> meshFormatNamed(const std::string& name) {
    for (const FormatName& f : kFormats)
        if (name == f.name) return f.format;
    return std::nullopt;
}

const char* meshFormatName(MeshFormat format) {
    return entryOf(format).name;
}

std::string meshFormatExtension(MeshFormat format) {
    return std::string(".") + meshFormatName(format);
}

bool isReadableMeshFormat(MeshFormat format) {
    return entryOf(format).readable;
}

std::vector<std::string> meshFormatNames(bool readableOnly) {
    std::vector<std::string> names;
    for (const FormatName& f : kFormats)
        if (f.readable || !readableOnly) names.push_back(f.name);
    return names;
}

std::string meshFormatList(bool readableOnly) {
    const std::vector<std::string> names = meshFormatNames(readableOnly);
    std::string out;
    for (std::size_t k = 0; k < names.size(); ++k)
        out += (k == 0 ? "" : k + 1 == names.size() ? " or " : ", ") + names[k];
    return out;
}

std::string meshExtensionList(bool readableOnly) {
    std::string out;
    for (const std::string& name : meshFormatNames(readableOnly))
        out += (out.empty() ? "." : " .") + name;
    return out;
}

}  // namespace dfrecon
