// tests/rib/resource_test.cpp: named attribute states (rib/resource.cpp). Resource "attributes"
// saves the graphics state and restores the subset asked for; ResourceBegin and ResourceEnd scope
// the names; other resource types are ignored with a warning.
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

const std::string kSphere = "Sphere 1 -1 1 360\n";

}  // namespace

TEST_CASE("rib: Resource saves the graphics state and restores the subset asked for", "[rib]") {
    const SceneDesc scene = ParseWorld(
        "Color 1 0 0\nSides 1\nTranslate 1 0 0\n"
        "Resource \"red\" \"attributes\" \"string operation\" \"save\"\n"
        "Color 0 1 0\nSides 2\nTranslate 0 2 0\n" +
        kSphere +
        // shading: the colour comes back, the sides and the transform stay
        "Resource \"red\" \"attributes\" \"string operation\" [\"restore\"] \"string subset\" [\"shading\"]\n" +
        kSphere +
        // two subsets at once
        "Resource \"red\" \"attributes\" \"string operation\" \"restore\" \"string subset\" "
        "\"geometrymodification,transform\"\n" +
        kSphere +
        // all, the default
        "Color 0 0 1\nSides 2\nIdentity\n"
        "Resource \"red\" \"attributes\" \"string operation\" \"restore\"\n" +
        kSphere);
    REQUIRE(scene.primitives.size() == 4);
    const auto& p = scene.primitives;
    CHECK(p[0].color == glm::dvec3(0, 1, 0));
    CHECK(p[0].attr().twoSided);
    CHECK(p[0].attr().objectToWorld[3] == glm::dvec4(1, 2, 0, 1));
    CHECK(p[1].color == glm::dvec3(1, 0, 0));
    CHECK(p[1].attr().twoSided);
    CHECK(p[1].attr().objectToWorld[3] == glm::dvec4(1, 2, 0, 1));
    CHECK(p[2].color == glm::dvec3(1, 0, 0));
    CHECK(!p[2].attr().twoSided);
    CHECK(p[2].attr().objectToWorld[3] == glm::dvec4(1, 0, 0, 1));
    CHECK(p[3].color == glm::dvec3(1, 0, 0));
    CHECK(!p[3].attr().twoSided);
    CHECK(p[3].attr().objectToWorld[3] == glm::dvec4(1, 0, 0, 1));
}

TEST_CASE("rib: Resource restores the lights that were on, outside the attribute stack", "[rib]") {
    // RenderMan for Maya's light linking: the default light list saved, changed, restored.
    const SceneDesc scene = ParseWorld(
        "LightSource \"pointlight\" 1\nLightSource \"pointlight\" 2\n"
        "Resource \"lights\" \"attributes\" \"string operation\" \"save\" \"string subset\" \"shading\"\n"
        "AttributeBegin\nIlluminate 2 0\n" +
        kSphere + "AttributeEnd\nIlluminate 1 0\n" + kSphere +
        "Resource \"lights\" \"attributes\" \"string operation\" \"restore\" \"string subset\" \"shading\"\n" +
        kSphere);
    REQUIRE(scene.primitives.size() == 3);
    CHECK(scene.primitives[0].attr().lights == std::optional<std::vector<int>>{{0}});
    CHECK(scene.primitives[1].attr().lights == std::optional<std::vector<int>>{{1}});
    CHECK(scene.primitives[2].attr().lights == std::optional<std::vector<int>>{{0, 1}});
}

TEST_CASE("rib: ResourceBegin and ResourceEnd scope the names saved", "[rib]") {
    CHECK(WorldError("Resource \"a\" \"attributes\" \"string operation\" \"save\"\nResourceBegin\n"
                     "Resource \"b\" \"attributes\" \"string operation\" \"save\"\n"
                     "Resource \"a\" \"attributes\" \"string operation\" \"restore\"\nResourceEnd\n"
                     "Resource \"a\" \"attributes\" \"string operation\" \"restore\"\n")
              .empty());
    CHECK(WorldError("ResourceBegin\nResource \"b\" \"attributes\" \"string operation\" \"save\"\nResourceEnd\n"
                     "Resource \"b\" \"attributes\" \"string operation\" \"restore\"\n") ==
          "t.rib:5: error: 'Resource' restores 'b', which no 'Resource' has saved");
    CHECK(WorldError("ResourceEnd\n") == "t.rib:2: error: 'ResourceEnd' without matching 'ResourceBegin'");
    CHECK(WorldError("ResourceBegin\n") == "t.rib:2: error: 'ResourceBegin' has no matching 'ResourceEnd'");
}

TEST_CASE("rib: Resource checks its arguments, and other types are ignored with a warning", "[rib]") {
    CHECK(WorldError("Resource \"a\"\n") ==
          "t.rib:2: error: 'Resource' expects a name, a resource type and parameters");
    CHECK(WorldError("Resource \"a\" \"attributes\" \"operation\" [1]\n") ==
          "t.rib:2: error: 'Resource' parameter 'operation' expects one string");
    CHECK(WorldError("Resource \"a\" \"attributes\"\n") ==
          "t.rib:2: error: 'Resource \"a\" \"attributes\"' needs \"string operation\" \"save\" or \"restore\"");
    CHECK(WorldError("Resource \"a\" \"attributes\" \"string operation\" \"save\"\n"
                     "Resource \"a\" \"attributes\" \"string operation\" \"restore\" \"string subset\" "
                     "\"shading,colour\"\n") ==
          "t.rib:3: error: 'Resource' subset 'colour' is unknown (expected shading, geometrymodification, "
          "geometrydefinition, hiding, visibility, transform or all, separated by commas)");
    diag::Report report;
    ParseWorld("Resource \"tex\" \"texture\" \"string filename\" \"a.tex\"\n", &report);
    REQUIRE(report.all().size() == 1);
    CHECK(ShortDiagnostic(report.all()[0]) ==
          "t.rib:2: warning: 'Resource' of type 'texture' is not supported; ignored");
}
