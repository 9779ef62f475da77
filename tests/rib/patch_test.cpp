// tests/rib/patch_test.cpp: the RIB reader's bicubic patches (rib/geometry.cpp, rib/attributes.cpp):
// Basis as attribute state, Patch "bicubic", PatchMesh split into its patches (periodic or not,
// bilinear or bicubic, with each patch's part of the mesh's (u,v)), and the errors of each.
#include <catch2/catch.hpp>

#include <glm/gtc/matrix_transform.hpp>
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

/// n points (i, j, i * j + k) of an nu-wide grid, u fastest, and the RIB "P" array.
std::vector<glm::dvec3> Grid(int nu, int nv, double k = 0) {
    std::vector<glm::dvec3> out;
    for (int j = 0; j < nv; ++j)
        for (int i = 0; i < nu; ++i) out.emplace_back(i, j, i * j * 0.25 + k + 0.1 * ((i * 7 + j * 3) % 5));
    return out;
}
std::string PArray(const std::vector<glm::dvec3>& points) {
    std::ostringstream out;
    out << "\"P\" [";
    for (const glm::dvec3& p : points) out << p.x << ' ' << p.y << ' ' << p.z << ' ';
    out << ']';
    return out.str();
}

void CheckSame(const BicubicPatch& got, const BicubicPatch& want) {
    for (int k = 0; k < 16; ++k)
        for (int c = 0; c < 3; ++c) {
            INFO("coefficient " << k << " component " << c);
            CHECK(got.c[k][c] == Approx(want.c[k][c]).margin(1e-12));
        }
}

std::array<glm::dvec3, 16> Gather(const std::vector<glm::dvec3>& points, int nu, int nv, int i0, int j0) {
    std::array<glm::dvec3, 16> g;
    for (int b = 0; b < 4; ++b)
        for (int a = 0; a < 4; ++a) g[4 * b + a] = points[size_t((j0 + b) % nv) * nu + size_t((i0 + a) % nu)];
    return g;
}

}  // namespace

TEST_CASE("rib patches: Patch \"bicubic\" with every basis, Basis saved by attribute blocks", "[rib][bicubic]") {
    const std::vector<glm::dvec3> g = Grid(4, 4);
    std::array<glm::dvec3, 16> points;
    std::copy(g.begin(), g.end(), points.begin());
    const std::string patch = "Patch \"bicubic\" " + PArray(g);
    const std::vector<PrimitiveDesc> prims = Primitives(
        // Default bezier, translated.
        "TransformBegin\nTranslate 1 2 3\n" + patch + "\nTransformEnd\n" +
        // Named bases, restored at AttributeEnd.
        "AttributeBegin\nBasis \"b-spline\" 1 \"catmull-rom\" 1\n" + patch + "\nBasis \"hermite\" 2 \"power\" 4\n" +
        patch + "\nAttributeEnd\n" + patch +
        // A basis given by its 16 numbers (bezier's, as the RI spec's example writes it).
        "\nBasis [-1 3 -3 1 3 -6 3 0 -3 3 0 0 1 0 0 0] 3 \"b-spline\" 1\n" + patch + "\nPatch \"bicubic\" \"Pw\" [" +
        [&] {
            std::string text;
            for (const glm::dvec3& p : g)
                text += std::to_string(p.x) + " " + std::to_string(p.y) + " " + std::to_string(p.z) + " 1 ";
            return text;
        }() +
        "]");
    REQUIRE(prims.size() == 6);
    for (const PrimitiveDesc& p : prims) {
        CHECK(p.base.kind() == BaseSurface::Kind::BicubicPatch);
        CHECK(p.base.range.unitP());
    }
    const CubicBasis bezier = CubicBasis::Bezier();
    auto named = [](const char* name) { return *CubicBasis::Named(name); };
    CheckSame(
        prims[0].base.bicubic(),
        BicubicPatch::FromControlPoints(points, bezier, bezier, glm::translate(glm::dmat4(1.0), glm::dvec3(1, 2, 3))));
    // A bezier patch passes through its corner points.
    CHECK(prims[0].base.bicubic().At(0, 0) == g[0] + glm::dvec3(1, 2, 3));
    CHECK(glm::length(prims[0].base.bicubic().At(1, 1) - (g[15] + glm::dvec3(1, 2, 3))) < 1e-12);
    CheckSame(prims[1].base.bicubic(),
              BicubicPatch::FromControlPoints(points, named("b-spline"), named("catmull-rom"), glm::dmat4(1.0)));
    CheckSame(prims[2].base.bicubic(),
              BicubicPatch::FromControlPoints(points, named("hermite"), named("power"), glm::dmat4(1.0)));
    CheckSame(prims[3].base.bicubic(), BicubicPatch::FromControlPoints(points, bezier, bezier, glm::dmat4(1.0)));
    CheckSame(prims[4].base.bicubic(),
              BicubicPatch::FromControlPoints(points, bezier, named("b-spline"), glm::dmat4(1.0)));
    CheckSame(prims[5].base.bicubic(), prims[4].base.bicubic());  // Pw with w = 1 is P
}

TEST_CASE("rib patches: PatchMesh is split into its patches, each on its part of the mesh's (u,v)", "[rib][bicubic]") {
    SECTION("bicubic bezier, nonperiodic: (nu - 4) / 3 + 1 patches") {
        const std::vector<glm::dvec3> g = Grid(7, 4);
        const std::vector<PrimitiveDesc> prims =
            Primitives("PatchMesh \"bicubic\" 7 \"nonperiodic\" 4 \"nonperiodic\" " + PArray(g));
        REQUIRE(prims.size() == 2);
        const CubicBasis bezier = CubicBasis::Bezier();
        for (int i = 0; i < 2; ++i) {
            CheckSame(prims[i].base.bicubic(),
                      BicubicPatch::FromControlPoints(Gather(g, 7, 4, 3 * i, 0), bezier, bezier, glm::dmat4(1.0)));
            CHECK(prims[i].base.range.u0 == 0.5 * i);
            CHECK(prims[i].base.range.u1 == 0.5 * (i + 1));
            CHECK(prims[i].base.range.v0 == 0);
            CHECK(prims[i].base.range.v1 == 1);
            CHECK(prims[i].attr().line == 2);
        }
    }
    SECTION("bicubic b-spline, periodic in u and v: nu / 1 x nv / 1 patches whose points wrap") {
        const std::vector<glm::dvec3> g = Grid(5, 4);
        const std::vector<PrimitiveDesc> prims = Primitives(
            "Basis \"b-spline\" 1 \"b-spline\" 1\n"
            "PatchMesh \"bicubic\" 5 \"periodic\" 4 \"periodic\" " +
            PArray(g));
        REQUIRE(prims.size() == 20);
        const CubicBasis bspline = *CubicBasis::Named("b-spline");
        for (int j = 0; j < 4; ++j)
            for (int i = 0; i < 5; ++i) {
                INFO("patch " << i << ", " << j);
                const PrimitiveDesc& p = prims[size_t(j) * 5 + size_t(i)];
                CheckSame(p.base.bicubic(),
                          BicubicPatch::FromControlPoints(Gather(g, 5, 4, i, j), bspline, bspline, glm::dmat4(1.0)));
                CHECK(p.base.range.u0 == Approx(i / 5.0));
                CHECK(p.base.range.v1 == Approx((j + 1) / 4.0));
            }
        // Periodic b-spline patches meet: patch 4's right edge is patch 0's left edge.
        CHECK(glm::length(prims[4].base.bicubic().At(1, 0.3) - prims[0].base.bicubic().At(0, 0.3)) < 1e-12);
    }
    SECTION("catmull-rom, periodic in u only; hermite with step 2") {
        const std::vector<glm::dvec3> g = Grid(6, 4);
        CHECK(Primitives("Basis \"catmull-rom\" 1 \"catmull-rom\" 1\nPatchMesh \"bicubic\" 6 \"periodic\" 4 "
                         "\"nonperiodic\" " +
                         PArray(g))
                  .size() == 6);
        CHECK(Primitives("Basis \"hermite\" 2 \"hermite\" 2\nPatchMesh \"bicubic\" 6 \"nonperiodic\" 4 "
                         "\"nonperiodic\" " +
                         PArray(g))
                  .size() == 2);
        CHECK(Primitives("Basis \"hermite\" 2 \"hermite\" 2\nPatchMesh \"bicubic\" 6 \"periodic\" 4 "
                         "\"periodic\" " +
                         PArray(g))
                  .size() == 6);
    }
    SECTION("bilinear: nu - 1 patches, nu if periodic") {
        const std::vector<glm::dvec3> g = Grid(3, 2);
        const std::vector<PrimitiveDesc> prims =
            Primitives("Translate 0 0 1\nPatchMesh \"bilinear\" 3 \"periodic\" 2 \"nonperiodic\" " + PArray(g));
        REQUIRE(prims.size() == 3);
        for (const PrimitiveDesc& p : prims) CHECK(p.base.kind() == BaseSurface::Kind::BilinearPatch);
        const glm::dvec3 up(0, 0, 1);
        // The last patch wraps from column 2 back to column 0.
        CHECK(prims[2].base.patch().corners[0] == g[2] + up);
        CHECK(prims[2].base.patch().corners[1] == g[0] + up);
        CHECK(prims[2].base.patch().corners[2] == g[5] + up);
        CHECK(prims[2].base.patch().corners[3] == g[3] + up);
        CHECK(prims[1].base.range.u0 == Approx(1 / 3.0));
        CHECK(prims[1].base.range.u1 == Approx(2 / 3.0));
        CHECK(Primitives("PatchMesh \"bilinear\" 3 \"nonperiodic\" 2 \"nonperiodic\" " + PArray(g)).size() == 2);
    }
}

TEST_CASE("rib patches: bad bases, counts, sizes and rational points are errors at their line", "[rib][bicubic]") {
    const std::string p16 = PArray(Grid(4, 4));
    CHECK(WorldError("Basis \"bspline\" 1 \"bezier\" 3") ==
          "t.rib:2: error: 'Basis': unknown u basis 'bspline' (expected \"bezier\", \"b-spline\", \"catmull-rom\", "
          "\"hermite\" or \"power\", or 16 numbers)");
    CHECK_THAT(WorldError("Basis \"bezier\" 0 \"bezier\" 3"),
               Contains("t.rib:2: error: 'Basis': the u step must be a positive"));
    CHECK_THAT(WorldError("Basis \"bezier\" 3 \"bezier\" 1.5"), Contains("'Basis': the v step must be a positive"));
    CHECK_THAT(WorldError("Basis \"bezier\" 3 [1 2 3] 1"), Contains("'Basis': the v basis must be a name"));
    CHECK(WorldError("Basis \"bezier\" 3") ==
          "t.rib:2: error: 'Basis' expects 4 arguments (ubasis ustep vbasis vstep), got 2");
    CHECK(WorldError("Patch \"bicubic\" \"P\" [0 0 0]") ==
          "t.rib:2: error: 'Patch \"bicubic\"' parameter 'P' expects 48 numbers, got 3");
    CHECK(WorldError("Patch \"bicubic\" \"Cs\" [1 1 1]") ==
          "t.rib:2: error: 'Patch \"bicubic\"' needs a \"P\" parameter");
    CHECK(WorldError("Patch \"bicubic\" \"Pz\" [1 2 3 4 5 6 7 8 9 10 11 12 13 14 15 16]") ==
          "t.rib:2: error: 'Patch \"bicubic\"' parameter 'Pz' is supported on 'Patch \"bilinear\"' only; give \"P\"");
    std::string pw = "Patch \"bicubic\" \"Pw\" [";
    for (int i = 0; i < 16; ++i) pw += i == 5 ? "0 0 0 -2 " : "0 0 0 1 ";
    CHECK(WorldError(pw + "]") ==
          "t.rib:2: error: 'Patch \"bicubic\"' parameter 'Pw': point 5 has w = -2; the weights of a rational patch "
          "must be "
          "positive");
    CHECK(WorldError("Patch \"trilinear\" " + p16) ==
          "t.rib:2: error: unknown patch type 'trilinear' (expected \"bilinear\" or \"bicubic\")");
    // PatchMesh counts against the basis step and the wrap mode.
    const std::string p20 = PArray(Grid(5, 4));
    CHECK(WorldError("PatchMesh \"bicubic\" 5 \"nonperiodic\" 4 \"nonperiodic\" " + p20) ==
          "t.rib:2: error: 'PatchMesh \"bicubic\"': a nonperiodic mesh needs nu = 4 + k * 3 (the u step), got 5");
    CHECK(WorldError("PatchMesh \"bicubic\" 4 \"nonperiodic\" 5 \"periodic\" " + p20) ==
          "t.rib:2: error: 'PatchMesh \"bicubic\"': a periodic mesh needs nv a multiple of the v step 3, got 5");
    CHECK(WorldError("PatchMesh \"bicubic\" 4 \"nonperiodic\" 4 \"nonperiodic\" " + p20) ==
          "t.rib:2: error: 'PatchMesh \"bicubic\"' parameter 'P' expects 48 numbers, got 60");
    CHECK_THAT(WorldError("PatchMesh \"bicubic\" 4 \"closed\" 4 \"nonperiodic\" " + p16),
               Contains("t.rib:2: error: 'PatchMesh \"bicubic\"': uwrap must be \"periodic\" or \"nonperiodic\""));
    CHECK_THAT(WorldError("PatchMesh \"bilinear\" 2.5 \"periodic\" 4 \"nonperiodic\" " + p16),
               Contains("'PatchMesh \"bilinear\"': nu must be a positive integer"));
    CHECK(WorldError("PatchMesh \"bilinear\" 1 \"periodic\" 4 \"nonperiodic\" " + p16) ==
          "t.rib:2: error: 'PatchMesh \"bilinear\"': nu must be at least 2");
    CHECK(WorldError("PatchMesh \"bicubic\" 4 \"nonperiodic\"") ==
          "t.rib:2: error: 'PatchMesh \"bicubic\"' expects nu uwrap nv vwrap after the type, got 2 arguments");
    CHECK(WorldError("PatchMesh \"bicubic\" 4 \"nonperiodic\" 4 \"nonperiodic\"") ==
          "t.rib:2: error: 'PatchMesh \"bicubic\"' needs a \"P\" parameter");
}
