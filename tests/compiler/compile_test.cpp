// tests/compiler/compile_test.cpp: language semantics (expected values), compiler diagnostics
// (exact text) and the shape of the emitted code (opcode sequences). Specialisation is
// tests/compiler/specialise_test.cpp's; the listing, tests/vm/disasm_test.cpp's.
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>

#include "compiler/ir.h"
#include "tests/test_util.h"
#include "vm/bytecode_file.h"

using namespace affray;
using Catch::Matchers::WithinAbs;

namespace {

/// The displaced P.z of `body` (statements of a displacement shader) at (u, v).
double ZOf(const std::string& body, double u = 0.25, double v = 0.75, const std::string& params = "") {
    compiler::CompiledShader s = test::CompileOrThrow("displacement t(" + params + ") {\n" + body + "\n}\n");
    return test::PointOnSquare(s.shade, u, v).z;
}

std::string Diagnose(const std::string& source) {
    compiler::CompileResult r = compiler::CompileSource("test.sl", source);
    REQUIRE_FALSE(r.ok());
    return r.diagnostics.format();
}

std::vector<vm::Op> Opcodes(const vm::Program& p) {
    std::vector<vm::Op> ops;
    for (const vm::Instr& in : p.code) ops.push_back(in.op);
    return ops;
}

}  // namespace

TEST_CASE("arithmetic and precedence give the expected values", "[compiler]") {
    CHECK_THAT(ZOf("P += 1 + 2 * 3;"), WithinAbs(7, 1e-15));
    CHECK_THAT(ZOf("P += (1 + 2) * 3;"), WithinAbs(9, 1e-15));
    CHECK_THAT(ZOf("P += 8 / 4 / 2;"), WithinAbs(1, 1e-15));
    CHECK_THAT(ZOf("P += 2 - 3 - 4;"), WithinAbs(-5, 1e-15));
    CHECK_THAT(ZOf("P += -2 * -3;"), WithinAbs(6, 1e-15));
    // '.' binds tighter than '+': 1 + (a . b)
    CHECK_THAT(ZOf("P += 1 + vector(1, 2, 3) . vector(4, 5, 6);"), WithinAbs(33, 1e-15));
    // '^' is the cross product; x ^ y = z
    CHECK_THAT(ZOf("P += zcomp(vector(1, 0, 0) ^ vector(0, 1, 0));"), WithinAbs(1, 1e-15));
    // '^' binds looser than '*': a ^ (b * 2)
    CHECK_THAT(ZOf("P += zcomp(vector(1, 0, 0) ^ vector(0, 1, 0) * 2);"), WithinAbs(2, 1e-15));
}

TEST_CASE("globals of the unit square", "[compiler]") {
    CHECK_THAT(ZOf("P += u;", 0.25, 0.75), WithinAbs(0.25, 1e-15));
    CHECK_THAT(ZOf("P += v;", 0.25, 0.75), WithinAbs(0.75, 1e-15));
    CHECK_THAT(ZOf("P += s * 10 + t;", 0.25, 0.75), WithinAbs(3.25, 1e-15));
    CHECK_THAT(ZOf("P += xcomp(P) + ycomp(P);", 0.25, 0.75), WithinAbs(1.0, 1e-15));
    CHECK_THAT(ZOf("P += zcomp(N);"), WithinAbs(1.0, 1e-15));
    CHECK_THAT(ZOf("P += xcomp(dPdu) + 10 * ycomp(dPdv);"), WithinAbs(11.0, 1e-15));
    CHECK_THAT(ZOf("P += PI;"), WithinAbs(std::numbers::pi, 1e-15));
    CHECK_THAT(ZOf("P += du * 1024;"), WithinAbs(1.0, 1e-15));
}

TEST_CASE("built-ins give their RenderMan values", "[compiler]") {
    CHECK_THAT(ZOf("P += sin(PI / 2);"), WithinAbs(1, 1e-15));
    CHECK_THAT(ZOf("P += cos(0);"), WithinAbs(1, 1e-15));
    CHECK_THAT(ZOf("P += tan(PI / 4);"), WithinAbs(1, 1e-15));
    CHECK_THAT(ZOf("P += exp(1);"), WithinAbs(std::exp(1.0), 1e-15));
    CHECK_THAT(ZOf("P += log(exp(2));"), WithinAbs(2, 1e-15));
    CHECK_THAT(ZOf("P += log(8, 2);"), WithinAbs(3, 1e-15));
    CHECK_THAT(ZOf("P += sqrt(16);"), WithinAbs(4, 1e-15));
    CHECK_THAT(ZOf("P += abs(-3);"), WithinAbs(3, 1e-15));
    CHECK_THAT(ZOf("P += sign(-3) + 10 * sign(2);"), WithinAbs(9, 1e-15));
    CHECK_THAT(ZOf("P += pow(2, 10);"), WithinAbs(1024, 1e-12));
    CHECK_THAT(ZOf("P += pow(u, 3);", 0.5), WithinAbs(0.125, 1e-15));
    CHECK_THAT(ZOf("P += length(vector(3, 4, 12));"), WithinAbs(13, 1e-14));
    CHECK_THAT(ZOf("P += distance(point(1, 1, 1), point(4, 5, 1));"), WithinAbs(5, 1e-14));
    CHECK_THAT(ZOf("P += xcomp(normalize(vector(3, 0, 4)));"), WithinAbs(0.6, 1e-15));
    CHECK_THAT(ZOf("P += radians(180);"), WithinAbs(std::numbers::pi, 1e-15));
    CHECK_THAT(ZOf("P += degrees(PI);"), WithinAbs(180, 1e-12));
    CHECK_THAT(ZOf("P += mix(2, 4, 0.25);"), WithinAbs(2.5, 1e-15));
    CHECK_THAT(ZOf("P += ycomp(mix(point(0, 0, 0), point(0, 8, 0), 0.5));"), WithinAbs(4, 1e-15));
    CHECK_THAT(ZOf("P += inversesqrt(4);"), WithinAbs(0.5, 1e-15));
    // reflect(I, N) = I - 2 (I.N) N: (1, 0, -1) off the plane z = 0 is (1, 0, 1)
    CHECK_THAT(ZOf("P += zcomp(reflect(vector(1, 0, -1), normal(0, 0, 1)));"), WithinAbs(1, 1e-15));
    CHECK_THAT(ZOf("P += xcomp(reflect(vector(1, 0, -1), normal(0, 0, 1)));"), WithinAbs(1, 1e-15));
    // area(P) = length(Du(P) du ^ Dv(P) dv) = du * dv on the unit square
    CHECK_THAT(ZOf("P += area(P) * 1024 * 1024;"), WithinAbs(1, 1e-12));
    // Deriv(num, den) = Du(num)/Du(den) + Dv(num)/Dv(den): d(u^2)/du + d(u^2 v)/... on (u, v)
    CHECK_THAT(ZOf("P += Deriv(u * u, u + v);", 0.25, 0.75), WithinAbs(0.5, 1e-15));
    CHECK_THAT(ZOf("P += comp(point(4, 5, 6), 1);"), WithinAbs(5, 1e-15));
    CHECK_THAT(ZOf("point q = (1, 2, 3); setcomp(q, 2, 7); P += q;"), WithinAbs(7, 1e-15));
    CHECK_THAT(ZOf("setzcomp(P, 2.5);"), WithinAbs(2.5, 1e-15));
    CHECK_THAT(ZOf("setxcomp(P, 9); P += vector(0, 0, xcomp(P));"), WithinAbs(9, 1e-15));
    // Du and Dv are exact derivatives along u and v.
    CHECK_THAT(ZOf("P += Du(u * u) + 10 * Dv(u * v);", 0.25, 0.75), WithinAbs(0.5 + 2.5, 1e-14));
}

TEST_CASE("calculatenormal is Du(P) ^ Dv(P)", "[compiler]") {
    compiler::CompiledShader s =
        test::CompileOrThrow("displacement t() { P += 0.5 * u * u * N; N = calculatenormal(P); }");
    // P = (u, v, u^2/2): dP/du = (1, 0, u), dP/dv = (0, 1, 0); cross = (-u, 0, 1).
    glm::dvec3 n = test::PointOnSquare(s.shade, 0.5, 0.5, "N");
    CHECK_THAT(n.x, WithinAbs(-0.5, 1e-15));
    CHECK_THAT(n.y, WithinAbs(0, 1e-15));
    CHECK_THAT(n.z, WithinAbs(1, 1e-15));
}

TEST_CASE("variables, promotion, compound assignment and scopes", "[compiler]") {
    CHECK_THAT(ZOf("float a = 2, b = a * 3; P += b;"), WithinAbs(6, 1e-15));
    CHECK_THAT(ZOf("vector w = 2; P += zcomp(w) + xcomp(w);"), WithinAbs(4, 1e-15));
    CHECK_THAT(ZOf("float a = 1; a += 2; a *= 5; a -= 1; a /= 2; P += a;"), WithinAbs(7, 1e-15));
    CHECK_THAT(ZOf("float a = 1; { float a = 5; P += a; } P += a;"), WithinAbs(6, 1e-15));
    CHECK_THAT(ZOf("point q = P; q *= 2; P = q;", 0.25, 0.75), WithinAbs(0, 1e-15));
    CHECK_THAT(ZOf("float a, b; a = b = 3; P += a + b;"), WithinAbs(6, 1e-15));
    CHECK_THAT(ZOf("P += point(1, 2, 3) + 1 - vector(0, 0, 1);"), WithinAbs(3, 1e-15));
}

TEST_CASE("parameters take defaults and overrides", "[compiler]") {
    const std::string src =
        "displacement t(float Km = 0.5, k2 = Km * 2; point c = (1, 2, 3);) { P += Km + k2 + zcomp(c); }";
    CHECK_THAT(test::PointOnSquare(test::CompileOrThrow(src).shade, 0, 0).z, WithinAbs(4.5, 1e-15));
    // Defaults are constants fixed at compile time: k2's default saw Km's default (0.5), and an
    // instance value of Km does not change it.
    CHECK_THAT(test::PointOnSquare(test::CompileOrThrow(src, {{"Km", {2}}}).shade, 0, 0).z,
               WithinAbs(2 + 1 + 3, 1e-15));
    CHECK_THAT(test::PointOnSquare(test::CompileOrThrow(src, {{"c", {0, 0, 10}}}).shade, 0, 0).z,
               WithinAbs(11.5, 1e-15));

    // A value for a parameter the shader does not declare is left out, and said (prman ignores
    // it with a warning): the instance is the one without it.
    compiler::CompileResult lenient = compiler::CompileSource("t.sl", src, {{"Kx", {1}}, {"Km", {2}}, {"Kx", {3}}});
    REQUIRE(lenient.ok());
    CHECK(lenient.paramErrors.empty());
    CHECK(lenient.undeclared == std::vector<std::string>{"shader 't' has no parameter 'Kx'"});
    CHECK(lenient.shader->undeclared == lenient.undeclared);
    CHECK_THAT(test::PointOnSquare(lenient.shader->shade, 0, 0).z, WithinAbs(2 + 1 + 3, 1e-15));
    // Specialise itself, called directly, still refuses a name the program does not have.
    std::vector<std::string> errors;
    CHECK_FALSE(compiler::Specialise(lenient.shader->genericBound, {{"Kx", {1}}}, &errors));
    CHECK(errors == std::vector<std::string>{"shader 't' has no parameter 'Kx'"});
    // ... and said even when another value fails the compilation.
    compiler::CompileResult bad = compiler::CompileSource("t.sl", src, {{"Kx", {1}}, {"Km", {1, 2}}});
    REQUIRE_FALSE(bad.ok());
    CHECK(bad.undeclared == std::vector<std::string>{"shader 't' has no parameter 'Kx'"});
    bad = compiler::CompileSource("t.sl", src, {{"Km", {NAN}}});
    REQUIRE(bad.paramErrors ==
            std::vector<std::string>{"parameter 'Km' of shader 't' must be finite (got NaN or infinity)"});
    bad = compiler::CompileSource("t.sl", src, {{"Km", {1, 2}}});
    REQUIRE(bad.paramErrors ==
            std::vector<std::string>{"parameter 'Km' of shader 't' is a float and takes 1 value, got 2"});
}

TEST_CASE("compiler diagnostics are exact", "[compiler]") {
    CHECK(Diagnose("displacement t() {\n  P += foo;\n}\n") ==
          "test.sl:2:8: error: unknown identifier 'foo'\n      P += foo;\n           ^\n");
    CHECK(Diagnose("displacement t() {\n  float x = 1;\n  float x = 2;\n}\n") ==
          "test.sl:3:9: error: redefinition of 'x'\n      float x = 2;\n            ^\n"
          "test.sl:2:9: note: 'x' was declared here\n      float x = 1;\n            ^\n");
    CHECK(Diagnose("displacement t() {\n  u = 1;\n}\n") ==
          "test.sl:2:5: error: cannot assign to 'u': it is a read-only global\n      u = 1;\n        ^\n");
    CHECK(Diagnose("displacement t() {\n  float x = P;\n}\n") ==
          "test.sl:2:9: error: cannot assign a point to float variable 'x'\n      float x = P;\n            ^\n");
    CHECK(
        Diagnose("displacement t() {\n  P += sin(P);\n}\n") ==
        "test.sl:2:8: error: no version of 'sin' takes (point); expected (float)\n      P += sin(P);\n           ^\n");
    CHECK(Diagnose("displacement t() {\n  P += pow(2);\n}\n") ==
          "test.sl:2:8: error: 'pow' expects 2 arguments, got 1\n      P += pow(2);\n           ^\n");
    CHECK(Diagnose("displacement t() {\n  P += frob(2);\n}\n") ==
          "test.sl:2:8: error: unknown function 'frob'\n      P += frob(2);\n           ^\n");
    CHECK(Diagnose("displacement t() {\n  P += texture(\"x\");\n}\n") ==
          "test.sl:2:16: error: cannot find texture 'x' (looked in the working directory)\n      P += "
          "texture(\"x\");\n                   ^\n");
    CHECK(Diagnose("displacement t() {\n  float x;\n  P += x + color(1, 0, 0);\n}\n") ==
          "test.sl:3:8: warning: variable 'x' is used before it is assigned a value (it is 0 here)\n"
          "      P += x + color(1, 0, 0);\n           ^\n"
          "test.sl:3:5: error: cannot assign a color to point variable 'P'\n"
          "      P += x + color(1, 0, 0);\n        ^\n");
    CHECK(Diagnose("displacement t() {\n  P += color(1, 0, 0);\n}\n") ==
          "test.sl:2:5: error: cannot assign a color to point variable 'P'\n      P += color(1, 0, 0);\n        ^\n");
    CHECK(Diagnose("displacement t() {\n  P += P . 1;\n}\n") ==
          "test.sl:2:10: error: invalid operands to '.' (point and float): '.' is the dot product of two triples\n"
          "      P += P . 1;\n             ^\n");
    CHECK(Diagnose("volume t() {\n  P += 1;\n}\n") ==
          "test.sl:1:8: error: volume shaders are not supported yet; affray runs displacement, surface and light "
          "shaders\n"
          "    volume t() {\n           ^\n");
    CHECK(Diagnose("displacement t(float k) {\n  P += k;\n}\n") ==
          "test.sl:1:22: error: parameter 'k' needs a default value\n    displacement t(float k) {\n                   "
          "      ^\n");
    CHECK(Diagnose("displacement t(float k = u) {\n  P += k;\n}\n") ==
          "test.sl:1:22: error: default value of parameter 'k' must be a constant expression\n"
          "    displacement t(float k = u) {\n                         ^\n");
    CHECK(Diagnose("displacement t() {\n  if (u) break;\n}\n") ==
          "test.sl:2:10: error: 'break' outside of a loop\n      if (u) break;\n             ^\n");
    CHECK(Diagnose("displacement t() {\n  P += point \"shoder\" (1, 2, 3);\n}\n") ==
          "test.sl:2:8: error: unknown coordinate space 'shoder'\n"
          "      P += point \"shoder\" (1, 2, 3);\n           ^\n");
    CHECK(Diagnose("") == "test.sl:1:1: error: no shader definition in file\n");
    CHECK(Diagnose("displacement t() {\n  P += comp(P, u);\n}\n") ==
          "test.sl:2:16: error: the component index of 'comp' must be the constant 0, 1 or 2\n"
          "      P += comp(P, u);\n                   ^\n");
    CHECK(Diagnose("displacement t() {\n  setxcomp(u, 1);\n}\n") ==
          "test.sl:2:12: error: the first argument of 'setxcomp' must be a point, vector, normal or color\n"
          "      setxcomp(u, 1);\n               ^\n");
    CHECK(Diagnose("displacement t() {\n  setxcomp(dPdu, 1);\n}\n") ==
          "test.sl:2:12: error: cannot assign to 'dPdu': it is a read-only global\n"
          "      setxcomp(dPdu, 1);\n               ^\n");
    // Several independent errors are all reported.
    std::string many = Diagnose("displacement t() {\n  P += a;\n  P += b;\n}\n");
    CHECK(many.find("'a'") != std::string::npos);
    CHECK(many.find("'b'") != std::string::npos);
}

TEST_CASE("warnings: unused variables and shaders that change nothing", "[compiler]") {
    compiler::CompileResult r = compiler::CompileSource("test.sl", "displacement t() {\n  float unused = 1;\n}\n");
    REQUIRE(r.ok());
    CHECK(r.diagnostics.format() ==
          "test.sl:2:9: warning: unused variable 'unused'\n      float unused = 1;\n            ^\n"
          "test.sl:1:14: warning: shader 't' never changes P or N\n    displacement t() {\n                 ^\n");
}

TEST_CASE("constants fold, shared subexpressions are computed once, dead code goes", "[compiler]") {
    using vm::Op;
    // A constant expression folds to one constant; x + 0 leaves P.x and P.y untouched.
    compiler::CompiledShader k = test::CompileOrThrow("displacement t() { P += vector(0, 0, (1 + 2) * sin(0.5)); }");
    CHECK(Opcodes(k.bound) == std::vector<Op>{Op::AddRK});
    // u*u becomes one Sqr; the repeated sin(u) is computed once.
    compiler::CompiledShader s =
        test::CompileOrThrow("displacement t() { P += vector(0, 0, u * u + sin(u) + sin(u)); }");
    CHECK(Opcodes(s.bound) == std::vector<Op>{Op::Sqr, Op::Sin, Op::AddRR, Op::AddRR, Op::AddRR});
    // -u * u and u * -u are -sqr(u): the same double, and a square's bound.
    for (const char* product : {"-u * u", "u * -u"}) {
        compiler::CompiledShader q =
            test::CompileOrThrow(std::string("displacement t() { P += vector(0, 0, ") + product + "); }");
        INFO(product);
        CHECK(Opcodes(q.bound) == std::vector<Op>{Op::Sqr, Op::Neg, Op::AddRR});
    }
    // A parameter bound to a constant folds away; unused locals emit nothing.
    compiler::CompiledShader p = test::CompileOrThrow(
        "displacement t(float Km = 2) { float unused = sin(u) * 7; P += vector(0, 0, Km * 0.5); }");
    CHECK(Opcodes(p.bound) == std::vector<Op>{Op::AddRK});
    // The bound program leaves out N's computation; the shade program keeps it.
    compiler::CompiledShader n = test::CompileOrThrow("displacement t() { P += u * N; N = calculatenormal(P); }");
    CHECK_FALSE(n.bound.usesDerivatives());
    CHECK(n.shade.usesDerivatives());
    CHECK(n.bound.code.size() < n.shade.code.size());
    CHECK_FALSE(n.bound.readsGlobal(vm::Global::dPdu));
}

TEST_CASE("only the globals a shader reads are inputs", "[compiler]") {
    compiler::CompiledShader s = test::CompileOrThrow("displacement t() { P += s * N; }");
    CHECK(s.bound.readsGlobal(vm::Global::P));
    CHECK(s.bound.readsGlobal(vm::Global::N));
    CHECK(s.bound.readsGlobal(vm::Global::s));
    CHECK_FALSE(s.bound.readsGlobal(vm::Global::t));
    CHECK_FALSE(s.bound.readsGlobal(vm::Global::I));
}

TEST_CASE("a loaded .afb whose shade program does not specialise or lacks an output is an error",
          "[compiler][bytecode]") {
    test::TempDir dir;
    const compiler::CompileResult compiled = compiler::CompileSource("k.sl", "displacement d() { P += 0.123 * N; }");
    REQUIRE(compiled.ok());
    const compiler::CompiledShader& shader = *compiled.shader;
    auto load = [&](const vm::Program& shade) {
        const vm::BytecodeFile file{shader.name, "k.sl", 0, shader.genericBound, shade};
        return compiler::LoadCompiledShader(dir.Write("k.afb", vm::SaveBytecode(file)));
    };
    CHECK(load(shader.genericShade).ok());

    // The shade program alone runs a loop past its unrolling (the bound program does not).
    vm::Program poisoned = shader.genericShade;
    bool replaced = false;
    for (double& k : poisoned.constants) {
        if (k != 0.123) continue;
        k = compiler::kParameterLoopPoison;
        replaced = true;
    }
    REQUIRE(replaced);
    compiler::CompileResult r = load(poisoned);
    CHECK_FALSE(r.ok());
    REQUIRE(r.paramErrors.size() == 1);
    CHECK(r.paramErrors[0].find("a loop runs longer than the compiled program was unrolled for") != std::string::npos);

    // No output N.
    vm::Program noNormal = shader.genericShade;
    for (vm::ProgramOutput& out : noNormal.outputs)
        if (out.name == "N") out.name = "Q";
    r = load(noNormal);
    CHECK_FALSE(r.ok());
    CHECK(r.diagnostics.format().find("error: program 'shade' has no output N of three values") != std::string::npos);

    // The fuzzer's input, as found.
    r = compiler::LoadCompiledShader(std::string(AFFRAY_SOURCE_DIR) + "/fuzz/regressions/fuzz_afb/shade_poison.afb");
    CHECK_FALSE(r.ok());
    CHECK(r.paramErrors.size() == 1);
}
