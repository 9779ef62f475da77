// tests/tools/limits_cli_test.cpp: the resource limits on the command line (diag/limits.h):
// `affray limits`, --limit on every command that reads input, refusals of bad --limit values,
// and the wall-clock --time-limit, which stops a render like an interruption (no image, the
// checkpoint kept) but with exit status 4 and an error naming the limit.
#include <catch2/catch.hpp>

#include <chrono>
#include <filesystem>

#include "diag/limits.h"
#include "tests/test_util.h"

using namespace affray;

TEST_CASE("cli: affray limits prints every limit, with --limit applied", "[tools][limits]") {
    test::CliOutput out = test::RunCli("limits --limit call-depth=100");
    CHECK(out.status == 0);
    for (int i = 0; i < diag::kLimitCount; ++i)
        CHECK(out.out.find(diag::Info(static_cast<diag::Limit>(i)).name) != std::string::npos);
    CHECK(out.out.find("call-depth                100 ") != std::string::npos);

    test::CliOutput bad = test::RunCli("limits --limit call-depth=1000", true);
    CHECK(bad.status == 2);
    CHECK(bad.out.find("affray: error: limit call-depth takes a whole number from 1 to 256, not '1000'") == 0);
}

TEST_CASE("cli: --limit on compile and eval changes where a shader is refused", "[tools][limits]") {
    test::TempDir dir;
    const std::string shader = dir.Write("loop.sl",
                                         "displacement t() {\n  float i;\n  for (i = 0; i < 300; i += 1)\n"
                                         "    P += 0.0001 * N;\n}\n");
    CHECK(test::RunCli("compile " + test::Quote(shader) + " -o " + test::Quote(dir.Path("a.afb"))).status == 0);
    test::CliOutput refused = test::RunCli("compile " + test::Quote(shader) + " --limit loop-iterations=299", true);
    CHECK(refused.status == 1);
    CHECK(refused.out.find("this loop runs more than 299 iterations") != std::string::npos);
    CHECK(refused.out.find("(limit loop-iterations = 299; raise it with --limit loop-iterations=N)") !=
          std::string::npos);
    CHECK(test::RunCli("eval " + test::Quote(shader) + " --at 0.5,0.5 --limit loop-iterations=299").status == 1);
    CHECK(test::RunCli("eval " + test::Quote(shader) + " --at 0.5,0.5 --limit loop-iterations=300").status == 0);

    test::CliOutput unknown = test::RunCli("compile " + test::Quote(shader) + " --limit loops=5", true);
    CHECK(unknown.status == 2);
    CHECK(unknown.out.find("unknown limit 'loops'") != std::string::npos);
    CHECK(test::RunCli("compile " + test::Quote(shader) + " --limit", true).status == 2);
}

TEST_CASE("cli: --time-limit stops a render: no image, the checkpoint kept, exit 4", "[tools][limits][render]") {
    test::TempDir dir;
    // 8 x 8 samples at 320 x 240: far longer than a second, in any build.
    dir.Write("scene.rib", test::WaveSphereScene(320, 240, "slow.exr", "PixelSamples 8 8\n"));
    std::filesystem::copy_file(test::SourceDir() + "/shaders/wave.sl", dir.Path("wave.sl"));
    const std::string output = dir.Path("slow.exr");
    const auto start = std::chrono::steady_clock::now();
    test::CliOutput out = test::RunCli(
        "render " + test::Quote(dir.Path("scene.rib")) + " -o " + test::Quote(output) + " --quiet --time-limit 1",
        true);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    INFO(out.out);
    CHECK(out.status == diag::kExitResources);
    CHECK(out.out.find(output + ": error: stopped after 1 s of wall-clock time (limit time-limit = 1; raise it with "
                                "--limit time-limit=N): no image written") != std::string::npos);
    CHECK_FALSE(std::filesystem::exists(output));
    CHECK(std::filesystem::exists(output + ".checkpoint"));
    CHECK(seconds < 30);  // stopped, not rendered to the end (a generous bound: sanitiser builds are slow)
}
