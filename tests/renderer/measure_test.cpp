// tests/renderer/measure_test.cpp: a region bound measured along directions (renderer/measure.h)
// against its points: every point of the bound, sampled at the corners of its symbols and inside,
// measured in long double, lies in the measure's range over the symbols' box; and the ranges are
// closed, so a ray grazing a bound (a range ending at 0) is not said to miss it.
#include <catch2/catch.hpp>

#include <random>

#include "renderer/measure.h"

using namespace affray;
using renderer::Measure;
using renderer::Range;

TEST_CASE("measure: a range holds its ends, 0 among them", "[renderer][intersect]") {
    CHECK_FALSE((Range{0.0, 1.0}.excludesZero()));
    CHECK_FALSE((Range{-1.0, 0.0}.excludesZero()));
    CHECK_FALSE((Range{0.0, 0.0}.excludesZero()));
    CHECK_FALSE((Range{-0.0, 0.0}.excludesZero()));
    CHECK_FALSE((Range{-2.0, 3.0}.excludesZero()));
    CHECK((Range{1e-300, 1.0}.excludesZero()));
    CHECK((Range{-1.0, -1e-300}.excludesZero()));
}

TEST_CASE("measure: a bound's measures hold each of its points", "[renderer][intersect]") {
    // A bound is the points c + a eps_u + b eps_v + g eps_w + r * delta (every eps and delta_i
    // in [-1, 1]). Along a unit n from o, its measure over a box of (eps_u, eps_v) holds
    // n . (p - o) for each of them: a linear function of the symbols, largest and smallest at the
    // box's corners, which are sampled with random points inside.
    std::mt19937_64 rng(41);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    auto vec = [&](double scale) { return glm::dvec3(unit(rng), unit(rng), unit(rng)) * scale; };
    for (int trial = 0; trial < 120; ++trial) {
        renderer::RegionBound b;
        const double scale = std::ldexp(1.0, static_cast<int>(8 * unit(rng)));
        b.c = vec(scale);
        b.a = vec(0.3 * scale);
        b.b = vec(0.3 * scale);
        b.g = vec(trial % 3 == 0 ? 0.0 : 0.1 * scale);
        b.r = glm::abs(vec(trial % 4 == 0 ? 0.0 : 0.05 * scale));
        b.boundedMask = 7;
        const glm::dvec3 o = vec(2 * scale);
        const glm::dvec3 n[3] = {glm::normalize(vec(1)), glm::normalize(vec(1)), glm::normalize(vec(1))};
        Measure m[3];
        renderer::MeasureAlong<3>(b, o, n, m);
        // A box of (eps_u, eps_v): the whole square, or a random part of it.
        double eu0 = -1, eu1 = 1, ev0 = -1, ev1 = 1;
        if (trial % 2) {
            eu0 = unit(rng), eu1 = unit(rng), ev0 = unit(rng), ev1 = unit(rng);
            if (eu0 > eu1) std::swap(eu0, eu1);
            if (ev0 > ev1) std::swap(ev0, ev1);
        }
        for (int k = 0; k < 3; ++k) {
            REQUIRE(m[k].bounded);
            const Range whole = renderer::Over(m[k], 0, 1, 0, 1);
            const Range part = renderer::OverBox(m[k], eu0, eu1, ev0, ev1);
            long double lo = INFINITY, hi = -INFINITY;
            for (int sample = 0; sample < 100; ++sample) {
                // The first 64 samples are the corners of (eps_u, eps_v, eps_w, delta).
                const bool corner = sample < 64;
                const double su = corner ? (sample & 1 ? 1.0 : -1.0) : unit(rng);
                const double sv = corner ? (sample & 2 ? 1.0 : -1.0) : unit(rng);
                const double eu = eu0 + (eu1 - eu0) * (0.5 + 0.5 * su), ev = ev0 + (ev1 - ev0) * (0.5 + 0.5 * sv);
                const double ew = corner ? (sample & 4 ? 1.0 : -1.0) : unit(rng);
                const double delta[3] = {corner ? (sample & 8 ? 1.0 : -1.0) : unit(rng),
                                         corner ? (sample & 16 ? 1.0 : -1.0) : unit(rng),
                                         corner ? (sample & 32 ? 1.0 : -1.0) : unit(rng)};
                long double d = 0;
                for (int i = 0; i < 3; ++i) {
                    const long double p = static_cast<long double>(b.c[i]) + static_cast<long double>(b.a[i]) * eu +
                                          static_cast<long double>(b.b[i]) * ev +
                                          static_cast<long double>(b.g[i]) * ew +
                                          static_cast<long double>(b.r[i]) * delta[i];
                    d += static_cast<long double>(n[k][i]) * (p - o[i]);
                }
                lo = std::min(lo, d);
                hi = std::max(hi, d);
                INFO("trial " << trial << " direction " << k << " sample " << sample);
                CHECK(static_cast<long double>(part.lo) <= d);
                CHECK(d <= static_cast<long double>(part.hi));
                CHECK(static_cast<long double>(whole.lo) <= d);
                CHECK(d <= static_cast<long double>(whole.hi));
            }
            // And not much wider than the points' extent: the rounding terms are a few ulps of the
            // terms' magnitudes (each within 4 scale).
            INFO("trial " << trial << " direction " << k);
            CHECK(static_cast<long double>(part.hi - part.lo) <= (hi - lo) + 1e-12L * scale);
        }
    }
}
