#include "app/StandardStreams.hpp"

#include <iostream>
#include <stdexcept>

namespace dfrecon::app {

bool isStandardStream(const std::string& path) {
    return path == "-";
}

const CLI::Validator kNotStandardStream(
    [](std::string& value) -> std::string {
        return isStandardStream(value)
                   ? "'-' (standard input or output) is not possible here: give a file"
                   : "";
    },
    "", "not -");

std::string MeshOutput::label() const {
    return toStandardOutput() ? "standard output" : path;
}

void addMeshFormatOption(CLI::App& command, std::string& format) {
    command
        .add_option("--format", format,
                    "Mesh format for -o - (standard output): ply, obj, off or stl (with a file "
                    "the extension decides)")
        ->check(CLI::IsMember({"ply", "obj", "off", "stl"}));
}

MeshOutput meshOutput(const std::string& output, const std::string& format, bool json) {
    if (isStandardStream(output)) {
        if (format.empty())
            throw std::invalid_argument("-o - (standard output) needs --format ply|obj|off|stl");
        if (json)
            throw std::invalid_argument(
                "-o - and --json would both write to standard output: give one");
        return {output, "." + format};
    }
    if (!isMeshExtension(output))
        throw std::invalid_argument("output '" + output +
                                    "' needs a mesh extension (.ply .stl .obj .off)");
    const std::string extension = lowerExtension(output);
    if (!format.empty() && extension != "." + format)
        throw std::invalid_argument("--format " + format + " disagrees with output '" + output +
                                    "' (--format is for -o -)");
    return {output, extension};
}

void writeMeshOutput(const TriMesh& mesh, const MeshOutput& output,
                     const MeshWriteOptions& options) {
    if (output.toStandardOutput())
        writeMesh(mesh, std::cout, output.extension, options);
    else
        writeMesh(mesh, output.path, options);
}

std::ostream& reportStream(bool resultOnStandardOutput) {
    return resultOnStandardOutput ? std::cerr : std::cout;
}

}  // namespace dfrecon::app
