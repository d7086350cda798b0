// Label volumes: NRRD written by us and read back, NRRD and NIfTI files
// written independently (by hand, with zlib, with niftilib itself) read
// with the expected LPS geometry, and hostile files refused with an
// InputError rather than a crash or a huge allocation.
#include <gtest/gtest.h>
#include <nifti2_io.h>
#include <unistd.h>
#include <zlib.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <random>
#include <stdexcept>

#include "contours/InputError.hpp"
#include "io/labels/LabelVolume.hpp"
#include "tests/TempDir.hpp"

namespace dfrecon {
namespace {

namespace fs = std::filesystem;
using Direction = std::array<std::array<double, 3>, 3>;

using TempDir = ::dfrecon::testing::TempDir;

void writeFile(const std::string& path, const std::string& bytes) {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(bytes.data(), std::streamsize(bytes.size()));
    ASSERT_TRUE(out.good()) << path;
}

std::string readFile(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
}

// A gzip stream (not zlib's own wrapper), as NRRD's gzip encoding holds.
std::string gzip(const std::string& raw) {
    z_stream stream{};
    EXPECT_EQ(deflateInit2(&stream, Z_BEST_COMPRESSION, Z_DEFLATED, 15 + 16, 8, Z_DEFAULT_STRATEGY),
              Z_OK);
    std::string out(deflateBound(&stream, uLong(raw.size())) + 64, '\0');
    stream.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(raw.data()));
    stream.avail_in = uInt(raw.size());
    stream.next_out = reinterpret_cast<Bytef*>(out.data());
    stream.avail_out = uInt(out.size());
    EXPECT_EQ(deflate(&stream, Z_FINISH), Z_STREAM_END);
    out.resize(stream.total_out);
    deflateEnd(&stream);
    return out;
}

template <class T>
std::string bytesOf(const std::vector<T>& values) {
    return std::string(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(T));
}

// Rotation by `degrees` about `axis` (Rodrigues); column a is where the
// unit vector e_a goes, so direction[a] = column a.
Direction rotation(std::array<double, 3> axis, double degrees) {
    const double n = std::sqrt(axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]);
    for (double& c : axis) c /= n;
    const double t = degrees * M_PI / 180, c = std::cos(t), s = std::sin(t);
    const auto& [x, y, z] = axis;
    const double r[3][3] = {
        {c + x * x * (1 - c), x * y * (1 - c) - z * s, x * z * (1 - c) + y * s},
        {y * x * (1 - c) + z * s, c + y * y * (1 - c), y * z * (1 - c) - x * s},
        {z * x * (1 - c) - y * s, z * y * (1 - c) + x * s, c + z * z * (1 - c)}};
    Direction d;
    for (int a = 0; a < 3; ++a)
        for (int row = 0; row < 3; ++row) d[a][row] = r[row][a];
    return d;
}

VolumeGeometry obliqueGeometry() {
    VolumeGeometry g;
    g.size = {17, 11, 9};
    g.spacingMm = {0.7, 1.3, 2.5};
    g.originMm = {-120.25, 33.5, 7.125};
    g.direction = rotation({1, 2, 3}, 30);
    return g;
}

void expectGeometryNear(const VolumeGeometry& actual, const VolumeGeometry& expected,
                        double tolerance) {
    EXPECT_EQ(actual.size, expected.size);
    for (int a = 0; a < 3; ++a) {
        EXPECT_NEAR(actual.spacingMm[a], expected.spacingMm[a], tolerance) << "axis " << a;
        EXPECT_NEAR(actual.originMm[a], expected.originMm[a], tolerance) << "coordinate " << a;
        for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(actual.direction[a][c], expected.direction[a][c], tolerance)
                << "direction " << a << " coordinate " << c;
    }
}

// Reading `path` must fail with an InputError naming the file and saying
// `expected`.
void expectInputError(const std::string& path, const std::string& expected) {
    try {
        readLabelVolume(path);
        ADD_FAILURE() << path << ": read without error, expected \"" << expected << "\"";
    } catch (const InputError& e) {
        EXPECT_EQ(e.file(), path);
        EXPECT_NE(e.problem().find(expected), std::string::npos)
            << "problem: \"" << e.problem() << "\", expected \"" << expected << "\"";
    }
}

// A NIfTI-1 file written by niftilib: `dims` = (nx, ny, nz, ...), samples
// in `bytes` (host order), transforms set by `setup`.
void writeNifti(const std::string& path, const std::vector<std::int64_t>& dims, int datatype,
                const std::string& bytes, const std::function<void(nifti_image&)>& setup) {
    std::int64_t d[8] = {std::int64_t(dims.size()), 1, 1, 1, 1, 1, 1, 1};
    for (std::size_t a = 0; a < dims.size(); ++a) d[a + 1] = dims[a];
    nifti_image* image = nifti_make_new_nim(d, datatype, 1);
    ASSERT_NE(image, nullptr);
    ASSERT_EQ(std::size_t(image->nvox) * std::size_t(image->nbyper), bytes.size());
    std::memcpy(image->data, bytes.data(), bytes.size());
    ASSERT_EQ(nifti_set_filenames(image, path.c_str(), 0, 1), 0);
    image->nifti_type = NIFTI_FTYPE_NIFTI1_1;
    image->qform_code = 0;
    image->sform_code = 0;
    setup(*image);
    nifti_image_write(image);
    nifti_image_free(image);
    ASSERT_TRUE(fs::exists(path)) << path;
}

TEST(VolumeGeometry, WorldOfIndexFollowsOriginSpacingAndDirections) {
    VolumeGeometry g;
    g.size = {4, 5, 6};
    g.spacingMm = {2, 3, 4};
    g.originMm = {10, 20, 30};
    // Axis 0 runs posterior→anterior (−y), axis 1 along +x, axis 2 along +z.
    g.direction = {{{0, -1, 0}, {1, 0, 0}, {0, 0, 1}}};
    EXPECT_EQ(g.voxelCount(), 120u);
    EXPECT_EQ(g.linearIndex(1, 2, 3), std::size_t((3 * 5 + 2) * 4 + 1));
    const Vec3 p = g.worldOfIndex(1.5, -1, 2);
    EXPECT_DOUBLE_EQ(p.x, 10 - 3);
    EXPECT_DOUBLE_EQ(p.y, 20 - 3);
    EXPECT_DOUBLE_EQ(p.z, 30 + 8);
    const auto index = g.indexOfWorld(p);
    EXPECT_NEAR(index[0], 1.5, 1e-12);
    EXPECT_NEAR(index[1], -1, 1e-12);
    EXPECT_NEAR(index[2], 2, 1e-12);
}

TEST(VolumeGeometry, IndexOfWorldInvertsWorldOfIndexOnObliqueAxes) {
    const VolumeGeometry g = obliqueGeometry();
    const Vec3 origin = g.worldOfIndex(0, 0, 0);
    EXPECT_DOUBLE_EQ(origin.x, g.originMm[0]);
    EXPECT_DOUBLE_EQ(origin.z, g.originMm[2]);
    std::mt19937 random(7);
    std::uniform_real_distribution<double> coordinate(-3, 20);
    for (int n = 0; n < 200; ++n) {
        const double i = coordinate(random), j = coordinate(random), k = coordinate(random);
        const auto index = g.indexOfWorld(g.worldOfIndex(i, j, k));
        EXPECT_NEAR(index[0], i, 1e-9);
        EXPECT_NEAR(index[1], j, 1e-9);
        EXPECT_NEAR(index[2], k, 1e-9);
    }
    // One step along axis 1 moves spacing[1] along direction[1].
    const Vec3 step = g.worldOfIndex(0, 1, 0) - origin;
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(step[c], g.spacingMm[1] * g.direction[1][c], 1e-12);

    VolumeGeometry flat = g;
    flat.direction[2] = flat.direction[0];
    EXPECT_THROW(flat.indexOfWorld({0, 0, 0}), std::domain_error);
}

TEST(LabelVolume, MaskRoundTripsThroughNrrdWithObliqueAnisotropicGeometry) {
    TempDir dir("labelvolume");
    const VolumeGeometry geometry = obliqueGeometry();
    std::mt19937 random(2024);
    std::bernoulli_distribution inside(0.3);
    std::vector<std::uint8_t> mask(geometry.voxelCount());
    for (auto& m : mask) m = inside(random) ? 1 : 0;
    const std::string path = dir / "mask.nrrd";
    writeMaskNrrd(path, geometry, mask);

    // What 3D Slicer needs to place it: LPS, directions, origin, kinds.
    const std::string text = readFile(path);
    const std::string header = text.substr(0, text.find("\n\n"));
    EXPECT_EQ(header.rfind("NRRD000", 0), 0u);
    EXPECT_NE(header.find("type: unsigned char"), std::string::npos) << header;
    EXPECT_NE(header.find("space: left-posterior-superior"), std::string::npos) << header;
    EXPECT_NE(header.find("kinds: domain domain domain"), std::string::npos) << header;
    EXPECT_NE(header.find("encoding: gzip"), std::string::npos) << header;
    EXPECT_NE(header.find("space origin: (-120.25,33.5,7.125)"), std::string::npos) << header;

    const LabelVolume read = readLabelVolume(path);
    expectGeometryNear(read.geometry, geometry, 1e-12);
    ASSERT_EQ(read.labels.size(), mask.size());
    for (std::size_t n = 0; n < mask.size(); ++n)
        ASSERT_EQ(read.labels[n], mask[n]) << "voxel " << n;
}

TEST(LabelVolume, LabelMapRoundTripsInTheNarrowestType) {
    TempDir dir("labelvolume");
    LabelVolume volume;
    volume.geometry = obliqueGeometry();
    volume.geometry.size = {5, 4, 3};
    for (std::size_t n = 0; n < volume.geometry.voxelCount(); ++n)
        volume.labels.push_back(std::int32_t(n * 7) % 300);
    writeLabelNrrd(dir / "ushort.nrrd", volume);
    EXPECT_NE(readFile(dir / "ushort.nrrd").find("type: unsigned short"), std::string::npos);
    EXPECT_EQ(readLabelVolume(dir / "ushort.nrrd").labels, volume.labels);

    volume.labels[3] = -5;
    volume.labels[7] = 2000000000;
    writeLabelNrrd(dir / "int.nrrd", volume);
    EXPECT_NE(readFile(dir / "int.nrrd").find("type: int"), std::string::npos);
    const LabelVolume read = readLabelVolume(dir / "int.nrrd");
    EXPECT_EQ(read.labels, volume.labels);
    expectGeometryNear(read.geometry, volume.geometry, 1e-12);
}

TEST(LabelVolume, LayersRoundTripAsSlicersFourDimensionalSegmentation) {
    // Two overlapping segments on two layers, written as 3D Slicer writes
    // them (a first axis of kind list, no space direction) and read back.
    TempDir dir("labelvolume");
    LabelVolume volume;
    volume.geometry = obliqueGeometry();
    volume.geometry.size = {6, 5, 4};
    const std::size_t voxels = volume.geometry.voxelCount();
    volume.layerCount = 2;
    volume.labels.assign(2 * voxels, 0);
    for (std::size_t n = 0; n < voxels; ++n) {
        volume.labels[n] = n % 3 == 0 ? 7 : 0;      // layer 0
        volume.labels[voxels + n] = n % 2 ? 9 : 0;  // layer 1, overlapping it
    }
    const std::string path = dir / "two.seg.nrrd";
    writeLabelNrrd(path, volume);
    const std::string text = readFile(path);
    const std::string header = text.substr(0, text.find("\n\n"));
    EXPECT_NE(header.find("dimension: 4"), std::string::npos) << header;
    EXPECT_NE(header.find("sizes: 2 6 5 4"), std::string::npos) << header;
    EXPECT_NE(header.find("kinds: list domain domain domain"), std::string::npos) << header;
    EXPECT_NE(header.find("space directions: none ("), std::string::npos) << header;
    const LabelVolume read = readLabelVolume(path);
    EXPECT_EQ(read.layerCount, 2);
    expectGeometryNear(read.geometry, volume.geometry, 1e-12);
    EXPECT_EQ(read.labels, volume.labels);
    // NIfTI has no layers.
    EXPECT_THROW(writeLabelVolume(dir / "two.nii.gz", volume), std::invalid_argument);
}

TEST(LabelVolume, KeyValuePairsRoundTripThroughNrrd) {
    TempDir dir("labelvolume");
    LabelVolume volume;
    volume.geometry.size = {3, 2, 2};
    volume.labels.assign(12, 1);
    volume.keyValues = {{"Segment0_Name", "Left lung"}, {"Segment0_Color", "0.5 0 1"}};
    writeLabelNrrd(dir / "s.seg.nrrd", volume);
    EXPECT_EQ(readLabelVolume(dir / "s.seg.nrrd").keyValues, volume.keyValues);
}

TEST(LabelVolume, LabelMapRoundTripsThroughNiftiWithObliqueGeometry) {
    // NIfTI-1 keeps the sform and qform in float32: within 1e-7 relative,
    // a few nanometres at patient coordinates.
    TempDir dir("labelvolume");
    LabelVolume volume;
    volume.geometry = obliqueGeometry();
    for (std::size_t n = 0; n < volume.geometry.voxelCount(); ++n)
        volume.labels.push_back(std::int32_t(n * 7) % 300 - 20);
    for (const char* name : {"v.nii", "v.nii.gz"}) {
        writeLabelVolume(dir / name, volume);
        const LabelVolume read = readLabelVolume(dir / name);
        EXPECT_EQ(read.labels, volume.labels) << name;
        expectGeometryNear(read.geometry, volume.geometry, 1e-4);
    }
    // The qform alone (readers that ignore the sform) gives the same grid.
    nifti_image* image = nifti_image_read((dir / "v.nii").c_str(), 0);
    ASSERT_NE(image, nullptr);
    EXPECT_EQ(image->sform_code, NIFTI_XFORM_SCANNER_ANAT);
    EXPECT_EQ(image->qform_code, NIFTI_XFORM_SCANNER_ANAT);
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 4; ++c)
            EXPECT_NEAR(image->qto_xyz.m[r][c], image->sto_xyz.m[r][c], 1e-4) << r << c;
    nifti_image_free(image);
    EXPECT_THROW(writeLabelVolume(dir / "v.mha", volume), std::invalid_argument);
}

TEST(LabelVolume, ReadsAHandWrittenGzipNrrdInRasSpaceAsLps) {
    TempDir dir("labelvolume");
    // 3 x 2 x 2 big-endian shorts, n·100 − 500 at position n.
    std::string samples;
    for (int n = 0; n < 12; ++n) {
        const std::uint16_t v = std::uint16_t(std::int16_t(n * 100 - 500));
        samples += char(v >> 8);
        samples += char(v & 0xff);
    }
    const std::string path = dir / "ras.nrrd";
    writeFile(path,
              "NRRD0004\n"
              "# written by hand for the test\n"
              "type: short\n"
              "dimension: 3\n"
              "space: right-anterior-superior\n"
              "sizes: 3 2 2\n"
              "space directions: (0,2,0) (-1.5,0,0) (0,0,4)\n"
              "space origin: (10,-20,30)\n"
              "endian: big\n"
              "encoding: gzip\n"
              "\n" +
                  gzip(samples));
    const LabelVolume volume = readLabelVolume(path);
    // RAS → LPS negates x and y of every direction and of the origin.
    VolumeGeometry expected;
    expected.size = {3, 2, 2};
    expected.spacingMm = {2, 1.5, 4};
    expected.originMm = {-10, 20, 30};
    expected.direction = {{{0, -1, 0}, {1, 0, 0}, {0, 0, 1}}};
    expectGeometryNear(volume.geometry, expected, 1e-15);
    ASSERT_EQ(volume.labels.size(), 12u);
    for (int n = 0; n < 12; ++n) EXPECT_EQ(volume.labels[n], n * 100 - 500);
}

TEST(LabelVolume, ReadsADetachedRawNrrdWithoutSpaceAsIdentityAxes) {
    TempDir dir("labelvolume");
    std::vector<std::uint8_t> samples(4 * 3 * 2);
    for (std::size_t n = 0; n < samples.size(); ++n) samples[n] = std::uint8_t(n % 5);
    writeFile(dir / "labels.raw", bytesOf(samples));
    writeFile(dir / "labels.nhdr",
              "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 4 3 2\nspacings: 0.5 0.75 2\n"
              "encoding: raw\ndata file: labels.raw\n");
    const LabelVolume volume = readLabelVolume(dir / "labels.nhdr");
    VolumeGeometry expected;
    expected.size = {4, 3, 2};
    expected.spacingMm = {0.5, 0.75, 2};
    expectGeometryNear(volume.geometry, expected, 0);
    EXPECT_EQ(volume.labels, std::vector<std::int32_t>(samples.begin(), samples.end()));

    // No spacing at all: 1 mm.
    writeFile(
        dir / "bare.nrrd",
        "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 4 3 2\nencoding: raw\n\n" + bytesOf(samples));
    EXPECT_EQ(readLabelVolume(dir / "bare.nrrd").geometry.spacingMm,
              (std::array<double, 3>{1, 1, 1}));
}

TEST(LabelVolume, ReadsNiftiSformFromRasToLps) {
    TempDir dir("labelvolume");
    std::vector<std::int16_t> samples(3 * 4 * 5);
    for (std::size_t n = 0; n < samples.size(); ++n) samples[n] = std::int16_t(n % 7) - 1;
    const std::string path = dir / "sform.nii";
    writeNifti(path, {3, 4, 5}, DT_INT16, bytesOf(samples), [](nifti_image& image) {
        // Columns in RAS: i steps 0.8 mm posterior (−y), j 1.25 mm superior,
        // k 2.5 mm right (+x); voxel 0 is centred at (−50, 40, −12).
        const double sform[3][4] = {{0, 0, 2.5, -50}, {-0.8, 0, 0, 40}, {0, 1.25, 0, -12}};
        image.sform_code = NIFTI_XFORM_SCANNER_ANAT;
        for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 4; ++c) image.sto_xyz.m[r][c] = sform[r][c];
        // A different qform, which must lose to the sform.
        image.qform_code = NIFTI_XFORM_SCANNER_ANAT;
        image.qoffset_x = 99;
    });
    const LabelVolume volume = readLabelVolume(path);
    VolumeGeometry expected;
    expected.size = {3, 4, 5};
    expected.spacingMm = {0.8, 1.25, 2.5};
    expected.originMm = {50, -40, -12};
    expected.direction = {{{0, 1, 0}, {0, 0, 1}, {-1, 0, 0}}};
    // NIfTI-1 stores the sform in single precision.
    expectGeometryNear(volume.geometry, expected, 1e-6);
    EXPECT_EQ(volume.labels, std::vector<std::int32_t>(samples.begin(), samples.end()));
}

TEST(LabelVolume, ReadsGzipNiftiQformAndScaling) {
    TempDir dir("labelvolume");
    std::vector<std::uint8_t> samples(2 * 3 * 2);
    for (std::size_t n = 0; n < samples.size(); ++n) samples[n] = std::uint8_t(n);
    const std::string path = dir / "qform.nii.gz";
    writeNifti(path, {2, 3, 2}, DT_UINT8, bytesOf(samples), [](nifti_image& image) {
        // 90° about +z (quaternion (cos 45°, 0, 0, sin 45°)), pixdim 2, 3, 4.
        image.qform_code = NIFTI_XFORM_SCANNER_ANAT;
        image.quatern_b = image.quatern_c = 0;
        image.quatern_d = std::sqrt(0.5);
        image.qfac = 1;
        image.qoffset_x = 10;
        image.qoffset_y = 20;
        image.qoffset_z = 30;
        image.dx = image.pixdim[1] = 2;
        image.dy = image.pixdim[2] = 3;
        image.dz = image.pixdim[3] = 4;
        image.scl_slope = 2;
        image.scl_inter = -1;
    });
    ASSERT_EQ(readFile(path).substr(0, 2), std::string("\x1f\x8b"));  // really gzip
    const LabelVolume volume = readLabelVolume(path);
    // In RAS, i → +y·2, j → −x·3, k → +z·4, voxel 0 at (10, 20, 30).
    VolumeGeometry expected;
    expected.size = {2, 3, 2};
    expected.spacingMm = {2, 3, 4};
    expected.originMm = {-10, -20, 30};
    expected.direction = {{{0, -1, 0}, {1, 0, 0}, {0, 0, 1}}};
    expectGeometryNear(volume.geometry, expected, 1e-6);
    for (std::size_t n = 0; n < samples.size(); ++n)
        EXPECT_EQ(volume.labels[n], 2 * int(n) - 1) << "voxel " << n;
}

TEST(LabelVolume, RefusesMissingAndUnknownFiles) {
    TempDir dir("labelvolume");
    expectInputError(dir / "absent.nrrd", "no such file");
    expectInputError(dir / "absent.nii.gz", "no such file");
    writeFile(dir / "volume.mha", "ObjectType = Image\n");
    expectInputError(dir / "volume.mha", "unknown label volume format");
    expectInputError(dir / "", "unknown label volume format");
    fs::create_directories(dir / "folder.nrrd");
    expectInputError(dir / "folder.nrrd", "not a regular file");
    writeFile(dir / "text.nrrd", "P5\n2 2\n255\nabcd");
    expectInputError(dir / "text.nrrd", "not a NRRD file");
    writeFile(dir / "text.nii", std::string(400, 'x'));
    expectInputError(dir / "text.nii", "not a readable NIfTI file");
}

TEST(LabelVolume, RefusesImagesThatAreNotThreeDimensional) {
    TempDir dir("labelvolume");
    writeFile(dir / "flat.nrrd",
              "NRRD0004\ntype: uint8\ndimension: 2\nsizes: 4 4\nencoding: raw\n\n" +
                  std::string(16, '\1'));
    expectInputError(dir / "flat.nrrd", "2-D image");
    // Four axes are layers only when the first is a list, and not too many.
    writeFile(dir / "time.nrrd",
              "NRRD0004\ntype: uint8\ndimension: 4\nsizes: 2 2 2 3\nencoding: raw\n\n" +
                  std::string(24, '\1'));
    expectInputError(dir / "time.nrrd", "4-D image");
    writeFile(dir / "layers.nrrd",
              "NRRD0004\ntype: uint8\ndimension: 4\nsizes: 300 2 2 2\nkinds: list domain "
              "domain domain\nencoding: raw\n\n" +
                  std::string(2400, '\1'));
    expectInputError(dir / "layers.nrrd", "300 layers");
    writeNifti(dir / "flat.nii", {4, 4}, DT_UINT8, std::string(16, '\1'), [](nifti_image&) {});
    expectInputError(dir / "flat.nii", "2-D image");
    writeNifti(dir / "series.nii", {2, 2, 2, 3}, DT_UINT8, std::string(24, '\1'),
               [](nifti_image&) {});
    expectInputError(dir / "series.nii", "4-D image");
    // A fourth axis of size 1 is still a volume.
    writeNifti(dir / "single.nii", {2, 2, 2, 1}, DT_UINT8, std::string(8, '\1'),
               [](nifti_image&) {});
    EXPECT_EQ(readLabelVolume(dir / "single.nii").labels, std::vector<std::int32_t>(8, 1));
}

TEST(LabelVolume, RefusesTruncatedData) {
    TempDir dir("labelvolume");
    const std::string header =
        "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 10 10 10\nencoding: raw\n\n";
    writeFile(dir / "raw.nrrd", header + std::string(1000, '\2'));
    EXPECT_EQ(readLabelVolume(dir / "raw.nrrd").labels.size(), 1000u);
    writeFile(dir / "raw.nrrd", header + std::string(100, '\2'));
    expectInputError(dir / "raw.nrrd", "truncated");

    // A valid gzip NRRD cut in the middle of its compressed data.
    VolumeGeometry geometry;
    geometry.size = {40, 30, 20};
    std::vector<std::uint8_t> mask(geometry.voxelCount());
    std::mt19937 random(5);
    for (auto& m : mask) m = std::uint8_t(random() % 2);
    writeMaskNrrd(dir / "cut.nrrd", geometry, mask);
    fs::resize_file(dir / "cut.nrrd", fs::file_size(dir / "cut.nrrd") * 2 / 3);
    expectInputError(dir / "cut.nrrd", "cannot read the data");

    // A detached header whose data file is short.
    writeFile(dir / "short.raw", std::string(999, '\0'));
    writeFile(dir / "short.nhdr",
              "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 10 10 10\nencoding: raw\n"
              "data file: short.raw\n");
    expectInputError(dir / "short.nhdr", "truncated: the data file can hold at most 999 bytes");

    // A NIfTI file cut after its header.
    writeNifti(dir / "cut.nii", {10, 10, 10}, DT_INT16, std::string(2000, '\0'),
               [](nifti_image&) {});
    fs::resize_file(dir / "cut.nii", 352 + 500);
    expectInputError(dir / "cut.nii", "truncated");
}

TEST(LabelVolume, RefusesAbsurdSizesBeforeAllocating) {
    TempDir dir("labelvolume");
    // 10^15 voxels: over the cap.
    writeFile(dir / "huge.nrrd",
              "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 100000 100000 100000\n"
              "encoding: raw\n\n");
    expectInputError(dir / "huge.nrrd", "more than the limit");
    // Sizes whose product overflows 64 bits.
    writeFile(dir / "overflow.nrrd",
              "NRRD0004\ntype: uint8\ndimension: 3\n"
              "sizes: 4294967296 4294967296 4294967296\nencoding: raw\n\n");
    expectInputError(dir / "overflow.nrrd", "too large");  // teem catches this one itself
    // Within the memory budget (10^8 voxels, 500 MB with their labels) but
    // with no data: refused by the size check, which runs before anything is
    // allocated.
    writeFile(dir / "empty.nrrd",
              "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 1000 1000 100\nencoding: raw\n\n");
    expectInputError(dir / "empty.nrrd", "truncated: the file can hold at most 0 bytes");
    writeFile(dir / "bomb.nrrd",
              "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 1000 1000 100\nencoding: gzip\n\n" +
                  gzip(std::string(1000, '\0')));
    expectInputError(dir / "bomb.nrrd", "truncated");
    writeNifti(dir / "huge.nii", {2, 2, 2}, DT_UINT8, std::string(8, '\0'), [](nifti_image&) {});
    // Patch dim[1..3] of the NIfTI-1 header (int16 at byte 42) to 30000 each.
    std::string bytes = readFile(dir / "huge.nii");
    for (int a = 1; a <= 3; ++a) {
        const std::int16_t big = 30000;
        std::memcpy(&bytes[40 + 2 * a], &big, 2);
    }
    writeFile(dir / "huge.nii", bytes);
    expectInputError(dir / "huge.nii", "more than the limit");
}

TEST(LabelVolume, RefusesVolumesOverTheMemoryBudgetBeforeAllocating) {
    TempDir dir("labelvolume");
    // 10^9 voxels: under the voxel cap, but 5 GB with their labels. A
    // megabyte of gzip can hold them, so the header alone decides.
    writeFile(dir / "bomb.nrrd",
              "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 1000 1000 1000\nencoding: gzip\n\n" +
                  gzip(std::string(1 << 20, '\0')));
    expectInputError(dir / "bomb.nrrd", "over the 2048 MiB a label volume may take");
    writeNifti(dir / "bomb.nii", {2, 2, 2}, DT_UINT8, std::string(8, '\0'), [](nifti_image&) {});
    std::string bytes = readFile(dir / "bomb.nii");
    for (int a = 1; a <= 3; ++a) {
        const std::int16_t size = 1000;
        std::memcpy(&bytes[40 + 2 * a], &size, 2);
    }
    writeFile(dir / "bomb.nii.gz", gzip(bytes + std::string(1 << 20, '\0')));
    expectInputError(dir / "bomb.nii.gz", "over the 2048 MiB a label volume may take");
    // int32 samples: 4 + 4 bytes a voxel; 300 · 10^6 voxels are 2.4 GB.
    writeFile(dir / "wide.nrrd",
              "NRRD0004\ntype: int32\ndimension: 3\nsizes: 1000 1000 300\nendian: little\n"
              "encoding: gzip\n\n" +
                  gzip(std::string(1000, '\0')));
    expectInputError(dir / "wide.nrrd", "300000000 voxels of 4 byte(s)");
}

TEST(LabelVolume, RefusesGeometryNoPatientHas) {
    TempDir dir("labelvolume");
    const std::string start = "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 2 2 2\nencoding: raw\n";
    const std::string data = "\n" + std::string(8, '\0');
    // teem reads nan as "not given": it used to become 1 mm.
    writeFile(dir / "nan.nrrd", start + "spacings: 1 nan 1\n" + data);
    expectInputError(dir / "nan.nrrd", "spacings holds nan");
    writeFile(dir / "nan-origin.nrrd", start +
                                           "space: left-posterior-superior\n"
                                           "space directions: (1,0,0) (0,1,0) (0,0,1)\n"
                                           "space origin: (nan,nan,nan)\n" +
                                           data);
    expectInputError(dir / "nan-origin.nrrd", "space origin holds nan");
    writeFile(dir / "far.nrrd", start +
                                    "space: left-posterior-superior\n"
                                    "space directions: (1,0,0) (0,1,0) (0,0,1)\n"
                                    "space origin: (1e30,0,0)\n" +
                                    data);
    expectInputError(dir / "far.nrrd", "beyond the limit of ±1000000 mm");
    writeFile(dir / "long.nrrd", start + "spacings: 1 1e308 1\n" + data);
    expectInputError(dir / "long.nrrd", "beyond the limit of ±1000000 mm");
    writeFile(dir / "tiny.nrrd", start + "spacings: 1 1e-9 1\n" + data);
    expectInputError(dir / "tiny.nrrd", "axis 1 has spacing 1e-09 mm");
    // niftilib makes a pixdim that is not positive 1 mm, for the qform as
    // for no transform at all.
    for (const float pixdim : {0.0f, -1.0f, NAN, INFINITY})
        for (const int qform : {0, 1}) {
            writeNifti(dir / "pixdim.nii", {2, 2, 2}, DT_UINT8, std::string(8, '\0'),
                       [&](nifti_image& i) {
                           i.qform_code = qform;
                           i.sform_code = 0;
                       });
            std::string bytes = readFile(dir / "pixdim.nii");
            std::memcpy(&bytes[76 + 4 * 2], &pixdim, 4);  // pixdim[2]
            writeFile(dir / "pixdim.nii", bytes);
            expectInputError(dir / "pixdim.nii", "pixdim[2] is");
        }
    writeNifti(dir / "sform.nii", {2, 2, 2}, DT_UINT8, std::string(8, '\0'), [](nifti_image& i) {
        i.sform_code = NIFTI_XFORM_SCANNER_ANAT;
        i.sto_xyz = {};
        for (int a = 0; a < 3; ++a) i.sto_xyz.m[a][a] = 1;
        i.sto_xyz.m[0][3] = 1e38;
    });
    expectInputError(dir / "sform.nii", "beyond the limit of ±1000000 mm");
}

TEST(LabelVolume, RefusesVoxOffsetsOutsideTheFile) {
    TempDir dir("labelvolume");
    for (const float offset : {1e20f, 100.0f, 4096.0f, NAN}) {
        writeNifti(dir / "offset.nii", {2, 2, 2}, DT_UINT8, std::string(8, '\1'),
                   [](nifti_image&) {});
        std::string bytes = readFile(dir / "offset.nii");
        std::memcpy(&bytes[108], &offset, 4);  // vox_offset
        writeFile(dir / "offset.nii", bytes);
        expectInputError(dir / "offset.nii", offset == 4096.0f ? "truncated" : "vox_offset");
    }
}

TEST(LabelVolume, RefusesNanVoxelsThatNiftilibWouldReadAsZero) {
    TempDir dir("labelvolume");
    for (const float bad : {NAN, INFINITY}) {
        std::vector<float> samples(8, 1.0f);
        samples[5] = bad;
        writeNifti(dir / "nan.nii", {2, 2, 2}, DT_FLOAT32, bytesOf(samples), [](nifti_image&) {});
        expectInputError(dir / "nan.nii", "voxel (1, 0, 1) holds NaN or infinity");
        writeFile(dir / "nan.nii.gz", gzip(readFile(dir / "nan.nii")));
        expectInputError(dir / "nan.nii.gz", "voxel (1, 0, 1) holds NaN or infinity");
    }
    std::vector<double> samples(8, 2.0);
    samples[7] = NAN;
    writeNifti(dir / "nan64.nii", {2, 2, 2}, DT_FLOAT64, bytesOf(samples), [](nifti_image&) {});
    expectInputError(dir / "nan64.nii", "voxel (1, 1, 1) holds NaN");
}

TEST(LabelVolume, RefusesLabelsThatAreNotInt32Integers) {
    TempDir dir("labelvolume");
    const std::string header =
        "NRRD0004\ndimension: 3\nsizes: 2 1 1\nendian: little\n"
        "encoding: raw\n";
    writeFile(dir / "half.nrrd", header + "type: float\n\n" + bytesOf(std::vector<float>{1, 0.5f}));
    expectInputError(dir / "half.nrrd", "voxel (1, 0, 0) holds 0.5, not an integer label");
    writeFile(dir / "whole.nrrd",
              header + "type: double\n\n" + bytesOf(std::vector<double>{3, -4}));
    EXPECT_EQ(readLabelVolume(dir / "whole.nrrd").labels, (std::vector<std::int32_t>{3, -4}));
    writeFile(dir / "nan.nrrd", header + "type: float\n\n" + bytesOf(std::vector<float>{NAN, 1}));
    expectInputError(dir / "nan.nrrd", "not a finite label");
    writeFile(dir / "big.nrrd",
              header + "type: uint\n\n" + bytesOf(std::vector<std::uint32_t>{1, 3000000000u}));
    expectInputError(dir / "big.nrrd", "outside the int32 label range");
    writeNifti(dir / "float.nii", {2, 1, 1}, DT_FLOAT32, bytesOf(std::vector<float>{2.25f, 1}),
               [](nifti_image&) {});
    expectInputError(dir / "float.nii", "voxel (0, 0, 0) holds 2.25, not an integer label");
}

TEST(LabelVolume, RefusesBadGeometry) {
    TempDir dir("labelvolume");
    const std::string start = "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 2 2 2\nencoding: raw\n";
    const std::string data = "\n" + std::string(8, '\0');
    writeFile(dir / "zero.nrrd", start +
                                     "space: left-posterior-superior\n"
                                     "space directions: (1,0,0) (0,0,0) (0,0,1)\n" +
                                     data);
    expectInputError(dir / "zero.nrrd", "axis 1 has zero spacing");
    writeFile(dir / "negative.nrrd", start + "spacings: 1 -2 1\n" + data);
    expectInputError(dir / "negative.nrrd", "spacing must be positive");
    writeFile(dir / "parallel.nrrd", start +
                                         "space: left-posterior-superior\n"
                                         "space directions: (1,0,0) (0,1,0) (2,0,0)\n" +
                                         data);
    expectInputError(dir / "parallel.nrrd", "parallel");
    writeFile(dir / "scanner.nrrd", start +
                                        "space: scanner-xyz\n"
                                        "space directions: (1,0,0) (0,1,0) (0,0,1)\n" +
                                        data);
    expectInputError(dir / "scanner.nrrd", "not a 3-D patient space");
    writeFile(dir / "colour.nrrd", start + "kinds: list domain domain\n" + data);
    expectInputError(dir / "colour.nrrd", "not a spatial axis");
    writeNifti(dir / "zero.nii", {2, 2, 2}, DT_UINT8, std::string(8, '\0'), [](nifti_image& i) {
        i.sform_code = NIFTI_XFORM_SCANNER_ANAT;
        i.sto_xyz = {};
        i.sto_xyz.m[0][0] = 1;
        i.sto_xyz.m[2][2] = 1;  // column 1 stays zero
    });
    expectInputError(dir / "zero.nii", "axis 1 has zero spacing");
}

TEST(LabelVolume, RefusesDataFileFormsThatTeemMishandles) {
    TempDir dir("labelvolume");
    const std::string start = "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 2 2 2\nencoding: raw\n";
    // teem would sprintf these names into a buffer sized for 10 digits.
    writeFile(dir / "format.nhdr", start + "data file: x%0999d 1 2 1 2\n");
    expectInputError(dir / "format.nhdr", "not supported");
    writeFile(dir / "strings.nhdr", start + "data file: x%d%s%s%s 1 2 1 2\n");
    expectInputError(dir / "strings.nhdr", "not supported");
    // Also when the line ends in a lone carriage return, as teem allows.
    writeFile(dir / "mac.nhdr",
              "NRRD0004\rtype: uint8\rdimension: 3\rsizes: 2 2 2\r"
              "encoding: raw\rdata file: x%0999d 1 2 1 2\r");
    expectInputError(dir / "mac.nhdr", "not supported");
    writeFile(dir / "list.nhdr", start + "data file: LIST\na.raw\nb.raw\n");
    expectInputError(dir / "list.nhdr", "not supported");
    writeFile(dir / "stdin.nhdr", start + "data file: -\n");
    expectInputError(dir / "stdin.nhdr", "standard input");
    writeFile(dir / "missing.nhdr", start + "data file: missing.raw\n");
    expectInputError(dir / "missing.nhdr", "missing or not a regular file");
    writeFile(dir / "device.nhdr", start + "data file: /dev/zero\n");
    expectInputError(dir / "device.nhdr", "missing or not a regular file");
    writeFile(dir / "bzip2.nrrd",
              "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 2 2 2\n"
              "encoding: bzip2\n\nBZh9");
    expectInputError(dir / "bzip2.nrrd", "encoding bzip2 is not supported");
}

TEST(LabelVolume, WritersRefuseInconsistentArgumentsAndLeaveNothingOnFailure) {
    TempDir dir("labelvolume");
    VolumeGeometry geometry;
    geometry.size = {2, 2, 2};
    EXPECT_THROW(writeMaskNrrd(dir / "m.nrrd", geometry, std::vector<std::uint8_t>(7)),
                 std::invalid_argument);
    EXPECT_THROW(writeMaskNrrd(dir / "m.nhdr", geometry, std::vector<std::uint8_t>(8)),
                 std::invalid_argument);
    VolumeGeometry skewed = geometry;
    skewed.direction[0] = {1, 1, 0};  // not a unit vector
    EXPECT_THROW(writeMaskNrrd(dir / "m.nrrd", skewed, std::vector<std::uint8_t>(8)),
                 std::invalid_argument);
    VolumeGeometry negative = geometry;
    negative.spacingMm[2] = -1;
    EXPECT_THROW(writeLabelNrrd(dir / "m.nrrd", {negative, std::vector<std::int32_t>(8), 1, {}}),
                 std::invalid_argument);
    EXPECT_FALSE(fs::exists(dir / "m.nrrd"));
    EXPECT_THROW(
        writeMaskNrrd(dir / "no/such/folder/m.nrrd", geometry, std::vector<std::uint8_t>(8)),
        std::runtime_error);
    EXPECT_TRUE(fs::is_empty(fs::path(dir / "")));
}

}  // namespace
}  // namespace dfrecon
