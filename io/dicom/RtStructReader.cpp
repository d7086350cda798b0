// Reading RT Structure Sets with DCMTK's dcmdata: every attribute is looked up
// by tag so that a message can name the one that is wrong.
#include <dcmtk/config/osconfig.h>  // first, as DCMTK requires
#include <dcmtk/dcmdata/dctk.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>

#include "geometry/ContourValidation.hpp"
#include "geometry/PlaneReading.hpp"
#include "geometry/PolygonXor.hpp"
#include "io/dicom/DicomAttributes.hpp"
#include "io/dicom/DicomNesting.hpp"
#include "io/dicom/RtStruct.hpp"
#include "io/files/FileNames.hpp"
#include "io/files/InputsInUse.hpp"
#include "io/files/RegularFile.hpp"
#include "io/files/TextEncoding.hpp"

namespace dfrecon {

const char* holeConventionName(HoleConvention convention) {
    for (const auto& [name, value] : kHoleConventionNames)
        if (value == convention) return name;
    return "?";
}

namespace {

std::string tagName(const DcmTagKey& key) {
    return dicomTagName(key);
}

// One closed contour as read, in patient coordinates.
struct RtStructContour {
    std::vector<Vec3> points;
    std::size_t item = 0;  // 1-based position in its ContourSequence
    bool xorType = false;
    double planeZ = 0;  // along the ROI's normal, once the frame is known
};

class Reader {
  public:
    Reader(std::string path, const RtStructLimits& limits)
        : file_(std::move(path)), limits_(limits) {}

    RtStructLoad run() {
        silenceDcmtkLog();
        checkRegularFile(file_, limits_.maxFileBytes, "an RTSTRUCT file");
        checkDicomNesting(file_, limits_.maxNestingDepth);
        DcmFileFormat fileFormat;
        const OFCondition status = fileFormat.loadFile(file_.c_str(), EXS_Unknown, EGL_noChange,
                                                       DCM_MaxReadLength, ERM_autoDetect);
        if (status.bad()) fail("not a readable DICOM file (" + std::string(status.text()) + ")");
        DcmDataset& data = *fileFormat.getDataset();
        // Names are written back as UTF-8 (ISO_IR 192): read them as such.
        if (const std::string problem = convertDicomTextToUtf8(data); !problem.empty())
            warn(problem + "; names are read as stored");
        checkModality(data);
        readIdentity(data);
        readRoiList(data);
        readRoiContours(data);
        readRoiObservations(data);
        // A structure whose contours cannot be made valid (a loop crossing
        // itself, planes that are not planes) is that structure's problem:
        // it is kept with its defect and no slices, the others load.
        for (std::size_t r = 0; r < out_.contours.rois.size(); ++r) {
            try {
                buildSlices(r);
            } catch (const InputError& e) {
                Roi& roi = out_.contours.rois[r];
                roi.slices.clear();
                roi.defect = e;
            }
        }
        return std::move(out_);
    }

  private:
    [[noreturn]] void fail(const std::string& problem) const {
        throw InputError(file_, 0, problem);
    }
    void warn(const std::string& message) {
        out_.warnings.push_back({file_, 0, message, about_ ? out_.rois[*about_].name : ""});
    }

    // While one ROI's items are read its warnings carry its name
    // (InputWarning::roi), so a command on one ROI shows only its own.
    std::optional<std::size_t> about_;
    struct About {
        std::optional<std::size_t>& slot;
        About(std::optional<std::size_t>& s, std::size_t r) : slot(s) { slot = r; }
        ~About() { slot.reset(); }
        About(const About&) = delete;
        About& operator=(const About&) = delete;
    };

    std::string roiLabel(std::size_t r) const {
        return "ROI " + std::to_string(out_.rois[r].number) + " '" + out_.rois[r].name + "'";
    }

    static std::string text(DcmItem& item, const DcmTagKey& key) { return dicomText(item, key); }

    void checkModality(DcmDataset& data) {
        const std::string sopClass = text(data, DCM_SOPClassUID);
        const std::string modality = text(data, DCM_Modality);
        if (!sopClass.empty() && sopClass != UID_RTStructureSetStorage)
            fail(tagName(DCM_SOPClassUID) + " is " +
                 dcmFindNameOfUID(sopClass.c_str(), sopClass.c_str()) +
                 ", not RT Structure Set Storage");
        if (!modality.empty() && modality != "RTSTRUCT")
            fail(tagName(DCM_Modality) + " is '" + modality + "', not RTSTRUCT");
        if (sopClass.empty() && modality.empty())
            warn("no " + tagName(DCM_SOPClassUID) + " or " + tagName(DCM_Modality) +
                 "; read as an RT Structure Set");
    }

    void readIdentity(DcmDataset& data) {
        out_.studyInstanceUid = text(data, DCM_StudyInstanceUID);
        out_.seriesInstanceUid = text(data, DCM_SeriesInstanceUID);
        out_.patientId = text(data, DCM_PatientID);
        out_.patientName = text(data, DCM_PatientName);
        DcmItem* frame = nullptr;
        if (data.findAndGetSequenceItem(DCM_ReferencedFrameOfReferenceSequence, frame, 0).good())
            out_.frameOfReferenceUid = text(*frame, DCM_FrameOfReferenceUID);
    }

    void readRoiList(DcmDataset& data) {
        DcmSequenceOfItems* list = nullptr;
        if (data.findAndGetSequence(DCM_StructureSetROISequence, list).bad() || !list)
            fail("missing " + tagName(DCM_StructureSetROISequence));
        if (list->card() > limits_.maxRois)
            fail(tagName(DCM_StructureSetROISequence) + " has " + std::to_string(list->card()) +
                 " items, over the limit of " + std::to_string(limits_.maxRois));
        for (unsigned long i = 0; i < list->card(); ++i) {
            DcmItem& item = *list->getItem(i);
            const std::string where =
                tagName(DCM_StructureSetROISequence) + " item " + std::to_string(i + 1);
            Sint32 number = 0;
            if (item.findAndGetSint32(DCM_ROINumber, number).bad())
                fail(where + ": missing or invalid " + tagName(DCM_ROINumber));
            if (indexOfNumber_.count(number))
                fail(where + ": " + tagName(DCM_ROINumber) + " " + std::to_string(number) +
                     " is used twice");
            indexOfNumber_[number] = out_.rois.size();
            RtStructRoiInfo info;
            info.number = number;
            info.name = validRoiName(text(item, DCM_ROIName), where);
            if (info.name.empty()) {
                info.name = "ROI " + std::to_string(number);
                warn(where + ": no " + tagName(DCM_ROIName) + "; called '" + info.name + "'");
            }
            Roi roi;
            roi.name = info.name;
            roi.number = number;
            out_.rois.push_back(info);
            out_.contours.rois.push_back(std::move(roi));
            contours_.emplace_back();
        }
        if (out_.rois.empty()) warn(tagName(DCM_StructureSetROISequence) + " is empty: no ROIs");
    }

    // The writer, like any DICOM consumer, accepts only valid LO values (no
    // control characters or backslashes; DCMTK does not check the 64
    // character limit), so a name that is not one is mended here, with a
    // warning, rather than make every file read from it unwritable (found by
    // fuzzing: a control character in ROIName made writeRtStruct throw).
    // Names are UTF-8 by now, which DCMTK's checker does not know
    // (isValidDicomText).
    std::string validRoiName(std::string name, const std::string& where) {
        // Latin-1 written without a SpecificCharacterSet, as older planning
        // systems do: read as Windows-1252 rather than mended into '_'.
        name = utf8FromLegacyText(name);
        if (name.size() > kMaxRoiNameBytes) {
            std::size_t cut = kMaxRoiNameBytes;  // at a character's start
            while (cut > 0 && (static_cast<unsigned char>(name[cut]) & 0xC0) == 0x80) --cut;
            warn(where + ": " + tagName(DCM_ROIName) + " of " + std::to_string(name.size()) +
                 " bytes cut to " + std::to_string(cut) + ", the most a name may have");
            name.resize(cut);
        }
        if (isValidDicomText(name)) return name;
        name = mendedDicomText(std::move(name));
        warn(where + ": " + tagName(DCM_ROIName) +
             " is not a valid LO value (control characters, backslashes or malformed UTF-8); "
             "read as '" +
             name + "'");
        return name;
    }

    void readRoiContours(DcmDataset& data) {
        DcmSequenceOfItems* list = nullptr;
        if (data.findAndGetSequence(DCM_ROIContourSequence, list).bad() || !list) {
            if (!out_.rois.empty())
                warn("no " + tagName(DCM_ROIContourSequence) + ": every ROI is empty");
            return;
        }
        for (unsigned long i = 0; i < list->card(); ++i) {
            DcmItem& item = *list->getItem(i);
            const std::string where =
                tagName(DCM_ROIContourSequence) + " item " + std::to_string(i + 1);
            Sint32 number = 0;
            if (item.findAndGetSint32(DCM_ReferencedROINumber, number).bad())
                fail(where + ": missing or invalid " + tagName(DCM_ReferencedROINumber));
            const auto found = indexOfNumber_.find(number);
            if (found == indexOfNumber_.end()) {
                warn(where + ": " + tagName(DCM_ReferencedROINumber) + " " +
                     std::to_string(number) + " names no ROI of " +
                     tagName(DCM_StructureSetROISequence) + "; ignored");
                continue;
            }
            readRoiColour(item, found->second, where);
            DcmSequenceOfItems* contours = nullptr;
            if (item.findAndGetSequence(DCM_ContourSequence, contours).good() && contours)
                readContours(*contours, found->second, where);
        }
    }

    // RTROIInterpretedType is the one observation kept: writing the set
    // again must not turn a PTV into an ORGAN. Values that are not valid CS
    // (the writer could not write them) are dropped with a warning.
    void readRoiObservations(DcmDataset& data) {
        DcmSequenceOfItems* list = nullptr;
        if (data.findAndGetSequence(DCM_RTROIObservationsSequence, list).bad() || !list) return;
        for (unsigned long i = 0; i < list->card(); ++i) {
            DcmItem& item = *list->getItem(i);
            const std::string where =
                tagName(DCM_RTROIObservationsSequence) + " item " + std::to_string(i + 1);
            Sint32 number = 0;
            const std::string type = text(item, DCM_RTROIInterpretedType);
            if (type.empty() || item.findAndGetSint32(DCM_ReferencedROINumber, number).bad())
                continue;
            const auto found = indexOfNumber_.find(number);
            if (found == indexOfNumber_.end()) continue;
            if (DcmCodeString::checkStringValue(type.c_str(), "1").bad()) {
                warn(where + ": " + tagName(DCM_RTROIInterpretedType) +
                     " is not a valid CS value; ignored");
                continue;
            }
            out_.contours.rois[found->second].interpretedType = type;
        }
    }

    void readRoiColour(DcmItem& item, std::size_t r, const std::string& where) {
        Sint32 rgb[3];
        for (unsigned long c = 0; c < 3; ++c)
            if (item.findAndGetSint32(DCM_ROIDisplayColor, rgb[c], c).bad()) return;
        for (Sint32 v : rgb)
            if (v < 0 || v > 255) {
                warn(where + ": " + tagName(DCM_ROIDisplayColor) + " outside 0..255; ignored");
                return;
            }
        out_.contours.rois[r].colour =
            Rgb{std::uint8_t(rgb[0]), std::uint8_t(rgb[1]), std::uint8_t(rgb[2])};
    }

    void readContours(DcmSequenceOfItems& sequence, std::size_t r, const std::string& parent) {
        const About about(about_, r);
        RtStructRoiInfo& info = out_.rois[r];
        info.hasContourSequence = true;
        if (contours_[r].size() + sequence.card() > limits_.maxContoursPerRoi)
            fail(roiLabel(r) + ": more than " + std::to_string(limits_.maxContoursPerRoi) +
                 " contours");
        std::map<std::string, std::size_t> skipped;
        for (unsigned long k = 0; k < sequence.card(); ++k) {
            DcmItem& item = *sequence.getItem(k);
            const std::string where = parent + " > " + tagName(DCM_ContourSequence) + " item " +
                                      std::to_string(k + 1) + " (" + roiLabel(r) + ")";
            const std::string type = text(item, DCM_ContourGeometricType);
            if (type != "CLOSED_PLANAR" && type != "CLOSEDPLANAR_XOR") {
                ++skipped[type.empty() ? "untyped" : type];
                ++info.contoursSkipped;
                continue;
            }
            RtStructContour contour;
            contour.item = k + 1;
            contour.xorType = type == "CLOSEDPLANAR_XOR";
            contour.points = readPoints(item, where);
            readSlab(item, r, where);
            // A contour of one or two points bounds nothing: counted with
            // the contours of no area that reading drops (one warning per ROI).
            const std::size_t drawn = contour.points.size();
            const bool enough = dropRepeatedPoints(contour.points);
            out_.contours.rois[r].reading.repeatedPoints += drawn - contour.points.size();
            if (!enough) {
                ++out_.contours.rois[r].reading.zeroAreaContours;
                continue;
            }
            contours_[r].push_back(std::move(contour));
        }
        for (const auto& [type, count] : skipped)
            warn(roiLabel(r) + ": skipped " + std::to_string(count) + " " + type +
                 " contour(s); only closed planar contours bound a volume");
    }

    std::vector<Vec3> readPoints(DcmItem& item, const std::string& where) {
        DcmElement* element = nullptr;
        if (item.findAndGetElement(DCM_ContourData, element).bad() || !element)
            fail(where + ": missing " + tagName(DCM_ContourData));
        if (element->ident() != EVR_DS && element->ident() != EVR_UN)
            fail(where + ": " + tagName(DCM_ContourData) + " has VR " +
                 DcmVR(element->ident()).getVRName() + ", expected DS");
        // Bound the work by the value's length before parsing: each number
        // takes at least two bytes with its separator.
        const std::size_t values = (element->getLength() + 1) / 2;
        if (totalPoints_ + values / 3 > limits_.maxPointsTotal)
            fail(where + ": " + tagName(DCM_ContourData) + " would take the file over " +
                 std::to_string(limits_.maxPointsTotal) + " points");
        OFVector<Float64> numbers;
        if (element->ident() == EVR_UN) {
            // Explicit VR gives DS a 16-bit length, so writers (plastimatch
            // among them) store a contour of more than about 1 300 points
            // as UN. The bytes are still the DS text, as the data
            // dictionary says (PS3.5 §6.2.2), and are read as such.
            Uint8* bytes = nullptr;
            if (element->getUint8Array(bytes).bad() || (!bytes && element->getLength() > 0))
                fail(where + ": " + tagName(DCM_ContourData) + " (VR UN) could not be read");
            DcmDecimalString asDs(DcmTag(DCM_ContourData, EVR_DS));
            if (asDs.putString(reinterpret_cast<const char*>(bytes), element->getLength()).bad() ||
                asDs.getFloat64Vector(numbers).bad())
                fail(where + ": " + tagName(DCM_ContourData) +
                     " (VR UN) holds a value that is not a number");
            if (!unContourDataWarned_)
                warn(where + ": " + tagName(DCM_ContourData) +
                     " is stored with VR UN (too long for explicit VR's DS); read as DS");
            unContourDataWarned_ = true;
        } else if (static_cast<DcmDecimalString*>(element)->getFloat64Vector(numbers).bad()) {
            fail(where + ": " + tagName(DCM_ContourData) + " holds a value that is not a number");
        }
        if (numbers.size() % 3 != 0)
            fail(where + ": " + tagName(DCM_ContourData) + " has " +
                 std::to_string(numbers.size()) + " values, not a list of x,y,z triplets");
        Sint32 declared = 0;
        if (item.findAndGetSint32(DCM_NumberOfContourPoints, declared).good() &&
            std::size_t(declared) != numbers.size() / 3)
            warn(where + ": " + tagName(DCM_NumberOfContourPoints) + " says " +
                 std::to_string(declared) + " but " + tagName(DCM_ContourData) + " holds " +
                 std::to_string(numbers.size() / 3) + " points; the data is used");
        std::vector<Vec3> points(numbers.size() / 3);
        for (std::size_t i = 0; i < points.size(); ++i) {
            points[i] = {numbers[3 * i], numbers[3 * i + 1], numbers[3 * i + 2]};
            for (int a = 0; a < 3; ++a)
                if (!std::isfinite(points[i][a]) ||
                    std::abs(points[i][a]) > limits_.maxAbsCoordinateMm)
                    fail(where + ": " + tagName(DCM_ContourData) + " point " +
                         std::to_string(i + 1) + " has a coordinate beyond " +
                         std::to_string(std::int64_t(limits_.maxAbsCoordinateMm)) + " mm");
        }
        totalPoints_ += points.size();
        return points;
    }

    void readSlab(DcmItem& item, std::size_t r, const std::string& where) {
        Float64 thickness = 0;
        if (item.findAndGetFloat64(DCM_RETIRED_ContourSlabThickness, thickness).bad()) return;
        if (!(thickness > 0) || thickness > limits_.maxAbsCoordinateMm) {
            warn(where + ": " + tagName(DCM_RETIRED_ContourSlabThickness) + " " +
                 std::to_string(thickness) + " is not a positive length; ignored");
            return;
        }
        double& slab = out_.contours.rois[r].slabThicknessMm;
        if (slab > 0 && std::abs(slab - thickness) > kSamePlaneToleranceMm && !slabWarned_) {
            warn(roiLabel(r) + ": contours give different " +
                 tagName(DCM_RETIRED_ContourSlabThickness) + " values; the largest is used");
            slabWarned_ = true;
        }
        slab = std::max(slab, double(thickness));
    }

    // Drops consecutive repeats and a closing point equal to the first
    // (CLOSED_PLANAR does not repeat it, but some writers do). False if
    // fewer than 3 points remain.
    static bool dropRepeatedPoints(std::vector<Vec3>& points) {
        points.erase(std::unique(points.begin(), points.end()), points.end());
        while (points.size() > 1 && points.back() == points.front()) points.pop_back();
        return points.size() >= 3;
    }

    // ---- geometry: frame, planes, holes --------------------------------------

    // Newell's normal: robust for non-convex polygons; its length is twice
    // the area.
    static Vec3 newellNormal(const std::vector<Vec3>& p) {
        Vec3 n;
        for (std::size_t i = 0; i < p.size(); ++i) {
            const Vec3 a = p[i], b = p[(i + 1) % p.size()];
            n = n + Vec3{(a.y - b.y) * (a.z + b.z), (a.z - b.z) * (a.x + b.x),
                         (a.x - b.x) * (a.y + b.y)};
        }
        return n;
    }

    static double spanAlong(const std::vector<Vec3>& points, Vec3 n) {
        double lo = INFINITY, hi = -INFINITY;
        for (const Vec3& p : points) {
            lo = std::min(lo, dot(p, n));
            hi = std::max(hi, dot(p, n));
        }
        return hi - lo;
    }

    // Axial stacks (each contour at one z) keep the identity, so their
    // coordinates stay exactly as written; other stacks get the frame of
    // their common normal.
    PlaneFrame chooseFrame(std::size_t r) {
        std::vector<RtStructContour>& contours = contours_[r];
        const bool axial = std::all_of(contours.begin(), contours.end(), [](const auto& c) {
            return spanAlong(c.points, {0, 0, 1}) <= kSamePlaneToleranceMm;
        });
        if (axial) return {};
        Vec3 sum;
        for (const RtStructContour& c : contours) {
            const Vec3 n = newellNormal(c.points);
            sum = sum + (dot(n, sum) < 0 ? -1.0 : 1.0) * n;
        }
        if (length(sum) == 0)
            fail(roiLabel(r) + ": contours have no area; cannot find their plane");
        Vec3 normal = (1.0 / length(sum)) * sum;
        for (int a = 0; a < 3; ++a)  // a patient axis within rounding is that axis
            if (std::abs(std::abs(normal[a]) - 1) < 1e-9) {
                const double s = normal[a] < 0 ? -1 : 1;
                normal = a == 0 ? Vec3{s, 0, 0} : a == 1 ? Vec3{0, s, 0} : Vec3{0, 0, s};
            }
        for (const RtStructContour& c : contours) {
            const double span = spanAlong(c.points, normal);
            if (span > kSamePlaneToleranceMm)
                fail(roiLabel(r) + ": contour " + std::to_string(c.item) + " of " +
                     tagName(DCM_ContourSequence) +
                     " is not planar, or not parallel to the "
                     "others: its points spread " +
                     std::to_string(span) + " mm along the common normal");
        }
        // Which way the contours ran does not matter (orientation is
        // normalised later): a patient axis gets its one canonical frame.
        const PlaneFrame frame = canonicalFrame(frameWithNormal(normal));
        warn(roiLabel(r) + ": contours lie in " + frame.orientationName() +
             " planes; reconstructed in their own frame, outputs are in patient coordinates");
        return frame;
    }

    void buildSlices(std::size_t r) {
        const About about(about_, r);
        Roi& roi = out_.contours.rois[r];
        RtStructRoiInfo& info = out_.rois[r];
        std::vector<RtStructContour>& contours = contours_[r];
        info.contoursRead = contours.size();
        if (contours.empty()) return;
        roi.frame = chooseFrame(r);
        for (RtStructContour& c : contours) {
            std::vector<double> z;
            for (Vec3 p : c.points) z.push_back(roi.frame.fromPatient(p).z);
            std::nth_element(z.begin(), z.begin() + std::ptrdiff_t(z.size() / 2), z.end());
            c.planeZ = z[z.size() / 2];  // a value of the file, so round trips are exact
        }
        std::stable_sort(contours.begin(), contours.end(),
                         [](const auto& a, const auto& b) { return a.planeZ < b.planeZ; });
        bool anyXor = false;
        for (std::size_t begin = 0; begin < contours.size();) {
            std::size_t end = begin + 1;
            while (end < contours.size() &&
                   contours[end].planeZ - contours[begin].planeZ <= kSamePlaneToleranceMm)
                ++end;
            // A plane whose every contour had no area, or cancelled another,
            // holds nothing: no slice.
            if (Slice slice = buildSlice(r, begin, end); !slice.contours.empty())
                roi.slices.push_back(std::move(slice));
            for (std::size_t i = begin; i < end; ++i) anyXor = anyXor || contours[i].xorType;
            begin = end;
        }
        bool anyHole = false;
        for (const Slice& slice : roi.slices)
            for (int depth : nestingDepths(slice)) anyHole = anyHole || depth % 2 == 1;
        info.holes = anyXor                           ? HoleConvention::Xor
                     : roi.reading.keyholeCuts > 0    ? HoleConvention::Keyhole
                     : roi.reading.planesResolved > 0 ? HoleConvention::Xor
                     : anyHole                        ? HoleConvention::Nested
                                                      : HoleConvention::None;
        if (roi.reading.changedShape())
            warn(roiLabel(r) + ": read as planning systems read it: " + roi.reading.summary());
        // Uneven spacing is judged per run of planes once the file's runs
        // are known (api readContours): a gap where an ROI ends and starts
        // again is no uneven spacing.
    }

    Slice buildSlice(std::size_t r, std::size_t begin, std::size_t end) {
        Roi& roi = out_.contours.rois[r];
        std::vector<RtStructContour>& contours = contours_[r];
        std::vector<double> z;
        for (std::size_t i = begin; i < end; ++i) z.push_back(contours[i].planeZ);
        Slice slice;
        slice.zMm = z[(z.size() - 1) / 2];
        std::vector<Polygon> drawn;
        for (std::size_t i = begin; i < end; ++i) {
            Polygon polygon;
            for (Vec3 p : contours[i].points) {
                const Vec3 q = roi.frame.fromPatient(p);  // exact for the identity
                polygon.push_back({q.x, q.y});
            }
            drawn.push_back(std::move(polygon));
        }
        // Each plane within its limit, and all planes within the file's.
        const std::size_t fileLeft = limits_.maxXorCrossingsPerFile > xorWork_
                                         ? limits_.maxXorCrossingsPerFile - xorWork_
                                         : 0;
        PlaneReading reading;
        try {
            reading =
                readPlaneContours(std::move(drawn), std::min(limits_.maxXorCrossings, fileLeft));
        } catch (const TooManyCrossings& e) {
            std::ostringstream plane;
            plane << slice.zMm;
            fail(roiLabel(r) + ", plane " + plane.str() + " mm: " + e.what() +
                 (fileLeft < limits_.maxXorCrossings
                      ? " (what was left of " + std::to_string(limits_.maxXorCrossingsPerFile) +
                            " for the whole file)"
                      : std::string()));
        }
        xorWork_ += reading.work;
        roi.reading += reading.counts;
        slice.contours = std::move(reading.contours);
        std::vector<std::size_t> items;  // source item of each polygon, for messages
        for (std::size_t source : reading.sourceOf)
            items.push_back(source == kResolvedContour ? 0 : contours[begin + source].item);
        // What reading leaves is valid but for a plane too complex to search
        // or crossings rounded onto one another: reported, never guessed.
        validate(r, slice, items);
        normaliseOrientation(slice);
        return slice;
    }

    void validate(std::size_t r, const Slice& slice, const std::vector<std::size_t>& items) {
        const std::optional<ContourDefect> defect = findContourDefect(slice.contours);
        if (!defect) return;
        std::ostringstream z;
        z << slice.zMm;
        const std::string plane = roiLabel(r) + ", plane " + z.str() + " mm: ";
        if (defect->kind == ContourDefect::Kind::TooComplex)
            fail(plane + "too complex to validate (pathological segment layout)");
        const std::string how = defect->contact == SegmentContact::Overlap ? " overlaps "
                                : defect->contact == SegmentContact::Touch ? " touches "
                                                                           : " crosses ";
        auto segment = [&](std::size_t contour, std::size_t s) {
            return (items[contour] > 0 ? "contour " + std::to_string(items[contour])
                                       : std::string("a combined contour")) +
                   " segment " + std::to_string(s + 1);
        };
        if (defect->kind == ContourDefect::Kind::SelfIntersection)
            fail(plane +
                 "self-intersecting contour: " + segment(defect->contourA, defect->segmentA) + how +
                 "its segment " + std::to_string(defect->segmentB + 1));
        fail(plane + "contours cross: " + segment(defect->contourA, defect->segmentA) + how +
             segment(defect->contourB, defect->segmentB));
    }

    std::string file_;
    RtStructLimits limits_;
    RtStructLoad out_;
    std::map<Sint32, std::size_t> indexOfNumber_;
    std::vector<std::vector<RtStructContour>> contours_;  // per ROI
    std::size_t totalPoints_ = 0;
    std::size_t xorWork_ = 0;  // contours and crossings combined by XOR so far
    bool slabWarned_ = false;
    bool unContourDataWarned_ = false;  // warned once per file
};

}  // namespace

RtStructLoad readRtStruct(const std::string& path, const RtStructLimits& limits) {
    const ReadingInput reading(path);
    return Reader(path, limits).run();
}

}  // namespace dfrecon
