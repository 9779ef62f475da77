// tests/rib/nurbs_test.cpp: the RIB reader's NuPatch, TrimCurve and rational patches
// (rib/nurbs.cpp, rib/geometry.cpp): spans as primitives with their (u,v) ranges, texture
// coordinates by storage class, trim curves as attribute state (and the spans they remove), and
// the errors of each, at their line.
#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include "rib/rib.h"
#include "tests/rib/rib_test_util.h"
#include "tests/test_util.h"

using namespace affray::renderer;
using namespace affray::rib;
using namespace affray::test;
using Catch::Matchers::Contains;

namespace {

std::vector<PrimitiveDesc> Primitives(const std::string& world) { return ParseWorld(world).primitives; }

/// A 4 x 3 control grid "P" of a bicubic-by-quadratic NuPatch over knots [0 0 0 0 1 1 1 1] (u,
/// 1 span) x [0 0 0 0.5 1 1 1]... as text.
const std::string kGridP =
    "\"P\" [0 0 0  1 0 0.2  2 0 0  3 0 0.1   0 1 0.3  1 1 0  2 1 0.4  3 1 0   0 2 0  1 2 0.1  2 2 0  3 2 0.2]";

/// The quarter of a unit circle (u) swept along z (v): rational.
const std::string kQuarter =
    "NuPatch 3 3 [0 0 0 1 1 1] 0 1 2 2 [0 0 1 1] 0 1 \"Pw\" [1 0 0 1  0.7071067811865476 0.7071067811865476 0 "
    "0.7071067811865476  0 1 0 1   1 0 1 1  0.7071067811865476 0.7071067811865476 0.7071067811865476 "
    "0.7071067811865476  0 1 1 1]";

}  // namespace

TEST_CASE("rib nurbs: a NuPatch becomes one rational patch per knot span, on the knot parameters", "[rib][nurbs]") {
    // u: order 4, 4 points, one span [0, 1]; v: order 2, 3 points, knots [0 0 0.5 1 1]: two spans.
    std::vector<PrimitiveDesc> prims = Primitives("NuPatch 4 4 [0 0 0 0 1 1 1 1] 0 1 3 2 [0 0 0.5 1 1] 0 1 " + kGridP);
    REQUIRE(prims.size() == 2);
    for (const PrimitiveDesc& p : prims) {
        CHECK(p.base.kind() == BaseSurface::Kind::RationalPatch);
        CHECK_FALSE(p.base.rational().rational);
        CHECK(p.base.rational().degreeU == 3);
        CHECK(p.base.rational().degreeV == 1);
        CHECK(p.attr().line == 2);
    }
    CHECK(prims[0].base.range.v0 == 0);
    CHECK(prims[0].base.range.v1 == 0.5);
    CHECK(prims[1].base.range.v0 == 0.5);
    // Bezier ends interpolate the corners: (0, 0, 0) at u = v = 0 and (3, 2, 0.2) at u = v = 1.
    affray::test::RequireVec(prims[0].base.rational().At(0, 0), {0, 0, 0});
    affray::test::RequireVec(prims[1].base.rational().At(1, 1), {3, 2, 0.2});
    // The middle row is interpolated at v = 0.5 (order 2).
    affray::test::RequireVec(prims[0].base.rational().At(0, 1), {0, 1, 0.3});

    // Clipped by umin umax vmin vmax: the ranges are the clipped knot parameters.
    prims = Primitives("NuPatch 4 4 [0 0 0 0 1 1 1 1] 0.25 0.75 3 2 [0 0 0.5 1 1] 0.6 1 " + kGridP);
    REQUIRE(prims.size() == 1);
    CHECK(prims[0].base.range.u0 == 0.25);
    CHECK(prims[0].base.range.u1 == 0.75);
    CHECK(prims[0].base.range.v0 == 0.6);

    // Rational: a quarter cylinder of radius 1, placed by the current transform.
    prims = Primitives("Translate 0 0 5\n" + kQuarter);
    REQUIRE(prims.size() == 1);
    CHECK(prims[0].base.rational().rational);
    const glm::dvec3 mid = prims[0].base.rational().At(0.5, 0.5);
    CHECK(std::hypot(mid.x, mid.y) == Approx(1).margin(1e-15));
    CHECK(mid.z == Approx(5.5));
}

TEST_CASE("rib nurbs: texture coordinates of every storage class", "[rib][nurbs]") {
    const std::string patch = "NuPatch 4 4 [0 0 0 0 1 1 1 1] 0 1 3 2 [0 0 0.5 1 1] 0 1 " + kGridP;
    // varying: one per segment corner, 2 x 3 here.
    std::vector<PrimitiveDesc> prims = Primitives(patch + " \"st\" [0 0  1 0  0 5  1 5  0 10  1 10]");
    REQUIRE(prims.size() == 2);
    REQUIRE(prims[1].base.rational().hasST);
    double s, t;
    RationalST<double>(prims[1].base.rational(), 0.5, 0.5, &s, &t);
    CHECK(s == Approx(0.5));
    CHECK(t == Approx(7.5));
    // uniform: one per segment (1 x 2); "s" and "t" given apart.
    prims = Primitives(patch + " \"uniform float s\" [3 4] \"uniform float t\" [7 8]");
    RationalST<double>(prims[1].base.rational(), 0.2, 0.9, &s, &t);
    CHECK(s == 4);
    CHECK(t == 8);
    // vertex: interpolated like P.
    prims = Primitives(patch + " \"vertex float[2] st\" [0 0 1 0 2 0 3 0  0 1 1 1 2 1 3 1  0 2 1 2 2 2 3 2]");
    RationalST<double>(prims[0].base.rational(), 0.0, 1.0, &s, &t);
    CHECK(s == Approx(0).margin(1e-15));
    CHECK(t == Approx(1));
}

TEST_CASE("rib nurbs: TrimCurve is attribute state that cuts the NuPatches after it", "[rib][nurbs]") {
    // A square hole [0.3, 0.7]^2 as one order-2 loop, on a NuPatch of 3 x 3 spans over [0, 3]^2.
    const std::string square =
        "NuPatch 4 2 [0 0 1 2 3 3] 0 3 4 2 [0 0 1 2 3 3] 0 3 \"P\" [0 0 0 1 0 0 2 0 0 3 0 0  0 1 0 1 1 0 2 1 0 3 1 0 "
        " 0 2 0 1 2 0 2 2 0 3 2 0  0 3 0 1 3 0 2 3 0 3 3 0]";
    const std::string hole =
        "TrimCurve [1] [2] [0 0 1 2 3 4 4] [0] [4] [5] [1.2 1.8 1.8 1.2 1.2] [1.2 1.2 1.8 1.8 1.2] "
        "[1 1 1 1 1]";
    std::vector<PrimitiveDesc> prims =
        Primitives("AttributeBegin\n" + hole + "\nAttribute \"trimcurve\" \"sense\" \"outside\"\n" + square +
                   "\nAttributeEnd\n" + square);
    // With the sense "outside" the hole lies inside the middle span: all 9 spans stay, trimmed;
    // after AttributeEnd the next NuPatch is untrimmed.
    REQUIRE(prims.size() == 18);
    REQUIRE(prims[4].base.trim);
    CHECK_FALSE(prims[4].base.trim->keepInside);
    CHECK_FALSE(prims[4].base.trim->KeptP(1.5, 1.5));
    CHECK(prims[4].base.trim->KeptP(1.1, 1.5));
    CHECK_FALSE(prims[9].base.trim);
    // With the default sense "inside" only the middle span holds kept surface.
    prims = Primitives(hole + "\n" + square);
    REQUIRE(prims.size() == 1);
    CHECK(prims[0].base.range.u0 == 1);
    CHECK(prims[0].base.range.v0 == 1);
    // The C binding's leading nloops is accepted; empty arrays remove the trim.
    prims = Primitives(
        "TrimCurve 1 [1] [2] [0 0 1 2 3 4 4] [0] [4] [5] [1.2 1.8 1.8 1.2 1.2] [1.2 1.2 1.8 1.8 1.2] "
        "[1 1 1 1 1]\n" +
        square + "\nTrimCurve [] [] [] [] [] [] [] [] []\n" + square);
    CHECK(prims.size() == 10);
}

TEST_CASE("rib nurbs: rational Patch and PatchMesh", "[rib][nurbs]") {
    std::vector<PrimitiveDesc> prims = Primitives(
        "Patch \"bilinear\" \"Pw\" [2 0 0 2  1 0 0 1  0 1 0 1  1 1 0 1]\n"
        "Patch \"bicubic\" \"Pw\" [0 0 0 1  1 0 0 1  2 0 0 1  3 0 0 1  0 1 0 1  2 2 0 2  2 1 0 1  3 1 0 1 "
        "0 2 0 1  1 2 0 1  2 2 0 1  3 2 0 1  0 3 0 1  1 3 0 1  2 3 0 1  3 3 0 1]\n"
        "PatchMesh \"bilinear\" 2 \"nonperiodic\" 2 \"nonperiodic\" \"Pw\" [0 0 0 1  2 0 0 2  0 1 0 1  1 1 0 1]\n"
        "Patch \"bilinear\" \"Pw\" [0 0 0 1  1 0 0 1  0 1 0 1  1 1 0 1]");
    REQUIRE(prims.size() == 4);
    CHECK(prims[0].base.kind() == BaseSurface::Kind::RationalPatch);
    // The corners are the points x / w; between them the weights pull the patch.
    affray::test::RequireVec(prims[0].base.rational().At(0, 0), {1, 0, 0});
    affray::test::RequireVec(prims[0].base.rational().At(1, 1), {1, 1, 0});
    // At s = 0.5, t = 0: (2 * 1 * 0.5 + ...) / (2 * 0.5 + 1 * 0.5): (w0 P0 + w1 P1) / (w0 + w1).
    affray::test::RequireVec(prims[0].base.rational().At(0.5, 0), {1, 0, 0});
    CHECK(prims[1].base.kind() == BaseSurface::Kind::RationalPatch);
    CHECK(prims[1].base.rational().rational);
    CHECK(prims[2].base.kind() == BaseSurface::Kind::RationalPatch);
    // Every w = 1: the bilinear fast path.
    CHECK(prims[3].base.kind() == BaseSurface::Kind::BilinearPatch);
}

TEST_CASE("rib nurbs: bad knots, orders, counts, ranges and weights are errors at their line", "[rib][nurbs]") {
    const std::string p4 = "\"P\" [0 0 0 1 0 0 0 1 0 1 1 0]";
    CHECK(WorldError("NuPatch 2 2 [0 1 0 1] 0 1 2 2 [0 0 1 1] 0 1 " + p4) ==
          "t.rib:2: error: 'NuPatch': the u knot vector decreases at knot 2 (1 then 0)");
    CHECK(WorldError("NuPatch 2 2 [0 0 1 1 1] 0 1 2 2 [0 0 1 1] 0 1 " + p4) ==
          "t.rib:2: error: 'NuPatch': the u knot vector needs n + order = 4 knots, got 5");
    CHECK(WorldError("NuPatch 2 3 [0 0 0 1 1] 0 1 2 2 [0 0 1 1] 0 1 " + p4) ==
          "t.rib:2: error: 'NuPatch': the u direction has 2 control points, fewer than its order 3");
    CHECK(WorldError("NuPatch 2 2 [0 0 1 1] 0 1 2 12 [0 0 1 1] 0 1 " + p4) ==
          "t.rib:2: error: 'NuPatch': the v order must be 2 to 11 (degree 1 to 10), got 12");
    CHECK(WorldError("NuPatch 2 1 [0 0 1] 0 1 2 2 [0 0 1 1] 0 1 " + p4) ==
          "t.rib:2: error: 'NuPatch': the u order must be 2 to 11 (degree 1 to 10), got 1");
    CHECK(WorldError("NuPatch 2 2 [0 0 1 1] 0 1.5 2 2 [0 0 1 1] 0 1 " + p4) ==
          "t.rib:2: error: 'NuPatch': the u range umin 0, umax 1.5 must be increasing and within the knots' parameter "
          "range [0, 1]");
    CHECK(
        WorldError("NuPatch 2 2 [0 0 1 1] 0 1 2 2 [0 0 1 1] 0.5 0.5 " + p4) ==
        "t.rib:2: error: 'NuPatch': the v range vmin 0.5, vmax 0.5 must be increasing and within the knots' parameter "
        "range [0, 1]");
    CHECK(WorldError("NuPatch 2 2 [0 0 1 1] 0 1 2 2 [0 0 1 1] 0 1 \"P\" [0 0 0 1 0 0]") ==
          "t.rib:2: error: 'NuPatch' parameter 'P' expects 12 numbers, got 6");
    CHECK(WorldError("NuPatch 2 2 [0 0 1 1] 0 1 2 2 [0 0 1 1] 0 1 \"Pw\" [0 0 0 1 1 0 0 1 0 1 0 0 1 1 0 1]") ==
          "t.rib:2: error: 'NuPatch' parameter 'Pw': point 2 has w = 0; NURBS weights must be positive");
    CHECK(WorldError("NuPatch 2 2 [0 0 1 1] 0 1 2 2 [0 0 1 1] 0 1 \"Cs\" [1 1 1]") ==
          "t.rib:2: error: 'NuPatch' needs a \"P\" or \"Pw\" parameter");
    CHECK(WorldError("NuPatch 2 2 [0 0 1 1] 0 1 2 2") ==
          "t.rib:2: error: 'NuPatch' expects nu uorder uknot umin umax nv vorder vknot vmin vmax, got 7 arguments");
    CHECK(WorldError("NuPatch 2.5 2 [0 0 1 1] 0 1 2 2 [0 0 1 1] 0 1 " + p4) ==
          "t.rib:2: error: 'NuPatch': nu must be a positive integer, got number 2.5");
    CHECK(WorldError("NuPatch 2 2 [0 0 1 1] 0 1 2 2 [0 0 1 1] 0 1 " + p4 + " \"st\" [0 0 1 1]") ==
          "t.rib:2: error: 'NuPatch' parameter 'st' expects 8 numbers, got 4");
    CHECK(WorldError("NuPatch 2 2 [0 0 1 1] 0 1 2 2 [0 0 1 1] 0 1 " + p4 + " \"s\" [0 0 1 1]") ==
          "t.rib:2: error: 'NuPatch' needs both \"s\" and \"t\" (or \"st\"): one alone is not supported");
    CHECK(WorldError("NuPatch 2 2 [0 0 1 1] 0 1 2 2 [0 0 1 1] 0 1 " + p4 + " \"facevarying float[2] st\" [0 0 1 1]") ==
          "t.rib:2: error: 'NuPatch' parameter 'st': storage class 'facevarying' is not defined on a NuPatch");
    // Rational patches need positive weights.
    CHECK(WorldError("Patch \"bilinear\" \"Pw\" [0 0 0 1  1 0 0 -1  0 1 0 1  1 1 0 1]") ==
          "t.rib:2: error: 'Patch \"bilinear\"' parameter 'Pw': point 1 has w = -1; the weights of a rational patch "
          "must be "
          "positive");
    // TrimCurve: counts and knots.
    CHECK(WorldError("TrimCurve [1] [2] [0 0 1 1] [0] [1] [2] [0 1] [0 1] [1 1 1]") ==
          "t.rib:2: error: 'TrimCurve' w has 3 values; the curves need 2");
    CHECK(WorldError("TrimCurve [1] [2] [0 0 1 1 1] [0] [1] [2] [0 1] [0 1] [1 1]") ==
          "t.rib:2: error: 'TrimCurve' knot has 5 values; the curves need 4");
    CHECK(WorldError("TrimCurve [1] [2] [0 1 0 1] [0] [1] [2] [0 1] [0 1] [1 1]") ==
          "t.rib:2: error: 'TrimCurve': the trim curve 0 knot vector decreases at knot 2 (1 then 0)");
    CHECK(WorldError("TrimCurve [1] [2] [0 0 1 1] [0] [1] [2] [0 1] [0 1] [1 0]") ==
          "t.rib:2: error: 'TrimCurve' point 1 has w = 0; trim curve weights must be positive");
    CHECK(WorldError("TrimCurve [2] [2] [0 0 1 1] [0] [1] [2] [0 1] [0 1] [1 1]") ==
          "t.rib:2: error: 'TrimCurve' order has 1 values; the curves need 2");
    CHECK(WorldError("TrimCurve [1] [2] [0 0 1 1]") ==
          "t.rib:2: error: 'TrimCurve' expects ncurves order knot min max n u v w, got 3 arguments");
    CHECK_THAT(WorldError("Attribute \"trimcurve\" \"sense\" \"sideways\""),
               Contains("'Attribute \"trimcurve\"' takes \"sense\" \"inside\" or \"outside\""));
}
