#pragma once
// "-" as a file argument: standard input or output, where the format can
// stream (docs/cli.md, "Standard input and output"). The rule, the same for
// every command:
//  - a contour input "-" is `.slices` text read from standard input (the one
//    contour format that is text read front to back; DICOM, label volumes
//    and mask stacks need a file), under the same limits as a file;
//  - an output "-" is standard output for one mesh (reconstruct, simplify:
//    --format names the format, there being no extension) or one `.slices`
//    file (synth); what is reported then goes to stderr, and --json, which
//    would share standard output, is refused;
//  - anywhere else "-" is refused as a usage error (exit 1) before any work.
#include <iosfwd>
#include <string>

#include <CLI/CLI.hpp>

#include "io/mesh/MeshIO.hpp"
#include "report/MeshFormatOption.hpp"

namespace dfrecon::app {

/// True for "-".
bool isStandardStream(const std::string& path);

/// Refuses "-" for an argument that must name a file or folder.
extern const CLI::Validator kNotStandardStream;

/// Where a mesh-writing command writes one mesh.
struct MeshOutput {
    std::string path;                     // as given: a file, or "-"
    MeshFormat format = MeshFormat::Ply;  // the file's extension's, or --format's for "-"
    bool toStandardOutput() const { return isStandardStream(path); }
    /// The path, or "standard output", for messages.
    std::string label() const;
};

/// -o and --format together: a mesh file (--format, if given, must agree
/// with its extension) or "-" (--format required; not with --json). Throws
/// std::invalid_argument (exit 1) otherwise.
MeshOutput meshOutput(const std::string& output, const std::string& format, bool json);

/// Writes `mesh` where `output` says: a file atomically (io/files/AtomicWrite), or
/// standard output, flushed and checked. `mesh` gains the written
/// properties in place (writeMesh's rvalue overload: no copy).
void writeMeshOutput(TriMesh&& mesh, const MeshOutput& output, const MeshWriteOptions& options);

/// Flushes standard output and throws std::runtime_error (exit 3, "cannot
/// write to standard output: REASON") when anything written to it since the
/// start was lost: a full disk, a closed pipe, /dev/full. main() calls it
/// after every command, so no report or streamed mesh that did not arrive
/// ends in exit 0. O(1) beyond the flush.
void checkStandardOutput();

/// Where a command's text report goes: stderr when its result goes to
/// standard output (keeping that stream the result alone), else stdout.
std::ostream& reportStream(bool resultOnStandardOutput);

}  // namespace dfrecon::app
