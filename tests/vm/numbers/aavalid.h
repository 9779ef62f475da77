// tests/vm/numbers/aavalid.h: the operands of Stolfi's aavalid method, shared by the containment tests of
// every affine type (tests/vm/numbers/affine_test.cpp, tests/vm/numbers/reduced_affine_test.cpp): a random region
// u = uc + ur*eps_u, v = vc + vr*eps_v with a point (eps_u, eps_v) in it, all exact doubles, and
// random recipes that build operands from u and v with the same code on any number type, random
// straight-line programs over every built-in, and the sweeps every affine type's test runs alike.
#pragma once

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <type_traits>
#include <vector>

#include "tests/test_random.h"
#include "vm/numbers/number.h"

namespace affray::test::aavalid {

using vm::And;
using vm::Div;
using vm::Equal;
using vm::Less;
using vm::LessEq;
using vm::Max;
using vm::Min;
using vm::Not;
using vm::NotEqual;
using vm::Or;
using vm::Pow;
using vm::Select;
using vm::sign;
using vm::sqr;
using vm::Sqrt;

inline bool ExactSum(double c, double r, double e, double* out) {
    double p = r * e, s = c + p;
    *out = s;
    return std::fma(r, e, -p) == 0 && vm::TwoSumError(c, p, s) == 0;
}

/// One region and one point in it, exactly representable.
struct Region {
    double uc, ur, vc, vr, eu, ev, u, v;
};

struct RegionConfig {
    int expLo = -20, expHi = 20;  // magnitude (log2) of u and v
    double touchZero = 0.15;      // chance that u's range touches 0
    double uWidth = 0;            // if > 0: ur is about uWidth/2 (sin/cos periods)
    double uCenter = 0;           // if > 0: |uc| up to this
};

inline Region RandomRegion(Rng& rng, const RegionConfig& cfg) {
    for (;;) {
        Region r;
        int eu = rng.integer(cfg.expLo, cfg.expHi), ev = rng.integer(cfg.expLo, cfg.expHi);
        r.ur = std::fabs(rng.dyadic(eu - rng.integer(0, 8), 16));
        r.uc = rng.dyadic(eu, 20);
        r.vr = std::fabs(rng.dyadic(ev - rng.integer(0, 8), 16));
        r.vc = rng.dyadic(ev, 20);
        if (cfg.uWidth > 0) {
            // A grid fine enough for the width, coarse enough to keep uc + ur exact.
            double q = std::ldexp(1.0, std::ilogb(std::fmax(cfg.uCenter, 1.0)) - 44);
            double w = cfg.uWidth * rng.uniform(0.97, 1.03);
            r.ur = std::round(w / 2 / q) * q;
            r.uc = std::round(rng.uniform(-cfg.uCenter, cfg.uCenter) / q) * q;
        }
        if (rng.chance(cfg.touchZero)) r.uc = rng.chance(0.5) ? r.ur : -r.ur;
        double t;
        if (r.ur == 0 || !ExactSum(r.uc, r.ur, 1, &t) || !ExactSum(r.uc, r.ur, -1, &t) ||
            !ExactSum(r.vc, r.vr, 1, &t) || !ExactSum(r.vc, r.vr, -1, &t))
            continue;
        // A random point if it is exact, else a corner or the center (exact by the above).
        for (int k = 0; k < 20; ++k) {
            r.eu = rng.eps();
            r.ev = rng.eps();
            if (ExactSum(r.uc, r.ur, r.eu, &r.u) && ExactSum(r.vc, r.vr, r.ev, &r.v)) return r;
        }
        r.eu = rng.integer(-1, 1);
        r.ev = rng.integer(-1, 1);
        ExactSum(r.uc, r.ur, r.eu, &r.u);
        ExactSum(r.vc, r.vr, r.ev, &r.v);
        return r;
    }
}

/// A recipe for an operand: the same operations run on any number type.
struct Recipe {
    int kind = 0;
    double c[4] = {0, 0, 0, 0};
    double shift = 0;
    double scale = 1;
};

struct RecipeConfig {
    int kindHi = 6;                      // kinds 0..kindHi
    int coefExpLo = -4, coefExpHi = 4;   // coefficient magnitudes (log2)
    std::vector<double> shifts = {0.0};  // added at the end (e.g. 700 for exp)
    double scale = 1;                    // multiplies the result (applied before the shift)
};

inline Recipe RandomRecipe(Rng& rng, const RecipeConfig& cfg) {
    Recipe r;
    r.kind = rng.integer(0, cfg.kindHi);
    for (double& c : r.c) c = rng.chance(0.1) ? 1.0 : rng.dyadic(rng.integer(cfg.coefExpLo, cfg.coefExpHi), 24);
    r.shift = cfg.shifts[rng.integer(0, static_cast<int>(cfg.shifts.size()) - 1)];
    r.scale = cfg.scale;
    return r;
}

template <class T>
T Build(const Recipe& r, const T& u, const T& v) {
    using std::cos, std::sin;
    T x = u;
    switch (r.kind) {
        case 0: x = u; break;
        case 1: x = v; break;
        case 2: x = r.c[0] + r.c[1] * u + r.c[2] * v; break;
        case 3: x = r.c[0] * u * v + r.c[1] * u - r.c[2]; break;
        case 4: x = r.c[0] + r.c[1] * sqr(u - r.c[2]) + r.c[3] * v; break;
        case 5: x = r.c[0] * u + r.c[1] * sin(r.c[2] * u + v); break;
        default: {
            // Many nonlinear terms: more fresh symbols than Affine::kCapacity.
            x = r.c[0] * v;
            for (int k = 1; k <= 14; ++k) x = x + (r.c[1] / k) * cos(k * u + r.c[2] * v);
        }
    }
    if (r.scale != 1) x = x * r.scale;
    if (r.shift != 0) x = x + r.shift;
    return x;
}

/// A random straight-line program over registers 0 = u, 1 = v: every built-in, any operands.
struct Step {
    int op, a, b;
    double k;
};

template <class T>
T RunStep(const Step& s, const T& a, const T& b) {
    // The VM's semantics: Div, Sqrt and Pow are its own rules for double (vm/numbers/number.h).
    using std::abs, std::cos, std::exp, std::log, std::sin;
    // clang-format off
    switch (s.op) {
        case 0: return a + b;       case 1: return a - b;      case 2: return a * b;
        case 3: return Div(a, b);   case 4: return sqr(a);     case 5: return Sqrt(a);
        case 6: return exp(a);      case 7: return log(a);     case 8: return sin(a);
        case 9: return cos(a);      case 10: return abs(a);    case 11: return sign(a);
        case 12: return Pow(a, b);  case 13: return Pow(a, T(s.k));
        case 14: return a * s.k + b;  case 15: return Div(T(s.k), a);  default: return s.k - a;
    }
    // clang-format on
}

/// 16 random steps, each reading one of the last 4 registers and any other.
inline std::vector<Step> RandomSteps(Rng& rng) {
    std::vector<Step> program;
    for (int i = 0; i < 16; ++i) {
        int n = 2 + i;
        Step s{rng.integer(0, 16), rng.integer(std::max(0, n - 4), n - 1), rng.integer(0, n - 1),
               rng.dyadic(rng.integer(-3, 2), 8)};
        if (s.op == 13) s.k = rng.integer(-4, 5) + (rng.chance(0.3) ? 0.5 : 0.0);
        program.push_back(s);
    }
    return program;
}

template <class T>
std::vector<T> RunProgram(const std::vector<Step>& program, const T& u, const T& v) {
    std::vector<T> r = {u, v};
    for (const Step& s : program) r.push_back(RunStep(s, r[s.a], r[s.b]));
    return r;
}

// --- The sweeps every affine type's containment test runs -----------------------------------
// Each takes the test's own check(seed, n, region, xRecipe, yRecipe, op), which runs op on the
// types the test compares and returns its report, and expect(name, report, minBoundedFraction,
// ratio), which checks the report against the test's width ratio limit `ratio`.

/// The width ratio limits of SweepArithmetic: x * y's, x / y's, c / x's, sqr's and every linear
/// operation's.
struct ArithmeticRatios {
    double product = 1.01, quotient = 1.01, reciprocal = 1.01, square = 1.01, linear = 1.01;
};

/// +, -, *, / of two operands and with a constant, negation and sqr.
template <class Check, class Expect>
void SweepArithmetic(Check check, Expect expect, const ArithmeticRatios& ratio) {
    const int n = Samples(20000);
    RegionConfig g;
    RecipeConfig r;
    const double k = ratio.linear;
    // clang-format off
    expect("x + y", check(1, n, g, r, r, [](const auto& x, const auto& y) { return x + y; }), 1.0, k);
    expect("x - y", check(2, n, g, r, r, [](const auto& x, const auto& y) { return x - y; }), 1.0, k);
    expect("x * y", check(3, n, g, r, r, [](const auto& x, const auto& y) { return x * y; }), 1.0, ratio.product);
    expect("x / y", check(4, n, g, r, r, [](const auto& x, const auto& y) { return Div(x, y); }), 0.3,
           ratio.quotient);
    expect("-x", check(5, n, g, r, r, [](const auto& x, const auto&) { return -x; }), 1.0, k);
    expect("x + c", check(6, n, g, r, r, [](const auto& x, const auto&) { return x + 0.1; }), 1.0, k);
    expect("c - x", check(7, n, g, r, r, [](const auto& x, const auto&) { return 1e3 - x; }), 1.0, k);
    expect("x * c", check(8, n, g, r, r, [](const auto& x, const auto&) { return x * 0.7; }), 1.0, k);
    expect("x / c", check(9, n, g, r, r, [](const auto& x, const auto&) { return x / 3.0; }), 1.0, k);
    expect("c / x", check(10, n, g, r, r, [](const auto& x, const auto&) { return Div(3.0, x); }), 0.3,
           ratio.reciprocal);
    expect("sqr", check(11, n, g, r, r, [](const auto& x, const auto&) { return sqr(x); }), 1.0, ratio.square);
    // clang-format on
}

/// The width ratio limits of SweepFunctions: the smooth fits' (sqrt, log, exp, sin, cos) and
/// abs's and sign's.
struct FunctionRatios {
    double smooth = 1.01, piecewise = 1.01;
};

/// sqrt, log, abs and sign over every region; exp (near overflow too), sin and cos over small ones.
template <class Check, class Expect>
void SweepFunctions(Check check, Expect expect, const FunctionRatios& ratio) {
    using std::abs, std::cos, std::exp, std::log, std::sin;
    const int n = Samples(20000);
    RegionConfig g;
    RecipeConfig r;
    const double k = ratio.smooth;
    // clang-format off
    expect("sqrt", check(20, n, g, r, r, [](const auto& x, const auto&) { return Sqrt(x); }), 0.2, k);
    expect("log", check(21, n, g, r, r, [](const auto& x, const auto&) { return log(x); }), 0.2, k);
    expect("abs", check(22, n, g, r, r, [](const auto& x, const auto&) { return abs(x); }), 1.0, ratio.piecewise);
    expect("sign", check(23, n, g, r, r, [](const auto& x, const auto&) { return sign(x); }), 1.0, ratio.piecewise);
    RegionConfig small;
    small.expLo = -20;
    small.expHi = 4;
    RecipeConfig mild = r;
    mild.coefExpHi = 1;
    expect("exp", check(24, n, small, mild, r, [](const auto& x, const auto&) { return exp(x); }), 0.9, k);
    RecipeConfig nearOverflow = mild;
    nearOverflow.shifts = {700.0, 704.0, 708.0, 709.5, 710.0};
    nearOverflow.kindHi = 4;
    expect("exp near overflow", check(25, n, small, nearOverflow, r, [](const auto& x, const auto&) { return exp(x); }),
           0.1, k);
    expect("sin", check(26, n, small, mild, r, [](const auto& x, const auto&) { return sin(x); }), 1.0, k);
    expect("cos", check(27, n, small, mild, r, [](const auto& x, const auto&) { return cos(x); }), 1.0, k);
    // clang-format on
}

/// sin and cos over regions a quarter, half or whole period wide (or 1e-6), centred up to 1e6.
template <class Check, class Expect>
void SweepSinCosPeriods(Check check, Expect expect, double ratio) {
    using std::cos, std::sin;
    const int n = Samples(20000) / 4;
    const double pi = 3.141592653589793;
    RecipeConfig exact;
    exact.kindHi = 2;
    // v stays small: the argument's range is u's.
    exact.coefExpLo = -1;
    exact.coefExpHi = 0;
    for (double width : {pi / 2, pi, 2 * pi, 1e-6}) {
        for (double center : {4.0, 1e3, 1e6}) {
            RegionConfig g;
            g.expHi = -2;
            g.uWidth = width;
            g.uCenter = center;
            g.touchZero = 0;
            INFO("width " << width << " center " << center);
            expect("sin", check(30, n, g, exact, exact, [](const auto& x, const auto&) { return sin(x); }), 1.0, ratio);
            expect("cos", check(31, n, g, exact, exact, [](const auto& x, const auto&) { return cos(x); }), 1.0, ratio);
        }
    }
}

/// pow to constant exponents (integers up to past kMaxIntegerPower, fractions, 0, negative), of
/// negative bases to integer exponents, and to varying exponents.
template <class Check, class Expect>
void SweepPow(Check check, Expect expect) {
    const int n = Samples(20000) / 2;
    RegionConfig g;
    g.expLo = -10;
    g.expHi = 3;
    RecipeConfig r;
    r.coefExpHi = 1;
    auto power = [](double p) {
        return [p](const auto& x, const auto&) { return Pow(x, std::decay_t<decltype(x)>(p)); };
    };
    for (double p : {2.0, 3.0, -1.0, -2.0, 5.0, 0.5, 2.5, -0.75, 0.0, 1.0, 64.0, 65.0}) {
        INFO("exponent " << p);
        expect("pow(x, p)", check(40, n, g, r, r, power(p)), 0.05, 1e300);
    }
    RecipeConfig negative = r;
    negative.kindHi = 2;
    negative.shifts = {-4.0, -0.5};
    for (double p : {2.0, 3.0, -3.0, 4.0}) {
        INFO("negative base, exponent " << p);
        expect("pow(-x, n)", check(41, n, g, negative, r, power(p)), 0.2, 1e300);
    }
    RecipeConfig exponent = r;
    exponent.scale = 0.25;
    expect("pow(x, y)", check(42, n, g, r, exponent, [](const auto& x, const auto& y) { return Pow(x, y); }), 0.05,
           1e300);
}

/// The width ratio limits of SweepBranches: atan2's, Select's, and every other function's.
struct BranchRatios {
    double atan2 = 1.01, select = 1.01, others = 1.01;
};

/// floor, ceil, round, asin, acos, atan, atan2, Min, Max, the comparisons, logic and Select on
/// recipe operands (nonlinear terms, fresh symbols); tests/vm/branch_test.cpp fixes every symbol
/// instead, and checks the exactness properties.
template <class Check, class Expect>
void SweepBranches(Check check, Expect expect, const BranchRatios& ratio) {
    using std::acos, std::asin, std::atan, std::atan2, std::ceil, std::floor, std::round;
    const int n = Samples(20000) / 2;
    RegionConfig g;
    RecipeConfig r;
    RegionConfig small;
    small.expLo = -20;
    small.expHi = 3;
    RecipeConfig mild = r;
    mild.coefExpHi = 1;
    const double k = ratio.others;
    // clang-format off
    expect("floor", check(80, n, small, mild, r, [](const auto& x, const auto&) { return floor(x); }), 1.0, k);
    expect("ceil", check(81, n, small, mild, r, [](const auto& x, const auto&) { return ceil(x * 3.0); }), 1.0, k);
    expect("round", check(82, n, small, mild, r, [](const auto& x, const auto&) { return round(x); }), 1.0, k);
    expect("floor wide", check(83, n, g, r, r, [](const auto& x, const auto&) { return floor(x); }), 1.0, k);
    RegionConfig unit;
    unit.expLo = -20;
    unit.expHi = 0;
    RecipeConfig quarter = mild;
    quarter.scale = 0.25;
    expect("asin", check(84, n, unit, quarter, r, [](const auto& x, const auto&) { return asin(x); }), 0.3, k);
    expect("acos", check(85, n, unit, quarter, r, [](const auto& x, const auto&) { return acos(x); }), 0.3, k);
    expect("atan", check(86, n, g, r, r, [](const auto& x, const auto&) { return atan(x); }), 1.0, k);
    expect("atan small", check(87, n, small, mild, r, [](const auto& x, const auto&) { return atan(x); }), 1.0, k);
    expect("atan2", check(88, n, small, mild, mild, [](const auto& x, const auto& y) { return atan2(x, y); }), 1.0,
           ratio.atan2);
    expect("atan2 wide", check(89, n, g, r, r, [](const auto& x, const auto& y) { return atan2(y, x); }), 1.0,
           ratio.atan2);
    expect("Min", check(90, n, g, r, r, [](const auto& x, const auto& y) { return Min(x, y); }), 1.0, k);
    expect("Max", check(91, n, g, r, r, [](const auto& x, const auto& y) { return Max(x, y); }), 1.0, k);
    expect("Less", check(92, n, g, r, r, [](const auto& x, const auto& y) { return Less(x, y); }), 1.0, k);
    expect("LessEq", check(93, n, g, r, r, [](const auto& x, const auto& y) { return LessEq(x, y); }), 1.0, k);
    expect("Equal", check(94, n, g, r, r, [](const auto& x, const auto& y) { return Equal(x, y); }), 1.0, k);
    expect("NotEqual", check(95, n, g, r, r, [](const auto& x, const auto& y) { return NotEqual(x, y); }), 1.0, k);
    expect("And", check(96, n, g, r, r, [](const auto& x, const auto& y) { return And(x, y - 1.0); }), 1.0, k);
    expect("Or", check(97, n, g, r, r, [](const auto& x, const auto& y) { return Or(x - 0.5, y); }), 1.0, k);
    expect("Not", check(98, n, g, r, r, [](const auto& x, const auto&) { return Not(x); }), 1.0, k);
    expect("Select",
           check(99, n, g, r, r, [](const auto& x, const auto& y) { return Select(Less(x, y), y - x, x * y); }), 0.3,
           ratio.select);
    // clang-format on
}

}  // namespace affray::test::aavalid
