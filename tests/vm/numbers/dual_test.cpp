// tests/vm/numbers/dual_test.cpp: dual numbers. Dual<double> derivatives agree with central finite
// differences for every function at smooth points; Dual<Affine>, Dual<ReducedAffine> and
// Dual<Interval> contain the Dual<double> value and derivatives at every point of the region (the
// same template code runs on all, so this is the containment invariant applied to derivative expressions, branches and
// steps included: ShaderD); and the
// Number API pieces (DerivU/DerivV, traits, IsExactlyZero) behave as documented.
#include <catch2/catch.hpp>
#include <cstdio>
#include <cstdlib>
#include <random>

#include "tests/test_random.h"
#include "vm/numbers/number.h"

using namespace affray::vm;
using affray::test::Samples;

namespace {

// Shader-like functions of (u, v), each written once for every number type.
template <class T>
T ShaderA(const T& u, const T& v) {
    using std::cos, std::exp, std::sin;
    return sin(3.0 * u) * exp(-sqr(v)) + u * v / (2.0 + cos(v));
}
template <class T>
T ShaderB(const T& u, const T& v) {
    using std::log, std::pow, std::sqrt;
    return sqrt(1.0 + sqr(u)) + pow(1.5 + u * u, v) + log(2.0 + u * v) - pow(v + 3.0, T(2.5));
}
template <class T>
T ShaderC(const T& u, const T& v) {
    using std::abs, std::cos, std::pow;
    return abs(u - 0.3) * sign(v + 2.0) + pow(u - 2.0, T(3.0)) + 1.0 / (3.0 + sqr(u) * v) + cos(u * 10.0 + v);
}

// Branches, steps and inverse trigonometry: not smooth everywhere, so only in the containment
// test (Select with an undecided condition joins the values and derivatives of both arms).
template <class T>
T ShaderD(const T& u, const T& v) {
    using std::asin, std::atan, std::atan2, std::floor;
    T a = atan2(v + 0.3, u + 2.0) + asin(0.5 * u) + atan(3.0 * v);
    T b = Min(u * v, 0.25 * u) + Max(sqr(v), u);
    T c = Select(Less(u, v), sqr(u), u * v);
    return a + b + c + floor(4.0 * u + 0.5 * v) * 0.1 + Not(LessEq(v, u * 0.5)) * 0.5;
}

template <class T>
T Shader(int which, const T& u, const T& v) {
    switch (which) {
        case 0: return ShaderA(u, v);
        case 1: return ShaderB(u, v);
        case 2: return ShaderC(u, v);
        default: return ShaderD(u, v);
    }
}

// |a - b| small relative to the scale of the derivative and of the function.
bool Near(double a, double b, double scale) { return std::fabs(a - b) <= 1e-6 * (scale + std::fabs(b)); }

}  // namespace

TEST_CASE("dual derivatives match central differences", "[vm][dual]") {
    std::mt19937_64 rng(1);
    std::uniform_real_distribution<> unit(-1, 1);
    int failures = 0;
    for (int i = 0; i < Samples(20000) / 10; ++i) {
        double u = unit(rng), v = unit(rng);
        if (std::fabs(u - 0.3) < 1e-3) continue;  // abs's kink
        for (int which = 0; which < 3; ++which) {
            Dual<double> r = Shader(which, Dual<double>(u, 1, 0), Dual<double>(v, 0, 1));
            const double h = 1e-5;
            double fu = (Shader(which, u + h, v) - Shader(which, u - h, v)) / (2 * h);
            double fv = (Shader(which, u, v + h) - Shader(which, u, v - h)) / (2 * h);
            double scale = 1 + std::fabs(r.v);
            if (r.v != Shader(which, u, v) || !Near(r.du, fu, scale) || !Near(r.dv, fv, scale)) {
                if (failures++ < 4)
                    WARN("shader " << which << " at " << u << ", " << v << ": " << ToString(r) << " vs " << fu << ", "
                                   << fv);
            }
        }
    }
    CHECK(failures == 0);
}

TEST_CASE("every dual function matches central differences", "[vm][dual]") {
    using std::abs, std::cos, std::exp, std::log, std::pow, std::sin, std::sqrt;
    struct Fn {
        const char* name;
        Dual<double> (*dual)(const Dual<double>&);
        double (*scalar)(double);
        double lo, hi;
    };
    const Fn fns[] = {
        {"sqr", [](const Dual<double>& x) { return sqr(x); }, [](double x) { return sqr(x); }, -3, 3},
        {"sqrt", [](const Dual<double>& x) { return sqrt(x); }, [](double x) { return std::sqrt(x); }, 0.1, 9},
        {"exp", [](const Dual<double>& x) { return exp(x); }, [](double x) { return std::exp(x); }, -5, 5},
        {"log", [](const Dual<double>& x) { return log(x); }, [](double x) { return std::log(x); }, 0.1, 9},
        {"sin", [](const Dual<double>& x) { return sin(x); }, [](double x) { return std::sin(x); }, -9, 9},
        {"cos", [](const Dual<double>& x) { return cos(x); }, [](double x) { return std::cos(x); }, -9, 9},
        {"abs", [](const Dual<double>& x) { return abs(x); }, [](double x) { return std::fabs(x); }, -3, 3},
        {"sign", [](const Dual<double>& x) { return sign(x); }, [](double x) { return sign(x); }, -3, 3},
        {"neg", [](const Dual<double>& x) { return -x; }, [](double x) { return -x; }, -3, 3},
        {"1/x", [](const Dual<double>& x) { return 1.0 / x; }, [](double x) { return 1.0 / x; }, 0.2, 3},
        {"x/3", [](const Dual<double>& x) { return x / 3.0; }, [](double x) { return x / 3.0; }, -3, 3},
        {"x/(x+2)", [](const Dual<double>& x) { return x / (x + 2.0); }, [](double x) { return x / (x + 2.0); }, -1, 3},
        {"x*x*x", [](const Dual<double>& x) { return x * x * x; }, [](double x) { return x * x * x; }, -3, 3},
        {"1-x", [](const Dual<double>& x) { return 1.0 - x; }, [](double x) { return 1.0 - x; }, -3, 3},
        {"pow(x,2.5)", [](const Dual<double>& x) { return pow(x, 2.5); }, [](double x) { return std::pow(x, 2.5); },
         0.1, 3},
        {"pow(x,-3)", [](const Dual<double>& x) { return pow(x, -3.0); }, [](double x) { return std::pow(x, -3.0); },
         -3, -0.2},
        {"pow(2,x)", [](const Dual<double>& x) { return pow(2.0, x); }, [](double x) { return std::pow(2.0, x); }, -3,
         3},
        {"pow(x,x)", [](const Dual<double>& x) { return pow(x, x); }, [](double x) { return std::pow(x, x); }, 0.1, 3},
        {"asin", [](const Dual<double>& x) { return asin(x); }, [](double x) { return std::asin(x); }, -0.95, 0.95},
        {"acos", [](const Dual<double>& x) { return acos(x); }, [](double x) { return std::acos(x); }, -0.95, 0.95},
        {"atan", [](const Dual<double>& x) { return atan(x); }, [](double x) { return std::atan(x); }, -5, 5},
        // Steps between their jumps: derivative 0.
        {"floor", [](const Dual<double>& x) { return floor(x); }, [](double x) { return std::floor(x); }, 1.01, 1.99},
        {"ceil", [](const Dual<double>& x) { return ceil(x); }, [](double x) { return std::ceil(x); }, -1.99, -1.01},
        {"round", [](const Dual<double>& x) { return round(x); }, [](double x) { return std::round(x); }, 2.51, 3.49},
        {"Not", [](const Dual<double>& x) { return Not(x); }, [](double x) { return Not(x); }, 0.1, 3},
    };
    std::mt19937_64 rng(2);
    for (const Fn& f : fns) {
        std::uniform_real_distribution<> pick(f.lo, f.hi);
        int failures = 0;
        for (int i = 0; i < 2000; ++i) {
            double x = pick(rng);
            if (std::fabs(x) < 1e-3) continue;  // the kinks of abs and sign
            Dual<double> r = f.dual(Dual<double>(x, 1, 0));
            double h = 1e-6 * std::fmax(1, std::fabs(x));
            double fd = (f.scalar(x + h) - f.scalar(x - h)) / (2 * h);
            if (r.v != f.scalar(x) || !Near(r.du, fd, 1 + std::fabs(r.v)) || r.dv != 0) failures++;
        }
        INFO(f.name);
        CHECK(failures == 0);
    }
}

TEST_CASE("dual atan2, Min and Max match central differences in both operands", "[vm][dual]") {
    using std::atan2;
    struct Fn2 {
        const char* name;
        Dual<double> (*dual)(const Dual<double>&, const Dual<double>&);
        double (*scalar)(double, double);
    };
    const Fn2 fns[] = {
        {"atan2", [](const Dual<double>& y, const Dual<double>& x) { return atan2(y, x); },
         [](double y, double x) { return std::atan2(y, x); }},
        {"Min", [](const Dual<double>& y, const Dual<double>& x) { return Min(y, x); },
         [](double y, double x) { return std::fmin(y, x); }},
        {"Max", [](const Dual<double>& y, const Dual<double>& x) { return Max(y, x); },
         [](double y, double x) { return std::fmax(y, x); }},
        {"Select", [](const Dual<double>& y, const Dual<double>& x) { return Select(Less(y, x), y * x, sqr(x)); },
         [](double y, double x) { return y < x ? y * x : x * x; }},
    };
    std::mt19937_64 rng(4);
    std::uniform_real_distribution<> pick(-3, 3);
    for (const Fn2& f : fns) {
        int failures = 0;
        for (int i = 0; i < 2000; ++i) {
            double y = pick(rng), x = pick(rng);
            // Away from the kinks (y = x) and the branch cut of atan2 (y = 0, x < 0).
            if (std::fabs(y - x) < 1e-3 || (std::fabs(y) < 1e-3 && x < 0)) continue;
            // y's derivative goes into du, x's into dv.
            Dual<double> r = f.dual(Dual<double>(y, 1, 0), Dual<double>(x, 0, 1));
            double h = 1e-6;
            double fy = (f.scalar(y + h, x) - f.scalar(y - h, x)) / (2 * h);
            double fx = (f.scalar(y, x + h) - f.scalar(y, x - h)) / (2 * h);
            double scale = 1 + std::fabs(r.v);
            if (r.v != f.scalar(y, x) || !Near(r.du, fy, scale) || !Near(r.dv, fx, scale)) {
                if (failures++ < 4)
                    WARN(f.name << " at " << y << ", " << x << ": " << ToString(r) << " vs " << fy << ", " << fx);
            }
        }
        INFO(f.name);
        CHECK(failures == 0);
    }
}

TEST_CASE("dual edge cases", "[vm][dual]") {
    using std::pow, std::sqrt;
    // A constant exponent never takes log of the base: negative bases keep finite derivatives.
    Dual<double> r = pow(Dual<double>(-2, 1, 0), Dual<double>(3.0));
    CHECK(r.v == -8);
    CHECK(r.du == 12);
    CHECK(r.dv == 0);
    // sqrt at 0: the derivative is what T gives for 0.5/0.
    CHECK(std::isinf(sqrt(Dual<double>(0, 1, 0)).du));
    Affine::BeginEvaluation();
    CHECK(sqrt(Dual<Affine>(Affine(0.0), Affine(1.0), Affine(0.0))).du.isUnbounded());
    CHECK(IsUnbounded(sqrt(Dual<Affine>(Affine(0.0), Affine(1.0), Affine(0.0)))));
    CHECK(sqrt(Dual<Interval>(Interval(0.0), Interval(1.0), Interval(0.0))).du.isUnbounded());
    // An exactly zero derivative stays 0 through an infinite chain-rule factor (not inf*0 = NaN).
    Dual<double> flat = sqrt(Max(Dual<double>(0.0), Dual<double>(-0.5, 1, 0)));
    CHECK(flat.v == 0);
    CHECK(flat.du == 0);
    CHECK(flat.dv == 0);
    CHECK(pow(Dual<double>(0.0), 0.5).du == 0);
    CHECK(asin(Dual<double>(1.0)).dv == 0);
    CHECK(std::isinf(asin(Dual<double>(1.0, 1.0, 0.0)).du));
    CHECK(IsExactlyZero(sqrt(Dual<Affine>(0.0)).du));
    // DerivU/DerivV take a derivative as a value with zero derivatives of its own.
    Dual<double> x(2.0, 3.0, 5.0);
    Dual<double> du = DerivU(x), dv = DerivV(x);
    CHECK(du.v == 3.0);
    CHECK(du.du == 0.0);
    CHECK(dv.v == 5.0);
    CHECK(std::isnan(DerivU(1.0)));
    CHECK(DerivU(Affine(1.0)).isUnbounded());
    CHECK(DerivV(Interval(1.0)).isUnbounded());
    CHECK(RangeOf(x).lo() == 2.0);
    CHECK(IsExactlyZero(Dual<double>(0.0)));
    CHECK_FALSE(IsExactlyZero(Dual<double>(0.0, 1.0, 0.0)));
    CHECK(ToString(Dual<double>(1.5, 0, -1)) == "(1.5; 0; -1)");
    CHECK(std::string(NumberTraits<Dual<Affine>>::kName) == "dual-affine");
    CHECK(std::string(NumberTraits<double>::kName) == "scalar");
    CHECK(NumberTraits<Dual<double>>::kHasDerivatives);
    CHECK_FALSE(NumberTraits<Affine>::kHasDerivatives);
}

namespace {

template <class T>
bool Contains(const T& bound, double d, double eu, double ev) {
    if (!std::isfinite(d)) return IsUnbounded(bound);
    if constexpr (std::is_same_v<T, Affine> || std::is_same_v<T, ReducedAffine>)
        return bound.isUnbounded() || (bound.evaluateAt(eu, ev).contains(d) && bound.range().contains(d));
    else
        return bound.contains(d);
}

}  // namespace

TEST_CASE("dual affine and dual interval contain dual double", "[vm][dual]") {
    std::mt19937_64 rng(3);
    std::uniform_real_distribution<> unit(-1, 1);
    int failures = 0, bounded = 0, boundedReduced = 0, checked = 0;
    for (int region = 0; region < Samples(20000) / 10; ++region) {
        // Dyadic centers, radii and points keep u and v exact.
        double uc = std::ldexp(std::round(std::ldexp(unit(rng), 20)), -20);
        double vc = std::ldexp(std::round(std::ldexp(unit(rng), 20)), -20);
        double ur = std::ldexp(1.0, -static_cast<int>(std::fabs(unit(rng)) * 20) - 1);
        double vr = std::ldexp(1.0, -static_cast<int>(std::fabs(unit(rng)) * 20) - 1);
        int which = region % 4;
        Affine::BeginEvaluation();
        Dual<Affine> ua(Affine::FromSymbol(uc, ur, Affine::kSymbolU), 1.0, 0.0);
        Dual<Affine> va(Affine::FromSymbol(vc, vr, Affine::kSymbolV), 0.0, 1.0);
        Dual<Affine> ra = Shader(which, ua, va);
        Dual<Interval> ri = Shader(which, Dual<Interval>(Interval(uc - ur, uc + ur), 1.0, 0.0),
                                   Dual<Interval>(Interval(vc - vr, vc + vr), 0.0, 1.0));
        Dual<ReducedAffine> rr =
            Shader(which, Dual<ReducedAffine>(ReducedAffine::FromSymbol(uc, ur, ReducedAffine::kSymbolU), 1.0, 0.0),
                   Dual<ReducedAffine>(ReducedAffine::FromSymbol(vc, vr, ReducedAffine::kSymbolV), 0.0, 1.0));
        bounded += !IsUnbounded(ra);
        boundedReduced += !IsUnbounded(rr);
        for (int p = 0; p < 10; ++p) {
            double eu = std::ldexp(std::round(std::ldexp(unit(rng), 10)), -10);
            double ev = std::ldexp(std::round(std::ldexp(unit(rng), 10)), -10);
            if (p == 0) eu = ev = -1;
            Dual<double> rd = Shader(which, Dual<double>(uc + ur * eu, 1, 0), Dual<double>(vc + vr * ev, 0, 1));
            checked++;
            bool ok = Contains(ra.v, rd.v, eu, ev) && Contains(ra.du, rd.du, eu, ev) &&
                      Contains(ra.dv, rd.dv, eu, ev) && Contains(ri.v, rd.v, eu, ev) &&
                      Contains(ri.du, rd.du, eu, ev) && Contains(ri.dv, rd.dv, eu, ev) &&
                      Contains(rr.v, rd.v, eu, ev) && Contains(rr.du, rd.du, eu, ev) && Contains(rr.dv, rd.dv, eu, ev);
            if (!ok && failures++ < 4)
                WARN("shader " << which << " eps " << eu << ", " << ev << "\n  double " << ToString(rd) << "\n  affine "
                               << ToString(ra) << "\n  interval " << ToString(ri) << "\n  reduced " << ToString(rr));
        }
    }
    if (std::getenv("AFFRAY_VERBOSE"))
        std::printf("dual containment: %d points, %d of %d regions bounded\n", checked, bounded, Samples(20000) / 10);
    CHECK(failures == 0);
    CHECK(bounded > Samples(20000) / 40);
    CHECK(boundedReduced > Samples(20000) / 40);
}
