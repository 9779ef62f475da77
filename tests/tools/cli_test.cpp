// tests/tools/cli_test.cpp: the `affray` program end to end: exit codes, the JSON that users and
// tests rely on, a tiny render checked pixel by pixel, and bad input never leaving an image.
#include <catch2/catch.hpp>
#include <cstdlib>

#include <sys/wait.h>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "image/exr_writer.h"
#include "tests/test_util.h"

namespace fs = std::filesystem;
using namespace affray;

namespace {

using Output = test::CliOutput;

Output Run(const std::string& args, bool withStderr = false) { return test::RunCli(args, withStderr); }

fs::path TempDir(const std::string& name) {
    fs::path dir = fs::temp_directory_path() / ("affray_cli_test_" + name + "_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

void WriteFile(const fs::path& path, const std::string& text) { std::ofstream(path) << text; }

const std::string kWave = test::SourceDir() + "/shaders/wave.sl";

std::string SmallWaveScene(int w, int h) {
    return "Format " + std::to_string(w) + " " + std::to_string(h) + " 1\n" +
           R"(Projection "perspective" "fov" [40]
Display "small.exr" "file" "rgba"
Translate 0 0 3.1
Rotate -130 1 0 0
WorldBegin
  LightSource "ambientlight" 1 "intensity" [0.06]
  LightSource "distantlight" 2 "intensity" [1.1] "from" [-3 1.5 1.1] "to" [0 0 0]
  Color [0.85 0.62 0.35]
  Surface "plastic"
  Displacement "wave" "Km" [0.06] "frequency" [8] "decay" [2.5]
  Patch "bilinear" "P" [-1 -1 0  1 -1 0  -1 1 0  1 1 0]
WorldEnd
)";
}

}  // namespace

TEST_CASE("cli: eval --at prints P and N as JSON with round-trip precision", "[tools]") {
    Output r = Run("eval " + kWave + " --at 0.5,0.5 --at 0.25,0.5");
    REQUIRE(r.status == 0);
    // At the centre r = 0: P = (0.5, 0.5, Km) with Km = 0.06.
    std::string first = r.out.substr(0, r.out.find('\n'));
    CHECK(first.rfind("{\"P\":[0.5,0.5,0.059999999999999998],\"N\":[", 0) == 0);
    CHECK(std::count(r.out.begin(), r.out.end(), '\n') == 2);
    // The second line: r = 0.25, P.z = Km * exp(-2.5 * 0.25) * cos(2 pi 8 0.25) = Km * exp(-0.625).
    double expected = 0.06 * std::exp(-0.625) * std::cos(2 * M_PI * 8 * 0.25);
    std::string second = r.out.substr(r.out.find('\n') + 1);
    double z = std::stod(second.substr(second.find(',', second.find(',') + 1) + 1));
    CHECK(z == Approx(expected).epsilon(1e-15));
}

TEST_CASE("cli: eval --region prints a bound that contains --at values", "[tools]") {
    Output region = Run("eval " + kWave + " --region 0.1,0.2,0.3,0.4 --mode affine");
    REQUIRE(region.status == 0);
    CHECK(region.out.rfind("{\"P\":{\"lo\":[", 0) == 0);
    double zlo = 0, zhi = 0;
    {
        std::string lo = region.out.substr(region.out.find("\"lo\":[") + 6);
        std::string hi = region.out.substr(region.out.find("\"hi\":[") + 6);
        zlo = std::stod(lo.substr(lo.rfind(',', lo.find(']')) + 1));
        zhi = std::stod(hi.substr(hi.rfind(',', hi.find(']')) + 1));
    }
    Output at = Run("eval " + kWave + " --at 0.15,0.35");
    REQUIRE(at.status == 0);
    std::string p = at.out.substr(6, at.out.find(']') - 6);
    double z = std::stod(p.substr(p.rfind(',') + 1));
    CHECK(zlo <= z);
    CHECK(z <= zhi);
    CHECK(Run("eval " + kWave + " --region 0.1,0.2,0.3,0.4 --mode interval").status == 0);
}

TEST_CASE("cli: parameters, bad parameters and bad command lines", "[tools]") {
    Output km = Run("eval " + kWave + " --param Km=0.5 --at 0.5,0.5");
    REQUIRE(km.status == 0);
    CHECK(km.out.find("[0.5,0.5,0.5]") != std::string::npos);
    Output unknown = Run("eval " + kWave + " --param Kx=1 --at 0.5,0.5", true);
    CHECK(unknown.status == 1);
    CHECK(unknown.out == "affray: error: shader 'wave' has no parameter 'Kx'\n");
    CHECK(Run("eval " + kWave + " --param Km=nan --at 0.5,0.5").status == 2);
    CHECK(Run("eval " + kWave + " --param Km=inf --at 0.5,0.5").status == 2);
    CHECK(Run("eval " + kWave).status == 2);
    CHECK(Run("eval " + kWave + " --region 0.5,0.1,0,1 --mode affine").status == 2);
    CHECK(Run("render").status == 2);
    CHECK(Run("frobnicate").status == 2);
    CHECK(Run("render x.rib --tolerance -1").status == 2);
    CHECK(Run("render x.rib -o out.png").status == 2);  // -o writes OpenEXR (--png a preview)
    CHECK(Run("render x.rib -o out.TIF").status == 2);
}

TEST_CASE("cli: compile exits 0 or prints diagnostics and exits 1", "[tools]") {
    CHECK(Run("compile " + kWave).status == 0);
    Output listing = Run("compile " + kWave + " --disasm");
    CHECK(listing.status == 0);
    CHECK(listing.out.find("bound program") != std::string::npos);
    CHECK(listing.out.find("Cos") != std::string::npos);
    fs::path dir = TempDir("compile");
    WriteFile(dir / "bad.sl", "displacement bad() {\n  P += ;\n}\n");
    Output bad = Run("compile " + (dir / "bad.sl").string(), true);
    CHECK(bad.status == 1);
    CHECK(bad.out.find("bad.sl:2:") != std::string::npos);
    CHECK(bad.out.find('^') != std::string::npos);
    CHECK(Run("compile " + (dir / "missing.sl").string()).status == 1);
    Output stats = Run("compile " + kWave + " --stats");
    CHECK(stats.status == 0);
    CHECK(stats.out.rfind("{\"shader\":\"wave\",\"operations_requested\":", 0) == 0);
    CHECK(stats.out.find("\"globals_read\":[\"P\",\"N\",\"s\",\"t\"]") != std::string::npos);
    fs::remove_all(dir);
}

TEST_CASE("cli: a surface shader compiles and disassembles, but is neither written as .afb nor evaluated",
          "[tools][surface]") {
    const std::string plastic = test::SourceDir() + "/shaders/plastic.sl";
    Output listing = Run("compile " + plastic + " --disasm --stats");
    CHECK(listing.status == 0);
    CHECK(listing.out.find("surface program (Ci and Oi)") != std::string::npos);
    CHECK(listing.out.find("\"surface_specialised\":") != std::string::npos);
    CHECK(listing.out.find("\"globals_read\":[\"Cs\",\"Os\"]") != std::string::npos);  // no light list here
    fs::path dir = TempDir("surface");
    Output afb = Run("compile " + plastic + " -o " + (dir / "plastic.afb").string(), true);
    CHECK(afb.status == 1);
    CHECK(afb.out.find("error: surface shader 'plastic' cannot be written as bytecode") != std::string::npos);
    CHECK_FALSE(fs::exists(dir / "plastic.afb"));
    Output eval = Run("eval " + plastic + " --at 0.5,0.5", true);
    CHECK(eval.status == 1);
    CHECK(eval.out.find("'affray eval' evaluates displacement shaders; 'plastic' is a surface shader") !=
          std::string::npos);
}

TEST_CASE("cli: a tiny render is lit, shadowed, and the same with any thread count", "[tools][render]") {
    fs::path dir = TempDir("render");
    fs::copy_file(kWave, dir / "wave.sl");
    WriteFile(dir / "small.rib", SmallWaveScene(48, 36));
    Output one =
        Run("render " + (dir / "small.rib").string() + " -o " + (dir / "one.exr").string() + " --threads 1 --stats");
    REQUIRE(one.status == 0);
    // 2 x 2 samples per pixel (RenderMan's default), and again those of the filter's margin
    // that neighbouring tiles share.
    const size_t rays = one.out.find("\"camera_rays\":");
    REQUIRE(rays != std::string::npos);
    const long long cameraRays = std::strtoll(one.out.c_str() + rays + 14, nullptr, 10);
    CHECK(cameraRays >= 48LL * 36 * 4);
    CHECK(cameraRays <= 48LL * 36 * 4 * 2);
    CHECK(one.out.find("\"max_certified_error\":") != std::string::npos);
    CHECK(one.out.find("\"shaders\":[{\"name\":\"wave\",\"operations_requested\":") != std::string::npos);
    REQUIRE(
        Run("render " + (dir / "small.rib").string() + " -o " + (dir / "two.exr").string() + " --threads 2").status ==
        0);
    image::ImageBuffer a, b;
    affray::diag::Report error;
    REQUIRE(image::ReadExrRgba((dir / "one.exr").string(), &a, &error));
    REQUIRE(image::ReadExrRgba((dir / "two.exr").string(), &b, &error));
    CHECK(a.rgba == b.rgba);
    // The patch covers the centre of the image; the corners see the background.
    auto pixel = [&](int x, int y, int c) { return a.rgba[(static_cast<size_t>(y) * a.width + x) * 4 + c]; };
    CHECK(pixel(24, 18, 3) == 1.0f);
    CHECK(pixel(0, 0, 3) == 0.0f);
    // Ripples and shadows: among covered pixels, some are bright and some only ambient-lit.
    int bright = 0, dark = 0;
    for (int y = 0; y < a.height; ++y)
        for (int x = 0; x < a.width; ++x) {
            if (pixel(x, y, 3) != 1.0f) continue;
            float luminance = pixel(x, y, 0) + pixel(x, y, 1) + pixel(x, y, 2);
            bright += luminance > 0.8f;
            dark += luminance < 0.15f;
        }
    // (The default 2 x 2 gaussian filter softens shadow edges: fewer pixels stay fully dark.)
    CHECK(bright > 20);
    CHECK(dark > 8);
    fs::remove_all(dir);
}

TEST_CASE("cli: bad scenes fail with their location and leave no image", "[tools][render]") {
    fs::path dir = TempDir("badscene");
    fs::copy_file(kWave, dir / "wave.sl");
    std::string scene = SmallWaveScene(8, 8);
    WriteFile(dir / "typo.rib", scene + "Frobnicate 1 2 3\n");
    Output typo = Run("render " + (dir / "typo.rib").string() + " -o " + (dir / "out.exr").string(), true);
    CHECK(typo.status == 1);
    CHECK(typo.out.find("typo.rib:14:") != std::string::npos);
    std::string nanScene = scene;
    nanScene.replace(nanScene.find("\"Km\" [0.06]"), 11, "\"Km\" [1e999]");
    WriteFile(dir / "nan.rib", nanScene);
    CHECK(Run("render " + (dir / "nan.rib").string() + " -o " + (dir / "out.exr").string()).status == 1);
    std::string noShader = scene;
    noShader.replace(noShader.find("\"wave\""), 6, "\"nosuch\"");
    WriteFile(dir / "noshader.rib", noShader);
    // A shader found nowhere is not a bad scene (prman renders it undisplaced): a warning, an image.
    Output missing =
        Run("render " + (dir / "noshader.rib").string() + " -o " + (dir / "undisplaced.exr").string(), true);
    CHECK(missing.status == 0);
    CHECK(missing.out.find("warning: shader 'nosuch' not found") != std::string::npos);
    CHECK(fs::exists(dir / "undisplaced.exr"));
    fs::remove(dir / "undisplaced.exr");
    CHECK(Run("render " + (dir / "nothere.rib").string() + " -o " + (dir / "out.exr").string()).status == 1);
    // Unwritable output: fails, and nothing is left behind.
    WriteFile(dir / "valid.rib", scene);
    CHECK(Run("render " + (dir / "valid.rib").string() + " -o /nonexistent/dir/out.exr").status == diag::kExitOutput);
    CHECK_FALSE(fs::exists(dir / "out.exr"));
    for (const auto& entry : fs::directory_iterator(dir)) CHECK(entry.path().extension() != ".tmp");
    fs::remove_all(dir);
}

TEST_CASE("cli: compiled .afb shaders evaluate and render like their source", "[tools][bytecode]") {
    fs::path dir = TempDir("afb");
    fs::path afb = dir / "wave.afb";
    REQUIRE(Run("compile " + kWave + " -o " + afb.string()).status == 0);
    REQUIRE(fs::exists(afb));
    // The same numbers from the compiled file as from the source, with a parameter set.
    Output fromSource = Run("eval " + kWave + " --param Km=0.1 --at 0.25,0.5 --at 0.7,0.1");
    Output fromBytecode = Run("eval " + afb.string() + " --param Km=0.1 --at 0.25,0.5 --at 0.7,0.1");
    REQUIRE(fromSource.status == 0);
    CHECK(fromBytecode.status == 0);
    CHECK(fromBytecode.out == fromSource.out);
    CHECK(Run("eval " + afb.string() + " --param Kx=1 --at 0.5,0.5").status == 1);
    // The renderer finds NAME.afb when there is no NAME.sl.
    WriteFile(dir / "scene.rib", SmallWaveScene(16, 12));
    CHECK(Run("render " + (dir / "scene.rib").string() + " -o " + (dir / "out.exr").string()).status == 0);
    // A damaged file is an error naming it, never a crash.
    std::string bytes;
    {
        std::ifstream in(afb, std::ios::binary);
        bytes.assign(std::istreambuf_iterator<char>(in), {});
    }
    WriteFile(dir / "cut.afb", bytes.substr(0, bytes.size() / 2));
    Output cut = Run("eval " + (dir / "cut.afb").string() + " --at 0.5,0.5", true);
    CHECK(cut.status == 1);
    CHECK(cut.out.find("cut.afb: error: truncated file") != std::string::npos);
    fs::remove_all(dir);
}

TEST_CASE("cli: -I and -D reach the preprocessor of compile, eval and render", "[tools][preprocess]") {
    fs::path dir = TempDir("pp");
    fs::create_directories(dir / "include");
    WriteFile(dir / "include" / "amp.h", "#define AMPLITUDE(x) (0.5 * (x))\n");
    WriteFile(dir / "pp.sl",
              "#include \"amp.h\"\n"
              "displacement pp() {\n"
              "#ifdef HIGH\n"
              "    P += vector(0, 0, AMPLITUDE(LEVEL));\n"
              "#else\n"
              "    P += vector(0, 0, AMPLITUDE(1));\n"
              "#endif\n"
              "}\n");
    const std::string sl = (dir / "pp.sl").string(), inc = (dir / "include").string();
    Output missing = Run("compile " + sl, true);
    CHECK(missing.status == 1);
    CHECK(missing.out.find("pp.sl:1:") != std::string::npos);
    CHECK(Run("compile " + sl + " -I " + inc).status == 0);
    Output low = Run("eval " + sl + " -I" + inc + " --at 0.5,0.5");
    CHECK(low.out == "{\"P\":[0.5,0.5,0.5],\"N\":[0,0,1]}\n");
    Output high = Run("eval " + sl + " -I " + inc + " -D HIGH -DLEVEL=4 --at 0.5,0.5");
    CHECK(high.out == "{\"P\":[0.5,0.5,2],\"N\":[0,0,1]}\n");
    fs::remove_all(dir);
}

TEST_CASE("cli: string parameters from --param and RIB, and one compilation per distinct instance", "[tools][render]") {
    fs::path dir = TempDir("strings");
    WriteFile(dir / "s.sl",
              "displacement s(float Km = 0.05; string mode = \"up\") {\n"
              "  P += (mode == \"up\" ? Km : -Km) * normalize(N);\n}\n");
    Output up = Run("eval " + (dir / "s.sl").string() + " --at 0.5,0.5");
    Output down = Run("eval " + (dir / "s.sl").string() + " --param mode=down --at 0.5,0.5");
    REQUIRE((up.status == 0 && down.status == 0));
    CHECK(up.out.find("\"P\":[0.5,0.5,0.050000000000000003]") != std::string::npos);
    CHECK(down.out.find("\"P\":[0.5,0.5,-0.050000000000000003]") != std::string::npos);
    CHECK(Run("eval " + (dir / "s.sl").string() + " --param Km=down --at 0.5,0.5").status == 1);

    // Two patches with the same instance share one compilation; a third differs.
    std::string scene = R"(Format 8 6 1
Projection "perspective" "fov" [40]
Translate 0 0 3.1
WorldBegin
  AttributeBegin
    Displacement "s" "mode" "down"
    Patch "bilinear" "P" [-1 -1 0  0 -1 0  -1 1 0  0 1 0]
  AttributeEnd
  AttributeBegin
    Displacement "s" "mode" "down"
    Patch "bilinear" "P" [0 -1 0  1 -1 0  0 1 0  1 1 0]
  AttributeEnd
  AttributeBegin
    Displacement "s" "mode" "up"
    Patch "bilinear" "P" [0 -1 1  1 -1 1  0 1 1  1 1 1]
  AttributeEnd
WorldEnd
)";
    WriteFile(dir / "s.rib", scene);
    Output render = Run("render " + (dir / "s.rib").string() + " -o " + (dir / "s.exr").string() + " --stats");
    REQUIRE(render.status == 0);
    CHECK(render.out.find("\"shader_compilations\":2,\"shader_compilations_reused\":1") != std::string::npos);
    // The two patches of the "down" instance are one entry of the shader list, counted twice.
    CHECK(render.out.find("\"primitives\":2}") != std::string::npos);
    CHECK(render.out.find("\"primitives\":1}") != std::string::npos);
    fs::remove_all(dir);
}

TEST_CASE("cli: every scene in scenes/ parses and its shaders compile", "[tools][render]") {
    // A full render of each takes minutes; a copy rendered at 2x2 pixels is the cheap check that
    // the scene parses and its shaders and their instances all compile and run.
    fs::path dir = TempDir("scenes");
    fs::create_directories(dir / "scenes");
    // Shaders that belong to one scene live beside it.
    for (const auto& entry : fs::directory_iterator(test::SourceDir() + "/scenes"))
        if (entry.path().extension() == ".sl") fs::copy_file(entry.path(), dir / "scenes" / entry.path().filename());
    int scenes = 0;
    for (const auto& entry : fs::directory_iterator(test::SourceDir() + "/scenes")) {
        if (entry.path().extension() != ".rib") continue;
        ++scenes;
        std::ifstream in(entry.path());
        std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        size_t format = text.find("Format ");
        REQUIRE(format != std::string::npos);
        text.replace(format, text.find('\n', format) - format, "Format 2 2 1");
        fs::create_directories(dir / "scenes");
        WriteFile(dir / "scenes" / entry.path().filename(), text);
        fs::copy(test::SourceDir() + "/shaders", dir / "shaders",
                 fs::copy_options::recursive | fs::copy_options::skip_existing);
        Output out =
            Run("render " + (dir / "scenes" / entry.path().filename()).string() + " -o " + (dir / "out.exr").string(),
                true);
        INFO(entry.path().string() << "\n" << out.out);
        CHECK(out.status == 0);
    }
    CHECK(scenes >= 3);
    fs::remove_all(dir);
}

TEST_CASE("cli: diff reports the RMSE and largest RGB error of one image against another", "[tools]") {
    fs::path dir = TempDir("diff");
    // Two 2x1 images: the second differs by 0.5 in R of one pixel and 0.25 in B of the other.
    image::ImageBuffer a{2, 1, {0.5f, 0.5f, 0.5f, 1, 0.25f, 0, 1, 1}, {}, {}};
    image::ImageBuffer b = a;
    b.rgba[0] = 1.0f;
    b.rgba[6] = 0.75f;
    image::ImageBuffer wide{3, 1, std::vector<float>(12, 0.0f), {}, {}};
    REQUIRE(image::WriteExr((dir / "a.exr").string(), a, nullptr));
    REQUIRE(image::WriteExr((dir / "b.exr").string(), b, nullptr));
    REQUIRE(image::WriteExr((dir / "wide.exr").string(), wide, nullptr));
    // RMSE over 6 values: sqrt((0.25 + 0.0625) / 6).
    Output same = Run("diff " + (dir / "a.exr").string() + " " + (dir / "a.exr").string());
    CHECK(same.status == 0);
    CHECK(same.out == "{\"pixels\":2,\"rmse\":0,\"max\":0}\n");
    Output d = Run("diff " + (dir / "a.exr").string() + " " + (dir / "b.exr").string());
    CHECK(d.status == 0);
    CHECK(d.out.find("\"max\":0.5}") != std::string::npos);
    CHECK(d.out.find("\"rmse\":0.2282177322938192") != std::string::npos);
    Output size = Run("diff " + (dir / "a.exr").string() + " " + (dir / "wide.exr").string(), true);
    CHECK(size.status == 1);
    CHECK(size.out.find("wide.exr: error: the image is 3x1 but the reference '") != std::string::npos);
    Output missing = Run("diff " + (dir / "a.exr").string() + " " + (dir / "none.exr").string(), true);
    CHECK(missing.status == 1);
    CHECK(missing.out.find("cannot read") != std::string::npos);
    CHECK(Run("diff " + (dir / "a.exr").string()).status == 2);
    fs::remove_all(dir);
}

TEST_CASE("cli: an uncalled function passing a string parameter as a space compiles, evaluates and renders",
          "[tools][render]") {
    // Regression test (issue 14): compile, eval and render all died with a segmentation fault
    // (exit 139, nothing printed) on this shader.
    fs::path dir = TempDir("uncalled");
    WriteFile(dir / "r.sl",
              "float D (string space) { return xcomp(vtransform(space, N)); }\n"
              "point T (string space) { return transform(space, P); }\n"
              "displacement r() { P += 0.05 * sin(10 * u) * normalize(N); }\n");
    const std::string sl = (dir / "r.sl").string();
    CHECK(Run("compile " + sl).status == 0);
    Output eval = Run("eval " + sl + " --at 0.25,0.5");
    CHECK(eval.status == 0);
    CHECK(eval.out.rfind("{\"P\":[0.25,0.5,", 0) == 0);
    WriteFile(dir / "r.rib",
              "Format 16 12 1\nProjection \"perspective\" \"fov\" [40]\nDisplay \"r.exr\" \"file\" "
              "\"rgba\"\nTranslate 0 0 3\nWorldBegin\nDisplacement \"r\"\n"
              "Patch \"bilinear\" \"P\" [-1 -1 0  1 -1 0  -1 1 0  1 1 0]\nWorldEnd\n");
    Output render = Run("render " + (dir / "r.rib").string() + " -o " + (dir / "r.exr").string() + " --quiet", true);
    INFO(render.out);
    CHECK(render.status == 0);
    CHECK(fs::exists(dir / "r.exr"));
    fs::remove_all(dir);
}

TEST_CASE("cli: the exit codes of the README, and every message in the one diagnostic format", "[tools][diagnostics]") {
    const fs::path dir = TempDir("exit");
    fs::copy_file(kWave, dir / "wave.sl");
    WriteFile(dir / "small.rib", SmallWaveScene(8, 6));
    const std::string rib = (dir / "small.rib").string();
    const std::string missingDir = (dir / "no" / "such" / "dir").string();
    // A message line is "place: error: text" (the place "affray" for the command line).
    auto firstLine = [](const std::string& out) { return out.substr(0, out.find('\n')); };

    // 0: success.
    CHECK(Run("render " + rib + " -o " + (dir / "ok.exr").string() + " --quiet").status == diag::kExitSuccess);
    CHECK(Run("--version").status == diag::kExitSuccess);

    // 1: bad input, of every kind: shader, scene, compiled shader, image.
    WriteFile(dir / "bad.sl", "displacement bad() {\n  P += ;\n}\n");
    Output shader = Run("compile " + (dir / "bad.sl").string(), true);
    CHECK(shader.status == diag::kExitBadInput);
    CHECK(firstLine(shader.out).rfind((dir / "bad.sl").string() + ":2:8: error: ", 0) == 0);
    WriteFile(dir / "bad.rib", "WorldBegin\n  Sphere 1 -1 1\nWorldEnd\n");
    Output scene = Run("render " + (dir / "bad.rib").string(), true);
    CHECK(scene.status == diag::kExitBadInput);
    CHECK(scene.out == (dir / "bad.rib").string() +
                           ":2:3: error: 'Sphere' expects 4 numbers (radius zmin zmax thetamax), got 3\n"
                           "      Sphere 1 -1 1\n"
                           "      ^\n");
    WriteFile(dir / "bad.afb", "not bytecode");
    Output afb = Run("eval " + (dir / "bad.afb").string() + " --at 0.5,0.5", true);
    CHECK(afb.status == diag::kExitBadInput);
    CHECK(afb.out == (dir / "bad.afb").string() + ": error: not an affray bytecode file\n");
    Output image = Run("diff " + (dir / "none.exr").string() + " " + (dir / "ok.exr").string(), true);
    CHECK(image.status == diag::kExitBadInput);
    CHECK(firstLine(image.out).rfind((dir / "none.exr").string() + ": error: cannot read image: ", 0) == 0);
    Output missing = Run("render " + (dir / "none.rib").string(), true);
    CHECK(missing.status == diag::kExitBadInput);
    CHECK(missing.out == (dir / "none.rib").string() + ": error: cannot read file: No such file or directory\n");

    // 2: bad usage, with the usage after the message.
    Output usage = Run("render " + rib + " --threads 0", true);
    CHECK(usage.status == diag::kExitUsage);
    CHECK(firstLine(usage.out) == "affray: error: --threads takes an integer from 1 to 1024");
    CHECK(usage.out.find("usage:") != std::string::npos);

    // 3: an output that cannot be written, and nothing left behind.
    Output exr = Run("render " + rib + " --quiet -o " + missingDir + "/out.exr", true);
    CHECK(exr.status == diag::kExitOutput);
    CHECK(exr.out ==
          missingDir + "/out.exr: error: cannot write file: directory '" + missingDir + "' does not exist\n");
    Output png =
        Run("render " + rib + " --quiet -o " + (dir / "p.exr").string() + " --png " + missingDir + "/p.png", true);
    CHECK(png.status == diag::kExitOutput);
    CHECK(firstLine(png.out).rfind(missingDir + "/p.png: error: cannot write file: ", 0) == 0);
    Output bytecode = Run("compile " + kWave + " -o " + missingDir + "/w.afb", true);
    CHECK(bytecode.status == diag::kExitOutput);
    CHECK(bytecode.out == missingDir + "/w.afb: error: cannot write file: No such file or directory\n");
    CHECK_FALSE(fs::exists(dir / "no"));
    fs::remove_all(dir);
}

TEST_CASE("cli: a message holding a line break prints on one line", "[tools][diagnostics]") {
    const fs::path dir = TempDir("oneline");
    // A Display mode string with a line break inside: the message quotes it.
    WriteFile(dir / "s.rib", "Display \"out.exr\" \"file\" \"rgba\nzz\"\nWorldBegin\nWorldEnd\n");
    Output r = Run("render " + (dir / "s.rib").string(), true);
    CHECK(r.status == diag::kExitBadInput);
    CHECK(r.out.rfind((dir / "s.rib").string() + ":1:26: error: 'Display' mode 'rgba\\nzz' has an unknown", 0) == 0);
    // Three lines: the message, the source line, the caret.
    CHECK(std::count(r.out.begin(), r.out.end(), '\n') == 3);
    fs::remove_all(dir);
}
