// tests/renderer/primvar_render_test.cpp: "Cs" and "Os" through the whole renderer (rib/, the
// colour fields of scene/geometry/primvar.h, renderer/render.cpp): a vertex-coloured mesh
// shows its vertices' colours at its corners, and partly transparent surfaces are composited
// front to back over what lies behind them, alpha their coverage.
#include <catch2/catch.hpp>

#include "tests/renderer/render_coverage.h"

using namespace affray;

namespace {

glm::dvec3 Rgb(const image::ImageBuffer& image, int x, int y) {
    const size_t i = 4 * (static_cast<size_t>(y) * image.width + x);
    return {image.rgba[i], image.rgba[i + 1], image.rgba[i + 2]};
}
float Alpha(const image::ImageBuffer& image, int x, int y) {
    return image.rgba[4 * (static_cast<size_t>(y) * image.width + x) + 3];
}

/// An orthographic camera looking at [-1, 1]^2 of the plane z = 0 along +z from z = -5, 32 x 32
/// pixels.
const char* const kCamera =
    "Format 32 32 1\nScreenWindow -1 1 -1 1\nTranslate 0 0 5\nWorldBegin\nSurface \"constant\"\n";

}  // namespace

TEST_CASE("primvar render: a vertex-coloured mesh is coloured corner to corner", "[renderer][primvar]") {
    test::TempDir dir;
    const std::string rib = std::string(kCamera) +
                            "PointsPolygons [4] [0 1 2 3] \"P\" [-1 -1 0  1 -1 0  1 1 0  -1 1 0]\n"
                            "  \"Cs\" [1 0 0  0 1 0  0 0 1  1 1 1]\nWorldEnd\n";
    const image::ImageBuffer image = test::RenderRib(dir, rib);
    // The corners' pixels are nearest their vertices' colours; the image's y runs down and
    // world y up, so vertex 0 (-1, -1) is at the bottom left.
    const glm::dvec3 bottomLeft = Rgb(image, 0, 31), bottomRight = Rgb(image, 31, 31), topRight = Rgb(image, 31, 0),
                     topLeft = Rgb(image, 0, 0);
    CHECK(bottomLeft.r > 0.9);
    CHECK(bottomLeft.g < 0.1);
    CHECK(bottomRight.g > 0.9);
    CHECK(bottomRight.r < 0.1);
    CHECK(topRight.b > 0.9);
    CHECK(topRight.r < 0.1);
    CHECK(glm::length(topLeft - glm::dvec3(1.0)) < 0.1);
    // The centre is the mean of the four.
    const glm::dvec3 centre =
        0.25 * (Rgb(image, 15, 15) + Rgb(image, 16, 15) + Rgb(image, 15, 16) + Rgb(image, 16, 16));
    CHECK(glm::length(centre - glm::dvec3(0.5)) < 0.02);
}

TEST_CASE("primvar render: partly transparent surfaces composite front to back", "[renderer][primvar]") {
    test::TempDir dir;
    // A red square of opacity 0.5 over the left half, and behind it an opaque blue square
    // over the top half. (The camera looks along +z: the red square, at z = -1, is in front.)
    const std::string rib = std::string(kCamera) +
                            "AttributeBegin\nOpacity 0.5 0.5 0.5\nColor 1 0 0\n"
                            "Patch \"bilinear\" \"P\" [-1 -1 -1  0 -1 -1  -1 1 -1  0 1 -1]\nAttributeEnd\n"
                            "Color 0 0 1\nPatch \"bilinear\" \"P\" [-1 0 0  1 0 0  -1 1 0  1 1 0]\nWorldEnd\n";
    const image::ImageBuffer image = test::RenderRib(dir, rib);
    // Through both: half the red, then half of the blue behind it.
    CHECK(glm::length(Rgb(image, 4, 4) - glm::dvec3(0.5, 0, 0.5)) < 1e-6);
    CHECK(Alpha(image, 4, 4) == 1.0f);
    // The red alone: half covered.
    CHECK(glm::length(Rgb(image, 4, 28) - glm::dvec3(0.5, 0, 0)) < 1e-6);
    CHECK(Alpha(image, 4, 28) == 0.5f);
    // The blue alone.
    CHECK(glm::length(Rgb(image, 28, 4) - glm::dvec3(0, 0, 1)) < 1e-6);
    CHECK(Alpha(image, 28, 28) == 0.0f);
    // The blue square 0.01 behind the red one, within the red hit's certified error (a pixel is
    // 0.0625 here): the ray goes on past the red square alone, and still meets the blue one.
    const std::string close = std::string(kCamera) +
                              "AttributeBegin\nOpacity 0.5 0.5 0.5\nColor 1 0 0\n"
                              "Patch \"bilinear\" \"P\" [-1 -1 -1  0 -1 -1  -1 1 -1  0 1 -1]\nAttributeEnd\n"
                              "Color 0 0 1\nPatch \"bilinear\" \"P\" [-1 0 -0.99  1 0 -0.99  -1 1 -0.99  1 1 -0.99]\n"
                              "WorldEnd\n";
    const image::ImageBuffer near = test::RenderRib(dir, close);
    CHECK(glm::length(Rgb(near, 4, 4) - glm::dvec3(0.5, 0, 0.5)) < 1e-6);
    CHECK(Alpha(near, 4, 4) == 1.0f);
    // An "Os" primitive variable: opaque at the left edge, clear at the right, over the blue.
    const std::string varying = std::string(kCamera) +
                                "Color 1 0 0\nPatch \"bilinear\" \"P\" [-1 -1 -1  1 -1 -1  -1 1 -1  1 1 -1]"
                                " \"Os\" [1 1 1  0 0 0  1 1 1  0 0 0]\n"
                                "Color 0 0 1\nPatch \"bilinear\" \"P\" [-1 0 0  1 0 0  -1 1 0  1 1 0]\nWorldEnd\n";
    const image::ImageBuffer ramp = test::RenderRib(dir, varying);
    for (int x : {0, 10, 20, 31}) {
        const double os = 1 - (x + 0.5) / 32;  // at the pixel's centre
        CHECK(glm::length(Rgb(ramp, x, 4) - glm::dvec3(os, 0, 1 - os)) < 1e-6);
        CHECK(Alpha(ramp, x, 28) == Approx(os).epsilon(1e-6));
    }
}
