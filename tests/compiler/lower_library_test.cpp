// tests/compiler/lower_library_test.cpp: the built-ins that need more than a table row
// (compiler/lower_library.cpp): spline and its bases, filterstep, transform, vtransform and
// ntransform with their spaces, noise's range, lattice values and return-type overloads, cellnoise
// and pnoise.
// Part of the language-semantics suite: values worked out by hand on the unit square, each
// cross-checked as tests/compiler/semantics_util.h says.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>

#include "tests/compiler/semantics_util.h"

using namespace affray;
using namespace affray::test::semantics;

TEST_CASE("built-ins: spline", "[compiler][semantics][builtins]") {
    // Catmull-Rom through the interior knots: 5 knots, 2 segments, 10 -> 20 -> 40.
    const std::string knots = "0, 10, 20, 40, 50";
    CHECK_THAT(Z("P += spline(0, " + knots + ");"), WithinAbs(10, kEps));
    CHECK_THAT(Z("P += spline(0.5, " + knots + ");"), WithinAbs(20, kEps));
    CHECK_THAT(Z("P += spline(1, " + knots + ");"), WithinAbs(40, kEps));
    // Mid-segment: (-k0 + 9 k1 + 9 k2 - k3) / 16 = (0 + 90 + 180 - 40) / 16.
    CHECK_THAT(Z("P += spline(0.25, " + knots + ");"), WithinAbs(14.375, kEps));
    // (-10 + 180 + 360 - 50) / 16
    CHECK_THAT(Z("P += spline(0.75, " + knots + ");"), WithinAbs(30, kEps));
    // t is clamped to [0, 1].
    CHECK_THAT(Z("P += spline(-1, " + knots + ") + spline(2, " + knots + ");"), WithinAbs(50, kEps));
    CHECK_THAT(Z("P += spline(u, " + knots + ");", 0.5), WithinAbs(20, kEps));
    CHECK_THAT(Z("P += spline(\"catmull-rom\", 0.25, " + knots + ");"), WithinAbs(14.375, kEps));
    // Four knots: one segment from k1 to k2.
    CHECK_THAT(Z("P += spline(0, 0, 1, 2, 3) + 10 * spline(1, 0, 1, 2, 3);"), WithinAbs(21, kEps));
    // Point knots, componentwise: (-k0 + 9 k1 + 9 k2 - k3) / 16.
    CheckVec(PAt("P = spline(0.5, point(0, 0, 0), point(1, 2, 3), point(2, 4, 6), point(3, 6, 9));"), {1.5, 3, 4.5});
    // The linear basis interpolates the same interior knots linearly: 10 + 0.5 * 10, 20 + 0.5 * 20.
    CHECK_THAT(Z("P += spline(\"linear\", 0.25, " + knots + ");"), WithinAbs(15, kEps));
    CHECK_THAT(Z("P += spline(\"linear\", 0.75, " + knots + ");"), WithinAbs(30, kEps));
    CHECK_THAT(Z("P += spline(\"linear\", 0.5, " + knots + ");"), WithinAbs(20, kEps));
}

TEST_CASE("built-ins: spline bases", "[compiler][semantics][builtins]") {
    // Bezier, one segment: (k0 + 3 k1 + 3 k2 + k3) / 8 at t = 0.5; through k0 and k3 at the ends.
    CHECK_THAT(Z("P += spline(\"bezier\", 0.5, 0, 1, 3, 8);"), WithinAbs(2.5, kEps));
    CHECK_THAT(Z("P += spline(\"bezier\", 1, 0, 1, 3, 8);"), WithinAbs(8, kEps));
    // Bezier, two segments (7 knots, step 3): t = 0.75 is the middle of the second: (8 + 3*2 + 3*2 + 0) / 8.
    CHECK_THAT(Z("P += spline(\"bezier\", 0.75, 0, 1, 3, 8, 2, 2, 0);"), WithinAbs(2.5, kEps));
    // B-spline at a segment start: (k0 + 4 k1 + k2) / 6.
    CHECK_THAT(Z("P += spline(\"bspline\", 0, 0, 6, 12, 6);"), WithinAbs(6, kEps));
    // Hermite (p0, t0, p1, t1): p1 at t = 1, p0 at t = 0.
    CHECK_THAT(Z("P += spline(\"hermite\", 1, 1, 0, 5, 0) + 10 * spline(\"hermite\", 0, 1, 0, 5, 0);"),
               WithinAbs(15, kEps));
    // Power basis: k0 u^3 + k1 u^2 + k2 u + k3.
    CHECK_THAT(Z("P += spline(\"power\", 0.5, 8, 4, 2, 1);"), WithinAbs(1 + 1 + 1 + 1, kEps));
}

TEST_CASE("built-ins: filterstep", "[compiler][semantics][builtins]") {
    // A constant x has zero filter width: the plain step (edge <= x).
    CHECK_THAT(Z("P += filterstep(0.5, 0.7);"), WithinAbs(1, kEps));
    CHECK_THAT(Z("P += filterstep(0.5, 0.3);"), WithinAbs(0, kEps));
    CHECK_THAT(Z("P += filterstep(0.5, 0.5);"), WithinAbs(1, kEps));
    // The 3-argument form: the fraction of [x0, x1] above the edge.
    CHECK_THAT(Z("P += filterstep(0.5, 0.25, 0.75);"), WithinAbs(0.5, kEps));
    CHECK_THAT(Z("P += filterstep(0.6, 0, 1);"), WithinAbs(0.4, kEps));
    CHECK_THAT(Z("P += filterstep(2, 0, 1);"), WithinAbs(0, kEps));
    CHECK_THAT(Z("P += filterstep(-1, 0, 1);"), WithinAbs(1, kEps));
    CHECK_THAT(Z("P += filterstep(0.5, 0.5, 0.5);"), WithinAbs(1, kEps));
    // x = u sweeps du = 1/1024 per sample: the box is u +- 1/2048.
    CHECK_THAT(Z("P += filterstep(0.5, u);", 0.5), WithinAbs(0.5, kEps));
    CHECK_THAT(Z("P += filterstep(0.5, u);", 0.25), WithinAbs(0, kEps));
    CHECK_THAT(Z("P += filterstep(0.5, u);", 0.75), WithinAbs(1, kEps));
    CHECK_THAT(Z("P += filterstep(0.5, u);", 0.5 + 1.0 / 4096), WithinAbs(0.75, kEps));
    // "width" scales the box to u +- 1/1024: (1/4096 + 1/1024) / (2/1024).
    CHECK_THAT(Z("P += filterstep(0.5, u, \"width\", 2);", 0.5 + 1.0 / 4096), WithinAbs(0.625, kEps));
    // "filter" is accepted (and ignored).
    CHECK_THAT(Z("P += filterstep(0.5, 0.25, 0.75, \"filter\", 1);"), WithinAbs(0.5, kEps));
}

TEST_CASE("built-ins: transform vtransform ntransform and spaces", "[compiler][semantics][builtins]") {
    // Every named space is the identity for now.
    for (const char* space : {"current", "world", "object", "shader", "camera"}) {
        const std::string sp = std::string("\"") + space + "\"";
        INFO("space " << space);
        CheckVec(PAt("P = transform(" + sp + ", P + vector(0, 0, 1));"), {0.25, 0.75, 1});
        CheckVec(PAt("P = transform(" + sp + ", \"world\", P + vector(0, 0, 2));"), {0.25, 0.75, 2});
        CheckVec(PAt("P = vtransform(" + sp + ", vector(1, 2, 3));"), {1, 2, 3});
        CheckVec(PAt("P = vtransform(\"object\", " + sp + ", vector(1, 2, 3));"), {1, 2, 3});
        CheckVec(PAt("P = ntransform(" + sp + ", normal(0, 1, 0));"), {0, 1, 0});
        CheckVec(PAt("P = ntransform(" + sp + ", " + sp + ", normal(0, 1, 0));"), {0, 1, 0});
        CheckVec(PAt("P = point " + sp + " (1, 2, 3);"), {1, 2, 3});
        CheckVec(PAt("P = vector " + sp + " (0, 0, 1);"), {0, 0, 1});
        CheckVec(PAt("P = normal " + sp + " (0, 1, 0);"), {0, 1, 0});
    }
    // A space named by a string variable or parameter.
    CheckVec(PAt("string sp = \"object\"; P = transform(sp, P + 1);"), {1.25, 1.75, 1});
    CheckVec(Eval(Shader("P = transform(space, P + vector(0, 0, 1));", "string space = \"shader\""), 0.25, 0.75),
             {0.25, 0.75, 1});
    // A float is transformed as a point.
    CheckVec(PAt("P = transform(\"world\", 2);"), {2, 2, 2});
    // A color cast in "rgb".
    CHECK_THAT(Z("color c = color \"rgb\" (1, 2, 3); P += comp(c, 2);"), WithinAbs(3, kEps));
}

TEST_CASE("built-ins: noise range, lattice values and return-type overloads",
          "[compiler][semantics][builtins][noise]") {
    // 0.5 at lattice points, in every dimension.
    CHECK_THAT(Z("P += float noise(2);"), WithinAbs(0.5, kEps));
    CHECK_THAT(Z("P += float noise(1, 2);"), WithinAbs(0.5, kEps));
    CHECK_THAT(Z("P += float noise(point(1, 2, 3));"), WithinAbs(0.5, kEps));
    CHECK_THAT(Z("P += float noise(point(1, 2, 3), 4);"), WithinAbs(0.5, kEps));
    CheckVec(PAt("P = vector noise(point(-1, 0, 5));"), {0.5, 0.5, 0.5});
    // In [0, 1] everywhere, with a mean near 0.5.
    compiler::CompiledShader s = test::CompileOrThrow(Shader("P = vector noise(P * 7.3 + 0.1);"));
    double sum = 0;
    int n = 0;
    for (int i = 0; i <= 20; ++i) {
        for (int j = 0; j <= 20; ++j) {
            glm::dvec3 p = Run(s.shade, i / 20.0, j / 20.0);
            for (int c = 0; c < 3; ++c) {
                CHECK(p[c] >= 0);
                CHECK(p[c] <= 1);
                sum += p[c];
                ++n;
            }
        }
    }
    CHECK(sum / n == Approx(0.5).margin(0.1));
    // The result type comes from the context: a triple gets three different channels, and the
    // float version is one value.
    glm::dvec3 w = PAt("vector w = noise(P * 3.7 + 0.2); P = w;", 0.3, 0.6);
    CHECK(w.x != w.y);
    CHECK(w.y != w.z);
    CHECK(w.x != w.z);
    glm::dvec3 f = PAt("float x = noise(P * 3.7 + 0.2); P = x;", 0.3, 0.6);
    CHECK(f.x == f.y);
    CHECK(f.y == f.z);
    CHECK(f.x != 0.5);
    glm::dvec3 c = PAt("P = point noise(P * 3.7 + 0.2);", 0.3, 0.6);
    CHECK(c.x != c.y);
    glm::dvec3 k =
        PAt("color k = color noise(P * 3.7 + 0.2); P = point(comp(k, 0), comp(k, 1), comp(k, 2));", 0.3, 0.6);
    CHECK(k.x != k.y);
    // 1-D, 2-D, 3-D and 4-D noise are different functions.
    const double n1 = Z("P += float noise(u * 3.7 + 0.2);", 0.3, 0.6);
    const double n2 = Z("P += float noise(u * 3.7 + 0.2, v * 3.7 + 0.2);", 0.3, 0.6);
    const double n3 = Z("P += float noise(P * 3.7 + 0.2);", 0.3, 0.6);
    const double n4 = Z("P += float noise(P * 3.7 + 0.2, 0.45);", 0.3, 0.6);
    CHECK(n1 != n2);
    CHECK(n2 != n3);
    CHECK(n3 != n4);
    for (double x : {n1, n2, n3, n4}) {
        CHECK(x >= 0);
        CHECK(x <= 1);
    }
}

TEST_CASE("built-ins: cellnoise is constant within a cell", "[compiler][semantics][builtins][noise]") {
    const std::string body = "P += float cellnoise(u * 4);";
    const double a = Z(body, 0.3), b = Z(body, 0.45), c = Z(body, 0.55);  // cells 1, 1, 2
    CHECK(a == b);
    CHECK(a != c);
    for (double x : {a, c}) {
        CHECK(x >= 0);
        CHECK(x < 1);
    }
    // 2-D and 3-D: the same within the cell (1, 2), different in the next one.
    const std::string body2 = "P += float cellnoise(u * 4, v * 4);";
    CHECK(Z(body2, 0.3, 0.55) == Z(body2, 0.45, 0.7));
    CHECK(Z(body2, 0.3, 0.55) != Z(body2, 0.3, 0.8));
    glm::dvec3 p = PAt("P = vector cellnoise(P * 4);", 0.3, 0.55);
    glm::dvec3 q = PAt("P = vector cellnoise(P * 4);", 0.45, 0.7);
    CHECK(p == q);
    CHECK(p.x != p.y);
}

TEST_CASE("built-ins: pnoise is periodic", "[compiler][semantics][builtins][noise]") {
    // Period 4 in x = 8u: u and u + 0.5 give the same value.
    const std::string body = "P += float pnoise(u * 8, 4);";
    CHECK_THAT(Z(body, 0.1), WithinAbs(Z(body, 0.6), kEps));
    CHECK(Z(body, 0.1) != Z(body, 0.2));
    // Inside one period, pnoise is noise: floor(1.3) + 1 < 4.
    CHECK_THAT(Z("P += float pnoise(1.3, 4);"), WithinAbs(Z("P += float noise(1.3);"), kEps));
    // 2-D, 3-D and 4-D periods.
    const std::string body2 = "P += float pnoise(u * 8, v * 8, 4, 4);";
    CHECK_THAT(Z(body2, 0.1, 0.2), WithinAbs(Z(body2, 0.6, 0.7), kEps));
    const std::string body3 = "P += float pnoise(P * 8, point(4, 4, 4));";
    CHECK_THAT(Z(body3, 0.1, 0.2), WithinAbs(Z(body3, 0.6, 0.7), kEps));
    const std::string body4 = "P += float pnoise(P * 8, u * 8, point(4, 4, 4), 4);";
    CHECK_THAT(Z(body4, 0.1, 0.2), WithinAbs(Z(body4, 0.6, 0.7), kEps));
    // A triple context: three channels, each periodic.
    glm::dvec3 a = PAt("P = vector pnoise(P * 8, point(4, 4, 4));", 0.1, 0.2);
    glm::dvec3 b = PAt("P = vector pnoise(P * 8, point(4, 4, 4));", 0.6, 0.7);
    CheckVec(a, b);
    CHECK(a.x != a.y);
}
