#pragma once
// A command's outputs checked together, before any work: none may be an
// input of the command, another output of it (also ignoring letter case,
// as macOS and Windows file systems do), a device, a FIFO or a socket, and
// a file output may not be a folder. Commands mark their output options;
// the program checks the chosen command once its command line is parsed.
// io/files/OutputTarget holds the rules and checks every write again.
#include <CLI/CLI.hpp>

namespace dfrecon::app {

/// What an output option names.
enum class OutputKind {
    File,          // a file ("-" passes: standard output, where allowed)
    Folder,        // a folder, created if missing
    FileOrFolder,  // either, decided by other options (reconstruct -o with --all)
};

/// Marks `option` as naming an output of its command. Returns `option`.
CLI::Option* asOutput(CLI::Option* option, OutputKind kind = OutputKind::File);

/// Throws std::invalid_argument (exit 1) naming the option and path when an
/// output given to `command` breaks a rule above. Inputs are the values of
/// the command's and `root`'s other options that name existing files. O(options²)
/// system calls.
void checkOutputOptions(const CLI::App& command, const CLI::App& root);

}  // namespace dfrecon::app
