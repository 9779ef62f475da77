// tests/tools/oiio_test.cpp: the EXR files `affray render` writes, as an independent reader sees
// them: OpenImageIO's command-line tools (Debian package openimageio-tools, installed by
// tools/setup.sh) must read the resolution, the channel names (layer.component, so they group)
// and types (RGBA half, AOVs float), and find renders with different thread counts identical.
// Missing tools are a failure naming the package, not a skip: these checks must not quietly
// stop running on a machine set up without them.
#include <catch2/catch.hpp>

#include <sys/wait.h>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <sstream>
#include <string_view>

#include "tests/test_util.h"

using namespace affray;

namespace {

using Shell = test::CliOutput;

/// Runs a shell command, capturing stdout and stderr.
Shell Run(const std::string& command) { return test::RunShell(command + " 2>&1"); }

using test::Quote;

/// Fails, naming the package, unless `tool` is on the PATH.
void RequireTool(const std::string& tool) {
    const bool found = Run("command -v " + tool).status == 0;
    if (!found)
        FAIL("'" << tool
                 << "' is not installed: install the Debian package openimageio-tools "
                    "(sudo apt-get install openimageio-tools, or run tools/setup.sh)");
}

constexpr int kWidth = 24, kHeight = 16;

std::string Scene() {
    return "Format " + std::to_string(kWidth) + " " + std::to_string(kHeight) + " 1\n" +
           R"(Projection "perspective" "fov" [40]
Display "oiio.exr" "file" "rgba,Z,N,P,st,cost,err"
Translate 0 0 3.1
Rotate -130 1 0 0
WorldBegin
  LightSource "ambientlight" 1 "intensity" [0.06]
  LightSource "distantlight" 2 "intensity" [1.1] "from" [-3 1.5 1.1] "to" [0 0 0]
  Surface "plastic"
  Displacement "wave" "Km" [0.06] "frequency" [8] "decay" [2.5]
  Patch "bilinear" "P" [-1 -1 0  1 -1 0  -1 1 0  1 1 0]
WorldEnd
)";
}

/// Renders the scene in `dir` into `name` with `extra` arguments; returns the file's path.
std::string Render(const test::TempDir& dir, const std::string& name, const std::string& extra) {
    std::string path = dir.Path(name);
    test::CliOutput out =
        test::RunCli("render " + Quote(dir.Path("scene.rib")) + " -o " + Quote(path) + " --quiet " + extra, true);
    INFO(out.out);
    REQUIRE(out.status == 0);
    return path;
}

/// The "channel list: R (half), G (half), ..." line of `oiiotool --info -v` / `iinfo -v`, as
/// name -> type.
std::map<std::string, std::string> Channels(const std::string& info) {
    std::map<std::string, std::string> out;
    const size_t at = info.find("channel list:");
    if (at == std::string::npos) return out;
    // (Parsed by hand: std::regex trips GCC 12's -Wmaybe-uninitialized in the -O1 ASan build.)
    const size_t begin = at + std::string("channel list:").size();
    std::istringstream line(info.substr(begin, info.find('\n', at) - begin));
    std::string entry;
    while (std::getline(line, entry, ',')) {
        const size_t open = entry.find('('), close = entry.find(')');
        if (open == std::string::npos || close == std::string::npos || close < open) continue;
        const size_t first = entry.find_first_not_of(' ');
        std::string name = entry.substr(first, open - first);
        while (!name.empty() && name.back() == ' ') name.pop_back();
        out[name] = entry.substr(open + 1, close - open - 1);
    }
    return out;
}

void CheckInfo(const std::string& info) {
    INFO(info);
    // "FILE :   24 x   16, 15 channel, half/.../float openexr"
    const size_t colon = info.find(" : ");
    REQUIRE(colon != std::string::npos);
    // "W x H, N channel": three integers, read with strtol so that a malformed line fails here.
    const char* p = info.c_str() + colon + 3;
    char* end = nullptr;
    const long width = std::strtol(p, &end, 10);
    REQUIRE(end != p);
    REQUIRE(std::string_view(end).substr(0, 3) == " x ");
    p = end + 3;
    const long height = std::strtol(p, &end, 10);
    REQUIRE(end != p);
    REQUIRE(std::string_view(end).substr(0, 2) == ", ");
    p = end + 2;
    const long channelCount = std::strtol(p, &end, 10);
    REQUIRE(end != p);
    REQUIRE(std::string_view(end).substr(0, 8) == " channel");
    CHECK(width == kWidth);
    CHECK(height == kHeight);
    CHECK(channelCount == 15);
    CHECK(info.find("openexr") != std::string::npos);
    const std::map<std::string, std::string> channels = Channels(info);
    const std::map<std::string, std::string> expected = {
        {"R", "half"},    {"G", "half"},     {"B", "half"},     {"A", "half"},     {"Z", "float"},
        {"N.X", "float"}, {"N.Y", "float"},  {"N.Z", "float"},  {"P.X", "float"},  {"P.Y", "float"},
        {"P.Z", "float"}, {"st.s", "float"}, {"st.t", "float"}, {"cost", "float"}, {"err", "float"}};
    CHECK(channels == expected);
}

}  // namespace

TEST_CASE("oiio: oiiotool and iinfo read the resolution, channel names and types of a render", "[tools][oiio]") {
    RequireTool("oiiotool");
    RequireTool("iinfo");
    test::TempDir dir;
    dir.Write("scene.rib", Scene());
    std::filesystem::copy_file(test::SourceDir() + "/shaders/wave.sl", dir.Path("wave.sl"));
    const std::string exr = Render(dir, "out.exr", "");
    Shell oiiotool = Run("oiiotool --info -v " + Quote(exr));
    INFO(oiiotool.out);
    REQUIRE(oiiotool.status == 0);
    CheckInfo(oiiotool.out);
    Shell iinfo = Run("iinfo -v " + Quote(exr));
    INFO(iinfo.out);
    REQUIRE(iinfo.status == 0);
    CheckInfo(iinfo.out);
    // Statistics over all 15 channels: no NaN or infinity anywhere (a miss's Z is 1e30, finite),
    // and alpha reaches 1 (the patch covers the centre).
    Shell stats = Run("oiiotool --stats " + Quote(exr));
    INFO(stats.out);
    REQUIRE(stats.status == 0);
    CHECK(stats.out.find("Stats NanCount: 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0") != std::string::npos);
    CHECK(stats.out.find("Stats InfCount: 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0") != std::string::npos);
    const size_t maxAt = stats.out.find("Stats Max:");
    REQUIRE(maxAt != std::string::npos);
    std::istringstream maxima(stats.out.substr(maxAt + 10));
    double r = 0, g = 0, b = 0, a = 0;
    REQUIRE(maxima >> r >> g >> b >> a);
    CHECK(a == 1.0);
    // A file that is not an image is an error for the tools too (so exit 0 above means something).
    dir.Write("bad.exr", "not an image");
    CHECK(Run("oiiotool --info -v " + Quote(dir.Path("bad.exr"))).status != 0);
}

TEST_CASE("oiio: idiff finds renders with 1 and 2 threads identical in every channel", "[tools][oiio]") {
    RequireTool("idiff");
    test::TempDir dir;
    dir.Write("scene.rib", Scene());
    std::filesystem::copy_file(test::SourceDir() + "/shaders/wave.sl", dir.Path("wave.sl"));
    const std::string one = Render(dir, "one.exr", "--threads 1");
    const std::string two = Render(dir, "two.exr", "--threads 2");
    // -fail 0 -warn 0: any difference at all, in any channel, is a failure.
    Shell same = Run("idiff -fail 0 -warn 0 " + Quote(one) + " " + Quote(two));
    INFO(same.out);
    CHECK(same.status == 0);
    CHECK(same.out.find("PASS") != std::string::npos);
    // And idiff does see a difference: a crop of the same scene is zero on its right half.
    const std::string crop = Render(dir, "crop.exr", "--threads 2 --crop 0,0.5,0,1");
    Shell differs = Run("idiff -fail 0 -warn 0 " + Quote(one) + " " + Quote(crop));
    INFO(differs.out);
    CHECK(differs.status != 0);
    CHECK(differs.out.find("FAILURE") != std::string::npos);
}
