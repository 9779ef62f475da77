// tests/renderer/rib_test.cpp: the RIB reader (renderer/rib.*, rib_lexer.*, rib_args.*).
// A full scene with hand-computed world-space answers, the exact text of the errors and warnings,
// and fuzzing with random bytes, random token soup and mutations of a valid scene.
#include "renderer/rib.h"

#include <catch2/catch.hpp>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "../test_util.h"

using namespace affray::renderer;

namespace {

using affray::test::RequireVec;

// The error ParseRib gives for `text` (empty if it parses).
std::string ErrorOf(const std::string& text) {
    std::string error;
    std::optional<SceneDesc> scene = ParseRib(text, "t.rib", &error, nullptr);
    if (scene) return "";
    return error;
}

const char* const kScene = R"(# a full scene
version 3.03
Format 320 240 1
Projection "perspective" "fov" [60]
Display "test.exr" "openexr" "rgba"
LightSource "pointlight" 9 "from" [0 0 0]   # camera space: at the eye
Translate 0 0 5
WorldBegin
  LightSource "distantlight" 1 "intensity" [0.8] "from" [0 0 0] "to" [0 0 1]
  TransformBegin
    Translate 0 1 0
    LightSource "pointlight" "key" "float intensity" 2 "from" [1 2 3] "lightcolor" [1 0.5 0.25]
  TransformEnd
  LightSource "ambientlight" 3 "intensity" 0.1
  Color [1 0 0]
  Surface "plastic" "Ks" [0.7] "roughness" 0.2
  AttributeBegin
    Translate 1 0 0
    Rotate 90 0 0 1
    Scale 2 2 2
    Color 0 1 0
    Surface "matte" "Kd" 0.25
    Displacement "wave" "uniform float Km" [0.2] "string mapname" "foo.tex" "freq" [4 5]
    Patch "bilinear" "P" [0 0 0  1 0 0  0 1 0  1 1 0]
  AttributeEnd
  Patch "bilinear" "P" [0 0 0  1 0 0  0 1 0  1 1 0]
  ConcatTransform [1 0 0 0  0 1 0 0  0 0 1 0  3 4 5 1]
  Patch "bilinear" "P" [0 0 0  1 0 0  0 1 0  1 1 0]
WorldEnd
)";

}  // namespace

TEST_CASE("A full RIB scene parses into world space", "[renderer]") {
    std::string error;
    std::vector<std::string> warnings;
    std::optional<SceneDesc> scene = ParseRib(kScene, "scene.rib", &error, &warnings);
    INFO(error);
    REQUIRE(scene);
    CHECK(warnings.empty());
    CHECK(scene->path == "scene.rib");

    SECTION("camera and display") {
        const CameraDesc& c = scene->camera;
        CHECK(c.xres == 320);
        CHECK(c.yres == 240);
        CHECK(c.pixelAspect == 1);
        CHECK(c.perspective);
        CHECK(c.fovDegrees == 60);
        // The CTM at WorldBegin is world->camera: the world origin sits 5 units ahead.
        RequireVec(glm::dvec3(c.worldToCamera * glm::dvec4(0, 0, 0, 1)), {0, 0, 5});
        CHECK(scene->displayName == "test.exr");
        CHECK(scene->displayType == "openexr");
        CHECK(scene->displayMode == "rgba");
    }

    SECTION("lights are in world space") {
        REQUIRE(scene->lights.size() == 4);
        // Given before WorldBegin (camera space, at the eye): the eye is at world z = -5.
        const LightDesc& eye = scene->lights[0];
        CHECK(eye.kind == LightDesc::Kind::Point);
        CHECK(eye.handle == "9");
        RequireVec(eye.from, {0, 0, -5});

        const LightDesc& sun = scene->lights[1];
        CHECK(sun.kind == LightDesc::Kind::Distant);
        CHECK(sun.handle == "1");
        CHECK(sun.intensity == Approx(0.8));
        RequireVec(sun.from, {0, 0, 0});
        RequireVec(sun.to, {0, 0, 1});

        const LightDesc& key = scene->lights[2];
        CHECK(key.kind == LightDesc::Kind::Point);
        CHECK(key.handle == "key");
        CHECK(key.intensity == 2);
        RequireVec(key.from, {1, 3, 3});  // moved by the Translate inside TransformBegin/End
        RequireVec(key.color, {1, 0.5, 0.25});
        CHECK(key.line == 12);

        CHECK(scene->lights[3].kind == LightDesc::Kind::Ambient);
        CHECK(scene->lights[3].intensity == Approx(0.1));
    }

    SECTION("transforms apply last-given first") {
        REQUIRE(scene->primitives.size() == 3);
        const PrimitiveDesc& p = scene->primitives[0];
        // Scale 2, then Rotate 90 about z (x -> y), then Translate (1,0,0).
        RequireVec(p.corners[0], {1, 0, 0});
        RequireVec(p.corners[1], {1, 2, 0});
        RequireVec(p.corners[2], {-1, 0, 0});
        RequireVec(p.corners[3], {-1, 2, 0});
        CHECK(p.line == 24);
    }

    SECTION("AttributeBegin/End scopes the transform, color, surface and displacement") {
        const PrimitiveDesc& inside = scene->primitives[0];
        RequireVec(inside.color, {0, 1, 0});
        CHECK(inside.surface.model == SurfaceDesc::Model::Matte);
        CHECK(inside.surface.Ka == 1);
        CHECK(inside.surface.Kd == 0.25);
        REQUIRE(inside.displacement);

        const PrimitiveDesc& after = scene->primitives[1];
        RequireVec(after.corners[3], {1, 1, 0});
        RequireVec(after.color, {1, 0, 0});
        CHECK(after.surface.model == SurfaceDesc::Model::Plastic);
        CHECK(after.surface.Ks == Approx(0.7));
        CHECK(after.surface.roughness == Approx(0.2));
        CHECK(after.surface.Kd == 0.5);
        CHECK_FALSE(after.displacement);
    }

    SECTION("ConcatTransform takes RIB's row-vector matrix order") {
        RequireVec(scene->primitives[2].corners[0], {3, 4, 5});
        RequireVec(scene->primitives[2].corners[3], {4, 5, 5});
    }

    SECTION("displacement parameters keep their raw values and drop inline declarations") {
        const ShaderRef& d = *scene->primitives[0].displacement;
        CHECK(d.name == "wave");
        CHECK(d.line == 23);
        REQUIRE(d.params.size() == 3);
        CHECK(d.params[0].name == "Km");
        CHECK(d.params[0].declaration == "uniform float");
        CHECK(d.params[0].numbers == std::vector<double>{0.2});
        CHECK(d.params[1].name == "mapname");
        CHECK(d.params[1].strings == std::vector<std::string>{"foo.tex"});
        CHECK(d.params[2].name == "freq");
        CHECK(d.params[2].declaration.empty());
        CHECK(d.params[2].numbers == std::vector<double>{4, 5});
    }
}

TEST_CASE("RIB transforms follow the RenderMan conventions", "[renderer]") {
    auto corner = [](const std::string& transforms) {
        std::string error;
        auto scene =
            ParseRib("WorldBegin\n" + transforms +
                         "\nPatch \"bilinear\" \"P\" [1 0 0  1 0 0  0 1 0  1 1 0]\nWorldEnd\n",
                     "t.rib", &error, nullptr);
        INFO(error);
        REQUIRE(scene);
        return scene->primitives.at(0).corners[0];
    };
    RequireVec(corner("Translate 1 2 3"), {2, 2, 3});
    RequireVec(corner("Rotate 90 0 0 1"), {0, 1, 0});
    RequireVec(corner("Rotate 90 0 1 0"), {0, 0, -1});
    RequireVec(corner("Scale 2 3 4"), {2, 0, 0});
    RequireVec(corner("Translate 1 0 0 Scale 2 2 2"), {3, 0, 0});  // scale applies first
    RequireVec(corner("Scale 2 2 2 Translate 1 0 0"), {4, 0, 0});
    RequireVec(corner("Translate 5 5 5 Identity"), {1, 0, 0});
    RequireVec(corner("Translate 5 5 5 Transform [2 0 0 0 0 2 0 0 0 0 2 0 0 0 1 1]"), {2, 0, 1});
    RequireVec(corner("TransformBegin Translate 9 9 9 TransformEnd"), {1, 0, 0});
    RequireVec(corner("Color [0 0 1] Translate [0 1 0]"), {1, 1, 0});  // arrays for positional args
}

TEST_CASE("RIB defaults and variants", "[renderer]") {
    std::string error;
    auto scene = ParseRib("WorldBegin WorldEnd", "t.rib", &error, nullptr);
    REQUIRE(scene);
    CHECK_FALSE(scene->camera.perspective);  // RI default without Projection: orthographic
    CHECK(scene->camera.xres == 640);
    CHECK(scene->lights.empty());
    CHECK(scene->displayName == "out.exr");

    scene = ParseRib("FrameBegin 1\nProjection \"perspective\"\nWorldBegin\nWorldEnd\nFrameEnd\n",
                     "t.rib", &error, nullptr);
    REQUIRE(scene);
    CHECK(scene->camera.perspective);
    CHECK(scene->camera.fovDegrees == 90);

    // Pw (homogeneous) and Pz (heights over the unit square).
    scene = ParseRib(
        "WorldBegin\nPatch \"bilinear\" \"Pw\" [2 0 0 2  1 0 0 1  0 1 0 1  1 1 0 1]\n"
        "Patch \"bilinear\" \"Pz\" [1 2 3 4]\nWorldEnd\n",
        "t.rib", &error, nullptr);
    INFO(error);
    REQUIRE(scene);
    RequireVec(scene->primitives[0].corners[0], {1, 0, 0});
    RequireVec(scene->primitives[1].corners[3], {1, 1, 4});
}

TEST_CASE("Unsupported RIB requests warn once per name, unknown ones are errors", "[renderer]") {
    std::string error;
    std::vector<std::string> warnings;
    auto scene = ParseRib(
        "PixelSamples 4 4\nPixelSamples 2 2\nShadingRate 1\nWorldBegin\n"
        "Attribute \"displacementbound\" \"sphere\" [0.5]\nWorldEnd\n",
        "t.rib", &error, &warnings);
    REQUIRE(scene);
    REQUIRE(warnings.size() == 3);
    CHECK(warnings[0] == "t.rib:1: warning: request 'PixelSamples' is not supported yet; ignored");
    CHECK(warnings[1] == "t.rib:3: warning: request 'ShadingRate' is not supported yet; ignored");
    CHECK(warnings[2] == "t.rib:5: warning: request 'Attribute' is not supported yet; ignored");

    CHECK(ErrorOf("Fooo 1 2\n") == "t.rib:1: error: unknown RIB request 'Fooo'");
    CHECK(ErrorOf("WorldBegin\nSphere 1 -1 1 360\nWorldEnd\n") ==
          "t.rib:2: error: 'Sphere' is not supported yet");
    CHECK(
        ErrorOf("WorldBegin\n\nPointsPolygons [3] [0 1 2] \"P\" [0 0 0 1 0 0 0 1 0]\nWorldEnd\n") ==
        "t.rib:3: error: 'PointsPolygons' is not supported yet");
    CHECK(ErrorOf("WorldBegin\nPatch \"bicubic\" \"P\" [0 0 0]\nWorldEnd\n") ==
          "t.rib:2: error: 'Patch \"bicubic\"' is not supported yet");
    CHECK(ErrorOf("Skew 45 0 1 0 1 0 0\n") == "t.rib:1: error: 'Skew' is not supported yet");

    // Other ignored things: unknown shader parameters, light shaders and surface shaders.
    warnings.clear();
    scene = ParseRib(
        "WorldBegin\nLightSource \"spotlight\" 1\nSurface \"metal\"\n"
        "Surface \"plastic\" \"foo\" 1\nWorldEnd\n",
        "t.rib", &error, &warnings);
    REQUIRE(scene);
    REQUIRE(warnings.size() == 3);
    CHECK(warnings[0] ==
          "t.rib:2: warning: light source 'spotlight' is not supported yet; ignored");
    CHECK(warnings[1] ==
          "t.rib:3: warning: surface shader 'metal' is not supported yet; using \"plastic\"");
    CHECK(warnings[2] == "t.rib:4: warning: 'Surface \"plastic\"' has no parameter 'foo'; ignored");
}

TEST_CASE("Malformed RIB gives exact errors with the line", "[renderer]") {
    const std::string patch = "Patch \"bilinear\" \"P\" [0 0 0 1 0 0 0 1 0 1 1 0]\n";
    // Lexical errors.
    CHECK(ErrorOf("Display \"a.exr\" \"file\" \"rgba\nWorldBegin\nWorldEnd\n") ==
          "t.rib:1: error: unterminated string");
    CHECK(ErrorOf("WorldBegin\nColor [1 0 0\n") ==
          "t.rib:2: error: unterminated array: '[' has no matching ']'");
    CHECK(ErrorOf("WorldBegin\nColor [1 0 0\nWorldEnd\n") ==
          "t.rib:3: error: expected a number, a string or ']' in the array opened on line 2, found "
          "'WorldEnd'");
    CHECK(ErrorOf("Color [1 \"a\" 2]") == "t.rib:1: error: array mixes numbers and strings");
    CHECK(ErrorOf("Color [1 [0] 0]") == "t.rib:1: error: nested arrays are not allowed");
    CHECK(ErrorOf("\n]") == "t.rib:2: error: ']' without matching '['");
    CHECK(ErrorOf("# x\nTranslate nan 0 0\n") ==
          "t.rib:2: error: invalid number 'nan': NaN and infinity are not allowed");
    CHECK(ErrorOf("Translate 0 -inf 0\n") ==
          "t.rib:1: error: invalid number '-inf': NaN and infinity are not allowed");
    CHECK(ErrorOf("Translate 0 0\n1e999\n") == "t.rib:2: error: number '1e999' is out of range");
    CHECK(ErrorOf("Translate 1.2.3 0 0") == "t.rib:1: error: malformed number '1.2.3'");
    CHECK(ErrorOf("Translate 1 2 3\x01") == "t.rib:1: error: unexpected byte 0x01");
    CHECK(ErrorOf("1 2 3\n") == "t.rib:1: error: expected a request name, found number 1");

    // Argument errors.
    CHECK(ErrorOf("Translate 1 2\n") ==
          "t.rib:1: error: 'Translate' expects 3 numbers (dx dy dz), got 2");
    CHECK(ErrorOf("Rotate 90 \"x\" 0 0\n") ==
          "t.rib:1: error: 'Rotate' expects 4 numbers (angle dx dy dz), got string \"x\"");
    CHECK(ErrorOf("Rotate 90 0 0 0\n") == "t.rib:1: error: 'Rotate' axis must not be zero");
    CHECK(ErrorOf("Format 0 480 1\n") ==
          "t.rib:1: error: 'Format' xresolution must be an integer from 1 to 65536, got 0");
    CHECK(ErrorOf("Format 640 -480 1\n") ==
          "t.rib:1: error: 'Format' yresolution must be an integer from 1 to 65536, got -480");
    CHECK(ErrorOf("Format 640 480 0\n") ==
          "t.rib:1: error: 'Format' pixelaspectratio must be positive, got 0");
    CHECK(ErrorOf("Projection \"perspective\" \"fov\" [180]\n") ==
          "t.rib:1: error: 'Projection' fov must be between 0 and 180 degrees, got 180");
    CHECK(ErrorOf("Surface \"plastic\" \"Ks\"\n") ==
          "t.rib:1: error: 'Surface' parameter 'Ks' has no value");
    CHECK(ErrorOf("Surface \"plastic\" \"roughness\" [0]\n") ==
          "t.rib:1: error: 'Surface \"plastic\"' roughness must be positive, got 0");
    CHECK(ErrorOf("WorldBegin\n" + std::string("Patch \"bilinear\" \"P\" [0 0 0 1 0 0 0 1 0]\n") +
                  "WorldEnd\n") ==
          "t.rib:2: error: 'Patch \"bilinear\"' parameter 'P' expects 12 numbers, got 9");
    CHECK(ErrorOf("WorldBegin\nLightSource \"pointlight\"\nWorldEnd\n") ==
          "t.rib:2: error: 'LightSource' expects a light handle (a number or a string) after the "
          "shader name");
    CHECK(ErrorOf("WorldBegin\nLightSource \"pointlight\" 1 \"from\" [0 0]\nWorldEnd\n") ==
          "t.rib:2: error: 'LightSource \"pointlight\"' parameter 'from' expects 3 numbers, got 2");
    CHECK(ErrorOf("WorldBegin 1\nWorldEnd\n") ==
          "t.rib:1: error: 'WorldBegin' takes no arguments, found number 1");

    // Structure errors.
    CHECK(ErrorOf("WorldBegin\nAttributeEnd\nWorldEnd\n") ==
          "t.rib:2: error: 'AttributeEnd' without matching 'AttributeBegin'");
    CHECK(ErrorOf("WorldBegin\nTransformBegin\nAttributeBegin\nTransformEnd\n") ==
          "t.rib:4: error: 'TransformEnd' does not match 'AttributeBegin' on line 3");
    CHECK(ErrorOf("WorldBegin\n" + patch) ==
          "t.rib:1: error: 'WorldBegin' has no matching 'WorldEnd'");
    CHECK(ErrorOf("WorldBegin\nAttributeBegin\nWorldEnd\n") ==
          "t.rib:3: error: 'WorldEnd' does not match 'AttributeBegin' on line 2");
    CHECK(ErrorOf(patch + "WorldBegin\nWorldEnd\n") ==
          "t.rib:1: error: 'Patch' must come between 'WorldBegin' and 'WorldEnd'");
    CHECK(ErrorOf("WorldBegin\nWorldEnd\n" + patch) ==
          "t.rib:3: error: 'Patch' must come between 'WorldBegin' and 'WorldEnd'");
    CHECK(ErrorOf("WorldBegin\nFormat 10 10 1\nWorldEnd\n") ==
          "t.rib:2: error: 'Format' is an option and must come before 'WorldBegin'");
    CHECK(ErrorOf("WorldBegin\nWorldEnd\nWorldBegin\nWorldEnd\n") ==
          "t.rib:3: error: a second 'WorldBegin' (several frames) is not supported yet");
    CHECK(ErrorOf("Scale 0 1 1\nWorldBegin\nWorldEnd\n") ==
          "t.rib:2: error: the camera transform (the transform at 'WorldBegin') is singular");
    CHECK(ErrorOf("Format 64 64 1\n") ==
          "t.rib:1: error: no 'WorldBegin': the file describes no scene");
    CHECK(ErrorOf("") == "t.rib:1: error: no 'WorldBegin': the file describes no scene");
    CHECK(
        ErrorOf("ConcatTransform [1 0 0 1  0 1 0 0  0 0 1 0  0 0 0 1]") ==
        "t.rib:1: error: 'ConcatTransform' matrix must be affine (last column 0 0 0 1); projective "
        "transforms are not supported yet");
}

TEST_CASE("ReadRib reports files it cannot read", "[renderer]") {
    std::string error;
    CHECK_FALSE(ReadRib("/nonexistent/affray/scene.rib", &error, nullptr));
    CHECK(error ==
          "/nonexistent/affray/scene.rib: error: cannot read file: No such file or directory");

    std::filesystem::path file =
        std::filesystem::temp_directory_path() /
        ("affray_rib_test_" + std::to_string(std::random_device{}()) + ".rib");
    {
        FILE* f = std::fopen(file.c_str(), "w");
        REQUIRE(f);
        std::fputs(kScene, f);
        std::fclose(f);
    }
    auto scene = ReadRib(file.string(), &error, nullptr);
    std::filesystem::remove(file);
    REQUIRE(scene);
    CHECK(scene->path == file.string());
    CHECK(scene->primitives.size() == 3);
}

TEST_CASE("The RIB reader survives random input", "[renderer]") {
    std::mt19937 rng(12345);
    auto check = [](const std::string& text) {
        std::string error;
        std::vector<std::string> warnings;
        auto scene = ParseRib(text, "f.rib", &error, &warnings);
        if (!scene) {
            // Every failure is a well-formed message.
            REQUIRE(error.rfind("f.rib:", 0) == 0);
            REQUIRE(error.find(": error: ") != std::string::npos);
        }
    };

    SECTION("random bytes") {
        const std::string alphabet = "WorldBeginEndPatch\"[]#.-+0123456789eE \n\t";
        for (int i = 0; i < 3000; ++i) {
            std::string text(rng() % 120, '\0');
            for (char& c : text)
                c = rng() % 2 ? static_cast<char>(rng() % 256) : alphabet[rng() % alphabet.size()];
            check(text);
        }
    }

    SECTION("random token soup") {
        const std::vector<std::string> vocab = {"WorldBegin",
                                                "WorldEnd",
                                                "AttributeBegin",
                                                "AttributeEnd",
                                                "TransformBegin",
                                                "TransformEnd",
                                                "FrameBegin",
                                                "FrameEnd",
                                                "Patch",
                                                "\"bilinear\"",
                                                "\"P\"",
                                                "\"Pw\"",
                                                "Translate",
                                                "Rotate",
                                                "Scale",
                                                "ConcatTransform",
                                                "Transform",
                                                "Identity",
                                                "Color",
                                                "Surface",
                                                "\"plastic\"",
                                                "\"matte\"",
                                                "Displacement",
                                                "\"wave\"",
                                                "\"float Km\"",
                                                "LightSource",
                                                "\"pointlight\"",
                                                "\"distantlight\"",
                                                "\"from\"",
                                                "\"to\"",
                                                "Format",
                                                "Projection",
                                                "\"perspective\"",
                                                "\"fov\"",
                                                "Display",
                                                "Sphere",
                                                "PixelSamples",
                                                "[",
                                                "]",
                                                "0",
                                                "1",
                                                "-1",
                                                "90",
                                                "0.5",
                                                "1e300",
                                                "\"\"",
                                                "#c\n",
                                                "\n",
                                                "Fooo"};
        for (int i = 0; i < 3000; ++i) {
            std::string text;
            int n = static_cast<int>(rng() % 60);
            for (int k = 0; k < n; ++k) text += vocab[rng() % vocab.size()] + " ";
            check(text);
        }
    }

    SECTION("mutations of a valid scene") {
        const std::string base = kScene;
        for (int i = 0; i < 2000; ++i) {
            std::string text = base;
            int edits = 1 + static_cast<int>(rng() % 4);
            for (int k = 0; k < edits && !text.empty(); ++k) {
                size_t at = rng() % text.size();
                switch (rng() % 3) {
                    case 0:
                        text.erase(at, 1 + rng() % 8);
                        break;
                    case 1:
                        text[at] = static_cast<char>(rng() % 256);
                        break;
                    default:
                        text.insert(at, text.substr(rng() % text.size(), rng() % 16));
                        break;
                }
            }
            check(text);
        }
    }
}
