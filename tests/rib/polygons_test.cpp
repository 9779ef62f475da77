// tests/rib/polygons_test.cpp: the polygon requests of the RIB reader (rib/polygons.cpp): Polygon,
// GeneralPolygon, PointsPolygons and PointsGeneralPolygons become mesh pieces in world space, with
// their primitive variables by storage class, and wrong counts or indices are errors with the line.
#include <catch2/catch.hpp>

#include <string>

#include "rib/rib.h"
#include "tests/rib/rib_test_util.h"
#include "tests/test_util.h"

using namespace affray::renderer;
using namespace affray::rib;
using namespace affray::test;

namespace {

MeshPiece PieceOf(const SceneDesc& scene, size_t i) {
    REQUIRE(i < ElementPrimitives(scene).size());
    REQUIRE(ElementPrimitives(scene)[i].base.kind() == BaseSurface::Kind::MeshPiece);
    return ElementPrimitives(scene)[i].base.piece();
}

}  // namespace

TEST_CASE("rib polygons: Polygon, GeneralPolygon, PointsPolygons, PointsGeneralPolygons make pieces",
          "[rib][polygons]") {
    SECTION("Polygon: a quad in world space, one piece") {
        const SceneDesc s = ParseWorld("Translate 0 0 2\nPolygon \"P\" [0 0 0  1 0 0  1 1 0  0 1 0]\n");
        REQUIRE(ElementPrimitives(s).size() == 1);
        const MeshPiece& p = PieceOf(s, 0);
        CHECK_FALSE(p.triangle);
        // Patch order: a, b, d, c.
        affray::test::RequireVec(p.P[0], {0, 0, 2});
        affray::test::RequireVec(p.P[1], {1, 0, 2});
        affray::test::RequireVec(p.P[2], {0, 1, 2});
        affray::test::RequireVec(p.P[3], {1, 1, 2});
        affray::test::RequireVec(p.faceNormal, {0, 0, 1});
        CHECK(ElementPrimitives(s)[0].attr().line == 3);
    }
    SECTION("GeneralPolygon with a hole") {
        const SceneDesc s =
            ParseWorld("GeneralPolygon [4 4] \"P\" [0 0 0  4 0 0  4 4 0  0 4 0   1 1 0  1 3 0  3 3 0  3 1 0]\n");
        CHECK(ElementPrimitives(s).size() == 8);
    }
    SECTION("PointsPolygons with vertex normals, facevarying st and uniform s") {
        const SceneDesc s = ParseWorld(
            "Scale 2 1 1\n"
            "PointsPolygons [3 3] [0 1 2  0 2 3] \"P\" [0 0 0  1 0 0  1 1 0  0 1 0]\n"
            "  \"N\" [0 0 1  1 0 1  0 0 1  0 0 1]\n"
            "  \"facevarying float[2] st\" [0 0 1 0 1 1  0 0 1 1 0 1]\n");
        REQUIRE(ElementPrimitives(s).size() == 2);
        const MeshPiece& p = PieceOf(s, 0);
        CHECK(p.triangle);
        CHECK(p.hasNormals);
        CHECK(p.hasST);
        affray::test::RequireVec(p.P[1], {2, 0, 0});
        // Normals carry to world by the inverse transpose: (1, 0, 1) scaled by x 2 leans by half.
        affray::test::RequireVec(p.N[1], {0.5, 0, 1});
        CHECK(p.st[1] == glm::dvec2(1, 0));
        CHECK(PieceOf(s, 1).st[1] == glm::dvec2(1, 1));
    }
    SECTION("PointsGeneralPolygons: a face with a hole beside a triangle, uniform and constant variables") {
        affray::diag::Report report;
        const SceneDesc s = ParseWorld(
            "PointsGeneralPolygons [2 1] [4 3 3] [0 1 2 3  4 5 6  0 7 1]\n"
            "  \"P\" [0 0 0  4 0 0  4 4 0  0 4 0  1 1 0  2 3 0  3 1 0  2 -2 0]\n"
            "  \"uniform float s\" [0.25 0.75] \"constant float t\" [0.5] \"Cs\" [1 0 0 0 1 0 0 0 1 1 1 1 0 0 0 "
            "1 0 0 0 1 0 0 0 1]\n",
            &report);
        CHECK(ElementPrimitives(s).size() == 8);  // 4 + 3 corners with a hole: 7 triangles; and the triangle
        const MeshPiece& last = PieceOf(s, 7);
        CHECK(last.face == 1);
        CHECK(last.st[0] == glm::dvec2(0.75, 0.5));
        CHECK(report.all().empty());
        // Cs by point: the triangle's corners 0 7 1 are red, blue and green.
        REQUIRE(ElementPrimitives(s)[7].colorField);
        CHECK(ElementPrimitives(s)[7].colorField->At(0, 0) == glm::dvec3(1, 0, 0));
        CHECK(ElementPrimitives(s)[7].colorField->At(0, 1) == glm::dvec3(0, 1, 0));
    }
}

TEST_CASE("rib polygons: wrong counts and indices are errors with the line", "[rib][polygons]") {
    CHECK(WorldError("Polygon \"P\" [0 0 0  1 0 0]\n") == "t.rib:2: error: 'Polygon' needs at least 3 points, got 2");
    CHECK(WorldError("Polygon \"P\" [0 0 0  1 0 0  1 1]\n") ==
          "t.rib:2: error: 'Polygon' parameter 'P' expects a multiple of 3 numbers, got 8");
    CHECK(WorldError("Polygon \"N\" [0 0 1]\n") == "t.rib:2: error: 'Polygon' needs a \"P\" parameter");
    CHECK(WorldError("\nPolygon \"P\" [0 0 0  1 0 0  1 1 0] \"N\" [0 0 1 0 0 1]\n") ==
          "t.rib:3: error: 'Polygon' parameter 'N' (varying normal) expects 3 values of 3 numbers, got 6 numbers");
    CHECK(WorldError("GeneralPolygon [3 3] \"P\" [0 0 0  1 0 0  1 1 0]\n") ==
          "t.rib:2: error: 'GeneralPolygon' has 6 vertices (by nverts) but 3 points in 'P'");
    CHECK(WorldError("PointsPolygons [3] [0 1 3] \"P\" [0 0 0  1 0 0  1 1 0]\n") ==
          "t.rib:2: error: 'PointsPolygons' vertex index 3 is out of range ('P' has 3 points)");
    CHECK(WorldError("PointsPolygons [3 3] [0 1 2] \"P\" [0 0 0  1 0 0  1 1 0]\n") ==
          "t.rib:2: error: 'PointsPolygons' nverts add up to 6 vertices, but the vertices array has 3");
    CHECK(WorldError("PointsPolygons [2] [0 1] \"P\" [0 0 0  1 0 0]\n") ==
          "t.rib:2: error: 'PointsPolygons' nverts must be integers of at least 3, got 2");
    CHECK(WorldError("PointsPolygons [3] [0 1 -2] \"P\" [0 0 0  1 0 0  1 1 0]\n") ==
          "t.rib:2: error: 'PointsPolygons' vertices must be integers of at least 0, got -2");
    CHECK(WorldError("PointsPolygons [3] [0 1 2] \"P\" [0 0 0  1 0 0  1 1 0] \"uniform float s\" [1 2]\n") ==
          "t.rib:2: error: 'PointsPolygons' parameter 's' (uniform float) expects 1 value of 1 number, got 2 numbers");
    CHECK(WorldError("PointsPolygons [3] [0 1 2] \"P\" [0 0 0  1 0 0  1 1 0] \"facevarying float[2] st\" [1 2]\n") ==
          "t.rib:2: error: 'PointsPolygons' parameter 'st' (facevarying float[2]) expects 3 values of 2 numbers, got "
          "2 numbers");
    CHECK(WorldError("Polygon \"P\" [0 0 0  1 0 0  1 1 0]\n"
                     "PointsGeneralPolygons [1 1] [3] [0 1 2] \"P\" [0 0 0  1 0 0  1 1 0]\n") ==
          "t.rib:3: error: 'PointsGeneralPolygons' nloops add up to 2 loops, but nverts has 1 entries");
    CHECK(WorldError("PointsPolygons [3] [0 1 2] \"P\" [0 0 0  1 1 1  2 2 2]\n") ==
          "t.rib:2: error: 'PointsPolygons' face 0 is degenerate: its outline has no area (its corners are "
          "collinear or coincide)");
    CHECK(WorldError("PointsPolygons [3] [0 1 2] \"P\" [0 0 0  1 0 0  0 1 0] \"N\" [0 0 1  0 0 0  0 0 1]\n") ==
          "t.rib:2: error: 'PointsPolygons' normal 1 is zero or not finite");
    CHECK(WorldError("PointsPolygons [3] \"P\" [0 0 0  1 0 0  0 1 0]\n") ==
          "t.rib:2: error: 'PointsPolygons' expects an array of integers vertices as argument 2");
}
