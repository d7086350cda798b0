// Mask stacks: label images written with OpenCV (PNG, 16-bit TIFF) and a
// stack.json read back to the same volume and the same contours as the
// volume itself; hostile sidecars and images are refused with an InputError
// naming the file at fault.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "contours/InputError.hpp"
#include "io/labels/MaskContours.hpp"
#include "io/labels/MaskStack.hpp"
#include "shapes/AnalyticShapes.hpp"
#include "tests/TempDir.hpp"

namespace dfrecon {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

using TempDir = ::dfrecon::testing::TempDir;

// Writes plane k of `volume` as an image of `type` (CV_8U or CV_16U).
void writePlanes(const LabelVolume& volume, const TempDir& dir, const std::string& prefix,
                 const std::string& extension, int type, json& files) {
    const VolumeGeometry& g = volume.geometry;
    for (int k = 0; k < g.size[2]; ++k) {
        cv::Mat image(g.size[1], g.size[0], type);
        for (int j = 0; j < g.size[1]; ++j)
            for (int i = 0; i < g.size[0]; ++i) {
                const std::int32_t label = volume.labels[g.linearIndex(i, j, k)];
                if (type == CV_8U)
                    image.at<std::uint8_t>(j, i) = std::uint8_t(label);
                else
                    image.at<std::uint16_t>(j, i) = std::uint16_t(label);
            }
        const std::string name = prefix + std::to_string(k) + extension;
        ASSERT_TRUE(cv::imwrite(dir / name, image));
        files.push_back(name);
    }
}

void writeJson(const std::string& path, const json& doc) {
    std::ofstream(path) << doc.dump(2);
}

TEST(MaskStack, PngStackGivesTheSameContoursAsTheVolume) {
    const auto blobs = makeShape("two-blobs");
    LabelVolume volume;
    volume.geometry.size = {100, 40, 14};
    volume.geometry.spacingMm = {0.7, 0.7, 2.0};
    volume.geometry.originMm = {-33.2, -14.1, -13.0};
    volume.labels.assign(volume.geometry.voxelCount(), 0);
    for (int k = 0; k < 14; ++k)
        for (int j = 0; j < 40; ++j)
            for (int i = 0; i < 100; ++i)
                if (blobs->signedDistance(volume.geometry.worldOfIndex(i, j, k)) < 0)
                    volume.labels[volume.geometry.linearIndex(i, j, k)] = 1;
    volume.labels[volume.geometry.linearIndex(3, 4, 5)] = 9;
    TempDir dir("maskstack");
    json files = json::array();
    writePlanes(volume, dir, "slice_", ".png", CV_8U, files);
    writeJson(dir / "stack.json", {{"pixelSpacingMm", {0.7, 0.7}},
                                   {"originMm", {-33.2, -14.1, -13.0}},
                                   {"sliceSpacingMm", 2.0},
                                   {"files", files},
                                   {"labels", {{"1", "Blobs"}}}});
    EXPECT_TRUE(isMaskStackPath(dir.str()));
    EXPECT_TRUE(isMaskStackPath(dir / "stack.json"));
    EXPECT_FALSE(isMaskStackPath(dir / "slice_0.png"));
    const MaskStack stack = readMaskStack(dir.str());
    EXPECT_EQ(stack.volume.geometry.size, volume.geometry.size);
    EXPECT_EQ(stack.volume.labels, volume.labels);
    EXPECT_EQ(stack.labelNames.at(1), "Blobs");

    MaskContourOptions options;
    options.names = stack.labelNames;
    options.planePositionsMm = stack.slicePositionsMm;
    const ContourSet fromStack = contoursFromLabels(stack.volume, options);
    const ContourSet direct = contoursFromLabels(volume);
    ASSERT_EQ(fromStack.rois.size(), 2u);
    ASSERT_EQ(direct.rois.size(), 2u);
    EXPECT_EQ(fromStack.rois[0].name, "Blobs");
    EXPECT_EQ(fromStack.rois[1].name, "label_9");
    for (std::size_t r = 0; r < 2; ++r) {
        const Roi &a = fromStack.rois[r], &b = direct.rois[r];
        ASSERT_EQ(a.slices.size(), b.slices.size());
        for (std::size_t s = 0; s < a.slices.size(); ++s) {
            EXPECT_EQ(a.slices[s].zMm, b.slices[s].zMm);
            ASSERT_EQ(a.slices[s].contours.size(), b.slices[s].contours.size());
            for (std::size_t c = 0; c < a.slices[s].contours.size(); ++c)
                EXPECT_EQ(a.slices[s].contours[c], b.slices[s].contours[c]);
        }
    }
}

TEST(MaskStack, SixteenBitTiffPatternAndUnevenPositions) {
    LabelVolume volume;
    volume.geometry.size = {5, 4, 3};
    volume.labels.assign(volume.geometry.voxelCount(), 0);
    for (int k = 0; k < 3; ++k) volume.labels[volume.geometry.linearIndex(2, 1, k)] = 300 + k;
    TempDir dir("maskstack");
    json files = json::array();
    // Names s8, s9, s10 sort naturally (s10 last), not as text.
    for (int k = 0; k < 3; ++k) {
        cv::Mat image(4, 5, CV_16U, cv::Scalar(0));
        image.at<std::uint16_t>(1, 2) = std::uint16_t(300 + k);
        ASSERT_TRUE(cv::imwrite(dir / ("s" + std::to_string(8 + k) + ".tif"), image));
    }
    writeJson(dir / "mystack.json", {{"pixelSpacingMm", {0.5, 0.25}},
                                     {"slicePositionsMm", {-4.0, -1.5, 2.0}},
                                     {"pattern", "s*.tif"}});
    const MaskStack stack = readMaskStack(dir / "mystack.json");
    EXPECT_EQ(stack.volume.labels, volume.labels);
    EXPECT_EQ(stack.slicePositionsMm, (std::vector<double>{-4.0, -1.5, 2.0}));
    EXPECT_DOUBLE_EQ(stack.volume.geometry.spacingMm[2], 3.0);
    MaskContourOptions options;
    options.planePositionsMm = stack.slicePositionsMm;
    const ContourSet set = contoursFromLabels(stack.volume, options);
    ASSERT_EQ(set.rois.size(), 3u);
    EXPECT_EQ(set.rois[2].number, 302);
    EXPECT_EQ(set.rois[2].slices[0].zMm, 2.0);
    EXPECT_NEAR(signedArea(set.rois[2].slices[0].contours[0]), 0.5 * 0.5 * 0.25, 1e-12);
}

TEST(MaskStack, HostileStacksAreRefused) {
    TempDir dir("maskstack");
    cv::Mat small(4, 5, CV_8U, cv::Scalar(1)), other(5, 5, CV_8U, cv::Scalar(1));
    ASSERT_TRUE(cv::imwrite(dir / "a.png", small));
    ASSERT_TRUE(cv::imwrite(dir / "b.png", other));
    ASSERT_TRUE(cv::imwrite(dir / "rgb.png", cv::Mat(4, 5, CV_8UC3, cv::Scalar(1, 2, 3))));
    ASSERT_TRUE(cv::imwrite(dir / "float.tif", cv::Mat(4, 5, CV_32F, cv::Scalar(1))));
    ASSERT_TRUE(cv::imwrite(dir / "big.png", cv::Mat(1000, 1000, CV_8U, cv::Scalar(0))));
    std::ofstream(dir / "text.png") << "not an image";
    const json good = {{"pixelSpacingMm", {1, 1}}, {"sliceSpacingMm", 1}, {"files", {"a.png"}}};
    writeJson(dir / "good.json", good);
    EXPECT_NO_THROW(readMaskStack(dir / "good.json"));

    auto refused = [&](const json& doc, const std::string& expectedFile, const std::string& why) {
        writeJson(dir / "bad.json", doc);
        try {
            readMaskStack(dir / "bad.json");
            ADD_FAILURE() << "accepted: " << doc.dump();
        } catch (const InputError& e) {
            EXPECT_EQ(e.file(), dir / expectedFile) << e.what();
            EXPECT_NE(e.problem().find(why), std::string::npos) << e.what();
        }
    };
    auto with = [&](const std::string& key, const json& value) {
        json doc = good;
        if (value.is_null())
            doc.erase(key);
        else
            doc[key] = value;
        return doc;
    };
    refused(with("pixelSpacingMm", nullptr), "bad.json", "pixelSpacingMm");
    refused(with("pixelSpacingMm", {1, 0}), "bad.json", "pixelSpacingMm");
    refused(with("pixelSpacingMm", "1"), "bad.json", "pixelSpacingMm");
    refused(with("sliceSpacingMm", -2), "bad.json", "sliceSpacingMm");
    refused(with("slicePositionsMm", {1.0}), "bad.json", "exactly one");
    refused(with("sliceSpacingMm", nullptr), "bad.json", "exactly one");
    json positions = with("sliceSpacingMm", nullptr);
    positions["slicePositionsMm"] = {2.0, 2.0};
    positions["files"] = {"a.png", "a.png"};
    refused(positions, "bad.json", "strictly increasing");
    positions["slicePositionsMm"] = {2.0};
    refused(positions, "bad.json", "1 positions for 2 images");
    refused(with("files", json::array()), "bad.json", "no images");
    refused(with("files", {"missing.png"}), "missing.png", "not found");
    refused(with("files", {"a.png", "b.png"}), "b.png", "5x5");
    refused(with("files", {"rgb.png"}), "rgb.png", "single channel");
    refused(with("files", {"float.tif"}), "float.tif", "single channel");
    refused(with("files", {"text.png"}), "text.png", "decode");
    refused(with("pattern", "*.png"), "bad.json", "exactly one");
    refused(with("labels", {{"one", "Liver"}}), "bad.json", "not an integer");
    refused(with("labels", {{"1", 5}}), "bad.json", "must be a string");
    // 2200 copies of a 1000 × 1000 image: over 2^31 voxels, refused before
    // the volume is allocated.
    refused(with("files", std::vector<std::string>(2200, "big.png")), "bad.json", "2^31");
    // 600 copies: under 2^31 voxels, but their labels take 2.4 GB.
    refused(with("files", std::vector<std::string>(600, "big.png")), "bad.json",
            "over the 2048 MiB a label volume may take");
    // Geometry that is no patient's (1e308 mm printed -nan extents).
    refused(with("sliceSpacingMm", 1e308), "bad.json", "sliceSpacingMm must be a length");
    refused(with("pixelSpacingMm", {1e308, 1}), "bad.json", "pixelSpacingMm must be a length");
    refused(with("pixelSpacingMm", {1, 1e-9}), "bad.json", "pixelSpacingMm must be a length");
    refused(with("originMm", {1e30, 0}), "bad.json", "beyond the limit");
    json close = with("sliceSpacingMm", nullptr);
    close["slicePositionsMm"] = {0.0, 1e-9};
    close["files"] = {"a.png", "a.png"};
    refused(close, "bad.json", "axis 2 has spacing");
    json far = good;
    far["files"] = {"a.png", "a.png"};
    far["sliceSpacingMm"] = 999999;
    refused(far, "bad.json", "beyond the limit");
    std::ofstream(dir / "bad.json") << "{ not json";
    EXPECT_THROW(readMaskStack(dir / "bad.json"), InputError);
    EXPECT_THROW(readMaskStack(dir / "absent.json"), InputError);
    EXPECT_THROW(readMaskStack(dir.str()), InputError);  // folder without stack.json
}

}  // namespace
}  // namespace dfrecon
