// tests/rib/unsupported_test.cpp: what the reader does with the forms real exporters write that
// affray does not render as asked (rib/unsupported.cpp, and the leniencies of rib/rib.cpp and
// rib/frames.cpp): a non-positive pixel aspect ratio, a world wrapped in a TransformBegin or
// AttributeBegin block, Skew, solids, primitives affray cannot make, and other renderers'
// requests. Each is accepted with one warning or note, or refused with a located error.
#include <catch2/catch.hpp>
#include <optional>
#include <string>
#include <vector>

#include "rib/rib.h"
#include "tests/rib/rib_test_util.h"

using namespace affray;
using namespace affray::test;
using renderer::SceneDesc;

namespace {

using Messages = std::vector<std::string>;

// The frames of `text`, with every diagnostic (as ShortDiagnostic gives it) in *messages.
std::optional<std::vector<SceneDesc>> Frames(const std::string& text, Messages* messages) {
    diag::Report report;
    std::optional<std::vector<SceneDesc>> frames = rib::ParseRibFrames(text, "t.rib", &report);
    messages->clear();
    for (const diag::Diagnostic& d : report.all()) messages->push_back(ShortDiagnostic(d));
    return frames;
}

// The one frame of `text`, which must parse.
SceneDesc Scene(const std::string& text, Messages* messages) {
    std::optional<std::vector<SceneDesc>> frames = Frames(text, messages);
    INFO(text);
    REQUIRE(frames);
    REQUIRE(frames->size() == 1);
    return frames->front();
}

const std::string kPatch = "Patch \"bilinear\" \"P\" [0 0 0  1 0 0  0 1 0  1 1 0]\n";

}  // namespace

TEST_CASE("rib: a pixel aspect ratio that is not positive is the default, 1, with a note", "[rib]") {
    for (const char* aspect : {"-1", "0"}) {
        Messages messages;
        const SceneDesc scene = Scene("Format 40 30 " + std::string(aspect) + "\nWorldBegin\nWorldEnd\n", &messages);
        CHECK(scene.camera.xres == 40);
        CHECK(scene.camera.yres == 30);
        CHECK(scene.camera.pixelAspect == 1);
        CHECK(messages == Messages{"t.rib:1: note: 'Format' pixelaspectratio " + std::string(aspect) +
                                   " asks for the display's default (RI 3.2): using 1, square pixels"});
    }
    Messages messages;
    CHECK(Scene("Format 40 30 2\nWorldBegin\nWorldEnd\n", &messages).camera.pixelAspect == 2);
    CHECK(messages.empty());
    // The lexer refuses NaN and infinity, so they never reach Format.
    CHECK(FirstError("Format 40 30 inf\nWorldBegin\nWorldEnd\n") ==
          "t.rib:1: error: invalid number 'inf': NaN and infinity are not allowed");
}

TEST_CASE("rib: a world inside TransformBegin or AttributeBegin starts from the camera transform", "[rib]") {
    // As Houdini writes it: the camera's motion block and the world in one TransformBegin block.
    const std::string camera =
        "MotionBegin [0 1]\n"
        "ConcatTransform [1 0 0 0  0 1 0 0  0 0 1 0  0 0 5 1]\n"
        "ConcatTransform [1 0 0 0  0 1 0 0  0 0 1 0  0 0 6 1]\n"
        "MotionEnd\n";
    Messages messages;
    SceneDesc scene = Scene(
        "Translate 1 0 0\nTransformBegin\n" + camera + "WorldBegin\n" + kPatch + "WorldEnd\nTransformEnd\n", &messages);
    CHECK(scene.camera.worldToCamera[3] == glm::dvec4(1, 0, 5, 1));  // Translate, then the first sample
    // The camera moves: Translate, then each sample.
    REQUIRE(scene.camera.motion);
    CHECK(scene.camera.motion->matrices[1][3] == glm::dvec4(1, 0, 6, 1));
    REQUIRE(scene.primitives.size() == 1);
    CHECK(scene.primitives[0].base.patch().corners[3] == glm::dvec3(1, 1, 0));  // world space starts at identity
    CHECK_FALSE(scene.primitives[0].attr().motion);                             // and stands still
    CHECK(messages == Messages{
                          "t.rib:7: note: 'WorldBegin' inside 'TransformBegin': the world starts from the transform "
                          "current here (the camera transform), and 'TransformEnd' after 'WorldEnd' ends the block",
                      });

    // In frames, each world in its own block, the note once; an AttributeBegin around the world
    // restores the attributes given before it after AttributeEnd, and the frame ends cleanly.
    std::optional<std::vector<SceneDesc>> frames;
    std::string text;
    for (int frame = 1; frame <= 2; ++frame)
        text += "FrameBegin " + std::to_string(frame) + "\nAttributeBegin\nColor 1 0 0\nTranslate 0 0 " +
                std::to_string(frame) + "\nWorldBegin\n" + kPatch + "WorldEnd\nAttributeEnd\nFrameEnd\n";
    frames = Frames(text, &messages);
    REQUIRE(frames);
    REQUIRE(frames->size() == 2);
    for (int frame = 1; frame <= 2; ++frame) {
        const SceneDesc& f = (*frames)[static_cast<size_t>(frame - 1)];
        CHECK(f.camera.worldToCamera[3] == glm::dvec4(0, 0, frame, 1));
        CHECK(f.primitives.at(0).color == glm::dvec3(1, 0, 0));
    }
    CHECK(messages == Messages{"t.rib:5: note: 'WorldBegin' inside 'AttributeBegin': the world starts from the "
                               "transform current here (the camera transform), and 'AttributeEnd' after 'WorldEnd' "
                               "ends the block"});

    // The block must still close after the world, and in order.
    CHECK(FirstError("TransformBegin\nWorldBegin\nWorldEnd\n") ==
          "t.rib:1: error: 'TransformBegin' has no matching 'TransformEnd'");
    CHECK(FirstError("TransformBegin\nWorldBegin\nTransformEnd\nWorldEnd\n") ==
          "t.rib:3: error: 'TransformEnd' does not match 'WorldBegin' on line 2");
    CHECK(FirstError("FrameBegin 1\nTransformBegin\nWorldBegin\nWorldEnd\nFrameEnd\nTransformEnd\n") ==
          "t.rib:5: error: 'FrameEnd' does not match 'TransformBegin' on line 2");
    CHECK(FirstError("TransformBegin\nWorldBegin\nWorldEnd\nTransformEnd\nWorldBegin\nWorldEnd\n") ==
          "t.rib:5: error: a second 'WorldBegin' outside frames; give each world its own 'FrameBegin'/'FrameEnd'");
    CHECK(FirstError("TransformBegin\nFrameBegin 1\nWorldBegin\nWorldEnd\nFrameEnd\nTransformEnd\n") ==
          "t.rib:2: error: 'FrameBegin' inside 'TransformBegin' on line 1");
}

TEST_CASE("rib: Skew shears along the second axis, turning the first by the angle", "[rib]") {
    Messages messages;
    // RI 3.2's example: the y axis turns 45 degrees towards x.
    SceneDesc scene = Scene(InWorld("Skew 45 0 1 0 1 0 0\n" + kPatch), &messages);
    CHECK(messages.empty());
    REQUIRE(scene.primitives.size() == 1);
    const auto& corners = scene.primitives[0].base.patch().corners;
    CHECK(corners[1] == glm::dvec3(1, 0, 0));  // points on the second axis do not move
    CHECK(glm::length(corners[2] - glm::dvec3(1, 1, 0)) < 1e-15);
    CHECK(glm::length(corners[3] - glm::dvec3(2, 1, 0)) < 1e-15);
    // Axes 60 degrees apart, a turn of -30 degrees: the first axis ends 90 degrees from the second,
    // moved along it only (its part across the second axis stays).
    scene = Scene(InWorld("Skew -30 0.5 0.8660254037844386 0  2 0 0\n"
                          "Patch \"bilinear\" \"P\" [0 0 0  0.5 0.8660254037844386 0  0 0 1  1 0 0]\n"),
                  &messages);
    const glm::dvec3 d1 = scene.primitives[0].base.patch().corners[1];
    CHECK(std::abs(d1.x) < 1e-15);
    CHECK(std::abs(d1.y - 0.8660254037844386) < 1e-15);
    CHECK(scene.primitives[0].base.patch().corners[3] == glm::dvec3(1, 0, 0));

    CHECK(WorldError("Skew 45 0 1 0 0 2 0\n") == "t.rib:2: error: 'Skew' axes must be nonzero and not parallel");
    CHECK(WorldError("Skew 45 0 0 0 1 0 0\n") == "t.rib:2: error: 'Skew' axes must be nonzero and not parallel");
    CHECK(WorldError("Skew 90 0 1 0 1 0 0\n") ==
          "t.rib:2: error: 'Skew' angle must be less than the angle between the axes (90 degrees) and more than "
          "that angle minus 180, got 90");
    CHECK(WorldError("Skew -90 0 1 0 1 0 0\n") ==
          "t.rib:2: error: 'Skew' angle must be less than the angle between the axes (90 degrees) and more than "
          "that angle minus 180, got -90");
    CHECK(WorldError("Skew 45 0 1 0\n") ==
          "t.rib:2: error: 'Skew' expects 7 numbers (angle dx1 dy1 dz1 dx2 dy2 dz2), got 4");
}

TEST_CASE("rib: solids render their parts for unions and are skipped for intersections and differences", "[rib]") {
    Messages messages;
    SceneDesc scene = Scene(InWorld("SolidBegin \"primitive\"\n" + kPatch + "SolidEnd\nSolidBegin \"union\"\n" +
                                    "SolidBegin \"primitive\"\nSphere 1 -1 1 360\nSolidEnd\n" + kPatch +
                                    "SolidEnd\nSolidBegin \"union\"\nSolidEnd\n"),
                            &messages);
    CHECK(scene.primitives.size() == 3);
    CHECK(messages == Messages{"t.rib:5: note: 'SolidBegin \"union\"': the surfaces of the parts are rendered, which "
                               "shows the union of closed, opaque parts"});

    // A difference is skipped whole: its nested blocks, transforms, attributes and primitives;
    // what follows it renders with the state before it.
    scene = Scene(InWorld("SolidBegin \"difference\"\nColor 1 0 0\nTranslate 5 0 0\nSphere 1 -1 1 360\n"
                          "AttributeBegin\nSolidBegin \"intersection\"\nPoints \"P\" [0 0 0]\nFooBar\nSolidEnd\n"
                          "AttributeEnd\nSolidEnd\n" +
                          kPatch + "SolidBegin \"intersection\"\nSolidEnd\n"),
                  &messages);
    REQUIRE(scene.primitives.size() == 1);
    CHECK(scene.primitives[0].color == glm::dvec3(1));
    CHECK(scene.primitives[0].base.patch().corners[1] == glm::dvec3(1, 0, 0));
    CHECK(messages ==
          Messages{"t.rib:2: warning: 'SolidBegin \"difference\"' (constructive solid geometry) is not supported yet: "
                   "the solid is skipped",
                   "t.rib:14: warning: 'SolidBegin \"intersection\"' (constructive solid geometry) is not supported "
                   "yet: the solid is skipped"});

    CHECK(WorldError("SolidBegin \"xor\"\nSolidEnd\n") ==
          "t.rib:2: error: unknown solid operation 'xor' (expected \"primitive\", \"union\", \"intersection\" or "
          "\"difference\")");
    CHECK(WorldError("SolidBegin \"union\" \"x\"\nSolidEnd\n") ==
          "t.rib:2: error: 'SolidBegin' expects one string (the operation)");
    CHECK(WorldError("SolidBegin\n") == "t.rib:2: error: 'SolidBegin' expects a solid operation as its first argument");
    CHECK(WorldError("SolidEnd\n") == "t.rib:2: error: 'SolidEnd' without matching 'SolidBegin'");
    CHECK(WorldError("SolidBegin \"union\"\nAttributeBegin\nSolidEnd\n") ==
          "t.rib:4: error: 'SolidEnd' does not match 'AttributeBegin' on line 3");
    CHECK(WorldError("SolidBegin \"difference\"\nAttributeBegin\nSolidEnd\n") ==
          "t.rib:4: error: 'SolidEnd' does not match 'AttributeBegin' on line 3");
    CHECK(WorldError("SolidBegin \"union\"\n") == "t.rib:4: error: 'WorldEnd' does not match 'SolidBegin' on line 2");
    CHECK(FirstError("SolidBegin \"union\"\nSolidEnd\n") ==
          "t.rib:1: error: 'SolidBegin' must come between 'WorldBegin' and 'WorldEnd'");
    // In an object, a solid is a block of the object's own.
    CHECK(FirstError("ObjectBegin 1\nSolidBegin \"union\"\nObjectEnd\n") ==
          "t.rib:3: error: 'ObjectEnd' inside an 'AttributeBegin' or 'TransformBegin' of the object");
    scene = Scene("ObjectBegin 1\nSolidBegin \"union\"\n" + kPatch + "SolidEnd\nObjectEnd\n" +
                      InWorld("ObjectInstance 1\nObjectInstance 1\n"),
                  &messages);
    CHECK(scene.primitives.size() == 2);
}

TEST_CASE("rib: primitives affray cannot make are skipped with one warning per name", "[rib]") {
    Messages messages;
    const SceneDesc scene = Scene(InWorld("Blobby 1 [1001 0] [1 0 0 0  0 1 0 0  0 0 1 0  0 0 0 1] [\"\"]\n"
                                          "Geometry \"teapot\"\nGeometry \"sphere\"\n"
                                          "Volume \"box\" [0 1 0 1 0 1] [1 1 1]\n" +
                                          kPatch),
                                  &messages);
    CHECK(scene.primitives.size() == 1);
    CHECK(messages == Messages{
                          "t.rib:2: warning: 'Blobby' is not supported yet: skipped, so the image lacks these "
                          "primitives",
                          "t.rib:3: warning: 'Geometry' is not supported yet: skipped, so the image lacks these "
                          "primitives",
                          "t.rib:5: warning: 'Volume' is not supported yet: skipped, so the image lacks these "
                          "primitives",
                      });
    // Outside the world they are misplaced, as every primitive is.
    CHECK(FirstError("Curves \"linear\" [2] \"nonperiodic\" \"P\" [0 0 0 1 1 1]\n") ==
          "t.rib:1: error: 'Curves' must come between 'WorldBegin' and 'WorldEnd'");
}

TEST_CASE("rib: other renderers' requests warn once per name, unknown names are errors", "[rib]") {
    Messages messages;
    const SceneDesc scene = Scene(
        "Camera \"world\" \"float[2] shutteropening\" [0 1]\nDisplayChannel \"color Ci\"\n"
        "PixelVariance 0.01\nWorldBegin\nDeformation \"twist\" \"angle\" [30]\nDetailRange [0 0 10 20]\n" +
            kPatch + "DetailRange [10 20 1e38 1e38]\n" + kPatch +
            "Bxdf \"PxrDiffuse\" \"d\"\nShader \"noise\" \"n\"\nInterior \"water\"\n"
            "WorldEnd\n",
        &messages);
    // Without a Detail bound the detail is unbounded: only the level up to 1e38 is drawn.
    CHECK(scene.primitives.size() == 1);
    CHECK(messages ==
          Messages{
              "t.rib:1: warning: 'Camera' does not apply to affray; ignored",
              "t.rib:3: warning: 'PixelVariance' does not apply to affray; ignored",
              "t.rib:5: warning: 'Deformation' is not supported (deformation shaders are an optional RI 3.2 "
              "capability); ignored: the geometry is not deformed",
              "t.rib:6: warning: 'DetailRange' without a 'Detail' bound: its detail is taken as unbounded (the "
              "level whose maxvisible is infinite is drawn)",
              "t.rib:6: note: 'DetailRange' transitions are not dissolved: each level is drawn up to the middle of "
              "its transitions",
              "t.rib:10: warning: request 'Bxdf' is not supported yet; ignored",
              "t.rib:11: warning: request 'Shader' is not supported yet; ignored",
              "t.rib:12: warning: request 'Interior' is not supported yet; ignored",
          });
    CHECK(FirstError("WorldBegin\nSpehre 1 -1 1 360\nWorldEnd\n") == "t.rib:2: error: unknown RIB request 'Spehre'");
}

TEST_CASE("rib: Perspective before any camera transform is the camera's projection, elsewhere refused", "[rib]") {
    // The same camera as Projection "perspective" "fov" [40], over the default orthographic
    // projection or a given one, the transforms after it being the camera transform.
    Messages messages;
    const SceneDesc reference =
        Scene("Projection \"perspective\" \"fov\" [40]\nTranslate 0 0 5\nWorldBegin\nWorldEnd\n", &messages);
    for (const char* projection : {"", "Projection \"orthographic\"\n"}) {
        const SceneDesc scene =
            Scene(std::string(projection) + "Perspective 40\nTranslate 0 0 5\nWorldBegin\nWorldEnd\n", &messages);
        CHECK(scene.camera.perspective);
        CHECK(scene.camera.fovDegrees == 40);
        CHECK(scene.camera.worldToCamera == reference.camera.worldToCamera);
        CHECK(messages == Messages{"t.rib:" + std::string(*projection ? "2" : "1") +
                                   ": note: 'Perspective 40' before any other camera transform is the camera's "
                                   "projection: taken as 'Projection \"perspective\" \"fov\" [40]'"});
    }
    // Identity, Transform and the end of a TransformBegin block replace or restore it with the CTM:
    // the camera stays orthographic.
    for (const char* around :
         {"Perspective 40\nIdentity\n", "Perspective 40\nTransform [1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1]\n",
          "TransformBegin\nPerspective 40\nTransformEnd\n"})
        CHECK(!Scene(std::string(around) + "WorldBegin\nWorldEnd\n", &messages).camera.perspective);
    // A Projection after it makes it a screen transform, which is ignored with a warning.
    const SceneDesc screen =
        Scene("Perspective 40\nProjection \"perspective\" \"fov\" [30]\nWorldBegin\nWorldEnd\n", &messages);
    CHECK(screen.camera.fovDegrees == 30);
    CHECK(messages.back() ==
          "t.rib:2: warning: transforms before 'Projection' (screen transforms) are not supported; ignored");

    CHECK(FirstError("WorldBegin\nPerspective 40\nWorldEnd\n") ==
          "t.rib:2: error: 'Perspective 40' inside the world block makes the object transform projective (affray's "
          "transforms are affine); not supported");
    CHECK(FirstError("Rotate 10 0 1 0\nPerspective 40\nWorldBegin\nWorldEnd\n") ==
          "t.rib:2: error: 'Perspective 40' after other transforms makes the camera transform projective (affray's "
          "transforms are affine); not supported: give 'Projection \"perspective\" \"fov\" [40]' before the "
          "camera's transforms instead");
    CHECK(FirstError("Projection \"perspective\"\nPerspective 40\nWorldBegin\nWorldEnd\n") ==
          "t.rib:2: error: 'Perspective 40' after 'Projection \"perspective\"' composes two perspective "
          "transforms, a projective camera transform (affray's transforms are affine); not supported");
    CHECK(FirstError("Perspective 40\nPerspective 30\nWorldBegin\nWorldEnd\n") ==
          "t.rib:2: error: 'Perspective 30' after the 'Perspective' on line 1 composes two perspective "
          "transforms, a projective camera transform (affray's transforms are affine); not supported");
    CHECK(FirstError("Perspective 40\nCoordinateSystem \"lens\"\nWorldBegin\nWorldEnd\n") ==
          "t.rib:2: error: 'CoordinateSystem' after 'Perspective' on line 1 is placed in the projective space it "
          "makes (affray's transforms are affine); not supported: give it after 'WorldBegin', or 'Projection "
          "\"perspective\"' instead of 'Perspective'");
    CHECK(FirstError("Perspective 180\nWorldBegin\nWorldEnd\n") ==
          "t.rib:1: error: 'Perspective' fov must be between 0 and 180 degrees, got 180");
}

TEST_CASE("rib: a Display mode may name channels DisplayChannel, Declare or an inline type declares", "[rib]") {
    // RenderMan for Maya 21 and later: the beauty display with the denoiser's channels. affray's
    // own are kept under their names; the others are left out with a warning.
    Messages messages;
    const SceneDesc scene = Scene(
        "DisplayChannel \"color Ci\"\nDisplayChannel \"float a\"\nDisplayChannel \"color mse\" \"string filter\" "
        "\"gaussian\"\nDeclare \"albedo\" \"varying color\"\n"
        "Display \"beauty.exr\" \"openexr\" \"Ci,a,mse,albedo, color diffuse ,z\"\nWorldBegin\nWorldEnd\n",
        &messages);
    CHECK(scene.displayMode == "Ci,a,z");
    CHECK(messages == Messages{
                          "t.rib:3: warning: 'DisplayChannel' parameter 'filter' is not supported; ignored",
                          "t.rib:5: warning: 'Display' channel 'mse' is an output variable affray does not compute: "
                          "left out of the image",
                          "t.rib:5: warning: 'Display' channel 'albedo' is an output variable affray does not "
                          "compute: left out of the image",
                          "t.rib:5: warning: 'Display' channel 'diffuse' is an output variable affray does not "
                          "compute: left out of the image",
                      });
    // A channel declared nowhere is most often a typo; a mode of no channel affray has renders nothing.
    CHECK(FirstError("Display \"x.exr\" \"openexr\" \"rgba,mse\"\nWorldBegin\nWorldEnd\n") ==
          "t.rib:1: error: 'Display' mode 'rgba,mse' has an unknown channel group 'mse' (expected rgb, rgba, rgbz, "
          "rgbaz, r, g, b, a, z, Ci, Oi, Z, N, P, st, cost or err, or a channel declared by DisplayChannel, "
          "separated by commas)");
    CHECK(FirstError("DisplayChannel \"color mse\"\nDisplay \"x.exr\" \"openexr\" \"mse\"\nWorldBegin\nWorldEnd\n") ==
          "t.rib:2: error: 'Display' mode 'mse' has no channel affray computes");
    CHECK(FirstError("DisplayChannel \"  \"\nWorldBegin\nWorldEnd\n") ==
          "t.rib:1: error: 'DisplayChannel' needs a channel name");
}

TEST_CASE("rib: Option and Attribute \"Ri\" (RenderMan 21 and later) run as the requests they stand for", "[rib]") {
    Messages messages;
    const SceneDesc scene = Scene(
        "Option \"Ri\" \"int[2] FormatResolution\" [320 240] \"float FormatPixelAspectRatio\" [2] \"int Frame\" [7]\n"
        "Option \"Ri\" \"float[4] ScreenWindow\" [-2 2 -1 1] \"float[2] Clipping\" [0.5 100]\n"
        "Option \"Ri\" \"string PixelFilterName\" [\"box\"] \"float ExposureGamma\" [2.2]\n"
        "Option \"Ri\" \"int[2] PixelSamples\" [3 2] \"float[2] PixelFilterWidth\" [1 1.5]\n"
        "WorldBegin\n"
        "Attribute \"Ri\" \"int Sides\" [1] \"color Color\" [1 0 0] \"float ShadingRate\" [16]\n"
        "Attribute \"Ri\" \"color Opacity\" [0.5 0.5 0.5] \"string Orientation\" [\"inside\"]\n" +
            kPatch + "WorldEnd\n",
        &messages);
    const renderer::CameraDesc& c = scene.camera;
    CHECK(c.xres == 320);
    CHECK(c.yres == 240);
    CHECK(c.pixelAspect == 2);
    REQUIRE(c.screenWindow);
    CHECK(*c.screenWindow == glm::dvec4(-2, 2, -1, 1));
    CHECK(c.nearClip == 0.5);
    CHECK(c.farClip == 100);
    CHECK(c.xsamples == 3);
    CHECK(c.ysamples == 2);
    // Split requests take what the other parameter leaves out from the values in effect: the
    // second Option "Ri" gives the widths of the filter the first one named, and the gain stays 1.
    CHECK(c.filter.kind == renderer::FilterDesc::Kind::Box);
    CHECK(c.filter.xwidth == 1);
    CHECK(c.filter.ywidth == 1.5);
    CHECK(c.exposureGain == 1);
    CHECK(c.exposureGamma == 2.2);
    REQUIRE(scene.primitives.size() == 1);
    const renderer::PrimitiveDesc& p = scene.primitives[0];
    CHECK_FALSE(p.attr().twoSided);
    CHECK(p.attr().sceneTolerance == 2);  // 0.5 sqrt(16)
    CHECK(p.color == glm::dvec3(1, 0, 0));
    CHECK(p.opacity == glm::dvec3(0.5));
    CHECK(messages == Messages{"t.rib:6: note: 'ShadingRate' 16: the primitives that follow are certified to 2 "
                               "pixels, not 0.5 (unless --tolerance is given)"});
    // Another renderer's options and attributes under "Ri": one warning each; a value the request
    // refuses is refused with that request's message, at the parameter.
    Scene("Option \"Ri\" \"int bucketorder\" [1]\nWorldBegin\nAttribute \"Ri\" \"int Coolness\" [1]\nWorldEnd\n",
          &messages);
    CHECK(messages == Messages{"t.rib:1: warning: 'Option \"Ri\"' parameter 'bucketorder' does not apply to affray; "
                               "ignored",
                               "t.rib:3: warning: 'Attribute \"Ri\"' parameter 'Coolness' does not apply to affray; "
                               "ignored"});
    CHECK(FirstError("Option \"Ri\" \"float[4] CropWindow\" [0.5 0.2 0 1]\nWorldBegin\nWorldEnd\n") ==
          "t.rib:1: error: 'CropWindow' needs 0 <= xmin < xmax <= 1, got 0.5 0.2");
    CHECK(FirstError("WorldBegin\nAttribute \"Ri\" \"int Sides\" [3]\nWorldEnd\n").find("t.rib:2: error: 'Sides'") ==
          0);
}

TEST_CASE("rib: Points are spheres of their width around each point, with the point's colours", "[rib]") {
    Messages messages;
    const SceneDesc scene = Scene(
        InWorld("Translate 0 0 2\nOpacity [0.5 0.5 0.5]\n"
                "Points \"P\" [0 0 0  1 0 0  2 0 0  3 0 0] \"width\" [0.5 0 1 2] \"Cs\" [1 0 0  0 1 0  0 0 1  1 1 0]\n"
                "Points \"P\" [0 1 0] \"constantwidth\" [0.25] \"uniform color Os\" [0.2 0.3 0.4] \"N\" [0 0 1]\n"),
        &messages);
    // The width-0 point draws nothing; the others are spheres of radius width / 2 moved to P.
    REQUIRE(scene.primitives.size() == 4);
    const double radius[] = {0.25, 0.5, 1.0, 0.125};
    const glm::dvec3 centre[] = {{0, 0, 2}, {2, 0, 2}, {3, 0, 2}, {0, 1, 2}};
    const glm::dvec3 color[] = {{1, 0, 0}, {0, 0, 1}, {1, 1, 0}, {1, 1, 1}};
    for (size_t i = 0; i < 4; ++i) {
        INFO("point " << i);
        const renderer::BaseSurface& b = scene.primitives[i].base;
        REQUIRE(b.kind() == renderer::BaseSurface::Kind::Quadric);
        const renderer::PlacedQuadric& q = b.quadric();
        CHECK(q.quadric.kind == renderer::Quadric::Kind::Sphere);
        CHECK(q.quadric.radius == radius[i]);
        CHECK(glm::dvec3(q.objectToWorld[3]) == centre[i]);
        CHECK(scene.primitives[i].color == color[i]);
        CHECK(scene.primitives[i].opacity == (i < 3 ? glm::dvec3(0.5) : glm::dvec3(0.2, 0.3, 0.4)));
    }
    CHECK(messages ==
          Messages{"t.rib:4: note: 'Points' are drawn as spheres of their width (prman draws discs facing the camera)",
                   "t.rib:4: warning: 'Points': 1 point of width 0 or less drawn as nothing",
                   "t.rib:5: warning: 'Points' parameter 'N' is not supported yet; ignored"});
    CHECK(WorldError("Points \"P\" [0 0]") ==
          "t.rib:2: error: 'Points' parameter 'P' expects 3 numbers a point, got 2 numbers");
    CHECK(WorldError("Points \"constantwidth\" [1]") == "t.rib:2: error: 'Points' needs \"P\"");
    CHECK(WorldError("Points \"P\" [0 0 0  1 1 1] \"width\" [1 2 3]") ==
          "t.rib:2: error: 'Points' parameter 'width' expects 2 numbers (one a point) or 1, got 3");
    CHECK(WorldError("Points \"P\" [0 0 0  1 1 1] \"Cs\" [1 0 0  0 1 0  0 0 1]")
              .find("t.rib:2: error: 'Points' parameter 'Cs'") == 0);
}
