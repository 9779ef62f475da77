// tests/tools/determinism_cli_test.cpp: `affray render` writes the same bytes (the OpenEXR file,
// RGBA and every AOV) whatever the options that must not change pixels (issue 17): thread counts,
// tile order (--tile-order reverse, a test option), the bound hierarchies' memory budget
// (--cache-mb: a 64 KiB and a zero budget evict and rebuild all the time, while threads share
// the hierarchies) and the texture tiles' budget. Crops pasted together are compared with the
// whole render in tests/tools/crop_test.cpp, resumed renders in tests/tools/faults_cli_test.cpp.
#include <catch2/catch.hpp>

#include <filesystem>

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
