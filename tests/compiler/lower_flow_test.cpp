// tests/compiler/lower_flow_test.cpp: statements and control flow turned into data flow
// (compiler/lower_flow.cpp): if/else on constant and varying conditions, for and while loops,
// break and continue (with levels), return from functions and from the shader body, loops bounded
// by parameters and the limits of their unrolling, variables assigned in one arm only.
// Part of the language-semantics suite: values worked out by hand on the unit square, each
// cross-checked as tests/compiler/semantics_util.h says.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>

#include "tests/compiler/semantics_util.h"

using namespace affray;
using namespace affray::test::semantics;

TEST_CASE("if/else with a constant condition keeps only the arm taken", "[compiler][semantics]") {
    CHECK_THAT(Z("if (1) P += 1; else P += 2;"), WithinAbs(1, kEps));
    CHECK_THAT(Z("if (0) P += 1; else P += 2;"), WithinAbs(2, kEps));
    CHECK_THAT(Z("if (2 < 1) P += 1;"), WithinAbs(0, kEps));
    // A float condition means "!= 0".
    CHECK_THAT(Z("if (0.5) P += 3;"), WithinAbs(3, kEps));
    // 'else' belongs to the nearest 'if'.
    CHECK_THAT(Z("if (1) if (0) P += 1; else P += 2;"), WithinAbs(2, kEps));
    CHECK_THAT(Z("if (0) if (1) P += 1; else P += 2;"), WithinAbs(0, kEps));
    // A condition on a parameter: constant in the instance, a register in the generic program.
    const std::string src = Shader("if (k > 0) P += 1; else P -= 1;", "float k = 1");
    CHECK_THAT(ZSource(src), WithinAbs(1, kEps));
    CHECK_THAT(ZSource(src, 0.25, 0.75, {{"k", {-1}}}), WithinAbs(-1, kEps));
}

TEST_CASE("if/else with a varying condition selects per point", "[compiler][semantics]") {
    const std::string body = "if (u < 0.5) P += 1; else P += 2;";
    CHECK_THAT(Z(body, 0.25), WithinAbs(1, kEps));
    CHECK_THAT(Z(body, 0.75), WithinAbs(2, kEps));
    CHECK_THAT(Z(body, 0.5), WithinAbs(2, kEps));  // 0.5 < 0.5 is false
    // A float condition: true where it is not 0.
    CHECK_THAT(Z("if (u - 0.5) P += 1; else P += 2;", 0.5), WithinAbs(2, kEps));
    CHECK_THAT(Z("if (u - 0.5) P += 1; else P += 2;", 0.25), WithinAbs(1, kEps));
    // Without an else, the other points keep the old value.
    CHECK_THAT(Z("float a = 5; if (u > 0.5) a = 7; P += a;", 0.25), WithinAbs(5, kEps));
    CHECK_THAT(Z("float a = 5; if (u > 0.5) a = 7; P += a;", 0.75), WithinAbs(7, kEps));
    // Triples are selected per component: (u, v, 1) or (u, v, -1).
    CheckVec(PAt("if (v > 0.5) P += vector(0, 0, 1); else P -= vector(0, 0, 1);", 0.25, 0.75), {0.25, 0.75, 1});
    CheckVec(PAt("if (v > 0.5) P += vector(0, 0, 1); else P -= vector(0, 0, 1);", 0.25, 0.25), {0.25, 0.25, -1});
}

TEST_CASE("nested if/else and else-if chains", "[compiler][semantics]") {
    const std::string body =
        "if (u < 0.5) { if (v < 0.5) P += 1; else P += 2; } else { if (v < 0.5) P += 3; else P += 4; }";
    CHECK_THAT(Z(body, 0.25, 0.25), WithinAbs(1, kEps));
    CHECK_THAT(Z(body, 0.25, 0.75), WithinAbs(2, kEps));
    CHECK_THAT(Z(body, 0.75, 0.25), WithinAbs(3, kEps));
    CHECK_THAT(Z(body, 0.75, 0.75), WithinAbs(4, kEps));
    const std::string chain = "if (u < 0.3) P += 1; else if (u < 0.6) P += 2; else P += 3;";
    CHECK_THAT(Z(chain, 0.1), WithinAbs(1, kEps));
    CHECK_THAT(Z(chain, 0.5), WithinAbs(2, kEps));
    CHECK_THAT(Z(chain, 0.9), WithinAbs(3, kEps));
    // A varying if inside a constant one, and the other way round.
    CHECK_THAT(Z("if (1) { if (u < 0.5) P += 1; } else P += 100;", 0.25), WithinAbs(1, kEps));
    CHECK_THAT(Z("if (1) { if (u < 0.5) P += 1; } else P += 100;", 0.75), WithinAbs(0, kEps));
    CHECK_THAT(Z("if (u < 0.5) { if (0) P += 100; else P += 1; }", 0.25), WithinAbs(1, kEps));
}

TEST_CASE("for loops", "[compiler][semantics]") {
    // 1 + 2 + 3 + 4 = 10, and the counter ends at 5.
    CheckVec(PAt("float i, s = 0; for (i = 1; i <= 4; i += 1) s += i; P = point(s, i, 0);"), {10, 5, 0});
    // No iteration at all.
    CHECK_THAT(Z("float i, s = 7; for (i = 0; i < 0; i += 1) s += 1; P += s;"), WithinAbs(7, kEps));
    // No condition: runs until the break, at i = 3.
    CHECK_THAT(Z("float i = 0; for (;;) { i += 1; if (i >= 3) break; } P += i;"), WithinAbs(3, kEps));
    // Nested, the inner bound depending on the outer counter: 0 + 1 + 2 = 3 iterations.
    CHECK_THAT(Z("float i, j, n = 0; for (i = 0; i < 3; i += 1) for (j = 0; j < i; j += 1) n += 1; P += n;"),
               WithinAbs(3, kEps));
    // A varying body: u * (0 + 1 + 2 + 3) = 0.25 * 6.
    CHECK_THAT(Z("float i, s = 0; for (i = 0; i < 4; i += 1) s += u * i; P += s;", 0.25), WithinAbs(1.5, kEps));
    // A counting-down loop with a fractional step: 2, 1.5, 1, 0.5 -> 5.
    CHECK_THAT(Z("float i, s = 0; for (i = 2; i > 0; i -= 0.5) s += i; P += s;"), WithinAbs(5, kEps));
}

TEST_CASE("while loops", "[compiler][semantics]") {
    // 0 + 1 + 2 + 3 + 4 = 10
    CHECK_THAT(Z("float i = 0, s = 0; while (i < 5) { s += i; i += 1; } P += s;"), WithinAbs(10, kEps));
    // A float condition: 4 + 3 + 2 + 1 = 10, stopping when n reaches 0.
    CHECK_THAT(Z("float n = 4, s = 0; while (n) { s += n; n -= 1; } P += s;"), WithinAbs(10, kEps));
    // A condition false from the start.
    CHECK_THAT(Z("float n = 0; while (n > 0) n -= 1; P += n + 2;"), WithinAbs(2, kEps));
}

TEST_CASE("break", "[compiler][semantics]") {
    // s = 0 + 1 + 2, then break with i = 3 (the step does not run).
    CheckVec(PAt("float i, s = 0; for (i = 0; i < 10; i += 1) { if (i == 3) break; s += i; } P = point(s, i, 0);"),
             {3, 3, 0});
    CHECK_THAT(Z("float i = 0; while (1) { if (i >= 4) break; i += 1; } P += i;"), WithinAbs(4, kEps));
    // A varying break in a loop with a constant bound: n counts the i < 10u.
    const std::string body =
        "float i, n = 0; for (i = 0; i < 10; i += 1) { if (i >= u * 10) break; n += 1; } P = point(n, i, 0);";
    CheckVec(PAt(body, 0.25), {3, 3, 0});    // 2.5
    CheckVec(PAt(body, 0.75), {8, 8, 0});    // 7.5
    CheckVec(PAt(body, 0.99), {10, 10, 0});  // 9.9: the loop ends on its condition
    // Only the innermost loop is left: 3 outer iterations, one inner each.
    CHECK_THAT(
        Z("float i, j, n = 0; for (i = 0; i < 3; i += 1) for (j = 0; j < 3; j += 1) { if (j == 1) break; n += 1; } "
          "P += n;"),
        WithinAbs(3, kEps));
    // Code after a break in the same block does not run.
    CHECK_THAT(Z("float i, n = 0; for (i = 0; i < 3; i += 1) { n += 1; break; n += 100; } P += n;"),
               WithinAbs(1, kEps));
}

TEST_CASE("continue", "[compiler][semantics]") {
    // 0 + 1 + 3 + 4 = 8; the step still runs after a continue, so i ends at 5.
    CheckVec(PAt("float i, s = 0; for (i = 0; i < 5; i += 1) { if (i == 2) continue; s += i; } P = point(s, i, 0);"),
             {8, 5, 0});
    // In a while loop the condition is tested again: 1 + 2 + 4 + 5 = 12.
    CHECK_THAT(Z("float i = 0, s = 0; while (i < 5) { i += 1; if (i == 3) continue; s += i; } P += s;"),
               WithinAbs(12, kEps));
    // A varying continue: skips the i < 4u among i = 0..3.
    const std::string body = "float i, s = 0; for (i = 0; i < 4; i += 1) { if (i < u * 4) continue; s += 1; } P += s;";
    CHECK_THAT(Z(body, 0.25), WithinAbs(3, kEps));  // skips i = 0
    CHECK_THAT(Z(body, 0.75), WithinAbs(1, kEps));  // skips i = 0, 1, 2
}

TEST_CASE("break 2 and continue 2 in nested loops", "[compiler][semantics]") {
    // i = 0 and 1 run 4 inner iterations each, i = 2 one (j = 0), then break 2 at j = 1.
    CheckVec(PAt("float s = 0, i, j;\n"
                 "for (i = 0; i < 4; i += 1)\n"
                 "    for (j = 0; j < 4; j += 1) {\n"
                 "        if (i == 2 && j == 1) break 2;\n"
                 "        s += 1;\n"
                 "    }\n"
                 "P = point(s, i, j);"),
             {9, 2, 1});
    // continue 2 at j = 1 goes to the outer step: s = 0 + 10 + 20, i ends at 3 and j at 1.
    CheckVec(PAt("float s = 0, i, j;\n"
                 "for (i = 0; i < 3; i += 1)\n"
                 "    for (j = 0; j < 3; j += 1) {\n"
                 "        if (j == 1) continue 2;\n"
                 "        s += 10 * i + j;\n"
                 "    }\n"
                 "P = point(s, i, j);"),
             {30, 3, 1});
    // break 2 from three loops deep leaves the two inner ones: one count per outer iteration.
    CHECK_THAT(Z("float i, j, k, n = 0;\n"
                 "for (i = 0; i < 2; i += 1) for (j = 0; j < 3; j += 1) for (k = 0; k < 3; k += 1) {\n"
                 "    if (k == 1) break 2;\n"
                 "    n += 1;\n"
                 "}\n"
                 "P += n;"),
               WithinAbs(2, kEps));
    // Varying: break 2 at the first (i, j) with 4i + j >= 16u.
    const std::string brk =
        "float s = 0, i, j;\n"
        "for (i = 0; i < 4; i += 1) for (j = 0; j < 4; j += 1) { if (i * 4 + j >= u * 16) break 2; s += 1; }\n"
        "P = point(s, i, j);";
    CheckVec(PAt(brk, 0.25), {4, 1, 0});
    CheckVec(PAt(brk, 0.75), {12, 3, 0});
    // Varying: continue 2 at the first j >= 4u, in each of 3 outer iterations.
    const std::string cont =
        "float s = 0, i, j;\n"
        "for (i = 0; i < 3; i += 1) for (j = 0; j < 3; j += 1) { if (j >= u * 4) continue 2; s += 1; }\n"
        "P += s;";
    CHECK_THAT(Z(cont, 0.25), WithinAbs(3, kEps));  // j = 0 counts
    CHECK_THAT(Z(cont, 0.4), WithinAbs(6, kEps));   // j = 0, 1 count
    CHECK_THAT(Z(cont, 0.6), WithinAbs(9, kEps));   // all count
}

TEST_CASE("return from a function inside a loop, constant", "[compiler][semantics]") {
    const std::string f =
        "float firstSquareAbove(float x) {\n"
        "    float i;\n"
        "    for (i = 0; i < 10; i += 1)\n"
        "        if (i * i > x) return i;\n"
        "    return -1;\n"
        "}\n";
    // 4 * 4 = 16 > 10; no i < 10 has i * i > 200.
    CHECK_THAT(ZSource(f + Shader("P += firstSquareAbove(10);")), WithinAbs(4, kEps));
    CHECK_THAT(ZSource(f + Shader("P += firstSquareAbove(200);")), WithinAbs(-1, kEps));
}

TEST_CASE("return from a function inside a loop, varying", "[compiler][semantics]") {
    // Regression test (a bug found and fixed): a return under a varying condition is lost when the other path has not returned yet
    // (Lowerer::Merge ignores the then arm's return value while the else state has none).
    const std::string src =
        "float firstSquareAbove(float x) {\n"
        "    float i;\n"
        "    for (i = 0; i < 10; i += 1)\n"
        "        if (i * i > x) return i;\n"
        "    return -1;\n"
        "}\n" +
        Shader("P += firstSquareAbove(u * 100);");
    CHECK_THAT(ZSource(src, 0.25), WithinAbs(6, kEps));   // 36 > 25
    CHECK_THAT(ZSource(src, 0.75), WithinAbs(9, kEps));   // 81 > 75
    CHECK_THAT(ZSource(src, 0.99), WithinAbs(-1, kEps));  // 81 < 99
}

TEST_CASE("early return in the shader body", "[compiler][semantics]") {
    CHECK_THAT(Z("P += 1; if (u < 0.5) return; P += 2;", 0.25), WithinAbs(1, kEps));
    CHECK_THAT(Z("P += 1; if (u < 0.5) return; P += 2;", 0.75), WithinAbs(3, kEps));
    CHECK_THAT(Z("P += 1; return; P += 2;"), WithinAbs(1, kEps));
    // From inside a loop: three iterations, then the return skips the rest of the shader.
    CHECK_THAT(Z("float i; for (i = 0; i < 5; i += 1) { P += 1; if (i == 2) return; } P += 100;"), WithinAbs(3, kEps));
    // Varying: returns at the first i >= 4u, after i + 1 increments.
    const std::string body = "float i; for (i = 0; i < 5; i += 1) { P += 1; if (i >= u * 4) return; } P += 100;";
    CHECK_THAT(Z(body, 0.25), WithinAbs(2, kEps));  // i = 1
    CHECK_THAT(Z(body, 0.99), WithinAbs(5, kEps));  // i = 4 >= 3.96
    CHECK_THAT(Z(body, 0), WithinAbs(1, kEps));     // i = 0
}

TEST_CASE("loops whose bound is a parameter", "[compiler][semantics]") {
    // s = 1 + 2 + ... + octaves = n (n + 1) / 2 for a whole number of octaves.
    const std::string src =
        Shader("float i, s = 0;\nfor (i = 0; i < octaves; i += 1) s += i + 1;\nP += s;", "float octaves = 3");
    CHECK_THAT(ZSource(src), WithinAbs(6, kEps));
    CHECK_THAT(ZSource(src, 0.25, 0.75, {{"octaves", {3}}}), WithinAbs(6, kEps));
    CHECK_THAT(ZSource(src, 0.25, 0.75, {{"octaves", {0}}}), WithinAbs(0, kEps));
    CHECK_THAT(ZSource(src, 0.25, 0.75, {{"octaves", {2.5}}}), WithinAbs(6, kEps));  // i = 0, 1, 2
    // 100 iterations: past the generic program's unrolling budget (64), so only the instance,
    // lowered again with octaves = 100, has the value.
    CHECK_THAT(Eval(src, 0.25, 0.75, {{"octaves", {100}}}, Generic::Skip).z, WithinAbs(5050, kEps));
    // An fBm-like loop: amplitudes 1, 0.5, 0.25 -> 1.75.
    const std::string fbm =
        Shader("float i, amp = 1, s = 0;\nfor (i = 0; i < octaves; i += 1) { s += amp; amp *= 0.5; }\nP += s;",
               "float octaves = 3");
    CHECK_THAT(ZSource(fbm), WithinAbs(1.75, kEps));
    CHECK_THAT(ZSource(fbm, 0.25, 0.75, {{"octaves", {1}}}), WithinAbs(1, kEps));
}

TEST_CASE("a precompiled shader refuses a loop bounded by a parameter past 64 iterations", "[compiler][semantics]") {
    // `affray compile -o x.afb` stores the generic programs, and loading them specialises the
    // generic program, whose loop on a parameter was unrolled kVaryingLoopBudget = 64 times.
    const std::string src =
        Shader("float i, s = 0;\nfor (i = 0; i < octaves; i += 1) s += i + 1;\nP += s;", "float octaves = 3");
    compiler::CompiledShader s = test::CompileOrThrow(src);
    std::vector<std::string> errors;
    std::optional<vm::Program> loaded = compiler::Specialise(s.genericBound, {{"octaves", {100}}}, &errors);
    // The generic program was unrolled kVaryingLoopBudget = 64 times: the specialiser says so
    // rather than running a program that would give NaN.
    CHECK_FALSE(loaded);
    REQUIRE(errors.size() == 1);
    CHECK(errors[0].find("use the shader's source (.sl)") != std::string::npos);
    std::optional<vm::Program> fits = compiler::Specialise(s.genericBound, {{"octaves", {60}}}, &errors);
    REQUIRE(fits);
    CHECK_THAT(Run(*fits, 0.25, 0.75).z, WithinAbs(60.0 * 61 / 2, kEps));
}

TEST_CASE("a varying while loop", "[compiler][semantics]") {
    // i ends at the first whole number >= 10u.
    const std::string body = "float i = 0; while (i < u * 10) i += 1; P += i;";
    CHECK_THAT(Z(body, 0.25), WithinAbs(3, kEps));
    CHECK_THAT(Z(body, 0.75), WithinAbs(8, kEps));
    CHECK_THAT(Z(body, 0), WithinAbs(0, kEps));
    // Past the unrolling budget of 64 iterations, the paths still running get NaN (never a
    // wrong value); the others are exact.
    const std::string longer = "float i = 0; while (i < u * 1000) i += 1; P += i;";
    CHECK_THAT(Z(longer, 0.03125), WithinAbs(32, kEps));  // 31.25
    CHECK(std::isnan(Z(longer, 0.5)));                    // 500 iterations
}

TEST_CASE("a loop with a constant condition and a varying break compiles quickly", "[compiler][semantics]") {
    // Regression test (a bug found and fixed): `while (1)` (or `for (;;)`) left by a varying break is unrolled as a constant loop,
    // towards 100000 iterations, each simplifying a growing condition: the compiler runs for
    // minutes instead of treating the loop as varying (64 iterations, then NaN).
    const std::string body = "float i = 0; while (1) { if (i >= u * 10) break; i += 1; } P += i;";
    REQUIRE(CompilesWithin(Shader(body), 10));
    CHECK_THAT(Z(body, 0.25), WithinAbs(3, kEps));
}

TEST_CASE("variables assigned in one arm only", "[compiler][semantics]") {
    CHECK_THAT(Z("float a; if (u < 0.5) a = 3; else a = 4; P += a;", 0.25), WithinAbs(3, kEps));
    CHECK_THAT(Z("float a; if (u < 0.5) a = 3; else a = 4; P += a;", 0.75), WithinAbs(4, kEps));
    CHECK_THAT(Z("float a = 1; if (u < 0.5) a = 3; P += a;", 0.25), WithinAbs(3, kEps));
    CHECK_THAT(Z("float a = 1; if (u < 0.5) a = 3; P += a;", 0.75), WithinAbs(1, kEps));
    // Assigned on one path only (undefined elsewhere): where it was assigned, it has that value.
    CHECK_THAT(Z("float a; if (u < 0.5) a = 3; P += a;", 0.25), WithinAbs(3, kEps));
    CHECK_THAT(Z("float a; if (u < 0.5) P += 10; else a = 4; P += a;", 0.75), WithinAbs(4, kEps));
    // Triples too.
    CheckVec(PAt("point q; if (u < 0.5) q = point(1, 2, 3); else q = point(4, 5, 6); P = q;", 0.75), {4, 5, 6});
    // A declaration in an arm is local to it.
    CHECK_THAT(Z("float a = 1; if (u < 0.5) { float a = 5; P += a; } P += a;", 0.25), WithinAbs(6, kEps));
    CHECK_THAT(Z("float a = 1; if (u < 0.5) { float a = 5; P += a; } P += a;", 0.75), WithinAbs(1, kEps));
    // Assigned only inside a loop: its last value.
    CHECK_THAT(Z("float a, i; for (i = 0; i < 3; i += 1) a = i; P += a;"), WithinAbs(2, kEps));
}
