// HTML reports opened as a user opens them: in a browser (headless
// Chromium, `make setup` installs it), from a file:// URL, with no network
// (a network namespace of its own where the machine allows one). The page
// says what it drew (data-surfaces, data-webgl on its body) and a
// screenshot shows each ROI in its colour.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include <filesystem>
#include <fstream>
#include <regex>
#include <string>

#include "tests/CliRun.hpp"

namespace fs = std::filesystem;
using dfrecon::testing::CliResult;

namespace {

const char* const kChromium = "/usr/bin/chromium";

// A folder per test: ctest runs the tests of this file as processes side
// by side, and each browser needs a profile of its own.
fs::path scratch() {
    const fs::path dir = fs::temp_directory_path() / "dfrecon-test-report" /
                         ::testing::UnitTest::GetInstance()->current_test_info()->name();
    static std::string made;
    if (made != dir.string()) {
        fs::remove_all(dir);
        fs::create_directories(dir);
        made = dir.string();
    }
    return dir;
}

CliResult runDfrecon(const std::string& args) {
    return dfrecon::testing::runCli(scratch().string(), args);
}

// Chromium headless on `page` with `action` (--dump-dom, --screenshot=...):
// no network (unshare -n when it may make a namespace; the background
// services off in any case), software WebGL, a fresh profile.
CliResult browse(const fs::path& page, const std::string& action) {
    const std::string flags =
        " --headless --no-sandbox --disable-gpu --disable-background-networking "
        "--disable-component-update --disable-sync --no-first-run --use-angle=swiftshader "
        "--enable-unsafe-swiftshader --window-size=1200,800 --virtual-time-budget=20000 "
        "--user-data-dir=" +
        (scratch() / "profile").string() + " " + action + " file://" + page.string();
    const std::string chromium = kChromium + flags;
    return dfrecon::testing::runShell(
        scratch().string(), "if unshare -n true 2>/dev/null; then exec unshare -n " + chromium +
                                "; else exec " + chromium + "; fi");
}

// The body's data-NAME in the dumped DOM, or "".
std::string bodyData(const std::string& dom, const std::string& name) {
    std::smatch m;
    const std::regex pattern("<body[^>]*data-" + name + "=\"([^\"]*)\"");
    return std::regex_search(dom, m, pattern) ? m[1].str() : "";
}

// The dumped DOM of `page` once its script has run: the body says what it
// drew (data-webgl is 1 or 0 either way). Headless Chromium on a loaded
// machine (a sanitizer build beside another test run) has dumped the page
// before its script ran; such a dump is taken again, twice at most. A page
// whose script fails still fails the assertions on what it drew.
CliResult dumpDom(const fs::path& page) {
    CliResult dom;
    for (int attempt = 0; attempt < 3; ++attempt) {
        dom = browse(page, "--dump-dom");
        if (dom.exitCode != 0 || !bodyData(dom.out, "webgl").empty()) break;
    }
    return dom;
}

// Pixels of the screenshot whose colour is `rgb` lit by some amount: the
// same direction in colour space (shading scales all three), within 0.06.
std::size_t pixelsLike(const cv::Mat& image, cv::Vec3d rgb) {
    std::size_t count = 0;
    const cv::Vec3d want = rgb / cv::norm(rgb);
    for (int y = 0; y < image.rows; ++y)
        for (int x = image.cols / 2; x < image.cols; ++x) {  // the 3D view's half
            const cv::Vec3b bgr = image.at<cv::Vec3b>(y, x);
            const cv::Vec3d got(bgr[2], bgr[1], bgr[0]);
            if (cv::norm(got) < 60) continue;  // background and deep shade
            if (cv::norm(got / cv::norm(got) - want) < 0.06) ++count;
        }
    return count;
}

}  // namespace

TEST(HtmlReport, IsOneSelfContainedFile) {
    const fs::path page = scratch() / "two.html";
    const CliResult run = runDfrecon("-q reconstruct " + std::string(DFRECON_EXAMPLES) +
                                     "/two-rois.slices --all -o " + (scratch() / "two").string() +
                                     " --report " + page.string());
    ASSERT_EQ(run.exitCode, 0) << run.err;
    const std::string html = dfrecon::testing::slurp(page.string());
    // Nothing it loads from elsewhere: every script inline, no link.
    EXPECT_EQ(html.find("<script src"), std::string::npos);
    EXPECT_EQ(html.find("<link"), std::string::npos);
    EXPECT_NE(html.find("\"Left Kidney\""), std::string::npos);
    EXPECT_NE(html.find("WebGLRenderer"), std::string::npos);  // three.js, inlined
    // A report that cannot be written is an error, and leaves nothing.
    const CliResult bad = runDfrecon("-q reconstruct " + std::string(DFRECON_EXAMPLES) +
                                     "/two-rois.slices --all -o " + (scratch() / "two-b").string() +
                                     " --report /nonexistent-dir/r.html");
    EXPECT_EQ(bad.exitCode, 3) << bad.err;
    EXPECT_NE(bad.err.find("/nonexistent-dir/r.html"), std::string::npos) << bad.err;
}

TEST(HtmlReport, ChromiumDrawsEveryRoiInItsColour) {
    if (!fs::exists(kChromium)) GTEST_SKIP() << kChromium << " missing (make setup installs it)";
    const fs::path page = scratch() / "shown.html";
    ASSERT_EQ(runDfrecon("-q reconstruct " + std::string(DFRECON_EXAMPLES) +
                         "/two-rois.slices --all -o " + (scratch() / "shown").string() +
                         " --report " + page.string())
                  .exitCode,
              0);
    const CliResult dom = dumpDom(page);
    ASSERT_EQ(dom.exitCode, 0) << dom.err;
    EXPECT_EQ(bodyData(dom.out, "webgl"), "1") << dom.out.substr(0, 2000);
    EXPECT_EQ(bodyData(dom.out, "surfaces"), "2");
    const fs::path shot = scratch() / "shown.png";
    const CliResult screenshot = browse(page, "--screenshot=" + shot.string());
    ASSERT_EQ(screenshot.exitCode, 0) << screenshot.err;
    const cv::Mat image = cv::imread(shot.string(), cv::IMREAD_COLOR);
    ASSERT_FALSE(image.empty());
    // examples/two-rois.slices: Left Kidney 230 120 40; PTV has none and is
    // drawn in the palette's colour the page names.
    EXPECT_GT(pixelsLike(image, {230, 120, 40}), 500u);
    const std::string html = dfrecon::testing::slurp(page.string());
    std::smatch m;
    ASSERT_TRUE(std::regex_search(
        html, m, std::regex("\"name\":\"PTV\",\"colour\":\\[(\\d+),(\\d+),(\\d+)\\]")));
    EXPECT_GT(pixelsLike(image, {std::stod(m[1]), std::stod(m[2]), std::stod(m[3])}), 50u);
}

TEST(HtmlReport, AWholeAtlasOpensWithEveryRoi) {
    // 41 Brodmann areas from mricron-data's atlas.
#ifdef DFRECON_SANITIZE_BUILD
    GTEST_SKIP() << "41 reconstructions take minutes under the sanitizers; the two-ROI tests run";
#endif
    const std::string atlas = "/usr/share/mricron/templates/brodmann.nii.gz";
    if (!fs::exists(kChromium) || !fs::exists(atlas))
        GTEST_SKIP() << "needs " << kChromium << " and " << atlas << " (make setup)";
    const fs::path page = scratch() / "atlas.html";
    // Linear interpolation: the page is what is tested here, and it takes
    // 21 CPU-seconds where smooth takes 36 (a 62 MB page against 88 MB).
    const CliResult run =
        runDfrecon("-q reconstruct " + atlas + " --all --interpolation linear -o " +
                   (scratch() / "atlas").string() + " --report " + page.string());
    ASSERT_EQ(run.exitCode, 0) << run.err;
    const CliResult dom = dumpDom(page);
    ASSERT_EQ(dom.exitCode, 0) << dom.err;
    EXPECT_EQ(bodyData(dom.out, "webgl"), "1");
    EXPECT_EQ(bodyData(dom.out, "surfaces"), "41");
    EXPECT_NE(dom.out.find("label_48"), std::string::npos);  // the table's last row
    // The page drops its embedded data once drawn: the 62 MB of surfaces
    // are not kept in the document beside the meshes made from them.
    EXPECT_EQ(dom.out.find("id=\"dfrecon-data\""), std::string::npos);
    EXPECT_LT(dom.out.size(), std::size_t(1) << 20);
}

TEST(HtmlReport, SdmAndBatchReportPagesOpenWithTheirSurfaces) {
    if (!fs::exists(kChromium)) GTEST_SKIP() << kChromium << " missing (make setup installs it)";
    const std::string examples = DFRECON_EXAMPLES;
    // sdm: the two ROIs' meshes, each vertex coloured by its distance.
    const fs::path meshes = scratch() / "rois";
    ASSERT_EQ(
        runDfrecon("-q reconstruct " + examples + "/two-rois.slices --all -o " + meshes.string())
            .exitCode,
        0);
    const fs::path sdmPage = scratch() / "sdm.html";
    const CliResult sdm =
        runDfrecon("-q sdm " + (meshes / "Left_Kidney.ply").string() + " " +
                   (meshes / "PTV.ply").string() + " -o " + (scratch() / "sdm").string() +
                   " --size 64 --no-images --report " + sdmPage.string());
    ASSERT_EQ(sdm.exitCode, 0) << sdm.err;
    const CliResult sdmDom = dumpDom(sdmPage);
    EXPECT_EQ(bodyData(sdmDom.out, "webgl"), "1");
    EXPECT_EQ(bodyData(sdmDom.out, "surfaces"), "2");
    EXPECT_NE(sdmDom.out.find("signed distance to the nearest other mesh"), std::string::npos);
    // batch-report: a two-entry batch, every written mesh drawn.
    const fs::path archive = scratch() / "archive";
    fs::create_directories(archive);
    fs::copy_file(examples + "/two-rois.slices", archive / "two-rois.slices");
    fs::copy_file(examples + "/torus.slices", archive / "torus.slices");
    std::ofstream(archive / "manifest.csv")
        << "input,id\ntwo-rois.slices,both\ntorus.slices,torus\n";
    const fs::path out = scratch() / "batch";
    ASSERT_EQ(runDfrecon("-q batch " + (archive / "manifest.csv").string() + " -o " + out.string())
                  .exitCode,
              0);
    const fs::path batchPage = scratch() / "batch.html";
    const CliResult report =
        runDfrecon("batch-report " + out.string() + " --html " + batchPage.string());
    ASSERT_EQ(report.exitCode, 0) << report.err;
    const CliResult batchDom = dumpDom(batchPage);
    EXPECT_EQ(bodyData(batchDom.out, "webgl"), "1");
    EXPECT_EQ(bodyData(batchDom.out, "surfaces"), "3");  // two ROIs and the torus
}

TEST(HtmlReport, SegmentPageDrawsEachRegionInItsColour) {
    if (!fs::exists(kChromium)) GTEST_SKIP() << kChromium << " missing (make setup installs it)";
    const fs::path mesh = scratch() / "kidney.ply";
    ASSERT_EQ(runDfrecon("-q reconstruct " + std::string(DFRECON_EXAMPLES) +
                         "/two-rois.slices --roi \"Left Kidney\" -o " + mesh.string())
                  .exitCode,
              0);
    const fs::path page = scratch() / "segment.html";
    const CliResult run =
        runDfrecon("-q segment " + mesh.string() + " -k 5 --json -o " +
                   (scratch() / "regions.ply").string() + " --report " + page.string());
    ASSERT_EQ(run.exitCode, 0) << run.err;
    const nlohmann::json json = nlohmann::json::parse(run.out);
    const CliResult dom = dumpDom(page);
    ASSERT_EQ(dom.exitCode, 0) << dom.err;
    EXPECT_EQ(bodyData(dom.out, "webgl"), "1");
    // One surface per region, as many as the JSON report counts.
    EXPECT_EQ(bodyData(dom.out, "surfaces"), std::to_string(json["regionCount"].get<int>()));
    // Each region's colour is the one the output PLY gives its faces; the
    // page names it beside the region (surfaces are named as their rows).
    const std::string html = dfrecon::testing::slurp(page.string());
    std::smatch m;
    ASSERT_TRUE(std::regex_search(
        html, m, std::regex("\"name\":\"0\",\"colour\":\\[(\\d+),(\\d+),(\\d+)\\]")));
    const fs::path shot = scratch() / "segment.png";
    ASSERT_EQ(browse(page, "--screenshot=" + shot.string()).exitCode, 0);
    const cv::Mat image = cv::imread(shot.string(), cv::IMREAD_COLOR);
    ASSERT_FALSE(image.empty());
    std::size_t coloured = 0;
    for (int r = 0; r < json["regionCount"].get<int>(); ++r) {
        std::smatch c;
        ASSERT_TRUE(std::regex_search(html, c,
                                      std::regex("\"name\":\"" + std::to_string(r) +
                                                 "\",\"colour\":\\[(\\d+),(\\d+),(\\d+)\\]")));
        if (pixelsLike(image, {std::stod(c[1]), std::stod(c[2]), std::stod(c[3])}) > 50) ++coloured;
    }
    // A view from one side shows at least two of the regions.
    EXPECT_GE(coloured, 2u);
}

TEST(HtmlReport, HostileNamesStayTextAndThePageDraws) {
    // Names a planning system lets a user type: each would end the page's
    // data block or change the HTML parser's state if written raw.
    const std::string hostile[] = {"</script><script>document.title='ran'</script>", "<!--<script>",
                                   "A&B>C \xE2\x80\xA8 line"};
    std::string slices =
        dfrecon::testing::slurp(std::string(DFRECON_EXAMPLES) + "/two-rois.slices");
    slices.replace(slices.find("\"Left Kidney\""), 13, "\"" + hostile[0] + "\"");
    slices.replace(slices.find("roi PTV"), 7, "roi \"" + hostile[1] + hostile[2] + "\"");
    const fs::path input = scratch() / "hostile.slices";
    std::ofstream(input) << slices;
    const fs::path page = scratch() / "hostile.html";
    const CliResult run = runDfrecon("-q reconstruct " + input.string() + " --all -o " +
                                     (scratch() / "out").string() + " --report " + page.string());
    ASSERT_EQ(run.exitCode, 0) << run.err;
    // The data block holds no markup at all: no '<', '>' or '&', no raw
    // line separator.
    const std::string html = dfrecon::testing::slurp(page.string());
    const std::string open = "<script id=\"dfrecon-data\" type=\"application/json\">";
    const std::size_t begin = html.find(open) + open.size();
    const std::string data = html.substr(begin, html.find("</script>", begin) - begin);
    EXPECT_EQ(data.find_first_of("<>&"), std::string::npos);
    EXPECT_EQ(data.find("\xE2\x80\xA8"), std::string::npos);
    // JSON.parse gives the names back as they were.
    const nlohmann::json parsed = nlohmann::json::parse(data);
    const std::string names = parsed["rows"].dump();
    EXPECT_NE(names.find(nlohmann::json(hostile[0]).dump()), std::string::npos) << names;
    if (!fs::exists(kChromium)) GTEST_SKIP() << kChromium << " missing (make setup installs it)";
    const CliResult dom = dumpDom(page);
    ASSERT_EQ(dom.exitCode, 0) << dom.err;
    // The page drew both surfaces, no injected script ran, and the table
    // shows the names as text (escaped in the dumped DOM).
    EXPECT_EQ(bodyData(dom.out, "surfaces"), "2") << dom.out.substr(0, 3000);
    EXPECT_EQ(dom.out.find("<title>ran</title>"), std::string::npos);
    EXPECT_NE(dom.out.find("&lt;/script&gt;&lt;script&gt;document.title='ran'&lt;/script&gt;"),
              std::string::npos);
    EXPECT_NE(dom.out.find("&lt;!--&lt;script&gt;A&amp;B&gt;C"), std::string::npos);
}

namespace report_views_test {

// A .slices file: a box ROI `name` of x × y on planes z0..z1 every 5 mm.
std::string boxRoi(const std::string& name, const std::string& colour, double x, double y,
                   double z0, double z1) {
    std::string text = "roi " + name + " " + colour + "\n";
    for (double z = z0; z <= z1 + 1e-9; z += 5) {
        text += "slice " + std::to_string(z) + "\ncontour 4\n";
        text += std::to_string(-x / 2) + " " + std::to_string(-y / 2) + "\n";
        text += std::to_string(x / 2) + " " + std::to_string(-y / 2) + "\n";
        text += std::to_string(x / 2) + " " + std::to_string(y / 2) + "\n";
        text += std::to_string(-x / 2) + " " + std::to_string(y / 2) + "\n";
    }
    return text;
}

// Pixels of the view's half where green leads red and blue by 30.
std::size_t greenPixels(const cv::Mat& image) {
    std::size_t count = 0;
    for (int y = 0; y < image.rows; ++y)
        for (int x = image.cols / 2; x < image.cols; ++x) {
            const cv::Vec3b bgr = image.at<cv::Vec3b>(y, x);
            if (bgr[1] > bgr[2] + 30 && bgr[1] > bgr[0] + 30) ++count;
        }
    return count;
}

// Pixels of the view's half that are not its background (0x20242a).
std::size_t drawnPixels(const cv::Mat& image) {
    std::size_t count = 0;
    for (int y = 0; y < image.rows; ++y)
        for (int x = image.cols / 2; x < image.cols; ++x) {
            const cv::Vec3b bgr = image.at<cv::Vec3b>(y, x);
            if (std::abs(int(bgr[2]) - 0x20) + std::abs(int(bgr[1]) - 0x24) +
                    std::abs(int(bgr[0]) - 0x2a) >
                40)
                ++count;
        }
    return count;
}

}  // namespace report_views_test

TEST(HtmlReport, OutlinesAreTranslucentAndViewsAreAnatomical) {
    if (!fs::exists(kChromium)) GTEST_SKIP() << kChromium << " missing (make setup installs it)";
    using namespace report_views_test;
    // A wide, shallow body (60 × 20 × 40 mm) around a green organ.
    const fs::path input = scratch() / "nested.slices";
    std::ofstream(input) << "dfrecon-slices 1\nunits mm\n"
                         << boxRoi("Body", "230 40 40", 60, 20, 0, 40)
                         << boxRoi("Organ", "0 200 0", 10, 8, 10, 30);
    const fs::path page = scratch() / "nested.html";
    ASSERT_EQ(runDfrecon("-q reconstruct " + input.string() + " --all -o " +
                         (scratch() / "nested").string() + " --report " + page.string())
                  .exitCode,
              0);
    // Anterior by default, named on the page; the organ shows through the
    // body, which starts translucent because it holds the organ.
    const CliResult dom = dumpDom(page);
    EXPECT_EQ(bodyData(dom.out, "view"), "anterior");
    EXPECT_EQ(bodyData(dom.out, "surfaces"), "2");
    const fs::path front = scratch() / "anterior.png";
    ASSERT_EQ(browse(page, "--screenshot=" + front.string()).exitCode, 0);
    const cv::Mat anterior = cv::imread(front.string(), cv::IMREAD_COLOR);
    ASSERT_FALSE(anterior.empty());
    EXPECT_GT(greenPixels(anterior), 200u);
    // From above the body shows its 60 × 20 face instead of 60 × 40.
    const fs::path top = scratch() / "superior.png";
    const fs::path superiorPage = scratch() / "nested.html#view=superior";
    ASSERT_EQ(browse(superiorPage, "--screenshot=" + top.string()).exitCode, 0);
    const cv::Mat superior = cv::imread(top.string(), cv::IMREAD_COLOR);
    ASSERT_FALSE(superior.empty());
    EXPECT_LT(double(drawnPixels(superior)), 0.75 * double(drawnPixels(anterior)));
    EXPECT_EQ(bodyData(dumpDom(superiorPage).out, "view"), "superior");
}
