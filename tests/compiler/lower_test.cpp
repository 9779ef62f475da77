// tests/compiler/lower_test.cpp: names, declarations and expressions (compiler/lower.cpp): operator
// precedence, compound assignment, the promotion of floats to triples, and strings, compared at
// compile time and chosen under conditions on parameters.
// Part of the language-semantics suite: values worked out by hand on the unit square, each
// cross-checked as tests/compiler/semantics_util.h says.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>

#include "tests/compiler/semantics_util.h"

using namespace affray;
using namespace affray::test::semantics;

TEST_CASE("operator precedence follows RSL", "[compiler][semantics]") {
    // '.' binds tighter than '+': 2 + (a . b) = 2 + 3.
    CHECK_THAT(Z("P += 2 + vector(1, 0, 0) . vector(3, 4, 5);"), WithinAbs(5, kEps));
    // '.' binds tighter than '*': (a . b) * c = 6 * (1, 0, 2), not a . (b * c) = 7.
    CheckVec(PAt("P = vector(1, 2, 3) . vector(1, 1, 1) * vector(1, 0, 2);"), {6, 0, 12});
    // '^' binds looser than '*': a ^ (b * c) = (1,0,0) ^ (0,3,5) = (0,-5,3), not (a ^ b) * c = (0,-3,5).
    CheckVec(PAt("P = vector(1, 0, 0) ^ vector(0, 1, 1) * vector(2, 3, 5);"), {0, -5, 3});
    // '^' binds tighter than '+': a + (b ^ c) = (1,0,0) + (0,0,1), not (a + b) ^ c = (0,0,2).
    CheckVec(PAt("P = vector(1, 0, 0) + vector(1, 0, 0) ^ vector(0, 1, 0);"), {1, 0, 1});
    // Unary '!' binds tighter than '+' and '*': (!0) + 1 = 2, (!0) * 3 = 3.
    CHECK_THAT(Z("P += !0 + 1;"), WithinAbs(2, kEps));
    CHECK_THAT(Z("P += !0 * 3;"), WithinAbs(3, kEps));
    // Unary '-' binds tighter than '.': (-a) . b.
    CHECK_THAT(Z("P += -vector(1, 2, 3) . vector(1, 1, 1) + 10;"), WithinAbs(4, kEps));
    // '&&' binds tighter than '||': 1 || (0 && 0).
    CHECK_THAT(Z("P += 1 || 0 && 0;"), WithinAbs(1, kEps));
    CHECK_THAT(Z("P += (1 || 0) && 0;"), WithinAbs(0, kEps));
    // Relational binds looser than '+': 3 < (1 + 3), not (3 < 1) + 3.
    CHECK_THAT(Z("P += 3 < 1 + 3;"), WithinAbs(1, kEps));
    // Relational binds tighter than '&&': (2 > 1) && (0 < 1).
    CHECK_THAT(Z("P += 2 > 1 && 0 < 1;"), WithinAbs(1, kEps));
    // '?:' binds looser than '||': (0 || 1) ? 10 : 20.
    CHECK_THAT(Z("P += 0 || 1 ? 10 : 20;"), WithinAbs(10, kEps));
    // '?:' binds tighter than assignment and takes all of '+': 1 ? 1 : (2 + 3).
    CHECK_THAT(Z("P += 1 ? 1 : 2 + 3;"), WithinAbs(1, kEps));
    // '?:' is right associative.
    CHECK_THAT(Z("P += 0 ? 1 : 0 ? 2 : 3;"), WithinAbs(3, kEps));
    CHECK_THAT(Z("P += 0 ? 1 : 1 ? 2 : 3;"), WithinAbs(2, kEps));
    // '*' and '/' group left to right: (12 / 2) * 3.
    CHECK_THAT(Z("P += 12 / 2 * 3;"), WithinAbs(18, kEps));
    // Assignment is right associative and yields the value assigned.
    CHECK_THAT(Z("float a, b; a = b = 2; P += a * b;"), WithinAbs(4, kEps));
}

TEST_CASE("compound assignment on floats and points", "[compiler][semantics]") {
    // ((10 + 5 - 3) * 2) / 8 = 3
    CHECK_THAT(Z("float a = 10; a += 5; a -= 3; a *= 2; a /= 8; P += a;"), WithinAbs(3, kEps));
    // ((1,2,3) + 1) * (2,3,4) - 1 = (3, 8, 15), / 2 = (1.5, 4, 7.5)
    CheckVec(PAt("point q = (1, 2, 3); q += 1; q *= vector(2, 3, 4); q -= point(1, 1, 1); q /= 2; P = q;"),
             {1.5, 4, 7.5});
    CheckVec(PAt("vector w = (1, 2, 3); w *= 2; w /= 4; P = w;"), {0.5, 1, 1.5});
    CheckVec(PAt("P *= 2;"), {0.5, 1.5, 0});
    CheckVec(PAt("P -= vector(1, 1, 1);"), {-0.75, -0.25, -1});
    CheckVec(PAt("P /= vector(0.5, 0.25, 1);"), {0.5, 3, 0});
    // Varying: u^2 + v = 0.0625 + 0.75.
    CHECK_THAT(Z("float a = u; a *= a; a += v; P += a;"), WithinAbs(0.8125, kEps));
}

TEST_CASE("float to triple promotion", "[compiler][semantics]") {
    CheckVec(PAt("vector w = .1; P = w;"), {0.1, 0.1, 0.1});
    CheckVec(PAt("P += 1;"), {1.25, 1.75, 1});
    CheckVec(PAt("P = 2;"), {2, 2, 2});
    CheckVec(PAt("point q = u; P = q;"), {0.25, 0.25, 0.25});
    // (1, 2, 3) * 2 + 1 = (3, 5, 7)
    CheckVec(PAt("P += vector(1, 2, 3) * 2 + 1;"), {3.25, 5.75, 7});
    CheckVec(PAt("normal n = 0.5; P += n;"), {0.75, 1.25, 0.5});
    CheckVec(PAt("P = 1 - P;"), {0.75, 0.25, 1});
    CheckVec(PAt("P = 1 / vector(1, 2, 4);"), {1, 0.5, 0.25});
}

TEST_CASE("strings compare at compile time", "[compiler][semantics]") {
    CHECK_THAT(Z("string sp = \"shader\"; if (sp == \"shader\") P += 1; else P += 2;"), WithinAbs(1, kEps));
    CHECK_THAT(Z("string sp = \"shader\"; if (sp != \"shader\") P += 1; else P += 2;"), WithinAbs(2, kEps));
    CHECK_THAT(Z("string a = \"x\", b = \"x\", c = \"y\"; P += (a == b) + 10 * (a == c) + 100 * (b != c);"),
               WithinAbs(101, kEps));
    CHECK_THAT(Z("string sp = \"a\"; sp = \"b\"; P += sp == \"b\";"), WithinAbs(1, kEps));
    // Parameters.
    CHECK_THAT(ZSource(Shader("if (mode == \"up\") P += 1; else P -= 1;", "string mode = \"up\"")), WithinAbs(1, kEps));
    CHECK_THAT(ZSource(Shader("if (mode == \"up\") P += 1; else P -= 1;", "string mode = \"down\"")),
               WithinAbs(-1, kEps));
    // A string in ?: with a constant condition.
    CHECK_THAT(Z("string s2 = 1 > 0 ? \"world\" : \"object\"; if (s2 == \"world\") P += 1;"), WithinAbs(1, kEps));
    // A string passed to a function.
    CHECK_THAT(ZSource("float isUp(string s) { if (s == \"up\") return 1; return 0; }\n" +
                       Shader("P += isUp(\"up\") + 10 * isUp(\"down\");")),
               WithinAbs(1, kEps));
    // A string assigned under a constant condition.
    CHECK_THAT(Z("string dir = \"down\"; if (2 > 1) dir = \"up\"; if (dir == \"up\") P += 1; else P -= 1;"),
               WithinAbs(1, kEps));
}

TEST_CASE("a string assigned under a condition on a float parameter", "[compiler][semantics]") {
    // Regression test (a bug found and fixed): strings have ScalarCount 0, so Lowerer::Merge and Guard never select between string
    // values: in the generic program (the parameter is a register) `dir` silently keeps "down".
    // The instance is right (its condition is constant), but a shader loaded from an .afb file
    // is specialised from the generic program, and gives -1 with up = 1.
    const std::string src = Shader(
        "string dir = \"down\"; if (up > 0) dir = \"up\"; if (dir == \"up\") P += 1; else P -= 1;", "float up = 1");
    CHECK_THAT(ZSource(src), WithinAbs(1, kEps));
    CHECK_THAT(ZSource(src, 0.25, 0.75, {{"up", {-1}}}), WithinAbs(-1, kEps));
    compiler::CompiledShader s = test::CompileOrThrow(src);
    std::vector<std::string> errors;
    std::optional<vm::Program> loaded = compiler::Specialise(s.genericBound, {}, &errors);
    REQUIRE(loaded);
    CHECK_THAT(Run(*loaded, 0.25, 0.75).z, WithinAbs(1, kEps));
}

TEST_CASE("a string chosen by ?: on a float parameter", "[compiler][semantics]") {
    // Regression test (a bug found and fixed): parameters are uniform, yet `up > 0 ? "up" : "down"` is rejected with "a string
    // cannot depend on a condition that varies over the surface" (the generic lowering sees a
    // parameter register), while the same choice written with if/else compiles.
    const std::string src =
        Shader("string dir = up > 0 ? \"up\" : \"down\"; if (dir == \"up\") P += 1; else P -= 1;", "float up = 1");
    CHECK_THAT(ZSource(src), WithinAbs(1, kEps));
    CHECK_THAT(ZSource(src, 0.25, 0.75, {{"up", {-1}}}), WithinAbs(-1, kEps));
}
