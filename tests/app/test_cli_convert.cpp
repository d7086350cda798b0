// dfrecon convert to an RT Structure Set on a CT series (--like CTFOLDER):
// every contour's image reference is checked against the images' own
// headers, read here with dcmdata, and the output against dciodvfy.
#include "tests/SyntheticDicomSeries.hpp"  // DCMTK first

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>

#include <nlohmann/json.hpp>

#include "tests/CliRun.hpp"
#include "tests/TempDir.hpp"

namespace {

namespace fs = std::filesystem;
using dfrecon::testing::CliResult;
using dfrecon::testing::runCli;
using dfrecon::testing::slurp;
using dfrecon::testing::TempDir;

// Used by the release-only fixture test below.
#ifndef DFRECON_SANITIZE_BUILD
std::string text(DcmItem& item, const DcmTagKey& key, long index = -1) {
    OFString value;
    if (index < 0)
        item.findAndGetOFStringArray(key, value);
    else
        item.findAndGetOFString(key, value, static_cast<unsigned long>(index));
    return value.c_str();
}

std::vector<DcmItem*> itemsOf(DcmItem& parent, const DcmTagKey& key) {
    std::vector<DcmItem*> items;
    DcmSequenceOfItems* sequence = nullptr;
    if (parent.findAndGetSequence(key, sequence).good() && sequence)
        for (unsigned long i = 0; i < sequence->card(); ++i) items.push_back(sequence->getItem(i));
    return items;
}

std::size_t dciodvfyErrorLines(const std::string& path, std::string& all) {
    const std::string report = path + ".dciodvfy.txt";
    EXPECT_EQ(std::system(("dciodvfy " + path + " >" + report + " 2>&1").c_str()) == -1, false);
    std::ifstream in(report);
    std::size_t errors = 0;
    for (std::string line; std::getline(in, line);) {
        all += line + "\n";
        errors += line.rfind("Error", 0) == 0;
    }
    return errors;
}
#endif

}  // namespace

// plastimatch's structure set of the k-means labels (20 MB, 7 ROIs) takes
// minutes to read in a sanitized binary, so release runs only; the writer's
// references are checked under the sanitizers by test_RtStruct.
#ifndef DFRECON_SANITIZE_BUILD
TEST(CliConvert, LikeCtFolderRefersEveryContourToTheImageOfItsPlane) {
    const fs::path study = fs::path(DFRECON_FIXTURES) / "kmeans_axial";
    ASSERT_TRUE(fs::exists(study / "rtstruct.dcm")) << "run make setup";
    TempDir dir("cli-convert");
    const std::string out = dir / "like-ct.dcm";
    const CliResult run =
        runCli(dir.str(), "convert --json -q " + (study / "rtstruct.dcm").string() + " --like " +
                              (study / "dicom").string() + " --roi-type OAR -o " + out);
    ASSERT_EQ(run.exitCode, 0) << run.err;
    const auto report = nlohmann::json::parse(run.out);
    EXPECT_EQ(report["like"]["images"], 62);
    EXPECT_EQ(report["like"]["filesSkipped"], 1);  // rtss.dcm beside the images
    EXPECT_EQ(report["like"]["contoursOffImages"], 0);
    EXPECT_EQ(report["like"]["contoursOnImages"], report["contours"]);

    // The images as they say themselves: SOP Instance UID -> z.
    std::map<std::string, double> zOfImage;
    std::string seriesUid, frameUid, studyUid;
    for (const auto& entry : fs::directory_iterator(study / "dicom")) {
        if (entry.path().filename() == "rtss.dcm") continue;
        DcmFileFormat image;
        ASSERT_TRUE(image.loadFile(entry.path().c_str()).good()) << entry.path();
        DcmDataset& d = *image.getDataset();
        zOfImage[text(d, DCM_SOPInstanceUID)] = std::stod(text(d, DCM_ImagePositionPatient, 2));
        seriesUid = text(d, DCM_SeriesInstanceUID);
        frameUid = text(d, DCM_FrameOfReferenceUID);
        studyUid = text(d, DCM_StudyInstanceUID);
    }
    ASSERT_EQ(zOfImage.size(), 62u);

    DcmFileFormat input, output;
    ASSERT_TRUE(input.loadFile((study / "rtstruct.dcm").c_str()).good());
    ASSERT_TRUE(output.loadFile(out.c_str()).good());
    DcmDataset& rt = *output.getDataset();
    EXPECT_EQ(text(rt, DCM_StudyInstanceUID), studyUid);
    EXPECT_EQ(text(rt, DCM_FrameOfReferenceUID), frameUid);
    const auto frames = itemsOf(rt, DCM_ReferencedFrameOfReferenceSequence);
    ASSERT_EQ(frames.size(), 1u);
    EXPECT_EQ(text(*frames[0], DCM_FrameOfReferenceUID), frameUid);
    const auto studies = itemsOf(*frames[0], DCM_RTReferencedStudySequence);
    ASSERT_EQ(studies.size(), 1u);
    EXPECT_EQ(text(*studies[0], DCM_ReferencedSOPInstanceUID), studyUid);
    const auto series = itemsOf(*studies[0], DCM_RTReferencedSeriesSequence);
    ASSERT_EQ(series.size(), 1u);
    EXPECT_EQ(text(*series[0], DCM_SeriesInstanceUID), seriesUid);
    std::map<std::string, int> listed;
    for (DcmItem* image : itemsOf(*series[0], DCM_ContourImageSequence))
        ++listed[text(*image, DCM_ReferencedSOPInstanceUID)];
    EXPECT_EQ(listed.size(), 62u);
    for (const auto& [uid, z] : zOfImage) EXPECT_EQ(listed[uid], 1) << uid;

    const auto rois = itemsOf(rt, DCM_ROIContourSequence);
    const auto inputRois = itemsOf(*input.getDataset(), DCM_ROIContourSequence);
    ASSERT_EQ(rois.size(), 7u);
    ASSERT_EQ(inputRois.size(), 7u);
    std::size_t contours = 0;
    for (std::size_t r = 0; r < rois.size(); ++r) {
        // plastimatch's colours are kept.
        EXPECT_EQ(text(*rois[r], DCM_ROIDisplayColor), text(*inputRois[r], DCM_ROIDisplayColor));
        for (DcmItem* contour : itemsOf(*rois[r], DCM_ContourSequence)) {
            ++contours;
            const auto images = itemsOf(*contour, DCM_ContourImageSequence);
            ASSERT_EQ(images.size(), 1u);
            const std::string uid = text(*images[0], DCM_ReferencedSOPInstanceUID);
            ASSERT_EQ(zOfImage.count(uid), 1u) << uid;
            // plastimatch writes one float32 with 8 digits here and 7 there
            // (-6.0999985 and -6.099998): equal within 1e-5 mm.
            EXPECT_NEAR(std::stod(text(*contour, DCM_ContourData, 2)), zOfImage[uid], 1e-5);
        }
    }
    EXPECT_EQ(report["contours"], contours);
    // plastimatch writes no types: every ROI gets --roi-type.
    const auto observations = itemsOf(rt, DCM_RTROIObservationsSequence);
    ASSERT_EQ(observations.size(), 7u);
    for (DcmItem* observation : observations)
        EXPECT_EQ(text(*observation, DCM_RTROIInterpretedType), "OAR");

    std::string all;
    EXPECT_EQ(dciodvfyErrorLines(out, all), 0u) << all;
    EXPECT_NE(all.find("RTStructureSet"), std::string::npos) << all;
}
#endif

TEST(CliConvert, BadRoiTypeAndBadSeriesAreRefused) {
    TempDir dir("cli-convert-bad");
    const std::string slices = dir / "torus.slices";
    ASSERT_EQ(runCli(dir.str(), "synth torus -o " + slices).exitCode, 0);
    CliResult run =
        runCli(dir.str(), "convert " + slices + " --roi-type TUMOUR -o " + (dir / "a.dcm"));
    EXPECT_EQ(run.exitCode, 1);
    EXPECT_NE(run.err.find("--roi-type"), std::string::npos) << run.err;
    run = runCli(dir.str(), "convert " + slices + " --roi-type PTV -o " + (dir / "a.slices"));
    EXPECT_EQ(run.exitCode, 1);
    EXPECT_NE(run.err.find("--roi-type applies to DICOM output only"), std::string::npos)
        << run.err;

    const std::string empty = dir / "empty";
    fs::create_directories(empty);
    run = runCli(dir.str(), "convert " + slices + " --like " + empty + " -o " + (dir / "a.dcm"));
    EXPECT_EQ(run.exitCode, 2);
    EXPECT_NE(run.err.find("no DICOM images"), std::string::npos) << run.err;
    EXPECT_FALSE(fs::exists(dir / "a.dcm"));

    // A series whose planes miss the torus's: written, with a warning that
    // counts the contours on no image.
    const std::string ct = dir / "ct";
    fs::create_directories(ct);
    dfrecon::testing::writeSyntheticSeries(ct, 3, 1000, 2);
    run = runCli(dir.str(), "convert --json " + slices + " --like " + (ct + "/image_1.dcm") +
                                " -o " + (dir / "a.dcm"));
    ASSERT_EQ(run.exitCode, 0) << run.err;
    const auto report = nlohmann::json::parse(run.out);
    EXPECT_EQ(report["like"]["images"], 3);
    EXPECT_EQ(report["like"]["contoursOnImages"], 0);
    EXPECT_EQ(report["like"]["contoursOffImages"], report["contours"]);
    EXPECT_NE(run.err.find("lie in no image's plane"), std::string::npos) << run.err;
}
