// DICOM image series: the fixture series plastimatch wrote (axial and
// coronal), checked against the label volume they were made from, and
// synthetic series written here with dcmdata, broken in every way the reader
// must name.
#include "tests/SyntheticDicomSeries.hpp"  // DCMTK first

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>

#include "contours/InputError.hpp"
#include "io/dicom/DicomImageSeries.hpp"
#include "io/labels/LabelVolume.hpp"
#include "tests/TempDir.hpp"

using namespace dfrecon;
using dfrecon::testing::SyntheticImage;
using dfrecon::testing::TempDir;
using dfrecon::testing::writeSyntheticImage;
using dfrecon::testing::writeSyntheticSeries;
namespace fs = std::filesystem;

namespace {

const fs::path kFixtures = DFRECON_FIXTURES;

// The message of the InputError `read` throws ("" when it throws none).
template <class F>
std::string inputErrorOf(F read) {
    try {
        read();
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

std::string dicomString(const std::string& path, const DcmTagKey& key) {
    DcmFileFormat file;
    EXPECT_TRUE(file.loadFile(path.c_str()).good()) << path;
    OFString value;
    file.getDataset()->findAndGetOFStringArray(key, value);
    return value.c_str();
}

// The LPS centres of a grid's eight corner voxels, sorted, to compare two
// grids that may run their axes in opposite directions.
std::vector<std::array<double, 3>> cornerCentres(const VolumeGeometry& g) {
    std::vector<std::array<double, 3>> corners;
    for (int c = 0; c < 8; ++c) {
        const Vec3 p = g.worldOfIndex(c & 1 ? g.size[0] - 1 : 0, c & 2 ? g.size[1] - 1 : 0,
                                      c & 4 ? g.size[2] - 1 : 0);
        corners.push_back({p.x, p.y, p.z});
    }
    std::sort(corners.begin(), corners.end());
    return corners;
}

void expectSameGrid(const VolumeGeometry& a, const VolumeGeometry& b, double toleranceMm) {
    EXPECT_EQ(a.voxelCount(), b.voxelCount());
    const auto ca = cornerCentres(a), cb = cornerCentres(b);
    for (int c = 0; c < 8; ++c)
        for (int k = 0; k < 3; ++k) EXPECT_NEAR(ca[c][k], cb[c][k], toleranceMm) << c << " " << k;
}

}  // namespace

TEST(DicomImageSeries, AxialFixtureIsTheLabelVolumesGrid) {
    const fs::path study = kFixtures / "kmeans_axial";
    ASSERT_TRUE(fs::exists(study / "dicom/image0000.dcm")) << "run make setup";
    const DicomImageSeries series = readDicomImageSeries((study / "dicom").string());
    ASSERT_EQ(series.images.size(), 62u);
    // rtss.dcm sits beside the images and is no image.
    ASSERT_EQ(series.skipped.size(), 1u);
    EXPECT_NE(series.skipped[0].find("rtss.dcm: RTStructureSetStorage, not an image"),
              std::string::npos)
        << series.skipped[0];
    const std::string first = (study / "dicom/image0000.dcm").string();
    EXPECT_EQ(series.seriesInstanceUid, dicomString(first, DCM_SeriesInstanceUID));
    EXPECT_EQ(series.frameOfReferenceUid, dicomString(first, DCM_FrameOfReferenceUID));
    EXPECT_EQ(series.patientStudy.studyInstanceUid, dicomString(first, DCM_StudyInstanceUID));
    EXPECT_EQ(series.patientStudy.patientId, "dfrecon-kmeans_axial");
    EXPECT_EQ(series.modality, "CT");
    EXPECT_EQ(series.rows, 128);
    EXPECT_EQ(series.columns, 128);
    for (std::size_t k = 1; k < series.images.size(); ++k)
        EXPECT_NEAR(series.images[k].planePositionMm - series.images[k - 1].planePositionMm, 3,
                    1e-4);
    for (const DicomImage& image : series.images) {
        EXPECT_EQ(image.sopClassUid, UID_CTImageStorage);
        EXPECT_EQ(image.sopInstanceUid, dicomString(image.path, DCM_SOPInstanceUID));
    }
    // The voxels the images were made from: the same grid, axis for axis.
    const VolumeGeometry grid = gridOf(series);
    const VolumeGeometry labels = readLabelVolume((study / "labels.nii.gz").string()).geometry;
    for (int a = 0; a < 3; ++a) {
        EXPECT_EQ(grid.size[a], labels.size[a]);
        EXPECT_NEAR(grid.spacingMm[a], labels.spacingMm[a], 1e-5);
        EXPECT_NEAR(grid.originMm[a], labels.originMm[a], 1e-4);
        for (int b = 0; b < 3; ++b) EXPECT_NEAR(grid.direction[a][b], labels.direction[a][b], 1e-6);
    }
}

TEST(DicomImageSeries, CoronalFixtureCoversTheLabelVolumesVoxels) {
    const fs::path study = kFixtures / "kmeans";
    ASSERT_TRUE(fs::exists(study / "dicom/image0000.dcm")) << "run make setup";
    const DicomImageSeries series = readDicomImageSeries((study / "dicom").string());
    EXPECT_EQ(series.images.size(), 62u);
    EXPECT_NEAR(std::abs(series.normal.y), 1, 1e-9);  // coronal planes
    expectSameGrid(gridOf(series), readLabelVolume((study / "labels.nii.gz").string()).geometry,
                   1e-3);
}

TEST(DicomImageSeries, OneImageStandsForItsSeries) {
    const fs::path dicom = kFixtures / "kmeans_axial" / "dicom";
    ASSERT_TRUE(fs::exists(dicom / "image0030.dcm")) << "run make setup";
    const DicomImageSeries fromFile = readDicomImageSeries((dicom / "image0030.dcm").string());
    const DicomImageSeries fromFolder = readDicomImageSeries(dicom.string());
    ASSERT_EQ(fromFile.images.size(), fromFolder.images.size());
    for (std::size_t k = 0; k < fromFile.images.size(); ++k)
        EXPECT_EQ(fromFile.images[k].sopInstanceUid, fromFolder.images[k].sopInstanceUid);
}

TEST(DicomImageSeries, SyntheticSeriesSortsByPlaneAndPlacesContours) {
    TempDir dir("series");
    // Written out of order, the normal along -z: planes sort along the normal.
    SyntheticImage image;
    image.orientation = {0, 1, 0, 1, 0, 0};  // rows along y, columns along x: normal -z
    writeSyntheticSeries(dir.str(), 5, 10, -2.5, image);
    const DicomImageSeries series = readDicomImageSeries(dir.str());
    ASSERT_EQ(series.images.size(), 5u);
    EXPECT_NEAR(series.normal.z, -1, 1e-12);
    EXPECT_EQ(series.images.front().positionMm.z, 10);  // the first plane along -z
    EXPECT_EQ(series.images.back().positionMm.z, 0);
    EXPECT_EQ(series.patientStudy.patientBirthDate, "19700101");
    EXPECT_EQ(series.patientStudy.accessionNumber, "A1");

    const VolumeGeometry grid = gridOf(series);
    EXPECT_EQ(grid.size, (std::array<int, 3>{4, 3, 5}));
    EXPECT_EQ(grid.spacingMm, (std::array<double, 3>{0.75, 0.5, 2.5}));
    EXPECT_EQ(grid.direction[2], (std::array<double, 3>{0, 0, -1}));
    EXPECT_EQ(grid.originMm[2], 10);
    EXPECT_EQ(grid.worldOfIndex(0, 0, 4).z, 0);

    // A contour on z = 5 (within 0.01 mm) is on image 2's plane; one across
    // planes, or between them, is on none.
    const DicomImage* on = imageHolding(series, {{0, 0, 5.004}, {3, 0, 4.997}, {0, 2, 5}}, 0.01);
    ASSERT_NE(on, nullptr);
    EXPECT_EQ(on->positionMm.z, 5);
    EXPECT_EQ(on->sopInstanceUid, "1.2.826.0.1.3680043.10.99.1.3");
    EXPECT_EQ(imageHolding(series, {{0, 0, 5}, {3, 0, 5.02}}, 0.01), nullptr);
    EXPECT_EQ(imageHolding(series, {{0, 0, 6}}, 0.01), nullptr);
    EXPECT_EQ(imageHolding(series, {{0, 0, -3}}, 0.01), nullptr);
    EXPECT_NE(imageHolding(series, {{0, 0, 10.009}}, 0.01), nullptr);
}

TEST(DicomImageSeries, FolderWithoutImagesIsAnError) {
    TempDir dir("series-empty");
    EXPECT_NE(inputErrorOf([&] { readDicomImageSeries(dir.str()); }).find("no DICOM images"),
              std::string::npos);
    std::ofstream(dir / "notes.txt") << "not an image\n";
    std::ofstream(dir / "data.raw") << std::string(300, 'x');
    EXPECT_NE(inputErrorOf([&] { readDicomImageSeries(dir.str()); }).find("no DICOM images"),
              std::string::npos);
    EXPECT_NE(
        inputErrorOf([&] { readDicomImageSeries(dir / "missing"); }).find("no such file or folder"),
        std::string::npos);
    EXPECT_NE(inputErrorOf([&] {
                  readDicomImageSeries(dir / "notes.txt");
              }).find("not DICOM; an image of the series is needed"),
              std::string::npos);
    // Non-DICOM files beside the images are skipped and listed.
    writeSyntheticSeries(dir.str(), 2, 0, 1);
    const DicomImageSeries series = readDicomImageSeries(dir.str());
    EXPECT_EQ(series.images.size(), 2u);
    EXPECT_EQ(series.skipped.size(), 2u);
}

TEST(DicomImageSeries, InconsistentImagesNameBothFilesAndTheTag) {
    TempDir dir("series-mixed");
    writeSyntheticSeries(dir.str(), 3, 0, 2);
    SyntheticImage odd;
    odd.sopInstanceUid = "1.2.826.0.1.3680043.10.99.9";
    odd.positionMm = {0, 0, 6};
    odd.orientation = {1, 0, 0, 0, 0, -1};  // coronal among axial images
    writeSyntheticImage(dir / "image_3.dcm", odd);
    std::string message = inputErrorOf([&] { readDicomImageSeries(dir.str()); });
    EXPECT_NE(message.find("image_3.dcm: (0020,0037) ImageOrientationPatient is"),
              std::string::npos)
        << message;
    EXPECT_NE(message.find("image_0.dcm of the same series"), std::string::npos) << message;

    odd.orientation = {1, 0, 0, 0, 1, 0};
    odd.pixelSpacingMm = {0.5, 0.8};
    writeSyntheticImage(dir / "image_3.dcm", odd);
    message = inputErrorOf([&] { readDicomImageSeries(dir.str()); });
    EXPECT_NE(message.find("(0028,0030) PixelSpacing is 0.5\\0.8"), std::string::npos) << message;

    odd.pixelSpacingMm = {0.5, 0.75};
    odd.frameUid = "1.2.826.0.1.3680043.10.99.77";
    writeSyntheticImage(dir / "image_3.dcm", odd);
    message = inputErrorOf([&] { readDicomImageSeries(dir.str()); });
    EXPECT_NE(message.find("(0020,0052) FrameOfReferenceUID"), std::string::npos) << message;

    odd.frameUid = SyntheticImage{}.frameUid;
    odd.positionMm = {0, 0, 4.005};  // the plane of image_2
    writeSyntheticImage(dir / "image_3.dcm", odd);
    message = inputErrorOf([&] { readDicomImageSeries(dir.str()); });
    EXPECT_NE(message.find("puts it in the plane of"), std::string::npos) << message;

    odd.positionMm = {0, 0, 6};
    odd.sopInstanceUid = "1.2.826.0.1.3680043.10.99.1.1";  // image_0's
    writeSyntheticImage(dir / "image_3.dcm", odd);
    message = inputErrorOf([&] { readDicomImageSeries(dir.str()); });
    EXPECT_NE(message.find("(0008,0018) SOPInstanceUID 1.2.826.0.1.3680043.10.99.1.1 is also"),
              std::string::npos)
        << message;
}

TEST(DicomImageSeries, SeveralSeriesInAFolderAreListed) {
    TempDir dir("series-two");
    writeSyntheticSeries(dir.str(), 3, 0, 2);
    SyntheticImage other;
    other.sopInstanceUid = "1.2.826.0.1.3680043.10.98.1";
    other.seriesUid = "1.2.826.0.1.3680043.10.98.2";
    writeSyntheticImage(dir / "other.dcm", other);
    const std::string message = inputErrorOf([&] { readDicomImageSeries(dir.str()); });
    EXPECT_NE(message.find("holds images of 2 series"), std::string::npos) << message;
    EXPECT_NE(message.find("1.2.826.0.1.3680043.10.98.2 CT: 1 image(s)"), std::string::npos)
        << message;
    EXPECT_NE(message.find("1.2.826.0.1.3680043.10.99.2 CT: 3 image(s)"), std::string::npos)
        << message;
    // One image's file chooses its series; the other is skipped.
    const DicomImageSeries chosen = readDicomImageSeries(dir / "image_1.dcm");
    EXPECT_EQ(chosen.images.size(), 3u);
    ASSERT_EQ(chosen.skipped.size(), 1u);
    EXPECT_NE(chosen.skipped[0].find("1 image(s) of another series"), std::string::npos);
    EXPECT_EQ(readDicomImageSeries(dir / "other.dcm").images.size(), 1u);
}

TEST(DicomImageSeries, BrokenFilesAreErrorsNamingFileAndTag) {
    TempDir dir("series-broken");
    writeSyntheticSeries(dir.str(), 2, 0, 2);
    // Cut inside the header: DCMTK cannot parse it.
    const std::string whole = dir / "image_1.dcm";
    std::string bytes;
    {
        std::ifstream in(whole, std::ios::binary);
        bytes.assign(std::istreambuf_iterator<char>(in), {});
    }
    std::ofstream(whole, std::ios::binary | std::ios::trunc) << bytes.substr(0, 300);
    std::string message = inputErrorOf([&] { readDicomImageSeries(dir.str()); });
    EXPECT_NE(message.find("image_1.dcm: not a readable DICOM file"), std::string::npos) << message;

    SyntheticImage image;
    image.sopInstanceUid = "1.2.826.0.1.3680043.10.99.1.2";
    image.positionMm = {0, 0, 2};
    image.pixelSpacingMm = {0.5, 0};
    writeSyntheticImage(whole, image);
    message = inputErrorOf([&] { readDicomImageSeries(dir.str()); });
    EXPECT_NE(message.find("image_1.dcm: (0028,0030) PixelSpacing value 2 (0) is not a spacing"),
              std::string::npos)
        << message;

    image.pixelSpacingMm = {0.5, 0.75};
    image.orientation = {1, 0, 0, 1, 0, 0};
    writeSyntheticImage(whole, image);
    message = inputErrorOf([&] { readDicomImageSeries(dir.str()); });
    EXPECT_NE(message.find("(0020,0037) ImageOrientationPatient holds"), std::string::npos)
        << message;

    image.orientation = {1, 0, 0, 0, 1, 0};
    image.numberOfFrames = "3";
    writeSyntheticImage(whole, image);
    message = inputErrorOf([&] { readDicomImageSeries(dir.str()); });
    EXPECT_NE(message.find("(0028,0008) NumberOfFrames is 3"), std::string::npos) << message;

    // No ImagePositionPatient: not an image at all, skipped.
    image.numberOfFrames.clear();
    image.withPosition = false;
    writeSyntheticImage(whole, image);
    const DicomImageSeries series = readDicomImageSeries(dir.str());
    EXPECT_EQ(series.images.size(), 1u);
    ASSERT_EQ(series.skipped.size(), 1u);
    EXPECT_NE(series.skipped[0].find("CTImageStorage, not an image"), std::string::npos);
}

TEST(DicomImageSeries, LimitsBoundFilesAndTheirSize) {
    TempDir dir("series-limits");
    writeSyntheticSeries(dir.str(), 4, 0, 2);
    DicomSeriesLimits limits;
    limits.maxFiles = 3;
    EXPECT_NE(
        inputErrorOf([&] { readDicomImageSeries(dir.str(), limits); }).find("more than 3 entries"),
        std::string::npos);
    limits.maxFiles = 4;
    EXPECT_EQ(readDicomImageSeries(dir.str(), limits).images.size(), 4u);
    limits.maxFileBytes = 100;
    EXPECT_NE(inputErrorOf([&] {
                  readDicomImageSeries(dir.str(), limits);
              }).find("over the limit of 100 for one image"),
              std::string::npos);
}

TEST(DicomImageSeries, GridNeedsEvenSpacingAndAStraightStack) {
    TempDir dir("series-grid");
    writeSyntheticSeries(dir.str(), 3, 0, 2);
    SyntheticImage image;
    image.sopInstanceUid = "1.2.826.0.1.3680043.10.99.1.4";
    image.positionMm = {0, 0, 7};  // gaps 2, 2, 3
    writeSyntheticImage(dir / "image_3.dcm", image);
    const DicomImageSeries uneven = readDicomImageSeries(dir.str());
    EXPECT_NE(inputErrorOf([&] { gridOf(uneven); }).find("uneven spacing of the image planes"),
              std::string::npos);

    image.positionMm = {0.5, 0, 6};  // even, but shifted sideways: a tilted gantry
    writeSyntheticImage(dir / "image_3.dcm", image);
    const DicomImageSeries tilted = readDicomImageSeries(dir.str());
    EXPECT_NE(inputErrorOf([&] { gridOf(tilted); }).find("do not stack into a grid"),
              std::string::npos);

    // A single image takes its SliceThickness as the third spacing.
    TempDir one("series-one");
    writeSyntheticSeries(one.str(), 1, 3, 1);
    const VolumeGeometry grid = gridOf(readDicomImageSeries(one.str()));
    EXPECT_EQ(grid.size[2], 1);
    EXPECT_EQ(grid.spacingMm[2], 2);
    EXPECT_EQ(grid.originMm[2], 3);
}

TEST(DicomImageSeries, PatientNamesComeAsUtf8) {
    // ISO_IR 100 is Latin-1: u-umlaut is the byte FC, in UTF-8 C3 BC.
    TempDir dir("series-latin1");
    SyntheticImage image;
    image.characterSet = "ISO_IR 100";
    image.patientName = "M\xfcller^Anna";
    writeSyntheticSeries(dir.str(), 2, 0, 1, image);
    EXPECT_EQ(readDicomImageSeries(dir.str()).patientStudy.patientName, "M\xc3\xbcller^Anna");
}
