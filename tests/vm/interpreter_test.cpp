// tests/vm/interpreter_test.cpp: the interpreter's contracts over every shader in shaders/:
// containment (the scalar result at any point of a region lies in the region's affine and
// interval bounds), derivatives (duals agree with finite differences) and floor's splits. Every
// opcode under every number type, and the verifier over every opcode value, are
// tests/vm/conformance_test.cpp's; the verifier's own checks, tests/vm/verify_test.cpp's.
#include <catch2/catch.hpp>

#include <random>

#include "tests/test_util.h"
#include "tests/vm/shader_containment.h"

using namespace affray;

TEST_CASE("containment: every shader's scalar P lies in its affine and interval bounds", "[vm][containment]") {
    for (const std::string& path : test::AllShaders()) {
        compiler::CompileResult r = compiler::CompileFile(path);
        INFO(path << "\n" << r.diagnostics);
        REQUIRE(r.ok());
        test::CheckContainment<vm::Affine, vm::Interval>(path, r.shader->bound, 2000 / test::kSanitizerDivisor, 24, 42);
        test::CheckContainment<vm::Affine, vm::Interval>(path + " (shade)", r.shader->shade,
                                                         60 / test::kSanitizerDivisor, 12, 43);
    }
}

TEST_CASE("containment: stiff parameters of wave.sl", "[vm][containment]") {
    const std::string path = test::SourceDir() + "/shaders/wave.sl";
    const std::vector<std::vector<compiler::ParamOverride>> cases = {
        {{"frequency", {1000}}},               // many periods per region
        {{"Km", {1e3}}},                       // huge amplitude
        {{"decay", {200}}, {"Km", {5}}},       // steep decay
        {{"centerS", {0}}, {"centerT", {0}}},  // the sqrt's zero at a corner of the domain
    };
    for (const auto& params : cases) {
        compiler::CompileResult r = compiler::CompileFile(path, params);
        REQUIRE(r.ok());
        test::CheckContainment<vm::Affine, vm::Interval>(path + " " + params[0].name, r.shader->bound, 200, 16, 7);
    }
}

TEST_CASE("dual derivatives agree with finite differences", "[vm][dual]") {
    std::mt19937_64 rng(3);
    std::uniform_real_distribution<double> unit(0.05, 0.95);
    for (const std::string& path : test::AllShaders()) {
        compiler::CompileResult r = compiler::CompileFile(path);
        REQUIRE(r.ok());
        const vm::Program& program = r.shader->shade;
        for (int k = 0; k < 50; ++k) {
            double u = unit(rng), v = unit(rng);
            auto p = test::EvalOnSquare<vm::Dual<double>>(program, u, u, v, v);
            const double h = 1e-6;
            glm::dvec3 du = (test::PointOnSquare(program, u + h, v) - test::PointOnSquare(program, u - h, v)) / (2 * h);
            glm::dvec3 dv = (test::PointOnSquare(program, u, v + h) - test::PointOnSquare(program, u, v - h)) / (2 * h);
            for (int i = 0; i < 3; ++i) {
                INFO(path << " at (" << u << ", " << v << ") component " << i);
                CHECK(p[i].du == Approx(du[i]).epsilon(1e-5).margin(1e-6));
                CHECK(p[i].dv == Approx(dv[i]).epsilon(1e-5).margin(1e-6));
            }
        }
    }
}

TEST_CASE("floor straddling an integer is split into its two cases", "[vm][interpreter]") {
    // A bump in the middle of each of 4 cells along u: (frac(4u) - 0.5)^2 is 0.25 at every cell
    // boundary. Over a region straddling u = 0.25 the unsplit bound of frac is [0, 1], so the
    // bound would be [0, 0.25]; split, each side is within 4 * 1e-4 of frac = 0 or 1, so f^2 is
    // within 0.5 * 8e-4 of 0.25.
    compiler::CompiledShader s = test::CompileOrThrow(
        "displacement t() {\n  float f = u * 4 - floor(u * 4) - 0.5;\n  P = point(0, 0, f * f);\n}\n");
    const double u0 = 0.25 - 1e-4, u1 = 0.25 + 1e-4;
    for (vm::Interval z : {test::EvalOnSquare<vm::Affine>(s.bound, u0, u1, 0.5, 0.6).z.range(),
                           test::EvalOnSquare<vm::Interval>(s.bound, u0, u1, 0.5, 0.6).z,
                           test::EvalOnSquare<vm::Dual<vm::Affine>>(s.bound, u0, u1, 0.5, 0.6).z.v.range()}) {
        CHECK(z.lo() > 0.2495);
        CHECK(z.hi() < 0.2505);
        for (double u : {u0, 0.25 - 1e-9, 0.25, u1})  // both sides, and the boundary itself
            CHECK(z.contains(test::PointOnSquare(s.bound, u, 0.55).z));
    }
    // Two straddled boundaries (u and v): four cases, all joined.
    compiler::CompiledShader two =
        test::CompileOrThrow("displacement t() {\n  P = point(0, 0, floor(u * 4) + 10 * floor(v * 4));\n}\n");
    vm::Interval z = test::EvalOnSquare<vm::Affine>(two.bound, u0, u1, u0, u1).z.range();
    CHECK(z.lo() == 0);
    CHECK(z.hi() == 11);
    for (double u : {u0, u1})
        for (double v : {u0, u1}) CHECK(z.contains(test::PointOnSquare(two.bound, u, v).z));
}
