// tests/tools/frames_cli_test.cpp: `affray render` on files with several frames (tools/commands.cpp
// RunRender): each image frame to its Display, shadow passes skipped, --frame, -o numbering, the
// errors and their exit codes; and Illuminate seen in the pixels of a render.
#include <catch2/catch.hpp>
#include <filesystem>
#include <string>

#include "image/exr_writer.h"
#include "tests/test_util.h"

namespace fs = std::filesystem;
using namespace affray;

namespace {

// A small three-frame scene in `dir`: frame 1 a depth map pass, frames 2 and 3 images written
// to dir/two.exr and dir/three.exr.
std::string ThreeFrames(const test::TempDir& dir) {
    const std::string body = R"(
  WorldBegin
    LightSource "shadowspot" 1 "from" [0 4 -4] "to" [0 0 0] "shadowname" "key.shd" "samples" [16]
    Sphere 1 -1 1 360
  WorldEnd
)";
    return "Format 8 6 1\nPixelSamples 1 1\nProjection \"perspective\" \"fov\" [40]\n"
           "FrameBegin 1\n  Display \"" +
           dir.Path("key.z") + "\" \"zfile\" \"z\"\n  Translate 0 0 4" + body +
           "FrameEnd\nMakeShadow \"key.z\" \"key.shd\"\nFrameBegin 2\n  Display \"" + dir.Path("two.exr") +
           "\" \"file\" \"rgba\"\n  Translate 0 0 4" + body + "FrameEnd\nFrameBegin 3\n  Display \"" +
           dir.Path("three.exr") + "\" \"file\" \"rgba\"\n  Translate 0 0 6" + body + "FrameEnd\n";
}

test::CliOutput Render(const std::string& args) { return test::RunCli("render --quiet " + args, true); }

// The RGBA of pixel (x, y) of the image at `path`.
std::array<float, 4> PixelOf(const std::string& path, int x, int y) {
    image::ImageBuffer image;
    diag::Report report;
    INFO(path);
    REQUIRE(image::ReadExrRgba(path, &image, &report));
    const size_t i = (size_t(y) * image.width + x) * 4;
    return {image.rgba[i], image.rgba[i + 1], image.rgba[i + 2], image.rgba[i + 3]};
}

}  // namespace

TEST_CASE("frames cli: every image frame renders to its Display and the shadow pass is skipped", "[tools]") {
    test::TempDir dir;
    const std::string scene = dir.Write("frames.rib", ThreeFrames(dir));
    test::CliOutput r = Render(scene);
    INFO(r.out);
    REQUIRE(r.status == 0);
    CHECK(fs::exists(dir.Path("two.exr")));
    CHECK(fs::exists(dir.Path("three.exr")));
    CHECK_FALSE(fs::exists(dir.Path("key.z")));
    CHECK(r.out.find("frames.rib:4:1: note: frame 1 renders a depth map for a scanline renderer") != std::string::npos);
    CHECK(r.out.find("note: 'MakeShadow' makes a shadow map for a scanline renderer; affray traces shadows: "
                     "skipped") != std::string::npos);
    CHECK(r.out.find("note: light source 'shadowspot' renders as 'spotlight'") != std::string::npos);
    CHECK(r.out.find("warning") == std::string::npos);
    // Each frame's own camera: the sphere covers the centre of both, less of it in frame 3 (farther).
    const float near = PixelOf(dir.Path("two.exr"), 4, 3)[3], far = PixelOf(dir.Path("three.exr"), 4, 3)[3];
    CHECK(near == 1);
    CHECK(far > 0.5f);
    CHECK(far < near);
    CHECK(PixelOf(dir.Path("two.exr"), 0, 0)[3] == 0);
}

TEST_CASE("frames cli: -o numbers the frames and --frame renders one", "[tools]") {
    test::TempDir dir;
    const std::string scene = dir.Write("frames.rib", ThreeFrames(dir));
    test::CliOutput r = Render(scene + " -o " + dir.Path("out.exr") + " --png " + dir.Path("out.png"));
    INFO(r.out);
    REQUIRE(r.status == 0);
    CHECK(fs::exists(dir.Path("out.0002.exr")));
    CHECK(fs::exists(dir.Path("out.0003.exr")));
    CHECK(fs::exists(dir.Path("out.0002.png")));
    CHECK(fs::exists(dir.Path("out.0003.png")));
    CHECK_FALSE(fs::exists(dir.Path("out.exr")));
    CHECK_FALSE(fs::exists(dir.Path("two.exr")));

    // --frame N: only frame N, to its Display or to -o exactly.
    r = Render(scene + " --frame 3");
    REQUIRE(r.status == 0);
    CHECK(fs::exists(dir.Path("three.exr")));
    CHECK_FALSE(fs::exists(dir.Path("two.exr")));
    r = Render(scene + " --frame 2 -o " + dir.Path("only.exr"));
    REQUIRE(r.status == 0);
    CHECK(fs::exists(dir.Path("only.exr")));

    // The shadow pass renders no image: a note, nothing written, success.
    r = Render(scene + " --frame 1 -o " + dir.Path("shadow.exr"));
    CHECK(r.status == 0);
    CHECK(r.out.find(scene + ": note: frame 1 renders no image: nothing written") != std::string::npos);
    CHECK_FALSE(fs::exists(dir.Path("shadow.exr")));

    // A name without an extension gets the number at its end.
    r = Render(scene + " -o " + dir.Path("plain"));
    REQUIRE(r.status == 0);
    CHECK(fs::exists(dir.Path("plain.0002")));
    CHECK(fs::exists(dir.Path("plain.0003")));
}

TEST_CASE("frames cli: a frame number not in the file, nested frames and clashing outputs fail", "[tools]") {
    test::TempDir dir;
    const std::string scene = dir.Write("frames.rib", ThreeFrames(dir));
    test::CliOutput r = Render(scene + " --frame 9 -o " + dir.Path("x.exr"));
    CHECK(r.status == 2);
    CHECK(r.out.find(scene + ": error: --frame 9: the scene has no frame 9 (its frames: 1 on line 4, 2 on line 13, "
                             "3 on line 21)\n") != std::string::npos);
    r = Render(scene + " --frame x");
    CHECK(r.status == 2);
    CHECK_FALSE(fs::exists(dir.Path("x.exr")));

    const std::string nested = dir.Write("nested.rib", "FrameBegin 1\nWorldBegin\nFrameBegin 2\n");
    r = Render(nested + " -o " + dir.Path("x.exr"));
    CHECK(r.status == 1);
    CHECK(r.out.rfind(nested + ":3:1: error: 'FrameBegin' inside 'WorldBegin' on line 2\n", 0) == 0);

    // Two frames numbered alike writing one Display: refused before anything renders.
    const std::string frame = "FrameBegin 5\nDisplay \"" + dir.Path("same.exr") +
                              "\" \"file\" \"rgba\"\nFormat 4 4 1\nWorldBegin\nWorldEnd\nFrameEnd\n";
    const std::string clash = dir.Write("clash.rib", frame + frame);
    r = Render(clash);
    CHECK(r.status == 1);
    CHECK(r.out.find("error: frame 5 (line 1) and frame 5 (line 7) would both write " + dir.Path("same.0005.exr")) !=
          std::string::npos);
    CHECK_FALSE(fs::exists(dir.Path("same.exr")));
    CHECK_FALSE(fs::exists(dir.Path("same.0005.exr")));
}

// Two matte spheres side by side, seen head on, under an ambient light and a distant light from
// the camera; Illuminate turns the distant light off for the right one only.
TEST_CASE("frames cli: Illuminate turns a light off for one object", "[tools]") {
    test::TempDir dir;
    auto scene = [&](const std::string& rightAttributes) {
        return std::string(R"(Format 16 8 1
Projection "orthographic"
ScreenWindow -2 2 -1 1
PixelSamples 1 1
Hider "hidden" "jitter" [0]
PixelFilter "box" 1 1
Translate 0 0 5
WorldBegin
  LightSource "ambientlight" 1 "intensity" [0.1]
  LightSource "distantlight" "key" "from" [0 0 -5] "to" [0 0 0]
  Surface "matte"
  AttributeBegin
    Translate -1 0 0
    Sphere 0.9 -0.9 0.9 360
  AttributeEnd
  AttributeBegin
)") + rightAttributes +
               R"(
    Translate 1 0 0
    Sphere 0.9 -0.9 0.9 360
  AttributeEnd
  Translate 0 0 3
  Patch "bilinear" "P" [-2 -1 0  2 -1 0  -2 1 0  2 1 0]
WorldEnd
)";
    };
    const std::string both = dir.Write("both.rib", scene("")),
                      off = dir.Write("off.rib", scene("Illuminate \"key\" 0"));
    REQUIRE(Render(both + " -o " + dir.Path("both.exr")).status == 0);
    test::CliOutput r = Render(off + " -o " + dir.Path("off.exr"));
    INFO(r.out);
    REQUIRE(r.status == 0);
    CHECK(r.out.find("warning") == std::string::npos);

    // Pixels 4 and 11 of row 3 are mirror images, 0.125 off each sphere's centre.
    const double cosine = std::sqrt(1 - (0.125 * 0.125 + 0.125 * 0.125) / (0.9 * 0.9));
    const auto leftBoth = PixelOf(dir.Path("both.exr"), 4, 3), rightBoth = PixelOf(dir.Path("both.exr"), 11, 3);
    CHECK(leftBoth[0] == Approx(0.1 + cosine).epsilon(2e-3));
    CHECK(rightBoth[0] == Approx(leftBoth[0]).epsilon(2e-3));
    const auto leftOff = PixelOf(dir.Path("off.exr"), 4, 3), rightOff = PixelOf(dir.Path("off.exr"), 11, 3);
    CHECK(leftOff[0] == Approx(leftBoth[0]).epsilon(2e-3));  // the left sphere keeps its light
    CHECK(rightOff[0] == Approx(0.1).epsilon(2e-3));         // the right one has the ambient light only
    CHECK(rightOff[3] == 1);
    // The floor behind, after the right sphere's AttributeEnd, has both lights again.
    CHECK(PixelOf(dir.Path("off.exr"), 0, 0)[0] == Approx(PixelOf(dir.Path("both.exr"), 0, 0)[0]).epsilon(2e-3));
}
