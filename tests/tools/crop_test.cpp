// tests/tools/crop_test.cpp: `affray render --crop` end to end. Crops of a partition of the
// frame, pasted together with renderer::PasteCrop over the pixel rectangles renderer::CropPixels
// gives, must rebuild the whole render bit for bit in every channel (RGBA and every AOV), with
// the default 2 x 2 samples and gaussian filter whose footprint reaches across crop edges. A crop
// render is a full-resolution image that is zero outside its window.
#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <sstream>

#include "image/exr_writer.h"
#include "renderer/film.h"
#include "tests/test_util.h"

using namespace affray;

namespace {

constexpr int kWidth = 40, kHeight = 30;

std::string Scene() { return test::WaveSphereScene(kWidth, kHeight, "crop.exr"); }

image::ImageBuffer Read(const std::string& path) {
    image::ImageBuffer image;
    affray::diag::Report error;
    INFO(error);
    REQUIRE(image::ReadExrRgba(path, &image, &error));
    return image;
}

/// Renders the scene in `dir` with `extra` arguments into `name`; returns the image.
image::ImageBuffer Render(const test::TempDir& dir, const std::string& name, const std::string& extra) {
    test::CliOutput out = test::RunCli(
        "render " + test::Quote(dir.Path("scene.rib")) + " -o " + test::Quote(dir.Path(name)) + " --quiet " + extra,
        true);
    INFO(out.out);
    REQUIRE(out.status == 0);
    return Read(dir.Path(name));
}

/// The pixels of the crop window [x0,x1] x [y0,y1] at the scene's resolution.
renderer::PixelRange Pixels(const std::array<double, 4>& window) {
    renderer::CameraDesc camera;
    camera.xres = kWidth;
    camera.yres = kHeight;
    camera.cropWindow = glm::dvec4(window[0], window[1], window[2], window[3]);
    return renderer::CropPixels(camera);
}

std::string CropArg(const std::array<double, 4>& w) {
    std::ostringstream out;
    out << w[0] << "," << w[1] << "," << w[2] << "," << w[3];
    return out.str();
}

bool SameBits(float a, float b) { return std::bit_cast<uint32_t>(a) == std::bit_cast<uint32_t>(b); }

bool SameBits(const std::vector<float>& a, const std::vector<float>& b) {
    return std::equal(a.begin(), a.end(), b.begin(), b.end(), [](float x, float y) { return SameBits(x, y); });
}

/// The first pixel where `a` and `b` differ in a channel of `components` floats per pixel.
std::string FirstDifference(const std::vector<float>& a, const std::vector<float>& b, int components) {
    if (a.size() != b.size()) return "sizes " + std::to_string(a.size()) + " and " + std::to_string(b.size());
    for (size_t i = 0; i < a.size(); ++i)
        if (!SameBits(a[i], b[i])) {
            const size_t pixel = i / components;
            std::ostringstream out;
            out.precision(9);
            out << "pixel (" << pixel % kWidth << "," << pixel / kWidth << ") component " << i % components << ": "
                << a[i] << " vs " << b[i];
            return out.str();
        }
    return "none";
}

/// Renders the crops of `windows` (a partition of the frame), pastes them and compares with `whole`.
void CheckCropsRebuild(const test::TempDir& dir, const image::ImageBuffer& whole,
                       const std::vector<std::array<double, 4>>& windows) {
    image::ImageBuffer merged;
    int pixels = 0;
    for (size_t k = 0; k < windows.size(); ++k) {
        const renderer::PixelRange range = Pixels(windows[k]);
        INFO("crop " << CropArg(windows[k]) << " = pixels " << renderer::ToString(range));
        REQUIRE_FALSE(range.empty());
        pixels += range.width() * range.height();
        image::ImageBuffer crop = Render(dir, "crop" + std::to_string(k) + ".exr", "--crop " + CropArg(windows[k]));
        REQUIRE(crop.width == kWidth);
        REQUIRE(crop.height == kHeight);
        REQUIRE(crop.extraChannels.size() == whole.extraChannels.size());
        // Outside its window a crop render is 0 in every channel.
        int nonzeroOutside = 0;
        for (int y = 0; y < kHeight; ++y)
            for (int x = 0; x < kWidth; ++x) {
                if (range.Contains(x, y)) continue;
                const size_t i = static_cast<size_t>(y) * kWidth + x;
                for (int c = 0; c < 4; ++c) nonzeroOutside += crop.rgba[i * 4 + c] != 0.0f;
                for (const auto& [name, values] : crop.extraChannels) nonzeroOutside += values[i] != 0.0f;
            }
        CHECK(nonzeroOutside == 0);
        // Inside, some pixels are covered (alpha 1): the crop did render something.
        int covered = 0;
        for (int y = range.y0; y < range.y1; ++y)
            for (int x = range.x0; x < range.x1; ++x)
                covered += crop.rgba[(static_cast<size_t>(y) * kWidth + x) * 4 + 3] > 0;
        CHECK(covered > 0);
        std::string error;
        INFO(error);
        REQUIRE(renderer::PasteCrop(crop, range, &merged, &error));
    }
    REQUIRE(pixels == kWidth * kHeight);  // the windows partition the pixels
    REQUIRE(merged.width == kWidth);
    REQUIRE(merged.height == kHeight);
    INFO("RGBA first difference: " << FirstDifference(merged.rgba, whole.rgba, 4));
    CHECK(SameBits(merged.rgba, whole.rgba));
    REQUIRE(merged.extraChannels.size() == whole.extraChannels.size());
    for (size_t c = 0; c < whole.extraChannels.size(); ++c) {
        INFO("channel " << whole.extraChannels[c].first << ", first difference: "
                        << FirstDifference(merged.extraChannels[c].second, whole.extraChannels[c].second, 1));
        CHECK(merged.extraChannels[c].first == whole.extraChannels[c].first);
        CHECK(SameBits(merged.extraChannels[c].second, whole.extraChannels[c].second));
    }
}

}  // namespace

TEST_CASE("crop: crop renders pasted together equal the whole render bit for bit", "[tools][crop]") {
    test::TempDir dir;
    dir.Write("scene.rib", Scene());
    std::filesystem::copy_file(test::SourceDir() + "/shaders/wave.sl", dir.Path("wave.sl"));
    const image::ImageBuffer whole = Render(dir, "whole.exr", "");
    REQUIRE(whole.width == kWidth);
    REQUIRE(whole.height == kHeight);
    // Every AOV of the Display mode is there, and the scene shows both surfaces and background.
    std::vector<std::string> names;
    for (const auto& [name, values] : whole.extraChannels) names.push_back(name);
    std::sort(names.begin(), names.end());  // the file's order
    CHECK(names ==
          std::vector<std::string>{"N.X", "N.Y", "N.Z", "P.X", "P.Y", "P.Z", "Z", "cost", "err", "st.s", "st.t"});
    int covered = 0;
    for (int i = 0; i < kWidth * kHeight; ++i) covered += whole.rgba[i * 4 + 3] == 1.0f;
    CHECK(covered > kWidth * kHeight / 3);
    CHECK(covered < kWidth * kHeight);

    // Four quadrants, then an uneven split (40 * 0.3 and 30 * 0.55 fall off pixel centres).
    // (Not SECTIONs: each would render the whole image again.)
    CheckCropsRebuild(dir, whole, {{0, 0.5, 0, 0.5}, {0.5, 1, 0, 0.5}, {0, 0.5, 0.5, 1}, {0.5, 1, 0.5, 1}});
    CheckCropsRebuild(dir, whole, {{0, 0.3, 0, 0.55}, {0.3, 1, 0, 0.55}, {0, 0.3, 0.55, 1}, {0.3, 1, 0.55, 1}});
}

TEST_CASE("crop: a pasted crop differs from the whole render when a crop is missing", "[tools][crop]") {
    // The comparison above can fail: three quadrants pasted leave the fourth zero.
    test::TempDir dir;
    dir.Write("scene.rib", Scene());
    std::filesystem::copy_file(test::SourceDir() + "/shaders/wave.sl", dir.Path("wave.sl"));
    const image::ImageBuffer whole = Render(dir, "whole.exr", "--samples 1");
    const std::array<double, 4> window{0, 0.5, 0, 0.5};
    image::ImageBuffer crop = Render(dir, "crop.exr", "--samples 1 --crop " + CropArg(window));
    image::ImageBuffer merged;
    std::string error;
    REQUIRE(renderer::PasteCrop(crop, Pixels(window), &merged, &error));
    CHECK_FALSE(SameBits(merged.rgba, whole.rgba));
    // Inside the window the crop equals the whole render.
    const renderer::PixelRange range = Pixels(window);
    int differ = 0;
    for (int y = range.y0; y < range.y1; ++y)
        for (int x = range.x0; x < range.x1; ++x)
            for (int c = 0; c < 4; ++c) {
                const size_t i = (static_cast<size_t>(y) * kWidth + x) * 4 + c;
                differ += !SameBits(crop.rgba[i], whole.rgba[i]);
            }
    CHECK(differ == 0);
}
