#pragma once
// Small DICOM image series written with DCMTK's dcmdata, for the image
// series reader and the RTSTRUCT writer's references: CT images of 4 x 3
// pixels whose planes, orientation and UIDs a test chooses.
#include <dcmtk/config/osconfig.h>  // first, as DCMTK requires
#include <dcmtk/dcmdata/dctk.h>

#include <array>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

namespace dfrecon::testing {

/// What one synthetic image says about itself.
struct SyntheticImage {
    std::string sopInstanceUid = "1.2.826.0.1.3680043.10.99.1";
    std::string seriesUid = "1.2.826.0.1.3680043.10.99.2";
    std::string studyUid = "1.2.826.0.1.3680043.10.99.3";
    std::string frameUid = "1.2.826.0.1.3680043.10.99.4";
    std::array<double, 3> positionMm{{0, 0, 0}};
    std::array<double, 6> orientation{{1, 0, 0, 0, 1, 0}};
    std::array<double, 2> pixelSpacingMm{{0.5, 0.75}};  // between rows, between columns
    int rows = 3, columns = 4;
    std::string numberOfFrames;  // empty: not written
    std::string characterSet;    // SpecificCharacterSet; empty: not written (ASCII)
    std::string patientName = "SYNTHETIC^SERIES";  // in characterSet's encoding
    bool withPosition = true;
    bool withPixels = true;  // false: a header claiming rows × columns, no PixelData
};

inline std::string decimalList(const double* values, int count) {
    std::string text;
    for (int i = 0; i < count; ++i) {
        char number[32];
        std::snprintf(number, sizeof number, "%.10g", values[i]);
        text += (i ? "\\" : "") + std::string(number);
    }
    return text;
}

/// Writes `image` as a Part 10 CT image (explicit VR little endian) at
/// `path`. Throws std::runtime_error when DCMTK cannot.
inline void writeSyntheticImage(const std::string& path, const SyntheticImage& image) {
    DcmFileFormat file;
    DcmDataset& d = *file.getDataset();
    auto put = [&](const DcmTagKey& key, const std::string& value) {
        if (d.putAndInsertString(key, value.c_str()).bad())
            throw std::runtime_error(std::string("cannot set ") + DcmTag(key).getTagName() +
                                     std::string(" in ") + path);
    };
    put(DCM_SOPClassUID, UID_CTImageStorage);
    put(DCM_SOPInstanceUID, image.sopInstanceUid);
    put(DCM_StudyInstanceUID, image.studyUid);
    put(DCM_SeriesInstanceUID, image.seriesUid);
    put(DCM_FrameOfReferenceUID, image.frameUid);
    put(DCM_Modality, "CT");
    if (!image.characterSet.empty()) put(DCM_SpecificCharacterSet, image.characterSet);
    put(DCM_PatientName, image.patientName);
    put(DCM_PatientID, "synthetic-series");
    put(DCM_PatientBirthDate, "19700101");
    put(DCM_PatientSex, "O");
    put(DCM_StudyDate, "20240102");
    put(DCM_StudyTime, "030405");
    put(DCM_StudyID, "S1");
    put(DCM_AccessionNumber, "A1");
    put(DCM_SliceThickness, "2");
    if (image.withPosition) put(DCM_ImagePositionPatient, decimalList(image.positionMm.data(), 3));
    put(DCM_ImageOrientationPatient, decimalList(image.orientation.data(), 6));
    put(DCM_PixelSpacing, decimalList(image.pixelSpacingMm.data(), 2));
    if (!image.numberOfFrames.empty()) put(DCM_NumberOfFrames, image.numberOfFrames);
    d.putAndInsertUint16(DCM_Rows, Uint16(image.rows));
    d.putAndInsertUint16(DCM_Columns, Uint16(image.columns));
    d.putAndInsertUint16(DCM_SamplesPerPixel, 1);
    put(DCM_PhotometricInterpretation, "MONOCHROME2");
    d.putAndInsertUint16(DCM_BitsAllocated, 16);
    d.putAndInsertUint16(DCM_BitsStored, 16);
    d.putAndInsertUint16(DCM_HighBit, 15);
    d.putAndInsertUint16(DCM_PixelRepresentation, 1);
    if (image.withPixels) {
        std::vector<Uint16> pixels(std::size_t(image.rows) * std::size_t(image.columns), 0);
        d.putAndInsertUint16Array(DCM_PixelData, pixels.data(),
                                  static_cast<unsigned long>(pixels.size()));
    }
    if (file.saveFile(path.c_str(), EXS_LittleEndianExplicit).bad())
        throw std::runtime_error("cannot write " + path);
}

/// Writes an axial series of `count` images into `folder` (which must
/// exist), image k at z = firstZMm + k·spacingMm, named image_k.dcm, with
/// SOP Instance UIDs "<base>.k+1" where base is image.sopInstanceUid.
inline void writeSyntheticSeries(const std::string& folder, int count, double firstZMm,
                                 double spacingMm, SyntheticImage image = {}) {
    const std::string base = image.sopInstanceUid;
    for (int k = 0; k < count; ++k) {
        image.sopInstanceUid = base + "." + std::to_string(k + 1);
        image.positionMm[2] = firstZMm + k * spacingMm;
        writeSyntheticImage(folder + "/image_" + std::to_string(k) + ".dcm", image);
    }
}

}  // namespace dfrecon::testing
