// bench/bound_measure.h: what bench/bounds_bench.cpp measures for one shader: the widths of the
// bounds of the displaced P over square (u,v) regions of the unit square in one number type, the
// range the scalar program actually covers there (sampled), and evaluation rates.
// The shader is set up as the renderer sets it up (renderer/render.cpp: the bound program
// specialised on the globals constant over a flat patch; renderer/intersect.cpp: Dual<T> when the
// program takes derivatives; renderer::SetPatchGlobals for each region), so the figures are the
// ones the intersector sees.
// Rules: every function here is deterministic apart from timing (regions come from fixed seeds);
// rates of different modes are always measured interleaved (InterleavedRates), so that a change
// of machine load between measurements does not show up as a cost ratio.
#pragma once

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "bench/evals_per_second.h"
#include "compiler/compile.h"
#include "renderer/render.h"
#include "scene/geometry/surface.h"

namespace affray::bench {

/// One shader's bound program, ready to run on the unit square.
struct BenchShader {
    std::string name;  // file name without ".sl"
    vm::Program program;
    /// The renderer bounds such a program with Dual<Affine> / Dual<Interval> (and shades it with
    /// Dual<double>); the bench does the same.
    bool derivatives = false;
};

/// Compiles `path` with default parameters and specialises its bound program for the unit square
/// seen from the origin (renderer::ConstantGlobals); nullopt with the diagnostics on failure.
inline std::optional<BenchShader> LoadBenchShader(const std::string& path, std::string* error) {
    compiler::CompileResult result = compiler::CompileFile(path);
    if (!result.ok()) {
        *error = result.diagnostics.format();
        return std::nullopt;
    }
    const std::vector<compiler::ConstantGlobal> constants =
        renderer::ConstantGlobals(renderer::BilinearPatch::UnitSquare(), glm::dvec3(0.0), 0.0, 0.0);
    std::vector<std::string> errors;
    std::optional<vm::Program> program = compiler::Specialise(result.shader->bound, {}, &errors, constants);
    if (!program) {
        for (const std::string& e : errors) *error += e + "\n";
        return std::nullopt;
    }
    BenchShader s;
    s.name = std::filesystem::path(path).stem().string();
    s.program = std::move(*program);
    s.derivatives = s.program.usesDerivatives();
    return s;
}

/// The lower-left corners of `count` square regions of side `width` inside [0,1]^2, uniform,
/// from `seed`: every shader and mode is measured on the same regions.
inline std::vector<std::pair<double, double>> RegionCorners(double width, int count, uint64_t seed) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> corner(0.0, 1.0 - width);
    std::vector<std::pair<double, double>> out;
    for (int i = 0; i < count; ++i) {
        double u0 = corner(rng);
        out.emplace_back(u0, corner(rng));
    }
    return out;
}

/// The bound of P' over one region, as widths (hi - lo) of ranges.
struct RegionWidths {
    bool bounded = false;  // every component finite; the widths are meaningful only then
    double box = 0;        // mean over x, y, z of the width of each component's range
    double z = 0;          // z alone: the displacement along the unit square's normal
    double diag = 0;       // (x + y + z)/sqrt(3), a direction oblique to every axis
};

/// The widths of `V`'s bound of P (V: Affine, Interval or a Dual of either), region by region.
template <class V>
std::vector<RegionWidths> BoundWidths(const BenchShader& s, const std::vector<std::pair<double, double>>& corners,
                                      double width) {
    vm::Interpreter<V> interp(s.program);
    const vm::ProgramOutput& out = *s.program.findOutput("P");
    const auto square = renderer::BilinearPatch::UnitSquare();
    std::vector<RegionWidths> widths;
    for (auto [u0, v0] : corners) {
        vm::Vec3<V> p = renderer::EvaluateOnPatch(interp, square, u0, u0 + width, v0, v0 + width, glm::dvec3(0.0), out);
        // In the value's own type, so that an affine sum keeps the correlations of x, y and z, as
        // the intersector's ray-frame measures do.
        auto diag = (vm::ValueOf(p.x) + vm::ValueOf(p.y) + vm::ValueOf(p.z)) * (1 / std::sqrt(3.0));
        vm::Interval r[4] = {RangeOf(vm::ValueOf(p.x)), RangeOf(vm::ValueOf(p.y)), RangeOf(vm::ValueOf(p.z)),
                             RangeOf(diag)};
        RegionWidths w;
        w.bounded = std::all_of(r, r + 4, [](const vm::Interval& i) { return std::isfinite(i.width()); });
        if (w.bounded) {
            w.box = (r[0].width() + r[1].width() + r[2].width()) / 3;
            w.z = r[2].width();
            w.diag = r[3].width();
        }
        widths.push_back(w);
    }
    return widths;
}

/// The hull of z of P' at a (grid x grid) lattice of points of each region, corners included: a
/// lower bound of the true z range, to compare bounds with. NaN where a point is not finite.
template <class S>
std::vector<double> SampledZWidths(const BenchShader& s, const std::vector<std::pair<double, double>>& corners,
                                   double width, int grid) {
    vm::Interpreter<S> interp(s.program);
    const vm::ProgramOutput& out = *s.program.findOutput("P");
    const auto square = renderer::BilinearPatch::UnitSquare();
    std::vector<double> widths;
    for (auto [u0, v0] : corners) {
        double lo = INFINITY, hi = -INFINITY;
        for (int i = 0; i < grid; ++i)
            for (int j = 0; j < grid; ++j) {
                double u = u0 + width * i / (grid - 1), v = v0 + width * j / (grid - 1);
                double z = vm::ValueOf(renderer::EvaluateOnPatch(interp, square, u, u, v, v, glm::dvec3(0.0), out).z);
                lo = std::fmin(lo, z);
                hi = std::fmax(hi, z);
                if (!std::isfinite(z)) lo = hi = NAN;
            }
        widths.push_back(hi - lo);
    }
    return widths;
}

inline volatile double g_sink;  // keeps results alive so the optimiser cannot drop the work

/// One evaluation of `V` per call, cycling through the regions (or random points for a point type
/// when width is 0): what the rates count.
template <class V>
std::function<void()> Evaluator(const BenchShader& s, const std::vector<std::pair<double, double>>& corners,
                                double width) {
    auto interp = std::make_shared<vm::Interpreter<V>>(s.program);
    const int z = s.program.findOutput("P")->registers[2];
    size_t next = 0;
    return [interp, z, next, &corners, width]() mutable {
        auto [u0, v0] = corners[next];
        next = next + 1 == corners.size() ? 0 : next + 1;
        renderer::SetPatchGlobals(*interp, renderer::BilinearPatch::UnitSquare(), u0, u0 + width, v0, v0 + width,
                                  glm::dvec3(0.0));
        interp->Run();
        using vm::RangeOf;  // the double overload; the others are found by ADL
        g_sink = RangeOf(vm::ValueOf(interp->Register(z))).hi();
    };
}

/// Evaluations per second of each of `modes`, measured in alternating slices of about 20 ms
/// until each has run for `seconds` in all: slow changes of the machine's load then affect every
/// mode alike and cancel in the ratios.
inline std::vector<double> InterleavedRates(double seconds, std::vector<std::function<void()>> modes) {
    constexpr double kSlice = 0.02;
    constexpr int kBatch = 16;  // bounded evaluations take microseconds: a clock read costs nothing
    const int rounds = std::max(1, static_cast<int>(std::lround(seconds / kSlice)));
    std::vector<double> sum(modes.size(), 0.0);
    for (int k = 0; k < rounds; ++k)
        for (size_t m = 0; m < modes.size(); ++m)
            sum[m] += EvalsPerSecond(seconds / rounds, kBatch, [&](long) { modes[m](); });
    for (double& r : sum) r /= rounds;
    return sum;
}

}  // namespace affray::bench
