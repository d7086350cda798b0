// RTSTRUCT reading and writing on plastimatch's structure sets (the fixtures
// `make setup` generates), against DCMTK's own RT IOD reader: the baseline
// loads the file, reads the IOD and parses every ContourData, but groups,
// validates and combines nothing. Prints JSON lines.
#include <dcmtk/config/osconfig.h>
#include <dcmtk/dcmdata/dctk.h>
#include <dcmtk/dcmrt/drtstrct.h>

#include <filesystem>
#include <iostream>

#include <nlohmann/json.hpp>

#include "bench/Benchmarks.hpp"
#include "io/dicom/RtStruct.hpp"

namespace dfrecon::bench {

namespace {

// DCMTK's dcmrt classes: the whole IOD read, then every contour's numbers.
std::size_t dcmrtRead(const std::string& path) {
    DcmFileFormat file;
    if (file.loadFile(path.c_str()).bad()) return 0;
    DRTStructureSetIOD rt;
    if (rt.read(*file.getDataset()).bad()) return 0;
    std::size_t points = 0;
    DRTROIContourSequence& rois = rt.getROIContourSequence();
    for (OFCondition r = rois.gotoFirstItem(); r.good(); r = rois.gotoNextItem()) {
        DRTContourSequence& contours = rois.getCurrentItem().getContourSequence();
        for (OFCondition c = contours.gotoFirstItem(); c.good(); c = contours.gotoNextItem()) {
            OFVector<Float64> data;
            contours.getCurrentItem().getContourData(data);
            points += data.size() / 3;
        }
    }
    return points;
}

}  // namespace

int benchRtStruct() {
    namespace fs = std::filesystem;
    int status = 0;
    for (const std::string study : {"kmeans", "kmeans_axial"}) {
        const fs::path path = fs::path(DFRECON_FIXTURES) / study / "rtstruct.dcm";
        if (!fs::exists(path)) {
            std::cerr << path << " is missing: run make setup\n";
            status = 1;
            continue;
        }
        RtStructLoad load;
        const double readSeconds = bestSeconds(3, [&] { load = readRtStruct(path.string()); });
        std::size_t contours = 0, points = 0, combined = 0;
        for (const Roi& roi : load.contours.rois) {
            contours += roi.contourCount();
            points += roi.pointCount();
            combined += roi.reading.planesResolved;
        }
        std::size_t baselinePoints = 0;
        const double baselineSeconds =
            bestSeconds(3, [&] { baselinePoints = dcmrtRead(path.string()); });
        const std::string out = (fs::temp_directory_path() / "dfrecon-bench-rt.dcm").string();
        const double writeSeconds = bestSeconds(3, [&] { writeRtStruct(load.contours, out); });
        fs::remove(out);
        const auto bytes = fs::file_size(path);
        const std::string name = "plastimatch " + study;
        std::cout << nlohmann::ordered_json{{"bench", "rtstruct"},
                                            {"case", "read " + name},
                                            {"system", "dfrecon"},
                                            {"bytes", bytes},
                                            {"rois", load.contours.rois.size()},
                                            {"contours", contours},
                                            {"points", points},
                                            {"planesCombinedByXor", combined},
                                            {"seconds", readSeconds}}
                         .dump()
                  << "\n";
        std::cout << nlohmann::ordered_json{{"bench", "rtstruct"},
                                            {"case", "read " + name},
                                            {"system", "dcmtk-dcmrt-parse-only"},
                                            {"bytes", bytes},
                                            {"points", baselinePoints},
                                            {"seconds", baselineSeconds}}
                         .dump()
                  << "\n";
        std::cout << nlohmann::ordered_json{{"bench", "rtstruct"},
                                            {"case", "write " + name},
                                            {"system", "dfrecon"},
                                            {"points", points},
                                            {"seconds", writeSeconds}}
                         .dump()
                  << "\n";
    }
    return status;
}

}  // namespace dfrecon::bench
