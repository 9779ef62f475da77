// tests/rib/frames_test.cpp: the RIB reader's frames (rib/rib.cpp: FrameBegin/FrameEnd scoping,
// shadow and depth map passes, Make* requests), the shadow-map light shaders and Illuminate
// (rib/attributes.cpp). The command line's side of frames is in tests/tools/frames_cli_test.cpp.
#include <catch2/catch.hpp>
#include <string>
#include <vector>

#include "rib/rib.h"

using namespace affray::renderer;
using namespace affray::rib;
using affray::diag::Report;
using affray::diag::Severity;

namespace {

// The diagnostics of `report` of one severity, as "line: message".
std::vector<std::string> Messages(const Report& report, Severity severity) {
    std::vector<std::string> out;
    for (const affray::diag::Diagnostic& d : report.all())
        if (d.severity == severity) out.push_back(std::to_string(d.where.line) + ": " + d.message);
    return out;
}

// The frames of `text`, which must parse.
std::vector<SceneDesc> Frames(const std::string& text, Report* report) {
    std::optional<std::vector<SceneDesc>> frames = ParseRibFrames(text, "t.rib", report);
    INFO(*report);
    REQUIRE(frames);
    return *frames;
}

// The first error of `text`, "line: message", or "" if it parses.
std::string ErrorOf(const std::string& text) {
    Report report;
    if (ParseRibFrames(text, "t.rib", &report)) return "";
    std::vector<std::string> errors = Messages(report, Severity::Error);
    return errors.empty() ? "(no error reported)" : errors[0];
}

// A classic three-frame file: a shadow pass, then two image frames with options of their own.
const char* const kThreeFrames = R"(Format 64 48 1
PixelSamples 1 1
Display "default.exr" "file" "rgba"
LightSource "ambientlight" 9 "intensity" [0.1]
FrameBegin 1
  Display "key.z" "zfile" "z"
  Projection "perspective" "fov" [60]
  WorldBegin
    Sphere 1 -1 1 360
  WorldEnd
FrameEnd
MakeShadow "key.z" "key.shd"
FrameBegin 2
  Format 32 24 1
  Display "two.exr" "file" "rgba"
  Projection "perspective" "fov" [40]
  Translate 0 0 5
  WorldBegin
    LightSource "shadowspot" 1 "from" [0 4 0] "to" [0 0 0] "shadowname" "key.shd" "samples" [16]
    Sphere 1 -1 1 360
    Translate 0 -1 0
    Sphere 0.5 -0.5 0.5 360
  WorldEnd
FrameEnd
FrameBegin 3
  Translate 0 0 7
  WorldBegin
    Sphere 1 -1 1 360
  WorldEnd
FrameEnd
)";

}  // namespace

TEST_CASE("frames: one scene per frame with RenderMan's option scoping", "[rib]") {
    Report report;
    std::vector<SceneDesc> frames = Frames(kThreeFrames, &report);
    REQUIRE(frames.size() == 3);
    CHECK(frames[0].frame == 1);
    CHECK(frames[1].frame == 2);
    CHECK(frames[2].frame == 3);
    CHECK(frames[1].frameLine == 13);

    // Frame 1 only makes a depth map: skipped, with its primitives dropped.
    CHECK(frames[0].skipped == "a depth map for a scanline renderer (Display 'key.z' 'zfile' 'z')");
    CHECK(frames[0].primitives.empty());
    CHECK(frames[1].skipped.empty());
    CHECK(frames[2].skipped.empty());

    // Frame 2's own options; frame 3 gets the defaults back (Format, Display, no Projection).
    CHECK(frames[1].camera.xres == 32);
    CHECK(frames[1].displayName == "two.exr");
    CHECK(frames[1].camera.perspective);
    CHECK(frames[1].camera.fovDegrees == 40);
    CHECK(frames[2].camera.xres == 64);
    CHECK(frames[2].camera.yres == 48);
    CHECK(frames[2].camera.xsamples == 1);  // set before the first frame: every frame's default
    CHECK(frames[2].displayName == "default.exr");
    CHECK_FALSE(frames[2].camera.perspective);
    // The camera transform of frame 2 does not leak into frame 3.
    CHECK(frames[1].camera.worldToCamera[3][2] == 5);
    CHECK(frames[2].camera.worldToCamera[3][2] == 7);

    // The light before the first frame is in every frame; frame 2's shadowspot only in frame 2.
    REQUIRE(frames[1].lights.size() == 2);
    CHECK(frames[1].lights[0].kind == LightDesc::Kind::Ambient);
    CHECK(frames[1].lights[1].kind == LightDesc::Kind::Spot);
    REQUIRE(frames[2].lights.size() == 1);
    CHECK(frames[2].primitives.size() == 1);
    CHECK(frames[1].primitives.size() == 2);

    // One note for each thing skipped; no warning.
    CHECK(Messages(report, Severity::Warning).empty());
    std::vector<std::string> notes = Messages(report, Severity::Note);
    REQUIRE(notes.size() == 3);
    CHECK(notes[0] ==
          "5: frame 1 renders a depth map for a scanline renderer (Display 'key.z' 'zfile' 'z'); affray "
          "traces shadows: skipped");
    CHECK(notes[1] == "12: 'MakeShadow' makes a shadow map for a scanline renderer; affray traces shadows: skipped");
    CHECK(notes[2].rfind("19: light source 'shadowspot' renders as 'spotlight' with traced shadows", 0) == 0);

    // ParseRib, for one image: the first frame that is not skipped.
    std::optional<SceneDesc> first = ParseRib(kThreeFrames, "t.rib", nullptr);
    REQUIRE(first);
    CHECK(first->frame == 2);
}

TEST_CASE("frames: shadow passes are recognised by Display type or a depth-only mode", "[rib]") {
    auto skipped = [](const std::string& display) {
        Report report;
        std::vector<SceneDesc> frames =
            Frames("FrameBegin 4\n" + display + "\nWorldBegin\nWorldEnd\nFrameEnd\n", &report);
        REQUIRE(frames.size() == 1);
        CHECK(Messages(report, Severity::Warning).empty());  // no "display type not supported"
        return frames[0].skipped;
    };
    CHECK(skipped(R"(Display "a.shd" "shadow" "z")") ==
          "a shadow map for a scanline renderer (Display 'a.shd' 'shadow' 'z')");
    CHECK(skipped(R"(Display "a.dsm" "deepshadow" "deepopacity")").empty() == false);
    CHECK(skipped(R"(Display "a.z" "zfile" "rgbz")") != "");
    CHECK(skipped(R"(Display "a.tif" "file" "z")") != "");
    CHECK(skipped(R"(Display "a.exr" "openexr" "z")") == "");    // affray's depth image
    CHECK(skipped(R"(Display "a.exr" "file" "rgba,Z")") == "");  // the Z AOV is an image
    CHECK(skipped("") == "");

    // A file whose every frame is skipped: ParseRibFrames returns it, ParseRib says so.
    const std::string onlyShadow = "FrameBegin 1\nDisplay \"a.z\" \"zfile\" \"z\"\nWorldBegin\nWorldEnd\nFrameEnd\n";
    Report report;
    CHECK_FALSE(ParseRib(onlyShadow, "t.rib", &report));
    CHECK(Messages(report, Severity::Error) == std::vector<std::string>{"0: no frame of the file renders an image"});
}

TEST_CASE("frames: MakeTexture is kept for every later frame, the other Make* requests skipped with a note", "[rib]") {
    Report report;
    const std::vector<SceneDesc> frames = Frames(R"(MakeTexture "a.tif" "a.tex" "periodic" "clamp" "gaussian" 2 2
FrameBegin 1
MakeTexture "b.tif" "b.tex" "black" "periodic" "gaussian" 2 2 "float quality" [1]
MakeLatLongEnvironment "sky.tif" "sky.env" "gaussian" 2 2
MakeShadow "key.z" "key.shd"
WorldBegin
WorldEnd
FrameEnd
FrameBegin 2
WorldBegin
WorldEnd
FrameEnd
)",
                                                 &report);
    CHECK(Messages(report, Severity::Warning) ==
          std::vector<std::string>{"3: 'MakeTexture' parameter 'quality' ignored"});
    CHECK(Messages(report, Severity::Note) ==
          std::vector<std::string>{
              "4: 'MakeLatLongEnvironment' makes a map that affray's shaders cannot read yet: skipped",
              "5: 'MakeShadow' makes a shadow map for a scanline renderer; affray traces shadows: skipped"});
    REQUIRE(frames.size() == 2);
    for (const SceneDesc& frame : frames) {
        REQUIRE(frame.makeTextures.size() == 2);
        const SceneDesc::MakeTextureDesc &a = frame.makeTextures[0], &b = frame.makeTextures[1];
        CHECK((a.picture == "a.tif" && a.texture == "a.tex" && a.swrap == "periodic" && a.twrap == "clamp"));
        CHECK((b.picture == "b.tif" && b.texture == "b.tex" && b.swrap == "black" && b.twrap == "periodic"));
        CHECK((a.line == 1 && b.line == 3));
    }
    CHECK(ErrorOf("MakeShadow 1 2\nWorldBegin\nWorldEnd\n") ==
          "1: 'MakeShadow' expects an image file name as its first argument, found number 1");
    CHECK(ErrorOf("MakeTexture \"a.tif\" \"a.tex\" \"mirror\" \"clamp\" \"box\" 1 1\nWorldBegin\nWorldEnd\n") ==
          "1: 'MakeTexture' wrap mode 'mirror' is not periodic, clamp or black");
    CHECK(ErrorOf("MakeTexture \"a.tif\" \"a.tex\" \"clamp\" \"clamp\"\nWorldBegin\nWorldEnd\n") ==
          "1: 'MakeTexture' argument 5 must be a filter name");
    CHECK(ErrorOf("MakeTexture \"a.tif\" \"a.tex\" \"clamp\" \"clamp\" \"box\" 1 \"x\"\nWorldBegin\nWorldEnd\n") ==
          "1: 'MakeTexture' argument 7 must be a filter width");
}

TEST_CASE("frames: errors in the frame structure name their line", "[rib]") {
    const std::string world = "WorldBegin\nWorldEnd\n";
    CHECK(ErrorOf("FrameBegin 1\nFrameBegin 2\n") == "2: 'FrameBegin' inside 'FrameBegin' on line 1");
    CHECK(ErrorOf("FrameBegin 1\n" + world + world + "FrameEnd\n") ==
          "4: a second 'WorldBegin' in frame 1; give each world its own 'FrameBegin'/'FrameEnd'");
    CHECK(ErrorOf(world + world) ==
          "3: a second 'WorldBegin' outside frames; give each world its own 'FrameBegin'/'FrameEnd'");
    CHECK(ErrorOf(world + "FrameBegin 1\n" + world + "FrameEnd\n") ==
          "3: 'FrameBegin' after a 'WorldBegin' outside any frame");
    CHECK(ErrorOf("FrameBegin 1.5\n" + world + "FrameEnd\n") ==
          "1: 'FrameBegin' frame number must be an integer, got 1.5");
    CHECK(ErrorOf("FrameBegin\n" + world + "FrameEnd\n") == "1: 'FrameBegin' expects one frame number");
    CHECK(ErrorOf("FrameBegin 1\n" + world) == "1: 'FrameBegin' has no matching 'FrameEnd'");
    CHECK(ErrorOf("FrameBegin 1\nFrameEnd\n") == "2: no 'WorldBegin': the file describes no scene");
    // A frame that only makes maps has no world: that is fine beside a frame that has one.
    CHECK(ErrorOf("FrameBegin 1\nMakeShadow \"a.z\" \"a.shd\"\nFrameEnd\nFrameBegin 2\n" + world + "FrameEnd\n") == "");
    // Frames may share a number (a shadow pass and the image of one animation frame).
    Report report;
    CHECK(Frames("FrameBegin 7\n" + world + "FrameEnd\nFrameBegin 7\n" + world + "FrameEnd\n", &report).size() == 2);
}

TEST_CASE("lights: shadow-map light shaders map to traced-shadow lights", "[rib]") {
    Report report;
    std::vector<SceneDesc> frames = Frames(R"(WorldBegin
  LightSource "shadowspot" 1 "intensity" [3] "lightcolor" [1 0.5 0.25] "from" [0 5 0] "to" [0 0 0]
    "coneangle" [0.4] "conedeltaangle" [0.1] "beamdistribution" [3] "shadowname" "spot.shd" "samples" [16]
    "width" [2] "blur" [0.01] "bias" [0.2]
  LightSource "shadowpoint" 2 "intensity" [4] "from" [1 2 3] "sfpx" "px.shd" "sfnx" "nx.shd" "sfpy" "py.shd"
    "sfny" "ny.shd" "sfpz" "pz.shd" "sfnz" "nz.shd" "samples" [4]
  LightSource "shadowdistant" 3 "from" [0 1 0] "to" [0 0 0] "shadowname" "sun.shd" "width" [1]
  LightSource "spotlight" 4 "from" [0 1 0] "to" [0 0 0] "shadowname" "s.shd"
  LightSource "pointlight" 5 "from" [0 1 0] "shadowname" "p.shd"
  LightSource "shadowspot" 6 "from" [0 2 0] "to" [0 0 0] "shadowname" "other.shd"
  LightSource "arealight" 7
WorldEnd
)",
                                           &report);
    REQUIRE(frames.size() == 1);
    const std::vector<LightDesc>& lights = frames[0].lights;
    REQUIRE(lights.size() == 7);  // the area light's shader is looked for when the scene is prepared
    CHECK_FALSE(lights[6].builtIn);
    REQUIRE(lights[6].shader);
    CHECK(lights[6].shader->name == "arealight");
    CHECK(lights[0].kind == LightDesc::Kind::Spot);
    CHECK(lights[0].intensity == 3);
    CHECK(lights[0].color == glm::dvec3(1, 0.5, 0.25));
    CHECK(lights[0].from == glm::dvec3(0, 5, 0));
    CHECK(lights[0].coneAngle == 0.4);
    CHECK(lights[0].coneDeltaAngle == 0.1);
    CHECK(lights[0].beamDistribution == 3);
    CHECK(lights[1].kind == LightDesc::Kind::Point);
    CHECK(lights[1].from == glm::dvec3(1, 2, 3));
    CHECK(lights[2].kind == LightDesc::Kind::Distant);
    CHECK(lights[3].kind == LightDesc::Kind::Spot);
    CHECK(lights[4].kind == LightDesc::Kind::Point);
    // One note per shadow-map shader and one per standard light given a shadowname.
    // Each note's tail, shared: whole strings below, no literal split over lines.
    const std::string mapIgnored =
        " with traced shadows; its shadow map parameters (shadowname, samples, width, "
        "blur, bias, ...) are ignored";
    const std::string traced = "' parameter 'shadowname' names a shadow map; affray traces the light's shadows instead";
    CHECK(Messages(report, Severity::Note) ==
          std::vector<std::string>{"2: light source 'shadowspot' renders as 'spotlight'" + mapIgnored,
                                   "5: light source 'shadowpoint' renders as 'pointlight'" + mapIgnored,
                                   "7: light source 'shadowdistant' renders as 'distantlight'" + mapIgnored,
                                   "8: 'LightSource \"spotlight\"" + traced,
                                   "9: 'LightSource \"pointlight\"" + traced});
    CHECK(Messages(report, Severity::Warning).empty());  // (the area light's shader: looked for later)
    // The standard lights take no other shadow-map parameter.
    Report other;
    Frames("WorldBegin\nLightSource \"spotlight\" 1 \"samples\" [4]\nWorldEnd\n", &other);
    CHECK(Messages(other, Severity::Warning) ==
          std::vector<std::string>{"2: 'LightSource \"spotlight\"' has no parameter 'samples'; ignored"});
}

TEST_CASE("lights: Illuminate turns lights on and off in the attribute state", "[rib]") {
    Report report;
    std::vector<SceneDesc> frames = Frames(R"(LightSource "ambientlight" "cam" "intensity" [0.1]
WorldBegin
  Sphere 1 -1 1 360
  LightSource "pointlight" 1 "from" [0 5 0]
  LightSource "distantlight" "sun"
  Sphere 1 -1 1 360
  AttributeBegin
    Illuminate 1 0
    Illuminate "cam" 0
    Sphere 1 -1 1 360
    Illuminate 1 1
    LightSource "spotlight" 2
    Sphere 1 -1 1 360
  AttributeEnd
  Sphere 1 -1 1 360
  Illuminate 2 1
  Illuminate "sun" 0
  Sphere 1 -1 1 360
  ObjectBegin "thing"
    Illuminate 1 0
    Sphere 1 -1 1 360
  ObjectEnd
  ObjectInstance "thing"
  Sphere 1 -1 1 360
  Illuminate "nobody" 0
  LightSource "arealight" 3
  Illuminate 3 1
WorldEnd
)",
                                           &report);
    const std::vector<PrimitiveDesc>& prims = frames.at(0).primitives;
    REQUIRE(prims.size() == 8);
    using Lights = std::vector<int>;
    auto lightsOf = [&](size_t i) { return prims[i].attr().lights.value_or(Lights{-1}); };
    CHECK(lightsOf(0) == Lights{0});        // only the light declared before it
    CHECK(lightsOf(1) == Lights{0, 1, 2});  // every light is on when declared
    CHECK(lightsOf(2) == Lights{2});        // two turned off
    CHECK(lightsOf(3) == Lights{1, 2, 3});  // one back on, one declared inside the block
    CHECK(lightsOf(4) == Lights{0, 1, 2});  // AttributeEnd restores the list: light 2 is off
    CHECK(lightsOf(5) == Lights{0, 1, 3});  // a light off outside its block can be turned on
    CHECK(lightsOf(6) == Lights{0, 3});     // an object's Illuminate applies inside it
    CHECK(lightsOf(7) == Lights{0, 1, 3});  // and not after the instance
    // (The area light's shader is looked for when the scene is prepared: its light is the fifth.)
    CHECK(Messages(report, Severity::Warning) ==
          std::vector<std::string>{"25: 'Illuminate': no light source has the handle 'nobody'; ignored"});
    CHECK(frames[0].lights.size() == 5);
}
