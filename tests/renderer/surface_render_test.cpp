// tests/renderer/surface_render_test.cpp: surface shaders in renders (renderer/prepare.cpp finds
// and compiles them per light set, renderer/render.cpp runs them at camera hits): the standard
// surfaces of shaders/ against the built-in models they replace, under every kind of light and
// traced shadows; a scene's own shader of a standard name; light categories; derivatives; and the
// shader's Oi compositing.
#include <catch2/catch.hpp>

#include "tests/renderer/render_text.h"

using namespace affray;

namespace {

/// The pixel (x, y)'s RGB.
glm::dvec3 Pixel(const image::ImageBuffer& image, int x, int y) {
    const size_t i = (size_t(y) * size_t(image.width) + size_t(x)) * 4;
    return {image.rgba[i], image.rgba[i + 1], image.rgba[i + 2]};
}

/// Spheres of each standard surface on a matte floor under an ambient, a distant light that casts
/// shadows, a point light and a spotlight.
const char* const kStandardScene = R"(Format 96 72 1
PixelSamples 2 2
Projection "perspective" "fov" [40]
Translate 0 -0.3 6
Rotate -110 1 0 0
WorldBegin
  Attribute "light" "shadows" "on"
  LightSource "ambientlight" 1 "intensity" [0.1]
  LightSource "distantlight" 2 "from" [-3 2 4] "to" [0 0 0] "lightcolor" [1 0.9 0.8]
  Attribute "light" "shadows" "off"
  LightSource "pointlight" 3 "from" [2 -2 2] "intensity" [4]
  LightSource "spotlight" 4 "from" [0 -1 4] "to" [0 0 0] "intensity" [12] "coneangle" [0.4]
  Color [0.8 0.7 0.6]
  Surface "matte"
  Patch "bilinear" "P" [-4 -4 0  4 -4 0  -4 4 0  4 4 0]
  AttributeBegin
    Translate -1.2 0 0.5
    Color [0.9 0.3 0.2]
    Surface "plastic" "Ks" [0.7] "roughness" [0.05] "specularcolor" [0.5 0.5 1]
    Sphere 0.5 -0.5 0.5 360
  AttributeEnd
  AttributeBegin
    Translate 0 0.4 0.5
    Color [0.9 0.8 0.3]
    Surface "metal" "Ka" [0.5] "roughness" [0.2]
    Sphere 0.5 -0.5 0.5 360
  AttributeEnd
  AttributeBegin
    Translate 1.2 0 0.5
    Color [0.3 0.5 0.9]
    Surface "constant"
    Sphere 0.5 -0.5 0.5 360
  AttributeEnd
WorldEnd
)";

}  // namespace

TEST_CASE("surface render: the standard surfaces of shaders/ give the built-in models' images", "[renderer][surface]") {
    const image::ImageBuffer fromShaders = test::RenderText(kStandardScene);
    const image::ImageBuffer builtIn = test::RenderText(kStandardScene, std::vector<std::string>{});
    const double rmse = test::RgbRmse(fromShaders, builtIn);
    INFO("RMSE " << rmse);
    CHECK(rmse < 1e-4);
    // The two differ at all (the scene is lit and shadowed): a render of no light is far off.
    std::string dark = kStandardScene;
    dark.replace(dark.find("\"intensity\" [4]"), 15, "\"intensity\" [0]");
    CHECK(test::RgbRmse(test::RenderText(dark), builtIn) > 1e-2);
}

TEST_CASE("surface render: a scene's own shader of a standard name wins over the built-in model",
          "[renderer][surface]") {
    test::TempDir dir;
    dir.Write("plastic.sl", "surface plastic(float Ks = .5) { Oi = Os; Ci = color(0, Ks, 0); }\n");
    const std::string rib = R"(Format 8 8 1
Projection "perspective" "fov" [30]
Translate 0 0 5
WorldBegin
  Surface "plastic" "Ks" [0.75]
  Sphere 1 -1 1 360
WorldEnd
)";
    const image::ImageBuffer image = test::RenderText(rib, std::vector<std::string>{dir.Path("")});
    const glm::dvec3 centre = Pixel(image, 4, 4);
    CHECK(centre.x == Approx(0.0).margin(1e-6));
    CHECK(centre.y == Approx(0.75).margin(1e-6));
    CHECK(centre.z == Approx(0.0).margin(1e-6));
}

TEST_CASE("surface render: illuminance by category sees only that category's lights", "[renderer][surface]") {
    test::TempDir dir;
    dir.Write("keyonly.sl",
              "surface keyonly(string category = \"key\") { illuminance (category, P) Ci += Cl; Oi = 1; }\n");
    const std::string rib = R"(Format 8 8 1
Projection "perspective" "fov" [30]
Translate 0 0 5
WorldBegin
  LightSource "distantlight" 1 "lightcolor" [1 0 0] "string __category" ["fill,key"]
  LightSource "distantlight" 2 "lightcolor" [0 0 1] "__category" "rim"
  LightSource "ambientlight" 3 "lightcolor" [0 1 0]
  Surface "keyonly" "category" "CATEGORY"
  Sphere 1 -1 1 360
WorldEnd
)";
    auto centre = [&](const std::string& category) {
        std::string text = rib;
        text.replace(text.find("CATEGORY"), 8, category);
        return Pixel(test::RenderText(text, std::vector<std::string>{dir.Path("")}), 4, 4);
    };
    CHECK(centre("key") == glm::dvec3(1, 0, 0));
    CHECK(centre("rim") == glm::dvec3(0, 0, 1));
    CHECK(centre("") == glm::dvec3(1, 0, 1));  // every light a loop visits (not the ambient one)
    CHECK(centre("-key") == glm::dvec3(0, 0, 1));
}

TEST_CASE("surface render: a shader's derivatives, its own opacity, and values that are not finite",
          "[renderer][surface]") {
    test::TempDir dir;
    // s and t run along u and v over a lone patch: Du(s) = Dv(t) = 1 (the dual VM's derivatives).
    dir.Write("slopes.sl", "surface slopes() { Ci = color(Du(s), Dv(t), Du(t)); Oi = 1; }\n");
    dir.Write("veil.sl", "surface veil() { Oi = 0.25; Ci = Oi * color(1, 1, 0); }\n");
    dir.Write("broken.sl",
              "surface broken() { float zero = u - u; Ci = color(zero / zero, 1 / zero, 0.5); Oi = 1; }\n");
    const std::string rib = R"(Format 8 8 1
Projection "perspective" "fov" [30]
Translate 0 0 5
WorldBegin
  Surface "SHADER"
  Patch "bilinear" "P" [-2 -2 0  2 -2 0  -2 2 0  2 2 0]
WorldEnd
)";
    auto render = [&](const std::string& shader) {
        std::string text = rib;
        text.replace(text.find("SHADER"), 6, shader);
        return test::RenderText(text, std::vector<std::string>{dir.Path("")});
    };
    const glm::dvec3 slopes = Pixel(render("slopes"), 4, 4);
    CHECK(slopes.x == Approx(1.0).margin(1e-9));
    CHECK(slopes.y == Approx(1.0).margin(1e-9));
    CHECK(slopes.z == Approx(0.0).margin(1e-9));
    // A component that is not finite (0/0, 1/0) renders as 0, not as a NaN that spreads.
    CHECK(Pixel(render("broken"), 4, 4) == glm::dvec3(0, 0, 0.5));
    // The shader's Oi is the surface's coverage: a quarter of its colour, alpha a quarter.
    const image::ImageBuffer veil = render("veil");
    CHECK(Pixel(veil, 4, 4) == glm::dvec3(0.25, 0.25, 0.0));
    CHECK(veil.rgba[(4 * 8 + 4) * 4 + 3] == Approx(0.25));
}

TEST_CASE("surface render: trace() sees the surface along a ray, shaded, to a depth limit", "[renderer][surface]") {
    test::TempDir dir;
    // A mirror facing the camera reflects a red wall behind it (which the camera does not see).
    dir.Write("mirror.sl", "surface mirror(float Kr = 1) { Oi = 1; Ci = Kr * trace(P, reflect(I, normalize(N))); }\n");
    dir.Write("flat.sl", "surface flat() { Oi = 1; Ci = Cs; }\n");
    const std::string rib = R"(Format 16 16 1
Projection "perspective" "fov" [30]
WorldBegin
  Surface "mirror" "Kr" [0.5]
  Patch "bilinear" "P" [-5 -5 3  5 -5 3  -5 5 3  5 5 3]
  Color [1 0 0]
  Surface "flat"
  Patch "bilinear" "P" [-20 -20 -2  20 -20 -2  -20 20 -2  20 20 -2]
WorldEnd
)";
    const image::ImageBuffer image = test::RenderText(rib, std::vector<std::string>{dir.Path("")});
    for (const auto& [x, y] : {std::pair{8, 8}, std::pair{1, 1}, std::pair{14, 3}}) {
        const glm::dvec3 c = Pixel(image, x, y);
        INFO(x << " " << y << ": " << c.x << " " << c.y << " " << c.z);
        CHECK(c.x == Approx(0.5).margin(1e-6));
        CHECK(c.y == 0);
        CHECK(c.z == 0);
    }
    // Without the wall the mirror sees nothing: black.
    std::string open = rib;
    open.replace(open.find("  Color [1 0 0]"), open.find("WorldEnd") - open.find("  Color [1 0 0]"), "");
    CHECK(Pixel(test::RenderText(open, std::vector<std::string>{dir.Path("")}), 8, 8) == glm::dvec3(0.0));
    // Two mirrors facing each other: each trace goes one level deeper, until the limit.
    const std::string hall = R"(Format 8 8 1
Projection "perspective" "fov" [20]
Translate 0 0 -1
WorldBegin
  Surface "mirror" "Kr" [0.5]
  Patch "bilinear" "P" [-5 -5 0  5 -5 0  -5 5 0  5 5 0]
  Patch "bilinear" "P" [-5 -5 -2  5 -5 -2  -5 5 -2  5 5 -2]
WorldEnd
)";
    const image::ImageBuffer mirrors = test::RenderText(hall, std::vector<std::string>{dir.Path("")});
    CHECK(Pixel(mirrors, 4, 4) == glm::dvec3(0.0));  // black all the way down, and it ends
}

TEST_CASE("surface render: a scene whose only lights are not found is lit as a scene without lights",
          "[renderer][surface]") {
    // An exported scene's own light shaders that this machine lacks: they give no light, and the
    // scene gets affray's default key and ambient lights, as a scene without lights does.
    const std::string unlit = R"(Format 16 12 1
Projection "perspective" "fov" [40]
Translate 0 0 5
WorldBegin
  Surface "plastic"
  Sphere 1 -1 1 360
WorldEnd
)";
    std::string missing = unlit;
    missing.replace(missing.find("  Surface"), 0, "  LightSource \"nosuchlight\" 1 \"intensity\" [3]\n");
    const image::ImageBuffer a = test::RenderText(unlit), b = test::RenderText(missing);
    CHECK(test::RgbRmse(a, b) == 0.0);
    CHECK(Pixel(b, 8, 6).x > 0.1);  // lit
}
