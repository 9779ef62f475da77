// tests/tools/newton_cli_test.cpp: `affray render --newton` (issue 31): certified Newton hits at the
// leaves, counted by --stats, an image that differs little from the leaves' own, a render identity
// of its own (tiles rendered with and without it do not merge), and shadows without the error of
// the shadow rays' offset: the default scene much closer to a converged reference.
#include <catch2/catch.hpp>

#include <string>

#include "tests/test_util.h"

using namespace affray;

TEST_CASE("newton cli: --newton certifies hits by Newton and keeps the image", "[tools][newton]") {
    test::TempDir dir;
    const std::string rib = dir.Write("wave.rib", "Option \"searchpath\" \"shader\" [\"" + test::SourceDir() +
                                                      "/shaders\"]\n" + test::WaveSphereScene(48, 36, "wave.exr"));
    const std::string leaves = test::RenderWithStats(rib, dir.Path("leaves.exr"));
    const std::string newton = test::RenderWithStats(rib, dir.Path("newton.exr"), "--newton");
    CHECK(leaves.find("\"newton\":{\"camera_hits\":0,") != std::string::npos);
    CHECK(newton.find("\"newton\":{\"camera_hits\":0,") == std::string::npos);
    CHECK(newton.find("\"newton\":{\"camera_hits\":") != std::string::npos);
    CHECK(test::DiffRmse(dir.Path("leaves.exr"), dir.Path("newton.exr")) < 0.02);
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

TEST_CASE("newton cli: shadow terminators of the default scene are where the reference has them", "[tools][newton]") {
    // scenes/wave.rib at 96 x 72: the crests shadow the troughs under a low light. Without
    // --newton the shadow rays start twice the tolerance above the surface, which moves the
    // terminators; with it, a root that Newton proves on the shadow ray from just above the hit
    // blocks the light as well.
    test::TempDir dir;
    std::string scene = test::ReadText(test::SourceDir() + "/scenes/wave.rib");
    const size_t format = scene.find("Format 640 480 1");
    REQUIRE(format != std::string::npos);
    scene.replace(format, 16, "Format 96 72 1");
    const std::string rib =
        dir.Write("wave.rib", "Option \"searchpath\" \"shader\" [\"" + test::SourceDir() + "/shaders\"]\n" + scene);
    auto rmse = [&](const std::string& name, const std::string& extra) {
        test::RenderWithStats(rib, dir.Path(name), extra);
        return test::DiffRmse(dir.Path("reference.exr"), dir.Path(name));
    };
    test::RenderWithStats(rib, dir.Path("reference.exr"), "--tolerance 0.02 --bounds affine");
    const double leaves = rmse("leaves.exr", "");
    const double newton = rmse("newton.exr", "--newton");
    INFO("RMSE against the reference: " << leaves << " without --newton, " << newton << " with it");
    CHECK(newton < 0.3 * leaves);
    CHECK(newton < 0.006);
}
