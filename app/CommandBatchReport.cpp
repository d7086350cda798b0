// dfrecon batch-report OUT: one CSV and one JSON table over every record of
// a batch output folder, byte for byte the same however the entries were
// sharded (docs/cli.md, docs/cluster.md).
#include <filesystem>
#include <iostream>
#include <memory>

#include <nlohmann/json.hpp>

#include "app/BatchReport.hpp"
#include "app/Commands.hpp"
#include "app/HtmlReport.hpp"
#include "app/OutputOptions.hpp"
#include "contours/InputError.hpp"
#include "io/files/AtomicWrite.hpp"
#include "io/files/JsonText.hpp"
#include "io/images/Colours.hpp"
#include "io/mesh/MeshIO.hpp"

namespace dfrecon::app {

namespace {

struct BatchReportArgs {
    std::string folder, output, htmlPath;
    bool noSeconds = false, json = false;
};

// The HTML report: the table beside every written mesh (OUT/ID/FILE), each
// in the palette's colour of its row. A mesh that cannot be read is named
// under the table, not drawn.
void writeBatchPage(const BatchReportArgs& args, const nlohmann::ordered_json& rows,
                    bool withSeconds) {
    namespace fs = std::filesystem;
    HtmlReport page;
    page.title = "dfrecon batch-report " + fs::path(args.folder).filename().string();
    for (const std::string& column : kBatchReportColumns)
        if (withSeconds || column != "seconds") page.columns.push_back(column);
    page.rows = rows;
    std::string leftOut;
    for (std::size_t i = 0; i < rows.size(); ++i) {
        if (!rows[i]["mesh"].is_string()) continue;
        const std::string mesh = rows[i]["mesh"].get<std::string>();
        try {
            ReportSurface s{mesh,
                            categoricalColour(std::int64_t(i) + 1),
                            readTriangleSoup((fs::path(args.folder) / mesh).string()),
                            {}};
            if (!addSurface(page, std::move(s))) leftOut += (leftOut.empty() ? "" : ", ") + mesh;
        } catch (const std::exception& e) {
            leftOut += (leftOut.empty() ? "" : ", ") + mesh + " (" + e.what() + ")";
        }
    }
    if (!leftOut.empty()) page.note = "Not drawn: " + leftOut + ".";
    writeHtmlReport(args.htmlPath, page);
}

void runBatchReport(const BatchReportArgs& args) {
    namespace fs = std::filesystem;
    if (!fs::is_directory(args.folder)) throw InputError(args.folder, 0, "not a folder");
    const std::vector<nlohmann::json> records = readBatchRecords(args.folder);
    if (records.empty())
        throw InputError(args.folder, 0,
                         "no batch records (FOLDER/ID/record.json, written by dfrecon batch)");
    const bool withSeconds = !args.noSeconds;
    const nlohmann::ordered_json rows = batchReportRows(records, withSeconds);
    const nlohmann::ordered_json report{
        {"format", "dfrecon-batch-report 1"}, {"entries", records.size()}, {"rows", rows}};
    if (args.output == "-") {  // the table itself to standard output, no files
        std::cout << (args.json ? jsonText(report, 2) + "\n" : batchReportCsv(rows, withSeconds));
        return;
    }
    const std::string base =
        args.output.empty() ? (fs::path(args.folder) / "batch-report").string() : args.output;
    writeStreamAtomically(base + ".csv",
                          [&](std::ostream& out) { out << batchReportCsv(rows, withSeconds); });
    writeStreamAtomically(base + ".json",
                          [&](std::ostream& out) { out << jsonText(report, 2) << "\n"; });
    if (!args.htmlPath.empty()) writeBatchPage(args, rows, withSeconds);
    std::size_t failed = 0, invalid = 0;
    for (const auto& row : rows) {
        const int code = row["exitCode"].is_number() ? row["exitCode"].get<int>() : 0;
        failed += code != 0 && code != 4;
        invalid += code == 4;
    }
    if (args.json)
        std::cout << jsonText(nlohmann::ordered_json{{"command", "batch-report"},
                                                     {"entries", records.size()},
                                                     {"rows", rows.size()},
                                                     {"failed", failed},
                                                     {"notValidSolids", invalid},
                                                     {"csv", base + ".csv"},
                                                     {"json", base + ".json"}},
                              2)
                  << "\n";
    else
        std::cout << records.size() << " entries, " << rows.size() << " rows (" << failed
                  << " failed, " << invalid << " not a valid closed solid) -> " << base << ".csv, "
                  << base << ".json\n";
}

}  // namespace

void addBatchReportCommand(CLI::App& root, const GlobalOptions&) {
    auto args = std::make_shared<BatchReportArgs>();
    CLI::App* cmd = root.add_subcommand(
        "batch-report", "One CSV and one JSON table over every record of a batch output folder");
    cmd->footer(
        "Reads FOLDER/ID/record.json of every entry `dfrecon batch` has done (in any number "
        "of shards) and writes BASE.csv and BASE.json: one row per ROI (one per entry that "
        "failed before its ROIs) with entry, roi, mesh, volumeCc, contourVolumeCc (the volume "
        "planning systems count from the contours), validSolid, triangles, seconds, exitCode "
        "(0, the failure's code, 4 not a valid closed solid) and error; sorted by manifest "
        "position, then ROI order. Everything but the seconds is the same byte for byte "
        "however the entries were sharded; --no-seconds leaves them out. Exit codes: 0 "
        "written, 2 no records or one unreadable, 3 cannot write.");
    cmd->add_option("folder", args->folder, "The output folder of dfrecon batch")->required();
    cmd->add_option("-o,--output", args->output,
                    "Write BASE.csv and BASE.json (default: FOLDER/batch-report); - prints the "
                    "CSV table (with --json the JSON table) to standard output instead, no files");
    cmd->add_flag("--no-seconds", args->noSeconds,
                  "Leave the seconds column out (the rest does not depend on the run)");
    cmd->add_option("--html", args->htmlPath,
                    "Also write FILE.html: the table beside an interactive 3D view of every "
                    "written mesh (one self-contained page, no network needed to open it)");
    cmd->add_flag("--json", args->json, "Print a JSON summary instead of a line");
    asOutput(cmd->get_option("--html"), OutputKind::File);
    cmd->callback([args] { runBatchReport(*args); });
}

}  // namespace dfrecon::app
