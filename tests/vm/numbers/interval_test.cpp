// tests/vm/numbers/interval_test.cpp: containment and tightness of every Interval operation (the branch
// functions' exactness properties are in tests/vm/branch_test.cpp).
// Random operand intervals (magnitudes 1e-6..1e6, across and touching 0, points) and points chosen
// on purpose (both endpoints, 0, the extrema of sin and cos, random inner points): the double
// result at every point must lie in the interval result (Unbounded if it is NaN or infinite), and
// for unary functions the interval must not exceed the hull of the sampled results by more than
// rounding when the samples include every extreme. AFFRAY_SAMPLES=N raises the sample count.
#include <catch2/catch.hpp>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <sstream>

#include "tests/test_random.h"
#include "vm/numbers/number.h"

using namespace affray::vm;
using affray::test::Samples;
using affray::test::Tally;

namespace {

struct Gen {
    std::mt19937_64 rng;
    explicit Gen(uint64_t seed) : rng(seed) {}
    double uniform(double lo, double hi) { return std::uniform_real_distribution<>(lo, hi)(rng); }
    int integer(int lo, int hi) { return std::uniform_int_distribution<>(lo, hi)(rng); }
    double magnitude(double e10lo, double e10hi) { return std::pow(10.0, uniform(e10lo, e10hi)); }

    // An interval of one of several shapes, scaled by 10^[e10lo, e10hi].
    Interval interval(double e10lo, double e10hi) {
        double m = magnitude(e10lo, e10hi);
        double a = uniform(-m, m), w = m * std::pow(10.0, uniform(-8, 0.3));
        switch (integer(0, 7)) {
            case 0: return Interval(0.0, w);                   // touching 0 from above
            case 1: return Interval(-w, 0.0);                  // touching 0 from below
            case 2: return Interval(-w, w * uniform(0.1, 2));  // across 0
            case 3: return Interval(a);                        // a point
            case 4: return Interval(std::fabs(a), std::fabs(a) + w);
            default: return Interval(a, a + w);
        }
    }
    // Points of x chosen on purpose, then random ones.
    std::vector<double> points(const Interval& x, int random) {
        std::vector<double> p = {x.lo(), x.hi(), x.mid()};
        if (x.contains(0.0)) p.push_back(0.0);
        // The doubles nearest to the extrema k*pi/2 of sin and cos inside x.
        if (x.hi() - x.lo() < 100 && std::fabs(x.lo()) < 1e9) {
            const double halfPi = 1.5707963267948966;
            const auto first = static_cast<long long>(std::ceil(x.lo() / halfPi));
            for (long long k = first; double(k) * halfPi <= x.hi(); ++k)
                if (x.contains(double(k) * halfPi)) p.push_back(double(k) * halfPi);
        }
        for (int i = 0; i < random; ++i) p.push_back(std::fmin(x.hi(), uniform(x.lo(), x.hi())));
        return p;
    }
};

// `what` describes the sample; it is called only on failure.
template <class W>
void Contain(Tally& t, W what, double rd, const Interval& ri) {
    t.samples++;
    bool ok = std::isfinite(rd) ? ri.contains(rd) : ri.isUnbounded();
    if (!ok) t.fail(what() + " -> " + ToString(rd) + " not in " + ri.toString());
}

// Containment of f at every chosen point; for exactly sampled unary f, tightness too.
template <class F>
void CheckUnary(Tally& t, const Interval& x, F f, bool checkTight, Gen& g) {
    Interval r = f(x);
    if (!r.isUnbounded()) t.bounded++;
    double lo = INFINITY, hi = -INFINITY;
    bool allFinite = true;
    for (double p : g.points(x, 6)) {
        double d = f(p);
        Contain(
            t, [&] { return "f(" + ToString(p) + ") over " + x.toString(); }, d, r);
        allFinite = allFinite && std::isfinite(d);
        lo = std::fmin(lo, d);
        hi = std::fmax(hi, d);
    }
    if (!checkTight || !allFinite) return;
    if (r.isUnbounded()) {
        // Every sampled value is finite, the ends included: none of these functions needs
        // Unbounded there. (Sound, but a lost bound: acos with its ends swapped gave lo > hi.)
        t.loose++;
        if (t.loose <= 4) t.first << "loose: unbounded over " << x.toString() << ", every sample finite\n";
        return;
    }
    double slack = 1e-13 * std::fmax(std::fabs(lo), std::fabs(hi)) + 1e-300;
    if (r.lo() < lo - slack || r.hi() > hi + slack) {
        t.loose++;
        if (t.loose <= 4)
            t.first << "loose: " << r.toString() << " vs samples [" << ToString(lo) << ", " << ToString(hi) << "] over "
                    << x.toString() << "\n";
    }
}

template <class F>
void CheckBinary(Tally& t, const Interval& x, const Interval& y, F f, Gen& g) {
    Interval r = f(x, y);
    if (!r.isUnbounded()) t.bounded++;
    for (double p : g.points(x, 3))
        for (double q : g.points(y, 3))
            Contain(
                t,
                [&] {
                    return "f(" + ToString(p) + ", " + ToString(q) + ") over " + x.toString() + ", " + y.toString();
                },
                f(p, q), r);
}

void Report(const char* name, const Tally& t) {
    if (std::getenv("AFFRAY_VERBOSE"))
        std::printf("%-12s %8d points %6d bounded  loose %d  failures %d\n", name, t.samples, t.bounded, t.loose,
                    t.failures);
    INFO(name << ": " << t.samples << " points\n" << t.first.str());
    CHECK(t.failures == 0);
    CHECK(t.loose == 0);
    CHECK(t.samples > 0);
}

}  // namespace

TEST_CASE("interval arithmetic contains the scalar result", "[vm][interval]") {
    const int n = Samples(20000) / 4;
    Gen g(1);
    Tally add, sub, mul, div, neg, mixed;
    for (int i = 0; i < n; ++i) {
        Interval x = g.interval(-6, 6), y = g.interval(-6, 6);
        CheckBinary(
            add, x, y, [](auto a, auto b) { return a + b; }, g);
        CheckBinary(
            sub, x, y, [](auto a, auto b) { return a - b; }, g);
        CheckBinary(
            mul, x, y, [](auto a, auto b) { return a * b; }, g);
        CheckBinary(
            div, x, y, [](auto a, auto b) { return Div(a, b); }, g);
        CheckUnary(
            neg, x, [](auto a) { return -a; }, true, g);
        CheckUnary(
            mixed, x, [](auto a) { return (0.1 - a) * 3.0 / 7.0 + 1e-3; }, false, g);
    }
    Report("add", add);
    Report("sub", sub);
    Report("mul", mul);
    Report("div", div);
    Report("neg", neg);
    Report("mixed", mixed);
}

TEST_CASE("interval functions contain the scalar result and are tight", "[vm][interval]") {
    const int n = Samples(20000);
    Gen g(2);
    Tally sq, rt, ex, lg, sn, cs, ab, sg;
    for (int i = 0; i < n; ++i) {
        Interval x = g.interval(-6, 6);
        Interval small = g.interval(-6, 1);
        CheckUnary(
            sq, x, [](auto a) { return sqr(a); }, true, g);
        CheckUnary(
            rt, x, [](auto a) { return Sqrt(a); }, true, g);
        CheckUnary(
            ex, small, [](auto a) { return exp(a); }, true, g);
        CheckUnary(
            ex, small + 700.0 + 10.0 * (i % 2) * g.uniform(0, 1), [](auto a) { return exp(a); }, true, g);
        CheckUnary(
            lg, x, [](auto a) { return log(a); }, true, g);
        // Points include the extrema of sin and cos only on narrower ranges.
        CheckUnary(
            sn, x, [](auto a) { return sin(a); }, x.width() < 100, g);
        CheckUnary(
            cs, x, [](auto a) { return cos(a); }, x.width() < 100, g);
        CheckUnary(
            ab, x, [](auto a) { return abs(a); }, true, g);
        CheckUnary(
            sg, x, [](auto a) { return sign(a); }, true, g);
    }
    Report("sqr", sq);
    Report("sqrt", rt);
    Report("exp", ex);
    Report("log", lg);
    Report("sin", sn);
    Report("cos", cs);
    Report("abs", ab);
    Report("sign", sg);
}

TEST_CASE("interval functions contain the exact value, not only the library's rounded double", "[vm][interval]") {
    // The library's double lies within an ulp of the exact value, on either side of it: an end
    // that trusted it (LibmDown or LibmUp left out) would exclude the exact value at about half of
    // the points, though it contains the double. The reference is the long double function (a
    // 64-bit significand: within a small fraction of a double's ulp).
    struct Case {
        const char* name;
        Interval (*f)(const Interval&);
        long double (*exact)(long double);
        double lo, hi;
    };
    const Case cases[] = {
        {"exp", [](const Interval& x) { return exp(x); }, [](long double x) { return std::exp(x); }, -30, 30},
        {"log", [](const Interval& x) { return log(x); }, [](long double x) { return std::log(x); }, 1e-3, 1e3},
        {"sin", [](const Interval& x) { return sin(x); }, [](long double x) { return std::sin(x); }, -10, 10},
        {"cos", [](const Interval& x) { return cos(x); }, [](long double x) { return std::cos(x); }, -10, 10},
        {"tan", [](const Interval& x) { return tan(x); }, [](long double x) { return std::tan(x); }, -1.5, 1.5},
        {"asin", [](const Interval& x) { return asin(x); }, [](long double x) { return std::asin(x); }, -1, 1},
        {"acos", [](const Interval& x) { return acos(x); }, [](long double x) { return std::acos(x); }, -1, 1},
        {"atan", [](const Interval& x) { return atan(x); }, [](long double x) { return std::atan(x); }, -10, 10},
    };
    Gen g(31);
    const int n = Samples(2000);
    for (const Case& c : cases) {
        int misses = 0;
        for (int i = 0; i < n; ++i) {
            const double x = g.uniform(c.lo, c.hi);
            const Interval r = c.f(Interval(x));
            const long double exact = c.exact(x);
            if (r.lo() <= exact && exact <= r.hi()) continue;
            if (++misses == 1)
                UNSCOPED_INFO(c.name << "(" << x << ") = " << static_cast<double>(exact) << " not in " << r.toString());
        }
        INFO(c.name);
        CHECK(misses == 0);
    }
}

TEST_CASE("interval steps, inverse trigonometry, min/max and logic contain the scalar result", "[vm][interval]") {
    using std::floor, std::ceil, std::round, std::asin, std::acos, std::atan, std::atan2;
    const int n = Samples(20000) / 2;
    Gen g(6);
    Tally fl, ce, ro, as, ac, at, at2, mn, mx, cmp, logic;
    for (int i = 0; i < n; ++i) {
        Interval x = g.interval(-6, 6), y = g.interval(-6, 6);
        // Magnitudes up to about 1.3: inside, across and outside [-1, 1].
        Interval unit = g.interval(-4, 0.1);
        // Near integers and half-integers.
        Interval near = Interval(0.5 * std::round(g.uniform(-10, 10))) + g.interval(-8, 0);
        for (const Interval& z : {x, near}) {
            CheckUnary(
                fl, z, [](auto a) { return floor(a); }, true, g);
            CheckUnary(
                ce, z, [](auto a) { return ceil(a); }, true, g);
            CheckUnary(
                ro, z, [](auto a) { return round(a); }, true, g);
        }
        CheckUnary(
            as, unit, [](auto a) { return asin(a); }, true, g);
        CheckUnary(
            ac, unit, [](auto a) { return acos(a); }, true, g);
        CheckUnary(
            at, x, [](auto a) { return atan(a); }, true, g);
        CheckBinary(
            at2, y, x, [](auto a, auto b) { return atan2(a, b); }, g);
        CheckBinary(
            at2, unit, x, [](auto a, auto b) { return atan2(a, b); }, g);
        // Signed zeros on the branch cut: atan2(-0, x < 0) = -pi, atan2(+-0, -0) = +-pi.
        for (const Interval& yy : {y, unit})
            if (yy.contains(0.0))
                for (double p : g.points(x, 2))
                    for (double zero : {0.0, -0.0})
                        for (double q : {p, p == 0 ? -0.0 : p})
                            Contain(
                                at2, [&] { return "atan2(" + ToString(zero) + ", " + ToString(q) + ")"; },
                                std::atan2(zero, q), atan2(yy, x));
        CheckBinary(
            mn, x, y, [](auto a, auto b) { return Min(a, b); }, g);
        CheckBinary(
            mx, x, y, [](auto a, auto b) { return Max(a, b); }, g);
        for (const Interval& yy : {y, x}) {
            CheckBinary(
                cmp, x, yy, [](auto a, auto b) { return Less(a, b); }, g);
            CheckBinary(
                cmp, x, yy, [](auto a, auto b) { return LessEq(a, b); }, g);
            CheckBinary(
                cmp, x, yy, [](auto a, auto b) { return Equal(a, b); }, g);
            CheckBinary(
                cmp, x, yy, [](auto a, auto b) { return NotEqual(a, b); }, g);
        }
        CheckBinary(
            logic, x, y, [](auto a, auto b) { return And(a, b); }, g);
        CheckBinary(
            logic, x, y, [](auto a, auto b) { return Or(a, b); }, g);
        CheckUnary(
            logic, x, [](auto a) { return Not(a); }, false, g);
    }
    Report("floor", fl);
    Report("ceil", ce);
    Report("round", ro);
    Report("asin", as);
    Report("acos", ac);
    Report("atan", at);
    Report("atan2", at2);
    Report("Min", mn);
    Report("Max", mx);
    Report("comparisons", cmp);
    Report("logic", logic);
    CHECK(as.bounded > n / 10);
    CHECK(as.bounded < n);  // some ranges leave [-1, 1]
    CHECK(atan2(Interval(1, 2), Interval(1, 2)).lo() > 0.4);
    CHECK(Min(Interval(1, 4), Interval(2, 3)).hi() == 3);
    CHECK(Max(Interval(1, 4), Interval(2, 3)).lo() == 2);
}

TEST_CASE("interval sin and cos over periods and far from 0", "[vm][interval]") {
    const double pi = 3.141592653589793;
    Gen g(3);
    Tally sn, cs;
    for (double width : {pi / 2, pi, 2 * pi - 1e-9, 2 * pi, 1e-9})
        for (double center : {0.0, 4.0, 1e3, 1e6, 1e9}) {
            for (int i = 0; i < Samples(20000) / 25; ++i) {
                double c = g.uniform(-center, center), w = width * g.uniform(0.99, 1.01);
                Interval x(c - w / 2, c + w / 2);
                CheckUnary(
                    sn, x, [](auto a) { return sin(a); }, center < 1e8, g);
                CheckUnary(
                    cs, x, [](auto a) { return cos(a); }, center < 1e8, g);
            }
        }
    Report("sin periods", sn);
    Report("cos periods", cs);
    CHECK(sin(Interval(0, 2 * pi)).lo() == -1);
    CHECK(sin(Interval(0, 2 * pi)).hi() == 1);
    CHECK(cos(Interval(-0.5, 0.5)).hi() == 1);
    CHECK(sin(Interval(1e10, 1e10 + 1)).lo() == -1);
}

TEST_CASE("interval pow contains the scalar result", "[vm][interval]") {
    const int n = Samples(20000) / 4;
    Gen g(4);
    Tally integer, real, general;
    for (int i = 0; i < n; ++i) {
        Interval x = g.interval(-3, 1);
        double k = g.integer(-6, 6);
        CheckUnary(
            integer, x, [k](auto a) { return Pow(a, decltype(a)(k)); }, true, g);
        double p = g.uniform(-3, 3);
        CheckUnary(
            real, x, [p](auto a) { return Pow(a, decltype(a)(p)); }, true, g);
        CheckBinary(
            general, x, g.interval(-1, 0.5), [](auto a, auto b) { return Pow(a, b); }, g);
    }
    Report("pow integer", integer);
    Report("pow real", real);
    Report("pow general", general);
    CHECK(pow(Interval(-2, 3), Interval(2)).lo() == 0);
    CHECK(pow(Interval(-2, -1), Interval(3)).hi() < -0.99);
    CHECK(pow(Interval(-2, 3), Interval(-1)).isUnbounded());
    CHECK(pow(Interval(-2, 3), Interval(0.5)).lo() == 0);  // a negative base to 0.5 is 0
    CHECK(pow(Interval(-2, 3), Interval(0.5)).hi() < 1.7321);
    CHECK(pow(Interval(-2, -1), Interval(-0.5)).isUnbounded());  // pow(0, -0.5)
    CHECK(pow(Interval(0, 3), Interval(-0.5)).isUnbounded());
    CHECK(pow(Interval(0, 3), Interval(0)).lo() == 1);
    CHECK(pow(Interval(0, 0), Interval(0.5)).hi() >= 0);
    CHECK(pow(Interval(-2, 3), Interval(1.5, 2)).isUnbounded());
}

TEST_CASE("interval Unbounded comes from every NaN/inf source and propagates", "[vm][interval]") {
    const double inf = std::numeric_limits<double>::infinity();
    Interval x(0.5, 2);
    // clang-format off
    std::vector<Interval> sources = {  // every way to NaN or infinity
        Interval(std::nan("")), Interval(inf), Interval(0, inf), Interval(3, 1),
        log(Interval(0, 1)), log(Interval(-1, 1)), x / Interval(0, 1),
        x / Interval(-1, 1), x / 0.0, exp(Interval(0, 710)), Interval(1e300) * 1e300,
        pow(Interval(-1, 1), Interval(-2)), pow(Interval(-1, 1), Interval(-0.5)),
        Interval::Unbounded(), DerivU(x), DerivV(x)};
    // clang-format on
    for (const Interval& s : sources) CHECK(s.isUnbounded());
    Interval U = Interval::Unbounded();
    CHECK(U.contains(inf));
    CHECK(U.contains(std::nan("")));
    CHECK_FALSE(x.contains(inf));
    CHECK_FALSE(x.contains(std::nan("")));
    std::vector<Interval> results = {U + x,      x + U,     U - x,   x - U,     U * x,     x * U,
                                     U / x,      x / U,     -U,      U + 1.0,   1.0 - U,   U * 0.0,
                                     2.0 / U,    sqr(U),    sqrt(U), exp(U),    log(U),    sin(U),
                                     cos(U),     abs(U),    sign(U), pow(U, x), pow(x, U), pow(U, Interval(0.0)),
                                     Hull(U, x), Hull(x, U)};
    for (size_t i = 0; i < results.size(); ++i) {
        INFO("result " << i);
        CHECK(results[i].isUnbounded());
    }
    CHECK(U.toString() == "unbounded");
}

TEST_CASE("directed roundings bound the exact result", "[vm][interval]") {
    // Checked exactly: the sign of the residual of an error-free transform (fma, TwoSum).
    Gen g(5);
    int failures = 0, exact = 0;
    for (int i = 0; i < Samples(20000) * 5; ++i) {
        double a = g.uniform(-1, 1) * g.magnitude(-8, 8), b = g.uniform(-1, 1) * g.magnitude(-8, 8);
        if (i % 4 == 0) b = std::ldexp(std::round(std::ldexp(b, 8)), -8);  // exact products too
        if (b == 0) b = 0.5;
        if (!(MulDown(a, b) <= a * b && std::fma(a, b, -MulDown(a, b)) >= 0)) failures++;
        if (!(std::fma(a, b, -MulUp(a, b)) <= 0)) failures++;
        // a + b = s + e exactly; AddDown must be s if e >= 0, else below s (AddUp alike).
        double s = a + b, e = TwoSumError(a, b, s), sd = AddDown(a, b), su = AddUp(a, b);
        if (!(sd < s || (sd == s && e >= 0))) failures++;
        if (!(su > s || (su == s && e <= 0))) failures++;
        if (!(std::fma(-DivDown(a, b), b, a) * b >= 0)) failures++;  // a/b >= DivDown
        if (!(std::fma(-DivUp(a, b), b, a) * b <= 0)) failures++;
        double x = std::fabs(a);
        if (!(std::fma(SqrtDown(x), SqrtDown(x), -x) <= 0)) failures++;
        if (!(std::fma(SqrtUp(x), SqrtUp(x), -x) >= 0)) failures++;
        if (!(NextDown(a) < a && NextUp(a) > a)) failures++;
        exact += MulUp(a, b) == MulDown(a, b);
    }
    CHECK(failures == 0);
    CHECK(exact > 0);  // exact products are not widened
    CHECK(LibmDown(1.0) < 1.0);
    CHECK(LibmUp(1.0) - 1.0 >= 3 * 0x1p-52);
    UpperSum sum;
    for (double t : {0.1, 0.2, 0.3}) sum.add(t);
    CHECK(sum.value() >= 0.6);
    UpperSum exactSum;
    for (double t : {0.5, 0.25, 1.0}) exactSum.add(t);
    CHECK(exactSum.value() == 1.75);
    // Against the exact sum (a long double holds the sum of three doubles in [1, 8) exactly):
    // value() is never below it, where the sum rounded to nearest often is.
    std::mt19937_64 rng(5);
    int nearestBelow = 0;
    for (int i = 0; i < 1000; ++i) {
        UpperSum upper;
        long double exactTotal = 0;
        double nearest = 0;
        for (int k = 0; k < 3; ++k) {
            const double t = std::uniform_real_distribution<>(1.0, 8.0)(rng);
            upper.add(t);
            exactTotal += t;
            nearest += t;
        }
        nearestBelow += nearest < exactTotal;
        INFO(i);
        CHECK(upper.value() >= exactTotal);
    }
    CHECK(nearestBelow > 100);
}

TEST_CASE("interval basics", "[vm][interval]") {
    CHECK(Interval().lo() == 0);
    CHECK(Interval().hi() == 0);
    Interval x(1, 3);
    CHECK(x.mid() == 2);
    CHECK(x.radius() == 1);
    CHECK(x.toString() == "[1, 3]");
    CHECK(Hull(Interval(1, 2), Interval(5, 6)).hi() == 6);
    // Exact operations stay points; inexact ones round outward by about an ulp.
    CHECK((Interval(1) + Interval(2)).isPoint());
    CHECK((Interval(3) * Interval(7)).isPoint());
    CHECK((Interval(1) / Interval(4)).isPoint());
    CHECK(sqrt(Interval(4)).isPoint());
    Interval s = Interval(0.1) + Interval(0.2);
    CHECK_FALSE(s.isPoint());
    CHECK(s.contains(0.1 + 0.2));
    CHECK(s.width() < 1e-16);
    Interval t = Interval(1) / Interval(3);
    CHECK(t.contains(1.0 / 3.0));
    CHECK(t.width() < 1e-16);
    CHECK(IsExactlyZero(Interval(0.0)));
    CHECK_FALSE(IsExactlyZero(Interval(0.0, 1e-300)));
    CHECK(sign(Interval(-1, 0)).lo() == -1);
    CHECK(sign(Interval(-1, 0)).hi() == 0);
    CHECK(RangeOf(x).lo() == 1);
    CHECK(abs(Interval(-3, 2)).lo() == 0);
    CHECK(abs(Interval(-3, 2)).hi() == 3);
    CHECK(sqr(Interval(-3, 2)).lo() == 0);
}
