// tests/renderer/texture_render_test.cpp: texture-displaced surfaces through the whole renderer
// (issue 16): one height map written in every format the issue names (EXR in float and half,
// tiled EXR, TIFF, PNG, JPEG, and a tiled, mip-mapped .tx made by OpenImageIO's maketx), each
// displacing a plane seen obliquely. Every render converges (no ray at the depth limit, certified
// errors finite), and the images agree: bit for bit between the formats that keep the texels
// exactly, within the quantisation of the half, 8-bit and lossy ones.

#include <catch2/catch.hpp>

#include <cmath>
#include <sstream>
#include <vector>

#include "tests/renderer/render_coverage.h"
#include "tests/texture/texture_test_util.h"

using namespace affray;

namespace {

constexpr int kMapSize = 64;

/// Rounded bumps in [0, 1]: smooth enough for 8-bit and JPEG copies to stay close.
std::vector<float> Bumps() {
    std::vector<float> texels;
    for (int y = 0; y < kMapSize; ++y)
        for (int x = 0; x < kMapSize; ++x) {
            const double u = (x + 0.5) / kMapSize, v = (y + 0.5) / kMapSize;
            texels.push_back(static_cast<float>(0.5 + 0.25 * std::sin(6 * M_PI * u) * std::sin(4 * M_PI * v) +
                                                0.2 * std::cos(2 * M_PI * (u + v))));
        }
    return texels;
}

struct Rendered {
    image::ImageBuffer image;
    renderer::RenderStats stats;
};

/// The plane displaced by `map`, rendered (one sample per pixel, no ray at the depth limit).
Rendered RenderWithMap(const test::TempDir& dir, const std::string& map) {
    const std::string rib =
        "Format 40 30 1\nProjection \"perspective\" \"fov\" [40]\n"
        "Translate 0 0 1.3\nRotate -120 1 0 0\nWorldBegin\n"
        "LightSource \"distantlight\" 1 \"from\" [-1 -2 3] \"to\" [0 0 0]\n"
        "Displacement \"heights\" \"string map\" [\"" +
        map +
        "\"]\n"
        "Patch \"bilinear\" \"P\" [-0.5 -0.5 0  0.5 -0.5 0  -0.5 0.5 0  0.5 0.5 0]\nWorldEnd\n";
    Rendered r;
    r.image = test::RenderRib(dir, rib, &r.stats);
    return r;
}

/// The root mean square difference of the RGBA values of two images of one size.
double Rmse(const image::ImageBuffer& a, const image::ImageBuffer& b) {
    REQUIRE(a.rgba.size() == b.rgba.size());
    double sum = 0;
    for (size_t i = 0; i < a.rgba.size(); ++i) sum += std::pow(double(a.rgba[i]) - double(b.rgba[i]), 2);
    return std::sqrt(sum / double(a.rgba.size()));
}

}  // namespace

TEST_CASE("texture render: one map in every format displaces a plane with certified hits", "[renderer][texture]") {
    test::TempDir dir;
    dir.Write("heights.sl",
              "displacement heights(string map = \"\"; float Km = 0.12) {\n"
              "    P += Km * texture(map, s, t) * normalize(N);\n"
              "    N = calculatenormal(P);\n}\n");
    const std::vector<float> texels = Bumps();
    auto write = [&](const char* name, test::tex::PixelFormat format, int tile = 0) {
        test::tex::ImageLayout layout;
        layout.format = format;
        layout.tile = tile;
        test::tex::WriteImage(dir.Path(name), kMapSize, kMapSize, 1, texels, layout);
    };
    write("float.exr", test::tex::PixelFormat::Float);
    write("tiled.exr", test::tex::PixelFormat::Float, 16);
    write("float.tif", test::tex::PixelFormat::Float);
    write("half.exr", test::tex::PixelFormat::Half);
    write("bytes.png", test::tex::PixelFormat::UInt8);
    write("lossy.jpg", test::tex::PixelFormat::UInt8);
    // The .tx a pipeline gets from maketx: tiled, mip-mapped TIFF, texels kept as float.
    {
        // maketx writes "black" wrap modes unless told: the lookups follow the file's.
        std::string error;
        const bool made = test::tex::Images().MakeTx(dir.Path("float.exr"), dir.Path("maketx.tx"), "periodic,periodic",
                                                     test::tex::PixelFormat::Float, &error);
        INFO(error);
        REQUIRE(made);
    }

    const Rendered reference = RenderWithMap(dir, "float.exr");
    size_t hits = 0;
    for (size_t i = 3; i < reference.image.rgba.size(); i += 4) hits += reference.image.rgba[i] > 0;
    CHECK(hits > 500);
    struct Case {
        const char* file;
        double rmse;  // difference from the float EXR's image
    };
    for (const Case& c : {Case{"float.exr", 0}, Case{"tiled.exr", 0}, Case{"float.tif", 0}, Case{"maketx.tx", 0},
                          Case{"half.exr", 1e-3}, Case{"bytes.png", 0.01}, Case{"lossy.jpg", 0.05}}) {
        INFO(c.file);
        const Rendered r = RenderWithMap(dir, c.file);
        CHECK(r.stats.camera.depthLimitHits == 0);
        CHECK(r.stats.camera.budgetExhausted == 0);
        CHECK(std::isfinite(r.stats.camera.maxHitError));
        const double difference = Rmse(reference.image, r.image);
        INFO("RMSE " << difference);
        CHECK(difference <= c.rmse);
        if (c.rmse == 0) CHECK(r.image.rgba == reference.image.rgba);
    }
}

TEST_CASE("texture render: MakeTexture makes a tiled, mip-mapped texture that a shader reads",
          "[renderer][texture][rib]") {
    // Named as affray's tools name it (.tx) or as prman's txmake does (.tex): a TIFF either way.
    const std::string name = GENERATE(as<std::string>(), "made.tx", "made.tex");
    INFO(name);
    test::TempDir dir;
    dir.Write("heights.sl",
              "displacement heights(string map = \"\"; float Km = 0.12) {\n"
              "    P += Km * texture(map, s, t) * normalize(N);\n}\n");
    std::vector<float> texels = Bumps();
    test::tex::ImageLayout bytes;
    bytes.format = test::tex::PixelFormat::UInt8;
    test::tex::WriteImage(dir.Path("picture.png"), kMapSize, kMapSize, 1, texels, bytes);
    const std::string scene = "MakeTexture \"picture.png\" \"" + name + "\" \"clamp\" \"black\" \"gaussian\" 2 2\n";
    Rendered made;
    made.image = test::RenderRib(dir,
                                 scene +
                                     "Format 40 30 1\nProjection \"perspective\" \"fov\" [40]\n"
                                     "Translate 0 0 1.3\nRotate -120 1 0 0\nWorldBegin\n"
                                     "Displacement \"heights\" \"string map\" [\"" +
                                     name +
                                     "\"]\n"
                                     "Patch \"bilinear\" \"P\" [-0.5 -0.5 0  0.5 -0.5 0  -0.5 0.5 0  0.5 0.5 0]\n"
                                     "WorldEnd\n",
                                 &made.stats);
    // The file: tiled, mip-mapped, the wrap modes of the request; texels those of the picture.
    const image::io::ImageHeader header = test::tex::ReadHeader(dir.Path(name));
    CHECK(header.tileWidth > 0);
    CHECK(header.mipLevels > 1);
    CHECK(header.wrapmodes == "clamp,black");
    std::string error;
    auto map = texture::Open(dir.Path(name), &error);
    REQUIRE(map);
    CHECK(map->swrap() == texture::Wrap::Clamp);
    CHECK(map->twrap() == texture::Wrap::Black);
    int w = 0, h = 0, c = 0;
    const std::vector<float> picture = test::tex::ReadImage(dir.Path("picture.png"), &w, &h, &c);
    for (int y = 0; y < h; y += 7)
        for (int x = 0; x < w; x += 5) CHECK(map->Texel(x, y, 0) == picture[static_cast<size_t>(y) * w + x]);
    CHECK(made.stats.camera.depthLimitHits == 0);
    size_t hits = 0;
    for (size_t i = 3; i < made.image.rgba.size(); i += 4) hits += made.image.rgba[i] > 0;
    CHECK(hits > 500);
}

TEST_CASE("texture render: only a scene that reads an image loads the image module", "[renderer][texture]") {
    // OpenImageIO is a module loaded on first use (image/image_io.h): a scene without maps
    // must not pay its start-up. CTest runs each test case in a process of its own.
    REQUIRE_FALSE(image::io::Loaded());
    test::TempDir dir;
    dir.Write("bumps.sl", "displacement bumps(float Km = 0.05) {\n    P += Km * noise(P * 4) * normalize(N);\n}\n");
    const std::string head = "Format 16 12 1\nProjection \"perspective\" \"fov\" [40]\nTranslate 0 0 3\nWorldBegin\n";
    test::RenderRib(dir, head + "Displacement \"bumps\"\nSphere 1 -1 1 360\nWorldEnd\n");
    CHECK_FALSE(image::io::Loaded());

    test::tex::WriteImage(dir.Path("map.exr"), 8, 8, 1, std::vector<float>(64, 0.5f));
    CHECK(image::io::Loaded());
    dir.Write("heights.sl",
              "displacement heights(string map = \"\") {\n    P += 0.1 * texture(map, s, t) * normalize(N);\n}\n");
    const image::ImageBuffer image = test::RenderRib(
        dir, head + "Displacement \"heights\" \"string map\" [\"map.exr\"]\nSphere 1 -1 1 360\nWorldEnd\n");
    size_t hits = 0;
    for (size_t i = 3; i < image.rgba.size(); i += 4) hits += image.rgba[i] > 0;
    CHECK(hits > 20);
}
