// tests/renderer/tiling_test.cpp: renderer/tiling.h. SplitFrame covers every frame exactly once
// with non-empty rectangles, awkward sizes and prime tile counts included; CropWindowText gives
// crop windows that the renderer's crop rule (CropPixels) maps back to exactly those rectangles;
// the header attributes round trip and are refused when missing or outside the image.
#include <catch2/catch.hpp>

#include <cstdlib>
#include <sstream>

#include "renderer/tiling.h"

using namespace affray;
using renderer::PixelRange;

namespace {

/// The pixels of the crop text "x0,x1,y0,y1" at width x height, read as affray render reads it.
PixelRange PixelsOf(const std::string& text, int width, int height) {
    std::vector<double> v;
    std::stringstream in(text);
    std::string item;
    while (std::getline(in, item, ',')) v.push_back(std::strtod(item.c_str(), nullptr));
    REQUIRE(v.size() == 4);
    REQUIRE((0 <= v[0] && v[0] < v[1] && v[1] <= 1 && 0 <= v[2] && v[2] < v[3] && v[3] <= 1));
    renderer::CameraDesc camera;
    camera.xres = width;
    camera.yres = height;
    camera.cropWindow = glm::dvec4(v[0], v[1], v[2], v[3]);
    return renderer::CropPixels(camera);
}

}  // namespace

TEST_CASE("tiling: tiles cover the frame exactly once and their crop windows map to them", "[renderer]") {
    const std::pair<int, int> sizes[] = {{67, 41}, {64, 48}, {640, 480}, {1, 1}, {3, 200}, {1920, 1080}, {7, 7}};
    for (const auto& [width, height] : sizes)
        for (int tiles : {1, 2, 3, 4, 5, 7, 12, 13, 64, 97}) {
            INFO(width << "x" << height << " in " << tiles << " tiles");
            const std::vector<PixelRange> ranges = renderer::SplitFrame(width, height, tiles);
            if (tiles > width * height) {
                CHECK(ranges.empty());
                continue;
            }
            if (ranges.empty()) continue;  // a layout the frame is too narrow for (3 wide)
            REQUIRE(ranges.size() == size_t(tiles));
            std::vector<int> count(size_t(width) * height, 0);
            for (const PixelRange& r : ranges) {
                REQUIRE_FALSE(r.empty());
                for (int y = r.y0; y < r.y1; ++y)
                    for (int x = r.x0; x < r.x1; ++x) ++count[size_t(y) * width + x];
                const std::string crop = renderer::CropWindowText(r, width, height);
                INFO("tile " << renderer::ToString(r) << " crop " << crop);
                CHECK(PixelsOf(crop, width, height) == r);
            }
            CHECK(std::all_of(count.begin(), count.end(), [](int c) { return c == 1; }));
        }
    // The 67 x 41 frame in 7 tiles is cut, not refused, and its windows are short decimals.
    REQUIRE(renderer::SplitFrame(67, 41, 7).size() == 7);
    CHECK(renderer::CropWindowText({0, 67, 0, 41}, 67, 41) == "0,1,0,1");
    CHECK(renderer::CropWindowText({0, 32, 12, 24}, 64, 48) == "0,0.5,0.25,0.5");
    CHECK(renderer::SplitFrame(4, 4, 0).empty());
    CHECK(renderer::SplitFrame(2, 2, 5).empty());
}

TEST_CASE("tiling: the header attributes round trip and are checked", "[renderer]") {
    image::ImageBuffer image;
    image.width = 10;
    image.height = 8;
    const renderer::RenderIdentity identity{"0123456789abcdef0123456789abcdef", "resolution=10x8\nsamples=2x2\n"};
    renderer::StampTile(identity, {2, 7, 0, 8}, "9.9.9", &image);
    std::string error;
    std::optional<renderer::TileHeader> header = renderer::ReadTileHeader(image, &error);
    INFO(error);
    REQUIRE(header);
    CHECK(header->version == "9.9.9");
    CHECK(header->identity == identity.Hash());
    CHECK(header->scene == identity.scene);
    CHECK(header->options == identity.options);
    CHECK(header->pixels == PixelRange{2, 7, 0, 8});

    image::ImageBuffer outside = image;
    outside.attributes["affray:pixels"] = "2,11,0,8";
    CHECK_FALSE(renderer::ReadTileHeader(outside, &error));
    CHECK(error.find("outside its 10x8 image") != std::string::npos);
    image::ImageBuffer malformed = image;
    malformed.attributes["affray:pixels"] = "2,7,0";
    CHECK_FALSE(renderer::ReadTileHeader(malformed, &error));
    CHECK(error.find("affray:pixels") != std::string::npos);
    image::ImageBuffer bare = image;
    bare.attributes.erase("affray:scene");
    CHECK_FALSE(renderer::ReadTileHeader(bare, &error));
    CHECK(error == "its header has no affray:scene attribute (not an image of affray render)");
}
