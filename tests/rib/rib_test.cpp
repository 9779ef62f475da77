// tests/rib/rib_test.cpp: the RIB reader (rib/: rib.*, lexer.*, args.*).
// A full scene with hand-computed world-space answers, the exact text of the errors and warnings,
// and fuzzing with random bytes, random token soup and mutations of a valid scene.
#include "rib/rib.h"

#include <catch2/catch.hpp>
#include <filesystem>
#include <glm/gtc/matrix_transform.hpp>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "tests/rib/rib_test_util.h"
#include "tests/test_util.h"

using namespace affray::renderer;
using namespace affray::rib;

namespace {

using affray::test::RequireVec;

// A diagnostic's first line without its column, "t.rib:3: error: message" (columns, source lines
// and carets have their own test below, and the golden tests show them all).
std::string Short(const affray::diag::Diagnostic& d) {
    static const char* const kKind[] = {"error", "warning", "note"};
    return d.where.file + ":" + std::to_string(d.where.line) + ": " + kKind[static_cast<int>(d.severity)] + ": " +
           d.message;
}

// The warnings of `report`, each as Short gives it.
std::vector<std::string> WarningsOf(const affray::diag::Report& report) {
    std::vector<std::string> out;
    for (const affray::diag::Diagnostic& d : report.all())
        if (d.severity == affray::diag::Severity::Warning) out.push_back(Short(d));
    return out;
}

// The error ParseRib gives for `text` (empty if it parses), as Short gives it.
std::string ErrorOf(const std::string& text) {
    affray::diag::Report report;
    std::optional<SceneDesc> scene = ParseRib(text, "t.rib", &report);
    if (scene) return "";
    REQUIRE(report.errorCount() == 1);
    for (const affray::diag::Diagnostic& d : report.all())
        if (d.severity == affray::diag::Severity::Error) return Short(d);
    return "(no error reported)";
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

// The newer requests: options, quadrics, orientation and coordinate systems.
const char* const kQuadricScene = R"(FrameAspectRatio 1.5
ScreenWindow -1.5 1.5 -1 1
CropWindow 0 1 0.25 0.75
Clipping 0.1 1000
PixelSamples 3 3
PixelFilter "gaussian" 2 2
Exposure 1.5 2.2
Option "searchpath" "shader" ["shaders:&:@"]
Display "q.exr" "file" "rgba,Z,N"
Scale 1 1 -1
CoordinateSystem "eye"
LightSource "spotlight" 1 "from" [0 0 0] "to" [0 0 1] "coneangle" 0.4
Translate 0 0 8
WorldBegin
  CoordinateSystem "world2"
  Attribute "displacementbound" "sphere" [0.3]
  Opacity 1 1 1
  Surface "metal" "roughness" 0.2
  AttributeBegin
    Sides 1
    Orientation "inside"
    Sphere 1 -1 1 360
    Cylinder [1 -1 1 180]
    Cone 2 1 360 "Cs" [1 0 0]
  AttributeEnd
  ReverseOrientation
  Surface "constant"
  Disk 0 1 360
  Torus 1 0.25 0 360 360
  Hyperboloid 1 0 -1 0 1 1 360
  Paraboloid 1 0 1 360
WorldEnd
)";

}  // namespace

TEST_CASE("A full RIB scene parses into world space", "[renderer][rib]") {
    affray::diag::Report error;
    std::optional<SceneDesc> scene = ParseRib(kScene, "scene.rib", &error);
    INFO(error);
    REQUIRE(scene);
    CHECK(error.empty());
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
        RequireVec(p.base.patch().corners[0], {1, 0, 0});
        RequireVec(p.base.patch().corners[1], {1, 2, 0});
        RequireVec(p.base.patch().corners[2], {-1, 0, 0});
        RequireVec(p.base.patch().corners[3], {-1, 2, 0});
        CHECK(p.attr().line == 24);
    }

    SECTION("AttributeBegin/End scopes the transform, color, surface and displacement") {
        const PrimitiveDesc& inside = scene->primitives[0];
        RequireVec(inside.color, {0, 1, 0});
        CHECK(inside.attr().surface.model == SurfaceDesc::Model::Matte);
        CHECK(inside.attr().surface.Ka == 1);
        CHECK(inside.attr().surface.Kd == 0.25);
        REQUIRE(inside.attr().displacement);

        const PrimitiveDesc& after = scene->primitives[1];
        RequireVec(after.base.patch().corners[3], {1, 1, 0});
        RequireVec(after.color, {1, 0, 0});
        CHECK(after.attr().surface.model == SurfaceDesc::Model::Plastic);
        CHECK(after.attr().surface.Ks == Approx(0.7));
        CHECK(after.attr().surface.roughness == Approx(0.2));
        CHECK(after.attr().surface.Kd == 0.5);
        CHECK_FALSE(after.attr().displacement);
    }

    SECTION("ConcatTransform takes RIB's row-vector matrix order") {
        RequireVec(scene->primitives[2].base.patch().corners[0], {3, 4, 5});
        RequireVec(scene->primitives[2].base.patch().corners[3], {4, 5, 5});
    }

    SECTION("displacement parameters keep their raw values and drop inline declarations") {
        const ShaderRef& d = *scene->primitives[0].attr().displacement;
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

TEST_CASE("RIB transforms follow the RenderMan conventions", "[renderer][rib]") {
    auto corner = [](const std::string& transforms) {
        affray::diag::Report error;
        auto scene = ParseRib(
            "WorldBegin\n" + transforms + "\nPatch \"bilinear\" \"P\" [1 0 0  1 0 0  0 1 0  1 1 0]\nWorldEnd\n",
            "t.rib", &error);
        INFO(error);
        REQUIRE(scene);
        return scene->primitives.at(0).base.patch().corners[0];
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

TEST_CASE("RIB defaults and variants", "[renderer][rib]") {
    affray::diag::Report error;
    auto scene = ParseRib("WorldBegin WorldEnd", "t.rib", &error);
    REQUIRE(scene);
    CHECK_FALSE(scene->camera.perspective);  // RI default without Projection: orthographic
    CHECK(scene->camera.xres == 640);
    CHECK(scene->lights.empty());
    CHECK(scene->displayName == "out.exr");

    scene = ParseRib("FrameBegin 1\nProjection \"perspective\"\nWorldBegin\nWorldEnd\nFrameEnd\n", "t.rib", &error);
    REQUIRE(scene);
    CHECK(scene->camera.perspective);
    CHECK(scene->camera.fovDegrees == 90);

    // Pw (homogeneous) and Pz (heights over the unit square).
    scene = ParseRib(
        "WorldBegin\nPatch \"bilinear\" \"Pw\" [2 0 0 2  1 0 0 1  0 1 0 1  1 1 0 1]\n"
        "Patch \"bilinear\" \"Pz\" [1 2 3 4]\nWorldEnd\n",
        "t.rib", &error);
    INFO(error);
    REQUIRE(scene);
    REQUIRE(scene->primitives[0].base.kind() == BaseSurface::Kind::RationalPatch);
    RequireVec(scene->primitives[0].base.rational().At(0, 0), {1, 0, 0});
    RequireVec(scene->primitives[1].base.patch().corners[3], {1, 1, 4});
}

TEST_CASE("Unsupported RIB requests warn once per name, unknown ones are errors", "[renderer][rib]") {
    affray::diag::Report error;
    auto scene = ParseRib(
        "ShadingRate 4\nPixelSamples 2 2\nShadingRate 1\nWorldBegin\n"
        "Attribute \"identifier\" \"name\" \"x\"\nWorldEnd\n",
        "t.rib", &error);
    REQUIRE(scene);
    std::vector<std::string> warnings = WarningsOf(error);
    REQUIRE(warnings.size() == 1);
    CHECK(warnings[0] == "t.rib:5: warning: 'Attribute \"identifier\"' does not apply to affray; ignored");

    CHECK(ErrorOf("Fooo 1 2\n") == "t.rib:1: error: unknown RIB request 'Fooo'");
    CHECK(ErrorOf("WorldBegin\nNuPatch 2 2 [0 0 1 1] 0 1\nWorldEnd\n") ==
          "t.rib:2: error: 'NuPatch' expects nu uorder uknot umin umax nv vorder vknot vmin vmax, got 5 arguments");
    CHECK(ErrorOf("WorldBegin\nPerspective 45\nWorldEnd\n") ==
          "t.rib:2: error: 'Perspective 45' inside the world block makes the object transform projective (affray's "
          "transforms are affine); not supported");
    CHECK(ErrorOf("WorldBegin\nPatch \"bicubic\" \"P\" [0 0 0]\nWorldEnd\n") ==
          "t.rib:2: error: 'Patch \"bicubic\"' parameter 'P' expects 48 numbers, got 3");

    // Other ignored things: unknown parameters of a standard shader. Surface and light shaders
    // are looked for when the scene is prepared (renderer/prepare.cpp), not read.
    error = {};
    scene = ParseRib(
        "WorldBegin\nLightSource \"arealight\" 1\nSurface \"wood\"\n"
        "Surface \"plastic\" \"foo\" 1\nWorldEnd\n",
        "t.rib", &error);
    REQUIRE(scene);
    warnings = WarningsOf(error);
    REQUIRE(warnings.size() == 1);
    CHECK(warnings[0] == "t.rib:4: warning: 'Surface \"plastic\"' has no parameter 'foo'; ignored");
}

TEST_CASE("Malformed RIB gives exact errors with the line", "[renderer][rib]") {
    const std::string patch = "Patch \"bilinear\" \"P\" [0 0 0 1 0 0 0 1 0 1 1 0]\n";
    // Lexical errors.
    CHECK(ErrorOf("Display \"a.exr\" \"file\" \"rgba\nWorldBegin\nWorldEnd\n") ==
          "t.rib:1: error: unterminated string");
    CHECK(ErrorOf("WorldBegin\nColor [1 0 0\n") == "t.rib:2: error: unterminated array: '[' has no matching ']'");
    CHECK(ErrorOf("WorldBegin\nColor [1 0 0\nWorldEnd\n") ==
          "t.rib:3: error: expected a number, a string or ']' in the array opened on line 2, found "
          "'WorldEnd'");
    CHECK(ErrorOf("Color [1 \"a\" 2]") == "t.rib:1: error: array mixes numbers and strings");
    CHECK(ErrorOf("Color [1 [0] 0]") == "t.rib:1: error: nested arrays are not allowed");
    CHECK(ErrorOf("\n]") == "t.rib:2: error: ']' without matching '['");
    CHECK(ErrorOf("# x\nTranslate nan 0 0\n") ==
          "t.rib:2: error: invalid number 'nan': NaN and infinity are not allowed");
    CHECK(ErrorOf("Translate 0 -inf 0\n") == "t.rib:1: error: invalid number '-inf': NaN and infinity are not allowed");
    CHECK(ErrorOf("Translate 0 0\n1e999\n") == "t.rib:2: error: number '1e999' is out of range");
    CHECK(ErrorOf("Translate 1.2.3 0 0") == "t.rib:1: error: malformed number '1.2.3'");
    CHECK(ErrorOf("Translate 1 2 3\x01") == "t.rib:1: error: unexpected byte 0x01");
    CHECK(ErrorOf("1 2 3\n") == "t.rib:1: error: expected a request name, found number 1");

    // Argument errors.
    CHECK(ErrorOf("Translate 1 2\n") == "t.rib:1: error: 'Translate' expects 3 numbers (dx dy dz), got 2");
    CHECK(ErrorOf("Rotate 90 \"x\" 0 0\n") ==
          "t.rib:1: error: 'Rotate' expects 4 numbers (angle dx dy dz), got string \"x\"");
    CHECK(ErrorOf("Rotate 90 0 0 0\n") == "t.rib:1: error: 'Rotate' axis must not be zero");
    CHECK(ErrorOf("Format 0 480 1\n") ==
          "t.rib:1: error: 'Format' xresolution must be an integer from 1 to 65536, got 0");
    CHECK(ErrorOf("Format 640 -480 1\n") ==
          "t.rib:1: error: 'Format' yresolution must be an integer from 1 to 65536, got -480");
    CHECK(ErrorOf("Projection \"perspective\" \"fov\" [180]\n") ==
          "t.rib:1: error: 'Projection' fov must be between 0 and 180 degrees, got 180");
    CHECK(ErrorOf("Surface \"plastic\" \"Ks\"\n") == "t.rib:1: error: 'Surface' parameter 'Ks' has no value");
    CHECK(ErrorOf("Surface \"plastic\" \"roughness\" [0]\n") ==
          "t.rib:1: error: 'Surface \"plastic\"' roughness must be positive, got 0");
    CHECK(ErrorOf("WorldBegin\n" + std::string("Patch \"bilinear\" \"P\" [0 0 0 1 0 0 0 1 0]\n") + "WorldEnd\n") ==
          "t.rib:2: error: 'Patch \"bilinear\"' parameter 'P' expects 12 numbers, got 9");
    CHECK(ErrorOf("WorldBegin\nLightSource \"pointlight\"\nWorldEnd\n") ==
          "t.rib:2: error: 'LightSource' expects a light handle (a number or a string) after the "
          "shader name");
    CHECK(ErrorOf("WorldBegin\nLightSource \"pointlight\" 1 \"from\" [0 0]\nWorldEnd\n") ==
          "t.rib:2: error: 'LightSource \"pointlight\"' parameter 'from' expects 3 numbers, got 2");
    CHECK(ErrorOf("WorldBegin 1\nWorldEnd\n") == "t.rib:1: error: 'WorldBegin' takes no arguments, found number 1");

    // Structure errors.
    CHECK(ErrorOf("WorldBegin\nAttributeEnd\nWorldEnd\n") ==
          "t.rib:2: error: 'AttributeEnd' without matching 'AttributeBegin'");
    CHECK(ErrorOf("WorldBegin\nTransformBegin\nAttributeBegin\nTransformEnd\n") ==
          "t.rib:4: error: 'TransformEnd' does not match 'AttributeBegin' on line 3");
    CHECK(ErrorOf("WorldBegin\n" + patch) == "t.rib:1: error: 'WorldBegin' has no matching 'WorldEnd'");
    CHECK(ErrorOf("WorldBegin\nAttributeBegin\nWorldEnd\n") ==
          "t.rib:3: error: 'WorldEnd' does not match 'AttributeBegin' on line 2");
    CHECK(ErrorOf(patch + "WorldBegin\nWorldEnd\n") ==
          "t.rib:1: error: 'Patch' must come between 'WorldBegin' and 'WorldEnd'");
    CHECK(ErrorOf("WorldBegin\nWorldEnd\n" + patch) ==
          "t.rib:3: error: 'Patch' must come between 'WorldBegin' and 'WorldEnd'");
    CHECK(ErrorOf("WorldBegin\nFormat 10 10 1\nWorldEnd\n") ==
          "t.rib:2: error: 'Format' is an option and must come before 'WorldBegin'");
    CHECK(ErrorOf("WorldBegin\nWorldEnd\nWorldBegin\nWorldEnd\n") ==
          "t.rib:3: error: a second 'WorldBegin' outside frames; give each world its own 'FrameBegin'/'FrameEnd'");
    CHECK(ErrorOf("Scale 0 1 1\nWorldBegin\nWorldEnd\n") ==
          "t.rib:2: error: the camera transform (the transform at 'WorldBegin') is singular");
    CHECK(ErrorOf("Format 64 64 1\n") == "t.rib:1: error: no 'WorldBegin': the file describes no scene");
    CHECK(ErrorOf("") == "t.rib:1: error: no 'WorldBegin': the file describes no scene");
    CHECK(ErrorOf("ConcatTransform [1 0 0 1  0 1 0 0  0 0 1 0  0 0 0 1]") ==
          "t.rib:1: error: 'ConcatTransform' matrix must be affine (last column 0 0 0 1); projective "
          "transforms are not supported yet");
}

TEST_CASE("ReadRib reports files it cannot read", "[renderer][rib]") {
    affray::diag::Report error;
    CHECK_FALSE(ReadRib("/nonexistent/affray/scene.rib", &error));
    CHECK(error.format() == "/nonexistent/affray/scene.rib: error: cannot read file: No such file or directory\n");

    std::filesystem::path file =
        std::filesystem::temp_directory_path() / ("affray_rib_test_" + std::to_string(std::random_device{}()) + ".rib");
    {
        FILE* f = std::fopen(file.c_str(), "w");
        REQUIRE(f);
        std::fputs(kScene, f);
        std::fclose(f);
    }
    auto scene = ReadRib(file.string(), &error);
    std::filesystem::remove(file);
    REQUIRE(scene);
    CHECK(scene->path == file.string());
    CHECK(scene->primitives.size() == 3);
}

TEST_CASE("The RIB reader survives random input", "[renderer][rib]") {
    std::mt19937 rng(12345);
    auto check = [](const std::string& text) {
        affray::diag::Report report;
        auto scene = ParseRib(text, "f.rib", &report);
        if (!scene) {
            // Every failure is one error, at a place in the file, printed as one line (and the
            // source line with a caret).
            REQUIRE(report.errorCount() == 1);
            const affray::diag::Diagnostic& e = report.all().back();
            REQUIRE(e.severity == affray::diag::Severity::Error);
            REQUIRE(e.where.file == "f.rib");
            REQUIRE(e.where.line >= 1);
            REQUIRE(e.where.column >= 1);
            const std::string printed = affray::diag::Format(e);
            REQUIRE(printed.rfind(
                        "f.rib:" + std::to_string(e.where.line) + ":" + std::to_string(e.where.column) + ": error: ",
                        0) == 0);
            REQUIRE(std::count(printed.begin(), printed.end(), '\n') == (e.where.text.empty() ? 1 : 3));
        }
    };

    SECTION("random bytes") {
        const std::string alphabet = "WorldBeginEndPatch\"[]#.-+0123456789eE \n\t";
        for (int i = 0; i < 3000; ++i) {
            std::string text(rng() % 120, '\0');
            for (char& c : text) c = rng() % 2 ? static_cast<char>(rng() % 256) : alphabet[rng() % alphabet.size()];
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
                                                "Fooo",
                                                "Cylinder",
                                                "Cone",
                                                "Disk",
                                                "Torus",
                                                "Hyperboloid",
                                                "Paraboloid",
                                                "Sides",
                                                "ReverseOrientation",
                                                "Orientation",
                                                "\"inside\"",
                                                "\"rh\"",
                                                "CoordinateSystem",
                                                "\"spotlight\"",
                                                "\"coneangle\"",
                                                "ScreenWindow",
                                                "CropWindow",
                                                "Clipping",
                                                "PixelFilter",
                                                "\"box\"",
                                                "Exposure",
                                                "FrameAspectRatio",
                                                "Option",
                                                "\"searchpath\"",
                                                "\"shader\"",
                                                "\"&:@:a\"",
                                                "Attribute",
                                                "\"displacementbound\"",
                                                "Opacity",
                                                "\"metal\"",
                                                "\"constant\""};
        for (int i = 0; i < 3000; ++i) {
            std::string text;
            int n = static_cast<int>(rng() % 60);
            for (int k = 0; k < n; ++k) text += vocab[rng() % vocab.size()] + " ";
            check(text);
        }
    }

    SECTION("mutations of a valid scene") {
        for (int i = 0; i < 3000; ++i) {
            const std::string base = i % 3 ? kScene : kQuadricScene;
            std::string text = base;
            int edits = 1 + static_cast<int>(rng() % 4);
            for (int k = 0; k < edits && !text.empty(); ++k) {
                size_t at = rng() % text.size();
                switch (rng() % 3) {
                    case 0: text.erase(at, 1 + rng() % 8); break;
                    case 1: text[at] = static_cast<char>(rng() % 256); break;
                    default: text.insert(at, text.substr(rng() % text.size(), rng() % 16)); break;
                }
            }
            check(text);
        }
    }
}

namespace {

// The scene `text` parses into; fails the test with the error if it does not parse.
SceneDesc Parsed(const std::string& text, std::vector<std::string>* warnings = nullptr) {
    affray::diag::Report error;
    std::optional<SceneDesc> scene = ParseRib(text, "t.rib", &error);
    INFO(error);
    REQUIRE(scene);
    if (warnings) *warnings = WarningsOf(error);
    return *scene;
}

// The one primitive of a world block holding `body`, after the options `options`.
PrimitiveDesc OnlyPrimitive(const std::string& body, const std::string& options = "") {
    SceneDesc scene = Parsed(options + "WorldBegin\n" + body + "\nWorldEnd\n");
    REQUIRE(scene.primitives.size() == 1);
    return scene.primitives[0];
}

glm::dvec3 Apply(const glm::dmat4& m, const glm::dvec3& p) { return glm::dvec3(m * glm::dvec4(p, 1.0)); }

}  // namespace

TEST_CASE("RIB camera options fill CameraDesc", "[renderer][rib]") {
    SECTION("defaults are RenderMan's") {
        const CameraDesc c = Parsed("WorldBegin WorldEnd").camera;
        CHECK_FALSE(c.frameAspectRatio);
        CHECK_FALSE(c.screenWindow);
        CHECK(c.cropWindow == glm::dvec4(0, 1, 0, 1));
        CHECK(c.nearClip == 1e-10);
        CHECK(c.farClip == 1e30);
        CHECK(c.xsamples == 2);
        CHECK(c.ysamples == 2);
        CHECK(c.filter.kind == FilterDesc::Kind::Gaussian);
        CHECK(c.filter.xwidth == 2);
        CHECK(c.exposureGain == 1);
        CHECK(c.exposureGamma == 1);
    }
    SECTION("every option, bare arguments") {
        const CameraDesc c = Parsed(
                                 "FrameAspectRatio 1.5\nScreenWindow -2 2 -1 1\nCropWindow 0.25 0.75 0 0.5\n"
                                 "Clipping 0.1 100\nPixelSamples 4 3\nPixelFilter \"box\" 1 1.5\n"
                                 "Exposure 2 2.2\nWorldBegin\nWorldEnd\n")
                                 .camera;
        REQUIRE(c.frameAspectRatio);
        CHECK(*c.frameAspectRatio == 1.5);
        REQUIRE(c.screenWindow);
        CHECK(*c.screenWindow == glm::dvec4(-2, 2, -1, 1));
        CHECK(c.cropWindow == glm::dvec4(0.25, 0.75, 0, 0.5));
        CHECK(c.nearClip == 0.1);
        CHECK(c.farClip == 100);
        CHECK(c.xsamples == 4);
        CHECK(c.ysamples == 3);
        CHECK(c.filter.kind == FilterDesc::Kind::Box);
        CHECK(c.filter.xwidth == 1);
        CHECK(c.filter.ywidth == 1.5);
        CHECK(c.exposureGain == 2);
        CHECK(c.exposureGamma == 2.2);
    }
    SECTION("array arguments, and a gaussian after a box") {
        const CameraDesc c = Parsed(
                                 "ScreenWindow [0 1 0 2]\nCropWindow [0 1 0.5 1]\nClipping [1 2]\n"
                                 "PixelFilter \"box\" 1 1\nPixelFilter \"gaussian\" 3 3\n"
                                 "WorldBegin\nWorldEnd\n")
                                 .camera;
        CHECK(*c.screenWindow == glm::dvec4(0, 1, 0, 2));
        CHECK(c.cropWindow == glm::dvec4(0, 1, 0.5, 1));
        CHECK(c.farClip == 2);
        CHECK(c.filter.kind == FilterDesc::Kind::Gaussian);
        CHECK(c.filter.xwidth == 3);
    }
    SECTION("other filters fall back to gaussian with a warning") {
        std::vector<std::string> warnings;
        const CameraDesc c = Parsed("PixelFilter \"catmull-rom\" 4 4\nWorldBegin\nWorldEnd\n", &warnings).camera;
        CHECK(c.filter.kind == FilterDesc::Kind::Gaussian);
        CHECK(c.filter.xwidth == 4);
        REQUIRE(warnings.size() == 1);
        CHECK(warnings[0] == "t.rib:1: warning: pixel filter 'catmull-rom' is not supported; using \"gaussian\"");
    }
}

TEST_CASE("RIB camera options give exact errors", "[renderer][rib]") {
    CHECK(ErrorOf("FrameAspectRatio 0\n") == "t.rib:1: error: 'FrameAspectRatio' must be positive, got 0");
    CHECK(ErrorOf("ScreenWindow -1 -1 0 1\n") ==
          "t.rib:1: error: 'ScreenWindow' must have a nonzero width and height, got -1 -1 0 1");
    CHECK(ErrorOf("ScreenWindow -1 1 0\n") ==
          "t.rib:1: error: 'ScreenWindow' expects 4 numbers (left right bottom top), got 3");
    CHECK(ErrorOf("CropWindow -0.1 1 0 1\n") == "t.rib:1: error: 'CropWindow' needs 0 <= xmin < xmax <= 1, got -0.1 1");
    CHECK(ErrorOf("CropWindow 0 1 0.5 0.5\n") ==
          "t.rib:1: error: 'CropWindow' needs 0 <= ymin < ymax <= 1, got 0.5 0.5");
    CHECK(ErrorOf("CropWindow 0 1 0 1.5\n") == "t.rib:1: error: 'CropWindow' needs 0 <= ymin < ymax <= 1, got 0 1.5");
    CHECK(ErrorOf("Clipping -1 10\n") == "t.rib:1: error: 'Clipping' needs 0 <= near < far, got -1 10");
    CHECK(ErrorOf("Clipping 10 1\n") == "t.rib:1: error: 'Clipping' needs 0 <= near < far, got 10 1");
    CHECK(ErrorOf("Clipping 0 0\n") == "t.rib:1: error: 'Clipping' needs 0 <= near < far, got 0 0");
    {
        // Exporters write a near plane of 0; RI 3.2 asks RI_EPSILON at least, and that is taken.
        affray::diag::Report report;
        std::optional<SceneDesc> scene = ParseRib("Clipping 0 1e30\nWorldBegin\nWorldEnd\n", "t.rib", &report);
        REQUIRE(scene);
        CHECK(scene->camera.nearClip == 1e-10);
        CHECK(scene->camera.farClip == 1e30);
        CHECK(WarningsOf(report) ==
              std::vector<std::string>{"t.rib:1: warning: 'Clipping' near 0 is below RI_EPSILON; taken as 1e-10"});
    }
    CHECK(ErrorOf("PixelSamples 0 2\n") ==
          "t.rib:1: error: 'PixelSamples' xsamples must be an integer from 1 to 64, got 0");
    CHECK(ErrorOf("PixelSamples 2 2.5\n") ==
          "t.rib:1: error: 'PixelSamples' ysamples must be an integer from 1 to 64, got 2.5");
    CHECK(ErrorOf("PixelSamples 65 1\n") ==
          "t.rib:1: error: 'PixelSamples' xsamples must be an integer from 1 to 64, got 65 (limit pixel-samples = 64; "
          "raise it with --limit pixel-samples=N)");
    CHECK(ErrorOf("PixelFilter \"box\" 0 1\n") == "t.rib:1: error: 'PixelFilter' widths must be positive, got 0 1");
    CHECK(ErrorOf("PixelFilter \"box\" 1\n") ==
          "t.rib:1: error: 'PixelFilter' expects a filter name and 2 numbers (xwidth ywidth)");
    CHECK(ErrorOf("PixelFilter 1 1\n") ==
          "t.rib:1: error: 'PixelFilter' expects a filter name as its first argument, found number "
          "1");
    CHECK(ErrorOf("Exposure 1 0\n") == "t.rib:1: error: 'Exposure' gain and gamma must be positive, got 1 0");
    CHECK(ErrorOf("Exposure -1 1\n") == "t.rib:1: error: 'Exposure' gain and gamma must be positive, got -1 1");
    // Options are frozen at WorldBegin.
    for (const char* option :
         {"FrameAspectRatio 1", "ScreenWindow -1 1 -1 1", "CropWindow 0 1 0 1", "Clipping 1 2", "PixelSamples 1 1",
          "PixelFilter \"box\" 1 1", "Exposure 1 1", "Option \"searchpath\" \"shader\" \"a\""}) {
        std::string name = std::string(option).substr(0, std::string(option).find(' '));
        CHECK(ErrorOf(std::string("WorldBegin\n") + option + "\nWorldEnd\n") ==
              "t.rib:2: error: '" + name + "' is an option and must come before 'WorldBegin'");
    }
}

TEST_CASE("RIB Display modes follow the channel grammar", "[renderer][rib]") {
    for (const char* mode : {"rgb", "rgba", "rgbz", "rgbaz", "r", "z", "rgba,Z,N,P,st,cost,err", "a,g", "Ci", "Ci,a"}) {
        INFO(mode);
        // (OpenEXR: "z" alone to a "file" is a depth map pass, tests/rib/frames_test.cpp)
        SceneDesc scene = Parsed(std::string("Display \"o.exr\" \"openexr\" \"") + mode + "\"\nWorldBegin\nWorldEnd\n");
        CHECK(scene.displayMode == mode);
    }
    CHECK(ErrorOf("Display \"o.exr\" \"file\" \"rgba,Cs\"\n") ==
          "t.rib:1: error: 'Display' mode 'rgba,Cs' has an unknown channel group 'Cs' (expected rgb, "
          "rgba, rgbz, rgbaz, r, g, b, a, z, Ci, Oi, Z, N, P, st, cost or err, or a channel declared by "
          "DisplayChannel, separated by commas)");
    CHECK(ErrorOf("Display \"o.exr\" \"file\" \"\"\n") ==
          "t.rib:1: error: 'Display' mode '' has an unknown channel group '' (expected rgb, rgba, "
          "rgbz, rgbaz, r, g, b, a, z, Ci, Oi, Z, N, P, st, cost or err, or a channel declared by DisplayChannel, "
          "separated by commas)");
    CHECK(ErrorOf("Display \"o.exr\" \"file\" \"rgb,,N\"\n") ==
          "t.rib:1: error: 'Display' mode 'rgb,,N' has an unknown channel group '' (expected rgb, "
          "rgba, rgbz, rgbaz, r, g, b, a, z, Ci, Oi, Z, N, P, st, cost or err, or a channel declared by "
          "DisplayChannel, separated by commas)");
    CHECK(ErrorOf("Display \"o.exr\" \"file\" \"RGB\"\n").find("unknown channel group 'RGB'") != std::string::npos);
}

TEST_CASE("RIB Option searchpath shader and texture expand & and @", "[renderer][rib]") {
    using Path = std::vector<std::string>;
    CHECK(Parsed("WorldBegin WorldEnd").shaderSearchPath.empty());  // the renderer's default
    CHECK(Parsed("Option \"searchpath\" \"shader\" [\"shaders:/opt/sl\"]\nWorldBegin WorldEnd").shaderSearchPath ==
          Path{"shaders", "/opt/sl"});
    // '&' is the previous value; '@' the default, the empty list; empty entries are skipped.
    CHECK(Parsed("Option \"searchpath\" \"shader\" \"a:b\"\n"
                 "Option \"searchpath\" \"string shader\" \"c:&:@::d\"\nWorldBegin WorldEnd")
              .shaderSearchPath == Path{"c", "a", "b", "d"});
    CHECK(Parsed("Option \"searchpath\" \"shader\" \"a\"\nOption \"searchpath\" \"shader\" \"@\"\n"
                 "WorldBegin WorldEnd")
              .shaderSearchPath.empty());
    CHECK(Parsed("Option \"searchpath\" \"shader\" \"&:x\"\nOption \"searchpath\" \"shader\" \"&:&\"\n"
                 "WorldBegin WorldEnd")
              .shaderSearchPath == Path{"x", "x"});
    CHECK(ErrorOf("Option \"searchpath\" \"shader\" [1]\n") ==
          "t.rib:1: error: 'Option \"searchpath\"' parameter 'shader' expects 1 string");

    std::vector<std::string> warnings;
    SceneDesc scene = Parsed(
        "Option \"searchpath\" \"texture\" \"t\"\nOption \"searchpath\" \"texture\" \"&:u\"\n"
        "Option \"searchpath\" \"procedural\" \"p\"\n"
        "Option \"limits\" \"bucketsize\" [16 16]\nOption \"statistics\"\nWorldBegin WorldEnd",
        &warnings);
    CHECK(scene.shaderSearchPath.empty());
    CHECK(scene.textureSearchPath == Path{"t", "u"});
    REQUIRE(warnings.size() == 3);
    CHECK(warnings[0] == "t.rib:3: warning: 'Option \"searchpath\" \"procedural\"' does not apply to affray; ignored");
    CHECK(warnings[1] == "t.rib:4: warning: 'Option \"limits\"' does not apply to affray; ignored");
    CHECK(warnings[2] == "t.rib:5: warning: 'Option \"statistics\"' does not apply to affray; ignored");
}

TEST_CASE("RIB motion blocks: transforms move the CTM, other requests take their first sample", "[renderer][rib]") {
    affray::diag::Report report;
    std::optional<SceneDesc> scene = ParseRib(
        "WorldBegin\n"
        "MotionBegin [0 1]\n  Translate 1 0 0\n  Translate 5 0 0\nMotionEnd\n"
        "MotionBegin [0.25 0.5 1]\n  Sphere 1 -1 1 360\n  Sphere 2 -2 2 360\n  Sphere 3 -3 3 360\nMotionEnd\n"
        "MotionBegin [0 1]\n  Surface \"matte\"\n  Surface \"plastic\"\nMotionEnd\n"
        "Scale 2 2 2\n"
        "Sphere 1 -1 1 360\n"
        "TransformBegin\nTranslate 0 1 0\nTransformEnd\n"
        "AttributeBegin\nIdentity\nSphere 1 -1 1 360\nAttributeEnd\n"
        "Sphere 1 -1 1 360\n"
        "WorldEnd\n",
        "t.rib", &report);
    INFO(report);
    REQUIRE(scene);
    std::vector<std::string> warnings = WarningsOf(report);
    REQUIRE(warnings.size() == 2);
    CHECK(warnings[0] ==
          "t.rib:6: warning: motion blur of 'Sphere' is not rendered: its motion block takes its first "
          "sample (time 0.25)");
    CHECK(warnings[1] ==
          "t.rib:11: warning: motion blur of 'Surface' is not rendered: its motion block takes its "
          "first sample (time 0)");
    REQUIRE(scene->primitives.size() == 4);
    // The first sample places the geometry; the path holds the CTM at each time.
    CHECK(scene->primitives[0].base.quadric().quadric.radius == 1);
    RequireVec(Apply(scene->primitives[0].attr().objectToWorld, {0, 0, 0}), {1, 0, 0});
    REQUIRE(scene->primitives[0].attr().motion);
    const MotionPath& path = *scene->primitives[0].attr().motion;
    CHECK(path.times == std::vector<double>{0, 1});
    RequireVec(Apply(path.matrices[1], {0, 0, 0}), {5, 0, 0});
    RequireVec(Apply(path.At(0.25), {0, 0, 0}), {2, 0, 0});
    CHECK(scene->primitives[1].attr().surface.model == SurfaceDesc::Model::Matte);
    // A transform after the block applies at every time: Scale 2 after each Translate.
    REQUIRE(scene->primitives[1].attr().motion);
    RequireVec(Apply(scene->primitives[1].attr().motion->matrices[0], {1, 0, 0}), {3, 0, 0});
    RequireVec(Apply(scene->primitives[1].attr().motion->matrices[1], {1, 0, 0}), {7, 0, 0});
    // Identity stops the motion; TransformEnd and AttributeEnd restore the moving CTM.
    CHECK_FALSE(scene->primitives[2].attr().motion);
    REQUIRE(scene->primitives[3].attr().motion);
    CHECK(scene->primitives[3].attr().motion->matrices == scene->primitives[1].attr().motion->matrices);

    // A block of equal transforms moves nothing; a block under a moving CTM takes the CTM at its
    // own times (the path's times are the block's).
    scene = ParseRib(
        "WorldBegin\nMotionBegin [0 1]\nTranslate 1 0 0\nTranslate 1 0 0\nMotionEnd\nSphere 1 -1 1 "
        "360\nMotionBegin [0 1]\nTranslate 0 0 0\nTranslate 0 2 0\nMotionEnd\n"
        "MotionBegin [0 0.5]\nScale 1 1 1\nScale 1 1 1\nMotionEnd\nSphere 1 -1 1 360\nWorldEnd\n",
        "t.rib", &report);
    REQUIRE(scene);
    REQUIRE(scene->primitives.size() == 2);
    CHECK_FALSE(scene->primitives[0].attr().motion);
    REQUIRE(scene->primitives[1].attr().motion);
    CHECK(scene->primitives[1].attr().motion->times == std::vector<double>{0, 0.5});
    RequireVec(Apply(scene->primitives[1].attr().motion->matrices[1], {0, 0, 0}), {1, 1, 0});

    CHECK(ErrorOf("WorldBegin\nMotionBegin [0 1]\nTranslate 1 0 0\nRotate 1 0 0 1\nMotionEnd\nWorldEnd\n") ==
          "t.rib:4: error: a motion block holds one kind of request, one per time: 'Rotate' after 'Translate'");
    CHECK(ErrorOf("WorldBegin\nMotionBegin [0 1]\nTranslate 1 0 0\nMotionEnd\nWorldEnd\n") ==
          "t.rib:4: error: the motion block started on line 2 has 1 request for 2 times");
    CHECK(ErrorOf("WorldBegin\nMotionBegin [0 1]\nScale 1 1 1\nScale 2 2 2\nScale 3 3 3\nMotionEnd\nWorldEnd\n") ==
          "t.rib:5: error: the motion block started on line 2 has more requests than its 2 times");
    CHECK(ErrorOf("WorldBegin\nMotionBegin [0 1]\nMotionBegin [0 1]\n") ==
          "t.rib:3: error: 'MotionBegin' inside the motion block started on line 2");
    CHECK(ErrorOf("WorldBegin\nMotionBegin [1 0]\n") ==
          "t.rib:2: error: 'MotionBegin' times must be finite and increasing");
    CHECK(ErrorOf("WorldBegin\nMotionBegin 0 1\n") ==
          "t.rib:2: error: 'MotionBegin' expects an array of the times of its samples");
    CHECK(ErrorOf("WorldBegin\nMotionEnd\n") == "t.rib:2: error: 'MotionEnd' without matching 'MotionBegin'");
    CHECK(ErrorOf("WorldBegin\nMotionBegin [0]\nTranslate 1 0 0\n") ==
          "t.rib:2: error: 'MotionBegin' has no matching 'MotionEnd'");
}

TEST_CASE("RIB CoordinateSystem stores object to world", "[renderer][rib]") {
    SceneDesc scene = Parsed(
        "Translate 1 0 0\nCoordinateSystem \"beforeworld\"\nTranslate 0 0 5\n"
        "WorldBegin\n"
        "  AttributeBegin\n    Translate 1 2 3\n    Scale 2 2 2\n    CoordinateSystem \"inworld\"\n"
        "  AttributeEnd\n  CoordinateSystem \"origin\"\nWorldEnd\n");
    REQUIRE(scene.coordinateSystems.size() == 3);
    // Before WorldBegin the CTM maps to camera space; world -> camera is Translate (1, 0, 5), so
    // "beforeworld" (camera Translate (1, 0, 0)) is world Translate (0, 0, -5).
    const glm::dmat4& before = scene.coordinateSystems.at("beforeworld");
    RequireVec(Apply(before, {0, 0, 0}), {0, 0, -5});
    RequireVec(Apply(before, {1, 2, 0}), {1, 2, -5});
    const glm::dmat4& inWorld = scene.coordinateSystems.at("inworld");
    RequireVec(Apply(inWorld, {0, 0, 0}), {1, 2, 3});
    RequireVec(Apply(inWorld, {1, 0, 0}), {3, 2, 3});
    CHECK(scene.coordinateSystems.at("origin") == glm::dmat4(1.0));

    // A later definition replaces an earlier one.
    scene = Parsed("WorldBegin\nCoordinateSystem \"a\"\nTranslate 0 1 0\nCoordinateSystem \"a\"\nWorldEnd\n");
    RequireVec(Apply(scene.coordinateSystems.at("a"), {0, 0, 0}), {0, 1, 0});

    CHECK(ErrorOf("WorldBegin\nCoordinateSystem \"world\"\nWorldEnd\n") ==
          "t.rib:2: error: 'CoordinateSystem' cannot redefine the standard space 'world'");
    CHECK(ErrorOf("WorldBegin\nCoordinateSystem 1\nWorldEnd\n") ==
          "t.rib:2: error: 'CoordinateSystem' expects a coordinate system name as its first "
          "argument, "
          "found number 1");
    CHECK(ErrorOf("WorldBegin\nWorldEnd\nCoordinateSystem \"late\"\n") ==
          "t.rib:3: error: 'CoordinateSystem' after 'WorldEnd'");
}

TEST_CASE("RIB ScopedCoordinateSystem names a space until the end of its block", "[renderer][rib]") {
    SceneDesc scene = Parsed(
        "WorldBegin\n"
        "  CoordinateSystem \"paint\"\n"
        "  AttributeBegin\n    Translate 1 2 3\n    ScopedCoordinateSystem \"paint\"\n"
        "    AttributeBegin\n      Translate 0 0 1\n      ScopedCoordinateSystem \"inner\"\n"
        "      Sphere 1 -1 1 360\n    AttributeEnd\n"
        "    Sphere 1 -1 1 360\n"
        "    Identity\n    CoordSysTransform \"paint\"\n    Sphere 1 -1 1 360\n"
        "  AttributeEnd\n"
        "  Sphere 1 -1 1 360\n"
        "WorldEnd\n");
    REQUIRE(scene.primitives.size() == 4);
    // Only CoordinateSystem names a space of the scene.
    REQUIRE(scene.coordinateSystems.size() == 1);
    CHECK(scene.coordinateSystems.at("paint") == glm::dmat4(1.0));
    // The inner block sees both scoped spaces; the outer one only its own; after it, none.
    REQUIRE(scene.primitives[0].attr().scopedSpaces);
    CHECK(scene.primitives[0].attr().scopedSpaces->size() == 2);
    RequireVec(Apply(scene.primitives[0].attr().scopedSpaces->at("paint"), {0, 0, 0}), {1, 2, 3});
    RequireVec(Apply(scene.primitives[0].attr().scopedSpaces->at("inner"), {0, 0, 0}), {1, 2, 4});
    REQUIRE(scene.primitives[1].attr().scopedSpaces);
    CHECK(scene.primitives[1].attr().scopedSpaces->size() == 1);
    // CoordSysTransform finds the scoped space first.
    RequireVec(Apply(scene.primitives[2].attr().objectToWorld, {0, 0, 0}), {1, 2, 3});
    CHECK_FALSE(scene.primitives[3].attr().scopedSpaces);
    CHECK(ErrorOf("WorldBegin\nScopedCoordinateSystem \"shader\"\nWorldEnd\n") ==
          "t.rib:2: error: 'ScopedCoordinateSystem' cannot redefine the standard space 'shader'");
}

TEST_CASE("RIB CoordSysTransform makes a named space current", "[renderer][rib]") {
    // world -> camera is Translate (0, 0, 5).
    SceneDesc scene = Parsed(
        "Translate 1 0 0\nCoordinateSystem \"eye1\"\nIdentity\nCoordSysTransform \"eye1\"\n"
        "CoordinateSystem \"eye1again\"\nIdentity\nTranslate 0 0 5\n"
        "WorldBegin\n"
        "  Translate 1 2 3\n  CoordinateSystem \"a\"\n  Identity\n"
        "  Rotate 90 0 0 1\n  CoordSysTransform \"a\"\n  Sphere 1 -1 1 360\n"
        "  CoordSysTransform \"world\"\n  Sphere 1 -1 1 360\n"
        "  CoordSysTransform \"camera\"\n  Sphere 1 -1 1 360\n"
        "  Translate 0 0 1\n  CoordSysTransform \"object\"\n  Sphere 1 -1 1 360\n"
        "  CoordSysTransform \"eye1\"\n  Sphere 1 -1 1 360\n"
        "WorldEnd\n");
    REQUIRE(scene.primitives.size() == 5);
    CHECK(scene.primitives[0].attr().objectToWorld == glm::translate(glm::dmat4(1.0), glm::dvec3(1, 2, 3)));
    CHECK(scene.primitives[1].attr().objectToWorld == glm::dmat4(1.0));
    RequireVec(Apply(scene.primitives[2].attr().objectToWorld, {0, 0, 0}), {0, 0, -5});  // the eye
    RequireVec(Apply(scene.primitives[3].attr().objectToWorld, {0, 0, 0}), {0, 0, -4});  // unchanged + 1
    RequireVec(Apply(scene.primitives[4].attr().objectToWorld, {0, 0, 0}), {1, 0, -5});  // camera (1, 0, 0)
    RequireVec(Apply(scene.coordinateSystems.at("eye1again"), {0, 0, 0}), {1, 0, -5});

    CHECK(ErrorOf("WorldBegin\nCoordSysTransform \"nowhere\"\nWorldEnd\n") ==
          "t.rib:2: error: 'CoordSysTransform': no coordinate system 'nowhere' has been defined (by "
          "'CoordinateSystem')");
    CHECK(ErrorOf("CoordSysTransform \"world\"\n") ==
          "t.rib:1: error: 'CoordSysTransform \"world\"' before 'WorldBegin': world space is not known yet");
    CHECK(ErrorOf("CoordSysTransform \"a\" \"b\"\n") == "t.rib:1: error: 'CoordSysTransform' expects one string");
}

TEST_CASE("RIB Attribute warns once, Opacity and visibility are attributes", "[renderer][rib]") {
    std::vector<std::string> warnings;
    SceneDesc scene = Parsed(
        "WorldBegin\nAttribute \"displacementbound\" \"sphere\" [0.5]\n"
        "Attribute \"displacementbound\" \"float sphere\" [2] \"string coordinatesystem\" "
        "\"object\"\n"
        "Attribute \"visibility\" \"int camera\" [1]\nAttribute \"visibility\" \"int camera\" [0]\n"
        "Opacity 1 1 1\nOpacity [0.5 0.5 0.5]\nOpacity 0 1 1\nWorldEnd\n",
        &warnings);
    REQUIRE(warnings.size() == 1);
    CHECK(warnings[0] ==
          "t.rib:2: warning: 'Attribute \"displacementbound\"' is not needed: affray bounds "
          "displacement exactly; ignored");
    CHECK(ErrorOf("WorldBegin\nOpacity 1 1\nWorldEnd\n") ==
          "t.rib:2: error: 'Opacity' expects 3 numbers (r g b), got 2");
    CHECK(ErrorOf("WorldBegin\nAttribute \"displacementbound\" \"sphere\"\nWorldEnd\n") ==
          "t.rib:2: error: 'Attribute' parameter 'sphere' has no value");
}

TEST_CASE("RIB constant and metal surfaces", "[renderer][rib]") {
    const std::string sphere = "\nSphere 1 -1 1 360";
    SurfaceDesc s = OnlyPrimitive("Surface \"constant\"" + sphere).attr().surface;
    CHECK(s.model == SurfaceDesc::Model::Constant);

    s = OnlyPrimitive("Surface \"metal\"" + sphere).attr().surface;
    CHECK(s.model == SurfaceDesc::Model::Metal);
    CHECK(s.Ka == 1);
    CHECK(s.Ks == 1);
    CHECK(s.Kd == 0);
    CHECK(s.roughness == 0.1);

    s = OnlyPrimitive("Surface \"metal\" \"Ka\" 0.5 \"Ks\" [0.25] \"roughness\" 0.3" + sphere).attr().surface;
    CHECK(s.Ka == 0.5);
    CHECK(s.Ks == 0.25);
    CHECK(s.roughness == 0.3);

    std::vector<std::string> warnings;
    Parsed(
        "WorldBegin\nSurface \"constant\" \"Ka\" 1\nSurface \"metal\" \"Kd\" 1\n"
        "Surface \"metal\" \"specularcolor\" [1 1 1]\nWorldEnd\n",
        &warnings);
    REQUIRE(warnings.size() == 3);
    CHECK(warnings[0] == "t.rib:2: warning: 'Surface \"constant\"' has no parameter 'Ka'; ignored");
    CHECK(warnings[1] == "t.rib:3: warning: 'Surface \"metal\"' has no parameter 'Kd'; ignored");
    CHECK(warnings[2] == "t.rib:4: warning: 'Surface \"metal\"' has no parameter 'specularcolor'; ignored");
    CHECK(ErrorOf("Surface \"metal\" \"roughness\" [0]\n") ==
          "t.rib:1: error: 'Surface \"metal\"' roughness must be positive, got 0");
}

TEST_CASE("RIB spotlight", "[renderer][rib]") {
    std::vector<std::string> warnings;
    SceneDesc scene = Parsed(
        "Translate 0 0 5\nWorldBegin\nLightSource \"spotlight\" 1\n"
        "Translate 1 0 0\nLightSource \"spotlight\" \"s\" \"intensity\" 3 \"lightcolor\" [1 0 0] "
        "\"from\" [0 1 0] \"to\" [0 0 0] \"coneangle\" 0.25 \"conedeltaangle\" 0.05 "
        "\"beamdistribution\" 4\nWorldEnd\n",
        &warnings);
    CHECK(warnings.empty());
    REQUIRE(scene.lights.size() == 2);
    const LightDesc& def = scene.lights[0];
    CHECK(def.kind == LightDesc::Kind::Spot);
    CHECK(def.intensity == 1);
    RequireVec(def.from, {0, 0, 0});
    RequireVec(def.to, {0, 0, 1});
    CHECK(def.coneAngle == Approx(glm::radians(30.0)));
    CHECK(def.coneDeltaAngle == Approx(glm::radians(5.0)));
    CHECK(def.beamDistribution == 2);
    const LightDesc& s = scene.lights[1];
    CHECK(s.handle == "s");
    CHECK(s.intensity == 3);
    RequireVec(s.color, {1, 0, 0});
    RequireVec(s.from, {1, 1, 0});
    RequireVec(s.to, {1, 0, 0});
    CHECK(s.coneAngle == 0.25);
    CHECK(s.coneDeltaAngle == 0.05);
    CHECK(s.beamDistribution == 4);

    // Before WorldBegin: camera space, mapped at WorldBegin (the eye is at world z = -5).
    scene = Parsed("LightSource \"spotlight\" 1\nTranslate 0 0 5\nWorldBegin\nWorldEnd\n");
    RequireVec(scene.lights.at(0).from, {0, 0, -5});
    RequireVec(scene.lights.at(0).to, {0, 0, -4});

    const std::string ctx = "t.rib:2: error: 'LightSource \"spotlight\"' ";
    auto light = [](const std::string& params) {
        return ErrorOf("WorldBegin\nLightSource \"spotlight\" 1 " + params + "\nWorldEnd\n");
    };
    CHECK(light("\"from\" [1 1 1] \"to\" [1 1 1]") == ctx + "'from' and 'to' must differ");
    CHECK(light("\"coneangle\" 0") == ctx + "coneangle must be in (0, pi] radians, got 0");
    CHECK(light("\"coneangle\" 4") == ctx + "coneangle must be in (0, pi] radians, got 4");
    CHECK(light("\"conedeltaangle\" -0.1") == ctx + "conedeltaangle must be from 0 to coneangle, got -0.1");
    CHECK(light("\"coneangle\" 0.1 \"conedeltaangle\" 0.2") ==
          ctx + "conedeltaangle must be from 0 to coneangle, got 0.2");
    CHECK(light("\"beamdistribution\" -1") == ctx + "beamdistribution must not be negative, got -1");
    CHECK(light("\"coneangle\" [1 2]") == ctx + "parameter 'coneangle' expects 1 number, got 2");
}

TEST_CASE("RIB quadrics take their arguments bare or in arrays", "[renderer][rib]") {
    auto both = [](const std::string& bare, const std::string& array) {
        Quadric a = OnlyPrimitive(bare).base.quadric().quadric, b = OnlyPrimitive(array).base.quadric().quadric;
        CHECK(ToString(a) == ToString(b));
        CHECK(a.kind == b.kind);
        return a;
    };
    Quadric q = both("Sphere 2 -1 1.5 270", "Sphere [2 -1 1.5 270]");
    CHECK(q.kind == Quadric::Kind::Sphere);
    CHECK(q.radius == 2);
    CHECK(q.zmin == -1);
    CHECK(q.zmax == 1.5);
    CHECK(q.thetamax == 270);

    q = both("Cylinder 0.5 -2 3 180", "Cylinder [0.5 -2 3 180]");
    CHECK(q.kind == Quadric::Kind::Cylinder);
    CHECK(q.radius == 0.5);
    CHECK(q.zmin == -2);
    CHECK(q.zmax == 3);
    CHECK(q.thetamax == 180);

    q = both("Cone 2 0.5 90", "Cone [2 0.5 90]");
    CHECK(q.kind == Quadric::Kind::Cone);
    CHECK(q.height == 2);
    CHECK(q.radius == 0.5);
    CHECK(q.thetamax == 90);

    q = both("Disk -1 3 360", "Disk [-1 3 360]");
    CHECK(q.kind == Quadric::Kind::Disk);
    CHECK(q.height == -1);
    CHECK(q.radius == 3);
    CHECK(q.thetamax == 360);

    q = both("Torus 2 0.5 -90 180 300", "Torus [2 0.5 -90 180 300]");
    CHECK(q.kind == Quadric::Kind::Torus);
    CHECK(q.majorRadius == 2);
    CHECK(q.minorRadius == 0.5);
    CHECK(q.phimin == -90);
    CHECK(q.phimax == 180);
    CHECK(q.thetamax == 300);

    // Grouped any way: a point per array (as exporters write a hyperboloid), or one-element arrays.
    CHECK(ToString(OnlyPrimitive("Hyperboloid [1 0 -1] [0 1 1] 360").base.quadric().quadric) ==
          ToString(OnlyPrimitive("Hyperboloid 1 0 -1 0 1 1 360").base.quadric().quadric));
    CHECK(ToString(OnlyPrimitive("Sphere [2] -1 [1.5] [270]").base.quadric().quadric) ==
          ToString(OnlyPrimitive("Sphere 2 -1 1.5 270").base.quadric().quadric));
    q = both("Hyperboloid 1 0 -1 0 1 1 360", "Hyperboloid [1 0 -1 0 1 1 360]");
    CHECK(q.kind == Quadric::Kind::Hyperboloid);
    CHECK(q.point1[0] == 1);
    CHECK(q.point1[1] == 0);
    CHECK(q.point1[2] == -1);
    CHECK(q.point2[0] == 0);
    CHECK(q.point2[1] == 1);
    CHECK(q.point2[2] == 1);
    CHECK(q.thetamax == 360);

    q = both("Paraboloid 1.5 0.5 2 120", "Paraboloid [1.5 0.5 2 120]");
    CHECK(q.kind == Quadric::Kind::Paraboloid);
    CHECK(q.radius == 1.5);
    CHECK(q.zmin == 0.5);
    CHECK(q.zmax == 2);
    CHECK(q.thetamax == 120);
}

TEST_CASE("RIB quadrics take the graphics state", "[renderer][rib]") {
    std::vector<std::string> warnings;
    SceneDesc scene = Parsed(
        "WorldBegin\nColor 1 0 0\nSurface \"matte\"\nDisplacement \"bumps\" \"Km\" 0.1\n"
        "Translate 0 0 3\nSphere 1 -1 1 360 \"Cs\" [0 1 0] \"st\" [0 0 1 1]\n"
        "Disk [0 1 360] \"Cs\" [0 0 1]\nWorldEnd\n",
        &warnings);
    REQUIRE(scene.primitives.size() == 2);
    const PrimitiveDesc& p = scene.primitives[0];
    CHECK(p.base.kind() == BaseSurface::Kind::Quadric);
    CHECK(p.attr().line == 6);
    RequireVec(p.color, {0, 1, 0});  // one colour for a varying "Cs": the sphere's
    CHECK(p.attr().surface.model == SurfaceDesc::Model::Matte);
    REQUIRE(p.attr().displacement);
    CHECK(p.attr().displacement->name == "bumps");
    RequireVec(Apply(p.attr().objectToWorld, {0, 0, 0}), {0, 0, 3});
    CHECK(p.attr().twoSided);
    CHECK_FALSE(p.base.flipNormal);
    CHECK(scene.primitives[1].base.quadric().quadric.kind == Quadric::Kind::Disk);
    RequireVec(scene.primitives[1].color, {0, 0, 1});
    REQUIRE(warnings.size() == 3);
    CHECK(warnings[0] ==
          "t.rib:6: warning: 'Sphere' parameter 'Cs' (varying color) expects 4 colors, got one: "
          "taken as the whole primitive's");
    CHECK(warnings[1] == "t.rib:6: warning: 'Sphere' parameter 'st' is not supported yet; ignored");
    CHECK(warnings[2] ==
          "t.rib:7: warning: 'Disk' parameter 'Cs' (varying color) expects 4 colors, got one: taken "
          "as the whole primitive's");
}

TEST_CASE("RIB quadric arguments give exact errors", "[renderer][rib]") {
    auto error = [](const std::string& request) { return ErrorOf("WorldBegin\n" + request + "\nWorldEnd\n"); };
    CHECK(error("Sphere 1 -1 1") == "t.rib:2: error: 'Sphere' expects 4 numbers (radius zmin zmax thetamax), got 3");
    CHECK(error("Sphere [1 -1 1]") == "t.rib:2: error: 'Sphere' expects 4 numbers (radius zmin zmax thetamax), got 3");
    // Numbers may be grouped in arrays any way (flattened), but not past the count.
    CHECK(error("Sphere 1 -1 [1 360 2]") ==
          "t.rib:2: error: 'Sphere' expects 4 numbers (radius zmin zmax thetamax), got array of 3 "
          "numbers");
    CHECK(error("Translate [1 2] 3 4") == "t.rib:2: error: 'Translate' expects 3 numbers (dx dy dz), got number 4");
    CHECK(error("Sphere 1 -1 1 360 5") == "t.rib:2: error: 'Sphere' expects a parameter name string, found number 5");
    CHECK(error("Cone 1 1") == "t.rib:2: error: 'Cone' expects 3 numbers (height radius thetamax), got 2");
    CHECK(error("Torus 1 1 1 1") ==
          "t.rib:2: error: 'Torus' expects 5 numbers (rmajor rminor phimin phimax thetamax), got 4");
    CHECK(error("Hyperboloid [1 0 0 1 0]") ==
          "t.rib:2: error: 'Hyperboloid' expects 7 numbers (x1 y1 z1 x2 y2 z2 thetamax), got 5");
    CHECK(error("Sphere -1 -1 1 360") == "t.rib:2: error: 'Sphere' the radius must be positive");
    CHECK(error("Sphere 1 0.5 -0.5 360") == "t.rib:2: error: 'Sphere' zmin..zmax does not cut the sphere");
    CHECK(error("Cone 1 -1 360") == "t.rib:2: error: 'Cone' the radius must be positive");
    CHECK(error("Torus 1 -0.1 0 360 360") == "t.rib:2: error: 'Torus' the minor radius must be positive");
    CHECK(error("Paraboloid -1 0 1 360") == "t.rib:2: error: 'Paraboloid' rmax must be positive");
    CHECK(error("Paraboloid 1 -1 1 360") == "t.rib:2: error: 'Paraboloid' it needs 0 <= zmin < zmax");
    // An empty surface (as an animated export writes at a sweep of 0) is skipped with a warning.
    const std::pair<const char*, const char*> empty[] = {
        {"Sphere 0 -1 1 360", "'Sphere' the radius is 0"},
        {"Sphere 1 2 3 360", "'Sphere' zmin..zmax does not cut the sphere"},
        {"Sphere 1 0.5 0.5 360", "'Sphere' zmin..zmax does not cut the sphere"},
        {"Sphere 1 -1 1 0", "'Sphere' thetamax is 0"},
        {"Cylinder 1 1 1 360", "'Cylinder' zmin equals zmax"},
        {"Disk 0 0 360", "'Disk' the radius is 0"},
        {"Torus 1 0 0 360 360", "'Torus' the minor radius is 0"},
        {"Torus 1 0.5 90 90 360", "'Torus' phimin equals phimax"},
        {"Hyperboloid 1 0 0 1 0 0 360", "'Hyperboloid' point1 equals point2"},
        {"Paraboloid 0 0 1 360", "'Paraboloid' rmax is 0"},
        {"Paraboloid 1 1 1 360", "'Paraboloid' zmin equals zmax"},
    };
    for (const auto& [request, why] : empty) {
        affray::diag::Report report;
        INFO(request);
        CHECK(affray::test::ParseWorld(request, &report).primitives.empty());
        REQUIRE(report.all().size() == 1);
        CHECK(affray::test::ShortDiagnostic(report.all()[0]) ==
              "t.rib:2: warning: " + std::string(why) + ": the surface is empty; skipped");
    }
    CHECK(affray::test::ParseWorld("Hyperboloid 1 0 0 1 0 1 360").primitives.size() == 1);
    CHECK(ErrorOf("Sphere 1 -1 1 360\nWorldBegin\nWorldEnd\n") ==
          "t.rib:1: error: 'Sphere' must come between 'WorldBegin' and 'WorldEnd'");
}

TEST_CASE("RIB Sides and orientation set twoSided and flipNormal", "[renderer][rib]") {
    const std::string sphere = "\nSphere 1 -1 1 360";
    auto flip = [&](const std::string& body, const std::string& options = "") {
        return OnlyPrimitive(body + sphere, options).base.flipNormal;
    };
    // flipNormal = (det objectToWorld < 0) XOR insideOut (scene.h).
    CHECK_FALSE(flip(""));              // normals point out
    CHECK(flip("ReverseOrientation"));  // inside out
    CHECK_FALSE(flip("ReverseOrientation ReverseOrientation"));
    CHECK_FALSE(flip("", "Scale 1 1 -1\n"));  // mirrored camera: still out
    CHECK(flip("ReverseOrientation", "Scale 1 1 -1\n"));
    CHECK(flip("Orientation \"inside\""));
    CHECK_FALSE(flip("Orientation \"outside\""));
    CHECK(flip("Orientation \"rh\""));
    CHECK_FALSE(flip("Orientation \"rh\" Orientation \"lh\""));
    CHECK(flip("Scale -1 1 1"));                          // a mirror turns the world dPdu x dPdv in; flipped back out
    CHECK(flip("Scale -1 1 1 Orientation \"outside\""));  // outside follows the space
    CHECK_FALSE(flip("Scale -1 1 1 Orientation \"inside\"", "Scale 1 1 -1\n"));
    CHECK(flip("Scale -1 1 1", "Scale 1 1 -1\n"));        // the camera's mirror does not matter
    CHECK(flip("Orientation \"outside\" Scale -1 1 1"));  // orientation set before the mirror
    // Orientation before WorldBegin, in a mirrored camera space: "outside" is still outside, and
    // "lh" there (a right-handed space) is inside out.
    CHECK_FALSE(flip("", "Scale 1 1 -1\nOrientation \"outside\"\n"));
    CHECK(flip("", "Scale 1 1 -1\nOrientation \"lh\"\n"));
    // Scoped by AttributeBegin/End, not by TransformBegin/End.
    CHECK_FALSE(flip("AttributeBegin ReverseOrientation AttributeEnd"));
    CHECK(flip("TransformBegin ReverseOrientation TransformEnd"));

    CHECK(OnlyPrimitive("Sides 2" + sphere).attr().twoSided);
    CHECK_FALSE(OnlyPrimitive("Sides 1" + sphere).attr().twoSided);
    CHECK_FALSE(OnlyPrimitive("Sides [1]" + sphere).attr().twoSided);
    CHECK(OnlyPrimitive("AttributeBegin Sides 1 AttributeEnd" + sphere).attr().twoSided);
    CHECK_FALSE(OnlyPrimitive(sphere, "Sides 1\n").attr().twoSided);  // attributes carry into the world

    // Patches get them too.
    PrimitiveDesc patch =
        OnlyPrimitive("Sides 1 ReverseOrientation\nPatch \"bilinear\" \"P\" [0 0 0 1 0 0 0 1 0 1 1 0]");
    CHECK_FALSE(patch.attr().twoSided);
    CHECK(patch.base.flipNormal);

    CHECK(ErrorOf("WorldBegin\nSides 3\nWorldEnd\n") == "t.rib:2: error: 'Sides' must be 1 or 2, got 3");
    CHECK(ErrorOf("WorldBegin\nOrientation \"up\"\nWorldEnd\n") ==
          "t.rib:2: error: unknown orientation 'up' (expected \"outside\", \"inside\", \"lh\" or "
          "\"rh\")");
    CHECK(ErrorOf("WorldBegin\nReverseOrientation 1\nWorldEnd\n") ==
          "t.rib:2: error: 'ReverseOrientation' takes no arguments, found number 1");
}

TEST_CASE("A RIB scene with quadrics, options and a mirrored camera", "[renderer][rib]") {
    std::vector<std::string> warnings;
    SceneDesc scene = Parsed(kQuadricScene, &warnings);
    REQUIRE(warnings.size() == 2);
    CHECK(warnings[0] ==
          "t.rib:16: warning: 'Attribute \"displacementbound\"' is not needed: affray bounds "
          "displacement exactly; ignored");
    CHECK(warnings[1] ==
          "t.rib:24: warning: 'Cone' parameter 'Cs' (varying color) expects 4 colors, got one: taken "
          "as the whole primitive's");
    CHECK(scene.shaderSearchPath == std::vector<std::string>{"shaders"});
    CHECK(scene.displayMode == "rgba,Z,N");
    CHECK(scene.camera.xsamples == 3);
    // world -> camera = Scale(1, 1, -1) * Translate(0, 0, 8); "eye" -> camera is the Scale, so
    // eye -> world is Translate(0, 0, -8): the right-handed world's axes at the eye.
    RequireVec(Apply(scene.coordinateSystems.at("eye"), {0, 0, 0}), {0, 0, -8});
    RequireVec(Apply(scene.coordinateSystems.at("eye"), {0, 0, 1}), {0, 0, -7});
    CHECK(scene.coordinateSystems.at("world2") == glm::dmat4(1.0));
    REQUIRE(scene.lights.size() == 1);
    RequireVec(scene.lights[0].from, {0, 0, -8});
    RequireVec(scene.lights[0].to, {0, 0, -7});  // given in "eye" space, toward the world origin

    REQUIRE(scene.primitives.size() == 7);
    const Quadric::Kind kinds[] = {Quadric::Kind::Sphere,    Quadric::Kind::Cylinder, Quadric::Kind::Cone,
                                   Quadric::Kind::Disk,      Quadric::Kind::Torus,    Quadric::Kind::Hyperboloid,
                                   Quadric::Kind::Paraboloid};
    for (size_t i = 0; i < 7; ++i) {
        const PrimitiveDesc& p = scene.primitives[i];
        INFO(ToString(p));
        CHECK(p.base.quadric().quadric.kind == kinds[i]);
        CHECK(p.attr().line == static_cast<int>(i < 3 ? 22 + i : 25 + i));
        // Inside the attribute block: one-sided and "inside"; after it ReverseOrientation: all
        // inside out, whatever the mirrored camera.
        CHECK(p.attr().twoSided == (i >= 3));
        CHECK(p.base.flipNormal);
        CHECK(p.attr().surface.model == (i < 3 ? SurfaceDesc::Model::Metal : SurfaceDesc::Model::Constant));
    }
}

// Found by fuzz_rib (fuzz/regressions/fuzz_rib/number_token_at_end.rib): a number token that
// starts like "-Inf" or "nan" and ends the text made libstdc++'s from_chars (long double) take
// strlen of the token, reading past the end of a text that is not NUL-terminated.
TEST_CASE("RIB numbers at the very end of a text without a NUL are read within it", "[renderer][rib]") {
    for (const std::string text :
         {"Sphere 1 -1 1 -Illuminate", "Translate 0 0 -Infx", "Translate 0 0 +nanny", "Translate 0 0 1.5"}) {
        INFO(text);
        // Exactly the text's bytes: no NUL after them for a reader to stop at.
        const std::unique_ptr<char[]> bytes(new char[text.size()]);
        std::copy(text.begin(), text.end(), bytes.get());
        affray::diag::Report report;
        ParseRib(std::string_view(bytes.get(), text.size()), "t.rib", &report);
        CHECK(report.errorCount() == 1);
    }
    affray::diag::Report report;
    CHECK_FALSE(ParseRib("Translate 0 0 -Infx", "t.rib", &report));
    CHECK(Short(report.all().at(0)) == "t.rib:1: error: malformed number '-Infx'");
}

TEST_CASE("RIB Imager: background sets the colour under the image, other imagers are warned about", "[renderer][rib]") {
    const auto camera = [](const std::string& options) {
        affray::diag::Report report;
        std::optional<SceneDesc> scene = ParseRib(options + "WorldBegin\nWorldEnd\n", "t.rib", &report);
        REQUIRE(scene);
        return std::make_pair(scene->camera, WarningsOf(report));
    };
    CHECK(camera("Imager \"background\" \"background\" [0.2 0.3 0.4]\n").first.background == glm::dvec3(0.2, 0.3, 0.4));
    CHECK(camera("Imager \"background\" \"color bgcolor\" [1 0 0]\n").first.background == glm::dvec3(1, 0, 0));
    CHECK(camera("Imager \"background\"\n").first.background == glm::dvec3(1.0));  // its default, white
    CHECK_FALSE(camera("Imager \"background\"\nImager \"null\"\n").first.background);
    const auto [sepia, warnings] = camera("Imager \"sepia\" \"amount\" [1]\n");
    CHECK_FALSE(sepia.background);
    CHECK(warnings == std::vector<std::string>{"t.rib:1: warning: imager shader 'sepia' is not supported (only "
                                               "\"background\"); ignored"});
    CHECK(ErrorOf("Imager \"background\" \"background\" [1 0]\nWorldBegin\nWorldEnd\n") ==
          "t.rib:1: error: 'Imager \"background\"' parameter 'background' expects 3 numbers, got 2");
    CHECK(ErrorOf("WorldBegin\nImager \"background\"\nWorldEnd\n").find("'Imager' is an option") != std::string::npos);
}
