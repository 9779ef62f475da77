// tests/renderer/shadow_rules_test.cpp: which lights trace shadows and which primitives stop
// them, through the whole renderer (rib/attributes.cpp, renderer/shade.cpp, renderer/render.cpp):
// RenderMan's standard lights cast none, so a constant-shaded sphere around the scene (a
// background, as in Advanced RenderMan's figure 8.5) leaves it lit; a light with Attribute
// "light" "shadows" "on" is blocked by an occluder unless the occluder's transmission says
// otherwise, by its opacity when it says "Os". Expected values are the matte colour
// Ka * ambient + Kd * cos (Cs = 1, Ka = Kd = 1) worked out from each scene's geometry.
#include <catch2/catch.hpp>

#include <cmath>

#include "tests/renderer/render_coverage.h"

using namespace affray;

namespace {

/// The mean red of the pixels whose P (world space) lies within `radius` of `at`, and how many
/// there are (the image must have a "P" channel).
double MeanRedNear(const image::ImageBuffer& image, const glm::dvec3& at, double radius, int* count) {
    const std::vector<float>*x = nullptr, *y = nullptr, *z = nullptr;
    for (const auto& [name, values] : image.extraChannels) {
        if (name == "P.X") x = &values;
        if (name == "P.Y") y = &values;
        if (name == "P.Z") z = &values;
    }
    REQUIRE((x && y && z));
    double sum = 0;
    *count = 0;
    for (size_t i = 0; i < x->size(); ++i) {
        if (image.rgba[4 * i + 3] == 0) continue;
        if (glm::length(glm::dvec3((*x)[i], (*y)[i], (*z)[i]) - at) > radius) continue;
        sum += image.rgba[4 * i];
        ++*count;
    }
    return *count ? sum / *count : 0;
}

/// A floor (z = 0, [-2, 2]^2) seen from 5 in front (the camera at z = -5 looking along +z), a
/// square occluder at z = -1 ([-0.5, 0.5]^2) between them, an ambient light of 0.1 and a distant
/// light from (1, 0, -1): the occluder's shadow is the floor's x in [-1.5, -0.5], lit with
/// cos 45 deg. `lights` goes before the lights, `occluder` before the occluder.
std::string FloorScene(const std::string& lights, const std::string& occluder) {
    return "Format 40 40 1\nDisplay \"t.exr\" \"file\" \"rgba,P\"\nProjection \"perspective\" \"fov\" [60]\n"
           "Translate 0 0 5\nWorldBegin\n" +
           lights +
           "LightSource \"ambientlight\" 1 \"intensity\" [0.1]\n"
           "LightSource \"distantlight\" 2 \"from\" [1 0 -1] \"to\" [0 0 0]\n"
           "Surface \"matte\"\n"
           "Patch \"bilinear\" \"P\" [-2 -2 0  2 -2 0  -2 2 0  2 2 0]\n"
           "AttributeBegin\n" +
           occluder +
           "Patch \"bilinear\" \"P\" [-0.5 -0.5 -1  0.5 -0.5 -1  -0.5 0.5 -1  0.5 0.5 -1]\n"
           "AttributeEnd\nWorldEnd\n";
}

const double kLit = 0.1 + std::sqrt(0.5), kShadowed = 0.1;

/// The floor's colour in the occluder's shadow (around (-1, 0, 0)) and beside it, lit (around
/// (1.2, 0, 0), outside the occluder's silhouette).
std::pair<double, double> FloorShadeAndLight(const std::string& lights, const std::string& occluder) {
    test::TempDir dir;
    const image::ImageBuffer image = test::RenderRib(dir, FloorScene(lights, occluder));
    int inShadow = 0, inLight = 0;
    const double shade = MeanRedNear(image, {-1, 0, 0}, 0.3, &inShadow);
    const double light = MeanRedNear(image, {1.2, 0, 0}, 0.3, &inLight);
    REQUIRE(inShadow > 5);
    REQUIRE(inLight > 5);
    return {shade, light};
}

}  // namespace

TEST_CASE("shadow rules: a constant sphere around the scene does not darken the standard lights",
          "[renderer][shadow]") {
    // Advanced RenderMan figure 8.5: the object inside a large constant-shaded sphere, the
    // background, lit by distantlights. They cast no shadows, so the object is lit.
    auto scene = [](const std::string& lights) {
        return "Format 24 24 1\nDisplay \"t.exr\" \"file\" \"rgba,P\"\nProjection \"perspective\" \"fov\" [30]\n"
               "Translate 0 0 5\nWorldBegin\n" +
               lights +
               "LightSource \"ambientlight\" 1 \"intensity\" [0.1]\n"
               "LightSource \"distantlight\" 2 \"from\" [0 0 -1] \"to\" [0 0 0]\n"
               "LightSource \"distantlight\" 3 \"from\" [0 1 -1] \"to\" [0 0 0] \"intensity\" [0]\n"
               "AttributeBegin\nSurface \"constant\"\nColor 0.2 0.3 0.4\nSphere 20 -20 20 360\nAttributeEnd\n"
               "Surface \"matte\"\nSphere 1 -1 1 360\nWorldEnd\n";
    };
    test::TempDir dir;
    int n = 0;
    // The sphere's point facing the camera and the light: N.L = 1.
    const image::ImageBuffer lit = test::RenderRib(dir, scene(""));
    CHECK(MeanRedNear(lit, {0, 0, -1}, 0.1, &n) == Approx(1.1).epsilon(0.01));
    CHECK(n > 0);
    // The background is the constant sphere's colour.
    CHECK(lit.rgba[0] == Approx(0.2f));
    CHECK(lit.rgba[2] == Approx(0.4f));
    // Asked to trace shadows, the light is blocked by the background sphere: ambient only.
    const image::ImageBuffer shadowed = test::RenderRib(dir, scene("Attribute \"light\" \"shadows\" \"on\"\n"));
    CHECK(MeanRedNear(shadowed, {0, 0, -1}, 0.1, &n) == Approx(0.1).epsilon(0.01));
}

TEST_CASE("shadow rules: a light with shadows on is blocked by an occluder, a standard one is not",
          "[renderer][shadow]") {
    const std::string on = "Attribute \"light\" \"shadows\" \"on\"\n";
    auto [shade, light] = FloorShadeAndLight("", "");
    CHECK(shade == Approx(kLit).epsilon(1e-3));
    CHECK(light == Approx(kLit).epsilon(1e-3));
    std::tie(shade, light) = FloorShadeAndLight(on, "");
    CHECK(shade == Approx(kShadowed).epsilon(1e-3));
    CHECK(light == Approx(kLit).epsilon(1e-3));
}

TEST_CASE("shadow rules: transparent occluders cast no shadow, \"Os\" ones let 1 - Os through", "[renderer][shadow]") {
    const std::string on = "Attribute \"light\" \"shadows\" \"on\"\n";
    for (const char* attribute :
         {"Attribute \"visibility\" \"transmission\" \"transparent\"\n",
          "Attribute \"visibility\" \"int transmission\" [0]\n", "Attribute \"render\" \"casts_shadows\" \"none\"\n"}) {
        INFO(attribute);
        const auto [shade, light] = FloorShadeAndLight(on, attribute);
        CHECK(shade == Approx(kLit).epsilon(1e-3));
        CHECK(light == Approx(kLit).epsilon(1e-3));
    }
    // Half opaque: "Os" lets half the light through, "opaque" (the default) none.
    auto [shade, light] =
        FloorShadeAndLight(on, "Opacity 0.5 0.5 0.5\nAttribute \"visibility\" \"transmission\" \"Os\"\n");
    CHECK(shade == Approx(0.1 + 0.5 * std::sqrt(0.5)).epsilon(1e-3));
    std::tie(shade, light) = FloorShadeAndLight(on, "Opacity 0.5 0.5 0.5\n");
    CHECK(shade == Approx(kShadowed).epsilon(1e-3));
}

TEST_CASE("shadow rules: an occluder invisible to the camera still casts its shadow", "[renderer][shadow]") {
    test::TempDir dir;
    const image::ImageBuffer image = test::RenderRib(
        dir, FloorScene("Attribute \"light\" \"shadows\" \"on\"\n", "Attribute \"visibility\" \"camera\" [0]\n"));
    int n = 0;
    CHECK(MeanRedNear(image, {-1, 0, 0}, 0.3, &n) == Approx(kShadowed).epsilon(1e-3));
    // The camera sees the floor through it: the floor's points behind the occluder, lit (the
    // light comes in beside the occluder there).
    CHECK(MeanRedNear(image, {0.3, 0, 0}, 0.2, &n) == Approx(kLit).epsilon(1e-3));
    CHECK(n > 0);
}
