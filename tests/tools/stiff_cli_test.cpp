// tests/tools/stiff_cli_test.cpp: the stiff suite (docs/stiff.md) through the `affray` program:
// every scene of tests/scenes/stiff/ renders (shrunk, so that this stays cheap; the full-size figures
// are bench/stiff_table.sh's), and NaN, infinite or overflowing parameter values are errors that
// name the parameter, exit non-zero and leave no image.
#include <catch2/catch.hpp>

#include <sys/wait.h>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "tests/test_util.h"

namespace fs = std::filesystem;
using namespace affray;

namespace {

using Output = test::CliOutput;

/// Runs the CLI, capturing stdout and stderr.
Output Run(const std::string& args) { return test::RunCli(args, true); }

/// The small scene the parameter checks render: wave.sl on the unit patch, 8 x 8 pixels.
std::string WaveScene(const std::string& displacement) {
    return "Format 8 8 1\nProjection \"perspective\" \"fov\" [40]\nTranslate 0 0 2.2\nRotate -130 1 0 0\n"
           "Translate -0.5 -0.5 0\nWorldBegin\n" +
           displacement + "\nPatch \"bilinear\" \"P\" [0 0 0  1 0 0  0 1 0  1 1 0]\nWorldEnd\n";
}

}  // namespace

TEST_CASE("stiff cli: every stiff scene renders, shrunk", "[tools][stiff]") {
    // A copy of tests/scenes/stiff/ and shaders/ side by side, as in the source tree (the stiff scenes'
    // wave.sl includes ../../../shaders/wave.sl), with each image shrunk eightfold.
    test::TempDir dir;
    fs::create_directories(dir.Path("tests/scenes"));
    fs::copy(test::SourceDir() + "/tests/scenes/stiff", dir.Path("tests/scenes/stiff"), fs::copy_options::recursive);
    fs::copy(test::SourceDir() + "/shaders", dir.Path("shaders"), fs::copy_options::recursive);
    int scenes = 0;
    for (const auto& entry : fs::directory_iterator(dir.Path("tests/scenes/stiff"))) {
        if (entry.path().extension() != ".rib") continue;
        ++scenes;
        const std::string text = test::ShrinkFormat(entry.path(), 8);
        std::string args;
        size_t at = text.find("##stiff-args:");
        if (at != std::string::npos) args = text.substr(at + 13, text.find('\n', at) - at - 13);
        const std::string exr = dir.Path(entry.path().stem().string() + ".exr");
        Output r = Run("render " + entry.path().string() + " -o " + exr + " --threads 2" + args);
        INFO(entry.path().filename().string() << args << "\n" << r.out);
        CHECK(r.status == 0);
        CHECK(fs::exists(exr));
    }
    CHECK(scenes >= 10);
}

TEST_CASE("stiff cli: NaN, infinite and overflowing parameters in a scene name the parameter", "[tools][stiff]") {
    test::TempDir dir;
    fs::copy_file(test::SourceDir() + "/shaders/wave.sl", dir.Path("wave.sl"));
    const std::string exr = dir.Path("out.exr");
    struct Case {
        const char* value;
        const char* message;
    };
    const Case cases[] = {
        {"[1e400]", "number '1e400' is out of range (in the value of parameter \"Km\" of Displacement)"},
        {"1e999", "number '1e999' is out of range (in the value of parameter \"Km\" of Displacement)"},
        {"[-1e400]", "number '-1e400' is out of range (in the value of parameter \"Km\" of Displacement)"},
        {"[nan]",
         "invalid number 'nan': NaN and infinity are not allowed (in the value of parameter \"Km\" of "
         "Displacement)"},
        {"[inf]",
         "invalid number 'inf': NaN and infinity are not allowed (in the value of parameter \"Km\" of "
         "Displacement)"},
        // Finite, but the bounds overflow in every region: a render that would never end.
        {"[1e300]", "parameter 'Km' = 1e+300 is too large"},
    };
    for (const Case& c : cases) {
        const std::string rib =
            dir.Write("scene.rib", WaveScene(std::string("Displacement \"wave\" \"Km\" ") + c.value));
        Output r = Run("render " + rib + " -o " + exr);
        INFO(c.value << ": " << r.out);
        CHECK(r.status == 1);
        CHECK(r.out.find("scene.rib:7:") != std::string::npos);
        CHECK(r.out.find(": error: ") != std::string::npos);
        CHECK(r.out.find(c.message) != std::string::npos);
        CHECK_FALSE(fs::exists(exr));
    }
    // The same check catches NaN computed from finite values everywhere on the surface.
    dir.Write("sqrtneg.sl", "displacement sqrtneg(float Km = 0.1) { P += Km * log(-1 - u) * normalize(N); }\n");
    Output nan = Run("render " + dir.Write("nan.rib", WaveScene("Displacement \"sqrtneg\"")) + " -o " + exr);
    INFO(nan.out);
    CHECK(nan.status == 1);
    CHECK(nan.out.find("cannot be bounded over any part of the patch") != std::string::npos);
    CHECK_FALSE(fs::exists(exr));
    // `render` takes parameters from the scene only.
    const std::string ok = dir.Write("ok.rib", WaveScene("Displacement \"wave\""));
    Output option = Run("render " + ok + " --param Km=nan -o " + exr);
    CHECK(option.status == 2);
    CHECK(option.out.find("unknown option '--param'") != std::string::npos);
    CHECK_FALSE(fs::exists(exr));
}

TEST_CASE("stiff cli: NaN and infinite values for eval --param name the parameter", "[tools][stiff]") {
    const std::string wave = test::SourceDir() + "/shaders/wave.sl";
    for (const char* value : {"nan", "inf", "-inf", "1e999", "-1e400", "NaN", "infinity"}) {
        Output r = Run("eval " + wave + " --param Km=" + value + " --at 0.5,0.5");
        INFO(value << ": " << r.out);
        CHECK(r.status == 2);
        CHECK(r.out.find("affray: error: --param Km: '" + std::string(value) + "' is not finite") != std::string::npos);
        CHECK(r.out.find("\"P\"") == std::string::npos);
    }
    Output other =
        Run("eval " + test::SourceDir() + "/tests/scenes/stiff/singular.sl --param centerS=nan --at 0.5,0.5");
    CHECK(other.status == 2);
    CHECK(other.out.find("--param centerS: 'nan' is not finite") != std::string::npos);
    // A finite value is taken, however large: the scalar result is what it is.
    Output large = Run("eval " + wave + " --param Km=1e308 --at 0.5,0.5");
    CHECK(large.status == 0);
    CHECK(large.out == "{\"P\":[0.5,0.5,1e+308],\"N\":[0,0,1]}\n");
}

TEST_CASE("stiff cli: a parameter default that folds to NaN or infinity is an error naming it", "[tools][stiff]") {
    test::TempDir dir;
    const std::string exr = dir.Path("out.exr");
    for (const char* value : {"1 / 0", "-1 / 0", "0 / 0", "1e200 * 1e200", "log(0)", "log(-1)", "pow(0, -0.5)"}) {
        const std::string sl = dir.Write("bad.sl", "displacement bad(float Km = 0.1; float k = " + std::string(value) +
                                                       ")\n{\n    P += Km * k * normalize(N);\n}\n");
        INFO(value);
        for (const std::string& command :
             {"compile " + sl, "eval " + sl + " --at 0.5,0.5", "eval " + sl + " --region 0,1,0,1 --mode affine"}) {
            Output r = Run(command);
            INFO(command << ": " << r.out);
            CHECK(r.status == 1);
            CHECK(r.out.find("bad.sl:1:") != std::string::npos);
            CHECK(r.out.find("parameter 'k'") != std::string::npos);
        }
        Output render = Run("render " + dir.Write("bad.rib", WaveScene("Displacement \"bad\"")) + " -o " + exr);
        INFO(render.out);
        CHECK(render.status == 1);
        CHECK(render.out.find("parameter 'k'") != std::string::npos);
        CHECK_FALSE(fs::exists(exr));
    }
}
