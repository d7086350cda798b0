// Reading the headers of a DICOM image series with DCMTK's dcmdata, up to
// the pixel data, which are never loaded.
#include "io/dicom/DicomImageSeries.hpp"

#include <dcmtk/config/osconfig.h>  // first, as DCMTK requires
#include <dcmtk/dcmdata/dctk.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <optional>
#include <sstream>

#include "contours/InputError.hpp"
#include "io/contours/ContourFormat.hpp"
#include "io/dicom/DicomAttributes.hpp"
#include "io/dicom/DicomNesting.hpp"
#include "io/files/InputLimits.hpp"
#include "io/files/InputsInUse.hpp"

namespace fs = std::filesystem;

namespace dfrecon {

namespace {

// Direction cosines are written with six decimals by most scanners and
// converters; two images of one series agree far better than this.
constexpr double kOrientationTolerance = 1e-4;
constexpr double kPixelSpacingToleranceMm = 1e-4;
// Two planes closer than this are one plane: the RTSTRUCT reader's rule.
constexpr double kPlaneToleranceMm = kSamePlaneToleranceMm;
// Longest value loaded while parsing; longer ones (pixel data, overlays)
// stay in the file, which stops at (7FE0,0010) anyway.
constexpr Uint32 kMaxLoadedValueBytes = 4096;

std::string numberText(double value) {
    std::ostringstream s;
    s.precision(10);
    s << value;
    return s.str();
}

std::string vecText(Vec3 v) {
    return "(" + numberText(v.x) + ", " + numberText(v.y) + ", " + numberText(v.z) + ")";
}

// One image file's header, as far as a series needs it.
struct ImageHeader {
    DicomImage image;
    DicomPatientStudy patientStudy;
    std::string seriesUid, frameUid, modality;
    int rows = 0, columns = 0;
    double pixelSpacingMm[2] = {0, 0};
    Vec3 rowDirection, columnDirection;
    double sliceThicknessMm = 0;
};

class HeaderReader {
  public:
    HeaderReader(std::string path, DcmDataset& data) : path_(std::move(path)), data_(data) {}

    [[noreturn]] void fail(const DcmTagKey& key, const std::string& problem) const {
        throw InputError(path_, 0, dicomTagName(key) + " " + problem);
    }

    std::string required(const DcmTagKey& key) const {
        std::string value = dicomText(data_, key);
        if (value.empty()) fail(key, "is missing or empty");
        return value;
    }

    // `count` decimal values of a DS attribute, each finite and within
    // `maxAbs`.
    std::vector<double> decimals(const DcmTagKey& key, unsigned long count, double maxAbs) const {
        DcmElement* element = nullptr;
        if (data_.findAndGetElement(key, element).bad() || !element || element->getVM() == 0)
            fail(key, "is missing or empty");
        if (element->getVM() != count)
            fail(key, "has " + std::to_string(element->getVM()) + " values, not " +
                          std::to_string(count));
        std::vector<double> values(count);
        for (unsigned long i = 0; i < count; ++i) {
            Float64 v = 0;
            if (element->getFloat64(v, i).bad())
                fail(key, "value " + std::to_string(i + 1) + " is not a number");
            if (!std::isfinite(v) || std::abs(v) > maxAbs)
                fail(key, "value " + std::to_string(i + 1) + " (" + numberText(v) +
                              ") is not a finite number within " + numberText(maxAbs));
            values[i] = v;
        }
        return values;
    }

    int positiveUs(const DcmTagKey& key) const {
        Uint16 value = 0;
        if (data_.findAndGetUint16(key, value).bad()) fail(key, "is missing or not a number");
        if (value == 0) fail(key, "is 0");
        return value;
    }

    ImageHeader read() const {
        ImageHeader h;
        h.image.path = path_;
        h.image.sopClassUid = required(DCM_SOPClassUID);
        h.image.sopInstanceUid = required(DCM_SOPInstanceUID);
        h.seriesUid = required(DCM_SeriesInstanceUID);
        h.modality = dicomText(data_, DCM_Modality);
        Sint32 frames = 1;
        if (data_.findAndGetSint32(DCM_NumberOfFrames, frames).good() && frames != 1)
            fail(DCM_NumberOfFrames,
                 "is " + std::to_string(frames) +
                     ": multi-frame images are not read (a series of single-frame images is)");
        h.patientStudy = dicomPatientStudy(data_);
        h.patientStudy.studyInstanceUid = required(DCM_StudyInstanceUID);
        h.frameUid = required(DCM_FrameOfReferenceUID);
        h.rows = positiveUs(DCM_Rows);
        h.columns = positiveUs(DCM_Columns);
        const std::vector<double> spacing = decimals(DCM_PixelSpacing, 2, kMaxAbsCoordinateMm);
        for (int a = 0; a < 2; ++a) {
            if (spacing[a] < kMinVoxelSpacingMm)
                fail(DCM_PixelSpacing, "value " + std::to_string(a + 1) + " (" +
                                           numberText(spacing[a]) +
                                           ") is not a spacing of at least " +
                                           numberText(kMinVoxelSpacingMm) + " mm");
            h.pixelSpacingMm[a] = spacing[a];
        }
        const std::vector<double> position =
            decimals(DCM_ImagePositionPatient, 3, kMaxAbsCoordinateMm);
        h.image.positionMm = {position[0], position[1], position[2]};
        const std::vector<double> cosines = decimals(DCM_ImageOrientationPatient, 6, 1.5);
        h.rowDirection = {cosines[0], cosines[1], cosines[2]};
        h.columnDirection = {cosines[3], cosines[4], cosines[5]};
        if (std::abs(length(h.rowDirection) - 1) > kOrientationTolerance ||
            std::abs(length(h.columnDirection) - 1) > kOrientationTolerance ||
            std::abs(dot(h.rowDirection, h.columnDirection)) > kOrientationTolerance)
            fail(DCM_ImageOrientationPatient, "holds " + vecText(h.rowDirection) + " and " +
                                                  vecText(h.columnDirection) +
                                                  ", not two orthogonal unit vectors");
        h.rowDirection = (1 / length(h.rowDirection)) * h.rowDirection;
        h.columnDirection = (1 / length(h.columnDirection)) * h.columnDirection;
        Float64 thickness = 0;
        if (data_.findAndGetFloat64(DCM_SliceThickness, thickness).good() &&
            std::isfinite(thickness) && thickness >= kMinVoxelSpacingMm &&
            thickness <= kMaxAbsCoordinateMm)
            h.sliceThicknessMm = thickness;
        return h;
    }

  private:
    std::string path_;
    DcmDataset& data_;
};

// What one file holds: an image header, or why it is not one.
struct FileLook {
    std::optional<ImageHeader> image;
    std::string notImage;
};

FileLook lookAt(const std::string& path, const DicomSeriesLimits& limits) {
    FileLook look;
    std::error_code error;
    if (!isDicomFile(path)) {
        look.notImage = "not DICOM";
        return look;
    }
    const std::uintmax_t bytes = fs::file_size(path, error);
    if (!error && bytes > limits.maxFileBytes)
        throw InputError(path, 0,
                         "a DICOM file of " + std::to_string(bytes) + " bytes, over the limit of " +
                             std::to_string(limits.maxFileBytes) + " for one image");
    const ReadingInput reading(path);
    checkDicomNesting(path, kMaxDicomNestingDepth);
    DcmFileFormat file;
    const OFCondition status =
        file.loadFileUntilTag(path.c_str(), EXS_Unknown, EGL_noChange, kMaxLoadedValueBytes,
                              ERM_autoDetect, DCM_PixelData);
    if (status.bad())
        throw InputError(path, 0, std::string("not a readable DICOM file (") + status.text() + ")");
    DcmDataset& data = *file.getDataset();
    if (const std::string problem = convertDicomTextToUtf8(data); !problem.empty())
        throw InputError(path, 0, problem);
    // Structure sets, plans, DICOMDIRs and reports have no plane: they sit
    // beside the images in exported folders.
    if (!data.tagExists(DCM_ImagePositionPatient)) {
        const std::string sopClass = dicomText(data, DCM_SOPClassUID);
        look.notImage =
            (sopClass.empty() ? std::string("no SOP class")
                              : std::string(dcmFindNameOfUID(sopClass.c_str(), sopClass.c_str()))) +
            ", not an image (no " + dicomTagName(DCM_ImagePositionPatient) + ")";
        return look;
    }
    look.image = HeaderReader(path, data).read();
    return look;
}

std::vector<std::string> filesOfFolder(const std::string& folder, const DicomSeriesLimits& limits) {
    std::vector<std::string> files;
    std::error_code error;
    std::size_t entries = 0;
    for (fs::directory_iterator it(folder, error), end; !error && it != end; it.increment(error)) {
        if (++entries > limits.maxFiles)
            throw InputError(folder, 0,
                             "more than " + std::to_string(limits.maxFiles) +
                                 " entries; an image series is read from a folder of at most "
                                 "that many");
        std::error_code typeError;
        if (it->is_regular_file(typeError)) files.push_back(it->path().string());
    }
    if (error) throw InputError(folder, 0, "cannot list the folder (" + error.message() + ")");
    std::sort(files.begin(), files.end());  // the same order, and messages, on every run
    return files;
}

[[noreturn]] void failBetween(const ImageHeader& first, const ImageHeader& other,
                              const DcmTagKey& key, const std::string& firstValue,
                              const std::string& otherValue) {
    throw InputError(other.image.path, 0,
                     dicomTagName(key) + " is " + otherValue + " but " + first.image.path +
                         " of the same series has " + firstValue);
}

// Every image agrees with the first on what makes them one grid of planes.
void checkConsistent(const ImageHeader& first, const ImageHeader& h) {
    if (h.patientStudy.studyInstanceUid != first.patientStudy.studyInstanceUid)
        failBetween(first, h, DCM_StudyInstanceUID, first.patientStudy.studyInstanceUid,
                    h.patientStudy.studyInstanceUid);
    if (h.frameUid != first.frameUid)
        failBetween(first, h, DCM_FrameOfReferenceUID, first.frameUid, h.frameUid);
    if (h.rows != first.rows)
        failBetween(first, h, DCM_Rows, std::to_string(first.rows), std::to_string(h.rows));
    if (h.columns != first.columns)
        failBetween(first, h, DCM_Columns, std::to_string(first.columns),
                    std::to_string(h.columns));
    for (int a = 0; a < 2; ++a)
        if (std::abs(h.pixelSpacingMm[a] - first.pixelSpacingMm[a]) > kPixelSpacingToleranceMm)
            failBetween(
                first, h, DCM_PixelSpacing,
                numberText(first.pixelSpacingMm[0]) + "\\" + numberText(first.pixelSpacingMm[1]),
                numberText(h.pixelSpacingMm[0]) + "\\" + numberText(h.pixelSpacingMm[1]));
    if (length(h.rowDirection - first.rowDirection) > kOrientationTolerance ||
        length(h.columnDirection - first.columnDirection) > kOrientationTolerance)
        failBetween(first, h, DCM_ImageOrientationPatient,
                    vecText(first.rowDirection) + " " + vecText(first.columnDirection),
                    vecText(h.rowDirection) + " " + vecText(h.columnDirection));
}

std::string folderOf(const std::string& file) {
    const fs::path parent = fs::path(file).parent_path();
    return parent.empty() ? "." : parent.string();
}

}  // namespace

DicomImageSeries readDicomImageSeries(const std::string& path, const DicomSeriesLimits& limits) {
    silenceDcmtkLog();
    std::error_code error;
    const bool isFolder = fs::is_directory(path, error);
    if (!isFolder && !fs::exists(path, error)) throw InputError(path, 0, "no such file or folder");

    std::string wantedSeries;  // a file stands for its series
    if (!isFolder) {
        const FileLook look = lookAt(path, limits);
        if (!look.image)
            throw InputError(path, 0, look.notImage + "; an image of the series is needed");
        wantedSeries = look.image->seriesUid;
    }
    const std::string folder = isFolder ? path : folderOf(path);

    DicomImageSeries series;
    std::vector<ImageHeader> headers;
    std::map<std::string, std::pair<std::size_t, std::string>> otherSeries;  // count, modality
    for (const std::string& file : filesOfFolder(folder, limits)) {
        FileLook look = lookAt(file, limits);
        if (!look.image) {
            series.skipped.push_back(file + ": " + look.notImage);
            continue;
        }
        if (!wantedSeries.empty() && look.image->seriesUid != wantedSeries) {
            auto& other = otherSeries[look.image->seriesUid];
            ++other.first;
            other.second = look.image->modality;
            continue;
        }
        headers.push_back(std::move(*look.image));
    }
    for (const auto& [uid, other] : otherSeries)
        series.skipped.push_back(std::to_string(other.first) + " image(s) of another series, " +
                                 uid + (other.second.empty() ? "" : " (" + other.second + ")"));
    if (headers.empty())
        throw InputError(
            folder, 0,
            "no DICOM images (files with " + dicomTagName(DCM_ImagePositionPatient) + ")");

    std::map<std::string, std::pair<std::size_t, std::string>> seriesFound;
    for (const ImageHeader& h : headers) {
        auto& found = seriesFound[h.seriesUid];
        ++found.first;
        found.second = h.modality;
    }
    if (seriesFound.size() > 1) {
        std::string list;
        for (const auto& [uid, found] : seriesFound)
            list += "\n  " + uid + (found.second.empty() ? "" : " " + found.second) + ": " +
                    std::to_string(found.first) + " image(s)";
        throw InputError(folder, 0,
                         "holds images of " + std::to_string(seriesFound.size()) + " series (" +
                             dicomTagName(DCM_SeriesInstanceUID) +
                             "); give one image's file to choose its series:" + list);
    }

    const ImageHeader& first = headers.front();
    std::map<std::string, const ImageHeader*> byInstance;
    for (const ImageHeader& h : headers) {
        checkConsistent(first, h);
        const auto [it, added] = byInstance.emplace(h.image.sopInstanceUid, &h);
        if (!added)
            throw InputError(h.image.path, 0,
                             dicomTagName(DCM_SOPInstanceUID) + " " + h.image.sopInstanceUid +
                                 " is also that of " + it->second->image.path);
    }
    series.patientStudy = first.patientStudy;
    series.seriesInstanceUid = first.seriesUid;
    series.frameOfReferenceUid = first.frameUid;
    series.modality = first.modality;
    series.rows = first.rows;
    series.columns = first.columns;
    series.pixelSpacingMm[0] = first.pixelSpacingMm[0];
    series.pixelSpacingMm[1] = first.pixelSpacingMm[1];
    series.rowDirection = first.rowDirection;
    series.columnDirection = first.columnDirection;
    const Vec3 normal = cross(first.rowDirection, first.columnDirection);
    series.normal = (1 / length(normal)) * normal;
    series.sliceThicknessMm = first.sliceThicknessMm;
    for (ImageHeader& h : headers) {
        h.image.planePositionMm = dot(h.image.positionMm, series.normal);
        series.images.push_back(std::move(h.image));
    }
    std::sort(series.images.begin(), series.images.end(),
              [](const DicomImage& a, const DicomImage& b) {
                  return a.planePositionMm < b.planePositionMm;
              });
    for (std::size_t i = 1; i < series.images.size(); ++i) {
        const DicomImage &a = series.images[i - 1], &b = series.images[i];
        if (b.planePositionMm - a.planePositionMm <= kPlaneToleranceMm)
            throw InputError(b.path, 0,
                             dicomTagName(DCM_ImagePositionPatient) + " puts it in the plane of " +
                                 a.path + " (" + numberText(a.planePositionMm) +
                                 " mm along the normal)");
    }
    return series;
}

VolumeGeometry gridOf(const DicomImageSeries& series) {
    if (series.images.empty()) throw std::invalid_argument("gridOf: a series without images");
    const DicomImage& first = series.images.front();
    const std::string folder = folderOf(first.path);
    double spacingMm = series.sliceThicknessMm;
    if (series.images.size() == 1 && !(spacingMm > 0))
        throw InputError(first.path, 0,
                         "a single image without " + dicomTagName(DCM_SliceThickness) +
                             ": the grid's spacing along the normal is unknown");
    if (series.images.size() > 1) {
        const DicomImage& last = series.images.back();
        spacingMm =
            (last.planePositionMm - first.planePositionMm) / double(series.images.size() - 1);
    }
    for (std::size_t k = 0; k < series.images.size(); ++k) {
        const DicomImage& image = series.images[k];
        const double expected = first.planePositionMm + double(k) * spacingMm;
        if (std::abs(image.planePositionMm - expected) > kPlaneToleranceMm)
            throw InputError(folder, 0,
                             "uneven spacing of the image planes: " + image.path + " lies at " +
                                 numberText(image.planePositionMm - first.planePositionMm) +
                                 " mm from the first along the normal, an even grid would put "
                                 "it at " +
                                 numberText(expected - first.planePositionMm) + " mm");
        const Vec3 offset = image.positionMm - first.positionMm;
        const Vec3 inPlane = offset - dot(offset, series.normal) * series.normal;
        if (length(inPlane) > kPlaneToleranceMm)
            throw InputError(folder, 0,
                             image.path + ": " + dicomTagName(DCM_ImagePositionPatient) + " is " +
                                 numberText(length(inPlane)) +
                                 " mm off the line through the first image's position along the "
                                 "normal: the images do not stack into a grid (a tilted "
                                 "gantry?)");
    }
    VolumeGeometry grid;
    grid.size = {series.columns, series.rows, int(series.images.size())};
    grid.spacingMm = {series.pixelSpacingMm[1], series.pixelSpacingMm[0], spacingMm};
    grid.originMm = {first.positionMm.x, first.positionMm.y, first.positionMm.z};
    const Vec3 axes[3] = {series.rowDirection, series.columnDirection, series.normal};
    for (int a = 0; a < 3; ++a) grid.direction[a] = {axes[a].x, axes[a].y, axes[a].z};
    return grid;
}

const DicomImage* imageHolding(const DicomImageSeries& series, const std::vector<Vec3>& pointsMm,
                               double toleranceMm) {
    if (pointsMm.empty() || series.images.empty()) return nullptr;
    double lo = INFINITY, hi = -INFINITY;
    for (const Vec3& p : pointsMm) {
        lo = std::min(lo, dot(p, series.normal));
        hi = std::max(hi, dot(p, series.normal));
    }
    const double middle = 0.5 * (lo + hi);
    const auto after = std::lower_bound(
        series.images.begin(), series.images.end(), middle,
        [](const DicomImage& image, double position) { return image.planePositionMm < position; });
    const DicomImage* nearest = nullptr;
    for (auto it : {after, after == series.images.begin() ? after : after - 1})
        if (it != series.images.end() &&
            (!nearest ||
             std::abs(it->planePositionMm - middle) < std::abs(nearest->planePositionMm - middle)))
            nearest = &*it;
    if (!nearest || nearest->planePositionMm - lo > toleranceMm ||
        hi - nearest->planePositionMm > toleranceMm)
        return nullptr;
    return nearest;
}

}  // namespace dfrecon
