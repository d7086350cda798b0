#pragma once
// Each subcommand registers itself on the root CLI::App. A command's
// callback does the work and sets the exit code; exceptions propagate to
// main(), which maps them to the documented exit codes.
#include <CLI/CLI.hpp>

namespace dfrecon::app {

/// Options every subcommand shares.
struct GlobalOptions {
    std::string device;            // --device, falls back to $DFRECON_DEVICE
    bool quiet = false;            // --quiet: no progress bar, no warnings on stderr
    std::string labelTable;        // --label-table: names and colours of label-volume labels
    bool acceptIntensity = false;  // --accept-intensity: contour a scan's every value
};

void addSynthCommand(CLI::App& root, const GlobalOptions& global);
void addDevicesCommand(CLI::App& root, const GlobalOptions& global);
void addInfoCommand(CLI::App& root, const GlobalOptions& global);
void addFieldsCommand(CLI::App& root, const GlobalOptions& global);
void addCheckCommand(CLI::App& root, const GlobalOptions& global);
void addCompareCommand(CLI::App& root, const GlobalOptions& global);
void addReconstructCommand(CLI::App& root, const GlobalOptions& global);
void addBatchCommand(CLI::App& root, const GlobalOptions& global);
void addBatchReportCommand(CLI::App& root, const GlobalOptions& global);
void addFieldCommand(CLI::App& root, const GlobalOptions& global);
void addSimplifyCommand(CLI::App& root, const GlobalOptions& global);
void addConvertCommand(CLI::App& root, const GlobalOptions& global);
void addMarginCommand(CLI::App& root, const GlobalOptions& global);
void addCombineCommand(CLI::App& root, const GlobalOptions& global);
void addHistogramCommand(CLI::App& root, const GlobalOptions& global);
void addRasterizeCommand(CLI::App& root, const GlobalOptions& global);
void addSdmCommand(CLI::App& root, const GlobalOptions& global);
void addSegmentCommand(CLI::App& root, const GlobalOptions& global);
void addGeodesicCommand(CLI::App& root, const GlobalOptions& global);

}  // namespace dfrecon::app
