// PNG and TIFF through libpng and libtiff (io/images/ImageFiles) against OpenCV's
// imgcodecs as the independent reference: every file OpenCV writes reads
// back to the pixels OpenCV reads from it, every file written here reads
// back in OpenCV unchanged, and what is not a grey 8- or 16-bit image, or
// not an image at all, is said or refused naming the file.
#include <gtest/gtest.h>
#include <tiffio.h>

#include <cmath>
#include <cstdint>
#include <fstream>
#include <limits>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <string>
#include <vector>

#include "contours/InputError.hpp"
#include "io/images/ImageFiles.hpp"
#include "tests/TempDir.hpp"

namespace dfrecon {
namespace {

using TempDir = ::dfrecon::testing::TempDir;

// A W×H image of `type` whose every pixel differs from its neighbours.
cv::Mat patterned(int width, int height, int type) {
    cv::Mat image(height, width, type);
    cv::randu(image, 0, type == CV_16UC1 ? 65536 : 256);
    return image;
}

bool samePixels(const cv::Mat& a, const cv::Mat& b) {
    return a.type() == b.type() && a.size() == b.size() && cv::norm(a, b, cv::NORM_INF) == 0;
}

// Reads `path` here and with OpenCV, and requires the same grey pixels.
void expectAsOpenCvReads(const std::string& path) {
    const cv::Mat reference = cv::imread(path, cv::IMREAD_UNCHANGED);
    ASSERT_FALSE(reference.empty()) << path;
    ImageSamples found;
    const cv::Mat image = readGreyImage(path, found);
    EXPECT_EQ(found.samplesPerPixel, 1) << path;
    EXPECT_TRUE(samePixels(image, reference)) << path;
}

// What readGreyImage says about a file that is an image but not a grey one.
ImageSamples samplesOf(const std::string& path) {
    ImageSamples found;
    EXPECT_TRUE(readGreyImage(path, found).empty()) << path;
    return found;
}

void expectRefused(const std::string& path, const std::string& what) {
    ImageSamples found;
    try {
        readGreyImage(path, found);
        ADD_FAILURE() << path << " was read";
    } catch (const InputError& e) {
        EXPECT_EQ(e.file(), path);
        EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
    }
}

// A TIFF opened with libtiff for writing one grey sample of `bits` a pixel,
// its size set; the caller adds its layout and data.
TIFF* greyTiff(const std::string& path, std::uint32_t width, std::uint32_t height, int bits) {
    TIFF* tiff = TIFFOpen(path.c_str(), "w");
    if (!tiff) return nullptr;
    TIFFSetField(tiff, TIFFTAG_IMAGEWIDTH, width);
    TIFFSetField(tiff, TIFFTAG_IMAGELENGTH, height);
    TIFFSetField(tiff, TIFFTAG_SAMPLESPERPIXEL, 1);
    TIFFSetField(tiff, TIFFTAG_BITSPERSAMPLE, bits);
    TIFFSetField(tiff, TIFFTAG_PHOTOMETRIC, PHOTOMETRIC_MINISBLACK);
    return tiff;
}

TEST(ImageFiles, GreyPngAndTiffReadAsOpenCvReadsThem) {
    const TempDir dir("image-files-grey");
    const cv::Mat bytes = patterned(37, 23, CV_8UC1), words = patterned(41, 19, CV_16UC1);
    const std::vector<std::pair<std::string, std::vector<int>>> writes = {
        {"plain.png", {}},
        {"fast.png", {cv::IMWRITE_PNG_COMPRESSION, 0}},
        {"lzw.tif", {cv::IMWRITE_TIFF_COMPRESSION, 5}},
        {"packbits.tif", {cv::IMWRITE_TIFF_COMPRESSION, 32773}},
        {"none.tif", {cv::IMWRITE_TIFF_COMPRESSION, 1}},
    };
    for (const auto& [name, params] : writes)
        for (const cv::Mat* image : {&bytes, &words}) {
            const std::string path = dir / ((image == &bytes ? "8-" : "16-") + name);
            ASSERT_TRUE(cv::imwrite(path, *image, params)) << path;
            expectAsOpenCvReads(path);
            ImageSamples found;
            EXPECT_TRUE(samePixels(readGreyImage(path, found), *image)) << path;
        }
    // A 1-bit PNG widens to 0 and 255, as in OpenCV.
    const std::string bilevel = dir / "bilevel.png";
    cv::Mat mask = patterned(16, 9, CV_8UC1) > 127;
    ASSERT_TRUE(cv::imwrite(bilevel, mask, {cv::IMWRITE_PNG_BILEVEL, 1}));
    expectAsOpenCvReads(bilevel);
    // The name does not choose the format: a PNG called .tif is a PNG.
    const std::string misnamed = dir / "png.tif";
    ASSERT_TRUE(cv::imwrite(dir / "a.png", bytes));
    std::filesystem::rename(dir / "a.png", misnamed);
    ImageSamples found;
    EXPECT_TRUE(samePixels(readGreyImage(misnamed, found), bytes));
}

TEST(ImageFiles, TiledTiffsReadWholeIncludingPartTiles) {
    // 16-bit tiles of 16 × 16 over a 40 × 35 image: the last column and row
    // of tiles are part outside the image.
    const TempDir dir("image-files-tiled");
    const cv::Mat image = patterned(40, 35, CV_16UC1);
    const std::string path = dir / "tiled.tif";
    TIFF* tiff = greyTiff(path, 40, 35, 16);
    ASSERT_NE(tiff, nullptr);
    TIFFSetField(tiff, TIFFTAG_COMPRESSION, COMPRESSION_ADOBE_DEFLATE);
    TIFFSetField(tiff, TIFFTAG_TILEWIDTH, 16u);
    TIFFSetField(tiff, TIFFTAG_TILELENGTH, 16u);
    std::vector<std::uint16_t> tile(16 * 16);
    for (int y = 0; y < 35; y += 16)
        for (int x = 0; x < 40; x += 16) {
            for (int r = 0; r < 16; ++r)
                for (int c = 0; c < 16; ++c)
                    tile[std::size_t(r * 16 + c)] =
                        y + r < 35 && x + c < 40 ? image.at<std::uint16_t>(y + r, x + c) : 0;
            ASSERT_GE(TIFFWriteTile(tiff, tile.data(), std::uint32_t(x), std::uint32_t(y), 0, 0),
                      0);
        }
    TIFFClose(tiff);
    ImageSamples found;
    EXPECT_TRUE(samePixels(readGreyImage(path, found), image));
    expectAsOpenCvReads(path);
}

TEST(ImageFiles, OtherPixelsAreSaidNotRead) {
    const TempDir dir("image-files-other");
    const std::string colour = dir / "colour.png", alpha = dir / "alpha.png",
                      floats = dir / "float.tif", rgb = dir / "rgb.tif";
    ASSERT_TRUE(cv::imwrite(colour, patterned(8, 8, CV_8UC3)));
    ASSERT_TRUE(cv::imwrite(alpha, patterned(8, 8, CV_8UC4)));
    ASSERT_TRUE(cv::imwrite(floats, cv::Mat(8, 8, CV_32FC1, cv::Scalar(1.5))));
    ASSERT_TRUE(cv::imwrite(rgb, patterned(8, 8, CV_16UC3)));
    EXPECT_EQ(samplesOf(colour).samplesPerPixel, 3);
    EXPECT_EQ(samplesOf(alpha).samplesPerPixel, 4);
    EXPECT_EQ(samplesOf(floats).bitsPerSample, 32);
    EXPECT_EQ(samplesOf(rgb).samplesPerPixel, 3);
}

TEST(ImageFiles, WhatIsNoImageIsRefusedNamingTheFile) {
    const TempDir dir("image-files-refused");
    const std::string text = dir / "text.png", empty = dir / "empty.png", cutPng = dir / "cut.png",
                      cutTiff = dir / "cut.tif", jpeg = dir / "photo.jpg";
    std::ofstream(text) << "not an image";
    std::ofstream(empty) << "";
    ASSERT_TRUE(cv::imwrite(jpeg, patterned(8, 8, CV_8UC1)));
    for (const std::string& path : {text, empty, jpeg})
        expectRefused(path, "cannot decode the image (PNG or TIFF expected)");
    // A folder is no image: refused at the gate every input passes.
    expectRefused(dir.str(), "not a regular file");
    // Cut short after the header: the rows are missing.
    std::vector<uchar> bytes;
    ASSERT_TRUE(cv::imencode(".png", patterned(64, 64, CV_8UC1), bytes));
    std::ofstream(cutPng, std::ios::binary).write(reinterpret_cast<const char*>(bytes.data()), 60);
    expectRefused(cutPng, "cannot decode the PNG image");
    ASSERT_TRUE(cv::imencode(".tiff", patterned(64, 64, CV_8UC1), bytes,
                             {cv::IMWRITE_TIFF_COMPRESSION, 1}));
    std::ofstream(cutTiff, std::ios::binary)
        .write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size() / 2));
    expectRefused(cutTiff, "cannot decode the TIFF image");
}

TEST(ImageFiles, HugeImagesAreRefusedBeforeTheirPixelsAreAllocated) {
    // A TIFF whose directory says 100 000 × 100 000 pixels and holds one
    // byte: 10^10 pixels, over the 2^30 an image may have.
    const TempDir dir("image-files-huge");
    const std::string path = dir / "huge.tif";
    TIFF* tiff = greyTiff(path, 100000, 100000, 8);
    ASSERT_NE(tiff, nullptr);
    TIFFSetField(tiff, TIFFTAG_ROWSPERSTRIP, 1u);
    const std::uint8_t row = 0;
    ASSERT_GE(TIFFWriteRawStrip(tiff, 0, const_cast<std::uint8_t*>(&row), 1), 0);
    TIFFClose(tiff);
    expectRefused(path, "more than the 2^30 an image may have");
}

TEST(ImageFiles, WrittenImagesReadBackInOpenCvUnchanged) {
    const TempDir dir("image-files-written");
    const cv::Mat grey = patterned(33, 21, CV_8UC1), colour = patterned(29, 17, CV_8UC3);
    writePng(dir / "grey.png", grey);
    writePng(dir / "colour.png", colour);  // blue first in both
    EXPECT_TRUE(samePixels(cv::imread(dir / "grey.png", cv::IMREAD_UNCHANGED), grey));
    EXPECT_TRUE(samePixels(cv::imread(dir / "colour.png", cv::IMREAD_UNCHANGED), colour));
    EXPECT_THROW(writePng(dir / "words.png", patterned(4, 4, CV_16UC1)), std::invalid_argument);

    // Floats keep every bit, NaN and infinities included; three channels are
    // stored red first, which OpenCV turns to blue first.
    std::vector<float> values(7 * 5 * 3);
    for (std::size_t k = 0; k < values.size(); ++k) values[k] = float(k) * 0.37f - 9.0f;
    values[4] = std::numeric_limits<float>::quiet_NaN();
    values[5] = -std::numeric_limits<float>::infinity();
    writeFloatTiff(dir / "one.tif", values.data(), 7, 5, 1);
    writeFloatTiff(dir / "three.tif", values.data(), 7, 5, 3);
    const cv::Mat one = cv::imread(dir / "one.tif", cv::IMREAD_UNCHANGED);
    const cv::Mat three = cv::imread(dir / "three.tif", cv::IMREAD_UNCHANGED);
    ASSERT_EQ(one.type(), CV_32FC1);
    ASSERT_EQ(three.type(), CV_32FC3);
    for (int r = 0; r < 5; ++r)
        for (int c = 0; c < 7; ++c) {
            const float expected = values[std::size_t(r * 7 + c)];
            const float got = one.at<float>(r, c);
            EXPECT_TRUE(got == expected || (std::isnan(got) && std::isnan(expected)));
            for (int s = 0; s < 3; ++s) {
                const float e3 = values[std::size_t((r * 7 + c) * 3 + s)];
                const float g3 = three.at<cv::Vec3f>(r, c)[2 - s];
                EXPECT_TRUE(g3 == e3 || (std::isnan(g3) && std::isnan(e3)));
            }
        }
    EXPECT_THROW(writeFloatTiff(dir / "bad.tif", values.data(), 7, 5, 2), std::invalid_argument);
}

}  // namespace
}  // namespace dfrecon
