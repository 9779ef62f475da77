// bench/eval_bench.cpp: evaluations per second of shaders/wave.sl in every VM mode, beside a
// hand-written C++ function computing the same displacement, all in one process so the figures
// are ratios against a baseline measured on the same machine at the same time.
// Usage: affray_bench_eval [SHADER.sl] [--seconds S]   (Release builds only)
#include <cmath>
#include <cstdio>
#include <cstring>
#include <numbers>
#include <random>
#include <string>

#include "bench/evals_per_second.h"
#include "compiler/compile.h"
#include "scene/geometry/surface.h"

using namespace affray;

namespace {

using affray::bench::EvalsPerSecond;
// Evaluations between clock reads.
constexpr int kBatch = 256;

/// wave.sl with its default parameters, written by hand: the speed a native shader would have.
double NativeWaveZ(double u, double v) {
    const double Km = 0.06, frequency = 8, decay = 2.5;
    double r = std::sqrt((u - 0.5) * (u - 0.5) + (v - 0.5) * (v - 0.5));
    return Km * std::exp(-decay * r) * std::cos(2 * std::numbers::pi * frequency * r);
}

volatile double g_sink;  // keeps results alive so the optimiser cannot drop the work

template <class N>
double RegionEvalsPerSecond(const vm::Program& program, double width, double seconds) {
    vm::Interpreter<N> interp(program);
    const vm::ProgramOutput& P = *program.findOutput("P");
    const auto square = renderer::BilinearPatch::UnitSquare();
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> corner(0.0, 1.0 - width);
    return EvalsPerSecond(seconds, kBatch, [&](long) {
        double u0 = corner(rng), v0 = corner(rng);
        renderer::SetPatchGlobals(interp, square, u0, u0 + width, v0, v0 + width, glm::dvec3(0.0));
        interp.Run();
        g_sink = RangeOf(interp.Register(P.registers[2])).hi();
    });
}

}  // namespace

int main(int argc, char** argv) {
    std::string shaderPath = std::string(AFFRAY_SOURCE_DIR) + "/shaders/wave.sl";
    double seconds = 1.0;
    for (int i = 1; i < argc; ++i) {
        if (!std::strcmp(argv[i], "--seconds") && i + 1 < argc)
            seconds = std::stod(argv[++i]);
        else
            shaderPath = argv[i];
    }
    compiler::CompileResult result = compiler::CompileFile(shaderPath);
    if (!result.ok()) {
        std::fputs(result.diagnostics.format().c_str(), stderr);
        return 1;
    }
    const vm::Program& bound = result.shader->bound;
    std::printf("shader %s: bound program %zu instructions (%d operations before optimisation)\n", shaderPath.c_str(),
                bound.code.size(), result.shader->opsBeforeOptimisation);

    std::mt19937_64 rng(1);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    double native = EvalsPerSecond(seconds, kBatch, [&](long) { g_sink = NativeWaveZ(unit(rng), unit(rng)); });

    vm::Interpreter<double> scalar(bound);
    const auto square = renderer::BilinearPatch::UnitSquare();
    double scalarRate = EvalsPerSecond(seconds, kBatch, [&](long) {
        double u = unit(rng), v = unit(rng);
        renderer::SetPatchGlobals(scalar, square, u, u, v, v, glm::dvec3(0.0));
        scalar.Run();
        g_sink = scalar.Register(bound.findOutput("P")->registers[2]);
    });
    double affineRate = RegionEvalsPerSecond<vm::Affine>(bound, 1.0 / 64, seconds);
    double intervalRate = RegionEvalsPerSecond<vm::Interval>(bound, 1.0 / 64, seconds);
    double reducedRate = RegionEvalsPerSecond<vm::ReducedAffine>(bound, 1.0 / 64, seconds);

    std::printf("%-44s %14s %18s\n", "mode", "evals/s", "time vs native C++");
    auto row = [&](const char* name, double rate) { std::printf("%-44s %14.0f %17.1fx\n", name, rate, native / rate); };
    row("native C++ (hand-written)", native);
    row("vm scalar (double)", scalarRate);
    row("vm affine (region 1/64)", affineRate);
    row("vm interval (region 1/64)", intervalRate);
    row("vm reduced affine (region 1/64)", reducedRate);
    std::printf("affine / scalar cost: %.1fx   interval / scalar cost: %.1fx   reduced / scalar cost: %.1fx\n",
                scalarRate / affineRate, scalarRate / intervalRate, scalarRate / reducedRate);

    // What the renderer runs on a flat patch: the program specialised on the globals that are
    // constant over the surface (N, Ng, dPdu, dPdv; see renderer/render.cpp).
    std::vector<std::string> errors;
    vm::Program flat = *compiler::Specialise(bound, {}, &errors,
                                             {{vm::Global::N, {0, 0, 1}},
                                              {vm::Global::Ng, {0, 0, 1}},
                                              {vm::Global::dPdu, {1, 0, 0}},
                                              {vm::Global::dPdv, {0, 1, 0}}});
    std::printf("bound program on a flat patch: %zu instructions\n", flat.code.size());
    row("vm affine, flat patch (region 1/64)", RegionEvalsPerSecond<vm::Affine>(flat, 1.0 / 64, seconds));
    row("vm interval, flat patch (region 1/64)", RegionEvalsPerSecond<vm::Interval>(flat, 1.0 / 64, seconds));
    row("vm reduced affine, flat patch (region 1/64)",
        RegionEvalsPerSecond<vm::ReducedAffine>(flat, 1.0 / 64, seconds));
    return 0;
}
