#include "io/contours/InputDigest.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>

#include "contours/InputError.hpp"
#include "io/contours/ContourSource.hpp"
#include "io/files/FileNames.hpp"
#include "io/files/RegularFile.hpp"
#include "io/files/Sha256.hpp"

namespace dfrecon {

namespace fs = std::filesystem;

namespace {

// Listed and measured first, hashed only once the whole input is known to
// be within kMaxInputBytes: a 100 GB sparse file or a folder of millions
// must be refused in a moment, not after hashing it.
void addFile(std::vector<InputFile>& files, const fs::path& file, const std::string& name,
             const std::string& input) {
    if (files.size() >= kMaxInputFiles)
        throw InputError(input, 0,
                         "more than " + std::to_string(kMaxInputFiles) + " files to checksum");
    files.push_back({name, checkRegularFile(file.string(), kMaxInputFileBytes, "an input file"),
                     file.string()});  // the path to hash, until hashed
}

void hashFiles(std::vector<InputFile>& files, const std::string& input) {
    std::uint64_t total = 0;
    for (const InputFile& file : files) total += file.bytes;
    if (total > kMaxInputBytes)
        throw InputError(input, 0,
                         "its files take " + std::to_string(total >> 20) + " MiB, over the " +
                             std::to_string(kMaxInputBytes >> 20) + " MiB an input may take");
    for (InputFile& file : files) file.sha256 = sha256OfFile(file.sha256);
}

}  // namespace

std::vector<InputFile> inputFiles(const std::string& path) {
    std::vector<InputFile> files;
    std::error_code error;
    const fs::file_status status = fs::status(path, error);
    if (!fs::exists(status)) return files;
    if (fs::is_directory(status)) {
        fs::recursive_directory_iterator it(path, error), end;
        for (; !error && it != end; it.increment(error))
            if (it->is_regular_file(error))
                addFile(files, it->path(), it->path().lexically_relative(path).generic_string(),
                        path);
        if (error) throw InputError(path, 0, "cannot list folder: " + error.message());
    } else if (endsWithIgnoringCase(path, ".nhdr") || endsWithIgnoringCase(path, ".json")) {
        const fs::path folder =
            fs::path(path).parent_path().empty() ? fs::path(".") : fs::path(path).parent_path();
        for (fs::directory_iterator it(folder, error), end; !error && it != end;
             it.increment(error))
            if (it->is_regular_file(error))
                addFile(files, it->path(), it->path().filename().string(), path);
        if (error) throw InputError(path, 0, "cannot list its folder: " + error.message());
    } else {
        addFile(files, path, fs::path(path).filename().string(), path);
        // The table beside a label volume names its ROIs and so the outputs:
        // the one the reader takes (contourSourceOf).
        if (const ContourSource source = contourSourceOf(path); !source.labelTablePath.empty())
            addFile(files, source.labelTablePath,
                    fs::path(source.labelTablePath).filename().string(), path);
    }
    std::sort(files.begin(), files.end(),
              [](const InputFile& a, const InputFile& b) { return a.path < b.path; });
    hashFiles(files, path);
    return files;
}

}  // namespace dfrecon
