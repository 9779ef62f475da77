// tests/compiler/specialise_test.cpp: binding a generic program's parameters to one instance's
// values (compiler/specialise.*). BindParameters gives every parameter its override or default,
// spreading one number over a triple or down a matrix's diagonal, and refuses an unknown name, a
// wrong count or a value that is not finite with one sentence each. Specialise lifts a program
// written by hand back into the value graph with the parameters (and the globals a surface fixes)
// as constants, so that what they make constant or dead folds away, and keeps what the program
// carries besides its code; a loop unrolled too short for the values is refused. Then the same
// on compiled shaders: generic and specialised programs agree.
#include <catch2/catch.hpp>

#include <cmath>

#include "compiler/ir.h"
#include "tests/test_util.h"
#include "vm/assemble.h"
#include "vm/verify.h"

using namespace affray;
using compiler::ParamOverride;
using vm::Op;

namespace {

std::vector<vm::Op> Opcodes(const vm::Program& p) {
    std::vector<vm::Op> ops;
    for (const vm::Instr& in : p.code) ops.push_back(in.op);
    return ops;
}

/// A generic program "s": P = (u * k, v + d.y, m[3][0] * u), parameters k (float, default 2),
/// d (vector, default (1, 2, 3)), m (matrix, default identity) and a[2] (float[2], unread).
vm::Program Generic() {
    vm::Assembler as;
    const int u = as.Global(vm::Global::u), v = as.Global(vm::Global::v);
    const int k = as.Param(0, 1), d = as.Param(1, 3), m = as.Param(2, 16);
    const int ops1[] = {u, k};
    const int x = as.Operation(Op::MulRR, ops1, 1);
    const int ops2[] = {v, d + 1};
    const int y = as.Operation(Op::AddRR, ops2, 2);
    const int ops3[] = {m + 12, u};
    const int z = as.Operation(Op::MulRR, ops3, 3);
    std::vector<vm::ProgramParam> params(4);
    params[0] = {"k", "float", 1, vm::kNoRegister, {2}};
    params[1] = {"d", "vector", 3, vm::kNoRegister, {1, 2, 3}};
    params[2] = {"m", "matrix", 16, vm::kNoRegister, {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}};
    params[3] = {"a", "float[2]", 2, vm::kNoRegister, {5, 6}};
    vm::Program p;
    p.shaderName = "s";
    as.Finish({{"P", 3, {x, y, z}}}, params, true, &p);
    std::string error;
    REQUIRE(vm::Verify(p, &error));
    return p;
}

/// P of `p` at (u, v) in doubles.
glm::dvec3 At(const vm::Program& p, double u, double v) {
    vm::Interpreter<double> interp(p);
    interp.SetGlobal(vm::Global::u, u);
    interp.SetGlobal(vm::Global::v, v);
    interp.Run();
    const vm::Vec3<double> r = interp.OutputTriple(*p.findOutput("P"));
    return {r.x, r.y, r.z};
}

}  // namespace

TEST_CASE("specialise: parameters bind to their overrides, else their defaults", "[compiler][specialise]") {
    const vm::Program p = Generic();
    std::vector<std::string> errors;
    auto values = compiler::BindParameters(p, {}, &errors);
    REQUIRE(values);
    CHECK(*values == std::vector<std::vector<double>>{p.params[0].defaults, p.params[1].defaults, p.params[2].defaults,
                                                      p.params[3].defaults});
    values = compiler::BindParameters(p, {{"d", {7, 8, 9}}, {"k", {4}}, {"a", {0, -1}}}, &errors);
    REQUIRE(values);
    CHECK((*values)[0] == std::vector<double>{4});
    CHECK((*values)[1] == std::vector<double>{7, 8, 9});
    CHECK((*values)[2] == p.params[2].defaults);
    CHECK((*values)[3] == std::vector<double>{0, -1});
    // One number spreads over a triple, and down a matrix's diagonal (x times the identity).
    values = compiler::BindParameters(p, {{"d", {5}}, {"m", {3}}}, &errors);
    REQUIRE(values);
    CHECK((*values)[1] == std::vector<double>{5, 5, 5});
    CHECK((*values)[2] == std::vector<double>{3, 0, 0, 0, 0, 3, 0, 0, 0, 0, 3, 0, 0, 0, 0, 3});
    // A later override of the same name wins.
    values = compiler::BindParameters(p, {{"k", {4}}, {"k", {6}}}, &errors);
    REQUIRE(values);
    CHECK((*values)[0] == std::vector<double>{6});
    CHECK(errors.empty());
}

TEST_CASE("specialise: each bad override is one sentence, and all of them are said", "[compiler][specialise]") {
    const vm::Program p = Generic();
    std::vector<std::string> errors;
    CHECK_FALSE(compiler::BindParameters(
        p, {{"q", {1}}, {"d", {1, 2}}, {"a", {1}}, {"k", {NAN}}, {"m", {1, INFINITY}}, {"k", {1}}}, &errors));
    CHECK(errors == std::vector<std::string>{
                        "shader 's' has no parameter 'q'",
                        "parameter 'd' of shader 's' is a vector and takes 3 values, got 2",
                        "parameter 'a' of shader 's' is a float[2] and takes 2 values, got 1",  // arrays do not spread
                        "parameter 'k' of shader 's' must be finite (got NaN or infinity)",
                        "parameter 'm' of shader 's' is a matrix and takes 16 values, got 2",
                    });
    errors.clear();
    CHECK_FALSE(compiler::Specialise(p, {{"k", {1, 2}}}, &errors));
    CHECK(errors == std::vector<std::string>{"parameter 'k' of shader 's' is a float and takes 1 value, got 2"});
}

TEST_CASE("specialise: parameters become constants and fold into the code", "[compiler][specialise]") {
    const vm::Program generic = Generic();
    std::vector<std::string> errors;
    // Defaults: u * 2 takes its constant as a K operand, v + 2 too, and 0 * u (the identity's
    // m[3][0]) folds to 0.
    std::optional<vm::Program> p = compiler::Specialise(generic, {}, &errors);
    REQUIRE(p);
    CHECK(p->params.empty());
    CHECK(Opcodes(*p) == std::vector<Op>{Op::MulRK, Op::AddRK, Op::LoadK});
    CHECK(At(*p, 0.25, 0.5) == glm::dvec3(0.5, 2.5, 0));
    CHECK(p->shaderName == "s");
    // k = 1 leaves u itself: the output reads the global's register, with no instruction.
    std::vector<double> m(16, 0.0);
    m[12] = 3;
    p = compiler::Specialise(generic, {{"k", {1}}, {"m", m}}, &errors);
    REQUIRE(p);
    CHECK(Opcodes(*p) == std::vector<Op>{Op::AddRK, Op::MulRK});
    CHECK(p->outputs[0].registers[0] == p->globalRegisters[int(vm::Global::u)]);
    CHECK(At(*p, 0.25, 0.5) == glm::dvec3(0.25, 2.5, 0.75));
    // The generic program with the same values set computes the same.
    vm::Interpreter<double> interp(generic);
    interp.SetGlobal(vm::Global::u, 0.25);
    interp.SetGlobal(vm::Global::v, 0.5);
    interp.SetParam(0, {1});
    interp.SetParam(2, m);
    interp.Run();
    const vm::Vec3<double> g = interp.OutputTriple(generic.outputs[0]);
    CHECK(glm::dvec3(g.x, g.y, g.z) == glm::dvec3(0.25, 2.5, 0.75));
    CHECK(errors.empty());
}

TEST_CASE("specialise: the program's name, source, lines and texture slots are kept", "[compiler][specialise]") {
    vm::Program generic = Generic();
    generic.sourcePath = "/x/s.sl";
    generic.textures = std::make_shared<vm::TextureSlots>(1);
    std::vector<std::string> errors;
    std::optional<vm::Program> p = compiler::Specialise(generic, {}, &errors);
    REQUIRE(p);
    CHECK(p->shaderName == "s");
    CHECK(p->sourcePath == "/x/s.sl");
    CHECK(p->textures == generic.textures);
    CHECK(p->lines == std::vector<int>{1, 2, 0});  // the folded 0 is loaded with no line
}

TEST_CASE("specialise: a constant that marks a loop unrolled too short is refused", "[compiler][specialise]") {
    // P = u < k ? u : poison, the poison being what lowering leaves for the paths still running
    // past the unrolling of a loop bounded by a parameter. With a k that leaves the condition to
    // the run time, the poison stays in the specialised code, and that is refused.
    vm::Assembler as;
    const int u = as.Global(vm::Global::u);
    const int k = as.Param(0, 1);
    const int less[] = {u, k};
    const int cond = as.Operation(Op::LtRR, less, 1);
    const int choose[] = {cond, u, as.Load(compiler::kParameterLoopPoison, 1)};
    const int out = as.Operation(Op::Select, choose, 1);
    vm::Program generic;
    generic.shaderName = "loop";
    as.Finish({{"P", 3, {out, out, out}}}, {{"k", "float", 1, vm::kNoRegister, {0}}}, false, &generic);
    std::vector<std::string> errors;
    CHECK_FALSE(compiler::Specialise(generic, {{"k", {0.5}}}, &errors));
    CHECK(errors == std::vector<std::string>{
                        "shader 'loop': with these parameter values a loop runs longer than the compiled program "
                        "was unrolled for; use the shader's source (.sl), which is unrolled for each instance's "
                        "values"});
}

TEST_CASE("specialise: a global a surface fixes is a constant too", "[compiler][specialise]") {
    // v fixed at 0.5: P.y = v + d.y folds to 2.5, loaded.
    std::vector<std::string> errors;
    std::optional<vm::Program> p =
        compiler::Specialise(Generic(), {}, &errors, {{vm::Global::v, {0.5}}, {vm::Global::N, {0, 0, 1}}});
    REQUIRE(p);
    CHECK_FALSE(p->readsGlobal(vm::Global::v));
    CHECK_FALSE(p->readsGlobal(vm::Global::N));  // not read before either
    CHECK(Opcodes(*p) == std::vector<Op>{Op::MulRK, Op::LoadK, Op::LoadK});
    CHECK(At(*p, 0.25, 0.9) == glm::dvec3(0.5, 2.5, 0));
}

TEST_CASE("generic programs read parameters, specialised ones fold them away", "[compiler][specialise]") {
    const std::string src = R"(
        displacement t(float Km = 0.5, freq = 4; vector dir = (0, 0, 1)) {
            P += Km * sin(freq * u) * dir;
        })";
    compiler::CompiledShader s = test::CompileOrThrow(src);
    // The generic program reads Km, freq and dir from registers.
    REQUIRE(s.genericBound.params.size() == 3);
    CHECK(s.genericBound.params[0].name == "Km");
    CHECK(s.genericBound.params[2].type == "vector");
    CHECK(s.genericBound.params[2].defaults == std::vector<double>{0, 0, 1});
    for (const vm::ProgramParam& p : s.genericBound.params) CHECK(p.firstRegister != vm::kNoRegister);
    // Specialised with the defaults, the parameters are constants that fold into K operands
    // (freq * u becomes one MulRK, Km * sin(...) another): shorter code, no parameter registers.
    CHECK(s.bound.params.empty());
    CHECK(s.bound.code.size() < s.genericBound.code.size());

    // Generic (with parameter values set at run time) and specialised programs agree.
    compiler::CompiledShader inst = test::CompileOrThrow(src, {{"Km", {2}}, {"freq", {7}}, {"dir", {0, 1, 0}}});
    vm::Interpreter<double> generic(s.genericBound);
    generic.SetParam(0, {2});
    generic.SetParam(1, {7});
    generic.SetParam(2, {0, 1, 0});
    vm::Vec3<double> g = renderer::EvaluateOnPatch(generic, renderer::BilinearPatch::UnitSquare(), 0.3, 0.3, 0.6, 0.6,
                                                   glm::dvec3(0), *s.genericBound.findOutput("P"));
    glm::dvec3 p = test::PointOnSquare(inst.bound, 0.3, 0.6);
    CHECK(g.x == p.x);
    CHECK(g.y == p.y);
    CHECK(g.z == p.z);
    CHECK(p.y == Approx(0.6 + 2 * std::sin(7 * 0.3)));

    // A parameter whose instance value makes code dead: Km = 0 leaves nothing but P.
    compiler::CompiledShader zero = test::CompileOrThrow(src, {{"Km", {0}}});
    CHECK(zero.bound.code.size() <= s.bound.code.size());
}

TEST_CASE("globals constant on a surface fold like parameters", "[compiler][specialise]") {
    compiler::CompiledShader s = test::CompileOrThrow("displacement t() { P += 0.1 * sin(u) * normalize(N); }");
    std::vector<std::string> errors;
    std::optional<vm::Program> flat = compiler::Specialise(s.bound, {}, &errors, {{vm::Global::N, {0, 0, 1}}});
    REQUIRE(flat);
    CHECK(errors.empty());
    CHECK_FALSE(flat->readsGlobal(vm::Global::N));
    // normalize(N) of a constant folds away, and so do the products with its zero components:
    // only sin(u), the product and the add on P.z remain.
    CHECK(Opcodes(*flat) == std::vector<vm::Op>{vm::Op::Sin, vm::Op::MulRK, vm::Op::AddRR});
    // Same values as the unspecialised program given that N.
    glm::dvec3 a = test::PointOnSquare(s.bound, 0.3, 0.7), b = test::PointOnSquare(*flat, 0.3, 0.7);
    CHECK(a == b);
}
