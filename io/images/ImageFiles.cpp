#include "io/images/ImageFiles.hpp"

#include <png.h>
#include <tiffio.h>

#include <opencv2/core/mat.hpp>

#include <algorithm>
#include <csetjmp>
#include <cstdarg>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <new>
#include <stdexcept>
#include <vector>

#include "contours/InputError.hpp"
#include "io/files/AtomicWrite.hpp"
#include "io/files/RegularFile.hpp"

namespace dfrecon {

namespace {

// ---- PNG --------------------------------------------------------------
//
// libpng reports an error by longjmp to the last setjmp. Each step that
// calls it sets its own in a frame that holds nothing to destroy, and
// everything it fills (rows, the message) belongs to the caller.

struct PngFile {
    std::FILE* file = nullptr;
    png_structp png = nullptr;
    png_infop info = nullptr;
    bool writing = false;
    char message[256] = "";
    ~PngFile() {
        if (writing)
            png_destroy_write_struct(&png, &info);
        else
            png_destroy_read_struct(&png, &info, nullptr);
        if (file) std::fclose(file);
    }
};

[[noreturn]] void pngError(png_structp png, png_const_charp message) {
    auto* owner = static_cast<PngFile*>(png_get_error_ptr(png));
    std::snprintf(owner->message, sizeof owner->message, "%s", message);
    png_longjmp(png, 1);
}

void pngWarning(png_structp, png_const_charp) {}  // ancillary-chunk complaints change no pixel

struct PngHeader {
    png_uint_32 width = 0, height = 0;
    int bitDepth = 0, colourType = 0;
};

bool readPngHeader(PngFile& f, PngHeader& header) {
    if (setjmp(png_jmpbuf(f.png))) return false;
    png_init_io(f.png, f.file);
    png_read_info(f.png, f.info);
    png_get_IHDR(f.png, f.info, &header.width, &header.height, &header.bitDepth, &header.colourType,
                 nullptr, nullptr, nullptr);
    if (header.colourType == PNG_COLOR_TYPE_GRAY && header.bitDepth < 8)
        png_set_expand_gray_1_2_4_to_8(f.png);
    // PNG stores 16-bit samples big-endian.
    if (header.bitDepth == 16) png_set_swap(f.png);
    png_read_update_info(f.png, f.info);
    return true;
}

bool readPngRows(PngFile& f, png_bytep* rows) {
    if (setjmp(png_jmpbuf(f.png))) return false;
    png_read_image(f.png, rows);
    png_read_end(f.png, nullptr);
    return true;
}

int pngSamples(int colourType) {
    switch (colourType) {
        case PNG_COLOR_TYPE_GRAY:
            return 1;
        case PNG_COLOR_TYPE_GRAY_ALPHA:
            return 2;
        case PNG_COLOR_TYPE_RGB_ALPHA:
            return 4;
        default:
            return 3;  // colour, and palettes of colours
    }
}

void checkPixelCount(const std::string& path, double width, double height) {
    if (width * height > kMaxImagePixels)
        throw InputError(path, 0,
                         "the image is " + std::to_string(std::uint64_t(width)) + " x " +
                             std::to_string(std::uint64_t(height)) +
                             " pixels, more than the 2^30 an image may have");
}

cv::Mat readPng(const std::string& path, ImageSamples& found) {
    PngFile f;
    f.file = std::fopen(path.c_str(), "rb");
    if (!f.file) throw InputError(path, 0, "cannot open the image");
    f.png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &f, pngError, pngWarning);
    if (f.png) f.info = png_create_info_struct(f.png);
    if (!f.png || !f.info) throw std::bad_alloc();
    PngHeader header;
    if (!readPngHeader(f, header))
        throw InputError(path, 0, std::string("cannot decode the PNG image: ") + f.message);
    checkPixelCount(path, header.width, header.height);
    found.samplesPerPixel = pngSamples(header.colourType);
    found.bitsPerSample =
        header.colourType == PNG_COLOR_TYPE_PALETTE ? 8 : std::max(8, header.bitDepth);
    if (found.samplesPerPixel != 1) return {};
    cv::Mat pixels(int(header.height), int(header.width),
                   header.bitDepth == 16 ? CV_16UC1 : CV_8UC1);
    std::vector<png_bytep> rows(header.height);
    for (png_uint_32 r = 0; r < header.height; ++r) rows[r] = pixels.ptr<png_byte>(int(r));
    if (!readPngRows(f, rows.data()))
        throw InputError(path, 0, std::string("cannot decode the PNG image: ") + f.message);
    return pixels;
}

bool writePngRows(PngFile& f, const cv::Mat& image, png_bytep* rows) {
    if (setjmp(png_jmpbuf(f.png))) return false;
    png_init_io(f.png, f.file);
    png_set_IHDR(f.png, f.info, png_uint_32(image.cols), png_uint_32(image.rows), 8,
                 image.channels() == 1 ? PNG_COLOR_TYPE_GRAY : PNG_COLOR_TYPE_RGB,
                 PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_write_info(f.png, f.info);
    if (image.channels() == 3) png_set_bgr(f.png);  // OpenCV's order
    png_write_image(f.png, rows);
    png_write_end(f.png, nullptr);
    return true;
}

// ---- TIFF -------------------------------------------------------------

// libtiff's messages for one file, kept instead of printed.
struct TiffMessages {
    std::string last;
};

int keepTiffError(TIFF*, void* userData, const char* module, const char* format, va_list args) {
    char text[256];
    std::vsnprintf(text, sizeof text, format, args);
    static_cast<TiffMessages*>(userData)->last =
        (module && *module ? std::string(module) + ": " : std::string()) + text;
    return 1;
}

int ignoreTiffWarning(TIFF*, void*, const char*, const char*, va_list) {
    return 1;  // unknown tags and the like change no pixel
}

// The largest single block libtiff may allocate for one file: a strip or
// tile that claims more is refused before memory is taken for it.
constexpr tmsize_t kMaxTiffAllocation = tmsize_t(1) << 30;

struct TiffFile {
    TIFF* tiff = nullptr;
    TiffMessages messages;
    ~TiffFile() {
        if (tiff) TIFFClose(tiff);
    }
};

void openTiff(TiffFile& f, const std::string& path, const char* mode) {
    TIFFOpenOptions* options = TIFFOpenOptionsAlloc();
    if (!options) throw std::bad_alloc();
    TIFFOpenOptionsSetErrorHandlerExtR(options, keepTiffError, &f.messages);
    TIFFOpenOptionsSetWarningHandlerExtR(options, ignoreTiffWarning, nullptr);
    TIFFOpenOptionsSetMaxSingleMemAlloc(options, kMaxTiffAllocation);
    f.tiff = TIFFOpenExt(path.c_str(), mode, options);
    TIFFOpenOptionsFree(options);
}

cv::Mat readTiff(const std::string& path, ImageSamples& found) {
    TiffFile f;
    openTiff(f, path, "r");
    auto fail = [&](const std::string& what) {
        return InputError(
            path, 0,
            "cannot decode the TIFF image: " + (f.messages.last.empty() ? what : f.messages.last));
    };
    if (!f.tiff) throw fail("not a TIFF file");
    std::uint32_t width = 0, height = 0;
    std::uint16_t samples = 1, bits = 1, format = SAMPLEFORMAT_UINT,
                  photometric = PHOTOMETRIC_MINISBLACK;
    if (!TIFFGetField(f.tiff, TIFFTAG_IMAGEWIDTH, &width) ||
        !TIFFGetField(f.tiff, TIFFTAG_IMAGELENGTH, &height))
        throw fail("no image size");
    TIFFGetFieldDefaulted(f.tiff, TIFFTAG_SAMPLESPERPIXEL, &samples);
    TIFFGetFieldDefaulted(f.tiff, TIFFTAG_BITSPERSAMPLE, &bits);
    TIFFGetFieldDefaulted(f.tiff, TIFFTAG_SAMPLEFORMAT, &format);
    TIFFGetField(f.tiff, TIFFTAG_PHOTOMETRIC, &photometric);
    checkPixelCount(path, width, height);
    found.samplesPerPixel = photometric == PHOTOMETRIC_PALETTE ? 3 : samples;
    found.bitsPerSample = bits;
    if (found.samplesPerPixel != 1 || (bits != 8 && bits != 16) || format != SAMPLEFORMAT_UINT)
        return {};
    if (width == 0 || height == 0) throw fail("an image of no pixels");
    cv::Mat pixels(int(height), int(width), bits == 16 ? CV_16UC1 : CV_8UC1);
    const std::size_t rowBytes = std::size_t(width) * (bits / 8);
    if (TIFFIsTiled(f.tiff)) {
        std::uint32_t tileWidth = 0, tileHeight = 0;
        TIFFGetField(f.tiff, TIFFTAG_TILEWIDTH, &tileWidth);
        TIFFGetField(f.tiff, TIFFTAG_TILELENGTH, &tileHeight);
        const tmsize_t tileBytes = TIFFTileSize(f.tiff);
        if (tileWidth == 0 || tileHeight == 0 || tileBytes <= 0 ||
            std::size_t(tileBytes) < std::size_t(tileWidth) * tileHeight * (bits / 8))
            throw fail("bad tile size");
        std::vector<unsigned char> tile(static_cast<std::size_t>(tileBytes));
        for (std::uint32_t y = 0; y < height; y += tileHeight)
            for (std::uint32_t x = 0; x < width; x += tileWidth) {
                if (TIFFReadTile(f.tiff, tile.data(), x, y, 0, 0) < 0)
                    throw fail("a tile does not decode");
                const std::uint32_t rows = std::min(tileHeight, height - y),
                                    columns = std::min(tileWidth, width - x);
                for (std::uint32_t r = 0; r < rows; ++r)
                    std::memcpy(pixels.ptr<unsigned char>(int(y + r)) + std::size_t(x) * (bits / 8),
                                tile.data() + std::size_t(r) * tileWidth * (bits / 8),
                                std::size_t(columns) * (bits / 8));
            }
    } else {
        if (std::size_t(TIFFScanlineSize(f.tiff)) < rowBytes) throw fail("bad row size");
        for (std::uint32_t r = 0; r < height; ++r)
            if (TIFFReadScanline(f.tiff, pixels.ptr<unsigned char>(int(r)), r, 0) < 0)
                throw fail("row " + std::to_string(r) + " does not decode");
    }
    return pixels;
}

bool startsWith(const unsigned char* bytes, std::size_t size, const char* signature,
                std::size_t length) {
    return size >= length && std::memcmp(bytes, signature, length) == 0;
}

}  // namespace

cv::Mat readGreyImage(const std::string& path, ImageSamples& found) {
    // The gate every input passes: a pipe or a device is refused before
    // libpng or libtiff would block on it or read it for ever.
    checkRegularFile(path, kMaxInputFileBytes, "an image");
    unsigned char head[8] = {};
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError(path, 0, "cannot open the image");
    in.read(reinterpret_cast<char*>(head), sizeof head);
    const std::size_t size = std::size_t(in.gcount());
    if (startsWith(head, size, "\x89PNG\r\n\x1a\n", 8)) return readPng(path, found);
    if (startsWith(head, size, "II*\0", 4) || startsWith(head, size, "MM\0*", 4) ||
        startsWith(head, size, "II+\0", 4) || startsWith(head, size, "MM\0+", 4))
        return readTiff(path, found);
    throw InputError(path, 0, "cannot decode the image (PNG or TIFF expected)");
}

void writePng(const std::string& path, const cv::Mat& image) {
    if (image.empty() || image.depth() != CV_8U || (image.channels() != 1 && image.channels() != 3))
        throw std::invalid_argument("writePng: an 8-bit image of 1 or 3 channels expected");
    std::vector<png_bytep> rows(std::size_t(image.rows));
    for (int r = 0; r < image.rows; ++r)
        rows[std::size_t(r)] = const_cast<png_bytep>(image.ptr<png_byte>(r));
    writeAtomically(path, [&](const std::string& temporary) {
        PngFile f;
        f.writing = true;
        f.file = std::fopen(temporary.c_str(), "wb");
        if (!f.file) return false;
        f.png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &f, pngError, pngWarning);
        if (f.png) f.info = png_create_info_struct(f.png);
        if (!f.png || !f.info) throw std::bad_alloc();
        if (!writePngRows(f, image, rows.data())) return false;
        const bool flushed = std::fflush(f.file) == 0 && !std::ferror(f.file);
        const bool closed = std::fclose(f.file) == 0;
        f.file = nullptr;
        return flushed && closed;
    });
}

void writeFloatTiff(const std::string& path, const float* values, int width, int height,
                    int channels) {
    if (width <= 0 || height <= 0 || (channels != 1 && channels != 3))
        throw std::invalid_argument("writeFloatTiff: bad image shape");
    writeAtomically(path, [&](const std::string& temporary) {
        TiffFile f;
        openTiff(f, temporary, "w");
        if (!f.tiff) return false;
        TIFFSetField(f.tiff, TIFFTAG_IMAGEWIDTH, std::uint32_t(width));
        TIFFSetField(f.tiff, TIFFTAG_IMAGELENGTH, std::uint32_t(height));
        TIFFSetField(f.tiff, TIFFTAG_SAMPLESPERPIXEL, std::uint16_t(channels));
        TIFFSetField(f.tiff, TIFFTAG_BITSPERSAMPLE, std::uint16_t(32));
        TIFFSetField(f.tiff, TIFFTAG_SAMPLEFORMAT, std::uint16_t(SAMPLEFORMAT_IEEEFP));
        TIFFSetField(f.tiff, TIFFTAG_PHOTOMETRIC,
                     std::uint16_t(channels == 1 ? PHOTOMETRIC_MINISBLACK : PHOTOMETRIC_RGB));
        TIFFSetField(f.tiff, TIFFTAG_PLANARCONFIG, std::uint16_t(PLANARCONFIG_CONTIG));
        TIFFSetField(f.tiff, TIFFTAG_COMPRESSION, std::uint16_t(COMPRESSION_LZW));
        TIFFSetField(f.tiff, TIFFTAG_ROWSPERSTRIP, TIFFDefaultStripSize(f.tiff, 0));
        const std::size_t rowValues = std::size_t(width) * std::size_t(channels);
        std::vector<float> row(rowValues);  // libtiff may encode in place
        for (int r = 0; r < height; ++r) {
            std::memcpy(row.data(), values + std::size_t(r) * rowValues, rowValues * sizeof(float));
            if (TIFFWriteScanline(f.tiff, row.data(), std::uint32_t(r), 0) < 0) return false;
        }
        if (!TIFFFlush(f.tiff)) return false;
        TIFFClose(f.tiff);
        f.tiff = nullptr;
        return true;
    });
}

}  // namespace dfrecon
