// tests/compiler/semantics_util.h: the language-semantics suite's helpers. The suite is one file
// per lowering source it covers (tests/compiler/lower_test.cpp, lower_flow_test.cpp,
// lower_logic_test.cpp, lower_functions_test.cpp, lower_library_test.cpp, builtins_test.cpp,
// value_matrix_test.cpp), each compiling tiny shaders and checking P (or N) at chosen (u, v) of
// the unit square against values worked out by hand in the comments. On the unit square
// P = (u, v, 0), N = Ng = (0, 0, 1), dPdu = (1, 0, 0), dPdv = (0, 1, 0), s = u, t = v,
// du = dv = 1/1024, E = 0.
//
// Every value is checked on the instance's shade program, and Eval also requires the instance's
// bound program and the generic shade program (parameters as registers, so branches and loops on
// parameters are not folded while lowering) to give the same P, and an Interval evaluation of the
// bound program at the point to contain it.
// Tests whose comment starts "Regression test" guard bugs found by the suite and fixed.
#pragma once

#include <catch2/catch.hpp>

#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <chrono>
#include <cmath>
#include <csignal>
#include <numbers>
#include <string>
#include <thread>
#include <vector>

#include "tests/test_util.h"

namespace affray::test::semantics {

using Catch::Matchers::WithinAbs;
using Overrides = std::vector<compiler::ParamOverride>;
inline constexpr double kPi = std::numbers::pi;
inline constexpr double kEps = 1e-12;

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
inline glm::dvec3 Run(const vm::Program& program, double u, double v, const Overrides& params = {},
                      const char* name = "P") {
    if (program.usesDerivatives()) {
        auto p = RunAs<vm::Dual<double>>(program, u, v, params, name);
        return {p.x.v, p.y.v, p.z.v};
    }
    auto p = RunAs<double>(program, u, v, params, name);
    return {p.x, p.y, p.z};
}

/// The Interval value of output `name` of `program` at the point (u, v).
inline std::array<vm::Interval, 3> RunInterval(const vm::Program& program, double u, double v, const char* name = "P") {
    if (program.usesDerivatives()) {
        auto p = RunAs<vm::Dual<vm::Interval>>(program, u, v, {}, name);
        return {p.x.v, p.y.v, p.z.v};
    }
    auto p = RunAs<vm::Interval>(program, u, v, {}, name);
    return {p.x, p.y, p.z};
}

inline bool SameNumber(double a, double b) {
    if (std::isnan(a) || std::isnan(b)) return std::isnan(a) && std::isnan(b);
    return std::abs(a - b) <= kEps * std::max(1.0, std::abs(a));
}

inline std::string Show(const glm::dvec3& p) {
    return "[" + std::to_string(p.x) + " " + std::to_string(p.y) + " " + std::to_string(p.z) + "]";
}

enum class Generic { Check, Skip };

/// Output `name` of the shader `source` (with `params`) at (u, v), from the instance's shade
/// program; requires its bound program (for P), the generic shade program and an Interval
/// evaluation to agree with it.
inline glm::dvec3 Eval(const std::string& source, double u, double v, const Overrides& params = {},
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
inline std::string Shader(const std::string& body, const std::string& params = "") {
    return "displacement t(" + params + ") {\n" + body + "\n}\n";
}

/// P of a shader body at (u, v).
inline glm::dvec3 PAt(const std::string& body, double u = 0.25, double v = 0.75) { return Eval(Shader(body), u, v); }
/// P.z of a shader body at (u, v).
inline double Z(const std::string& body, double u = 0.25, double v = 0.75) { return PAt(body, u, v).z; }
/// P.z of a whole source file at (u, v).
inline double ZSource(const std::string& source, double u = 0.25, double v = 0.75, const Overrides& params = {}) {
    return Eval(source, u, v, params).z;
}

inline void CheckVec(const glm::dvec3& got, const glm::dvec3& want, double eps = kEps) {
    INFO("got " << Show(got) << ", want " << Show(want));
    CHECK_THAT(got.x, WithinAbs(want.x, eps));
    CHECK_THAT(got.y, WithinAbs(want.y, eps));
    CHECK_THAT(got.z, WithinAbs(want.z, eps));
}

/// Whether compiling `source` finishes within `seconds` (in a child process, killed after that).
inline bool CompilesWithin(const std::string& source, int seconds) {
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

}  // namespace affray::test::semantics
