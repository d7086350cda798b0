// Writes the seed corpus of fuzz_rtstruct (tests/data/fuzz-rtstruct/) with
// DCMTK, so that every seed is a file a real writer could produce and the
// fuzzer starts from well-formed structure rather than from guesses:
// usage: make_rtstruct_seeds DIR. Ordinary cases go through writeRtStruct;
// the ones our writer never produces (POINT and CLOSEDPLANAR_XOR contours,
// no ContourSequence, implicit VR without preamble or meta header, as
// pydicom's test file) are built with dcmdata directly.
#include <dcmtk/config/osconfig.h>  // first, as DCMTK requires
#include <dcmtk/dcmdata/dctk.h>

#include <cstdio>
#include <string>
#include <vector>

#include "io/dicom/RtStruct.hpp"

using namespace dfrecon;

namespace {

Polygon square(double x0, double y0, double side, bool clockwise = false) {
    Polygon p = {{x0, y0}, {x0 + side, y0}, {x0 + side, y0 + side}, {x0, y0 + side}};
    if (clockwise) std::reverse(p.begin(), p.end());
    return p;
}

Roi roi(const std::string& name, int number) {
    Roi r;
    r.name = name;
    r.number = number;
    return r;
}

void write(const ContourSet& set, const std::string& dir, const char* name) {
    RtStructWriteOptions options;
    // Fixed UIDs keep regenerated seeds byte-stable apart from dates.
    options.frameOfReferenceUid = "1.2.826.0.1.3680043.10.1";
    options.patientStudy.studyInstanceUid = "1.2.826.0.1.3680043.10.2";
    options.patientStudy.patientId = "FUZZ";
    writeRtStruct(set, dir + "/" + name);
}

struct RawContour {
    const char* type;
    std::string data;  // ContourData as written (DS values, backslashes)
};

// A minimal dataset with one ROI per entry of `rois`; a null contour list
// leaves out the ContourSequence.
void writeRaw(const std::string& path, const std::vector<const std::vector<RawContour>*>& rois,
              bool implicitNoMeta) {
    DcmFileFormat file;
    DcmDataset& ds = *file.getDataset();
    ds.putAndInsertString(DCM_SOPClassUID, UID_RTStructureSetStorage);
    ds.putAndInsertString(DCM_SOPInstanceUID, "1.2.826.0.1.3680043.10.3");
    ds.putAndInsertString(DCM_Modality, "RTSTRUCT");
    DcmItem* item = nullptr;
    ds.findOrCreateSequenceItem(DCM_ReferencedFrameOfReferenceSequence, item, -2);
    item->putAndInsertString(DCM_FrameOfReferenceUID, "1.2.826.0.1.3680043.10.1");
    for (std::size_t r = 0; r < rois.size(); ++r) {
        ds.findOrCreateSequenceItem(DCM_StructureSetROISequence, item, -2);
        item->putAndInsertString(DCM_ROINumber, std::to_string(r + 1).c_str());
        item->putAndInsertString(DCM_ROIName, ("ROI" + std::to_string(r + 1)).c_str());
    }
    for (std::size_t r = 0; r < rois.size(); ++r) {
        ds.findOrCreateSequenceItem(DCM_ROIContourSequence, item, -2);
        item->putAndInsertString(DCM_ReferencedROINumber, std::to_string(r + 1).c_str());
        item->putAndInsertString(DCM_ROIDisplayColor, "0\\128\\255");
        if (!rois[r]) continue;
        for (const RawContour& c : *rois[r]) {
            DcmItem* contour = nullptr;
            item->findOrCreateSequenceItem(DCM_ContourSequence, contour, -2);
            contour->putAndInsertString(DCM_ContourGeometricType, c.type);
            std::size_t values = 1;
            for (char ch : c.data) values += ch == '\\';
            contour->putAndInsertString(DCM_NumberOfContourPoints,
                                        std::to_string(values / 3).c_str());
            contour->putAndInsertString(DCM_ContourData, c.data.c_str());
        }
    }
    const OFCondition status =
        implicitNoMeta ? file.saveFile(path.c_str(), EXS_LittleEndianImplicit, EET_UndefinedLength,
                                       EGL_recalcGL, EPD_noChange, 0, 0, EWM_dataset)
                       : file.saveFile(path.c_str(), EXS_LittleEndianExplicit);
    if (status.bad()) throw std::runtime_error(path + ": " + status.text());
}

}  // namespace

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: %s DIR\n", argv[0]);
        return 2;
    }
    const std::string dir = argv[1];

    {  // two ROIs of squares on three axial planes
        ContourSet set;
        Roi a = roi("Squares", 1), b = roi("Other", 2);
        for (int k = 0; k < 3; ++k) {
            a.slices.push_back({2.5 * k, {square(0, 0, 10), square(20, 0, 5)}});
            b.slices.push_back({2.5 * k, {square(-30, -30, 8)}});
        }
        b.colour = Rgb{0, 255, 0};
        set.rois = {a, b};
        write(set, dir, "squares.dcm");
    }
    {  // a ring: outer contour with a clockwise hole, nested
        ContourSet set;
        Roi r = roi("Ring", 3);
        r.slices.push_back({-1.25, {square(0, 0, 20), square(5, 5, 10, true)}});
        r.slices.push_back({0, {square(0, 0, 20), square(5, 5, 10, true), square(8, 8, 4)}});
        set.rois = {r};
        write(set, dir, "ring.dcm");
    }
    {  // a keyhole: the hole joined to the outside by a zero-width channel
        ContourSet set;
        Roi r = roi("Keyhole", 4);
        r.slices.push_back({3,
                            {{{0, 0},
                              {10, 0},
                              {10, 10},
                              {5, 10},
                              {5, 7},
                              {7, 7},
                              {7, 3},
                              {3, 3},
                              {3, 7},
                              {5, 7},
                              {5, 10},
                              {0, 10}}}});
        set.rois = {r};
        write(set, dir, "keyhole.dcm");
    }
    {  // contours of one plane written at z values 1e-4 apart (jitter)
        ContourSet set;
        Roi r = roi("Jitter", 5);
        r.slices.push_back({2.4991, {square(0, 0, 4)}});
        r.slices.push_back({2.4992, {square(10, 0, 4)}});
        r.slices.push_back({4.9993, {square(0, 0, 4)}});
        r.slices.push_back({5.0, {square(10, 0, 4.5)}});
        r.slabThicknessMm = 2.5;
        set.rois = {r};
        write(set, dir, "jitter.dcm");
    }
    {  // a sagittal stack: planes x = const, read back in their own frame
        ContourSet set;
        Roi r = roi("Sagittal", 6);
        r.frame = frameWithNormal({1, 0, 0});
        for (int k = 0; k < 3; ++k) r.slices.push_back({-10.0 + 3 * k, {square(0, 0, 6 + k)}});
        set.rois = {r};
        write(set, dir, "sagittal.dcm");
    }

    // ---- what our writer never writes, with dcmdata directly ----
    const std::vector<RawContour> pointAndOpen = {
        {"POINT", "1\\2\\3"},
        {"OPEN_PLANAR", "0\\0\\3\\5\\0\\3\\5\\5\\3"},
        {"CLOSED_PLANAR", "0\\0\\3\\5\\0\\3\\5\\5\\3\\0\\5\\3"}};
    const std::vector<RawContour> crossingXor = {
        {"CLOSEDPLANAR_XOR", "0\\0\\0\\10\\0\\0\\10\\10\\0\\0\\10\\0"},
        {"CLOSEDPLANAR_XOR", "5\\5\\0\\15\\5\\0\\15\\15\\0\\5\\15\\0"}};
    writeRaw(dir + "/point-open.dcm", {&pointAndOpen}, false);
    writeRaw(dir + "/xor.dcm", {&crossingXor}, false);
    writeRaw(dir + "/no-contour-sequence.dcm", {nullptr, &pointAndOpen}, false);
    writeRaw(dir + "/implicit-no-meta.dcm", {&crossingXor, &pointAndOpen}, true);
    return 0;
}
