// tests/tools/newton_cli_test.cpp: `affray render --newton` (issue 31): certified Newton hits at the
// leaves, counted by --stats, an image that differs little from the leaves' own, and a render
// identity of its own (tiles rendered with and without it do not merge).
#include <catch2/catch.hpp>

#include <string>

#include "tests/test_util.h"

using namespace affray;

TEST_CASE("newton cli: --newton certifies hits by Newton and keeps the image", "[tools][newton]") {
    test::TempDir dir;
    const std::string rib = dir.Write("wave.rib", "Option \"searchpath\" \"shader\" [\"" + test::SourceDir() +
                                                      "/shaders\"]\n" + test::WaveSphereScene(48, 36, "wave.exr"));
    auto render = [&](const std::string& name, const std::string& extra) {
        const test::CliOutput r =
            test::RunCli("render " + rib + " -o " + dir.Path(name) + " --stats --quiet " + extra, true);
        INFO(r.out);
        REQUIRE(r.status == 0);
        return r.out;
    };
    const std::string leaves = render("leaves.exr", "");
    const std::string newton = render("newton.exr", "--newton");
    CHECK(leaves.find("\"newton\":{\"camera_hits\":0,") != std::string::npos);
    CHECK(newton.find("\"newton\":{\"camera_hits\":0,") == std::string::npos);
    CHECK(newton.find("\"newton\":{\"camera_hits\":") != std::string::npos);
    const test::CliOutput diff = test::RunCli("diff " + dir.Path("leaves.exr") + " " + dir.Path("newton.exr"));
    INFO(diff.out);
    const size_t at = diff.out.find("\"rmse\":");
    REQUIRE(at != std::string::npos);
    CHECK(std::stod(diff.out.substr(at + 7)) < 0.02);
    // Another render identity: the halves of a split rendered with and without it do not merge.
    REQUIRE(test::RunCli("render " + rib + " -o " + dir.Path("left.exr") + " --quiet --crop 0,0.5,0,1", true).status ==
            0);
    REQUIRE(test::RunCli("render " + rib + " -o " + dir.Path("right.exr") + " --quiet --newton --crop 0.5,1,0,1", true)
                .status == 0);
    const test::CliOutput merged =
        test::RunCli("merge " + dir.Path("whole.exr") + " " + dir.Path("left.exr") + " " + dir.Path("right.exr"), true);
    INFO(merged.out);
    CHECK(merged.status != 0);
    CHECK(merged.out.find("different newton") != std::string::npos);
}
