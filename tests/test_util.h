// tests/test_util.h: helpers shared by the test files: compiling shader text, evaluating it on
// the unit square in any number type, and listing the shaders in shaders/.
#pragma once

#include <catch2/catch.hpp>

#include <filesystem>
#include <string>
#include <vector>

#include "compiler/compile.h"
#include "renderer/surface.h"

namespace affray::test {

inline std::string SourceDir() { return AFFRAY_SOURCE_DIR; }

/// Requires `got` to equal `want` within 1e-12 per component, printing both on failure.
inline void RequireVec(const glm::dvec3& got, const glm::dvec3& want) {
    INFO("got [" << got.x << " " << got.y << " " << got.z << "], want [" << want.x << " " << want.y << " "
                 << want.z << "]");
    REQUIRE(got.x == Approx(want.x).margin(1e-12));
    REQUIRE(got.y == Approx(want.y).margin(1e-12));
    REQUIRE(got.z == Approx(want.z).margin(1e-12));
}

/// Every .sl file in shaders/, sorted.
inline std::vector<std::string> AllShaders() {
    std::vector<std::string> paths;
    for (const auto& entry : std::filesystem::directory_iterator(SourceDir() + "/shaders"))
        if (entry.path().extension() == ".sl") paths.push_back(entry.path().string());
    std::sort(paths.begin(), paths.end());
    return paths;
}

/// Compiles a shader body given as text; throws with the diagnostics if it does not compile.
inline compiler::CompiledShader CompileOrThrow(const std::string& source,
                                               const std::vector<compiler::ParamOverride>& params = {}) {
    compiler::CompileResult r = compiler::CompileSource("test.sl", source, params);
    if (!r.ok()) throw std::runtime_error("does not compile:\n" + r.diagnostics);
    return std::move(*r.shader);
}

/// Runs `program` with number type N over [u0,u1] x [v0,v1] of the unit square; returns output
/// `name` (P or N).
template <class N>
vm::Vec3<N> EvalOnSquare(const vm::Program& program, double u0, double u1, double v0, double v1,
                         const char* name = "P") {
    vm::Interpreter<N> interp(program);
    return renderer::EvaluateOnPatch(interp, renderer::BilinearPatch::UnitSquare(), u0, u1, v0, v1, glm::dvec3(0.0),
                                     *program.findOutput(name));
}

/// The displaced P at one point, in doubles (through duals if the program takes derivatives).
inline glm::dvec3 PointOnSquare(const vm::Program& program, double u, double v, const char* name = "P") {
    if (program.usesDerivatives()) {
        auto p = EvalOnSquare<vm::Dual<double>>(program, u, u, v, v, name);
        return {p.x.v, p.y.v, p.z.v};
    }
    auto p = EvalOnSquare<double>(program, u, u, v, v, name);
    return {p.x, p.y, p.z};
}

}  // namespace affray::test
