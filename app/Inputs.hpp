#pragma once
// What every subcommand does with its inputs: load a contour file (progress
// on a TTY, repair warnings on stderr unless quiet) and pick ROIs by name.
#include <string>
#include <vector>

#include "app/Commands.hpp"
#include "io/SlicesFile.hpp"

namespace dfrecon::app {

/// Loads and validates `path`; throws InputError (exit 2) on bad input.
SlicesLoad loadContours(const std::string& path, const GlobalOptions& global);

/// The ROIs a command works on: `all` → every ROI with slices; a name → that
/// ROI; neither → the only ROI. Throws std::invalid_argument (exit 1) naming
/// the available ROIs when the choice is missing or unknown.
std::vector<const Roi*> selectRois(const ContourSet& contours, const std::string& name, bool all);

/// `name` made safe as part of a file name (letters, digits, - _ . kept).
std::string fileStem(const std::string& name);

}  // namespace dfrecon::app
