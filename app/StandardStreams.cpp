#include "app/StandardStreams.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <optional>
#include <stdexcept>
#include <utility>

#include <unistd.h>

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

MeshOutput meshOutput(const std::string& output, const std::string& format, bool json) {
    if (isStandardStream(output)) {
        const std::optional<MeshFormat> named = meshFormatNamed(format);
        if (!named)
            throw std::invalid_argument("-o - (standard output) needs --format (" +
                                        meshFormatList(false) + ")");
        if (json)
            throw std::invalid_argument(
                "-o - and --json would both write to standard output: give one");
        return {output, *named};
    }
    const std::optional<MeshFormat> extension = meshFormatOfPath(output);
    if (!extension)
        throw std::invalid_argument("output '" + output + "' needs a mesh extension (" +
                                    meshExtensionList(false) + ")");
    if (!format.empty() && meshFormatNamed(format) != extension)
        throw std::invalid_argument("--format " + format + " disagrees with output '" + output +
                                    "' (the extension names the format of a file)");
    return {output, *extension};
}

void writeMeshOutput(TriMesh&& mesh, const MeshOutput& output, const MeshWriteOptions& options) {
    if (output.toStandardOutput())
        writeMesh(std::move(mesh), std::cout, output.format, options);
    else
        writeMesh(std::move(mesh), output.path, options);
}

void checkStandardOutput() {
    errno = 0;
    std::cout.flush();
    const bool lost = !std::cout || std::fflush(stdout) != 0 || std::ferror(stdout);
    // A report longer than the stream's buffer failed while it was written,
    // and that write's errno is gone by now: a byte more on the broken
    // descriptor says why (a full disk, a closed pipe).
    if (lost && errno == 0) (void)!::write(STDOUT_FILENO, "\n", 1);
    if (lost)
        throw std::runtime_error("cannot write to standard output" +
                                 (errno != 0 ? ": " + std::string(std::strerror(errno)) : ""));
}

std::ostream& reportStream(bool resultOnStandardOutput) {
    return resultOnStandardOutput ? std::cerr : std::cout;
}

}  // namespace dfrecon::app
