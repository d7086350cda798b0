// dfrecon compare A B: how two structures agree, as contouring studies and QA
// checks report it — volumes, Dice, Jaccard, Hausdorff, HD95, mean surface
// distance, surface Dice, centroid distance, and for two contour inputs the
// planning system's per-plane overlap and the added path length — computed
// on the surfaces and contours (compare/), not on voxels, with the
// distances' error bound stated. Two structure sets are compared ROI by ROI
// (report/RoiMatching), one row per pair.
#include <initializer_list>
#include <iomanip>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>

#include <nlohmann/json.hpp>

#include "api/Stopwatch.hpp"
#include "app/Commands.hpp"
#include "app/CsvTable.hpp"
#include "app/Inputs.hpp"
#include "app/OutputOptions.hpp"
#include "app/Progress.hpp"
#include "cl/WorkerRuntimes.hpp"
#include "contours/InputError.hpp"
#include "dfrecon/Compare.hpp"
#include "dfrecon/Reconstruct.hpp"
#include "geometry/MeshCheck.hpp"
#include "geometry/OrderedParallel.hpp"
#include "geometry/SurfaceMeasures.hpp"
#include "io/files/AtomicWrite.hpp"
#include "io/files/JsonText.hpp"
#include "io/mesh/MeshIO.hpp"
#include "report/CompareReport.hpp"
#include "report/ExitCodes.hpp"
#include "report/Failure.hpp"
#include "report/NumberChecks.hpp"
#include "report/RoiMatching.hpp"

namespace dfrecon::app {

namespace {

struct CompareArgs {
    std::string a, b, roiA, roiB;
    double spacingMm = 0.2;
    double toleranceMm = 1;
    std::vector<std::string> matches;  // NAME_IN_A=NAME_IN_B
    std::string csvPath;
    unsigned jobs = 0;  // pairs at once; 0: defaultJobs()
    bool json = false;
};

ComparedSolid readSolid(const std::string& path) {
    ComparedSolid s{readTriangleSoup(path), {}, nullptr};
    s.check = checkMesh(s.surface);
    if (!s.check.validSolid())
        throw InputError(path, 0, "not a valid closed solid (dfrecon check says where)");
    return s;
}

void warnIfCoarsened(double usedMm, const CompareArgs& args, const GlobalOptions& global) {
    if (usedMm > args.spacingMm && !global.quiet)
        std::cerr << "dfrecon: warning: --spacing " << args.spacingMm << " mm would take more than "
                  << kMaxDistanceSamples << " samples on a surface; distances sampled every "
                  << usedMm << " mm, each within that of its exact value\n";
}

void printPair(const Comparison& r, std::ostream& out) {
    const Overlap& o = r.overlap;
    const SurfaceDistances& d = r.distances;
    out << "volume A " << o.volumeAMm3 / 1000 << " cc, B " << o.volumeBMm3 / 1000 << " cc, both "
        << o.intersectionMm3 / 1000 << " cc\n"
        << "Dice " << o.dice() << ", Jaccard " << o.jaccard() << " (" << o.method;
    if (o.shiftMm > 0) out << " " << o.shiftMm << " mm";
    out << ": intersection within " << o.intersectionBoundMm3 << " mm3)\n"
        << "Hausdorff " << d.hausdorffMm() << " mm (A to B " << d.aToB.maxMm << " mm, B to A "
        << d.bToA.maxMm << " mm), HD95 " << d.hd95Mm() << " mm (pooled " << d.hd95PooledMm
        << " mm), mean surface distance " << d.meanMm() << " mm (each within " << d.spacingMm
        << " mm)\n"
        << "surface Dice at " << d.toleranceMm << " mm " << d.surfaceDice()
        << ", centroid distance " << r.centroidDistanceMm << " mm\n";
    if (!r.planes) return;
    const PlaneComparison& p = *r.planes;
    if (!p.samePlanes) {
        out << "on the planes: not compared (" << p.whyNot << ")\n";
        return;
    }
    out << "on the planes (" << p.planes << "): volume A " << p.volumeAMm3 / 1000 << " cc, B "
        << p.volumeBMm3 / 1000 << " cc, Dice " << p.dice() << ", added path length "
        << p.addedPathLengthMm << " mm of " << p.pathLengthBMm << " mm at " << p.toleranceMm
        << " mm\n";
}

// The CSV columns of a pair; the row holds these keys.
const std::vector<std::string> kPairColumns{"roiA",
                                            "roiB",
                                            "matchedBy",
                                            "volumeACc",
                                            "volumeBCc",
                                            "dice",
                                            "jaccard",
                                            "hausdorffMm",
                                            "hausdorffAToBMm",
                                            "hausdorffBToAMm",
                                            "hd95Mm",
                                            "hd95PooledMm",
                                            "meanSurfaceDistanceMm",
                                            "surfaceDice",
                                            "centroidDistanceMm",
                                            "planeDice",
                                            "addedPathLengthMm",
                                            "overlapMethod",
                                            "exitCode",
                                            "error"};

nlohmann::ordered_json flatRow(const nlohmann::ordered_json& pair) {
    nlohmann::ordered_json row;
    for (const std::string& column : kPairColumns)
        row[column] = pair.contains(column) ? pair[column] : nlohmann::ordered_json();
    if (pair.contains("aToB")) {  // the directed distances, each way
        row["hausdorffAToBMm"] = pair["aToB"]["hausdorffMm"];
        row["hausdorffBToAMm"] = pair["bToA"]["hausdorffMm"];
    }
    if (pair.contains("volumeAMm3")) {
        row["volumeACc"] = pair["volumeAMm3"].get<double>() / 1000;
        row["volumeBCc"] = pair["volumeBMm3"].get<double>() / 1000;
    }
    const nlohmann::ordered_json planes = pair.value("onPlanes", nlohmann::ordered_json());
    if (planes.is_object() && planes.value("compared", false)) {
        row["planeDice"] = planes["dice"];
        row["addedPathLengthMm"] = planes["addedPathLengthMm"];
    }
    return row;
}

void writeCsv(const std::string& path, const nlohmann::ordered_json& pairs) {
    nlohmann::ordered_json rows = nlohmann::ordered_json::array();
    for (const nlohmann::ordered_json& pair : pairs) rows.push_back(flatRow(pair));
    const std::string csv = csvTable(rows, kPairColumns);
    writeStreamAtomically(path, [&](std::ostream& out) { out << csv; });
}

bool isStructureSetRun(const CompareArgs& args, const ContourInput* a, const ContourInput* b) {
    if (!a || !b || !args.roiA.empty() || !args.roiB.empty()) return false;
    auto several = [](const ContourInput& in) {
        std::size_t n = 0;
        for (const Roi& roi : in.contours.rois) n += isComparable(roi);
        return n > 1;
    };
    return !args.matches.empty() || several(*a) || several(*b);
}

void runOnePair(const CompareArgs& args, const GlobalOptions& global, const ContourInput* inputA,
                const ContourInput* inputB) {
    Stopwatch watch;
    ocl::Runtime runtime(global.device);
    auto structure = [&](const std::string& path, const ContourInput* input,
                         const std::string& roi) {
        if (!input) return readSolid(path);
        if (roi.empty() && std::none_of(input->contours.rois.begin(), input->contours.rois.end(),
                                        [](const Roi& r) { return isComparable(r); }))
            throw InputError(path, 0, "no ROI with contours to compare");
        return reconstructedSolid(runtime, path, *selectRois(input->contours, roi, false).front());
    };
    // A bar that moves with the work: the two surfaces, then the overlap,
    // the distances and the planes.
    Progress progress("compare", !global.quiet);
    progress.update(0);
    const ComparedSolid a = structure(args.a, inputA, args.roiA);
    progress.update(0.15);
    const ComparedSolid b = structure(args.b, inputB, args.roiB);
    progress.update(0.3);
    const double loadSeconds = watch.lap();
    CompareOptions options{args.spacingMm, args.toleranceMm};
    options.progress = [&progress](double done) { progress.update(0.3 + 0.7 * done); };
    const Comparison r = compareSolids(runtime, a, b, options);
    progress.finish();
    warnIfCoarsened(r.distances.spacingMm, args, global);
    nlohmann::ordered_json report{{"command", "compare"}, {"a", args.a}, {"b", args.b}};
    if (a.contours) report["roiA"] = a.contours->name;
    if (b.contours) report["roiB"] = b.contours->name;
    report.update(comparisonJson(r));
    report["seconds"]["load"] = loadSeconds;
    report["exitCode"] = 0;  // the CSV row's, as in a structure-set comparison
    report["error"] = nullptr;
    if (!args.csvPath.empty()) writeCsv(args.csvPath, nlohmann::ordered_json::array({report}));
    if (args.json)
        std::cout << jsonText(report, 2) << "\n";
    else
        printPair(r, std::cout);
}

void runStructureSets(const CompareArgs& args, const GlobalOptions& global,
                      const ContourInput& inputA, const ContourInput& inputB) {
    const RoiMatching matching = matchRois(inputA.contours, inputB.contours, args.matches);
    if (matching.pairs.empty()) {
        // An empty table is no comparison: say why and what pairs them.
        auto list = [](const std::vector<const Roi*>& rois) {
            std::string text;
            for (const Roi* roi : rois) text += (text.empty() ? "'" : ", '") + roi->name + "'";
            return text.empty() ? std::string("none") : text;
        };
        throw std::invalid_argument("no ROI of A pairs with one of B by name (A: " +
                                    list(matching.onlyA) + "; B: " + list(matching.onlyB) +
                                    "): pair them with --match NAME_IN_A=NAME_IN_B (repeatable)");
    }
    const std::size_t count = matching.pairs.size();
    const std::size_t jobs = jobsFor(args.jobs, count);
    ocl::WorkerRuntimes runtimes(global.device, jobs);
    nlohmann::ordered_json pairs = nlohmann::ordered_json::array();
    std::optional<Failure> firstFailure;
    std::size_t failures = 0;
    Progress progress("compare", !global.quiet);
    forEachInOrder(
        count, jobs,
        [&](std::size_t item, std::size_t worker) {
            return comparedPairRow(runtimes[worker], matching.pairs[item], args.a, args.b,
                                   CompareOptions{args.spacingMm, args.toleranceMm});
        },
        [&](std::size_t item, nlohmann::ordered_json row) {
            if (row["exitCode"] != 0) {
                if (!firstFailure)
                    firstFailure =
                        Failure{row["exitCode"].get<int>(), row["error"].get<std::string>()};
                ++failures;
            } else {
                warnIfCoarsened(row["distanceBoundMm"].get<double>(), args, global);
            }
            pairs.push_back(std::move(row));
            progress.update(double(item + 1) / double(count));
        });
    progress.finish();
    if (!args.csvPath.empty()) writeCsv(args.csvPath, pairs);
    if (args.json) {
        nlohmann::ordered_json report{
            {"command", "compare"}, {"a", args.a}, {"b", args.b}, {"pairs", pairs}};
        report.update(unpairedJson(matching));
        std::cout << jsonText(report, 2) << "\n";
    } else {
        std::cout << "ROI A | ROI B | Dice | Hausdorff mm | A to B mm | B to A mm | HD95 mm | "
                     "mean mm | surface Dice | plane Dice | added path mm\n";
        for (const nlohmann::ordered_json& pair : pairs) {
            const nlohmann::ordered_json row = flatRow(pair);
            std::cout << pair["roiA"].get<std::string>() << " | "
                      << pair["roiB"].get<std::string>();
            if (!row["error"].is_null()) {
                std::cout << " | failed: " << row["error"].get<std::string>() << "\n";
                continue;
            }
            // Ratios to four decimals, lengths to a hundredth of a mm: what a
            // table is read for (--json and --csv keep every digit).
            for (const auto& [key, decimals] :
                 std::initializer_list<std::pair<const char*, int>>{{"dice", 4},
                                                                    {"hausdorffMm", 2},
                                                                    {"hausdorffAToBMm", 2},
                                                                    {"hausdorffBToAMm", 2},
                                                                    {"hd95Mm", 2},
                                                                    {"meanSurfaceDistanceMm", 2},
                                                                    {"surfaceDice", 4},
                                                                    {"planeDice", 4},
                                                                    {"addedPathLengthMm", 1}}) {
                const nlohmann::ordered_json& value = row[key];
                std::ostringstream cell;
                if (value.is_number())
                    cell << std::fixed << std::setprecision(decimals) << value.get<double>();
                else
                    cell << "-";
                std::cout << " | " << cell.str();
            }
            std::cout << "\n";
        }
        for (const Roi* roi : matching.onlyA) std::cout << "only in A: " << roi->name << "\n";
        for (const Roi* roi : matching.onlyB) std::cout << "only in B: " << roi->name << "\n";
        for (const Roi* roi : matching.duplicateA)
            std::cout << "name used twice in A (not paired; --match pairs the first): " << roi->name
                      << "\n";
        for (const Roi* roi : matching.duplicateB)
            std::cout << "name used twice in B (not paired; --match pairs the first): " << roi->name
                      << "\n";
        for (const Roi* roi : matching.emptyA) std::cout << "empty in A: " << roi->name << "\n";
        for (const Roi* roi : matching.emptyB) std::cout << "empty in B: " << roi->name << "\n";
    }
    if (firstFailure)
        throw ItemsFailed(std::to_string(failures) + " of " + std::to_string(pairs.size()) +
                              " pairs failed; the first: " + firstFailure->message,
                          firstFailure->exitCode);
}

void runCompare(const CompareArgs& args, const GlobalOptions& global) {
    std::optional<ContourInput> inputA, inputB;
    if (!isMeshExtension(args.a)) inputA = loadContours(args.a, global);
    if (!isMeshExtension(args.b)) inputB = loadContours(args.b, global);
    const ContourInput* a = inputA ? &*inputA : nullptr;
    const ContourInput* b = inputB ? &*inputB : nullptr;
    if (!args.matches.empty() && !(a && b))
        throw std::invalid_argument("--match needs two contour files (structure sets)");
    if (isStructureSetRun(args, a, b))
        runStructureSets(args, global, *a, *b);
    else
        runOnePair(args, global, a, b);
}

}  // namespace

void addCompareCommand(CLI::App& root, const GlobalOptions& global) {
    auto args = std::make_shared<CompareArgs>();
    CLI::App* cmd = root.add_subcommand(
        "compare",
        "Volumes, Dice, Jaccard, Hausdorff, HD95, mean surface distance, surface Dice, added "
        "path length of two structures or two structure sets, on their surfaces and contours");
    cmd->footer(
        "A and B are mesh files (.ply .stl .obj .off; valid closed solids) or contour files "
        "(.slices, DICOM RTSTRUCT, label volumes; each ROI is reconstructed with reconstruct's "
        "defaults). Dice and Jaccard come from the volume of the intersection found on the "
        "surfaces (the flux through each surface's part inside the other: exact predicates, "
        "crossing points in double precision, its bound stated as intersectionBoundMm3; where "
        "the surfaces coincide in part, B is moved 1e-9 mm and area(B) x 1e-9 mm added to the "
        "bound), so they carry no voxelisation error. Distances: every triangle of each "
        "surface is cut into cells, every point of a cell within --spacing of its sample, and "
        "each sample gets its exact distance to the other surface (the closest-primitive "
        "kernel); Hausdorff is the larger directed "
        "maximum, HD95 the larger directed area-weighted 95th percentile (hd95PooledMm: of both "
        "directions pooled), the mean is area-weighted over both surfaces; surface Dice is the "
        "share of both surfaces' area within --tolerance of the other; the centroid distance is "
        "between the solids' centres of mass; each is within --spacing of its exact value (a "
        "spacing that would take more than 8 388 608 samples on a surface is coarsened until it "
        "does not, with a warning; the report's distanceBoundMm is the one used). Two contour "
        "inputs on the same planes are also compared the planning system's way (onPlanes): "
        "exact polygon Booleans on each plane times its thickness, and the added path length, "
        "the length of B's contours farther than --tolerance from A's on their plane (B the "
        "test, A the reference). Two structure sets (contour files with several ROIs and no "
        "--roi-a/--roi-b, or any --match) are compared ROI by ROI: matched by --match, then by "
        "name, then by name ignoring case, spaces and punctuation; one row per pair, unmatched "
        "ROIs listed. Exit codes: 0 done, 1 usage, 2 bad input (a surface that is not a valid "
        "closed solid), 3 runtime failure, 4 an ROI that gives no valid closed solid; with "
        "structure sets every pair is reported, then the first failure's code is the exit code.");
    cmd->add_option("a", args->a, "First structure (the reference): mesh or contour file")
        ->required();
    cmd->add_option("b", args->b, "Second structure (the test): mesh or contour file")->required();
    cmd->add_option("--roi-a", args->roiA, "ROI of A when A is a contour file with several");
    cmd->add_option("--roi-b", args->roiB, "ROI of B when B is a contour file with several");
    cmd->add_option("--match", args->matches,
                    "Pair ROIs of two structure sets whose names differ: NAME_IN_A=NAME_IN_B "
                    "(repeat for more pairs)");
    cmd->add_option("--csv", args->csvPath,
                    "Also write the table, one row per pair, to this CSV file (columns: "
                    "roiA, roiB, matchedBy, volumes in cc, Dice, Jaccard, distances in mm, "
                    "surfaceDice, planeDice, addedPathLengthMm, overlapMethod, exitCode, error)");
    cmd->add_option("--spacing", args->spacingMm,
                    "Distance sampling, mm: every point of the surfaces lies within this of a "
                    "sample, and every distance figure within this of its exact value")
        ->capture_default_str()
        ->check(kPositive);
    cmd->add_option("--tolerance", args->toleranceMm,
                    "Tolerance of surface Dice and of the added path length, mm: the share of "
                    "both surfaces within this distance of the other (surfaceDice); B's contour "
                    "length farther than this from A's (addedPathLengthMm)")
        ->capture_default_str()
        ->check(kNonNegative);
    cmd->add_option("-j,--jobs", args->jobs,
                    "Pairs of two structure sets compared at once (0: one per hardware "
                    "thread; never more than one per thread or per pair); the rows are the same "
                    "for any value but for their seconds")
        ->capture_default_str();
    cmd->add_flag("--json", args->json, "Print a JSON report instead of text");
    asOutput(cmd->get_option("--csv"), OutputKind::File);
    cmd->callback([args, &global] { runCompare(*args, global); });
}

}  // namespace dfrecon::app
