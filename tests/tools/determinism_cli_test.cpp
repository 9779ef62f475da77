// tests/tools/determinism_cli_test.cpp: `affray render` writes the same bytes (the OpenEXR file,
// RGBA and every AOV) whatever the options that must not change pixels (issue 17): thread counts,
// tile order (--tile-order reverse, a test option), the bound hierarchies' memory budget
// (--cache-mb: a 64 KiB and a zero budget evict and rebuild all the time, while threads share
// the hierarchies) and the texture tiles' budget; nor the BVH's shape (--bvh median, a test
// option) or the scene's order of primitives (issue 32). Crops pasted together are compared with the
// whole render in tests/tools/crop_test.cpp, resumed renders in tests/tools/faults_cli_test.cpp.
#include <catch2/catch.hpp>

#include <filesystem>
#include <vector>

#include "image/exr_writer.h"
#include "tests/test_util.h"

using namespace affray;

TEST_CASE("determinism: the same bytes with any threads, tile order and cache budget", "[tools][determinism]") {
    test::TempDir dir;
    dir.Write("scene.rib", test::WaveSphereScene(64, 48, "det.exr"));
    std::filesystem::copy_file(test::SourceDir() + "/shaders/wave.sl", dir.Path("wave.sl"));
    auto render = [&](const std::string& name, const std::string& extra) {
        const test::CliOutput out = test::RunCli(
            "render " + test::Quote(dir.Path("scene.rib")) + " -o " + test::Quote(dir.Path(name)) + " --quiet " + extra,
            true);
        INFO(out.out);
        REQUIRE(out.status == 0);
        const std::string bytes = test::ReadText(dir.Path(name));
        REQUIRE(bytes.size() > 1000);
        return bytes;
    };
    const std::string reference = render("reference.exr", "--threads 1");
    for (const char* extra : {"--threads 2", "--threads 4", "--tile-order reverse", "--threads 4 --tile-order reverse",
                              "--threads 4 --cache-mb 0.0625", "--threads 3 --cache-mb 0 --tile-order reverse",
                              "--threads 2 --texture-mb 0.0625"}) {
        INFO(extra);
        CHECK(render("test.exr", extra) == reference);
    }
    // The comparison can fail: an option that changes pixels changes the bytes.
    CHECK(render("test.exr", "--threads 2 --tolerance 0.3") != reference);
}

TEST_CASE("determinism: a textured scene gives the same bytes with any threads, tile order and budgets",
          "[tools][determinism]") {
    // scenes/textured.rib at a sixteenth of its size, its shaders and maps found in shaders/.
    test::TempDir dir;
    const std::string rib = dir.Path("textured.rib");
    dir.Write("textured.rib", "Option \"searchpath\" \"shader\" [\"" + test::SourceDir() + "/shaders\"]\n" +
                                  test::ReadText(test::SourceDir() + "/scenes/textured.rib"));
    test::ShrinkFormat(rib, 16);
    auto render = [&](const std::string& extra) {
        const test::CliOutput out = test::RunCli(
            "render " + test::Quote(rib) + " -o " + test::Quote(dir.Path("t.exr")) + " --quiet " + extra, true);
        INFO(out.out);
        REQUIRE(out.status == 0);
        return test::ReadText(dir.Path("t.exr"));
    };
    const std::string reference = render("--threads 1");
    REQUIRE(reference.size() > 1000);
    // (A zero texture budget reads tiles again for nearly every lookup, far too slow here; 64 KiB still
    // drops tiles all the time.)
    for (const char* extra : {"--threads 3 --tile-order reverse --cache-mb 0.0625",
                              "--threads 2 --texture-mb 0.0625 --tile-order reverse"}) {
        INFO(extra);
        CHECK(render(extra) == reference);
    }
}

TEST_CASE("determinism: the same pixels whatever the BVH's shape and the primitives' order", "[tools][determinism]") {
    // Issue 32: scenes/mixed.rib, where a cone stands on a displaced floor and the two surfaces'
    // hits lie within the tolerance of each other on a few pixels. The image (but its cost AOV,
    // the regions each sample tested, which the tree's shape does change) must not depend on
    // the BVH, built by SAH or median splits (--bvh median, a test option), nor on the order the
    // scene gives its primitives in (the five after the coordinate system's block, reversed).
    test::TempDir dir;
    std::string scene = test::ReadText(test::SourceDir() + "/scenes/mixed.rib");
    const std::string aovs = "\"rgba,Z,N,P,st,cost,err\"";
    const size_t display = scene.find(aovs);
    REQUIRE(display != std::string::npos);
    scene.replace(display, aovs.size(), "\"rgba,Z,N,P,st,err\"");
    scene = "Option \"searchpath\" \"shader\" [\"" + test::SourceDir() + "/shaders:" + test::SourceDir() +
            "/scenes\"]\n" + scene;
    // The blocks of WorldBegin .. WorldEnd, each from a line "  AttributeBegin".
    const size_t worldEnd = scene.find("WorldEnd");
    std::vector<size_t> starts;
    for (size_t at = scene.find("\n  AttributeBegin"); at < worldEnd; at = scene.find("\n  AttributeBegin", at + 1))
        starts.push_back(at + 1);
    REQUIRE(starts.size() == 6);
    starts.push_back(worldEnd);
    std::string reversed = scene.substr(0, starts[1]);
    for (size_t k = 6; k-- > 1;) reversed += scene.substr(starts[k], starts[k + 1] - starts[k]);
    reversed += scene.substr(worldEnd);
    REQUIRE(reversed.size() == scene.size());
    REQUIRE(reversed != scene);
    dir.Write("mixed.rib", scene);
    dir.Write("reversed.rib", reversed);
    // The pixels (the files' headers name the scene by a hash of its text).
    auto render = [&](const std::string& rib, const std::string& extra) {
        const test::CliOutput out = test::RunCli("render " + test::Quote(dir.Path(rib)) + " -o " +
                                                     test::Quote(dir.Path("t.exr")) + " --quiet --threads 2 " + extra,
                                                 true);
        INFO(out.out);
        REQUIRE(out.status == 0);
        image::ImageBuffer image;
        diag::Report error;
        REQUIRE(image::ReadExrRgba(dir.Path("t.exr"), &image, &error));
        return std::pair{image.rgba, image.extraChannels};
    };
    const auto reference = render("mixed.rib", "");
    REQUIRE(reference.first.size() == 160 * 120 * 4);
    REQUIRE(reference.second.size() == 10);  // Z, N (3), P (3), st (2), err
    CHECK(render("mixed.rib", "--bvh median") == reference);
    CHECK(render("reversed.rib", "") == reference);
    CHECK(render("reversed.rib", "--bvh median --tile-order reverse") == reference);
}
