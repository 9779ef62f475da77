// tests/rib/primvars_test.cpp: the colour primitive variables "Cs" and "Os" (rib/primvars.cpp
// and the requests that read them) of every storage class on polygons, subdivision meshes,
// patches, patch meshes, quadrics and NuPatches: each primitive's colour, or its colour field
// over its own (u,v), at points where the values are known by hand. Vertex values given equal
// to the control points make the field the surface itself, which checks that they are carried
// through the surface's own basis (or refinement) as P is.
#include <catch2/catch.hpp>

#include "tests/rib/rib_test_util.h"

using namespace affray;
using renderer::BaseSurface;
using renderer::PrimitiveDesc;

namespace {

/// Cs (or Os) of `p` at (u, v) of its own parameters.
glm::dvec3 ColorAt(const PrimitiveDesc& p, double u, double v, bool opacity = false) {
    const auto& field = opacity ? p.opacityField : p.colorField;
    return field ? field->At(u, v) : (opacity ? p.opacity : p.color);
}

void RequireNear(const glm::dvec3& got, const glm::dvec3& want, double tolerance = 1e-12) {
    INFO("got " << renderer::ToString(got) << ", want " << renderer::ToString(want));
    REQUIRE(glm::length(got - want) <= tolerance);
}

/// The point of a primitive's surface at (u, v) of its own parameters (patches only).
glm::dvec3 SurfaceAt(const PrimitiveDesc& p, double u, double v) {
    switch (p.base.kind()) {
        case BaseSurface::Kind::BicubicPatch: return p.base.bicubic().At(u, v);
        case BaseSurface::Kind::RationalPatch: return p.base.rational().At(u, v);
        case BaseSurface::Kind::SubdivPatch: return p.base.subdiv().geometry.At(u, v);
        default: FAIL("not a patch"); return {};
    }
}

const glm::dvec3 kRed(1, 0, 0), kGreen(0, 1, 0), kBlue(0, 0, 1), kWhite(1, 1, 1);

}  // namespace

TEST_CASE("primvars: Cs of every storage class on polygons", "[rib][primvar]") {
    // A convex quad a b c d is the piece (a, b, d, c): u runs a -> b, v runs a -> d.
    const std::string quad = "Polygon \"P\" [0 0 0  1 0 0  1 1 0  0 1 0] ";
    SECTION("constant and the Color in effect") {
        CHECK(renderer::ElementPrimitives(test::ParseWorld("Color 0.5 0.5 0.5\n" + quad))[0].color == glm::dvec3(0.5));
        const PrimitiveDesc p =
            renderer::ElementPrimitives(test::ParseWorld(quad + "\"constant color Cs\" [1 0 0]"))[0];
        CHECK(p.color == kRed);
        CHECK_FALSE(p.colorField);
    }
    SECTION("varying and vertex: bilinear between the corners") {
        // "color Cs" (no class, so uniform) with a colour per vertex reads as varying, with a note.
        for (const char* storage : {"", "varying color ", "vertex color ", "color "}) {
            INFO(storage);
            const PrimitiveDesc p = renderer::ElementPrimitives(
                test::ParseWorld(quad + "\"" + storage + "Cs\" [1 0 0  0 1 0  0 0 1  1 1 1]"))[0];
            REQUIRE(p.colorField);
            RequireNear(ColorAt(p, 0, 0), kRed);
            RequireNear(ColorAt(p, 1, 0), kGreen);
            RequireNear(ColorAt(p, 1, 1), kBlue);
            RequireNear(ColorAt(p, 0, 1), kWhite);
            RequireNear(ColorAt(p, 0.5, 0.5), (kRed + kGreen + kBlue + kWhite) / 4.0);
        }
    }
    SECTION("uniform per face, facevarying per face corner, on a shared vertex") {
        // Two triangles sharing the edge 1-2: (0 1 2) and (2 1 3).
        const std::string mesh = "PointsPolygons [3 3] [0 1 2  2 1 3] \"P\" [0 0 0  1 0 0  0 1 0  1 1 0] ";
        const renderer::SceneDesc uniform = test::ParseWorld(mesh + "\"uniform color Cs\" [1 0 0  0 0 1]");
        REQUIRE(renderer::ElementPrimitives(uniform).size() == 2);
        CHECK(renderer::ElementPrimitives(uniform)[0].color == kRed);
        CHECK(renderer::ElementPrimitives(uniform)[1].color == kBlue);
        CHECK_FALSE(renderer::ElementPrimitives(uniform)[1].colorField);
        // Vertex 1 is green in the first face and white in the second. A triangle's piece is
        // (a, b, c, c): (0,0) is a, (1,0) is b, v = 1 is c.
        const renderer::SceneDesc facevarying =
            test::ParseWorld(mesh + "\"facevarying color Cs\" [1 0 0  0 1 0  0 0 1   0 0 1  1 1 1  1 0 0]");
        const PrimitiveDesc first = renderer::ElementPrimitives(facevarying)[0],
                            second = renderer::ElementPrimitives(facevarying)[1];
        RequireNear(ColorAt(first, 1, 0), kGreen);
        RequireNear(ColorAt(second, 1, 0), kWhite);
        RequireNear(ColorAt(first, 0.3, 1), kBlue);
        RequireNear(ColorAt(second, 0, 0), kBlue);
        RequireNear(ColorAt(second, 0.5, 1), kRed);
        // Os likewise, clamped to [0, 1] with a warning.
        diag::Report report;
        const renderer::SceneDesc os =
            test::ParseWorld(mesh + "\"vertex color Os\" [1 1 1  0 0 0  0.5 0.5 0.5  2 2 2]", &report);
        RequireNear(ColorAt(renderer::ElementPrimitives(os)[0], 0, 0, true), kWhite);
        RequireNear(ColorAt(renderer::ElementPrimitives(os)[0], 0.5, 0, true), glm::dvec3(0.5));
        RequireNear(ColorAt(renderer::ElementPrimitives(os)[1], 0.2, 1, true), kWhite);  // 2 clamped to 1
        CHECK(report.all().size() == 1);
    }
}

TEST_CASE("primvars: Cs and Os of every storage class on a subdivision mesh", "[rib][primvar]") {
    // A cube: every vertex extraordinary (valence 3), refined twice into 96 patches.
    const std::string cube =
        "SubdivisionMesh \"catmull-clark\" [4 4 4 4 4 4] [0 1 3 2  2 3 5 4  4 5 7 6  6 7 1 0  1 7 5 3  6 0 2 4] "
        "\"P\" [-1 -1 1  1 -1 1  -1 1 1  1 1 1  -1 1 -1  1 1 -1  -1 -1 -1  1 -1 -1] ";
    const std::string points = "[-1 -1 1  1 -1 1  -1 1 1  1 1 1  -1 1 -1  1 1 -1  -1 -1 -1  1 -1 -1]";
    SECTION("constant and uniform: each patch's colour, from its control face") {
        const renderer::SceneDesc c = test::ParseWorld(cube + "\"constant color Cs\" [0 1 0]");
        for (const PrimitiveDesc& p : renderer::ElementPrimitives(c)) CHECK(p.color == kGreen);
        const renderer::SceneDesc u =
            test::ParseWorld(cube + "\"uniform color Cs\" [0 0 0  0.2 0 0  0.4 0 0  0.6 0 0  0.8 0 0  1 0 0]");
        REQUIRE(renderer::ElementPrimitives(u).size() == 96);
        for (const PrimitiveDesc& p : renderer::ElementPrimitives(u)) {
            CHECK_FALSE(p.colorField);
            RequireNear(p.color, glm::dvec3(0.2 * p.base.subdiv().controlFace, 0, 0));
        }
    }
    SECTION("vertex: refined and evaluated as P is, so Cs = P gives the limit surface") {
        const renderer::SceneDesc s = test::ParseWorld(cube + "\"vertex color Cs\" " + points);
        for (const PrimitiveDesc& p : renderer::ElementPrimitives(s)) {
            REQUIRE(p.colorField);
            for (double u : {0.0, 0.3, 1.0})
                for (double v : {0.0, 0.6, 1.0}) RequireNear(ColorAt(p, u, v), SurfaceAt(p, u, v), 1e-12);
        }
    }
    SECTION("varying: bilinear over the control faces, so Cs = P stays on the cube's faces") {
        const renderer::SceneDesc s = test::ParseWorld(cube + "\"varying color Cs\" " + points);
        for (const PrimitiveDesc& p : renderer::ElementPrimitives(s)) {
            REQUIRE(p.colorField);
            const glm::dvec3 c = p.colorField->At(0.3, 0.7);
            const double largest = std::max({std::fabs(c.x), std::fabs(c.y), std::fabs(c.z)});
            CHECK(largest == Approx(1).margin(1e-12));
        }
    }
    SECTION("facevarying: per face corner, one colour per face here") {
        std::string values;
        for (int f = 0; f < 6; ++f)
            for (int k = 0; k < 4; ++k) values += " " + std::to_string(f / 5.0) + " 0 0";
        const renderer::SceneDesc s = test::ParseWorld(cube + "\"facevarying color Cs\" [" + values + "]");
        for (const PrimitiveDesc& p : renderer::ElementPrimitives(s))
            RequireNear(ColorAt(p, 0.4, 0.8), glm::dvec3(p.base.subdiv().controlFace / 5.0, 0, 0), 1e-12);
    }
    SECTION("bad counts and declarations are errors") {
        CHECK(test::WorldError(cube + "\"vertex color Cs\" [1 0 0  0 1 0]") ==
              "t.rib:2: error: 'SubdivisionMesh' parameter 'Cs' (vertex color) expects 8 colors (24 numbers), got 6 "
              "numbers");
        CHECK(test::WorldError(cube + "\"constant float Cs\" [1]") ==
              "t.rib:2: error: 'SubdivisionMesh' parameter 'Cs' must be a color (3 numbers a value), declared "
              "'constant float'");
    }
}

TEST_CASE("primvars: Cs on patches, patch meshes and quadrics", "[rib][primvar]") {
    const std::string bezier =
        "[0 0 0  1 0 0.5  2 0 0  3 0 0.2   0 1 0  1 1 1  2 1 0.3  3 1 0 "
        " 0 2 0.1  1 2 0  2 2 1  3 2 0   0 3 0  1 3 0.4  2 3 0  3 3 0.6]";
    SECTION("a bicubic patch: varying values bilinear, vertex ones in the patch's basis") {
        const PrimitiveDesc varying = renderer::ElementPrimitives(
            test::ParseWorld("Patch \"bicubic\" \"P\" " + bezier + " \"Cs\" [1 0 0  0 1 0  0 0 1  1 1 1]"))[0];
        RequireNear(ColorAt(varying, 1, 0), kGreen);
        RequireNear(ColorAt(varying, 0, 1), kBlue);
        for (const char* basis : {"bezier", "b-spline", "catmull-rom"}) {
            INFO(basis);
            const PrimitiveDesc p = renderer::ElementPrimitives(
                test::ParseWorld(std::string("Basis \"") + basis + "\" 1 \"" + basis +
                                 "\" 1\nPatch \"bicubic\" \"P\" " + bezier + " \"vertex color Cs\" " + bezier))[0];
            for (double u : {0.0, 0.25, 1.0})
                for (double v : {0.0, 0.5, 0.9}) RequireNear(ColorAt(p, u, v), SurfaceAt(p, u, v), 1e-12);
        }
        // Rational (Pw): vertex values weighted by w and divided by W, as P is.
        std::string pw = "[";
        for (int i = 0; i < 16; ++i) {
            const int row = i / 4;
            const double w = 1 + 0.25 * (i % 3);
            pw += " " + std::to_string((i % 4) * w) + " " + std::to_string(row * w) + " " +
                  std::to_string(0.1 * (i % 5) * w) + " " + std::to_string(w);
        }
        std::string cs = "[";
        for (int i = 0; i < 16; ++i)
            cs += " " + std::to_string(i % 4) + " " + std::to_string(i / 4) + " " + std::to_string(0.1 * (i % 5));
        const PrimitiveDesc r = renderer::ElementPrimitives(
            test::ParseWorld("Patch \"bicubic\" \"Pw\" " + pw + "] \"vertex color Cs\" " + cs + "]"))[0];
        REQUIRE(r.base.kind() == BaseSurface::Kind::RationalPatch);
        for (double u : {0.0, 0.4, 1.0})
            for (double v : {0.2, 0.7}) RequireNear(ColorAt(r, u, v), SurfaceAt(r, u, v), 1e-9);
    }
    SECTION("a bilinear patch mesh: uniform per patch, varying at the patches' corners") {
        const std::string mesh =
            "PatchMesh \"bilinear\" 3 \"nonperiodic\" 2 \"nonperiodic\" "
            "\"P\" [0 0 0  1 0 0  2 0 0  0 1 0  1 1 0  2 1 0] ";
        const renderer::SceneDesc u = test::ParseWorld(mesh + "\"uniform color Cs\" [1 0 0  0 0 1]");
        REQUIRE(renderer::ElementPrimitives(u).size() == 2);
        CHECK(renderer::ElementPrimitives(u)[1].color == kBlue);
        const renderer::SceneDesc v =
            test::ParseWorld(mesh + "\"Cs\" [1 0 0  0 1 0  0 0 1  1 1 1  0 0 0  0.5 0.5 0.5]");
        RequireNear(ColorAt(renderer::ElementPrimitives(v)[1], 0, 0), kGreen);
        RequireNear(ColorAt(renderer::ElementPrimitives(v)[1], 1, 0), kBlue);
        RequireNear(ColorAt(renderer::ElementPrimitives(v)[1], 0, 1), glm::dvec3(0.0));
        RequireNear(ColorAt(renderer::ElementPrimitives(v)[1], 1, 1), glm::dvec3(0.5));
        // Periodic in u: 3 patches, the last wrapping to the first column.
        const renderer::SceneDesc w = test::ParseWorld(
            "PatchMesh \"bilinear\" 3 \"periodic\" 2 \"nonperiodic\" \"P\" [0 0 0  1 0 0  2 0 0  0 1 0  1 1 0  2 1 0] "
            "\"Cs\" [1 0 0  0 1 0  0 0 1  1 1 1  0 0 0  0.5 0.5 0.5]");
        REQUIRE(renderer::ElementPrimitives(w).size() == 3);
        RequireNear(ColorAt(renderer::ElementPrimitives(w)[2], 0, 0), kBlue);
        RequireNear(ColorAt(renderer::ElementPrimitives(w)[2], 1, 0), kRed);
        CHECK(test::WorldError(mesh + "\"Cs\" [1 0 0  0 1 0]") ==
              "t.rib:2: error: 'PatchMesh \"bilinear\"' parameter 'Cs' (varying color) expects 6 colors (18 "
              "numbers), got 6 numbers");
        // One colour where the class needs more: the primitive's, with a warning.
        CHECK(renderer::ElementPrimitives(test::ParseWorld(mesh + "\"Cs\" [0 0 1]"))[1].color == kBlue);
    }
    SECTION("a bicubic patch mesh: varying values one more than the patches across") {
        std::string points, colors;
        for (int j = 0; j < 4; ++j)
            for (int i = 0; i < 7; ++i) points += " " + std::to_string(i) + " " + std::to_string(j) + " 0";
        const renderer::SceneDesc s = test::ParseWorld(
            "PatchMesh \"bicubic\" 7 \"nonperiodic\" 4 \"nonperiodic\" \"P\" [" + points +
            "] \"Cs\" [0 0 0  0.5 0 0  1 0 0  0 1 0  0.5 1 0  1 1 0]" + " \"vertex color Os\" [" + points + "]");
        REQUIRE(renderer::ElementPrimitives(s).size() == 2);
        RequireNear(ColorAt(renderer::ElementPrimitives(s)[1], 0, 0), glm::dvec3(0.5, 0, 0));
        RequireNear(ColorAt(renderer::ElementPrimitives(s)[1], 1, 1), glm::dvec3(1, 1, 0));
        // The vertex values through the bezier basis: clamped to [0, 1] as Os, at a corner.
        RequireNear(ColorAt(renderer::ElementPrimitives(s)[0], 0, 0, true), glm::dvec3(0.0));
    }
    SECTION("quadrics: one value, or four at the corners of (u,v)") {
        CHECK(
            renderer::ElementPrimitives(test::ParseWorld("Sphere 1 -1 1 360 \"constant color Cs\" [0 0 1]"))[0].color ==
            kBlue);
        CHECK(renderer::ElementPrimitives(test::ParseWorld("Disk 0 1 360 \"uniform color Cs\" [0 1 0]"))[0].color ==
              kGreen);
        for (const char* storage : {"varying", "vertex", "facevarying"}) {
            const PrimitiveDesc p = renderer::ElementPrimitives(test::ParseWorld(
                std::string("Torus 1 0.25 0 360 360 \"") + storage + " color Cs\" [1 0 0  0 1 0  0 0 1  1 1 1]"))[0];
            RequireNear(ColorAt(p, 1, 0), kGreen);
            RequireNear(ColorAt(p, 0.5, 0.5), glm::dvec3(0.5));
        }
        CHECK(test::WorldError("Sphere 1 -1 1 360 \"Cs\" [1 0 0  0 1 0]") ==
              "t.rib:2: error: 'Sphere' parameter 'Cs' (varying color) expects 4 colors (12 numbers), got 6 numbers");
    }
}

TEST_CASE("primvars: Cs on NuPatches, by span", "[rib][primvar]") {
    // Order 3 in u over 4 points (two spans), order 2 in v over 2 points.
    const std::string head = "NuPatch 4 3 [0 0 0 1 2 2 2] 0 2 2 2 [0 0 1 1] 0 1 ";
    const std::string points = "[0 0 0  1 0 1  2 0 0  3 0 1  0 1 0  1 1 1  2 1 0  3 1 1]";
    SECTION("vertex values through the NURBS basis; uniform per span; varying at the segments' corners") {
        const renderer::SceneDesc s = test::ParseWorld(head + "\"P\" " + points + " \"vertex color Cs\" " + points);
        REQUIRE(renderer::ElementPrimitives(s).size() == 2);
        for (const PrimitiveDesc& p : renderer::ElementPrimitives(s))
            for (double u : {0.0, 0.3, 1.0}) RequireNear(ColorAt(p, u, 0.5), SurfaceAt(p, u, 0.5), 1e-12);
        const renderer::SceneDesc u =
            test::ParseWorld(head + "\"P\" " + points + " \"uniform color Cs\" [1 0 0  0 1 0]");
        CHECK(renderer::ElementPrimitives(u)[0].color == kRed);
        CHECK(renderer::ElementPrimitives(u)[1].color == kGreen);
        const renderer::SceneDesc v =
            test::ParseWorld(head + "\"P\" " + points + " \"Cs\" [1 0 0  0 1 0  0 0 1  1 1 1  0 0 0  0.5 0.5 0.5]");
        RequireNear(ColorAt(renderer::ElementPrimitives(v)[1], 0, 0), kGreen);
        RequireNear(ColorAt(renderer::ElementPrimitives(v)[1], 1, 1), glm::dvec3(0.5));
        RequireNear(ColorAt(renderer::ElementPrimitives(v)[0], 0.5, 0), (kRed + kGreen) / 2.0);
    }
    SECTION("rational: vertex values weighted as the points are") {
        std::string pw = "[", cs = "[";
        const double w[8] = {1, 2, 1, 0.5, 1, 3, 1, 1};
        const double p[8][3] = {{0, 0, 0}, {1, 0, 1}, {2, 0, 0}, {3, 0, 1}, {0, 1, 0}, {1, 1, 1}, {2, 1, 0}, {3, 1, 1}};
        for (int i = 0; i < 8; ++i) {
            for (int k = 0; k < 3; ++k) pw += " " + std::to_string(p[i][k] * w[i]), cs += " " + std::to_string(p[i][k]);
            pw += " " + std::to_string(w[i]);
        }
        const renderer::SceneDesc s = test::ParseWorld(head + "\"Pw\" " + pw + "] \"vertex color Cs\" " + cs + "]");
        for (const PrimitiveDesc& q : renderer::ElementPrimitives(s))
            for (double u : {0.0, 0.3, 1.0}) RequireNear(ColorAt(q, u, 0.25), SurfaceAt(q, u, 0.25), 1e-12);
    }
    SECTION("facevarying is not defined on a NuPatch") {
        CHECK(test::WorldError(head + "\"P\" " + points + " \"facevarying color Cs\" [1 0 0]") ==
              "t.rib:2: error: 'NuPatch' parameter 'Cs': storage class 'facevarying' is not defined on a NuPatch");
    }
}

TEST_CASE("primvars: a declaration without a class takes the class its count fits", "[rib][primvar]") {
    // Uniform by RI 3.2, but exporters write "float[2] st" with a value per vertex: the first class
    // whose count fits (the standard variable's own first) is taken, with a note; a count no class
    // fits is an error, as before.
    const std::string quad = "Polygon \"P\" [0 0 0  1 0 0  1 1 0  0 1 0] ";
    diag::Report report;
    test::ParseWorld(quad + "\"float[2] st\" [0 0 1 0 1 1 0 1]", &report);
    REQUIRE(report.all().size() == 1);
    CHECK(test::ShortDiagnostic(report.all()[0]) ==
          "t.rib:2: note: 'Polygon' parameter 'st' is declared \"float[2]\" without a storage class, which means "
          "uniform, but has 8 numbers: read as varying");
    diag::Report quiet;
    test::ParseWorld(quad + "\"float[2] st\" [0 0]", &quiet);  // uniform: one value for the one face
    CHECK(quiet.all().empty());
    diag::Report blue;
    const PrimitiveDesc p = renderer::ElementPrimitives(test::ParseWorld(
        "PointsPolygons [4 4] [0 1 2 3 1 4 5 2] \"P\" [0 0 0 1 0 0 1 1 0 0 1 0 2 0 0 2 1 0] \"color Cs\" [0 0 1]",
        &blue))[1];
    CHECK(p.color == kBlue);  // one colour for two faces: constant
    CHECK(test::WorldError(quad + "\"float[2] st\" [0 0 1 0 1 1]") ==
          "t.rib:2: error: 'Polygon' parameter 'st' (float[2]) expects 1 value of 2 numbers, got 6 numbers");
}
