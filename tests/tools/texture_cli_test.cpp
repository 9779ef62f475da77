// tests/tools/texture_cli_test.cpp: `affray render --texture-mb` (issue 16): the texture tiles'
// budget changes what is read and dropped, never the image; --stats reports the tiles.
#include <catch2/catch.hpp>

#include <string>

#include "tests/test_util.h"

using namespace affray;

TEST_CASE("texture cli: a tiny texture budget drops tiles and gives the same image", "[tools][texture]") {
    test::TempDir dir;
    // A plane displaced by shaders/texmap.sl (shaders/maps/tiles.exr: 16 tiles of 64 x 64 texels).
    const std::string rib =
        dir.Write("plane.rib", "Option \"searchpath\" \"shader\" [\"" + test::SourceDir() +
                                   "/shaders\"]\nFormat 32 24 1\nPixelSamples 1 1\n"
                                   "Projection \"perspective\" \"fov\" [40]\nTranslate 0 0 1.3\n"
                                   "Rotate -120 1 0 0\nWorldBegin\nLightSource \"distantlight\" 1\n"
                                   "Displacement \"texmap\" \"Km\" [0.1]\n"
                                   "Patch \"bilinear\" \"P\" [-0.5 -0.5 0  0.5 -0.5 0  -0.5 0.5 0  0.5 0.5 0]\n"
                                   "WorldEnd\n");
    const std::string full = test::RenderWithStats(rib, dir.Path("full.exr"));
    const std::string tiny = test::RenderWithStats(rib, dir.Path("tiny.exr"), "--texture-mb 0.01");
    CHECK(full.find("\"textures\":{\"budget_mb\":512.0,") != std::string::npos);
    CHECK(full.find("\"tiles_dropped\":0,") != std::string::npos);
    CHECK(tiny.find("\"budget_mb\":0.0,") != std::string::npos);
    CHECK(tiny.find("\"tiles_dropped\":0,") == std::string::npos);
    const test::CliOutput diff = test::RunCli("diff " + dir.Path("full.exr") + " " + dir.Path("tiny.exr"));
    CHECK(diff.out.find("\"rmse\":0,\"max\":0") != std::string::npos);
    const test::CliOutput bad = test::RunCli("render " + rib + " --texture-mb -1", true);
    CHECK(bad.status == 2);
    CHECK(bad.out.find("--texture-mb takes a size in MiB") != std::string::npos);
}
