// tests/rib/settings_test.cpp: the requests exported scenes set in their header and attributes
// (rib/settings.cpp; the declarations' rules are rib/args.cpp's): Hider and its jitter (rendered:
// samples at pixel centres), Declare and inline declarations on every kind of parameter list,
// Option and Attribute names that tune other renderers, ShadingRate, ShadingInterpolation and
// ArchiveRecord; and a header as exporters write it, which must parse with one warning per
// ignored name.
#include <catch2/catch.hpp>
#include <string>
#include <vector>

#include "renderer/film.h"
#include "renderer/renderer.h"
#include "rib/rib.h"
#include "tests/test_util.h"

using namespace affray;
using namespace affray::renderer;
using affray::rib::ParseRib;

namespace {

std::string Short(const diag::Diagnostic& d) {
    static const char* const kKind[] = {"error", "warning", "note"};
    return d.where.file + ":" + std::to_string(d.where.line) + ": " + kKind[static_cast<int>(d.severity)] + ": " +
           d.message;
}

// The scene `text` gives, with its diagnostics (each as Short gives it) in *messages.
std::optional<SceneDesc> Parse(const std::string& text, std::vector<std::string>* messages) {
    diag::Report report;
    std::optional<SceneDesc> scene = ParseRib(text, "t.rib", &report);
    messages->clear();
    for (const diag::Diagnostic& d : report.all()) messages->push_back(Short(d));
    return scene;
}

using Messages = std::vector<std::string>;

Messages ErrorsOf(const std::string& text) {
    Messages messages;
    CHECK_FALSE(Parse(text, &messages));
    return messages;
}

}  // namespace

TEST_CASE("Hider sets the jitter and accepts the depth filter", "[renderer][rib]") {
    Messages messages;
    std::optional<SceneDesc> scene = Parse("WorldBegin WorldEnd", &messages);
    REQUIRE(scene);
    CHECK(scene->camera.jitter);  // RI default
    scene = Parse("Hider \"hidden\" \"jitter\" [0] \"depthfilter\" \"min\"\nWorldBegin WorldEnd", &messages);
    REQUIRE(scene);
    CHECK_FALSE(scene->camera.jitter);
    CHECK(messages.empty());
    CHECK(ToString(scene->camera).find(" pixelsamples=2 2 jitter=0 ") != std::string::npos);
    scene = Parse(
        "Hider \"hidden\" \"int jitter\" 1 \"string depthfilter\" \"midpoint\" \"float sigma\" 0\n"
        "Hider \"raytrace\" \"jitter\" 0 \"int minsamples\" [4]\nHider \"stochastic\"\n"
        "Hider \"raytrace\"\nWorldBegin WorldEnd",
        &messages);
    REQUIRE(scene);
    CHECK_FALSE(scene->camera.jitter);
    CHECK(messages ==
          Messages{// NOLINTNEXTLINE(bugprone-suspicious-missing-comma): one message in two literals
                   "t.rib:1: warning: 'Hider \"hidden\"' depthfilter 'midpoint' is not supported; depth is each "
                   "sample's nearest hit (\"min\")",
                   "t.rib:1: warning: 'Hider \"hidden\"' parameter 'sigma' is not supported; ignored",
                   "t.rib:2: warning: hider 'raytrace' is not supported; rendering with affray's ray tracer (as "
                   "\"hidden\")",
                   "t.rib:2: warning: 'Hider \"raytrace\"' parameter 'minsamples' is not supported; ignored",
                   "t.rib:3: warning: hider 'stochastic' is not supported; rendering with affray's ray tracer (as "
                   "\"hidden\")"});

    CHECK(ErrorsOf("Hider \"hidden\" \"jitter\" [0.5]\n") ==
          Messages{"t.rib:1: error: 'Hider \"hidden\"' parameter 'jitter' must be 0 or 1, got 0.5"});
    CHECK(ErrorsOf("Hider \"hidden\" \"jitter\" [0 1]\n") ==
          Messages{"t.rib:1: error: 'Hider \"hidden\"' parameter 'jitter' expects 1 number, got 2"});
    CHECK(ErrorsOf("Hider \"hidden\" \"depthfilter\" 1\n") ==
          Messages{"t.rib:1: error: 'Hider \"hidden\"' parameter 'depthfilter' expects 1 string"});
    CHECK(ErrorsOf("WorldBegin\nHider \"hidden\"\n") ==
          Messages{"t.rib:2: error: 'Hider' is an option and must come before 'WorldBegin'"});
}

TEST_CASE("Without jitter the camera rays go through the stratum centres", "[renderer][rib]") {
    // An orthographic view of [-2, 2] x [-0.5, 0.5], 4 x 1 pixels of one unit: a square from x = -2
    // to -0.6 covers pixel 0, and of the 2 x 2 samples of pixel 1, those at x = -0.75 (hit) and not
    // those at -0.25 (miss).
    // Centred samples give exactly 1, 0.5, 0, 0; jittered ones only by chance.
    const std::string rib = R"(Format 4 1 1
Projection "orthographic"
ScreenWindow -2 2 -0.5 0.5
PixelSamples 2 2
PixelFilter "box" 1 1
Hider "hidden" "jitter" [0]
Scale 1 1 -1
Translate 0 0 -5
WorldBegin
  Patch "bilinear" "P" [-2 -1 0  -0.6 -1 0  -2 1 0  -0.6 1 0]
WorldEnd
)";
    diag::Report report;
    std::optional<SceneDesc> desc = ParseRib(rib, "t.rib", &report);
    INFO(report);
    REQUIRE(desc);
    PreparedScene prepared;
    REQUIRE(Renderer(Options{.shaderPaths = {}}).Prepare(*desc, &prepared, &report));
    // The film puts each sample at its stratum's centre.
    const Film film(desc->camera);
    CHECK(film.SamplePosition(1, 0, 0) == glm::dvec2(1.25, 0.25));
    CHECK(film.SamplePosition(1, 0, 3) == glm::dvec2(1.75, 0.75));
    Options options;
    options.threads = 2;
    image::ImageBuffer image;
    RenderStats stats;
    Renderer(options).Render(prepared, &image, &stats);
    REQUIRE(image.width == 4);
    CHECK(image.rgba[3] == 1.0f);
    CHECK(image.rgba[7] == 0.5f);
    CHECK(image.rgba[11] == 0.0f);
    CHECK(image.rgba[15] == 0.0f);
    // With jitter the samples leave the centres.
    desc->camera.jitter = true;
    CHECK(Film(desc->camera).SamplePosition(1, 0, 0) != glm::dvec2(1.25, 0.25));
}

TEST_CASE("Declare and inline declarations work on every parameter list", "[renderer][rib]") {
    Messages messages;
    // Declared names are usable bare; the declaration travels with the value.
    std::optional<SceneDesc> scene = Parse(
        "Declare \"Km\" \"uniform float\"\nDeclare \"offsets\" \"float[2]\"\nDeclare \"tint\" \"varying color\"\n"
        "Declare \"label\" \"constant string\"\n"
        "Option \"searchpath\" \"string shader\" \"s\"\n"
        "Display \"o.exr\" \"file\" \"rgba\" \"int[2] origin\" [0 0]\n"
        "Hider \"hidden\" \"uniform float jitter\" [0]\n"
        "Projection \"perspective\" \"uniform float fov\" [45]\n"
        "WorldBegin\n"
        "Attribute \"identifier\" \"constant string name\" \"a\"\n"
        "LightSource \"pointlight\" 1 \"point from\" [0 0 1] \"color lightcolor\" [1 1 1] \"float intensity\" 2\n"
        "Surface \"plastic\" \"uniform float Ks\" 0.25 \"color specularcolor\" [1 0 0]\n"
        "Displacement \"wave\" \"Km\" 0.5 \"offsets\" [1 2] \"label\" \"x\" \"matrix m\" [1 0 0 0 0 1 0 0 0 0 1 0 0 0 "
        "0 "
        "1] \"hpoint h\" [1 2 3 1] \"vector v\" [0 0 1] \"normal n\" [0 1 0] \"float [3] f\" [1 2 3]\n"
        "Sphere 1 -1 1 360 \"tint\" [1 0 0 0 1 0 0 0 1 1 1 1] \"vertex point P\" [0 0 0]\n"
        "Patch \"bilinear\" \"vertex point P\" [0 0 0 1 0 0 0 1 0 1 1 0] \"varying float s\" [0 1 0 1]\n"
        "WorldEnd\n",
        &messages);
    INFO(messages.size());
    REQUIRE(scene);
    CHECK_FALSE(scene->camera.jitter);
    CHECK(scene->camera.fovDegrees == 45);
    CHECK(scene->shaderSearchPath == std::vector<std::string>{"s"});
    REQUIRE(scene->lights.size() == 1);
    CHECK(scene->lights[0].intensity == 2);
    REQUIRE(scene->primitives.size() == 2);
    CHECK(scene->primitives[0].attr().surface.Ks == 0.25);
    const ShaderRef& wave = *scene->primitives[0].attr().displacement;
    REQUIRE(wave.params.size() == 8);
    CHECK(wave.params[0].name == "Km");
    CHECK(wave.params[0].declaration == "uniform float");
    CHECK(wave.params[1].declaration == "float[2]");
    CHECK(wave.params[2].declaration == "constant string");
    CHECK(wave.params[3].declaration == "matrix");
    // A later Declare replaces an earlier one.
    scene = Parse(
        "Declare \"Km\" \"float\"\nDeclare \"Km\" \"string\"\nWorldBegin\nDisplacement \"w\" \"Km\" \"a\"\n"
        "Sphere 1 -1 1 360\nWorldEnd\n",
        &messages);
    REQUIRE(scene);
    CHECK(scene->primitives[0].attr().displacement->params[0].declaration == "string");

    // Declarations are checked against the values.
    CHECK(ErrorsOf("Declare \"Km\" \"uniform float\"\nWorldBegin\nDisplacement \"w\" \"Km\" [1 2]\n") ==
          Messages{"t.rib:3: error: 'Displacement' parameter 'Km' is declared \"uniform float\" and expects 1 number, "
                   "got 2"});
    CHECK(ErrorsOf("WorldBegin\nSurface \"plastic\" \"color specularcolor\" [1 0]\n") ==
          Messages{"t.rib:2: error: 'Surface' parameter 'specularcolor' is declared \"color\" and expects 3 numbers, "
                   "got 2"});
    CHECK(ErrorsOf("WorldBegin\nSurface \"plastic\" \"string Ks\" [1]\n") ==
          Messages{"t.rib:2: error: 'Surface' parameter 'Ks' is declared \"string\" and expects strings, got numbers"});
    CHECK(ErrorsOf("WorldBegin\nSphere 1 -1 1 360 \"varying color Cs\" [1 0]\n") ==
          Messages{"t.rib:2: error: 'Sphere' parameter 'Cs' is declared \"varying color\" and expects a multiple of 3 "
                   "numbers, got 2"});
    CHECK(
        ErrorsOf("WorldBegin\nSphere 1 -1 1 360 \"vertex float[2] uv\" [1 2 3]\n") ==
        Messages{"t.rib:2: error: 'Sphere' parameter 'uv' is declared \"vertex float[2]\" and expects a multiple of 2 "
                 "numbers, got 3"});
    CHECK(ErrorsOf("WorldBegin\nAttribute \"user\" \"float[2] pair\" [1]\n") ==
          Messages{"t.rib:2: error: 'Attribute' parameter 'pair' is declared \"float[2]\" and expects 2 numbers, got "
                   "1"});
    CHECK(ErrorsOf("Option \"user\" \"quux float x\" [1]\n") ==
          Messages{"t.rib:1: error: 'Option' parameter 'x': declaration \"quux float\" has words after its type"});
    CHECK(ErrorsOf("Declare \"x\" \"uniform quux\"\n") ==
          Messages{"t.rib:1: error: 'Declare': declaration \"uniform quux\" has an unknown type 'quux' (expected "
                   "float, integer, string, color, point, vector, normal, hpoint or matrix)"});
    CHECK(ErrorsOf("Declare \"x\" \"float[0]\"\n") ==
          Messages{"t.rib:1: error: 'Declare': declaration \"float[0]\" needs a positive array size, as \"float[2]\""});
    CHECK(ErrorsOf("Declare \"x\" \"varying\"\n") ==
          Messages{"t.rib:1: error: 'Declare': declaration \"varying\" has no type"});
    CHECK(ErrorsOf("Declare \"x\"\n") == Messages{"t.rib:1: error: 'Declare' expects 2 strings (name declaration)"});
    CHECK(ErrorsOf("Declare \"a b\" \"float\"\n") == Messages{"t.rib:1: error: 'Declare' name 'a b' must be one word"});
}

TEST_CASE("Options and attributes of other renderers warn once per name, \"user\" is kept silently",
          "[renderer][rib]") {
    Messages messages;
    std::optional<SceneDesc> scene = Parse(
        "Option \"limits\" \"bucketsize\" [16 16]\nOption \"limits\" \"gridsize\" [256]\n"
        "Option \"statistics\" \"endofframe\" [1]\nOption \"searchpath\" \"texture\" \"t\" \"shader\" \"s\"\n"
        "Option \"searchpath\" \"procedural\" \"p\"\nOption \"user\" \"string pass\" \"beauty\"\n"
        "WorldBegin\n"
        "Attribute \"identifier\" \"name\" \"a\"\nAttribute \"identifier\" \"name\" \"b\"\n"
        "Attribute \"visibility\" \"int transmission\" [1]\nAttribute \"dice\" \"int rasterorient\" [0]\n"
        "Attribute \"user\" \"float id\" [3]\nAttribute \"trace\" \"int maxdiffusedepth\" [1]\n"
        "WorldEnd\n",
        &messages);
    REQUIRE(scene);
    CHECK(scene->shaderSearchPath == std::vector<std::string>{"s"});
    CHECK(messages == Messages{
                          "t.rib:1: warning: 'Option \"limits\"' does not apply to affray; ignored",
                          "t.rib:3: warning: 'Option \"statistics\"' does not apply to affray; ignored",

                          "t.rib:5: warning: 'Option \"searchpath\" \"procedural\"' does not apply to affray; ignored",
                          "t.rib:8: warning: 'Attribute \"identifier\"' does not apply to affray; ignored",
                          "t.rib:11: warning: 'Attribute \"dice\"' does not apply to affray; ignored",
                          "t.rib:13: warning: 'Attribute \"trace\"' does not apply to affray; ignored",
                      });
}

TEST_CASE("Illuminate turns lights on and off, and an unknown handle warns", "[renderer][rib]") {
    Messages messages;
    std::optional<SceneDesc> scene = Parse(
        "WorldBegin\nLightSource \"pointlight\" \"k\"\nIlluminate \"k\" 1\nIlluminate 2 0\nIlluminate \"k\" "
        "0\nSphere 1 -1 1 360\nWorldEnd\n",
        &messages);
    REQUIRE(scene);
    CHECK(scene->lights.size() == 1);
    CHECK(scene->primitives.at(0).attr().lights == std::vector<int>{});  // (tests/rib/frames_test.cpp has more)
    CHECK(messages == Messages{"t.rib:4: warning: 'Illuminate': no light source has the handle '2'; ignored"});
    CHECK(ErrorsOf("WorldBegin\nIlluminate \"k\"\n") ==
          Messages{"t.rib:2: error: 'Illuminate' expects a light handle and 0 or 1"});
    CHECK(ErrorsOf("WorldBegin\nIlluminate \"k\" 2\n") ==
          Messages{"t.rib:2: error: 'Illuminate' expects 0 or 1, got 2"});
}

TEST_CASE("Shutter sets the times camera samples take", "[renderer][rib]") {
    Messages messages;
    std::optional<SceneDesc> scene = Parse("Shutter 0.25 0.75\nWorldBegin\nWorldEnd\n", &messages);
    REQUIRE(scene);
    CHECK(messages.empty());
    CHECK(scene->camera.shutterOpen == 0.25);
    CHECK(scene->camera.shutterClose == 0.75);
    CHECK(ShutterOpenP(scene->camera));
    scene = Parse("Option \"Ri\" \"float[2] Shutter\" [2 2]\nWorldBegin\nWorldEnd\n", &messages);
    REQUIRE(scene);
    CHECK(scene->camera.shutterOpen == 2);
    CHECK_FALSE(ShutterOpenP(scene->camera));  // a shutter that does not open: no blur
    CHECK(ErrorsOf("Shutter 1 0\nWorldBegin\nWorldEnd\n") ==
          Messages{"t.rib:1: error: 'Shutter' needs finite times with max not before min, got 1 0"});
    CHECK(ErrorsOf("WorldBegin\nShutter 0 1\nWorldEnd\n") ==
          Messages{"t.rib:2: error: 'Shutter' is an option and must come before 'WorldBegin'"});
}

TEST_CASE("ShadingRate, ShadingInterpolation and ArchiveRecord", "[renderer][rib]") {
    Messages messages;
    std::optional<SceneDesc> scene = Parse(
        "ShadingRate 1\nShadingInterpolation \"smooth\"\nArchiveRecord \"comment\" \"made by hand\"\n"
        "WorldBegin\nShadingRate [0.25]\nShadingInterpolation \"constant\"\n"
        "ArchiveRecord \"structure\" \"Scene x\"\nWorldEnd\n",
        &messages);
    REQUIRE(scene);
    // ShadingRate 1 and 0.25 ask for no coarser tolerance than affray's: no message.
    CHECK(messages ==
          Messages{"t.rib:2: warning: 'ShadingInterpolation' does not apply: affray shades every ray hit; ignored"});
    CHECK(ErrorsOf("ShadingRate 0\n") == Messages{"t.rib:1: error: 'ShadingRate' must be positive, got 0"});
    CHECK(ErrorsOf("ShadingRate \"a\"\n") ==
          Messages{"t.rib:1: error: 'ShadingRate' expects 1 numbers (size), got string \"a\""});
    CHECK(ErrorsOf("ShadingInterpolation \"linear\"\n") ==
          Messages{"t.rib:1: error: unknown shading interpolation 'linear' (expected \"constant\" or \"smooth\")"});
    CHECK(ErrorsOf("ArchiveRecord \"verbatim\" \"Sphere 1 -1 1 360\\n\"\n") ==
          Messages{"t.rib:1: error: 'ArchiveRecord \"verbatim\"' (RIB text in a string) is not supported"});
}

TEST_CASE("A header as exporters write it parses with one warning per ignored name", "[renderer][rib]") {
    // The shape of the headers Maya, Houdini and Blender exporters write (RenderMan 3.x era).
    const std::string rib = R"(##RenderMan RIB-Structure 1.1
##Scene exported
##CreationDate Thu Nov 26 2026
version 3.04
Declare "Cs_ramp" "varying color"
Option "searchpath" "shader" ["shaders:@"] "texture" ["textures:@"] "archive" ["archives:@"]
Option "limits" "bucketsize" [32 32] "gridsize" [256] "eyesplits" [10]
Option "statistics" "endofframe" [0]
Option "trace" "maxdepth" [4]
Option "user" "string pass_class" ["beauty"]
FrameBegin 1
  Format 32 24 1
  FrameAspectRatio 1.333333
  ScreenWindow -1.333333 1.333333 -1 1
  Clipping 0.1 10000
  PixelSamples 3 3
  PixelFilter "gaussian" 2 2
  PixelVariance 0.01
  Hider "hidden" "jitter" [1] "depthfilter" "min"
  Exposure 1 2.2
  Quantize "rgba" 255 0 255 0.5
  Imager "background" "color bgcolor" [0 0 0]
  DepthOfField 1000000 1 1
  Shutter 0 1
  Display "out.exr" "openexr" "rgba"
  Projection "perspective" "fov" [37.8]
  Identity
  ConcatTransform [1 0 0 0  0 1 0 0  0 0 -1 0  0 0 10 1]
  WorldBegin
    Attribute "identifier" "string name" ["world"]
    Attribute "visibility" "int camera" [1] "int trace" [1] "int transmission" [1]
    Attribute "dice" "int binary" [1]
    Attribute "displacementbound" "float sphere" [0.1] "string coordinatesystem" ["shader"]
    ShadingRate 1
    ShadingInterpolation "smooth"
    Sides 2
    LightSource "distantlight" "key" "intensity" [1] "from" [0 0 0] "to" [0 0 1]
    Illuminate "key" 1
    AttributeBegin
      Attribute "identifier" "string name" ["ball"]
      Color [0.8 0.8 0.8]
      Opacity [1 1 1]
      Basis "bezier" 3 "bezier" 3
      Surface "plastic" "float Ks" [0.5]
      TransformBegin
        Translate 0 0 1
        Sphere 1 -1 1 360 "Cs_ramp" [1 0 0  0 1 0  0 0 1  1 1 1]
      TransformEnd
    AttributeEnd
  WorldEnd
FrameEnd
)";
    Messages messages;
    std::optional<SceneDesc> scene = Parse(rib, &messages);
    REQUIRE(scene);
    CHECK(scene->primitives.size() == 1);
    CHECK(scene->camera.xsamples == 3);
    CHECK(scene->camera.jitter);
    CHECK(scene->camera.background == glm::dvec3(0.0));  // Imager "background" "color bgcolor" [0 0 0]
    CHECK(scene->camera.fstop == 1e6);                   // DepthOfField 1000000 1 1: a lens 1e-6 wide
    CHECK(scene->camera.focalDistance == 1);
    CHECK(scene->camera.shutterOpen == 0);  // Shutter 0 1
    CHECK(scene->camera.shutterClose == 1);
    CHECK(messages == Messages{

                          "t.rib:7: warning: 'Option \"limits\"' does not apply to affray; ignored",
                          "t.rib:8: warning: 'Option \"statistics\"' does not apply to affray; ignored",
                          "t.rib:9: warning: 'Option \"trace\"' does not apply to affray; ignored",
                          "t.rib:18: warning: 'PixelVariance' does not apply to affray; ignored",
                          "t.rib:21: warning: 'Quantize' does not apply to affray; ignored",
                          "t.rib:30: warning: 'Attribute \"identifier\"' does not apply to affray; ignored",
                          "t.rib:31: warning: 'Attribute \"visibility\"' parameter 'trace' does not apply to affray; "
                          "ignored",
                          "t.rib:32: warning: 'Attribute \"dice\"' does not apply to affray; ignored",
                          // NOLINTNEXTLINE(bugprone-suspicious-missing-comma): one message in two literals
                          "t.rib:33: warning: 'Attribute \"displacementbound\"' is not needed: affray bounds "
                          "displacement exactly; ignored",
                          "t.rib:35: warning: 'ShadingInterpolation' does not apply: affray shades every ray hit; "
                          "ignored",
                          "t.rib:47: warning: 'Sphere' parameter 'Cs_ramp' is not supported yet; ignored",
                      });
}
