// tests/compiler/semantics_test.cpp: the language-semantics suite. One TEST_CASE per construct
// of the shading language (statements, operators, user functions, arrays, strings, every
// built-in), each compiling tiny shaders and checking P (or N) at chosen (u, v) of the unit square
// against values worked out by hand in the comments. On the unit square P = (u, v, 0),
// N = Ng = (0, 0, 1), dPdu = (1, 0, 0), dPdv = (0, 1, 0), s = u, t = v, du = dv = 1/1024, E = 0.
//
// Every value is checked on the instance's shade program, and the helper also requires the
// instance's bound program and the generic shade program (parameters as registers, so branches
// and loops on parameters are not folded while lowering) to give the same P, and an Interval
// evaluation of the bound program at the point to contain it.
// Tests whose comment starts "Regression test" guard bugs found by this suite and fixed.
#include <catch2/catch.hpp>

#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <csignal>
#include <numbers>
#include <thread>

#include "tests/test_util.h"

using namespace affray;
using Catch::Matchers::WithinAbs;

namespace {

using Overrides = std::vector<compiler::ParamOverride>;
constexpr double kPi = std::numbers::pi;
constexpr double kEps = 1e-12;

/// Runs `program` at (u, v) with number type N, its parameters (generic programs only) set from
/// `params`; returns output `name`.
template <class N>
vm::Vec3<N> RunAs(const vm::Program& program, double u, double v, const Overrides& params, const char* name) {
    vm::Interpreter<N> interp(program);
    for (const compiler::ParamOverride& o : params) {
        for (size_t i = 0; i < program.params.size(); ++i) {
            if (program.params[i].name != o.name) continue;
            std::vector<double> values = o.numbers;
            if (values.size() == 1 && program.params[i].size == 3) values.assign(3, values[0]);
            if (values.size() == 1 && program.params[i].size == 16)  // x times the identity
                for (int k = 0; k < 16; ++k) values.resize(16), values[k] = k % 5 == 0 ? o.numbers[0] : 0.0;
            interp.SetParam(i, values);
        }
    }
    return renderer::EvaluateOnPatch(interp, renderer::BilinearPatch::UnitSquare(), u, u, v, v, glm::dvec3(0.0),
                                     *program.findOutput(name));
}

/// Output `name` of `program` at (u, v) in doubles (through duals if it takes derivatives).
glm::dvec3 Run(const vm::Program& program, double u, double v, const Overrides& params = {}, const char* name = "P") {
    if (program.usesDerivatives()) {
        auto p = RunAs<vm::Dual<double>>(program, u, v, params, name);
        return {p.x.v, p.y.v, p.z.v};
    }
    auto p = RunAs<double>(program, u, v, params, name);
    return {p.x, p.y, p.z};
}

/// The Interval value of output `name` of `program` at the point (u, v).
std::array<vm::Interval, 3> RunInterval(const vm::Program& program, double u, double v, const char* name = "P") {
    if (program.usesDerivatives()) {
        auto p = RunAs<vm::Dual<vm::Interval>>(program, u, v, {}, name);
        return {p.x.v, p.y.v, p.z.v};
    }
    auto p = RunAs<vm::Interval>(program, u, v, {}, name);
    return {p.x, p.y, p.z};
}

bool SameNumber(double a, double b) {
    if (std::isnan(a) || std::isnan(b)) return std::isnan(a) && std::isnan(b);
    return std::abs(a - b) <= kEps * std::max(1.0, std::abs(a));
}

std::string Show(const glm::dvec3& p) {
    return "[" + std::to_string(p.x) + " " + std::to_string(p.y) + " " + std::to_string(p.z) + "]";
}

enum class Generic { Check, Skip };

/// Output `name` of the shader `source` (with `params`) at (u, v), from the instance's shade
/// program; requires its bound program (for P), the generic shade program and an Interval
/// evaluation to agree with it.
glm::dvec3 Eval(const std::string& source, double u, double v, const Overrides& params = {},
                Generic generic = Generic::Check, const char* name = "P") {
    compiler::CompiledShader s = test::CompileOrThrow(source, params);
    const glm::dvec3 shade = Run(s.shade, u, v, {}, name);
    INFO("shader:\n" << source << "\nat (" << u << ", " << v << "): shade " << Show(shade));
    if (std::string(name) == "P") {
        const glm::dvec3 bound = Run(s.bound, u, v);
        INFO("bound " << Show(bound));
        CHECK((SameNumber(bound.x, shade.x) && SameNumber(bound.y, shade.y) && SameNumber(bound.z, shade.z)));
        std::array<vm::Interval, 3> range = RunInterval(s.bound, u, v);
        for (int i = 0; i < 3; ++i) {
            INFO("component " << i << ": interval [" << range[i].lo() << ", " << range[i].hi() << "]");
            CHECK((std::isnan(shade[i]) || range[i].contains(shade[i])));
        }
    }
    if (generic == Generic::Check) {
        const glm::dvec3 g = Run(s.genericShade, u, v, params, name);
        INFO("generic " << Show(g));
        CHECK((SameNumber(g.x, shade.x) && SameNumber(g.y, shade.y) && SameNumber(g.z, shade.z)));
    }
    return shade;
}

/// `displacement t(<params>) { <body> }`.
std::string Shader(const std::string& body, const std::string& params = "") {
    return "displacement t(" + params + ") {\n" + body + "\n}\n";
}

/// P of a shader body at (u, v).
glm::dvec3 PAt(const std::string& body, double u = 0.25, double v = 0.75) { return Eval(Shader(body), u, v); }
/// P.z of a shader body at (u, v).
double Z(const std::string& body, double u = 0.25, double v = 0.75) { return PAt(body, u, v).z; }
/// P.z of a whole source file at (u, v).
double ZSource(const std::string& source, double u = 0.25, double v = 0.75, const Overrides& params = {}) {
    return Eval(source, u, v, params).z;
}

void CheckVec(const glm::dvec3& got, const glm::dvec3& want, double eps = kEps) {
    INFO("got " << Show(got) << ", want " << Show(want));
    CHECK_THAT(got.x, WithinAbs(want.x, eps));
    CHECK_THAT(got.y, WithinAbs(want.y, eps));
    CHECK_THAT(got.z, WithinAbs(want.z, eps));
}

/// Whether compiling `source` finishes within `seconds` (in a child process, killed after that).
bool CompilesWithin(const std::string& source, int seconds) {
    const pid_t child = fork();
    if (child == 0) {
        try {
            compiler::CompileResult r = compiler::CompileSource("test.sl", source);
            _exit(r.ok() ? 0 : 1);
        } catch (...) {
            _exit(2);
        }
    }
    REQUIRE(child > 0);
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(seconds);
    int status = 0;
    while (std::chrono::steady_clock::now() < deadline) {
        if (waitpid(child, &status, WNOHANG) == child) return WIFEXITED(status);
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    kill(child, SIGKILL);
    waitpid(child, &status, 0);
    return false;
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// Statements

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

// ---------------------------------------------------------------------------------------------
// Operators

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

TEST_CASE("logical operators and comparisons", "[compiler][semantics]") {
    CHECK_THAT(Z("P += !(u < 0.5);", 0.25), WithinAbs(0, kEps));
    CHECK_THAT(Z("P += !(u < 0.5);", 0.75), WithinAbs(1, kEps));
    const std::string both = "if (u < 0.5 && v > 0.5) P += 1;";
    CHECK_THAT(Z(both, 0.25, 0.75), WithinAbs(1, kEps));
    CHECK_THAT(Z(both, 0.25, 0.25), WithinAbs(0, kEps));
    CHECK_THAT(Z(both, 0.75, 0.75), WithinAbs(0, kEps));
    const std::string either = "if (u < 0.5 || v < 0.5) P += 1;";
    CHECK_THAT(Z(either, 0.75, 0.75), WithinAbs(0, kEps));
    CHECK_THAT(Z(either, 0.75, 0.25), WithinAbs(1, kEps));
    CHECK_THAT(Z(either, 0.25, 0.75), WithinAbs(1, kEps));
    // Floats in '&&' and '||' mean "!= 0".
    CHECK_THAT(Z("P += 2 && 0.5;"), WithinAbs(1, kEps));
    CHECK_THAT(Z("P += 0 || 0;"), WithinAbs(0, kEps));
    CHECK_THAT(Z("P += !2;"), WithinAbs(0, kEps));
    // Every comparison: 1 < 2, 2 <= 2, 3 > 2 hold; 2 >= 3, 1 != 1 do not; 1 == 1 holds.
    CHECK_THAT(Z("P += (1 < 2) + 10 * (2 <= 2) + 100 * (3 > 2) + 1000 * (2 >= 3) + 10000 * (1 == 1) + "
                 "100000 * (1 != 1);"),
               WithinAbs(10111, kEps));
    CHECK_THAT(Z("P += (2 < 1) + 10 * (3 <= 2) + 100 * (2 > 3) + 1000 * (3 >= 3) + 10000 * (1 == 2) + "
                 "100000 * (1 != 2);"),
               WithinAbs(101000, kEps));
    // Varying comparisons.
    CHECK_THAT(Z("P += (u <= 0.25) + 10 * (u >= 0.25) + 100 * (u == 0.25);", 0.25), WithinAbs(111, kEps));
    CHECK_THAT(Z("P += (u <= 0.25) + 10 * (u >= 0.25) + 100 * (u == 0.25);", 0.5), WithinAbs(10, kEps));
}

TEST_CASE("== and != on points", "[compiler][semantics]") {
    CHECK_THAT(Z("P += point(1, 2, 3) == point(1, 2, 3);"), WithinAbs(1, kEps));
    CHECK_THAT(Z("P += point(1, 2, 3) == point(1, 2, 4);"), WithinAbs(0, kEps));
    CHECK_THAT(Z("P += point(1, 2, 3) == point(0, 2, 3);"), WithinAbs(0, kEps));
    CHECK_THAT(Z("P += point(1, 2, 3) != point(1, 2, 4);"), WithinAbs(1, kEps));
    CHECK_THAT(Z("P += point(1, 2, 3) != point(1, 2, 3);"), WithinAbs(0, kEps));
    // A float compares as a triple of three copies.
    CHECK_THAT(Z("P += point(2, 2, 2) == 2;"), WithinAbs(1, kEps));
    CHECK_THAT(Z("P += point(2, 2, 3) == 2;"), WithinAbs(0, kEps));
    // Varying, and across point, vector and normal.
    CHECK_THAT(Z("if (P == point(u, v, 0)) P += 1;"), WithinAbs(1, kEps));
    CHECK_THAT(Z("if (P != point(0.25, v, 0)) P += 1;", 0.25), WithinAbs(0, kEps));
    CHECK_THAT(Z("if (P != point(0.25, v, 0)) P += 1;", 0.75), WithinAbs(1, kEps));
    CHECK_THAT(Z("P += vector(0, 0, 1) == N;"), WithinAbs(1, kEps));
}

TEST_CASE("?: with float and point arms", "[compiler][semantics]") {
    CHECK_THAT(Z("P += u < 0.5 ? 1 : 2;", 0.25), WithinAbs(1, kEps));
    CHECK_THAT(Z("P += u < 0.5 ? 1 : 2;", 0.75), WithinAbs(2, kEps));
    // A float arm is promoted to the point's type.
    CheckVec(PAt("point q = u < 0.5 ? point(1, 2, 3) : 7; P = q;", 0.25), {1, 2, 3});
    CheckVec(PAt("point q = u < 0.5 ? point(1, 2, 3) : 7; P = q;", 0.75), {7, 7, 7});
    CheckVec(PAt("P = u < 0.5 ? P + vector(0, 0, 1) : P - vector(0, 0, 1);", 0.75), {0.75, 0.75, -1});
    // A constant condition picks its arm.
    CHECK_THAT(Z("P += 1 ? 5 : 6;"), WithinAbs(5, kEps));
    // Boolean arms: at (0.25, 0.75) v > 0.5 holds; at (0.75, 0.75) v < 0.5 does not.
    CHECK_THAT(Z("P += (u < 0.5 ? v > 0.5 : v < 0.5) ? 10 : 20;", 0.25, 0.75), WithinAbs(10, kEps));
    CHECK_THAT(Z("P += (u < 0.5 ? v > 0.5 : v < 0.5) ? 10 : 20;", 0.75, 0.75), WithinAbs(20, kEps));
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

TEST_CASE("booleans used as floats", "[compiler][semantics]") {
    CHECK_THAT(Z("P += (u < 0.5) * 10;", 0.25), WithinAbs(10, kEps));
    CHECK_THAT(Z("P += (u < 0.5) * 10;", 0.75), WithinAbs(0, kEps));
    CHECK_THAT(Z("float b; b = u < 0.5; P += b;", 0.25), WithinAbs(1, kEps));
    CHECK_THAT(Z("P += -(1 < 2);"), WithinAbs(-1, kEps));
    CHECK_THAT(Z("P += sin(1 < 2);"), WithinAbs(std::sin(1.0), kEps));
    CHECK_THAT(Z("float a[2] = {1 < 2, 2 < 1}; P += a[0] * 10 + a[1];"), WithinAbs(10, kEps));
    CHECK_THAT(ZSource("float twice(float x) { return 2 * x; }\n" + Shader("P += twice(1 < 2);")), WithinAbs(2, kEps));
}

TEST_CASE("booleans initialise and are returned as floats", "[compiler][semantics]") {
    // Was a bug (fixed in Lowerer::Convert): `b = u < 0.5` was accepted, but `float b = u < 0.5`
    // and `return 1 < 2` in a float function were rejected ("cannot assign a boolean to ...").
    CHECK_THAT(Z("float b = u < 0.5; P += b;", 0.25), WithinAbs(1, kEps));
    CHECK_THAT(Z("float b = u < 0.5; P += b;", 0.75), WithinAbs(0, kEps));
    CheckVec(PAt("vector w = u < 0.5; P = w;", 0.25), {1, 1, 1});
    CHECK_THAT(ZSource("float yes() { return 1 < 2; }\n" + Shader("P += yes();")), WithinAbs(1, kEps));
}

// ---------------------------------------------------------------------------------------------
// User functions

TEST_CASE("functions: value parameters", "[compiler][semantics]") {
    // The callee's copy changes; the caller's a stays 3: 6 + 3.
    CHECK_THAT(ZSource("float twice(float x) { x *= 2; return x; }\n" + Shader("float a = 3; P += twice(a) + a;")),
               WithinAbs(9, kEps));
    CheckVec(Eval("point moved(point p; vector d) { return p + d; }\n" + Shader("P = moved(P, vector(0, 0, 2));"), 0.25,
                  0.75),
             {0.25, 0.75, 2});
    // A float argument is promoted to the triple parameter.
    CheckVec(Eval("vector same(vector d) { return d; }\n" + Shader("P += same(1);"), 0.25, 0.75), {1.25, 1.75, 1});
    // Names sharing a type; varying arguments.
    CHECK_THAT(ZSource("float sub(float a, b) { return a - b; }\n" + Shader("P += sub(5, 2) + sub(v, u);")),
               WithinAbs(3.5, kEps));
    // A parameter shadows the global of the same name.
    CHECK_THAT(ZSource("float f(float u) { return u * 2; }\n" + Shader("P += f(3);")), WithinAbs(6, kEps));
}

TEST_CASE("functions: output parameters", "[compiler][semantics]") {
    CHECK_THAT(
        ZSource("void dbl(float x; output float y) { y = 2 * x; }\n" + Shader("float r = 0; dbl(5, r); P += r;")),
        WithinAbs(10, kEps));
    const std::string lift = "void lift(output point q; float h) { q += vector(0, 0, h); }\n";
    CheckVec(Eval(lift + Shader("point a = (1, 2, 3); lift(a, 4); P = a;"), 0.25, 0.75), {1, 2, 7});
    CheckVec(Eval(lift + Shader("lift(P, 0.5);"), 0.25, 0.75), {0.25, 0.75, 0.5});
    // In a loop: 0 + 1 + 2 + 3.
    CHECK_THAT(ZSource("void acc(output float s; float x) { s += x; }\n" +
                       Shader("float i, s = 0; for (i = 0; i < 4; i += 1) acc(s, i); P += s;")),
               WithinAbs(6, kEps));
    // Under a varying condition: written only where it holds.
    const std::string set5 =
        "void set5(output float y) { y = 5; }\n" + Shader("float a = 1; if (u < 0.5) set5(a); P += a;");
    CHECK_THAT(ZSource(set5, 0.25), WithinAbs(5, kEps));
    CHECK_THAT(ZSource(set5, 0.75), WithinAbs(1, kEps));
    // An output parameter and a return value: 3 * 10 + 4.
    CHECK_THAT(ZSource("float both(output float y) { y = 3; return 4; }\n" +
                       Shader("float a = 0; float r = both(a); P += a * 10 + r;")),
               WithinAbs(34, kEps));
    // A point variable passed to an output vector parameter.
    CheckVec(Eval("void up(output vector q) { q = vector(0, 0, 1); }\n" + Shader("point p = (5, 5, 5); up(p); P = p;"),
                  0.25, 0.75),
             {0, 0, 1});
    // Written before an early return on some points only: y = 1 there, 2 elsewhere.
    const std::string early =
        "void f(output float y) { y = 1; if (u > 0.5) return; y = 2; }\n" + Shader("float a = 0; f(a); P += a;");
    CHECK_THAT(ZSource(early, 0.25), WithinAbs(2, kEps));
    CHECK_THAT(ZSource(early, 0.75), WithinAbs(1, kEps));
    // A variable with no value yet, assigned by the call.
    CHECK_THAT(ZSource("void seven(output float y) { y = 7; }\n" + Shader("float r; seven(r); P += r;")),
               WithinAbs(7, kEps));
}

TEST_CASE("functions calling functions, and nested definitions", "[compiler][semantics]") {
    // (2^2)^2, through a local (a call in the return expression itself: see the [bug] test below).
    CHECK_THAT(
        ZSource("float sq(float x) { return x * x; }\nfloat quad(float x) { float s = sq(x); s = sq(s); return s; }\n" +
                Shader("P += quad(2);")),
        WithinAbs(16, kEps));
    // A top-level function may call one defined after it.
    CHECK_THAT(ZSource("float a() { float r = b(); return r + 1; }\nfloat b() { return 3; }\n" + Shader("P += a();")),
               WithinAbs(4, kEps));
    // Defined in the shader body.
    CHECK_THAT(Z("float tw(float x) { return 2 * x; } P += tw(u);", 0.25), WithinAbs(0.5, kEps));
    // Defined inside another function: (2 + 1) * 10.
    CHECK_THAT(
        ZSource("float outer(float x) { float inner(float y) { return y + 1; } float r = inner(x); return r * 10; }\n" +
                Shader("P += outer(2);")),
        WithinAbs(30, kEps));
    // A nested definition shadows a top-level one.
    CHECK_THAT(ZSource("float f() { return 1; }\n" + Shader("float f() { return 2; } P += f();")), WithinAbs(2, kEps));
    // The top-level one is visible again outside the block defining the other.
    CHECK_THAT(ZSource("float f() { return 1; }\n" + Shader("{ float f() { return 2; } P += f(); } P += 10 * f();")),
               WithinAbs(12, kEps));
    // A void function calling a function.
    CHECK_THAT(ZSource("float sq(float x) { return x * x; }\nvoid addsq(float x) { P += vector(0, 0, sq(x)); }\n" +
                       Shader("addsq(3);")),
               WithinAbs(9, kEps));
}

TEST_CASE("loops inside functions, and declarations inside loops", "[compiler][semantics]") {
    // The first r with r * r >= x: x = 7.5 -> 3, x = 2.5 -> 2.
    const std::string root =
        "float f(float x) { float r = 0; while (r * r < x) r += 1; return r; }\n" + Shader("P += f(u * 10);");
    CHECK_THAT(ZSource(root, 0.75), WithinAbs(3, kEps));
    CHECK_THAT(ZSource(root, 0.25), WithinAbs(2, kEps));
    // A break in a function's loop: the first i > 4u, i.e. 4 for u = 0.75, 2 for u = 0.25.
    const std::string brk =
        "float f(float x) { float i; for (i = 0; i < 5; i += 1) { if (i > x) break; } return i; }\n" +
        Shader("P += f(u * 4);");
    CHECK_THAT(ZSource(brk, 0.75), WithinAbs(4, kEps));
    CHECK_THAT(ZSource(brk, 0.25), WithinAbs(2, kEps));
    // A variable declared in the loop body is a new one each iteration: 0 + 2 + 4.
    CHECK_THAT(Z("float i, s = 0; for (i = 0; i < 3; i += 1) { float k = i * 2; s += k; } P += s;"),
               WithinAbs(6, kEps));
    // A shader may share its name with a built-in.
    CHECK_THAT(ZSource("displacement round() {\n  P += round(0.5);\n}\n"), WithinAbs(1, kEps));
    // A user function may share its name with a built-in, and is the one called.
    CHECK_THAT(ZSource("float mod(float a, b) { return 42; }\n" + Shader("P += mod(1, 2);")), WithinAbs(42, kEps));
}

TEST_CASE("a user function named like noise, transform, spline or filterstep is the one called",
          "[compiler][semantics]") {
    // Regression test (a bug found and fixed): LowerExpr tries the library version first whenever the context wants a triple, so a
    // user function named noise (transform, spline, filterstep) is bypassed in `P = noise(P)`
    // or `P += noise(P)`, while it is called elsewhere (and a user `mod` always is).
    CheckVec(Eval("point noise(point p) { return p * 2; }\n" + Shader("P = noise(P);"), 0.25, 0.75), {0.5, 1.5, 0});
    CHECK_THAT(ZSource("float noise(point p) { return 7; }\n" + Shader("P += noise(P);")), WithinAbs(7, kEps));
    CheckVec(Eval("vector transform(string s; vector v) { return v * 3; }\n" + Shader("P = transform(\"world\", P);"),
                  0.25, 0.75),
             {0.75, 2.25, 0});
}

TEST_CASE("a return value computed by calling a function", "[compiler][semantics]") {
    // Regression test (a bug found and fixed): `return g(x);` in a function reports "function 'f' returns a float but has no
    // 'return' with a value": Lowerer::LowerJump keeps a reference into m_state.contexts across
    // lowering the returned expression, whose inlined call grows (reallocates) that vector.
    CHECK_THAT(ZSource("float sq(float x) { return x * x; }\nfloat quad(float x) { return sq(sq(x)); }\n" +
                       Shader("P += quad(2);")),
               WithinAbs(16, kEps));
    CHECK_THAT(ZSource("float a() { return b() + 1; }\nfloat b() { return 3; }\n" + Shader("P += a();")),
               WithinAbs(4, kEps));
    CHECK_THAT(ZSource("float outer(float x) { float inner(float y) { return y + 1; } return inner(x) * 10; }\n" +
                       Shader("P += outer(2);")),
               WithinAbs(30, kEps));
}

TEST_CASE("extern reads and writes the caller's variables", "[compiler][semantics]") {
    CHECK_THAT(Z("float k = 5; float f(float x) { extern float k; return x * k; } P += f(2);"), WithinAbs(10, kEps));
    // Each call writes back: 5 + 1 + 1.
    CHECK_THAT(Z("float k = 5; void bump() { extern float k; k += 1; } bump(); bump(); P += k;"), WithinAbs(7, kEps));
    CheckVec(PAt("point c = (1, 2, 3); void shift() { extern point c; c += 1; } shift(); P = c;"), {2, 3, 4});
    // The global P.
    CHECK_THAT(ZSource("void lift() { extern point P; P += vector(0, 0, 1); }\n" + Shader("lift();")),
               WithinAbs(1, kEps));
    // Through two levels: g sees f's extern k: 2 * 3 + 2.
    CHECK_THAT(
        Z("float k = 2;\n"
          "float f() { extern float k; float g() { extern float k; return k * 3; } float r = g(); return r + k; }\n"
          "P += f();"),
        WithinAbs(8, kEps));
    // A write under a varying condition.
    const std::string body = "float k = 0; void setk() { extern float k; k = 1; } if (u < 0.5) setk(); P += k;";
    CHECK_THAT(Z(body, 0.25), WithinAbs(1, kEps));
    CHECK_THAT(Z(body, 0.75), WithinAbs(0, kEps));
    // A shader parameter, from a top-level function.
    const std::string src =
        "float twiceKm() { extern float Km; return Km * 2; }\n" + Shader("P += twiceKm();", "float Km = 2");
    CHECK_THAT(ZSource(src), WithinAbs(4, kEps));
    CHECK_THAT(ZSource(src, 0.25, 0.75, {{"Km", {5}}}), WithinAbs(10, kEps));
}

TEST_CASE("a nested function uses the enclosing body's variables without extern, in every role",
          "[compiler][semantics]") {
    // Read and written.
    CHECK_THAT(Z("float k = 5; void bump() { k += 1; } bump(); bump(); P += k;"), WithinAbs(7, kEps));
    // As an output argument of a user function, and of a query (evalparam reads a parameter).
    CHECK_THAT(Z("float k = 1; void twice(output float x) { x *= 2; } void f() { twice(k); } f(); P += k;"),
               WithinAbs(2, kEps));
    CHECK_THAT(ZSource(Shader("float k = 0; void f() { evalparam(\"Km\", k); } f(); P += k;", "float Km = 3")),
               WithinAbs(3, kEps));
    // An array's elements, read and written.
    CHECK_THAT(Z("float a[3] = {1, 2, 3}; float f() { a[1] = 10; return a[0] + a[2]; } float r = f(); P += r + a[1];"),
               WithinAbs(14, kEps));
    // setzcomp's first argument.
    CHECK_THAT(Z("point q = (0, 0, 1); void f() { setzcomp(q, 4); } f(); P += zcomp(q);"), WithinAbs(4, kEps));
    // From a nested function called by another that never names it: read, and written back
    // through both calls (1 + 10, then doubled by the body).
    CHECK_THAT(Z("float k = 1; void inner() { k += 10; } void outer() { inner(); } outer(); P += 2 * k;"),
               WithinAbs(22, kEps));
    CHECK_THAT(Z("float k = 3; float inner() { return k * k; } float outer() { return inner() + 1; } P += outer();"),
               WithinAbs(10, kEps));
}

TEST_CASE("a shader class runs construct, begin and displacement over its members and parameters",
          "[compiler][semantics]") {
    const std::string source =
        "class c(float Km = 2) {\n"
        "  uniform float m = 0;\n"
        "  varying float w = 0;\n"
        "  float h(float x) { return x * m + w; }\n"
        "  void construct() { m = 1; }\n"
        "  public void begin() { float k; evalparam(\"Km\", k); m *= k; w = u; }\n"
        "  public void displacement(output point P; output normal N) {\n"
        "    if (u > 0.5) return;\n"
        "    P += vector(0, 0, h(3));\n"
        "    N = calculatenormal(P);\n"
        "  }\n"
        "  public void surface(output color Ci, Oi) { illuminance(P) { Ci += Cl * diffuse(N); } }\n"
        "}\n";
    // 3 * Km + u below u = 0.5; nothing above (the method returns early).
    CHECK_THAT(ZSource(source, 0.25), WithinAbs(6.25, kEps));
    CHECK_THAT(ZSource(source, 0.25, 0.75, {{"Km", {5}}}), WithinAbs(15.25, kEps));
    CHECK_THAT(ZSource(source, 0.75), WithinAbs(0, kEps));
}

TEST_CASE("void functions", "[compiler][semantics]") {
    CHECK_THAT(ZSource("void addz(float d) { P += vector(0, 0, d); }\n" + Shader("addz(1); addz(u);"), 0.25),
               WithinAbs(1.25, kEps));
    // An early return: nothing for d < 0.
    const std::string src =
        "void maybe(float d) { if (d < 0) return; P += vector(0, 0, d); }\n" + Shader("maybe(u - 0.5); maybe(2);");
    CHECK_THAT(ZSource(src, 0.25), WithinAbs(2, kEps));
    CHECK_THAT(ZSource(src, 0.75), WithinAbs(2.25, kEps));
    CHECK_THAT(ZSource("void nothing() { return; }\n" + Shader("nothing(); P += 1;")), WithinAbs(1, kEps));
}

TEST_CASE("a function with several returns, constant arguments", "[compiler][semantics]") {
    const std::string f = "float classify(float x) { if (x < 0) return -1; if (x == 0) return 0; return 1; }\n";
    // -1 + 10 * 0 + 100 * 1
    CHECK_THAT(ZSource(f + Shader("P += classify(-3) + 10 * classify(0) + 100 * classify(2);")), WithinAbs(99, kEps));
    // Both arms return.
    const std::string pick =
        "float pick(float x) { if (x < 0.5) return 10; else return 20; }\n" + Shader("P += pick(u);");
    CHECK_THAT(ZSource(pick, 0.25), WithinAbs(10, kEps));
    CHECK_THAT(ZSource(pick, 0.75), WithinAbs(20, kEps));
    // Only the else arm returns.
    const std::string pick2 =
        "float pick2(float x) { if (x < 0.5) { x = 1; } else return 20; return 30; }\n" + Shader("P += pick2(u);");
    CHECK_THAT(ZSource(pick2, 0.25), WithinAbs(30, kEps));
    CHECK_THAT(ZSource(pick2, 0.75), WithinAbs(20, kEps));
}

TEST_CASE("a function with several returns, varying arguments", "[compiler][semantics]") {
    // Regression test (a bug found and fixed): `if (x < 0) return -1;` without an else loses its return value when x varies:
    // classify(u - 0.5) is 1 everywhere (see Lowerer::Merge and FlowContext::returned).
    const std::string src = "float classify(float x) { if (x < 0) return -1; if (x == 0) return 0; return 1; }\n" +
                            Shader("P += classify(u - 0.5);");
    CHECK_THAT(ZSource(src, 0.25), WithinAbs(-1, kEps));
    CHECK_THAT(ZSource(src, 0.5), WithinAbs(0, kEps));
    CHECK_THAT(ZSource(src, 0.75), WithinAbs(1, kEps));
}

// ---------------------------------------------------------------------------------------------
// Arrays

TEST_CASE("arrays: initialiser lists and constant indices", "[compiler][semantics]") {
    CHECK_THAT(Z("float a[3] = {1, 2, 3}; P += a[0] + 10 * a[1] + 100 * a[2];"), WithinAbs(321, kEps));
    CheckVec(PAt("point pts[2] = {(1, 2, 3), point(4, 5, 6)}; P = pts[1];"), {4, 5, 6});
    // A float element is promoted: (1,1,1) + (1,2,3).
    CheckVec(PAt("vector w[2] = {1, vector(1, 2, 3)}; P = w[0] + w[1];"), {2, 3, 4});
    CHECK_THAT(Z("float a[4] = {10, 20, 30, 40}; P += a[1 + 2];"), WithinAbs(40, kEps));
    // Without an initialiser the elements are 0.
    CHECK_THAT(Z("float a[3]; a[0] = 1; P += a[0] + a[1];"), WithinAbs(1, kEps));
    // A loop over the elements: 1 + 2 + 3 + 4.
    CHECK_THAT(Z("float a[4] = {1, 2, 3, 4}; float i, s = 0; for (i = 0; i < 4; i += 1) s += a[i]; P += s;"),
               WithinAbs(10, kEps));
    // Varying elements.
    CHECK_THAT(Z("float a[2] = {u, v}; P += a[1] - a[0];"), WithinAbs(0.5, kEps));
}

TEST_CASE("arrays: varying indices", "[compiler][semantics]") {
    // The index is truncated: floor(4u).
    const std::string body = "float a[4] = {10, 20, 30, 40}; P += a[u * 4];";
    CHECK_THAT(Z(body, 0), WithinAbs(10, kEps));
    CHECK_THAT(Z(body, 0.25), WithinAbs(20, kEps));
    CHECK_THAT(Z(body, 0.6), WithinAbs(30, kEps));
    CHECK_THAT(Z(body, 0.75), WithinAbs(40, kEps));
    CheckVec(PAt("point pts[2] = {(1, 2, 3), (4, 5, 6)}; P = pts[u * 2];", 0.75), {4, 5, 6});
    // Outside the array: NaN, never a wrong element.
    CHECK(std::isnan(Z("float a[2] = {1, 2}; P += a[u * 4];", 0.75)));
}

TEST_CASE("arrays: element assignment", "[compiler][semantics]") {
    // a = {1, 7, 13}
    CHECK_THAT(Z("float a[3] = {1, 2, 3}; a[1] = 7; a[2] += 10; P += a[0] + 10 * a[1] + 100 * a[2];"),
               WithinAbs(1371, kEps));
    // A varying index floor(3u) writes one element.
    const std::string body = "float a[3] = {0, 0, 0}; a[u * 3] = 5; P += a[0] + 10 * a[1] + 100 * a[2];";
    CHECK_THAT(Z(body, 0.25), WithinAbs(5, kEps));
    CHECK_THAT(Z(body, 0.5), WithinAbs(50, kEps));
    CHECK_THAT(Z(body, 0.75), WithinAbs(500, kEps));
    // A varying compound assignment.
    CHECK_THAT(Z("float a[2] = {1, 2}; a[u * 2] *= 10; P += a[0] + a[1];", 0.75), WithinAbs(21, kEps));
    // Under a varying condition.
    CHECK_THAT(Z("float a[2] = {1, 2}; if (u < 0.5) a[0] = 9; P += a[0];", 0.25), WithinAbs(9, kEps));
    CHECK_THAT(Z("float a[2] = {1, 2}; if (u < 0.5) a[0] = 9; P += a[0];", 0.75), WithinAbs(1, kEps));
    // Point elements.
    CheckVec(PAt("point q[2] = {(0, 0, 0), (0, 0, 0)}; q[1] = P; setzcomp(P, 3); P = q[1] + P;"), {0.5, 1.5, 3});
}

TEST_CASE("arrays passed to functions", "[compiler][semantics]") {
    CHECK_THAT(ZSource("float sum3(float a[]) { return a[0] + a[1] + a[2]; }\n" +
                       Shader("float b[3] = {1, 2, 3}; P += sum3(b);")),
               WithinAbs(6, kEps));
    CHECK_THAT(ZSource("float second(float a[2]) { return a[1]; }\n" + Shader("float b[2] = {4, 5}; P += second(b);")),
               WithinAbs(5, kEps));
    // An output array is written back: b = {1, 7}.
    CHECK_THAT(ZSource("void fill(output float a[]) { a[1] = 7; }\n" +
                       Shader("float b[2] = {1, 2}; fill(b); P += b[0] + 10 * b[1];")),
               WithinAbs(71, kEps));
    // An array passed by value is the callee's copy: 100 + 1.
    CHECK_THAT(ZSource("float clobber(float a[]) { a[0] = 100; return a[0]; }\n" +
                       Shader("float b[1] = {1}; float r = clobber(b); P += r + b[0];")),
               WithinAbs(101, kEps));
    // Point arrays, with a varying index inside the function.
    CheckVec(Eval("point pick(point a[]; float i) { return a[i]; }\n" +
                      Shader("point b[2] = {(1, 1, 1), (2, 2, 2)}; P = pick(b, u * 2);"),
                  0.75, 0.75),
             {2, 2, 2});
}

// ---------------------------------------------------------------------------------------------
// Strings

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

// ---------------------------------------------------------------------------------------------
// Built-ins

TEST_CASE("built-ins: abs sign floor ceil round", "[compiler][semantics][builtins]") {
    CHECK_THAT(Z("P += abs(-2.5);"), WithinAbs(2.5, kEps));
    CHECK_THAT(Z("P += abs(u - 0.5);", 0.25), WithinAbs(0.25, kEps));
    CHECK_THAT(Z("P += sign(-3) + 10 * sign(0) + 100 * sign(2);"), WithinAbs(99, kEps));
    CHECK_THAT(Z("P += floor(-1.5) + 10 * floor(1.5);"), WithinAbs(8, kEps));  // -2 + 10
    CHECK_THAT(Z("P += ceil(-1.5) + 10 * ceil(1.2);"), WithinAbs(19, kEps));   // -1 + 20
    CHECK_THAT(Z("P += floor(3) + ceil(3);"), WithinAbs(6, kEps));
    // round: halves away from 0.
    CHECK_THAT(Z("P += round(0.5);"), WithinAbs(1, kEps));
    CHECK_THAT(Z("P += round(-0.5);"), WithinAbs(-1, kEps));
    CHECK_THAT(Z("P += round(1.5);"), WithinAbs(2, kEps));
    CHECK_THAT(Z("P += round(2.5);"), WithinAbs(3, kEps));
    CHECK_THAT(Z("P += round(-2.5);"), WithinAbs(-3, kEps));
    CHECK_THAT(Z("P += round(1.4) + 10 * round(-1.6);"), WithinAbs(-19, kEps));  // 1 - 20
    // On triples, componentwise.
    CheckVec(PAt("P = floor(point(1.5, -1.5, 2));"), {1, -2, 2});
    CheckVec(PAt("P = ceil(vector(1.5, -1.5, 2));"), {2, -1, 2});
    CheckVec(PAt("P = round(point(0.5, -0.5, 1.49));"), {1, -1, 1});
    CheckVec(PAt("P = floor(P * 4);", 0.3, 0.6), {1, 2, 0});
}

TEST_CASE("built-ins: mod has the sign of the divisor", "[compiler][semantics][builtins]") {
    CHECK_THAT(Z("P += mod(-1.5, 1);"), WithinAbs(0.5, kEps));
    CHECK_THAT(Z("P += mod(5, 3);"), WithinAbs(2, kEps));
    CHECK_THAT(Z("P += mod(-5, 3);"), WithinAbs(1, kEps));
    CHECK_THAT(Z("P += mod(5, -3);"), WithinAbs(-1, kEps));
    CHECK_THAT(Z("P += mod(7.5, 2);"), WithinAbs(1.5, kEps));
    CHECK_THAT(Z("P += mod(u * 10, 1);", 0.25), WithinAbs(0.5, kEps));
    CheckVec(PAt("P = mod(point(5, -5, 7.5), 3);"), {2, 1, 1.5});
}

TEST_CASE("built-ins: min max clamp", "[compiler][semantics][builtins]") {
    CHECK_THAT(Z("P += min(1, 2);"), WithinAbs(1, kEps));
    CHECK_THAT(Z("P += max(1, 2);"), WithinAbs(2, kEps));
    CHECK_THAT(Z("P += min(3, 1, 2);"), WithinAbs(1, kEps));
    CHECK_THAT(Z("P += max(3, 1, 2);"), WithinAbs(3, kEps));
    CHECK_THAT(Z("P += max(1, 2, 3);"), WithinAbs(3, kEps));
    CHECK_THAT(Z("P += min(u, v);", 0.25, 0.75), WithinAbs(0.25, kEps));
    CheckVec(PAt("P = min(point(1, 5, 3), point(4, 2, 6));"), {1, 2, 3});
    CheckVec(PAt("P = max(point(1, 5, 3), point(4, 2, 6), point(0, 0, 9));"), {4, 5, 9});
    CheckVec(PAt("P = min(point(1, 5, 3), 2);"), {1, 2, 2});
    CHECK_THAT(Z("P += clamp(5, 0, 1) + 10 * clamp(-1, 0, 1) + 100 * clamp(0.5, 0, 1);"), WithinAbs(51, kEps));
    CheckVec(PAt("P = clamp(point(-1, 0.5, 2), 0, 1);"), {0, 0.5, 1});
    CheckVec(PAt("P = clamp(point(-1, 0.5, 2), point(0, 0.75, 0), point(1, 1, 1.5));"), {0, 0.75, 1.5});
}

TEST_CASE("built-ins: step and smoothstep", "[compiler][semantics][builtins]") {
    // step(edge, x) = x < edge ? 0 : 1
    CHECK_THAT(Z("P += step(0.5, 0.4);"), WithinAbs(0, kEps));
    CHECK_THAT(Z("P += step(0.5, 0.5);"), WithinAbs(1, kEps));
    CHECK_THAT(Z("P += step(0.5, 0.6);"), WithinAbs(1, kEps));
    CHECK_THAT(Z("P += step(0.5, u);", 0.25), WithinAbs(0, kEps));
    // smoothstep: 0 below, 1 above, 3t^2 - 2t^3 between.
    CHECK_THAT(Z("P += smoothstep(0, 1, -1);"), WithinAbs(0, kEps));
    CHECK_THAT(Z("P += smoothstep(0, 1, 2);"), WithinAbs(1, kEps));
    CHECK_THAT(Z("P += smoothstep(0, 1, 0.5);"), WithinAbs(0.5, kEps));
    CHECK_THAT(Z("P += smoothstep(0, 2, 0.5);"), WithinAbs(0.15625, kEps));  // t = 1/4
    CHECK_THAT(Z("P += smoothstep(1, 3, 2.5);"), WithinAbs(0.84375, kEps));  // t = 3/4
    CHECK_THAT(Z("P += smoothstep(0, 1, u);", 0.25), WithinAbs(0.15625, kEps));
}

TEST_CASE("built-ins: pow sqrt inversesqrt exp log", "[compiler][semantics][builtins]") {
    CHECK_THAT(Z("P += pow(2, 0.5);"), WithinAbs(std::sqrt(2.0), kEps));
    CHECK_THAT(Z("P += pow(2, -1);"), WithinAbs(0.5, kEps));
    CHECK_THAT(Z("P += pow(9, u);", 0.5), WithinAbs(3, kEps));
    CHECK_THAT(Z("P += sqrt(2);"), WithinAbs(std::sqrt(2.0), kEps));
    CHECK_THAT(Z("P += sqrt(u);", 0.25), WithinAbs(0.5, kEps));
    CHECK_THAT(Z("P += inversesqrt(16);"), WithinAbs(0.25, kEps));
    CHECK_THAT(Z("P += exp(0);"), WithinAbs(1, kEps));
    CHECK_THAT(Z("P += exp(log(2));"), WithinAbs(2, kEps));
    CHECK_THAT(Z("P += log(1);"), WithinAbs(0, kEps));
    CHECK_THAT(Z("P += log(100, 10);"), WithinAbs(2, kEps));
    CHECK_THAT(Z("P += log(0.25, 2);"), WithinAbs(-2, kEps));
}

TEST_CASE("built-ins: trigonometry, radians, degrees and PI", "[compiler][semantics][builtins]") {
    CHECK_THAT(Z("P += sin(PI / 6);"), WithinAbs(0.5, kEps));
    CHECK_THAT(Z("P += cos(PI / 3);"), WithinAbs(0.5, kEps));
    CHECK_THAT(Z("P += tan(PI / 4);"), WithinAbs(1, kEps));
    CHECK_THAT(Z("P += tan(-PI / 4);"), WithinAbs(-1, kEps));
    CHECK_THAT(Z("P += asin(1);"), WithinAbs(kPi / 2, kEps));
    CHECK_THAT(Z("P += asin(0.5);"), WithinAbs(kPi / 6, kEps));
    CHECK_THAT(Z("P += acos(0);"), WithinAbs(kPi / 2, kEps));
    CHECK_THAT(Z("P += acos(-1);"), WithinAbs(kPi, kEps));
    CHECK_THAT(Z("P += atan(1);"), WithinAbs(kPi / 4, kEps));
    // atan(y, x): the angle of (x, y).
    CHECK_THAT(Z("P += atan(1, -1);"), WithinAbs(3 * kPi / 4, kEps));
    CHECK_THAT(Z("P += atan(-1, -1);"), WithinAbs(-3 * kPi / 4, kEps));
    CHECK_THAT(Z("P += atan(0, -1);"), WithinAbs(kPi, kEps));
    CHECK_THAT(Z("P += atan(2, 0);"), WithinAbs(kPi / 2, kEps));
    CHECK_THAT(Z("P += radians(90);"), WithinAbs(kPi / 2, kEps));
    CHECK_THAT(Z("P += degrees(PI / 2);"), WithinAbs(90, kEps));
    CHECK_THAT(Z("P += PI;"), WithinAbs(kPi, kEps));
    CHECK_THAT(Z("P += sin(u * PI);", 0.5), WithinAbs(1, kEps));
}

TEST_CASE("built-ins: length distance normalize and components", "[compiler][semantics][builtins]") {
    CHECK_THAT(Z("P += length(vector(2, 3, 6));"), WithinAbs(7, kEps));
    CHECK_THAT(Z("P += distance(point(1, 2, 3), point(4, 6, 3));"), WithinAbs(5, kEps));
    CHECK_THAT(Z("P += length(P);", 0.6, 0.8), WithinAbs(1, kEps));
    CheckVec(PAt("P = normalize(vector(0, 3, 4));"), {0, 0.6, 0.8});
    CheckVec(PAt("P = normalize(P);", 0.6, 0.8), {0.6, 0.8, 0});
    CHECK_THAT(Z("P += xcomp(point(1, 2, 3)) + 10 * ycomp(point(1, 2, 3)) + 100 * zcomp(point(1, 2, 3));"),
               WithinAbs(321, kEps));
    CHECK_THAT(Z("P += zcomp(N) + ycomp(P);", 0.25, 0.75), WithinAbs(1.75, kEps));
    CHECK_THAT(Z("P += comp(point(4, 5, 6), 0) + comp(vector(4, 5, 6), 2) + comp(color(1, 2, 3), 1);"),
               WithinAbs(12, kEps));
}

TEST_CASE("built-ins: setxcomp setycomp setzcomp setcomp", "[compiler][semantics][builtins]") {
    CheckVec(PAt("setxcomp(P, 5);"), {5, 0.75, 0});
    CheckVec(PAt("setycomp(P, 5);"), {0.25, 5, 0});
    CheckVec(PAt("setzcomp(P, 5);"), {0.25, 0.75, 5});
    CheckVec(PAt("point q = (1, 2, 3); setcomp(q, 0, 7); setcomp(q, 1, 8); P = q;"), {7, 8, 3});
    CheckVec(PAt("vector w = (1, 2, 3); setcomp(w, 2, u); P = w;", 0.25), {1, 2, 0.25});
    CheckVec(PAt("setzcomp(P, u * 2);", 0.25), {0.25, 0.75, 0.5});
    // Under a varying condition.
    CheckVec(PAt("if (u < 0.5) setycomp(P, 9);", 0.25), {0.25, 9, 0});
    CheckVec(PAt("if (u < 0.5) setycomp(P, 9);", 0.75), {0.75, 0.75, 0});
}

TEST_CASE("built-ins: mix", "[compiler][semantics][builtins]") {
    CHECK_THAT(Z("P += mix(0, 10, 0.3);"), WithinAbs(3, kEps));
    CHECK_THAT(Z("P += mix(2, 4, u);", 0.25), WithinAbs(2.5, kEps));
    CheckVec(PAt("P = mix(point(0, 0, 0), point(2, 4, 8), 0.25);"), {0.5, 1, 2});
    CheckVec(PAt("P = mix(P, point(1, 1, 1), 1);"), {1, 1, 1});
}

TEST_CASE("built-ins: faceforward and reflect", "[compiler][semantics][builtins]") {
    // faceforward(N, I) flips N when I . Ng > 0 (Ng = (0, 0, 1)).
    CheckVec(PAt("P = faceforward(normal(0, 0, 1), vector(0, 0, -1));"), {0, 0, 1});
    CheckVec(PAt("P = faceforward(normal(0, 0, 1), vector(0, 0, 1));"), {0, 0, -1});
    CheckVec(PAt("P = faceforward(normal(0, 1, 0), vector(0, 0, 1));"), {0, -1, 0});
    // faceforward(N, I, Nref) flips N when I . Nref > 0.
    CheckVec(PAt("P = faceforward(normal(1, 0, 0), vector(1, 0, 0), normal(1, 0, 0));"), {-1, 0, 0});
    CheckVec(PAt("P = faceforward(normal(1, 0, 0), vector(1, 0, 0), normal(-1, 0, 0));"), {1, 0, 0});
    // reflect(I, N) = I - 2 (I . N) N
    CheckVec(PAt("P = reflect(vector(1, -1, 0), normal(0, 1, 0));"), {1, 1, 0});
    CheckVec(PAt("P = reflect(vector(1, 2, 3), normal(0, 0, 1));"), {1, 2, -3});
}

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

TEST_CASE("built-ins: calculatenormal", "[compiler][semantics][builtins]") {
    // P = (u, v, uv): Du(P) = (1, 0, v), Dv(P) = (0, 1, u), cross = (-v, -u, 1).
    const std::string src = Shader("P += u * v * N; N = calculatenormal(P);");
    CheckVec(Eval(src, 0.25, 0.75, {}, Generic::Check, "N"), {-0.75, -0.25, 1});
    CheckVec(Eval(src, 0.5, 0.5, {}, Generic::Check, "N"), {-0.5, -0.5, 1});
    CheckVec(Eval(src, 0.25, 0.75), {0.25, 0.75, 0.1875});
    // A flat P: (0, 0, 1).
    CheckVec(Eval(Shader("N = calculatenormal(P);"), 0.25, 0.75, {}, Generic::Check, "N"), {0, 0, 1});
    // A normal passed where a point is expected (as real shaders do): Du = (1, 0, 0), Dv = (0, 1, 0).
    CheckVec(Eval(Shader("normal nn = normal(u, v, 0); N = calculatenormal(nn);"), 0.25, 0.75, {}, Generic::Check, "N"),
             {0, 0, 1});
}

TEST_CASE("built-ins: Du Dv area Deriv", "[compiler][semantics][builtins]") {
    // d(u^2 v)/du = 2uv = 0.375, d(u^2 v)/dv = u^2 = 0.0625.
    CHECK_THAT(Z("P += Du(u * u * v) + 10 * Dv(u * u * v);", 0.25, 0.75), WithinAbs(0.375 + 0.625, kEps));
    CheckVec(PAt("P = Du(P) + 10 * Dv(P);"), {1, 10, 0});
    CHECK_THAT(Z("P += Du(3) + Dv(3);"), WithinAbs(0, kEps));
    CheckVec(PAt("P = Du(vector(u * u, v, u * v));", 0.25, 0.75), {0.5, 0, 0.75});
    // area(P) = |Du(P) du ^ Dv(P) dv|; P scaled by 2 has 4 du dv.
    CHECK_THAT(Z("P *= 2; P += area(P) * 1024 * 1024;"), WithinAbs(4, 1e-9));
    // Deriv(uv, u + v) = v / 1 + u / 1.
    CHECK_THAT(Z("P += Deriv(u * v, u + v);", 0.25, 0.75), WithinAbs(1, kEps));
    // Derivatives of variables and of user function results.
    CHECK_THAT(ZSource("float sq(float x) { return x * x; }\n" + Shader("float a = sq(u); P += Du(a);"), 0.25),
               WithinAbs(0.5, kEps));
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

// ---------------------------------------------------------------------------------------------
// Matrices: RenderMan's row-vector convention, p' = p * M, translation in the last row.

namespace {
const char* const kTranslate567 = "matrix t = (1, 0, 0, 0,  0, 1, 0, 0,  0, 0, 1, 0,  5, 6, 7, 1);";
}  // namespace

TEST_CASE("matrices: construction, transform and vtransform", "[compiler][semantics][matrix]") {
    CheckVec(PAt(std::string(kTranslate567) + " P = transform(t, point(1, 2, 3));"), {6, 8, 10});
    CheckVec(PAt(std::string(kTranslate567) + " P = vtransform(t, vector(1, 2, 3));"), {1, 2, 3});
    // A float is that float times the identity; w = 2 divides out of a point.
    CheckVec(PAt("matrix m = 2; P = transform(m, point(1, 2, 3));"), {1, 2, 3});
    CheckVec(PAt("matrix m = 2; P = vtransform(m, vector(1, 2, 3));"), {2, 4, 6});
    CheckVec(PAt("matrix m = 0; m = 3; P = vtransform(m, vector(1, 2, 3));"), {3, 6, 9});
    // A projective matrix: w = 1 + x.
    CheckVec(PAt("matrix m = (1, 0, 0, 1,  0, 1, 0, 0,  0, 0, 1, 0,  0, 0, 0, 1); P = transform(m, point(1, 2, 4));"),
             {0.5, 1, 2});
    // Varying entries: the translation follows u (0.25) and v (0.75).
    CheckVec(PAt("matrix m = (1, 0, 0, 0,  0, 1, 0, 0,  0, 0, 1, 0,  u, v, u * v, 1); P = transform(m, P);"),
             {0.5, 1.5, 0.1875});
    // Every argument form: transform(from, m, x) goes from `from` to current first (the identity here).
    CheckVec(PAt(std::string(kTranslate567) + " P = transform(\"object\", t, point(0, 0, 0));"), {5, 6, 7});
}

TEST_CASE("matrices: translate, rotate, scale and their order", "[compiler][semantics][matrix]") {
    CheckVec(PAt("P = transform(translate(matrix 1, vector(1, 2, 3)), point(0, 0, 0));"), {1, 2, 3});
    CheckVec(PAt("P = transform(scale(matrix 1, point(2, 3, 4)), point(1, 1, 1));"), {2, 3, 4});
    // About +z by 90 degrees, x turns to y and y to -x; about +x, y turns to z.
    CheckVec(PAt("P = transform(rotate(matrix 1, PI / 2, vector(0, 0, 1)), point(1, 0, 0));"), {0, 1, 0});
    CheckVec(PAt("P = transform(rotate(matrix 1, PI / 2, vector(0, 0, 3)), point(0, 1, 0));"), {-1, 0, 0});
    CheckVec(PAt("P = transform(rotate(matrix 1, PI / 2, vector(1, 0, 0)), point(0, 1, 0));"), {0, 0, 1});
    // 120 degrees about (1,1,1) permutes the axes: x -> y.
    CheckVec(PAt("P = transform(rotate(matrix 1, 2 * PI / 3, vector(1, 1, 1)), point(1, 0, 0));"), {0, 1, 0});
    // The new transform applies first, then m (as RiTranslate concatenates): translate(scale)
    // moves then scales, scale(translate) scales then moves.
    CheckVec(PAt("P = transform(translate(scale(matrix 1, point(2, 2, 2)), vector(1, 0, 0)), point(0, 0, 0));"),
             {2, 0, 0});
    CheckVec(PAt("P = transform(scale(translate(matrix 1, vector(1, 0, 0)), point(2, 2, 2)), point(0, 0, 0));"),
             {1, 0, 0});
    // rotate(Q, angle, P0, P1): about the line through P0 and P1.
    CheckVec(PAt("P = rotate(point(1, 0, 0), PI / 2, point(0, 0, 0), point(0, 0, 1));"), {0, 1, 0});
    CheckVec(PAt("P = rotate(point(2, 1, 0), PI / 2, point(1, 1, 0), point(1, 1, 5));"), {1, 2, 0});
}

TEST_CASE("matrices: product, inverse, division and determinant", "[compiler][semantics][matrix]") {
    const std::string m =
        "matrix m = translate(rotate(scale(matrix 1, point(2, 3, 0.5)), 0.7, vector(1, 2, 3)), "
        "vector(4, -1, 2));";
    const std::string n = "matrix n = rotate(translate(matrix 1, vector(-2, 1, 1)), -1.1, vector(0, 1, 1));";
    // (m * n) applies m, then n.
    CheckVec(PAt(m + n + " P = transform(m * n, point(1, 2, 3));"),
             PAt(m + n + " P = transform(n, transform(m, point(1, 2, 3)));"), 1e-12);
    // 1/m undoes m; m/n is m times n's inverse.
    CheckVec(PAt(m + " P = transform(1 / m, transform(m, point(1, 2, 3)));"), {1, 2, 3}, 1e-12);
    CheckVec(PAt(m + n + " P = transform(n, transform(m / n, point(1, 2, 3)));"),
             PAt(m + " P = transform(m, point(1, 2, 3));"), 1e-12);
    CheckVec(PAt(m + " m /= m; P = transform(m, point(1, 2, 3));"), {1, 2, 3}, 1e-12);
    CheckVec(PAt(m + " m *= 1 / m; P = transform(m, point(1, 2, 3));"), {1, 2, 3}, 1e-12);
    // A matrix divided by a float divides every entry (w too: the point is unchanged).
    CheckVec(PAt("matrix d = (matrix 1) / 4; P = vtransform(d, vector(4, 8, 12));"), {1, 2, 3});
    // Determinants: the product of the scales; a rotation's is 1; a row swap negates.
    CHECK_THAT(Z("P += determinant(scale(matrix 1, point(2, 3, 4)));"), WithinAbs(24, kEps));
    CHECK_THAT(Z(m + " P += determinant(m);"), WithinAbs(3, 1e-12));
    CHECK_THAT(Z("P += determinant((0, 1, 0, 0,  1, 0, 0, 0,  0, 0, 1, 0,  0, 0, 0, 1));"), WithinAbs(-1, kEps));
    // A general matrix, by hand: expanding along row 3 gives 2 * det(3x3) = 2 * (1*(4*1-0*2) - 2*(0*1-0*2) + 3*(0*2-4*0)) ... = 8
    CHECK_THAT(Z("P += determinant((1, 2, 3, 0,  0, 4, 5, 0,  0, 0, 1, 0,  7, 8, 9, 2));"), WithinAbs(8, kEps));
    // A singular matrix has no inverse: NaN or infinity, never a wrong number.
    const glm::dvec3 singular = PAt("matrix z = 0; P = transform(1 / z, point(1, 2, 3));");
    CHECK(!std::isfinite(singular.x));
}

TEST_CASE("matrices: ntransform keeps normals perpendicular", "[compiler][semantics][matrix]") {
    // Scaling x by 2: the normal of the plane x + y = c becomes (1/2, 1, 0).
    CheckVec(PAt("P = ntransform(scale(matrix 1, point(2, 1, 1)), normal(1, 1, 0));"), {0.5, 1, 0});
    // A rotation turns normals like vectors.
    CheckVec(PAt("P = ntransform(rotate(matrix 1, PI / 2, vector(0, 0, 1)), normal(1, 0, 0));"), {0, 1, 0});
}

TEST_CASE("matrices: comp, setcomp, comparisons and ?:", "[compiler][semantics][matrix]") {
    CHECK_THAT(Z(std::string(kTranslate567) + " P += comp(t, 3, 1);"), WithinAbs(6, kEps));
    CHECK_THAT(Z(std::string(kTranslate567) + " P += comp(t, 0, 0) + comp(t, 0, 3);"), WithinAbs(1, kEps));
    CheckVec(PAt(std::string(kTranslate567) + " setcomp(t, 3, 0, 9); P = transform(t, point(0, 0, 0));"), {9, 6, 7});
    // Under a varying condition, setcomp writes only where it runs.
    CHECK_THAT(Z("matrix m = 1; if (u > 0.5) setcomp(m, 3, 2, 4); P = transform(m, P);", 0.75), WithinAbs(4, kEps));
    CHECK_THAT(Z("matrix m = 1; if (u > 0.5) setcomp(m, 3, 2, 4); P = transform(m, P);", 0.25), WithinAbs(0, kEps));
    CHECK_THAT(Z("P += (matrix 1) == (1, 0, 0, 0,  0, 1, 0, 0,  0, 0, 1, 0,  0, 0, 0, 1);"), WithinAbs(1, kEps));
    CHECK_THAT(Z("P += (matrix 1) == 1;"), WithinAbs(1, kEps));
    CHECK_THAT(Z("P += (matrix 1) != 2;"), WithinAbs(1, kEps));
    CHECK_THAT(Z(std::string(kTranslate567) + " P += t == 1;"), WithinAbs(0, kEps));
    CHECK_THAT(Z("matrix m = u < 0.5 ? matrix 2 : 1; P += determinant(m);", 0.25), WithinAbs(16, kEps));
    CHECK_THAT(Z("matrix m = u < 0.5 ? matrix 2 : 1; P += determinant(m);", 0.75), WithinAbs(1, kEps));
}

TEST_CASE("matrices: parameters, functions, arrays and spaces", "[compiler][semantics][matrix]") {
    // A parameter takes 16 numbers (or one: that times the identity).
    const std::string source = Shader("P = transform(m, P);", "matrix m = 1");
    const Overrides moved{{"m", {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 1, 2, 3, 1}}};
    CheckVec(Eval(source, 0.25, 0.75), {0.25, 0.75, 0});
    CheckVec(Eval(source, 0.25, 0.75, moved), {1.25, 2.75, 3});
    CheckVec(Eval(Shader("P = vtransform(m, P);", "matrix m = 1"), 0.25, 0.75, {{"m", {2}}}), {0.5, 1.5, 0});
    // Functions take and return matrices; output parameters write them back.
    CheckVec(PAt("matrix twice(matrix a) { return a * a; }\n"
                 "P = transform(twice(translate(matrix 1, vector(1, 0, 0))), point(0, 0, 0));"),
             {2, 0, 0});
    CheckVec(PAt("void shift(output matrix a) { a = translate(a, vector(0, 0, 1)); }\n"
                 "matrix m = 1; shift(m); shift(m); P = transform(m, point(0, 0, 0));"),
             {0, 0, 2});
    // Arrays of matrices, with a varying index.
    CheckVec(PAt("matrix a[2] = {matrix 1, translate(matrix 1, vector(0, 1, 0))};\n"
                 "P = transform(a[u > 0.5], point(0, 0, 0));",
                 0.75),
             {0, 1, 0});
    // `matrix "space" 1` maps current to that space, like transform("space", x).
    const glm::dvec3 viaMatrix = PAt("P = transform(matrix \"shader\" 1, P);");
    CheckVec(viaMatrix, PAt("P = transform(\"shader\", P);"));
}

TEST_CASE("array parameters: defaults, scene values and varying indices", "[compiler][semantics][arrays]") {
    const std::string source = Shader("P += w[0] + 10 * w[1] + 100 * w[2] + zcomp(c[1]);",
                                      "float w[3] = {1, 2, 3}; point c[2] = {0, (4, 5, 6)}");
    CHECK_THAT(Eval(source, 0.25, 0.75).z, WithinAbs(321 + 6, kEps));
    CHECK_THAT(Eval(source, 0.25, 0.75, {{"w", {4, 5, 6}}}).z, WithinAbs(654 + 6, kEps));
    CHECK_THAT(Eval(source, 0.25, 0.75, {{"c", {0, 0, 0, 0, 0, 9}}}).z, WithinAbs(321 + 9, kEps));
    // A varying index reads the scene's values too.
    const std::string varying = Shader("P += w[floor(u * 3)];", "float w[3] = {1, 2, 3}");
    CHECK_THAT(Eval(varying, 0.1, 0.5, {{"w", {7, 8, 9}}}).z, WithinAbs(7, kEps));
    CHECK_THAT(Eval(varying, 0.9, 0.5, {{"w", {7, 8, 9}}}).z, WithinAbs(9, kEps));
    // Every element must be given: one number does not stand for all three.
    const compiler::CompileResult r = compiler::CompileSource("test.sl", varying, {{"w", {7}}});
    REQUIRE(r.paramErrors.size() == 1);
    CHECK(r.paramErrors[0] == "parameter 'w' of shader 't' is a float[3] and takes 3 values, got 1");
}
