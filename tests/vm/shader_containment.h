// tests/vm/shader_containment.h: the containment check of whole shaders, shared by the tests of
// every bounded number type: over random regions of a base surface (the unit square unless a
// test gives another), the scalar P at points of a
// region must lie in the region's bound in each of the given types (run as Dual<T> when the
// program takes derivatives, as the renderer does), and no bound may be unbounded.
#pragma once

#include <catch2/catch.hpp>

#include <array>
#include <random>
#include <string>

#include "tests/test_util.h"

namespace affray::test {

/// The ranges of the bound of P over [u0,u1] x [v0,v1] of `surface` in number type N (Dual<N> if
/// the program takes derivatives).
template <class N>
std::array<vm::Interval, 3> BoundOnSurface(const vm::Program& program, const renderer::BaseSurface& surface, double u0,
                                           double u1, double v0, double v1) {
    std::array<vm::Interval, 3> out;
    if (program.usesDerivatives()) {
        auto p = EvalOnSurface<vm::Dual<N>>(program, surface, u0, u1, v0, v1);
        for (int i = 0; i < 3; ++i) out[i] = RangeOf(p[i].v);
    } else {
        auto p = EvalOnSurface<N>(program, surface, u0, u1, v0, v1);
        for (int i = 0; i < 3; ++i) out[i] = RangeOf(p[i]);
    }
    return out;
}

/// Checks containment for `program` on `surface` in every type of `Bounds` on `regions` random
/// regions (widths log-uniform from the whole domain down to 1e-9), each with `points` points
/// (corners and centre first).
template <class... Bounds>
void CheckContainmentOn(const std::string& name, const vm::Program& program, const renderer::BaseSurface& surface,
                        int regions, int points, uint64_t seed) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    const char* names[] = {vm::NumberTraits<Bounds>::kName...};
    int failures = 0, unbounded = 0;
    for (int r = 0; r < regions; ++r) {
        double width = std::pow(10.0, -9.0 * unit(rng));
        double wu = r == 0 ? 1.0 : width, wv = r == 0 ? 1.0 : width * (0.5 + unit(rng));
        wv = std::min(wv, 1.0);
        double u0 = (1 - wu) * unit(rng), v0 = (1 - wv) * unit(rng);
        double u1 = u0 + wu, v1 = v0 + wv;
        const std::array<vm::Interval, 3> bounds[] = {BoundOnSurface<Bounds>(program, surface, u0, u1, v0, v1)...};
        for (const auto& b : bounds)
            for (int i = 0; i < 3; ++i) unbounded += b[i].isUnbounded();
        for (int k = 0; k < points; ++k) {
            double fu = k < 4 ? (k & 1) : k == 4 ? 0.5 : unit(rng);
            double fv = k < 4 ? (k >> 1) : k == 4 ? 0.5 : unit(rng);
            double u = std::min(u1, u0 + fu * (u1 - u0)), v = std::min(v1, v0 + fv * (v1 - v0));
            glm::dvec3 p = PointOnSurface(program, surface, u, v);
            for (int i = 0; i < 3; ++i)
                for (size_t t = 0; t < sizeof...(Bounds); ++t)
                    if (!bounds[t][i].contains(p[i]) && failures++ < 5)
                        UNSCOPED_INFO(name << ": P[" << i << "] = " << p[i] << " at (" << u << ", " << v << ") region ["
                                           << u0 << "," << u1 << "]x[" << v0 << "," << v1 << "] not in " << names[t]
                                           << " " << bounds[t][i].toString());
        }
    }
    CHECK(failures == 0);
    // Containment in an unbounded value is trivially true: the shaders here are finite everywhere
    // on the domain, so their bounds must be too.
    CHECK(unbounded == 0);
}

/// CheckContainmentOn the unit square.
template <class... Bounds>
void CheckContainment(const std::string& name, const vm::Program& program, int regions, int points, uint64_t seed) {
    CheckContainmentOn<Bounds...>(name, program, renderer::BilinearPatch::UnitSquare(), regions, points, seed);
}

}  // namespace affray::test
