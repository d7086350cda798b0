#pragma once
// What VTK's own readers make of a .vtk or .vtp file (vtkPolyDataReader,
// vtkXMLPolyDataReader, run by tests/io/vtk_read_check.py under the
// system Python with python3-vtk9): the independent check that the files
// open in ParaView and 3D Slicer as written.
#include <sys/wait.h>

#include <cstdio>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace dfrecon::testing {

struct VtkRead {
    bool available = false;  // VTK's Python module is installed
    bool ok = false;         // every file read
    std::string error;
    std::vector<nlohmann::json> files;  // one per path, as the script describes it
};

/// Reads `paths` with VTK's readers in one Python run (about a second).
inline VtkRead readWithVtk(const std::vector<std::string>& paths) {
    std::string command = std::string(DFRECON_PYTHON) + " " + DFRECON_VTK_READER;
    for (const std::string& path : paths) command += " '" + path + "'";
    command += " 2>&1";
    VtkRead result;
    FILE* pipe = ::popen(command.c_str(), "r");
    if (!pipe) {
        result.error = "cannot start " + command;
        return result;
    }
    std::string text;
    char buffer[65536];
    for (std::size_t n; (n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0;)
        text.append(buffer, n);
    const int status = ::pclose(pipe);
    const int code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    result.available = code != 77;
    if (code != 0) {
        result.error = text;
        return result;
    }
    std::size_t start = 0;
    while (start < text.size()) {
        const std::size_t end = text.find('\n', start);
        const std::string line = text.substr(start, end - start);
        start = end == std::string::npos ? text.size() : end + 1;
        // VTK's own log lines (warnings) are not JSON objects.
        if (!line.empty() && line[0] == '{') result.files.push_back(nlohmann::json::parse(line));
    }
    result.ok = result.files.size() == paths.size();
    if (!result.ok) result.error = text;
    return result;
}

}  // namespace dfrecon::testing

/// Skips the test when VTK's Python module is missing (scripts/setup.sh
/// installs it), fails it when a reader fails.
#define DFRECON_READ_WITH_VTK(result, ...)                                                    \
    const ::dfrecon::testing::VtkRead result = ::dfrecon::testing::readWithVtk(__VA_ARGS__);  \
    if (!result.available) GTEST_SKIP() << "python3-vtk9 is not installed: " << result.error; \
    ASSERT_TRUE(result.ok) << result.error
