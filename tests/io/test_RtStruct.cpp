// RT Structure Sets: exact round trips through our writer, and the reader on
// datasets built here with DCMTK's dcmdata (jittered planes, skipped contour
// types, keyholes, XOR, non-axial stacks) and on broken files (the tag named).
#include <dcmtk/config/osconfig.h>
#include <dcmtk/dcmdata/dctk.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <set>
#include <tuple>

#include "io/dicom/RtStruct.hpp"
#include "shapes/AnalyticShapes.hpp"
#include "tests/HostileDicom.hpp"
#include "tests/RtStructWarnings.hpp"
#include "tests/SyntheticDicomSeries.hpp"
#include "tests/TempDir.hpp"

using namespace dfrecon;
namespace fs = std::filesystem;

namespace {

std::string tempPath(const std::string& name) {
    return (fs::temp_directory_path() / ("dfrecon-test-rt-" + name + ".dcm")).string();
}

// ---- datasets built by hand with dcmdata ----------------------------------

struct ContourSpec {
    std::string type = "CLOSED_PLANAR";
    std::vector<Vec3> points;
    std::string slabThickness;  // empty: absent
    // ContourData stored as VR UN, as writers store a DS value too long for
    // explicit VR's 16-bit length; `unAs` another VR of the same bytes.
    bool asUn = false;
    DcmEVR unAs = EVR_UN;
};
struct RoiSpec {
    int number = 1;
    std::string name = "PTV";
    bool hasContourSequence = true;
    std::vector<ContourSpec> contours;
};

// Valid DS values (at most 16 characters), as any DICOM writer must give.
std::string decimal(double v) {
    return formatDecimalString(v);
}

ContourSpec square(double x0, double y0, double side, double z, bool clockwise = false) {
    ContourSpec c;
    std::vector<Vec3> p = {
        {x0, y0, z}, {x0 + side, y0, z}, {x0 + side, y0 + side, z}, {x0, y0 + side, z}};
    if (clockwise) std::reverse(p.begin(), p.end());
    c.points = p;
    return c;
}

std::string contourDataText(const std::vector<Vec3>& points) {
    std::string text;
    for (const Vec3& p : points)
        for (int a = 0; a < 3; ++a) text += (text.empty() ? "" : "\\") + decimal(p[a]);
    return text;
}

void writeDataset(const std::string& path, const std::vector<RoiSpec>& rois,
                  const std::string& modality = "RTSTRUCT", bool withRoiList = true) {
    DcmFileFormat file;
    DcmDataset& ds = *file.getDataset();
    ds.putAndInsertString(DCM_SOPClassUID, UID_RTStructureSetStorage);
    ds.putAndInsertString(DCM_SOPInstanceUID, "1.2.3.4");
    ds.putAndInsertString(DCM_Modality, modality.c_str());
    DcmItem* item = nullptr;
    if (withRoiList) {
        ds.insertEmptyElement(DCM_StructureSetROISequence);
        for (const RoiSpec& roi : rois) {
            ds.findOrCreateSequenceItem(DCM_StructureSetROISequence, item, -2);
            item->putAndInsertString(DCM_ROINumber, std::to_string(roi.number).c_str());
            item->putAndInsertString(DCM_ROIName, roi.name.c_str());
        }
    }
    for (const RoiSpec& roi : rois) {
        ds.findOrCreateSequenceItem(DCM_ROIContourSequence, item, -2);
        item->putAndInsertString(DCM_ReferencedROINumber, std::to_string(roi.number).c_str());
        item->putAndInsertString(DCM_ROIDisplayColor, "10\\20\\30");
        if (!roi.hasContourSequence) continue;
        item->insertEmptyElement(DCM_ContourSequence);
        for (const ContourSpec& c : roi.contours) {
            DcmItem* contour = nullptr;
            item->findOrCreateSequenceItem(DCM_ContourSequence, contour, -2);
            contour->putAndInsertString(DCM_ContourGeometricType, c.type.c_str());
            contour->putAndInsertString(DCM_NumberOfContourPoints,
                                        std::to_string(c.points.size()).c_str());
            if (c.asUn) {
                const std::string text = contourDataText(c.points);
                auto* raw = new DcmOtherByteOtherWord(DcmTag(DCM_ContourData, c.unAs));
                raw->putUint8Array(reinterpret_cast<const Uint8*>(text.data()),
                                   Uint32(text.size()));
                contour->insert(raw, true);
            } else {
                contour->putAndInsertString(DCM_ContourData, contourDataText(c.points).c_str());
            }
            if (!c.slabThickness.empty())
                contour->putAndInsertString(DCM_RETIRED_ContourSlabThickness,
                                            c.slabThickness.c_str());
        }
    }
    ASSERT_TRUE(file.saveFile(path.c_str(), EXS_LittleEndianExplicit).good());
}

// The error that stops the file, or else the first ROI's that the reader
// kept with its defect (the other ROIs loading).
std::string readError(const std::string& path) {
    try {
        const RtStructLoad load = readRtStruct(path);
        for (const Roi& roi : load.contours.rois)
            if (roi.defect) {
                EXPECT_EQ(roi.defect->file(), path);
                EXPECT_TRUE(roi.slices.empty());
                return roi.defect->problem();
            }
    } catch (const InputError& e) {
        EXPECT_EQ(e.file(), path);
        return e.problem();
    }
    ADD_FAILURE() << "no error reading " << path;
    return "";
}

// A ring (hole inside) and a separate island on each of three slices.
ContourSet ringsAndIslands() {
    ContourSet set;
    Roi roi;
    roi.name = "Rectum wall";
    roi.number = 7;
    roi.colour = Rgb{200, 100, 0};
    for (int k = 0; k < 3; ++k) {
        Slice s;
        s.zMm = -12.5 + 2.5 * k;
        s.contours = {circlePolygon({1.25, -3.3}, 20, 48),
                      circlePolygon({1.25, -3.3}, 9.7, 36, true),
                      circlePolygon({60.1, 0.3}, 5 + k, 24)};
        roi.slices.push_back(s);
    }
    set.rois.push_back(roi);
    return set;
}

// Every point equal within toleranceMm (0: bit for bit); reports the first
// difference only.
void expectSameContours(const ContourSet& a, const ContourSet& b, double toleranceMm = 0) {
    ASSERT_EQ(a.rois.size(), b.rois.size());
    for (std::size_t r = 0; r < a.rois.size(); ++r) {
        const Roi &x = a.rois[r], &y = b.rois[r];
        EXPECT_EQ(x.name, y.name);
        ASSERT_EQ(x.slices.size(), y.slices.size()) << x.name;
        for (std::size_t s = 0; s < x.slices.size(); ++s) {
            ASSERT_NEAR(x.slices[s].zMm, y.slices[s].zMm, toleranceMm);
            ASSERT_EQ(x.slices[s].contours.size(), y.slices[s].contours.size());
            for (std::size_t c = 0; c < x.slices[s].contours.size(); ++c) {
                const Polygon &p = x.slices[s].contours[c], &q = y.slices[s].contours[c];
                ASSERT_EQ(p.size(), q.size());
                for (std::size_t i = 0; i < p.size(); ++i)
                    ASSERT_TRUE(std::abs(p[i].x - q[i].x) <= toleranceMm &&
                                std::abs(p[i].y - q[i].y) <= toleranceMm)
                        << x.name << " slice " << s << " contour " << c << " point " << i << ": ("
                        << p[i].x << ", " << p[i].y << ") vs (" << q[i].x << ", " << q[i].y << ")";
            }
        }
    }
}

}  // namespace

TEST(RtStruct, DecimalStringsFitSixteenCharactersAndReadBack) {
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> mm(-600, 600);
    for (int i = 0; i < 20000; ++i) {
        const double v = i % 2 ? mm(rng) : std::round(mm(rng) * 1e4) / 1e4;
        const std::string text = formatDecimalString(v);
        ASSERT_LE(text.size(), 16u) << v;
        const double back = std::stod(text);
        // 16 characters hold 13+ significant digits here; values with four
        // decimals (as planning systems write) come back exactly.
        if (i % 2 == 0)
            EXPECT_EQ(back, v) << text;
        else
            EXPECT_NEAR(back, v, 1e-10) << text;
    }
    EXPECT_EQ(formatDecimalString(-0.0), "0");
    EXPECT_LE(formatDecimalString(-1.234567890123456e-7).size(), 16u);
}

TEST(RtStruct, RoundTripKeepsEveryPoint) {
    ContourSet set = sliceShape(*makeShape("torus"), {2.0, 64, 0.3, 5});
    set.rois.front().colour = Rgb{1, 2, 3};
    const ContourSet rings = ringsAndIslands();
    set.rois.push_back(rings.rois.front());
    const std::string path = tempPath("roundtrip");
    writeRtStruct(set, path);
    const RtStructLoad load = readRtStruct(path);
    EXPECT_TRUE(load.warnings.empty()) << load.warnings.front().toString();
    // Full doubles become 16-character DS values on the way in...
    expectSameContours(set, load.contours, 1e-10);
    ASSERT_EQ(load.rois.size(), 2u);
    EXPECT_EQ(load.rois[0].number, 1);  // the torus had no number: its position
    EXPECT_EQ(load.rois[1].number, 7);
    EXPECT_EQ((*load.contours.rois[1].colour)[1], 100);
    EXPECT_EQ(load.rois[0].holes, HoleConvention::Nested);  // torus slices through the hole
    EXPECT_FALSE(load.frameOfReferenceUid.empty());

    // ...and from there RTSTRUCT -> ContourSet -> RTSTRUCT keeps every point exactly.
    const std::string again = tempPath("roundtrip2");
    writeRtStruct(load.contours, again);
    const RtStructLoad second = readRtStruct(again);
    expectSameContours(load.contours, second.contours);
    EXPECT_EQ(second.rois[1].number, 7);
    fs::remove(path);
    fs::remove(again);
}

TEST(RtStruct, JitteredPlanesGroupIntoSlices) {
    RoiSpec roi;
    roi.contours = {square(0, 0, 10, 2.4991), square(20, 0, 5, 2.4992), square(0, 0, 10, 5.0),
                    square(0, 0, 10, 8.0)};
    const std::string path = tempPath("jitter");
    writeDataset(path, {roi});
    const RtStructLoad load = readRtStruct(path);
    const Roi& read = load.contours.rois.front();
    ASSERT_EQ(read.slices.size(), 3u);
    EXPECT_EQ(read.slices[0].contours.size(), 2u);
    EXPECT_NEAR(read.slices[0].zMm, 2.4991, 1e-9);
    EXPECT_EQ(read.slices[2].zMm, 8.0);
    EXPECT_EQ((*read.colour)[2], 30);
    EXPECT_EQ(read.number, 1);
    fs::remove(path);
}

TEST(RtStruct, SkipsPointAndOpenContoursAndListsEmptyRois) {
    RoiSpec body;
    body.contours = {square(0, 0, 10, 0), square(0, 0, 10, 3)};
    ContourSpec point;
    point.type = "POINT";
    point.points = {{1, 2, 3}};
    ContourSpec open = square(0, 0, 4, 6);
    open.type = "OPEN_PLANAR";
    body.contours.push_back(point);
    body.contours.push_back(open);
    RoiSpec marker{2, "Marker", true, {point}};
    RoiSpec empty{3, "Empty", false, {}};
    const std::string path = tempPath("skip");
    writeDataset(path, {body, marker, empty});
    const RtStructLoad load = readRtStruct(path);
    ASSERT_EQ(load.rois.size(), 3u);
    EXPECT_EQ(load.contours.rois[0].slices.size(), 2u);
    EXPECT_EQ(load.rois[0].contoursSkipped, 2u);
    EXPECT_TRUE(anyWarning(load, "POINT"));
    EXPECT_TRUE(anyWarning(load, "OPEN_PLANAR"));
    EXPECT_TRUE(load.contours.rois[1].slices.empty());
    EXPECT_TRUE(load.contours.rois[2].slices.empty());
    EXPECT_FALSE(load.rois[2].hasContourSequence);
    EXPECT_EQ(load.contours.findRoiNumber(3)->name, "Empty");
    fs::remove(path);
}

// Found by fuzzing: names that are not valid LO values (control
// characters, backslashes) are mended on reading, so that what loads can be
// written. Longer names than LO's 64 characters pass DCMTK's check both ways
// and are kept.
TEST(RtStruct, InvalidRoiNamesAreMendedAndWritable) {
    RoiSpec control{1, "Left\x01Lung", true, {square(0, 0, 10, 0)}};
    RoiSpec slash{2, "A\\B", true, {square(0, 0, 10, 0)}};
    RoiSpec longName{3, std::string(80, 'x'), true, {square(0, 0, 10, 0)}};
    const std::string path = tempPath("names"), again = tempPath("names-again");
    writeDataset(path, {control, slash, longName});
    const RtStructLoad load = readRtStruct(path);
    ASSERT_EQ(load.rois.size(), 3u);
    EXPECT_EQ(load.rois[0].name, "Left_Lung");
    EXPECT_EQ(load.rois[1].name, "A_B");
    EXPECT_EQ(load.rois[2].name, std::string(80, 'x'));
    EXPECT_TRUE(anyWarning(load, "not a valid LO value"));
    writeRtStruct(load.contours, again);
    const RtStructLoad back = readRtStruct(again);
    EXPECT_EQ(back.contours.rois[0].name, "Left_Lung");
    EXPECT_EQ(back.contours.rois[2].name, std::string(80, 'x'));
    fs::remove(path);
    fs::remove(again);
}

TEST(RtStruct, KeyholeContoursBecomeOuterAndHole) {
    // plastimatch's way: one path around the outer square, in along a
    // zero-width channel, around the hole and back out.
    RoiSpec roi;
    for (double z : {0.0, 3.0}) {
        ContourSpec c;
        for (Point2 p : {Point2{0, 0}, Point2{5, 0}, Point2{5, 3}, Point2{3, 3}, Point2{3, 7},
                         Point2{7, 7}, Point2{7, 3}, Point2{5, 3}, Point2{5, 0}, Point2{10, 0},
                         Point2{10, 10}, Point2{0, 10}})
            c.points.push_back({p.x, p.y, z});
        roi.contours.push_back(c);
    }
    const std::string path = tempPath("keyhole");
    writeDataset(path, {roi});
    const RtStructLoad load = readRtStruct(path);
    EXPECT_EQ(load.rois[0].holes, HoleConvention::Keyhole);
    for (const Slice& slice : load.contours.rois[0].slices) {
        ASSERT_EQ(slice.contours.size(), 2u);
        const std::vector<int> depth = nestingDepths(slice);
        for (std::size_t c = 0; c < 2; ++c)
            EXPECT_DOUBLE_EQ(signedArea(slice.contours[c]), depth[c] == 0 ? 100.0 : -16.0);
    }
    fs::remove(path);
}

TEST(RtStruct, SagittalStackGetsItsFrame) {
    RoiSpec roi;
    for (double x : {-4.0, -2.0, 0.0}) {
        ContourSpec c;
        for (int k = 0; k < 16; ++k) {
            const double a = 2 * M_PI * k / 16;
            c.points.push_back({x, 10 + 5 * std::cos(a), -20 + 8 * std::sin(a)});
        }
        roi.contours.push_back(c);
    }
    const std::string path = tempPath("sagittal");
    writeDataset(path, {roi});
    const RtStructLoad load = readRtStruct(path);
    const Roi& read = load.contours.rois[0];
    EXPECT_STREQ(read.frame.orientationName(), "sagittal");
    EXPECT_TRUE(anyWarning(load, "sagittal"));
    // The warning is the ROI's own (a command on another ROI leaves it out).
    for (const InputWarning& w : load.warnings)
        if (w.message.find("sagittal") != std::string::npos) EXPECT_EQ(w.roi, read.name);
    ASSERT_EQ(read.slices.size(), 3u);
    // Plane coordinates map back onto the written points.
    const Point2 first = read.slices[0].contours[0][0];
    const Vec3 patient = read.frame.toPatient({first.x, first.y, read.slices[0].zMm});
    EXPECT_NEAR(patient.x, -4.0, 1e-12);
    EXPECT_NEAR(std::hypot((patient.y - 10) / 5, (patient.z + 20) / 8), 1.0, 1e-12);
    // And the writer puts them back where they were.
    writeRtStruct(load.contours, path);
    const RtStructLoad again = readRtStruct(path);
    expectSameContours(load.contours, again.contours);
    fs::remove(path);
}

TEST(RtStruct, XorContoursAreReported) {
    RoiSpec roi;
    ContourSpec outer = square(0, 0, 10, 0), inner = square(3, 3, 4, 0);
    outer.type = inner.type = "CLOSEDPLANAR_XOR";
    roi.contours = {outer, inner};
    const std::string path = tempPath("xor");
    writeDataset(path, {roi});
    const RtStructLoad load = readRtStruct(path);
    EXPECT_EQ(load.rois[0].holes, HoleConvention::Xor);
    EXPECT_EQ(nestingDepths(load.contours.rois[0].slices[0]), (std::vector<int>{0, 1}));
    fs::remove(path);
}

double regionArea(const Slice& slice) {
    double area = 0;  // outer contours count positive, holes negative
    for (const Polygon& contour : slice.contours) area += signedArea(contour);
    return area;
}

// Found by fuzzing when CGAL's Boolean operations took the exclusive or
// (they require simple polygons): a contour crossing itself on a plane
// with another it crosses. The arrangement that reads planes now takes any
// contours; the region is the even-odd rule's, checked by brute force.
TEST(RtStruct, SelfCrossingContourOnAnXorPlaneIsReadByTheEvenOddRule) {
    RoiSpec roi;
    ContourSpec square0 = square(0, 0, 10, 0), bowtie;
    bowtie.points = {{5, 5, 0}, {15, 5, 0}, {1, 15, 0}, {5, 15, 0}};
    square0.type = bowtie.type = "CLOSEDPLANAR_XOR";
    roi.contours = {square0, bowtie};
    const std::string path = tempPath("xor-self-crossing");
    writeDataset(path, {roi});
    const RtStructLoad load = readRtStruct(path);
    const Roi& read = load.contours.rois[0];
    ASSERT_FALSE(read.defect.has_value()) << read.defect->what();
    ASSERT_EQ(read.slices.size(), 1u);
    EXPECT_EQ(read.reading.resolvedContours, 2u);
    const std::vector<Polygon> drawn{{{0, 0}, {10, 0}, {10, 10}, {0, 10}},
                                     {{5, 5}, {15, 5}, {1, 15}, {5, 15}}};
    for (double y = 0.37; y < 16; y += 0.5)
        for (double x = 0.29; x < 16; x += 0.5) {
            int crossings = 0, winding = 0;
            for (const Polygon& c : drawn)
                for (std::size_t i = 0; i < c.size(); ++i)
                    crossings += windingCrossing({x, y}, c[i], c[(i + 1) % c.size()]) != 0;
            for (const Polygon& c : read.slices[0].contours) winding += windingNumber({x, y}, c);
            EXPECT_EQ(crossings % 2 == 1, winding != 0) << x << " " << y;
        }
    fs::remove(path);
}

TEST(RtStruct, ContoursSharingEdgesOrCrossingCombineByExclusiveOr) {
    // A notch reaching the border, drawn as its own contour on the outer
    // contour's edge (as mask converters do), and two crossing squares.
    RoiSpec notch;
    notch.contours = {square(0, 0, 10, 0), square(4, 0, 2, 0), square(0, 0, 10, 3)};
    RoiSpec crossing{2, "Crossing", true, {square(0, 0, 10, 0), square(5, 5, 10, 0)}};
    const std::string path = tempPath("evenodd");
    writeDataset(path, {notch, crossing});
    const RtStructLoad load = readRtStruct(path);
    EXPECT_EQ(load.rois[0].holes, HoleConvention::Xor);
    EXPECT_EQ(load.contours.rois[0].reading.planesResolved, 1u);
    EXPECT_DOUBLE_EQ(regionArea(load.contours.rois[0].slices[0]), 96.0);
    EXPECT_DOUBLE_EQ(regionArea(load.contours.rois[0].slices[1]), 100.0);
    EXPECT_DOUBLE_EQ(regionArea(load.contours.rois[1].slices[0]), 150.0);
    fs::remove(path);
}

TEST(RtStruct, SlabThicknessIsKept) {
    RoiSpec roi;
    roi.contours = {square(0, 0, 10, 0)};
    roi.contours[0].slabThickness = "3.5";
    const std::string path = tempPath("slab");
    writeDataset(path, {roi});
    EXPECT_EQ(readRtStruct(path).contours.rois[0].slabThicknessMm, 3.5);
    fs::remove(path);
}

TEST(RtStruct, BrokenFilesNameWhatIsWrong) {
    const std::string path = tempPath("broken");
    RoiSpec roi;
    roi.contours = {square(0, 0, 10, 0), square(0, 0, 10, 3)};

    writeDataset(path, {roi}, "CT");
    EXPECT_NE(readError(path).find("(0008,0060) Modality is 'CT'"), std::string::npos);

    writeDataset(path, {roi}, "RTSTRUCT", false);
    EXPECT_NE(readError(path).find("missing (3006,0020) StructureSetROISequence"),
              std::string::npos);

    RoiSpec sevenValues = roi;
    sevenValues.contours[0].points.push_back({1, 2, std::nan("")});
    writeDataset(path, {sevenValues});
    EXPECT_NE(readError(path).find("(3006,0050) ContourData"), std::string::npos);

    RoiSpec tilted = roi;
    tilted.contours[1].points[2].z += 0.5;  // not planar, and not parallel
    writeDataset(path, {tilted});
    EXPECT_NE(readError(path).find("not planar"), std::string::npos);

    RoiSpec twice = roi;
    writeDataset(path, {roi, twice});
    EXPECT_NE(readError(path).find("(3006,0022) ROINumber 1 is used twice"), std::string::npos);

    // Truncated in the middle of the contour data.
    writeDataset(path, {roi});
    fs::resize_file(path, fs::file_size(path) - 40);
    EXPECT_FALSE(readError(path).empty());

    std::ofstream(path) << "not DICOM at all";
    EXPECT_NE(readError(path).find("not a readable DICOM file"), std::string::npos);
    fs::remove(path);
    EXPECT_NE(readError(path).find("no such file"), std::string::npos);
}

TEST(RtStruct, LimitsStopHostileSizes) {
    RoiSpec roi;
    roi.contours = {square(0, 0, 10, 0), square(0, 0, 10, 3)};
    const std::string path = tempPath("limits");
    writeDataset(path, {roi});
    RtStructLimits limits;
    limits.maxPointsTotal = 5;
    try {
        readRtStruct(path, limits);
        FAIL() << "no error";
    } catch (const InputError& e) {
        EXPECT_NE(e.problem().find("points"), std::string::npos) << e.what();
    }
    fs::remove(path);
}

TEST(RtStruct, DeepNestingIsRefusedBeforeDcmtkParsesIt) {
    // 100 000 nested sequences exhausted DCMTK's stack (SIGSEGV).
    const std::string path = tempPath("nesting");
    std::ofstream(path, std::ios::binary) << dfrecon::testing::nestedSequencesDicom(100000);
    EXPECT_NE(readError(path).find("sequences nested more than 64 deep"), std::string::npos)
        << readError(path);
    // At the limit the file goes on to DCMTK, which finds what else is wrong.
    std::ofstream(path, std::ios::binary) << dfrecon::testing::nestedSequencesDicom(64);
    EXPECT_NE(readError(path).find("StructureSetROISequence"), std::string::npos)
        << readError(path);
    fs::remove(path);
}

TEST(RtStruct, GarbageAfterTheMagicIsRefusedBeforeDcmtkParsesIt) {
    // 2 GiB of zeros after "DICM": DCMTK parses an empty element every 8
    // bytes, a minute a gigabyte.
    const std::string path = tempPath("zeros");
    std::ofstream(path, std::ios::binary)
        << std::string(128, '\0') << "DICM" << std::string(1 << 16, '\0');
    EXPECT_NE(readError(path).find("a command element (0000,0000) at byte 0 of the data set"),
              std::string::npos)
        << readError(path);
    // One empty element over and over.
    std::string repeated;
    for (int k = 0; k < 1000; ++k)
        repeated += std::string(
            "\x08\x00\x05\x00"
            "CS\0\0",
            8);
    std::ofstream(path, std::ios::binary) << std::string(128, '\0') << "DICM" << repeated;
    EXPECT_NE(readError(path).find("the element (0008,0005) twice in a row at byte 8"),
              std::string::npos)
        << readError(path);
    fs::remove(path);
}

TEST(RtStruct, ExclusiveOrWorkIsBoundedPerPlaneAndPerFile) {
    // Stars that all cross one another: 150 of them took 2.5 GB in CGAL,
    // then overflowed the stack.
    const std::string path = tempPath("stars");
    std::ofstream(path, std::ios::binary) << dfrecon::testing::crossingStarsRtStruct(6, 8, 2);
    const RtStructLoad load = readRtStruct(path);  // 6 contours, 240 crossings a plane
    EXPECT_EQ(load.contours.rois[0].reading.planesResolved, 2u);
    // Over a limit, the ROI is kept with its defect and no slices.
    RtStructLimits limits;
    limits.maxXorCrossings = 200;
    {
        const RtStructLoad limited = readRtStruct(path, limits);
        ASSERT_TRUE(limited.contours.rois[0].defect.has_value());
        const InputError& e = *limited.contours.rois[0].defect;
        EXPECT_EQ(e.file(), path);
        EXPECT_NE(e.problem().find("ROI 1 'stars', plane 0 mm: 6 contours meeting in more than "
                                   "194 places"),
                  std::string::npos)
            << e.what();
        EXPECT_TRUE(limited.contours.rois[0].slices.empty());
    }
    limits.maxXorCrossings = 1000;
    limits.maxXorCrossingsPerFile = 400;
    {
        const RtStructLoad limited = readRtStruct(path, limits);
        ASSERT_TRUE(limited.contours.rois[0].defect.has_value());
        const InputError& e = *limited.contours.rois[0].defect;
        EXPECT_NE(e.problem().find("plane 2 mm"), std::string::npos) << e.what();
        EXPECT_NE(e.problem().find("for the whole file"), std::string::npos) << e.what();
    }
    fs::remove(path);
}

// dicom3tools' IOD checker (installed by `make setup`) on `path`: its
// lines starting with "Error", and everything it said.
std::pair<std::size_t, std::string> dciodvfyErrors(const std::string& path) {
    EXPECT_EQ(std::system("command -v dciodvfy >/dev/null"), 0)
        << "dciodvfy missing: run make setup";
    const std::string report = path + ".txt";
    EXPECT_NE(std::system(("dciodvfy " + path + " >" + report + " 2>&1").c_str()), -1);
    std::ifstream in(report);
    std::string line, all;
    std::size_t errors = 0;
    while (std::getline(in, line)) {
        all += line + "\n";
        errors += line.rfind("Error", 0) == 0;
    }
    fs::remove(report);
    return {errors, all};
}

TEST(RtStruct, WrittenFilesPassDciodvfy) {
    // No errors; the only warnings are the empty Patient ID and Study ID of
    // a standalone set.
    const std::string path = tempPath("dciodvfy");
    writeRtStruct(ringsAndIslands(), path);
    const auto [errors, all] = dciodvfyErrors(path);
    EXPECT_EQ(errors, 0u) << all;
    EXPECT_NE(all.find("RTStructureSet"), std::string::npos) << all;  // it checked the right IOD
    fs::remove(path);
}

// ---- references to an image series (convert --like CTFOLDER) ---------------

namespace {

Roi squaresAt(const std::string& name, std::vector<double> zs) {
    Roi roi;
    roi.name = name;
    for (double z : zs) roi.slices.push_back({z, {{{0, 0}, {4, 0}, {4, 3}, {0, 3}}}});
    return roi;
}

std::string itemText(DcmItem& item, const DcmTagKey& key) {
    OFString value;
    item.findAndGetOFStringArray(key, value);
    return value.c_str();
}

DcmItem* itemOf(DcmItem& parent, const DcmTagKey& sequence, unsigned long index = 0) {
    DcmItem* item = nullptr;
    parent.findAndGetSequenceItem(sequence, item, long(index));
    return item;
}

unsigned long itemCount(DcmItem& parent, const DcmTagKey& key) {
    DcmSequenceOfItems* sequence = nullptr;
    return parent.findAndGetSequence(key, sequence).good() && sequence ? sequence->card() : 0;
}

}  // namespace

TEST(RtStruct, ContoursReferToTheImagesOfTheirPlanes) {
    dfrecon::testing::TempDir dir("rt-series");
    const std::string ct = dir / "ct";
    fs::create_directories(ct);
    dfrecon::testing::writeSyntheticSeries(ct, 5, 0, 2);  // z = 0, 2, 4, 6, 8
    ContourSet set;
    set.rois.push_back(squaresAt("tumour", {2, 4.004, 5}));  // z = 5 lies between images
    set.rois.back().colour = Rgb{1, 2, 3};
    set.rois.back().interpretedType = "PTV";
    set.rois.push_back(squaresAt("cord", {0, 8}));
    Roi sagittal = squaresAt("sagittal", {1});
    sagittal.frame = canonicalFrame(frameWithNormal({1, 0, 0}));
    set.rois.push_back(sagittal);

    RtStructWriteOptions options = referenceFrom(ct);
    ASSERT_TRUE(options.imageSeries.has_value());
    options.defaultRoiType = "OAR";
    const std::string path = dir / "rt.dcm";
    const RtStructWriteSummary summary = writeRtStruct(set, path, options);
    EXPECT_EQ(summary.contours, 6u);
    EXPECT_EQ(summary.contoursOnImages, 4u);
    EXPECT_EQ(summary.contoursOffImages, 2u);
    ASSERT_EQ(summary.warnings.size(), 2u);
    EXPECT_NE(summary.warnings[0].find("ROI 1 'tumour': 1 of 3 contours lie in no image's plane"),
              std::string::npos)
        << summary.warnings[0];
    EXPECT_NE(summary.warnings[1].find("ROI 3 'sagittal' lies in sagittal planes, not parallel"),
              std::string::npos)
        << summary.warnings[1];

    // Read back with dcmdata: every image listed under the series, each
    // contour on the image of its z.
    DcmFileFormat file;
    ASSERT_TRUE(file.loadFile(path.c_str()).good());
    DcmDataset& data = *file.getDataset();
    const DicomImageSeries& series = *options.imageSeries;
    EXPECT_EQ(itemText(data, DCM_StudyInstanceUID), series.patientStudy.studyInstanceUid);
    EXPECT_EQ(itemText(data, DCM_PatientID), "synthetic-series");
    EXPECT_EQ(itemText(data, DCM_PatientBirthDate), "19700101");
    EXPECT_EQ(itemText(data, DCM_StudyDate), "20240102");
    EXPECT_EQ(itemText(data, DCM_AccessionNumber), "A1");
    EXPECT_EQ(itemText(data, DCM_FrameOfReferenceUID), series.frameOfReferenceUid);
    DcmItem* frame = itemOf(data, DCM_ReferencedFrameOfReferenceSequence);
    ASSERT_NE(frame, nullptr);
    EXPECT_EQ(itemText(*frame, DCM_FrameOfReferenceUID), series.frameOfReferenceUid);
    DcmItem* study = itemOf(*frame, DCM_RTReferencedStudySequence);
    ASSERT_NE(study, nullptr);
    EXPECT_EQ(itemText(*study, DCM_ReferencedSOPInstanceUID), series.patientStudy.studyInstanceUid);
    DcmItem* referenced = itemOf(*study, DCM_RTReferencedSeriesSequence);
    ASSERT_NE(referenced, nullptr);
    EXPECT_EQ(itemText(*referenced, DCM_SeriesInstanceUID), series.seriesInstanceUid);
    ASSERT_EQ(itemCount(*referenced, DCM_ContourImageSequence), 5u);
    std::map<std::string, double> zOfImage;
    for (unsigned long i = 0; i < 5; ++i) {
        DcmItem* image = itemOf(*referenced, DCM_ContourImageSequence, i);
        EXPECT_EQ(itemText(*image, DCM_ReferencedSOPClassUID), UID_CTImageStorage);
        zOfImage[itemText(*image, DCM_ReferencedSOPInstanceUID)] = 2.0 * i;
    }
    const std::vector<std::vector<double>> imageZ = {{2, 4, NAN}, {0, 8}, {NAN}};
    for (unsigned long r = 0; r < 3; ++r) {
        DcmItem* roi = itemOf(data, DCM_ROIContourSequence, r);
        ASSERT_NE(roi, nullptr);
        ASSERT_EQ(itemCount(*roi, DCM_ContourSequence), imageZ[r].size());
        for (unsigned long c = 0; c < imageZ[r].size(); ++c) {
            DcmItem* contour = itemOf(*roi, DCM_ContourSequence, c);
            if (std::isnan(imageZ[r][c])) {
                EXPECT_EQ(itemCount(*contour, DCM_ContourImageSequence), 0u) << r << " " << c;
                continue;
            }
            ASSERT_EQ(itemCount(*contour, DCM_ContourImageSequence), 1u) << r << " " << c;
            const std::string uid =
                itemText(*itemOf(*contour, DCM_ContourImageSequence), DCM_ReferencedSOPInstanceUID);
            ASSERT_EQ(zOfImage.count(uid), 1u) << uid;
            EXPECT_EQ(zOfImage[uid], imageZ[r][c]) << r << " " << c;
        }
    }
    // Types and colours: the ROI's own, else the default type and the palette.
    const std::vector<std::string> types = {"PTV", "OAR", "OAR"};
    for (unsigned long r = 0; r < 3; ++r)
        EXPECT_EQ(
            itemText(*itemOf(data, DCM_RTROIObservationsSequence, r), DCM_RTROIInterpretedType),
            types[r]);
    EXPECT_EQ(itemText(*itemOf(data, DCM_ROIContourSequence, 0), DCM_ROIDisplayColor), "1\\2\\3");
    for (unsigned long r = 1; r < 3; ++r) {
        const Rgb c = kDefaultRoiColours[r - 1];  // the palette in order for ROIs without one
        EXPECT_EQ(itemText(*itemOf(data, DCM_ROIContourSequence, r), DCM_ROIDisplayColor),
                  std::to_string(c[0]) + "\\" + std::to_string(c[1]) + "\\" + std::to_string(c[2]));
    }

    // Our reader keeps what was written, types included.
    const RtStructLoad load = readRtStruct(path);
    ASSERT_EQ(load.contours.rois.size(), 3u);
    for (std::size_t r = 0; r < 3; ++r) EXPECT_EQ(load.contours.rois[r].interpretedType, types[r]);
    EXPECT_EQ(load.frameOfReferenceUid, series.frameOfReferenceUid);
    EXPECT_EQ(load.contours.rois[0].slices.size(), 3u);

    const auto [errors, all] = dciodvfyErrors(path);
    EXPECT_EQ(errors, 0u) << all;
    EXPECT_NE(all.find("RTStructureSet"), std::string::npos) << all;
}

TEST(RtStruct, AStructureSetWrittenLikeAnRtStructKeepsItsSeries) {
    // margin/combine write back beside their source RTSTRUCT: the new file
    // must refer to the same images, or the planning system cannot place it.
    dfrecon::testing::TempDir dir("rt-series-again");
    const std::string ct = dir / "ct";
    fs::create_directories(ct);
    dfrecon::testing::writeSyntheticSeries(ct, 5, 0, 2);
    ContourSet set;
    set.rois.push_back(squaresAt("tumour", {2, 4}));
    const RtStructWriteOptions fromCt = referenceFrom(ct);
    const std::string first = dir / "first.dcm";
    writeRtStruct(set, first, fromCt);
    const RtStructWriteOptions like = referenceFrom(first);
    EXPECT_FALSE(like.imageSeries.has_value());
    ASSERT_TRUE(like.referencedSeries.has_value());
    EXPECT_EQ(like.referencedSeries->seriesInstanceUid, fromCt.imageSeries->seriesInstanceUid);
    ASSERT_EQ(like.referencedSeries->images.size(), 5u);
    set.rois.push_back(squaresAt("tumour+3", {2, 4}));
    const std::string second = dir / "second.dcm";
    writeRtStruct(set, second, like);
    DcmFileFormat file;
    ASSERT_TRUE(file.loadFile(second.c_str()).good());
    DcmItem* frame = itemOf(*file.getDataset(), DCM_ReferencedFrameOfReferenceSequence);
    ASSERT_NE(frame, nullptr);
    EXPECT_EQ(itemText(*frame, DCM_FrameOfReferenceUID), fromCt.frameOfReferenceUid);
    DcmItem* study = itemOf(*frame, DCM_RTReferencedStudySequence);
    ASSERT_NE(study, nullptr);
    DcmItem* series = itemOf(*study, DCM_RTReferencedSeriesSequence);
    ASSERT_NE(series, nullptr);
    EXPECT_EQ(itemText(*series, DCM_SeriesInstanceUID), fromCt.imageSeries->seriesInstanceUid);
    ASSERT_EQ(itemCount(*series, DCM_ContourImageSequence), 5u);
    std::set<std::string> images, referenced;
    for (const DicomImage& image : fromCt.imageSeries->images) images.insert(image.sopInstanceUid);
    DcmSequenceOfItems* sequence = nullptr;
    ASSERT_TRUE(series->findAndGetSequence(DCM_ContourImageSequence, sequence).good());
    for (unsigned long i = 0; i < sequence->card(); ++i)
        referenced.insert(itemText(*sequence->getItem(i), DCM_ReferencedSOPInstanceUID));
    EXPECT_EQ(referenced, images);
    const auto [errors, all] = dciodvfyErrors(second);
    EXPECT_EQ(errors, 0u) << all;
}

TEST(RtStruct, DefaultColoursDifferFromEveryColourOfTheSet) {
    for (std::size_t i = 0; i < kDefaultRoiColours.size(); ++i)
        for (std::size_t j = 0; j < i; ++j) {
            const Rgb a = kDefaultRoiColours[i], b = kDefaultRoiColours[j];
            EXPECT_GE(std::abs(int(a[0]) - int(b[0])) + std::abs(int(a[1]) - int(b[1])) +
                          std::abs(int(a[2]) - int(b[2])),
                      100)
                << i << " " << j;
        }
    ContourSet set;
    for (int i = 0; i < 14; ++i) set.rois.push_back(squaresAt("r" + std::to_string(i), {0}));
    // One ROI with a colour of the palette: no other ROI gets it.
    set.rois[5].colour = kDefaultRoiColours[0];
    const std::string path = tempPath("palette");
    writeRtStruct(set, path);
    const RtStructLoad load = readRtStruct(path);
    std::vector<Rgb> seen;
    for (std::size_t i = 0; i < 14; ++i) {
        ASSERT_TRUE(load.contours.rois[i].colour.has_value());
        const Rgb got = *load.contours.rois[i].colour;
        // The palette in order, skipping the colour ROI 5 has, then others.
        if (i < 5) EXPECT_EQ(got, kDefaultRoiColours[i + 1]) << i;
        if (i == 5) EXPECT_EQ(got, kDefaultRoiColours[0]);
        EXPECT_EQ(std::count(seen.begin(), seen.end(), got), 0) << i;  // no two alike
        seen.push_back(got);
        EXPECT_EQ(load.contours.rois[i].interpretedType, "ORGAN");
    }
    fs::remove(path);
}

TEST(RtStruct, RoiTypeMustBeADefinedTerm) {
    EXPECT_TRUE(isRoiInterpretedType("GTV"));
    EXPECT_TRUE(isRoiInterpretedType("DOSE_MEASUREMENT"));
    EXPECT_FALSE(isRoiInterpretedType("gtv"));
    EXPECT_FALSE(isRoiInterpretedType(""));
    RtStructWriteOptions options;
    options.defaultRoiType = "TUMOUR";
    EXPECT_THROW(writeRtStruct(ringsAndIslands(), tempPath("badtype"), options),
                 std::invalid_argument);
    EXPECT_FALSE(fs::exists(tempPath("badtype")));
}

TEST(RtStruct, ReferenceFromAStructureSetTakesItsFrameAndStudy) {
    dfrecon::testing::TempDir dir("rt-like-rt");
    RtStructWriteOptions first;
    first.frameOfReferenceUid = "1.2.826.0.1.3680043.10.5";
    first.patientStudy.studyInstanceUid = "1.2.826.0.1.3680043.10.6";
    first.patientStudy.patientId = "P7";
    writeRtStruct(ringsAndIslands(), dir / "first.dcm", first);
    const RtStructWriteOptions like = referenceFrom(dir / "first.dcm");
    EXPECT_FALSE(like.imageSeries.has_value());
    EXPECT_EQ(like.frameOfReferenceUid, first.frameOfReferenceUid);
    EXPECT_EQ(like.patientStudy.studyInstanceUid, first.patientStudy.studyInstanceUid);
    EXPECT_EQ(like.patientStudy.patientId, "P7");
    std::ofstream(dir / "text.dcm") << "no DICOM here";
    EXPECT_THROW(referenceFrom(dir / "text.dcm"), InputError);
}

TEST(RtStruct, Latin1NamesAreReadAsUtf8) {
    // A planning system's ISO_IR 100 file: u-umlaut is the byte FC, and the
    // name must reach our UTF-8 output as C3 BC.
    const std::string path = tempPath("latin1");
    writeRtStruct(ringsAndIslands(), path);
    {
        DcmFileFormat file;
        ASSERT_TRUE(file.loadFile(path.c_str()).good());
        DcmDataset& data = *file.getDataset();
        ASSERT_TRUE(data.putAndInsertString(DCM_SpecificCharacterSet, "ISO_IR 100").good());
        DcmItem* roi = itemOf(data, DCM_StructureSetROISequence);
        ASSERT_NE(roi, nullptr);
        ASSERT_TRUE(roi->putAndInsertString(DCM_ROIName,
                                            "H\xfc"
                                            "fte")
                        .good());
        ASSERT_TRUE(file.saveFile(path.c_str(), EXS_LittleEndianExplicit).good());
    }
    const RtStructLoad load = readRtStruct(path);
    EXPECT_EQ(load.contours.rois[0].name,
              "H\xc3\xbc"
              "fte");
    EXPECT_TRUE(load.warnings.empty()) << load.warnings.front().toString();
    // and written back as UTF-8, which reads back the same.
    writeRtStruct(load.contours, path);
    EXPECT_EQ(readRtStruct(path).contours.rois[0].name,
              "H\xc3\xbc"
              "fte");
    fs::remove(path);
}

// plastimatch (and other writers) store a ContourData of more than about
// 1 300 points as VR UN in explicit VR files: the DS text does not fit a
// 16-bit length. Its bytes are still DS and are read as such, with a
// warning; any other VR is refused, naming the element.
TEST(RtStruct, ContourDataStoredAsUnIsReadAsDecimalStrings) {
    RoiSpec body;
    body.contours = {square(0, 0, 10, 0), square(0, 0, 10, 3)};
    body.contours[1].asUn = true;
    const std::string path = tempPath("un");
    writeDataset(path, {body});
    const RtStructLoad load = readRtStruct(path);
    ASSERT_EQ(load.contours.rois[0].slices.size(), 2u);
    const Polygon& read = load.contours.rois[0].slices[1].contours.at(0);
    ASSERT_EQ(read.size(), 4u);
    EXPECT_DOUBLE_EQ(read[2].x, 10);
    EXPECT_DOUBLE_EQ(read[2].y, 10);
    EXPECT_TRUE(anyWarning(load, "VR UN"));

    body.contours[1].unAs = EVR_OB;
    writeDataset(path, {body});
    EXPECT_NE(readError(path).find("has VR OB, expected DS"), std::string::npos);

    fs::remove(path);
}
