#pragma once
// One ROI reconstructed, checked, simplified if asked and written, with its
// report: the step `reconstruct` runs per ROI and `batch` per ROI of every
// entry, so both write the same files and the same report keys.
#include <exception>
#include <string>

#include <nlohmann/json.hpp>

#include "app/Commands.hpp"
#include "app/Inputs.hpp"
#include "app/StandardStreams.hpp"
#include "cl/Runtime.hpp"
#include "dfrecon/Reconstruct.hpp"
#include "geometry/TriangleSoup.hpp"
#include "report/ReconstructSettings.hpp"
#include "report/RoiReport.hpp"

namespace dfrecon::app {

/// What one ROI gives: its report and the lines it would print, held until
/// the command prints them in ROI order.
struct RoiOutcome {
    nlohmann::ordered_json report;
    std::string out, err;  // for stdout (a summary line) and stderr
    int failure = 0;       // exit code of the error that stopped this ROI, 0 if none
    bool invalid = false;  // done, but not a valid closed solid (and open ends not asked for)
    /// The surface as written (patient mm), for reports that show it; empty
    /// when the ROI failed.
    TriangleSoup surface;
};

/// How writeRoiSurface reports while it works and what it keeps.
struct RoiWriteOptions {
    bool quiet = false;         // --quiet: no progress bar, no warning for an invalid surface
    bool showProgress = false;  // a progress bar per stage (one ROI at a time)
    bool keepSurface = false;   // the outcome keeps the surface (for an HTML report)
};

/// Reconstructs `roi` (one of input.contours.rois), writes it to `output` as
/// described in docs/reconstruction.md and returns the report `reconstruct
/// --json` gives per ROI. A surface that is not a valid closed solid is
/// reported (`invalid`) and written only with settings.allowInvalid. The
/// outcome holds the surface only with options.keepSurface; else it is
/// freed once the mesh to write is made, where a large ROI peaks. Throws
/// what the stages throw (input limits, OpenCL, memory, a write that
/// fails). Safe to call for several ROIs at once, one runtime each. O(the
/// reconstruction). (The API's reconstructRoi reconstructs only.)
RoiOutcome writeRoiSurface(ocl::Runtime& runtime, const Roi& roi, const MeshOutput& output,
                           const ContourInput& input, const ReconstructSettings& settings,
                           const RoiWriteOptions& options);

/// The first half of writeRoiSurface: `roi` reconstructed (and simplified
/// when settings ask and `simplify`), with the progress bars it shows.
RoiSurface reconstructForWriting(ocl::Runtime& runtime, const Roi& roi,
                                 const ReconstructSettings& settings,
                                 const RoiWriteOptions& options, bool simplify);

/// `result` (reconstructForWriting's without simplification) simplified as
/// the settings ask (--max-error), with its progress bar; nothing when they
/// do not or it was simplified already. O(the simplification).
void simplifyForWriting(ocl::Runtime& runtime, const Roi& roi, RoiSurface& result,
                        const ReconstructSettings& settings, const RoiWriteOptions& options);

/// The second half: `result` (reconstructForWriting's, simplified already
/// if asked) written and reported as writeRoiSurface does. Lets
/// `reconstruct` work on every ROI's surface (neighbours kept apart)
/// between the two.
RoiOutcome writeReconstructedRoi(const Roi& roi, RoiSurface result, const MeshOutput& output,
                                 const ContourInput& input, const ReconstructSettings& settings,
                                 const RoiWriteOptions& options);

/// The outcome of an ROI that failed with `error` (report/Failure names it):
/// reported with `error` and `exitCode`, so the other ROIs go on; a usage
/// error (the ROI's data refused as an argument) counts as bad input (2),
/// since the command line was read before any ROI. O(1).
RoiOutcome failedRoi(const Roi& roi, std::exception_ptr error);

}  // namespace dfrecon::app
