#pragma once
// PNG and TIFF files to and from OpenCV matrices, through libpng and libtiff
// themselves rather than OpenCV's imgcodecs: Debian builds imgcodecs
// against GDAL, whose 130 shared libraries every process linking it loads
// at start (`dfrecon --version` took 0.68 s with them, 0.07 s without, on a
// 2-core VM; paid again by every batch entry and every test that runs the
// program), while
// dfrecon reads and writes these two formats only. Pixels stay in OpenCV's
// layout (colour stored blue first), so drawing keeps using OpenCV.
#include <string>

// Declared only: this header's users need not see OpenCV's headers.
namespace cv {
class Mat;
}

namespace dfrecon {

/// The most pixels an image read here may have (OpenCV's imread default).
inline constexpr double kMaxImagePixels = double(1 << 30);

/// What a file's pixels are made of.
struct ImageSamples {
    int samplesPerPixel = 0;
    int bitsPerSample = 0;
};

/// The first image of a PNG or TIFF file (told apart by their signatures,
/// not the name), values unchanged, as CV_8UC1 or CV_16UC1: 16-bit samples
/// keep their 16 bits, and grey PNGs of 1, 2 or 4 bits are widened to 8
/// (the top value to 255, as OpenCV's imread does). `found` says what the
/// pixels are; for anything but one unsigned 8- or 16-bit sample a pixel
/// (colour, grey with alpha, palettes — counted as their 3 colour samples
/// —, signed or float samples, 1-bit TIFFs) the image returned is empty.
/// Throws InputError(path, 0, what is wrong) for a path that is no regular
/// file within io/files/RegularFile's limit, a file that is neither format, does
/// not decode, or has more than kMaxImagePixels pixels.
/// O(pixels).
cv::Mat readGreyImage(const std::string& path, ImageSamples& found);

/// Writes an 8-bit grey (CV_8UC1) or colour (CV_8UC3, blue first) image as
/// a PNG, atomically (io/files/AtomicWrite). Throws std::invalid_argument for
/// other matrix types and std::runtime_error naming the file when it
/// cannot be written. O(pixels).
void writePng(const std::string& path, const cv::Mat& image);

/// A float image (row-major, row 0 first, `channels` of 1 or 3 interleaved,
/// the three as red, green, blue) as a 32-bit float TIFF that keeps every
/// value (NaN included), LZW-compressed, for ParaView, 3D Slicer, Fiji or
/// numpy. Written atomically; throws as writePng. O(pixels).
void writeFloatTiff(const std::string& path, const float* values, int width, int height,
                    int channels);

}  // namespace dfrecon
