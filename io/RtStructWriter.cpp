// Writing RT Structure Sets with DCMTK's dcmrt IOD class, which checks that
// every required attribute is present and every value fits its VR.
#include <dcmtk/config/osconfig.h>  // first, as DCMTK requires
#include <dcmtk/dcmdata/dctk.h>
#include <dcmtk/dcmrt/drtstrct.h>

#include <charconv>
#include <ctime>
#include <stdexcept>

#include "io/AtomicWrite.hpp"
#include "io/DicomNesting.hpp"
#include "io/InputsInUse.hpp"
#include "io/RtStruct.hpp"

namespace dfrecon {

void silenceDcmtkLog();  // RtStructReader.cpp

std::string formatDecimalString(double value) {
    if (value == 0) return "0";  // also turns -0 into 0
    char buffer[64];
    auto written = std::to_chars(buffer, buffer + sizeof buffer, value);
    if (written.ptr - buffer <= 16) return std::string(buffer, written.ptr);
    for (int precision = 15; precision > 0; --precision) {
        written = std::to_chars(buffer, buffer + sizeof buffer, value, std::chars_format::general,
                                precision);
        if (written.ptr - buffer <= 16) return std::string(buffer, written.ptr);
    }
    throw std::invalid_argument("cannot write " + std::to_string(value) + " as a DICOM DS value");
}

namespace {

std::string newUid() {
    char uid[100];
    return dcmGenerateUniqueIdentifier(uid, SITE_INSTANCE_UID_ROOT);
}

void check(const OFCondition& status, const char* what) {
    if (status.bad())
        throw std::runtime_error(std::string("cannot write RTSTRUCT: ") + what + ": " +
                                 status.text());
}

std::string contourData(const Polygon& polygon, double zMm, const PlaneFrame& frame) {
    std::string data;
    data.reserve(polygon.size() * 3 * 12);
    for (const Point2& p : polygon) {
        const Vec3 patient = frame.toPatient({p.x, p.y, zMm});  // exact for the identity
        for (int a = 0; a < 3; ++a) {
            if (!data.empty()) data += '\\';
            data += formatDecimalString(patient[a]);
        }
    }
    return data;
}

void addRoi(DRTStructureSetIOD& rt, const Roi& roi, int number, const std::string& frameUid) {
    const OFString numberText = std::to_string(number).c_str();
    DRTStructureSetROISequence::Item* info = nullptr;
    check(rt.getStructureSetROISequence().addItem(info), "StructureSetROISequence");
    check(info->setROINumber(numberText), "ROINumber");
    check(info->setReferencedFrameOfReferenceUID(frameUid.c_str()),
          "ReferencedFrameOfReferenceUID");
    check(info->setROIName(roi.name.c_str()), "ROIName");
    check(info->setROIGenerationAlgorithm("SEMIAUTOMATIC"), "ROIGenerationAlgorithm");

    DRTROIContourSequence::Item* item = nullptr;
    check(rt.getROIContourSequence().addItem(item), "ROIContourSequence");
    check(item->setReferencedROINumber(numberText), "ReferencedROINumber");
    const Rgb colour = roi.colour.value_or(Rgb{255, 0, 0});
    check(item->setROIDisplayColor((std::to_string(colour[0]) + "\\" + std::to_string(colour[1]) +
                                    "\\" + std::to_string(colour[2]))
                                       .c_str()),
          "ROIDisplayColor");
    int contourNumber = 0;
    for (const Slice& slice : roi.slices)
        for (const Polygon& polygon : slice.contours) {
            DRTContourSequence::Item* contour = nullptr;
            check(item->getContourSequence().addItem(contour), "ContourSequence");
            check(contour->setContourNumber(std::to_string(++contourNumber).c_str()),
                  "ContourNumber");
            check(contour->setContourGeometricType("CLOSED_PLANAR"), "ContourGeometricType");
            check(contour->setNumberOfContourPoints(std::to_string(polygon.size()).c_str()),
                  "NumberOfContourPoints");
            // The value is checked below by the IOD's write; checking here
            // would scan every number twice.
            check(contour->setContourData(contourData(polygon, slice.zMm, roi.frame).c_str(),
                                          OFFalse),
                  "ContourData");
            if (roi.slabThicknessMm > 0)
                check(contour->setContourSlabThickness(
                          formatDecimalString(roi.slabThicknessMm).c_str()),
                      "ContourSlabThickness");
        }

    DRTRTROIObservationsSequence::Item* observation = nullptr;
    check(rt.getRTROIObservationsSequence().addItem(observation), "RTROIObservationsSequence");
    check(observation->setObservationNumber(numberText), "ObservationNumber");
    check(observation->setReferencedROINumber(numberText), "ReferencedROINumber");
    check(observation->setRTROIInterpretedType(""), "RTROIInterpretedType");
    check(observation->setROIInterpreter(""), "ROIInterpreter");
}

}  // namespace

RtStructWriteOptions referenceFrom(const std::string& dicomPath) {
    const ReadingInput reading(dicomPath);
    silenceDcmtkLog();
    checkDicomNesting(dicomPath, kMaxDicomNestingDepth);
    DcmFileFormat file;
    const OFCondition status = file.loadFile(dicomPath.c_str());
    if (status.bad())
        throw InputError(dicomPath, 0,
                         std::string("not a readable DICOM file (") + status.text() + ")");
    DcmDataset& data = *file.getDataset();
    auto text = [](DcmItem& item, const DcmTagKey& key) {
        OFString value;
        return item.findAndGetOFStringArray(key, value).good() ? std::string(value.c_str()) : "";
    };
    RtStructWriteOptions options;
    options.patientName = text(data, DCM_PatientName);
    options.patientId = text(data, DCM_PatientID);
    options.studyInstanceUid = text(data, DCM_StudyInstanceUID);
    options.frameOfReferenceUid = text(data, DCM_FrameOfReferenceUID);  // images
    DcmItem* frame = nullptr;
    if (options.frameOfReferenceUid.empty() &&
        data.findAndGetSequenceItem(DCM_ReferencedFrameOfReferenceSequence, frame, 0).good())
        options.frameOfReferenceUid = text(*frame, DCM_FrameOfReferenceUID);  // structure sets
    if (options.frameOfReferenceUid.empty())
        throw InputError(dicomPath, 0, "no (0020,0052) FrameOfReferenceUID to refer to");
    if (options.studyInstanceUid.empty())
        throw InputError(dicomPath, 0, "no (0020,000D) StudyInstanceUID to refer to");
    return options;
}

void writeRtStruct(const ContourSet& contours, const std::string& path,
                   const RtStructWriteOptions& options) {
    // The IOD requires at least one StructureSetROISequence item; say so
    // rather than let DCMTK's check fail with "Invalid Value" (found by
    // fuzzing: a file with an empty sequence reads as no ROIs).
    if (contours.rois.empty())
        throw std::runtime_error("cannot write RTSTRUCT " + path +
                                 ": no ROIs (an RT Structure Set needs at least one)");
    silenceDcmtkLog();
    char date[16], time[16];
    const std::time_t now = std::time(nullptr);
    std::tm local{};
    localtime_r(&now, &local);
    std::strftime(date, sizeof date, "%Y%m%d", &local);
    std::strftime(time, sizeof time, "%H%M%S", &local);
    const std::string frameUid =
        options.frameOfReferenceUid.empty() ? newUid() : options.frameOfReferenceUid;

    DRTStructureSetIOD rt;
    check(rt.setSpecificCharacterSet("ISO_IR 192"), "SpecificCharacterSet");  // UTF-8 names
    check(rt.setSOPClassUID(UID_RTStructureSetStorage), "SOPClassUID");
    check(rt.setSOPInstanceUID(newUid().c_str()), "SOPInstanceUID");
    check(rt.setInstanceCreationDate(date), "InstanceCreationDate");
    check(rt.setPatientName(options.patientName.c_str()), "PatientName");
    check(rt.setPatientID(options.patientId.c_str()), "PatientID");
    check(rt.setStudyInstanceUID(
              (options.studyInstanceUid.empty() ? newUid() : options.studyInstanceUid).c_str()),
          "StudyInstanceUID");
    check(rt.setStudyDate(date), "StudyDate");
    check(rt.setStudyTime(time), "StudyTime");
    check(rt.setStudyID(""), "StudyID");
    check(rt.setModality("RTSTRUCT"), "Modality");
    // The Frame of Reference module is part of the RTSTRUCT IOD since 2019
    // (dciodvfy asks for it); the UID is the one the contours refer to.
    check(rt.setFrameOfReferenceUID(frameUid.c_str()), "FrameOfReferenceUID");
    check(rt.setPositionReferenceIndicator(""), "PositionReferenceIndicator");
    check(rt.setSeriesInstanceUID(newUid().c_str()), "SeriesInstanceUID");
    check(rt.setSeriesNumber("1"), "SeriesNumber");
    check(rt.setSeriesDescription(options.seriesDescription.c_str()), "SeriesDescription");
    check(rt.setManufacturer("dfrecon"), "Manufacturer");
    check(rt.setStructureSetLabel(options.structureSetLabel.c_str()), "StructureSetLabel");
    check(rt.setStructureSetDate(date), "StructureSetDate");
    check(rt.setStructureSetTime(time), "StructureSetTime");
    DRTReferencedFrameOfReferenceSequence::Item* frame = nullptr;
    check(rt.getReferencedFrameOfReferenceSequence().addItem(frame),
          "ReferencedFrameOfReferenceSequence");
    check(frame->setFrameOfReferenceUID(frameUid.c_str()), "FrameOfReferenceUID");

    for (std::size_t i = 0; i < contours.rois.size(); ++i) {
        const Roi& roi = contours.rois[i];
        addRoi(rt, roi, roi.number.value_or(int(i) + 1), frameUid);
    }

    DcmFileFormat file;
    check(rt.write(*file.getDataset()), "dataset");
    writeAtomically(path, [&](const std::string& temp) {
        check(file.saveFile(temp.c_str(), EXS_LittleEndianExplicit), path.c_str());
        return true;
    });
}

}  // namespace dfrecon
