// tests/vm/numbers/quad_form_test.cpp: vm/numbers/quad_form.h. Every operation contains the double
// result of the same operation at every point (Stolfi's aavalid method, as for noise's
// LocalForm), the product's reductions of degrees 3 and 4 included; the quadratic part's range is
// exact.
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <string>

#include "tests/test_random.h"
#include "vm/numbers/quad_form.h"

using namespace affray::vm;
using affray::test::Rng;
using affray::test::Samples;

namespace {

/// The polynomial part of x at (u, v) and own symbol values w, in long double.
long double PolynomialAt(const QuadForm& x, long double u, long double v, const long double* w) {
    const double* c = x.c;
    long double s = c[QuadForm::k0] + c[QuadForm::kU] * u + c[QuadForm::kV] * v + c[QuadForm::kUU] * u * u +
                    c[QuadForm::kUV] * u * v + c[QuadForm::kVV] * v * v;
    for (int k = 0; k < QuadForm::kOwn; ++k) s += x.o[k] * w[k];
    return s;
}

/// A random point: (u, v) at a corner, on an edge or inside the square, and the own symbols'
/// values anywhere in [-1, 1]; Value draws a double that a form allows there.
struct SamplePoint {
    long double u, v, w[QuadForm::kOwn];

    explicit SamplePoint(Rng& rng) {
        auto coordinate = [&] { return rng.chance(0.3) ? static_cast<long double>(rng.integer(-1, 1)) : rng.eps(); };
        u = coordinate();
        v = coordinate();
        for (long double& wk : w) wk = coordinate();
    }
    /// A double within f at this point (NaN if the rounding to double left f).
    double Value(const QuadForm& f, Rng& rng) const {
        const long double m = PolynomialAt(f, u, v, w);
        const double x = static_cast<double>(m + static_cast<long double>(rng.eps()) * f.r);
        return std::fabs(x - m) <= f.r ? x : std::numeric_limits<double>::quiet_NaN();
    }
    /// Whether the double `scalar` lies in f at this point.
    bool Holds(const QuadForm& f, double scalar) const {
        return std::fabs(static_cast<long double>(scalar) - PolynomialAt(f, u, v, w)) <= f.r;
    }
    /// "at (u, v): scalar outside mid +- r", for a failure.
    std::string Outside(const QuadForm& f, double scalar) const {
        return "at (" + std::to_string(static_cast<double>(u)) + ", " + std::to_string(static_cast<double>(v)) +
               "): " + std::to_string(scalar) + " outside " +
               std::to_string(static_cast<double>(PolynomialAt(f, u, v, w))) + " +- " + std::to_string(f.r);
    }
};

QuadForm RandomForm(Rng& rng) {
    QuadForm x{};
    const double scale = std::ldexp(1.0, rng.integer(-30, 3));
    for (double& ck : x.c) ck = rng.chance(0.2) ? 0.0 : rng.uniform(-1, 1) * scale;
    for (double& ok : x.o) ok = rng.chance(0.5) ? 0.0 : rng.uniform(-1, 1) * scale * 0.1;
    if (rng.chance(0.1)) {  // an exact constant
        const double c0 = x.c[QuadForm::k0];
        x = QuadForm();
        x.c[QuadForm::k0] = c0;
        return x;
    }
    x.r = (std::fabs(x.c[QuadForm::k0]) + scale) * (rng.chance(0.5) ? 0x1p-45 : rng.uniform(0, 1) * 1e-3);
    return x;
}

}  // namespace

TEST_CASE("QuadForm operations contain the double results (aavalid)", "[vm][quadform]") {
    Rng rng(41);
    affray::test::Tally tally;
    int skipped = 0;
    for (int n = 0; n < Samples(4000); ++n) {
        const QuadForm x = RandomForm(rng);
        const bool square = rng.chance(0.2);
        const QuadForm y = square ? x : RandomForm(rng);
        const double k = rng.chance(0.3) ? rng.integer(-15, 15) : rng.uniform(-16, 16);
        const int op = rng.integer(0, 6);
        const QuadForm z = op == 0   ? x + y
                           : op == 1 ? x - y
                           : op == 2 ? x * y
                           : op == 3 ? x * k
                           : op == 4 ? x + k
                           : op == 5 ? -x
                                     : k * x;
        for (int trial = 0; trial < 16; ++trial) {
            const SamplePoint at(rng);
            const double a = at.Value(x, rng), b = square ? a : at.Value(y, rng);
            if (std::isnan(a) || std::isnan(b)) {
                ++skipped;
                continue;
            }
            const double scalar = op == 0   ? a + b
                                  : op == 1 ? a - b
                                  : op == 2 ? a * b
                                  : op == 3 ? a * k
                                  : op == 4 ? a + k
                                  : op == 5 ? -a
                                            : k * a;
            tally.samples++;
            if (!at.Holds(z, scalar)) tally.fail("op " + std::to_string(op) + " " + at.Outside(z, scalar));
        }
    }
    INFO(tally.samples << " samples, " << skipped << " skipped\n" << tally.first.str());
    CHECK(tally.failures == 0);
    CHECK(skipped < tally.samples / 2);
}

TEST_CASE("QuadForm Lerp contains the double lerp wherever s lies between 0 and 1 (aavalid)", "[vm][quadform]") {
    Rng rng(47);
    affray::test::Tally tally;
    int skipped = 0;
    for (int n = 0; n < Samples(4000); ++n) {
        const QuadForm v0 = RandomForm(rng), v1 = rng.chance(0.1) ? v0 : RandomForm(rng);
        // A fade-like s: mostly inside [0, 1] over the square, sometimes reaching its ends.
        QuadForm s = RandomForm(rng);
        const double c0 = rng.chance(0.2) ? static_cast<double>(rng.integer(0, 1)) : rng.uniform(0, 1);
        const double spread = s.coefficientSum() - std::fabs(s.c[QuadForm::k0]) + s.r;
        const double room = rng.chance(0.2) ? 0.5 : std::min(c0, 1 - c0);
        s = s * (spread > 0 ? rng.uniform(0, 1) * room / spread : 1.0);
        s.c[QuadForm::k0] = c0;
        const QuadForm z = Lerp(v0, v1, s);
        for (int trial = 0; trial < 16; ++trial) {
            const SamplePoint at(rng);
            const double a = at.Value(v0, rng), b = at.Value(v1, rng), f = at.Value(s, rng);
            if (std::isnan(a) || std::isnan(b) || !(f >= 0 && f <= 1)) {
                ++skipped;
                continue;
            }
            const double scalar = a + f * (b - a);
            tally.samples++;
            if (!at.Holds(z, scalar)) tally.fail("lerp " + at.Outside(z, scalar));
        }
    }
    INFO(tally.samples << " samples, " << skipped << " skipped\n" << tally.first.str());
    CHECK(tally.failures == 0);
    CHECK(tally.samples >= 4 * Samples(4000));  // a quarter of the draws or more
}

TEST_CASE("QuadForm Lerp weighs the ends' remainders by 1 - s and s", "[vm][quadform]") {
    // Two constants with remainder 0.01 each, s = 1/2 exactly: the lerp's remainder is about
    // 0.01 (the product v0 + s (v1 - v0) would give 0.02).
    QuadForm v0(1.0), v1(3.0);
    v0.r = v1.r = 0.01;
    const QuadForm half(0.5);
    const QuadForm z = Lerp(v0, v1, half), product = v0 + half * (v1 - v0);
    CHECK(z.c[QuadForm::k0] == 2.0);
    CHECK(z.r == Approx(0.01).epsilon(1e-9));
    CHECK(product.r == Approx(0.02).epsilon(1e-9));
    // A linear s keeps its slope: (1 + u)/2 between 0 and 2 is 1 + u.
    const QuadForm s = QuadForm::Linear(0.5, 0.5, 0, 0);
    const QuadForm line = Lerp(QuadForm(0.0), QuadForm(2.0), s);
    CHECK(line.c[QuadForm::k0] == 1.0);
    CHECK(line.c[QuadForm::kU] == 1.0);
    CHECK(line.r < 1e-14);
}

TEST_CASE("QuadForm products keep the quadratic part exactly and lose little to degrees 3 and 4", "[vm][quadform]") {
    // (1 + u)(1 + v) = 1 + u + v + uv: nothing to reduce, no remainder beyond rounding.
    const QuadForm a = QuadForm::Linear(1, 1, 0, 0), b = QuadForm::Linear(1, 0, 1, 0);
    const QuadForm p = a * b;
    CHECK(p.c[QuadForm::k0] == 1);
    CHECK(p.c[QuadForm::kU] == 1);
    CHECK(p.c[QuadForm::kV] == 1);
    CHECK(p.c[QuadForm::kUV] == 1);
    CHECK(p.r < 1e-13);
    // u * u^2 = u^3 = 0.75 u +- 0.25 (Chebyshev: the best line), u^2 * u^2 = u^4 = u^2 - 1/8 +- 1/8.
    QuadForm u = QuadForm::Linear(0, 1, 0, 0), uu{};
    uu.c[QuadForm::kUU] = 1;
    const QuadForm cube = u * uu, fourth = uu * uu;
    CHECK(cube.c[QuadForm::kU] == 0.75);
    CHECK(cube.r == Approx(0.25).epsilon(1e-12));
    CHECK(fourth.c[QuadForm::kUU] == 1);
    CHECK(fourth.c[QuadForm::k0] == -0.125);
    CHECK(fourth.r == Approx(0.125).epsilon(1e-12));
}

TEST_CASE("QuadForm's quadratic range is the exact range over the square", "[vm][quadform]") {
    Rng rng(43);
    for (int n = 0; n < Samples(500); ++n) {
        QuadForm x{};
        x.c[QuadForm::kUU] = rng.chance(0.2) ? 0.0 : rng.uniform(-2, 2);
        x.c[QuadForm::kUV] = rng.chance(0.2) ? 0.0 : rng.uniform(-2, 2);
        x.c[QuadForm::kVV] = rng.chance(0.2) ? 0.0 : rng.uniform(-2, 2);
        double lo, hi;
        x.quadraticRange(&lo, &hi);
        double sampledLo = INFINITY, sampledHi = -INFINITY;
        for (int i = 0; i <= 200; ++i)
            for (int j = 0; j <= 200; ++j) {
                const double u = -1 + i / 100.0, v = -1 + j / 100.0;
                const double q = x.c[QuadForm::kUU] * u * u + x.c[QuadForm::kUV] * u * v + x.c[QuadForm::kVV] * v * v;
                sampledLo = std::fmin(sampledLo, q);
                sampledHi = std::fmax(sampledHi, q);
            }
        INFO(x.c[QuadForm::kUU] << " u^2 + " << x.c[QuadForm::kUV] << " uv + " << x.c[QuadForm::kVV] << " v^2: [" << lo
                                << ", " << hi << "], sampled [" << sampledLo << ", " << sampledHi << "]");
        CHECK(lo <= sampledLo + 1e-12);
        CHECK(hi >= sampledHi - 1e-12);
        // The grid's spacing is 0.01, so the sampled extremes are within 1e-3 of the exact ones.
        CHECK(lo >= sampledLo - 1e-3);
        CHECK(hi <= sampledHi + 1e-3);
    }
}
