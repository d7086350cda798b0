// The batch report: the same bytes whatever order records were made or
// found in, rows per ROI and per failed entry, CSV quoted as RFC 4180 says.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "app/BatchRecord.hpp"
#include "app/BatchReport.hpp"
#include "contours/InputError.hpp"
#include "tests/TempDir.hpp"

using namespace dfrecon;
using namespace dfrecon::app;
using dfrecon::testing::TempDir;

namespace {

nlohmann::ordered_json roi(const std::string& name, bool valid, double seconds) {
    return {{"roi", name},
            {"validSolid", valid},
            {"triangles", 120},
            {"volumeCc", 33.5},
            {"contourVolumeCc", 33.25},
            {"mesh", valid ? nlohmann::ordered_json(name + ".ply") : nullptr},
            {"seconds", {{"fields", 0.1}, {"total", seconds}}}};
}

void writeRecord(const TempDir& dir, const std::string& id, std::size_t entry,
                 const nlohmann::ordered_json& rois, const nlohmann::ordered_json& error,
                 double seconds) {
    std::filesystem::create_directories(dir / id);
    nlohmann::ordered_json record{{"format", kRecordFormat},
                                  {"id", id},
                                  {"entry", entry},
                                  {"exitCode", error.is_null() ? 0 : 2},
                                  {"error", error},
                                  {"seconds", seconds},
                                  {"rois", rois}};
    std::ofstream(dir / (id + "/" + kRecordFileName)) << record.dump(2);
}

std::string report(const TempDir& dir, bool withSeconds) {
    const auto rows = batchReportRows(readBatchRecords(dir.str()), withSeconds);
    return batchReportCsv(rows, withSeconds) + rows.dump();
}

}  // namespace

TEST(BatchReport, SameBytesWhateverTheRunsTimes) {
    const TempDir one("report-one"), two("report-two");
    // Written in different orders, with different seconds: the report without
    // seconds is the same, sorted by manifest position.
    writeRecord(one, "b", 2, {roi("Lung, \"L\"", true, 1.0), roi("Cord", false, 2.0)}, nullptr, 3);
    writeRecord(one, "a", 1, nlohmann::ordered_json::array(), "a.dcm: cannot open file", 0.1);
    writeRecord(one, "c10", 10, nlohmann::ordered_json::array({roi("GTV", true, 1.0)}), nullptr, 1);
    writeRecord(two, "c10", 10, nlohmann::ordered_json::array({roi("GTV", true, 7.0)}), nullptr, 7);
    writeRecord(two, "a", 1, nlohmann::ordered_json::array(), "a.dcm: cannot open file", 0.2);
    writeRecord(two, "b", 2, {roi("Lung, \"L\"", true, 5.0), roi("Cord", false, 6.0)}, nullptr, 11);
    EXPECT_EQ(report(one, false), report(two, false));
    EXPECT_NE(report(one, true), report(two, true));

    const auto rows = batchReportRows(readBatchRecords(one.str()), true);
    const std::string csv = batchReportCsv(rows, true);
    EXPECT_EQ(
        csv,
        "entry,roi,mesh,volumeCc,contourVolumeCc,validSolid,triangles,seconds,exitCode,error\n"
        "a,,,,,,,0.1,2,a.dcm: cannot open file\n"
        "b,\"Lung, \"\"L\"\"\",\"b/Lung, \"\"L\"\".ply\",33.5,33.25,true,120,1.0,0,\n"
        "b,Cord,,33.5,33.25,false,120,2.0,4,not a valid closed solid\n"
        "c10,GTV,c10/GTV.ply,33.5,33.25,true,120,1.0,0,\n");
    EXPECT_EQ(
        batchReportCsv(batchReportRows(readBatchRecords(one.str()), false), false).substr(0, 76),
        "entry,roi,mesh,volumeCc,contourVolumeCc,validSolid,triangles,exitCode,error\n");
}

TEST(BatchReport, SkipsHiddenFoldersAndRefusesForeignRecords) {
    const TempDir dir("report-foreign");
    writeRecord(dir, "a", 1, nlohmann::ordered_json::array({roi("GTV", true, 1.0)}), nullptr, 1);
    std::filesystem::create_directories(dir / ".a.dfrecon-XXXXXX");
    std::filesystem::create_directories(dir / "no-record");
    EXPECT_EQ(readBatchRecords(dir.str()).size(), 1u);
    std::filesystem::create_directories(dir / "x");
    std::ofstream(dir / "x/record.json") << "{\"format\": \"something else\"}";
    try {
        readBatchRecords(dir.str());
        FAIL() << "a foreign record was read";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("x/record.json: not a batch record"),
                  std::string::npos)
            << e.what();
    }
}
