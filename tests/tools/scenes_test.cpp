// tests/tools/scenes_test.cpp: the gallery scenes of scenes/ (showcase, orbs, vase, donut,
// columns, mixed, rock, nurbs, creature, teapot, textured, focus, motion) through the `affray` program, shrunk so that this stays cheap: each renders,
// writes every AOV channel its Display mode asks for, hits something at a finite depth and
// reports a positive cost. The full-size figures are in each scene's header comment.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "image/exr_writer.h"
#include "tests/test_util.h"

namespace fs = std::filesystem;
using namespace affray;

namespace {

const std::vector<float>* Channel(const image::ImageBuffer& image, const std::string& name) {
    for (const auto& [n, values] : image.extraChannels)
        if (n == name) return &values;
    return nullptr;
}

}  // namespace

TEST_CASE("scenes cli: the gallery scenes render shrunk with every AOV", "[tools][scenes]") {
    // A copy of scenes/ and shaders/ side by side, as in the source tree (shaders are found in
    // ../shaders from a scene, scene-local ones next to it).
    test::TempDir dir;
    fs::copy(test::SourceDir() + "/scenes", dir.Path("scenes"), fs::copy_options::recursive);
    fs::copy(test::SourceDir() + "/shaders", dir.Path("shaders"), fs::copy_options::recursive);
    const char* channels[] = {"Z", "N.X", "N.Y", "N.Z", "P.X", "P.Y", "P.Z", "st.s", "st.t", "cost", "err"};
    for (const char* name : {"showcase", "orbs", "vase", "donut", "columns", "mixed", "rock", "nurbs", "creature",
                             "teapot", "textured", "focus", "motion"}) {
        INFO(name);
        const fs::path rib = dir.Path(std::string("scenes/") + name + ".rib");
        REQUIRE(fs::exists(rib));
        test::ShrinkFormat(rib, 10, 16, 12);
        const std::string exr = dir.Path(std::string(name) + ".exr");
        test::CliOutput r = test::RunCli("render " + rib.string() + " -o " + exr + " --samples 1 --quiet", true);
        INFO(r.out);
        REQUIRE(r.status == 0);
        image::ImageBuffer image;
        affray::diag::Report error;
        REQUIRE(image::ReadExrRgba(exr, &image, &error));
        const size_t pixels = size_t(image.width) * size_t(image.height);
        REQUIRE(pixels > 0);
        for (const char* channel : channels) {
            INFO(channel);
            const std::vector<float>* values = Channel(image, channel);
            REQUIRE(values != nullptr);
            CHECK(values->size() == pixels);
        }
        const std::vector<float>& z = *Channel(image, "Z");
        const std::vector<float>& cost = *Channel(image, "cost");
        size_t hits = 0;
        bool finiteDepth = true;
        for (size_t i = 0; i < pixels; ++i) {
            if (image.rgba[4 * i + 3] != 1.0f) continue;
            ++hits;
            if (!(std::isfinite(z[i]) && z[i] < 1e29f)) finiteDepth = false;
        }
        CHECK(hits > 0);
        CHECK(finiteDepth);
        CHECK(*std::max_element(cost.begin(), cost.end()) > 0.0f);
    }
}
