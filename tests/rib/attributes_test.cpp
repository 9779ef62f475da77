// tests/rib/attributes_test.cpp: which lights cast shadows and which primitives stop shadow and
// camera rays (rib/attributes.cpp): RenderMan's standard lights cast none; the shadow-map lights,
// a "shadowname" and BMRT's Attribute "light" "shadows" "on" turn them on; Attribute
// "visibility" (prman) and "render" (BMRT) set how primitives stop rays; Opacity sets Os. All of
// them attributes, restored by AttributeEnd.
#include <catch2/catch.hpp>

#include "tests/rib/rib_test_util.h"

using namespace affray;
using Transmission = renderer::PrimitiveDesc::Transmission;

namespace {

/// The castShadows of each light of `world`, in order.
std::vector<bool> LightShadows(const std::string& world, diag::Report* report = nullptr) {
    const renderer::SceneDesc scene = test::ParseWorld(world, report);
    std::vector<bool> out;
    for (const renderer::LightDesc& l : scene.lights) out.push_back(l.castShadows);
    return out;
}

/// The warnings of `world` as ShortDiagnostic gives them.
std::vector<std::string> Warnings(const std::string& world) {
    diag::Report report;
    test::ParseWorld(world, &report);
    std::vector<std::string> out;
    for (const diag::Diagnostic& d : report.all())
        if (d.severity == diag::Severity::Warning) out.push_back(test::ShortDiagnostic(d));
    return out;
}

const char* const kSphere = "Sphere 1 -1 1 360\n";

}  // namespace

TEST_CASE("attributes: the standard lights cast no shadows, Attribute \"light\" \"shadows\" turns them on",
          "[rib][shadow]") {
    const std::string lights =
        "LightSource \"ambientlight\" 1\nLightSource \"distantlight\" 2\nLightSource \"pointlight\" 3\n"
        "LightSource \"spotlight\" 4\n";
    CHECK(LightShadows(lights) == std::vector<bool>{false, false, false, false});
    CHECK(LightShadows("Attribute \"light\" \"shadows\" \"on\"\n" + lights) ==
          std::vector<bool>{true, true, true, true});
    // An attribute: "off" turns it off, AttributeEnd restores the block's value, and the inline
    // declaration Houdini writes is the same parameter.
    CHECK(LightShadows("Attribute \"light\" \"string shadows\" [\"on\"]\n"
                       "LightSource \"distantlight\" 1\n"
                       "AttributeBegin\nAttribute \"light\" \"shadows\" \"off\"\nLightSource \"distantlight\" 2\n"
                       "AttributeEnd\nLightSource \"distantlight\" 3\n") == std::vector<bool>{true, false, true});
    CHECK(LightShadows("AttributeBegin\nAttribute \"light\" \"shadows\" \"on\"\nAttributeEnd\n"
                       "LightSource \"pointlight\" 1\n") == std::vector<bool>{false});
}

TEST_CASE("attributes: shadow-map lights and shadownames cast shadows, empty map names do not", "[rib][shadow]") {
    // A shadow-map light without a map name reads none (RenderMan's default name is ""): no
    // shadows, as from prman, unless the attribute asks for them.
    CHECK(LightShadows("LightSource \"shadowspot\" 1\nLightSource \"shadowpoint\" 2\n"
                       "LightSource \"shadowdistant\" 3 \"shadowname\" \"sun.tex\"\n"
                       "Attribute \"light\" \"shadows\" \"on\"\nLightSource \"shadowspot\" 4\n") ==
          std::vector<bool>{false, false, true, true});
    // A file or "raytrace" (BMRT's and later prman's traced shadows) both mean shadows.
    CHECK(LightShadows("LightSource \"spotlight\" 1 \"shadowname\" \"key.tex\"\n"
                       "LightSource \"distantlight\" 2 \"shadowname\" \"raytrace\"\n") ==
          std::vector<bool>{true, true});
    // RenderMan's default "": no map is read, so no shadow; the attribute still turns them on.
    CHECK(LightShadows("LightSource \"shadowspot\" 1 \"shadowname\" \"\"\n"
                       "LightSource \"spotlight\" 2 \"shadowname\" \"\"\n"
                       "LightSource \"shadowpoint\" 3 \"sfpx\" \"\" \"sfnx\" \"\"\n"
                       "LightSource \"shadowpoint\" 4 \"sfpx\" \"\" \"sfnx\" \"nx.tex\"\n"
                       "Attribute \"light\" \"shadows\" \"on\"\n"
                       "LightSource \"shadowspot\" 5 \"shadowname\" \"\"\n") ==
          std::vector<bool>{false, false, false, true, true});
}

TEST_CASE("attributes: transmission and camera visibility, prman's and BMRT's", "[rib][shadow]") {
    auto primitive = [](const std::string& attributes) {
        const renderer::SceneDesc scene = test::ParseWorld(attributes + kSphere);
        REQUIRE(scene.primitives.size() == 1);
        return scene.primitives[0];
    };
    auto transmission = [&](const std::string& attributes) { return primitive(attributes).attr().transmission; };
    CHECK(transmission("") == Transmission::Opaque);  // BMRT's default: every object casts shadows
    CHECK(transmission("Attribute \"visibility\" \"transmission\" \"transparent\"\n") == Transmission::Transparent);
    CHECK(transmission("Attribute \"visibility\" \"string transmission\" [\"opaque\"]\n") == Transmission::Opaque);
    CHECK(transmission("Attribute \"visibility\" \"transmission\" \"Os\"\n") == Transmission::Opacity);
    CHECK(transmission("Attribute \"visibility\" \"transmission\" \"shader\"\n") == Transmission::Opacity);
    CHECK(transmission("Attribute \"visibility\" \"int transmission\" [0]\n") == Transmission::Transparent);
    CHECK(transmission("Attribute \"visibility\" \"int transmission\" [1]\n") == Transmission::Opacity);
    CHECK(transmission("Attribute \"render\" \"casts_shadows\" \"none\"\n") == Transmission::Transparent);
    CHECK(transmission("Attribute \"render\" \"casts_shadows\" \"opaque\"\n") == Transmission::Opaque);
    CHECK(transmission("Attribute \"render\" \"casts_shadows\" \"Os\"\n") == Transmission::Opacity);
    CHECK(transmission("Attribute \"render\" \"casts_shadows\" \"shade\"\n") == Transmission::Opacity);
    // BMRT's visibility bits: 1 camera, 4 shadow rays.
    CHECK(transmission("Attribute \"render\" \"visibility\" [3]\n") == Transmission::Transparent);
    CHECK(transmission("Attribute \"render\" \"visibility\" [3]\nAttribute \"render\" \"visibility\" [7]\n") ==
          Transmission::Opaque);
    CHECK_FALSE(primitive("Attribute \"render\" \"visibility\" [4]\n").attr().cameraVisible);
    CHECK_FALSE(primitive("Attribute \"visibility\" \"int camera\" [0]\n").attr().cameraVisible);
    CHECK(primitive("Attribute \"visibility\" \"camera\" [0]\nAttribute \"visibility\" \"camera\" [1]\n")
              .attr()
              .cameraVisible);
    // Attributes: restored by AttributeEnd.
    const renderer::SceneDesc scene = test::ParseWorld(
        "AttributeBegin\nAttribute \"visibility\" \"transmission\" \"transparent\"\n"
        "Attribute \"visibility\" \"camera\" [0]\nOpacity 0.5 0.5 0.5\nSphere 1 -1 1 360\nAttributeEnd\n" +
        std::string(kSphere));
    REQUIRE(scene.primitives.size() == 2);
    CHECK(scene.primitives[0].attr().transmission == Transmission::Transparent);
    CHECK_FALSE(scene.primitives[0].attr().cameraVisible);
    CHECK(scene.primitives[0].opacity == glm::dvec3(0.5));
    CHECK(scene.primitives[1].attr().transmission == Transmission::Opaque);
    CHECK(scene.primitives[1].attr().cameraVisible);
    CHECK(scene.primitives[1].opacity == glm::dvec3(1.0));
    // The scene's description prints them.
    const std::string text = renderer::ToString(scene.primitives[0]);
    CHECK(text.find(" transmission=transparent camera=0 ") != std::string::npos);
    CHECK(text.find(" opacity=[0.5 0.5 0.5] ") != std::string::npos);
}

TEST_CASE("attributes: unknown values and parameters of these attributes are warned about and ignored",
          "[rib][shadow]") {
    CHECK(Warnings("Attribute \"light\" \"shadows\" \"maybe\"\n") ==
          std::vector<std::string>{
              "t.rib:2: warning: 'Attribute \"light\" \"shadows\"' takes \"on\" or \"off\", got \"maybe\"; ignored"});
    CHECK(Warnings("Attribute \"visibility\" \"int transmission\" [2]\n") ==
          std::vector<std::string>{"t.rib:2: warning: 'Attribute \"visibility\" \"transmission\"' takes \"opaque\", "
                                   "\"Os\", \"shader\", \"transparent\", 1 or 0, got 2; ignored"});
    CHECK(Warnings("Attribute \"visibility\" \"int diffuse\" [1]\n") ==
          std::vector<std::string>{
              "t.rib:2: warning: 'Attribute \"visibility\"' parameter 'diffuse' does not apply to affray; ignored"});
    // An ignored value leaves the attribute as it was.
    const renderer::SceneDesc scene = test::ParseWorld(
        "Attribute \"render\" \"casts_shadows\" \"none\"\n"
        "Attribute \"render\" \"casts_shadows\" \"sometimes\"\n" +
        std::string(kSphere));
    CHECK(scene.primitives[0].attr().transmission == Transmission::Transparent);
    // Opacity outside [0, 1] is clamped, with a warning.
    CHECK(Warnings("Opacity 1.5 0.5 -1\n") ==
          std::vector<std::string>{"t.rib:2: warning: 'Opacity' components must be from 0 to 1; clamped"});
    CHECK(test::ParseWorld("Opacity 1.5 0.5 -1\n" + std::string(kSphere)).primitives[0].opacity ==
          glm::dvec3(1, 0.5, 0));
}

TEST_CASE("attributes: TextureCoordinates give the s, t of the quadrics and patches that follow", "[rib][st]") {
    diag::Report report;
    const renderer::SceneDesc scene = test::ParseWorld(
        "Sphere 1 -1 1 360\n"
        "AttributeBegin\n"
        "  TextureCoordinates 1 0 0 0 1 1 0 1\n"
        "  Patch \"bilinear\" \"P\" [0 0 0  1 0 0  0 1 0  1 1 0]\n"
        "  Sphere 1 -1 1 360\n"
        "  PointsPolygons [3] [0 1 2] \"P\" [0 0 0  1 0 0  0 1 0]\n"
        "  TextureCoordinates [0 0 1 0 0 1 1 1]\n"  // the default again
        "  Sphere 1 -1 1 360\n"
        "AttributeEnd\n"
        "Sphere 1 -1 1 360\n",
        &report);
    INFO(report);
    CHECK(report.all().empty());
    REQUIRE(scene.primitives.size() == 6);
    const std::array<double, 8> flipped = {1, 0, 0, 0, 1, 1, 0, 1};
    CHECK_FALSE(scene.primitives[0].base.textureCoordinates);
    for (size_t i : {1, 2, 3}) {
        REQUIRE(scene.primitives[i].base.textureCoordinates);
        CHECK(*scene.primitives[i].base.textureCoordinates == flipped);
    }
    CHECK_FALSE(scene.primitives[4].base.textureCoordinates);
    CHECK_FALSE(scene.primitives[5].base.textureCoordinates);  // AttributeEnd restored none
    CHECK(test::FirstError(test::InWorld("TextureCoordinates 0 0 1 0\n")) ==
          "t.rib:2: error: 'TextureCoordinates' expects 8 numbers (s1 t1 s2 t2 s3 t3 s4 t4), got 4");
}
