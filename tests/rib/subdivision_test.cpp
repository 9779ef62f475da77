// tests/rib/subdivision_test.cpp: the SubdivisionMesh request of the RIB reader (rib/subdivision.cpp):
// a mesh becomes patches in world space with its tags and "st", "N" is ignored with a warning,
// and wrong schemes, counts, indices and tags are errors at their place.
#include <catch2/catch.hpp>

#include <string>

#include "rib/rib.h"
#include "tests/rib/rib_test_util.h"
#include "tests/test_util.h"

using namespace affray::renderer;
using namespace affray::rib;
using namespace affray::test;

namespace {

const char* const kCube = "[4 4 4 4 4 4] [0 2 3 1 4 5 7 6 0 1 5 4 2 6 7 3 0 4 6 2 1 3 7 5]";
const char* const kCubeP = "\"P\" [-1 -1 -1 1 -1 -1 -1 1 -1 1 1 -1 -1 -1 1 1 -1 1 -1 1 1 1 1 1]";

}  // namespace

TEST_CASE("rib subdivision: SubdivisionMesh makes patches with its tags", "[rib][subdivision]") {
    SECTION("a cube: 16 patches per face, in world space") {
        const SceneDesc s = ParseWorld(std::string("Translate 0 0 5\nSubdivisionMesh \"catmull-clark\" ") + kCube +
                                       " " + kCubeP + "\n");
        REQUIRE(ElementPrimitives(s).size() == 96u);
        for (const PrimitiveDesc& p : ElementPrimitives(s)) {
            REQUIRE(p.base.kind() == BaseSurface::Kind::SubdivPatch);
            const glm::dvec3 c = p.base.subdiv().geometry.At(0.5, 0.5);
            CHECK(std::fabs(c.z - 5) < 1);
            CHECK(p.attr().line == 3);
        }
    }
    SECTION("tags: a hole, a crease, a corner, an unknown tag (warned about)") {
        affray::diag::Report report;
        const SceneDesc s = ParseWorld(std::string("SubdivisionMesh \"catmull-clark\" ") + kCube +
                                           " [\"hole\" \"crease\" \"corner\" \"bumpy\"] [1 0 2 1 1 1 0 0] [3 0 1 6] "
                                           "[2 10] " +
                                           kCubeP + " \"N\" [0 0 1 0 0 1 0 0 1 0 0 1 0 0 1 0 0 1 0 0 1 0 0 1]\n",
                                       &report);
        CHECK(ElementPrimitives(s).size() == 80u);
        int warnings = 0;
        for (const affray::diag::Diagnostic& d : report.all())
            if (d.severity == affray::diag::Severity::Warning) ++warnings;
        CHECK(warnings == 2);  // "bumpy" and "N"
    }
    SECTION("st by storage class") {
        for (const char* st :
             {"\"vertex float[2] st\" [0 0 1 0 0 1 1 1 0 0 1 0 0 1 1 1]", "\"st\" [0 0 1 0 0 1 1 1 0 0 1 0 0 1 1 1]",
              "\"facevarying float[2] st\" [0 0 1 0 1 1 0 1 0 0 1 0 1 1 0 1 0 0 1 0 1 1 0 1 0 0 1 0 1 1 0 1 0 0 1 0 1 "
              "1 0 "
              "1 0 0 1 0 1 1 0 1]"}) {
            INFO(st);
            const SceneDesc s =
                ParseWorld(std::string("SubdivisionMesh \"catmull-clark\" ") + kCube + " " + kCubeP + " " + st + "\n");
            REQUIRE(!ElementPrimitives(s).empty());
            for (const PrimitiveDesc& p : ElementPrimitives(s)) {
                CHECK(p.base.subdiv().hasST);
                double sv, tv;
                SubdivPatchST<double>(p.base.subdiv(), 0.5, 0.5, &sv, &tv);
                CHECK(sv >= -1e-9);
                CHECK(sv <= 1 + 1e-9);
                CHECK(tv >= -1e-9);
                CHECK(tv <= 1 + 1e-9);
            }
        }
    }
}

TEST_CASE("rib subdivision: HierarchicalSubdivisionMesh is the same mesh with string arguments", "[rib][subdivision]") {
    // The same tags as SubdivisionMesh, with three nargs a tag and a fifth array (stringargs);
    // a hierarchical edit (a tag that takes strings) is warned about and ignored.
    const std::string tags = " [\"hole\" \"crease\" \"corner\"] [1 0 2 1 1 1] [3 0 1 6] [2 10] ";
    const SceneDesc plain =
        ParseWorld(std::string("SubdivisionMesh \"catmull-clark\" ") + kCube + tags + kCubeP + "\n");
    const std::string htags =
        " [\"hole\" \"crease\" \"corner\" \"vertexedit\"] [1 0 0 2 1 0 1 1 0 2 1 2] [3 0 1 6 1 0] [2 10 0.5] "
        "[\"value\" \"add\"] ";
    affray::diag::Report report;
    const SceneDesc h = ParseWorld(
        std::string("HierarchicalSubdivisionMesh \"catmull-clark\" ") + kCube + htags + kCubeP + "\n", &report);
    REQUIRE(ElementPrimitives(h).size() == ElementPrimitives(plain).size());
    CHECK(ElementPrimitives(h).size() == 80u);
    for (size_t i = 0; i < ElementPrimitives(h).size(); ++i)
        CHECK(ElementPrimitives(h)[i].base.subdiv().geometry.At(0.3, 0.6) ==
              ElementPrimitives(plain)[i].base.subdiv().geometry.At(0.3, 0.6));
    REQUIRE(report.all().size() == 1);
    CHECK(ShortDiagnostic(report.all()[0]) ==
          "t.rib:2: warning: 'HierarchicalSubdivisionMesh' tag 'vertexedit' is not supported; ignored");
    CHECK(WorldError(std::string("HierarchicalSubdivisionMesh \"catmull-clark\" ") + kCube +
                     " [\"crease\"] [2 1] [0 1] [1] [] " + kCubeP + "\n") ==
          "t.rib:2: error: 'HierarchicalSubdivisionMesh' has 1 tags, so nargs needs 3 entries, got 2");
    CHECK(WorldError(std::string("HierarchicalSubdivisionMesh \"catmull-clark\" ") + kCube +
                     " [\"vertexedit\"] [0 0 1] [] [] [] " + kCubeP + "\n") ==
          "t.rib:2: error: 'HierarchicalSubdivisionMesh' nargs ask for more arguments than intargs, floatargs and "
          "stringargs hold (tag 'vertexedit')");
    CHECK(WorldError(std::string("HierarchicalSubdivisionMesh \"catmull-clark\" ") + kCube +
                     " [\"hole\"] [1 0 0] [3] [] " + kCubeP + "\n") ==
          "t.rib:2: error: 'HierarchicalSubdivisionMesh' expects an array of strings (stringargs) as argument 8, "
          "found string \"P\"");
}

TEST_CASE("rib subdivision: wrong meshes are errors at their place", "[rib][subdivision]") {
    const std::string cube = std::string(kCube) + " ";
    // Another scheme's mesh is skipped with a warning, as an unsupported primitive is.
    affray::diag::Report report;
    CHECK(ElementPrimitives(ParseWorld("SubdivisionMesh \"loop\" [3] [0 1 2] \"P\" [0 0 0 1 0 0 0 1 0]\n", &report))
              .empty());
    REQUIRE(report.all().size() == 1);
    CHECK(ShortDiagnostic(report.all()[0]) ==
          "t.rib:2: warning: 'SubdivisionMesh' scheme 'loop' is not supported (only \"catmull-clark\"): the mesh is "
          "skipped");
    CHECK(WorldError("SubdivisionMesh \"loop\" [3] [0 1 2] \"P\" [0 0 0 1 0 0 0 1 0]\n").empty());
    CHECK(WorldError("SubdivisionMesh \"catmull-clark\" [3 3] [0 1 2] \"P\" [0 0 0 1 0 0 0 1 0]\n") ==
          "t.rib:2: error: 'SubdivisionMesh' nvertices add up to 6 vertices, but the vertices array has 3");
    CHECK(WorldError("SubdivisionMesh \"catmull-clark\" [3] [0 1 7] \"P\" [0 0 0 1 0 0 0 1 0]\n") ==
          "t.rib:2: error: 'SubdivisionMesh' vertex index 7 is out of range ('P' has 3 points)");
    CHECK(WorldError("SubdivisionMesh \"catmull-clark\" [3] [0 1 2]\n") ==
          "t.rib:2: error: 'SubdivisionMesh' needs a \"P\" parameter");
    CHECK(WorldError("SubdivisionMesh \"catmull-clark\" [3] [0 1 2] \"Pw\" [0 0 0 1 1 0 0 1 0 1 0 2]\n") ==
          "t.rib:2: error: 'SubdivisionMesh' parameter 'Pw' has w = 2 at point 2: rational subdivision meshes are "
          "not supported");
    CHECK(WorldError("SubdivisionMesh \"catmull-clark\" " + cube + "[\"hole\"] [1 0] [6] [] " + kCubeP + "\n") ==
          "t.rib:2: error: 'SubdivisionMesh' tag 'hole' face index 6 is out of range (6 faces)");
    CHECK(WorldError("SubdivisionMesh \"catmull-clark\" " + cube + "[\"crease\"] [2 1] [0 7] [1] " + kCubeP + "\n") ==
          "t.rib:2: error: 'SubdivisionMesh' tag 'crease' joins vertices 0 and 7, which share no edge");
    CHECK(WorldError("SubdivisionMesh \"catmull-clark\" " + cube + "[\"crease\"] [2 0] [0 1] [] " + kCubeP + "\n") ==
          "t.rib:2: error: 'SubdivisionMesh' tag 'crease' expects at least 2 vertex indices and 1 sharpness, got 2 "
          "and 0");
    CHECK(WorldError("SubdivisionMesh \"catmull-clark\" " + cube + "[\"crease\"] [2] [0 1] [1] " + kCubeP + "\n") ==
          "t.rib:2: error: 'SubdivisionMesh' has 1 tags, so nargs needs 2 entries, got 1");
    CHECK(WorldError("SubdivisionMesh \"catmull-clark\" " + cube + "[\"corner\"] [3 1] [0 1] [1] " + kCubeP + "\n") ==
          "t.rib:2: error: 'SubdivisionMesh' nargs ask for more arguments than intargs and floatargs hold (tag "
          "'corner')");
    CHECK(WorldError("SubdivisionMesh \"catmull-clark\" [4 4] [0 1 2 3 0 1 2 3] \"P\" [0 0 0 1 0 0 1 1 0 0 1 0]\n") ==
          "t.rib:2: error: 'SubdivisionMesh' edge 0-1 is used twice in the same direction (a non-manifold edge, or "
          "faces of opposite orientation)");
    CHECK(WorldError("SubdivisionMesh \"catmull-clark\" " + cube + kCubeP + " \"st\" [0 0]\n") ==
          "t.rib:2: error: 'SubdivisionMesh' parameter 'st' (varying float[2]) expects 8 values of 2 numbers, got 2 "
          "numbers");
}
