// Writing RT Structure Sets with DCMTK's dcmrt IOD class, which checks that
// every required attribute is present and every value fits its VR.
#include <dcmtk/config/osconfig.h>  // first, as DCMTK requires
#include <dcmtk/dcmdata/dctk.h>
#include <dcmtk/dcmrt/drtstrct.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <ctime>
#include <filesystem>
#include <stdexcept>

#include "io/dicom/DicomAttributes.hpp"
#include "io/dicom/DicomNesting.hpp"
#include "io/dicom/RtStruct.hpp"
#include "io/files/AtomicWrite.hpp"
#include "io/files/InputsInUse.hpp"
#include "io/images/Colours.hpp"

namespace dfrecon {

std::vector<Rgb> displayColours(const ContourSet& set) {
    std::vector<Rgb> used;
    for (const Roi& roi : set.rois)
        if (roi.colour) used.push_back(*roi.colour);
    auto isUsed = [&](const Rgb& c) {
        return std::find(used.begin(), used.end(), c) != used.end();
    };
    std::vector<Rgb> colours;
    std::size_t nextDefault = 0;
    std::int64_t nextCategorical = 0;
    for (const Roi& roi : set.rois) {
        if (roi.colour) {
            colours.push_back(*roi.colour);
            continue;
        }
        while (nextDefault < kDefaultRoiColours.size() && isUsed(kDefaultRoiColours[nextDefault]))
            ++nextDefault;
        Rgb colour;
        if (nextDefault < kDefaultRoiColours.size()) {
            colour = kDefaultRoiColours[nextDefault++];
        } else {
            // 2^24 colours: an unused one comes within as many tries as
            // there are ROIs.
            do colour = categoricalColour(nextCategorical++);
            while (isUsed(colour));
        }
        used.push_back(colour);
        colours.push_back(colour);
    }
    return colours;
}

bool isRoiInterpretedType(const std::string& type) {
    return std::any_of(kRoiInterpretedTypes.begin(), kRoiInterpretedTypes.end(),
                       [&](const char* defined) { return type == defined; });
}

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

// A text value for a setter called without DCMTK's check, which takes every
// non-ASCII byte for an error although the file says UTF-8.
OFString text(const std::string& value, const char* what) {
    if (!isValidDicomText(value))
        throw std::runtime_error(std::string("cannot write RTSTRUCT: ") + what + " '" + value +
                                 "' holds control characters, a backslash or malformed UTF-8");
    return value.c_str();
}

// Contour points in patient coordinates, and those as ContourData.
std::vector<Vec3> patientPoints(const Polygon& polygon, double zMm, const PlaneFrame& frame) {
    std::vector<Vec3> points;
    points.reserve(polygon.size());
    for (const Point2& p : polygon)
        points.push_back(frame.toPatient({p.x, p.y, zMm}));  // exact for the identity
    return points;
}

std::string contourData(const std::vector<Vec3>& points) {
    std::string data;
    data.reserve(points.size() * 3 * 12);
    for (const Vec3& p : points)
        for (int a = 0; a < 3; ++a) {
            if (!data.empty()) data += '\\';
            data += formatDecimalString(p[a]);
        }
    return data;
}

std::string colourText(const Rgb& colour) {
    return std::to_string(colour[0]) + "\\" + std::to_string(colour[1]) + "\\" +
           std::to_string(colour[2]);
}

template <class Sequence>
void addImageReference(Sequence& sequence, const DicomImage& image) {
    typename Sequence::Item* reference = nullptr;
    check(sequence.addItem(reference), "ContourImageSequence");
    check(reference->setReferencedSOPClassUID(image.sopClassUid.c_str()), "ReferencedSOPClassUID");
    check(reference->setReferencedSOPInstanceUID(image.sopInstanceUid.c_str()),
          "ReferencedSOPInstanceUID");
}

// Planes whose normals differ by more than this (about 0.08 degrees) are
// not parallel: a contour that spans a few centimetres already leaves its
// image's plane by more than the 0.01 mm that finds it.
constexpr double kParallelCosine = 1 - 1e-6;

struct RoiToWrite {
    const Roi& roi;
    int number;
    Rgb colour;
    std::string type;
};

// The longest value explicit VR little endian gives DS (a 16-bit length,
// even).
constexpr std::size_t kExplicitValueBytes = 65534;

void addRoi(DRTStructureSetIOD& rt, const RoiToWrite& what, const std::string& frameUid,
            const DicomImageSeries* series, RtStructWriteSummary& summary) {
    const Roi& roi = what.roi;
    const OFString numberText = std::to_string(what.number).c_str();
    DRTStructureSetROISequence::Item* info = nullptr;
    check(rt.getStructureSetROISequence().addItem(info), "StructureSetROISequence");
    check(info->setROINumber(numberText), "ROINumber");
    check(info->setReferencedFrameOfReferenceUID(frameUid.c_str()),
          "ReferencedFrameOfReferenceUID");
    check(info->setROIName(text(roi.name, "ROIName"), OFFalse), "ROIName");
    check(info->setROIGenerationAlgorithm("SEMIAUTOMATIC"), "ROIGenerationAlgorithm");

    DRTROIContourSequence::Item* item = nullptr;
    check(rt.getROIContourSequence().addItem(item), "ROIContourSequence");
    check(item->setReferencedROINumber(numberText), "ReferencedROINumber");
    check(item->setROIDisplayColor(colourText(what.colour).c_str()), "ROIDisplayColor");
    const std::string label = "ROI " + std::to_string(what.number) + " '" + roi.name + "'";
    const bool parallel = series && roi.contourCount() > 0 &&
                          std::abs(dot(roi.frame.n, series->normal)) >= kParallelCosine;
    if (series && roi.contourCount() > 0 && !parallel)
        summary.warnings.push_back(label + " lies in " + roi.frame.orientationName() +
                                   " planes, not parallel to the images' planes: its contours "
                                   "refer to no image");
    std::size_t offImages = 0;
    int contourNumber = 0;
    for (const Slice& slice : roi.slices)
        for (const Polygon& polygon : slice.contours) {
            DRTContourSequence::Item* contour = nullptr;
            check(item->getContourSequence().addItem(contour), "ContourSequence");
            check(contour->setContourNumber(std::to_string(++contourNumber).c_str()),
                  "ContourNumber");
            const std::vector<Vec3> points = patientPoints(polygon, slice.zMm, roi.frame);
            if (series) {
                const DicomImage* image =
                    parallel ? imageHolding(*series, points, kSamePlaneToleranceMm) : nullptr;
                if (image)
                    addImageReference(contour->getContourImageSequence(), *image);
                else
                    ++offImages;
            }
            check(contour->setContourGeometricType("CLOSED_PLANAR"), "ContourGeometricType");
            check(contour->setNumberOfContourPoints(std::to_string(polygon.size()).c_str()),
                  "NumberOfContourPoints");
            // The value is checked below by the IOD's write; checking here
            // would scan every number twice.
            const std::string data = contourData(points);
            summary.longestValueBytes = std::max(summary.longestValueBytes, data.size());
            check(contour->setContourData(data.c_str(), OFFalse), "ContourData");
            if (roi.slabThicknessMm > 0)
                check(contour->setContourSlabThickness(
                          formatDecimalString(roi.slabThicknessMm).c_str()),
                      "ContourSlabThickness");
        }
    summary.contours += std::size_t(contourNumber);
    if (series) {
        summary.contoursOffImages += offImages;
        summary.contoursOnImages += std::size_t(contourNumber) - offImages;
        if (parallel && offImages > 0)
            summary.warnings.push_back(
                label + ": " + std::to_string(offImages) + " of " + std::to_string(contourNumber) +
                " contours lie in no image's plane (within " +
                formatDecimalString(kSamePlaneToleranceMm) + " mm) and refer to no image");
    }

    DRTRTROIObservationsSequence::Item* observation = nullptr;
    check(rt.getRTROIObservationsSequence().addItem(observation), "RTROIObservationsSequence");
    check(observation->setObservationNumber(numberText), "ObservationNumber");
    check(observation->setReferencedROINumber(numberText), "ReferencedROINumber");
    check(observation->setRTROIInterpretedType(what.type.c_str()), "RTROIInterpretedType");
    check(observation->setROIInterpreter(""), "ROIInterpreter");
}

// The series in the Referenced Frame of Reference Sequence: every image,
// whether a contour lies on it or not, as planning systems list them.
void addReferencedSeries(DRTReferencedFrameOfReferenceSequence::Item& frame,
                         const std::string& studyUid, const DicomImageSeries& series) {
    DRTRTReferencedStudySequence::Item* study = nullptr;
    check(frame.getRTReferencedStudySequence().addItem(study), "RTReferencedStudySequence");
    // Detached Study Management SOP Class (retired, but what RT Referenced
    // Study Sequence items name by convention: the study has no SOP instance).
    check(study->setReferencedSOPClassUID("1.2.840.10008.3.1.2.3.1"), "ReferencedSOPClassUID");
    check(study->setReferencedSOPInstanceUID(studyUid.c_str()), "ReferencedSOPInstanceUID");
    DRTRTReferencedSeriesSequence::Item* referenced = nullptr;
    check(study->getRTReferencedSeriesSequence().addItem(referenced), "RTReferencedSeriesSequence");
    check(referenced->setSeriesInstanceUID(series.seriesInstanceUid.c_str()), "SeriesInstanceUID");
    for (const DicomImage& image : series.images)
        addImageReference(referenced->getContourImageSequence(), image);
}

// The first RT Referenced Series of an RTSTRUCT's frame of reference item:
// its SeriesInstanceUID and the SOP class and instance UIDs of its Contour
// Image Sequence; none where the file names no series.
std::optional<DicomImageSeries> referencedSeriesOf(DcmItem& frame) {
    DcmItem* study = nullptr;
    DcmItem* series = nullptr;
    if (frame.findAndGetSequenceItem(DCM_RTReferencedStudySequence, study, 0).bad() ||
        study->findAndGetSequenceItem(DCM_RTReferencedSeriesSequence, series, 0).bad())
        return std::nullopt;
    DicomImageSeries referenced;
    referenced.seriesInstanceUid = dicomText(*series, DCM_SeriesInstanceUID);
    if (referenced.seriesInstanceUid.empty()) return std::nullopt;
    DcmSequenceOfItems* images = nullptr;
    if (series->findAndGetSequence(DCM_ContourImageSequence, images).good() && images)
        for (unsigned long i = 0; i < images->card(); ++i) {
            DicomImage image;
            image.sopClassUid = dicomText(*images->getItem(i), DCM_ReferencedSOPClassUID);
            image.sopInstanceUid = dicomText(*images->getItem(i), DCM_ReferencedSOPInstanceUID);
            if (!image.sopClassUid.empty() && !image.sopInstanceUid.empty())
                referenced.images.push_back(std::move(image));
        }
    return referenced;
}

}  // namespace

RtStructWriteOptions referenceFrom(const std::string& dicomPath) {
    std::error_code error;
    RtStructWriteOptions options;
    if (!std::filesystem::is_directory(dicomPath, error)) {
        const ReadingInput reading(dicomPath);
        silenceDcmtkLog();
        checkDicomNesting(dicomPath, kMaxDicomNestingDepth);
        DcmFileFormat file;
        // Only the header matters: nothing past the pixel data is read.
        const OFCondition status = file.loadFileUntilTag(
            dicomPath.c_str(), EXS_Unknown, EGL_noChange, 4096, ERM_autoDetect, DCM_PixelData);
        if (status.bad())
            throw InputError(dicomPath, 0,
                             std::string("not a readable DICOM file (") + status.text() + ")");
        DcmDataset& data = *file.getDataset();
        if (!data.tagExists(DCM_ImagePositionPatient)) {
            if (const std::string problem = convertDicomTextToUtf8(data); !problem.empty())
                throw InputError(dicomPath, 0, problem);
            options.patientStudy = dicomPatientStudy(data);
            options.frameOfReferenceUid = dicomText(data, DCM_FrameOfReferenceUID);
            DcmItem* frame = nullptr;
            if (data.findAndGetSequenceItem(DCM_ReferencedFrameOfReferenceSequence, frame, 0).bad())
                frame = nullptr;
            if (options.frameOfReferenceUid.empty() && frame)
                options.frameOfReferenceUid = dicomText(*frame, DCM_FrameOfReferenceUID);
            if (options.frameOfReferenceUid.empty())
                throw InputError(dicomPath, 0,
                                 "no " + dicomTagName(DCM_FrameOfReferenceUID) + " to refer to");
            if (options.patientStudy.studyInstanceUid.empty())
                throw InputError(dicomPath, 0,
                                 "no " + dicomTagName(DCM_StudyInstanceUID) + " to refer to");
            if (frame) options.referencedSeries = referencedSeriesOf(*frame);
            return options;
        }
    }
    DicomImageSeries series = readDicomImageSeries(dicomPath);
    options.patientStudy = series.patientStudy;
    options.frameOfReferenceUid = series.frameOfReferenceUid;
    options.imageSeries = std::move(series);
    return options;
}

RtStructWriteSummary writeRtStruct(const ContourSet& contours, const std::string& path,
                                   const RtStructWriteOptions& options) {
    if (!isRoiInterpretedType(options.defaultRoiType))
        throw std::invalid_argument("'" + options.defaultRoiType +
                                    "' is not a DICOM RT ROI Interpreted Type");
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
    const DicomPatientStudy& ps = options.patientStudy;
    // A study of its own is made now; an existing one keeps its attributes.
    const bool ownStudy = ps.studyInstanceUid.empty();
    const std::string studyUid = ownStudy ? newUid() : ps.studyInstanceUid;

    DRTStructureSetIOD rt;
    check(rt.setSpecificCharacterSet("ISO_IR 192"), "SpecificCharacterSet");  // UTF-8 names
    check(rt.setSOPClassUID(UID_RTStructureSetStorage), "SOPClassUID");
    check(rt.setSOPInstanceUID(newUid().c_str()), "SOPInstanceUID");
    check(rt.setInstanceCreationDate(date), "InstanceCreationDate");
    check(rt.setPatientName(text(ps.patientName, "PatientName"), OFFalse), "PatientName");
    check(rt.setPatientID(text(ps.patientId, "PatientID"), OFFalse), "PatientID");
    check(rt.setPatientBirthDate(ps.patientBirthDate.c_str()), "PatientBirthDate");
    check(rt.setPatientSex(ps.patientSex.c_str()), "PatientSex");
    check(rt.setStudyInstanceUID(studyUid.c_str()), "StudyInstanceUID");
    check(rt.setStudyDate(ownStudy ? date : ps.studyDate.c_str()), "StudyDate");
    check(rt.setStudyTime(ownStudy ? time : ps.studyTime.c_str()), "StudyTime");
    check(rt.setStudyID(text(ps.studyId, "StudyID"), OFFalse), "StudyID");
    check(rt.setAccessionNumber(text(ps.accessionNumber, "AccessionNumber"), OFFalse),
          "AccessionNumber");
    check(rt.setReferringPhysicianName(text(ps.referringPhysicianName, "ReferringPhysicianName"),
                                       OFFalse),
          "ReferringPhysicianName");
    if (!ps.studyDescription.empty())
        check(rt.setStudyDescription(text(ps.studyDescription, "StudyDescription"), OFFalse),
              "StudyDescription");
    check(rt.setModality("RTSTRUCT"), "Modality");
    // The Frame of Reference module is part of the RTSTRUCT IOD since 2019
    // (dciodvfy asks for it); the UID is the one the contours refer to.
    check(rt.setFrameOfReferenceUID(frameUid.c_str()), "FrameOfReferenceUID");
    check(rt.setPositionReferenceIndicator(""), "PositionReferenceIndicator");
    check(rt.setSeriesInstanceUID(newUid().c_str()), "SeriesInstanceUID");
    check(rt.setSeriesNumber("1"), "SeriesNumber");
    check(rt.setSeriesDescription(text(options.seriesDescription, "SeriesDescription"), OFFalse),
          "SeriesDescription");
    check(rt.setManufacturer("dfrecon"), "Manufacturer");
    check(rt.setStructureSetLabel(text(options.structureSetLabel, "StructureSetLabel"), OFFalse),
          "StructureSetLabel");
    check(rt.setStructureSetDate(date), "StructureSetDate");
    check(rt.setStructureSetTime(time), "StructureSetTime");
    DRTReferencedFrameOfReferenceSequence::Item* frame = nullptr;
    check(rt.getReferencedFrameOfReferenceSequence().addItem(frame),
          "ReferencedFrameOfReferenceSequence");
    check(frame->setFrameOfReferenceUID(frameUid.c_str()), "FrameOfReferenceUID");
    const DicomImageSeries* series = options.imageSeries ? &*options.imageSeries : nullptr;
    if (series)
        addReferencedSeries(*frame, studyUid, *series);
    else if (options.referencedSeries)
        addReferencedSeries(*frame, studyUid, *options.referencedSeries);

    RtStructWriteSummary summary;
    const std::vector<Rgb> colours = displayColours(contours);
    for (std::size_t i = 0; i < contours.rois.size(); ++i) {
        const Roi& roi = contours.rois[i];
        const RoiToWrite what{
            roi, roi.number.value_or(int(i) + 1), colours[i],
            roi.interpretedType.empty() ? options.defaultRoiType : roi.interpretedType};
        addRoi(rt, what, frameUid, series, summary);
    }
    summary.rois = contours.rois.size();

    DcmFileFormat file;
    check(rt.write(*file.getDataset()), "dataset");
    writeAtomically(path, [&](const std::string& temp) {
        // Explicit VR gives a DS value a 16-bit length; a contour of more
        // than about 1 300 points is longer, and DCMTK would write it as UN,
        // which readers refuse. Implicit VR (32-bit lengths, the transfer
        // syntax every reader must accept) holds it as DS.
        const E_TransferSyntax syntax = summary.longestValueBytes > kExplicitValueBytes
                                            ? EXS_LittleEndianImplicit
                                            : EXS_LittleEndianExplicit;
        check(file.saveFile(temp.c_str(), syntax), path.c_str());
        return true;
    });
    return summary;
}

}  // namespace dfrecon
