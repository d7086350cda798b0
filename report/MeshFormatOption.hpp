#pragma once
// The --format option of every command that writes meshes, defined once (the
// program's commands and reconstruct's settings, which batch manifests and
// the Python module read too).
#include <string>

#include <CLI/CLI.hpp>

#include "io/mesh/MeshFormat.hpp"

namespace dfrecon {

/// Adds --format (every format io/mesh/MeshFormat writes: ply obj off stl vtk
/// vtp) to a command that writes meshes, into `format` ("" when not
/// given), described by `description` with the list of names appended.
/// O(1).
inline void addMeshFormatOption(CLI::App& command, std::string& format,
                                const std::string& description) {
    command.add_option("--format", format, description + ": " + meshFormatList(false))
        ->check(CLI::IsMember(meshFormatNames(false)));
}

}  // namespace dfrecon
