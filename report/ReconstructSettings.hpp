#pragma once
// How an ROI is reconstructed and written: the options `reconstruct` and
// `batch` share, defined once. The same definitions parse the command line
// and a batch manifest's per-entry options (named like the options without
// the dashes), so both check values alike and name them alike.
#include <string>
#include <utility>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "io/mesh/MeshFormat.hpp"
#include "recon/Reconstruction.hpp"

namespace dfrecon {

struct ReconstructSettings {
    ReconstructionOptions options;
    double maxErrorMm = 0;  // 0: no simplification
    bool allowInvalid = false, ascii = false;
    std::string format;  // --format: a MeshFormat's name, "" when not given

    /// The format of the per-ROI files written into a folder (reconstruct
    /// --all, batch): --format, else PLY. O(1).
    MeshFormat folderFormat() const;
};

/// Adds --pixel-mm, --contour-error, --max-depth, --cap, --interpolation,
/// --smooth-tolerance, --cap-offset, --max-error, --allow-invalid, --ascii
/// and --format to `cmd`, each writing into `settings` (which must outlive
/// `cmd`); --help shows `settings`' values as the defaults. O(1).
void addReconstructSettingsOptions(CLI::App& cmd, ReconstructSettings& settings);

/// The names of those options without their dashes, in --help order. O(1).
std::vector<std::string> reconstructSettingsNames();

/// A per-entry option: its name without dashes, its value as text, and
/// where it was given (for messages, e.g. "manifest.csv:4: column 12").
struct GivenOption {
    std::string name, value, where;
};

/// `base` with every option of `given` applied through the definitions of
/// addReconstructSettingsOptions: the same checks, the same messages. A
/// flag's value is true/false (also yes/no, on/off, 1/0). Throws
/// std::invalid_argument "WHERE: NAME: problem" for an unknown name or a
/// bad value. O(given).
ReconstructSettings withGivenOptions(const ReconstructSettings& base,
                                     const std::vector<GivenOption>& given);

/// Every option's value, keyed by reconstructSettingsNames() in that order
/// (cap-offset null when automatic, format the folder format's name): what a batch record keeps to
/// tell whether the options of an entry changed. O(1).
nlohmann::ordered_json reconstructSettingsJson(const ReconstructSettings& settings);

}  // namespace dfrecon
