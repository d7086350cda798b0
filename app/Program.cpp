#include "app/Program.hpp"

#include <iostream>
#include <string>

#include "app/BatchWorkers.hpp"
#include "app/Commands.hpp"
#include "app/HeapArenas.hpp"
#include "app/OutputOptions.hpp"
#include "app/StandardStreams.hpp"
#include "io/files/OutputTarget.hpp"
#include "report/ExitCodes.hpp"
#include "report/Failure.hpp"
#include "report/NumberChecks.hpp"

namespace dfrecon::app {

int runProgram(int argc, char** argv) {
    oneHeapArenaPerCore();
    CLI::App root{
        "dfrecon: watertight, error-bounded triangle surfaces from planar contour slices.\n"
        "Lengths are in millimetres. Exit codes: 0 ok, 1 usage, 2 bad input, 3 device/runtime, 4 "
        "invalid result.",
        "dfrecon"};
    root.set_version_flag("--version", std::string(DFRECON_VERSION));
    root.require_subcommand(1);
    GlobalOptions global;
    root.add_option("--device", global.device,
                    "OpenCL device: cpu, gpu, an index from `dfrecon devices`, or part of its name "
                    "(default: $DFRECON_DEVICE, else the first GPU, else the CPU)");
    root.add_flag("-q,--quiet", global.quiet, "No progress bar and no warnings on stderr");
    // Contours are always read as planning systems read them now
    // (geometry/PlaneReading); the flag that asked for part of it stays
    // accepted, unlisted, so that scripts written for it keep running.
    bool repairContours = false;
    root.add_flag("--repair-contours", repairContours)->group("");
    root.add_option("--label-table", global.labelTable,
                    "Names and colours of a label volume's labels: an ITK-SNAP label description, "
                    "a FreeSurfer LUT or Slicer colour table (VALUE NAME R G B A), or a list of "
                    "VALUE NAME lines (default: a .seg.nrrd's own segments, else STEM.txt, "
                    "STEM.ctbl, STEM.lut or STEM-labels.txt beside the volume, else label_N)")
        ->check(CLI::ExistingFile);
    root.add_flag("--accept-intensity", global.acceptIntensity,
                  "Contour every value of a label volume that looks like an intensity image "
                  "(32 or more values, changing between most neighbouring voxels) instead of "
                  "refusing it");
    root.fallthrough();

    addSynthCommand(root, global);
    addDevicesCommand(root, global);
    addInfoCommand(root, global);
    addFieldsCommand(root, global);
    addReconstructCommand(root, global);
    addBatchCommand(root, global);
    addBatchReportCommand(root, global);
    addFieldCommand(root, global);
    addSimplifyCommand(root, global);
    addConvertCommand(root, global);
    addMarginCommand(root, global);
    addCombineCommand(root, global);
    addHistogramCommand(root, global);
    addRasterizeCommand(root, global);
    addSdmCommand(root, global);
    addSegmentCommand(root, global);
    addGeodesicCommand(root, global);
    addCheckCommand(root, global);
    addCompareCommand(root, global);
    // Outputs checked together once the chosen command's line is parsed,
    // before its work; every write is checked again against the files read.
    for (CLI::App* command : root.get_subcommands({})) {
        command->parse_complete_callback([command, &root] { checkOutputOptions(*command, root); });
        // Every floating-point option (CLI11 names their type FLOAT) takes
        // finite numbers only.
        for (CLI::Option* option : command->get_options())
            if (option->get_type_name().rfind("FLOAT", 0) == 0) option->check(kFiniteNumber);
    }
    guardInputsFromOutputs(true);

    // CLI11 reports a mistyped subcommand as a missing one; name it instead.
    // The first word that is neither an option nor a global option's value
    // (--device gpu, --label-table FILE) is the subcommand.
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        if (arg.empty() || arg[0] == '-') {
            const CLI::Option* option = root.get_option_no_throw(arg);
            if (option && option->get_items_expected_min() > 0) ++i;  // its value
            continue;
        }
        bool known = false;
        for (const CLI::App* command : root.get_subcommands({}))
            known = known || command->check_name(arg);
        if (!known) {
            std::cerr << "dfrecon: unknown subcommand '" << arg
                      << "' (dfrecon --help lists them)\n";
            return kExitUsage;
        }
        break;
    }

    keepProgramArguments(argc, argv);
    try {
        root.parse(argc, argv);
        checkStandardOutput();
        return kExitOk;
    } catch (const CLI::CallForHelp& e) {
        return root.exit(e);
    } catch (const CLI::CallForAllHelp& e) {
        return root.exit(e);
    } catch (const CLI::CallForVersion& e) {
        return root.exit(e);
    } catch (const CLI::ParseError& e) {
        root.exit(e);
        return kExitUsage;
    } catch (...) {
        const Failure failure = describeFailure(std::current_exception());
        std::cerr << "dfrecon: " << failure.message << "\n";
        return failure.exitCode;
    }
}

}  // namespace dfrecon::app
