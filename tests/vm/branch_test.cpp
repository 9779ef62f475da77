// tests/vm/branch_test.cpp: the step, inverse-trigonometric, min/max, comparison, logic and branch
// functions (floor, ceil, round, asin, acos, atan, atan2, Min, Max, Less, LessEq, Equal, NotEqual,
// And, Or, Not, TruthOf, Join, Select) of every number type.
// Containment by Stolfi's aavalid method with *every* symbol fixed: operand forms are built term
// by term on eps_u, eps_v and a few shared fresh symbols (dyadic coefficients on a common grid, so
// that an operand's value at an assignment is an exact double), plus a free part on a symbol of
// its own; every pooled symbol is fixed at -1, 0, +1 or a uniform grid value, the double function
// runs on the operand values, and its result must lie in the result form evaluated at the same
// assignment (symbols outside the pool free) and in the interval result on the operand ranges.
// A NaN or infinite double result requires Unbounded. Then random straight-line programs mixing
// these functions with arithmetic, and the exactness properties: decided comparisons and steps
// are exact constants, Select with a decided condition returns the arm itself, Unbounded operands
// never decide a comparison. AFFRAY_SAMPLES=N raises the sample counts; AFFRAY_VERBOSE=1 prints.
#include <catch2/catch.hpp>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <map>
#include <random>
#include <sstream>

#include "tests/test_random.h"
#include "vm/numbers/number.h"

using namespace affray::vm;
using affray::test::Rng;
using affray::test::Samples;
using affray::test::Tally;

namespace {

using SymbolId = Affine::SymbolId;
const double kNaN = std::numeric_limits<double>::quiet_NaN();
const double kInf = std::numeric_limits<double>::infinity();

// --- Synthetic operands -------------------------------------------------------------------------

// An affine operand with exactly known structure: center + sum coef*eps_sym + free*eps_free.
// Every number is a multiple of the quantum q (coefficients of 4096q), below 2^43 q in all, so
// the value at any assignment of grid eps values is an exact double.
struct Form {
    double q = 1;
    double center = 0;
    std::map<SymbolId, double> coefs;
    double free = 0;  // radius of the operand's own symbol, left free in every evaluation
    bool unbounded = false;
};

struct Assignment {
    std::map<SymbolId, double> eps;
};

// Symbols shared by the operands of one sample: eps_u, eps_v and three fresh ones.
std::vector<SymbolId> MakePool() {
    std::vector<SymbolId> pool = {Affine::kSymbolU, Affine::kSymbolV};
    for (int i = 0; i < 3; ++i) pool.push_back(Affine::NewSymbol());
    return pool;
}

// `exponent`: the operand's magnitude is about 2^exponent; its radius about 2^(exponent - shrink).
Form RandomForm(Rng& rng, const std::vector<SymbolId>& pool, int exponent) {
    Form f;
    f.q = std::ldexp(1.0, exponent - 40);
    f.center = static_cast<double>(rng.integer(-(int64_t(1) << 40), int64_t(1) << 40)) * f.q;
    const int64_t m = int64_t(1) << (28 - rng.integer(0, 24));
    for (SymbolId s : pool)
        if (rng.chance(0.6)) f.coefs[s] = static_cast<double>(rng.integer(-m, m)) * 4096 * f.q;
    if (rng.chance(0.3)) f.free = static_cast<double>(rng.integer<int64_t>(0, m)) * 4096 * f.q;
    return f;
}

double RadiusOf(const Form& f) {
    double r = f.free;
    for (auto& [s, c] : f.coefs) r += std::fabs(c);
    return r;
}

// Moves the center so that the range touches or straddles something interesting: an integer or
// a half-integer (steps), +-1 (asin, acos), 0 (atan2, comparisons, logic). Stays on the grid.
void Recenter(Rng& rng, Form& f, double target) {
    double r = RadiusOf(f);
    double offsets[] = {0.0, r, -r, r * 0.5, -r * 0.5};
    double c = target + offsets[rng.integer(0, 4)];
    f.center = std::round(c / f.q) * f.q;
}

Affine ToAffine(const Form& f) {
    if (f.unbounded) return Affine::Unbounded();
    Affine x(f.center);
    for (auto& [s, c] : f.coefs) x = x + Affine::FromSymbol(0.0, c, s);
    if (f.free != 0) x = x + Affine::FromInterval(Interval(-f.free, f.free));
    return x;
}

// The operand's value at `a`, with its free symbol at `freeEps` (exact, see Form).
double ValueAt(const Form& f, const Assignment& a, double freeEps, Rng& rng) {
    if (f.unbounded) {
        double choices[] = {kNaN, kInf, -kInf, 0.0, 1.0, -3.5};
        return choices[rng.integer(0, 5)];
    }
    double v = f.center;
    for (auto& [s, c] : f.coefs) v += c * a.eps.at(s);
    return v + f.free * freeEps;
}

// The result form with every symbol of `a` fixed, the others free, rounded outward.
Interval EvalAt(const Affine& r, const Assignment& a) {
    if (r.isUnbounded()) return Interval::Unbounded();
    double lo = r.center(), hi = r.center();
    UpperSum rest;
    rest.add(r.error());
    for (int i = 0; i < r.termCount(); ++i) {
        auto it = a.eps.find(r.termSymbol(i));
        double c = r.termCoef(i);
        if (it != a.eps.end()) {
            lo = AddDown(lo, MulDown(c, it->second));
            hi = AddUp(hi, MulUp(c, it->second));
        } else {
            rest.add(std::fabs(c));
        }
    }
    double w = rest.value();
    return Interval(SubDown(lo, w), AddUp(hi, w));
}

// One result triple: the double rd must be in the affine form at `a` and in its range, and in
// the interval result; NaN/inf requires both Unbounded. `what()` describes the sample (on failure).
template <class W>
void Check(Tally& t, W what, double rd, const Affine& ra, const Interval& ri, const Assignment& a) {
    t.samples++;
    if (!std::isfinite(rd)) {
        if (!ra.isUnbounded() || !ri.isUnbounded())
            t.fail(what() + ": " + ToString(rd) + " but affine " + ra.toString() + ", interval " + ri.toString());
        return;
    }
    t.finite++;
    if (!ra.isUnbounded()) t.bounded++;
    if (!EvalAt(ra, a).contains(rd) || !ra.range().contains(rd))
        t.fail(what() + ": " + ToString(rd) + " not in affine " + ra.toString() + " (at point " +
               EvalAt(ra, a).toString() + ", range " + ra.range().toString() + ")");
    if (!ri.contains(rd)) t.fail(what() + ": " + ToString(rd) + " not in interval " + ri.toString());
}

void Expect(const char* name, const Tally& t, double minBounded) {
    if (std::getenv("AFFRAY_VERBOSE"))
        std::printf("%-12s %7d samples %7d finite %7d bounded  failures %d\n", name, t.samples, t.finite, t.bounded,
                    t.failures);
    INFO(name << ": " << t.samples << " samples, " << t.bounded << " bounded of " << t.finite << " finite\n"
              << t.first.str());
    CHECK(t.failures == 0);
    CHECK(t.samples > 100);
    CHECK(t.bounded >= minBounded * t.finite);
}

// What a sample needs: the operand forms, their Affine and Interval values, an assignment and the
// operand values there.
struct Sample {
    Assignment a;
    std::vector<Form> forms;
    std::vector<Affine> xa;
    std::vector<Interval> xi;
    std::vector<double> xd;
    std::string describe() const {
        std::ostringstream s;
        s.precision(17);
        for (size_t i = 0; i < xd.size(); ++i) s << (i ? ", " : "") << xd[i] << " in " << xa[i].toString();
        return s.str();
    }
};

// Operand shapes: a fresh form, a form correlated with the first (x + small, -x, x itself, 2x),
// or (rarely) Unbounded.
struct Shape {
    std::vector<int> exponents = {-30, -8, -2, 0, 1, 4, 12};
    std::vector<double> targets = {};  // recenter on one of these (with chance 0.6)
    double unboundedChance = 0.0;
    bool correlate = true;
};

Sample MakeSample(Rng& rng, int operands, const Shape& shape) {
    Affine::BeginEvaluation();
    std::vector<SymbolId> pool = MakePool();
    Sample s;
    int exponent = rng.pick(shape.exponents);
    for (int k = 0; k < operands; ++k) {
        Form f = RandomForm(rng, pool, exponent);
        if (k > 0 && shape.correlate && rng.chance(0.5)) {
            // Correlated with the first operand.
            Form g = s.forms[0];
            switch (rng.integer(0, 3)) {
                case 0:  // g + a much smaller form (may cancel to decide comparisons)
                    for (auto& [sym, c] : f.coefs)
                        g.coefs[sym] += std::round(std::ldexp(c, -8) / (4096 * g.q)) * 4096 * g.q;
                    g.center += std::round(std::ldexp(f.center, -8) / g.q) * g.q;
                    g.free = 0;
                    break;
                case 1:  // -g
                    g.center = -g.center;
                    for (auto& [sym, c] : g.coefs) c = -c;
                    break;
                case 2:  // g itself
                    break;
                default:  // g + an integer (or 0.5) offset, when on the grid
                    if (g.q <= 0.5) g.center += rng.chance(0.5) ? 1.0 : 0.5;
            }
            f = g;
        } else if (!shape.targets.empty() && rng.chance(0.6)) {
            double target = rng.pick(shape.targets);
            if (std::fabs(target) < std::ldexp(1.0, exponent + 12) && std::fmod(target, f.q) == 0)
                Recenter(rng, f, target);
        }
        if (rng.chance(shape.unboundedChance)) f.unbounded = true;
        s.forms.push_back(f);
    }
    for (SymbolId sym : pool) s.a.eps[sym] = rng.eps();
    for (const Form& f : s.forms) {
        double freeEps = rng.eps();
        s.xa.push_back(ToAffine(f));
        s.xi.push_back(s.xa.back().range());
        s.xd.push_back(ValueAt(f, s.a, freeEps, rng));
    }
    return s;
}

// Runs `op` (a generic lambda over vectors of operands) on n samples.
template <class Op>
Tally Run(uint64_t seed, int n, int operands, const Shape& shape, Op op) {
    Rng rng(seed);
    Tally t;
    for (int i = 0; i < n; ++i) {
        Sample s = MakeSample(rng, operands, shape);
        // The operands themselves must contain their values (a harness check).
        for (size_t k = 0; k < s.xd.size(); ++k)
            if (std::isfinite(s.xd[k]) && !EvalAt(s.xa[k], s.a).contains(s.xd[k]))
                t.fail("operand " + std::to_string(k) + " misses its value: " + s.describe());
        double rd = op(s.xd);
        Affine ra = op(s.xa);
        Interval ri = op(s.xi);
        Check(
            t, [&] { return s.describe(); }, rd, ra, ri, s.a);
    }
    return t;
}

#define OP1(expr)                                                                 \
    [](const auto& v) {                                                           \
        using std::floor, std::ceil, std::round, std::asin, std::acos, std::atan; \
        const auto& x = v[0];                                                     \
        return expr;                                                              \
    }
#define OP2(expr)             \
    [](const auto& v) {       \
        using std::atan2;     \
        const auto& x = v[0]; \
        const auto& y = v[1]; \
        return expr;          \
    }

}  // namespace

TEST_CASE("step functions contain the scalar result at every assignment", "[vm][branch]") {
    const int n = Samples(20000);
    Shape s;
    s.targets = {0.0, 1.0, -1.0, 0.5, -0.5, 2.5, -2.5, 7.0, 1024.0, 4503599627370496.0};
    s.exponents = {-30, -6, -2, -1, 0, 1, 2, 3, 6, 20, 52, 53};
    Expect("floor", Run(1, n, 1, s, OP1(floor(x))), 1.0);
    Expect("ceil", Run(2, n, 1, s, OP1(ceil(x))), 1.0);
    Expect("round", Run(3, n, 1, s, OP1(round(x))), 1.0);
    Expect("floor(x)-x", Run(4, n, 1, s, OP1(floor(x) - x)), 1.0);
    s.unboundedChance = 0.05;
    Expect("floor (U)", Run(5, n / 4, 1, s, OP1(floor(x))), 0.9);
}

TEST_CASE("inverse trigonometric functions contain the scalar result", "[vm][branch]") {
    const int n = Samples(20000);
    Shape unit;
    unit.exponents = {-30, -10, -3, -1, 0};
    unit.targets = {1.0, -1.0, 0.0, 0.5, -0.5};
    Expect("asin", Run(10, n, 1, unit, OP1(asin(x))), 0.3);
    Expect("acos", Run(11, n, 1, unit, OP1(acos(x))), 0.3);
    Expect("asin(x)-x", Run(12, n, 1, unit, OP1(asin(x) - x)), 0.3);
    Shape wide;
    wide.exponents = {-30, -10, -3, -1, 0, 1, 3, 10, 30, 100};
    wide.targets = {0.0, 1.0, -1.0};
    Expect("atan", Run(13, n, 1, wide, OP1(atan(x))), 1.0);
    Expect("atan(x)-x", Run(14, n, 1, wide, OP1(atan(x) - 0.5 * x)), 1.0);
    wide.unboundedChance = 0.05;
    Expect("atan (U)", Run(15, n / 4, 1, wide, OP1(atan(x))), 0.9);
}

TEST_CASE("atan2 contains the scalar result, branch cut included", "[vm][branch]") {
    const int n = Samples(20000);
    Shape s;
    s.exponents = {-30, -6, -1, 0, 1, 8, 30};
    s.targets = {0.0};
    s.unboundedChance = 0.02;
    Expect("atan2", Run(20, n, 2, s, OP2(atan2(x, y))), 0.9);
    Expect("atan2 swap", Run(21, n, 2, s, OP2(atan2(y, x))), 0.9);
    Expect("atan2-x", Run(22, n, 2, s, OP2(atan2(x, y + 1.0) - x)), 0.9);
}

TEST_CASE("Min and Max contain the scalar result", "[vm][branch]") {
    const int n = Samples(20000);
    Shape s;
    s.targets = {0.0, 1.0};
    s.unboundedChance = 0.03;
    Expect("Min", Run(30, n, 2, s, OP2(Min(x, y))), 0.9);
    Expect("Max", Run(31, n, 2, s, OP2(Max(x, y))), 0.9);
    Expect("Min-x", Run(32, n, 2, s, OP2(Min(x, y) - x)), 0.9);
    Expect("Max(x,1-x)", Run(33, n, 1, s, OP1(Max(x, 1.0 - x))), 0.9);
}

TEST_CASE("comparisons and logic contain the scalar result", "[vm][branch]") {
    const int n = Samples(20000);
    Shape s;
    s.targets = {0.0, 1.0, -1.0};
    s.unboundedChance = 0.05;
    Expect("Less", Run(40, n, 2, s, OP2(Less(x, y))), 1.0);
    Expect("LessEq", Run(41, n, 2, s, OP2(LessEq(x, y))), 1.0);
    Expect("Equal", Run(42, n, 2, s, OP2(Equal(x, y))), 1.0);
    Expect("NotEqual", Run(43, n, 2, s, OP2(NotEqual(x, y))), 1.0);
    Expect("And", Run(44, n, 2, s, OP2(And(x, y))), 1.0);
    Expect("Or", Run(45, n, 2, s, OP2(Or(x, y))), 1.0);
    Expect("Not", Run(46, n, 1, s, OP1(Not(x))), 1.0);
    // Logic on comparison results, and Select on them.
    Expect("And(Less)", Run(47, n, 3, s, [](const auto& v) { return And(Less(v[0], v[1]), Not(Equal(v[2], v[0]))); }),
           1.0);
    Expect("Or(LessEq)", Run(48, n, 3, s, [](const auto& v) { return Or(LessEq(v[1], v[0]), NotEqual(v[2], v[1])); }),
           1.0);
    Expect("Select", Run(49, n, 3, s, [](const auto& v) { return Select(Less(v[0], v[1]), v[1] - v[0], v[2]); }), 0.9);
    Expect("Select(x)", Run(50, n, 3, s, [](const auto& v) { return Select(v[0], v[1], v[2]); }), 0.9);
}

TEST_CASE("Join contains both operands", "[vm][branch]") {
    Rng rng(60);
    Shape s;
    s.unboundedChance = 0.02;
    Tally t;
    for (int i = 0; i < Samples(20000); ++i) {
        Sample x = MakeSample(rng, 2, s);
        Affine ja = Join(x.xa[0], x.xa[1]);
        Interval ji = Join(x.xi[0], x.xi[1]);
        Check(
            t, [&] { return "Join a " + x.describe(); }, x.xd[0], ja, ji, x.a);
        Check(
            t, [&] { return "Join b " + x.describe(); }, x.xd[1], ja, ji, x.a);
        if (!ja.isUnbounded()) {
            // Within the hull of the ranges (the enclosure) and never wider than it.
            Interval hull = Hull(x.xa[0].range(), x.xa[1].range());
            if (ja.range().lo() < hull.lo() || ja.range().hi() > hull.hi())
                t.fail("Join range " + ja.range().toString() + " outside hull " + hull.toString());
        }
    }
    Expect("Join", t, 0.9);
    // Joining a form with itself keeps it (up to rounding), correlations included.
    Affine::BeginEvaluation();
    Affine u = Affine::FromSymbol(0.25, 0.5, Affine::kSymbolU);
    Affine j = Join(u, u);
    CHECK(j.coefficientOf(Affine::kSymbolU) == 0.5);
    CHECK(j.range().width() <= 1.0 + 1e-12);
    CHECK((j - u).range().width() < 1e-12);
    // Two different forms on the same symbol: the shared part stays on eps_u.
    Affine k = Join(u, u + 1.0);
    CHECK(k.coefficientOf(Affine::kSymbolU) == 0.5);
    CHECK(k.range().lo() <= -0.25);
    CHECK(k.range().hi() >= 1.75);
    CHECK(k.range().width() <= 2.0 + 1e-12);
    CHECK(Join(u, Affine::Unbounded()).isUnbounded());
    CHECK(Join(Interval(1, 2), Interval(5, 6)).lo() == 1);
    CHECK(Join(Interval(1, 2), Interval(5, 6)).hi() == 6);
    // A double holds one value: joining different ones gives NaN.
    CHECK(Join(1.5, 1.5) == 1.5);
    CHECK(std::isnan(Join(1.5, 2.5)));
    CHECK(std::isnan(Join(0.0, -0.0)));
    CHECK(std::isnan(Join(kNaN, kNaN)));
}

// --- Random programs ----------------------------------------------------------------------------

namespace {

struct Step {
    int op, a, b, c;
    double k;
};

template <class T>
T RunStep(const Step& s, const T& a, const T& b, const T& c) {
    using std::floor, std::ceil, std::round, std::asin, std::acos, std::atan, std::atan2, std::sin;
    // clang-format off
    switch (s.op) {
        case 0: return a + b;           case 1: return a - b;         case 2: return a * b;
        case 3: return a * s.k + b;     case 4: return sin(a * s.k);  case 5: return sqr(a);
        case 6: return floor(a * s.k);  case 7: return ceil(a);       case 8: return round(a * s.k);
        case 9: return asin(a * s.k);   case 10: return acos(a);      case 11: return atan(a * s.k);
        case 12: return atan2(a, b);    case 13: return Min(a, b);    case 14: return Max(a, -b);
        case 15: return Less(a, b);     case 16: return LessEq(a, b + s.k);
        case 17: return Equal(a, b);    case 18: return NotEqual(a, b);
        case 19: return And(a, b);      case 20: return Or(a, b);     case 21: return Not(a);
        case 22: return Select(Less(a, b), b - a, c);
        default: return Select(c, a, b);
    }
    // clang-format on
}

template <class T>
std::vector<T> RunProgram(const std::vector<Step>& program, const T& u, const T& v) {
    std::vector<T> r = {u, v};
    for (const Step& s : program) r.push_back(RunStep(s, r[s.a], r[s.b], r[s.c]));
    return r;
}

}  // namespace

TEST_CASE("random programs with branches contain the scalar result", "[vm][branch]") {
    Rng rng(70);
    Tally t;
    const int programs = Samples(20000) / 10;
    for (int p = 0; p < programs; ++p) {
        std::vector<Step> program;
        for (int i = 0; i < 16; ++i) {
            int n = 2 + i;
            Step s{static_cast<int>(rng.integer(0, 23)), static_cast<int>(rng.integer(0, n - 1)),
                   static_cast<int>(rng.integer(0, n - 1)), static_cast<int>(rng.integer(0, n - 1)),
                   std::ldexp(static_cast<double>(rng.integer(-64, 64)), -5)};
            program.push_back(s);
        }
        Affine::BeginEvaluation();
        // A dyadic region of u and v: center and radius multiples of 2^-20, points of 2^-12.
        int e = static_cast<int>(rng.integer(-12, 2));
        double uc = std::ldexp(static_cast<double>(rng.integer(-(1 << 20), 1 << 20)), -20);
        double vc = std::ldexp(static_cast<double>(rng.integer(-(1 << 20), 1 << 20)), -20);
        double ur = std::ldexp(static_cast<double>(rng.integer(1, 1 << 8)), e - 8);
        double vr = std::ldexp(static_cast<double>(rng.integer(1, 1 << 8)), e - 8);
        auto ra = RunProgram(program, Affine::FromSymbol(uc, ur, Affine::kSymbolU),
                             Affine::FromSymbol(vc, vr, Affine::kSymbolV));
        auto ri = RunProgram(program, Interval(uc - ur, uc + ur), Interval(vc - vr, vc + vr));
        for (int point = 0; point < 8; ++point) {
            Assignment a;
            a.eps[Affine::kSymbolU] = rng.eps();
            a.eps[Affine::kSymbolV] = rng.eps();
            double u = uc + ur * a.eps[Affine::kSymbolU], v = vc + vr * a.eps[Affine::kSymbolV];
            auto rd = RunProgram(program, u, v);
            for (size_t i = 2; i < rd.size(); ++i) {
                auto what = [&] { return "program " + std::to_string(p) + " step " + std::to_string(i); };
                Check(t, what, rd[i], ra[i], ri[i], a);
            }
        }
    }
    Expect("programs", t, 0.3);
}

// --- Exactness ----------------------------------------------------------------------------------

TEST_CASE("steps inside one integer cell are exact constants", "[vm][branch]") {
    Affine::BeginEvaluation();
    struct Case {
        double c, r, floor, ceil, round;
    };
    // Ranges [c - r, c + r] inside one cell of each function.
    for (Case k : {Case{2.5, 0.4, 2, 3, kNaN}, Case{3.0, 0.4, kNaN, kNaN, 3}, Case{-0.5, 0.4, -1, -0.0, kNaN},
                   Case{1e6 + 0.5, 0.25, 1e6, 1e6 + 1, kNaN}, Case{-7.25, 0.125, -8, -7, -7}}) {
        INFO("center " << k.c << " radius " << k.r);
        Affine x = Affine::FromSymbol(k.c, k.r, Affine::kSymbolU) * 1.0 + sin(Affine(0.0));
        if (!std::isnan(k.floor)) {
            CHECK(floor(x).isConstant());
            CHECK(floor(x).center() == k.floor);
            CHECK(floor(RangeOf(x)).isPoint());
        }
        if (!std::isnan(k.ceil)) {
            CHECK(ceil(x).isConstant());
            CHECK(ceil(x).center() == k.ceil);
        }
        if (!std::isnan(k.round)) {
            CHECK(round(x).isConstant());
            CHECK(round(x).center() == k.round);
        }
    }
    // Across cells: not constant, keeps the correlation with x, and within [f(lo), f(hi)].
    Affine x = Affine::FromSymbol(0.0, 2.75, Affine::kSymbolU);
    Affine f = floor(x);
    CHECK_FALSE(f.isConstant());
    CHECK(f.coefficientOf(Affine::kSymbolU) == 2.75);
    CHECK(f.range().lo() == -3);
    CHECK(f.range().hi() == 2);
    CHECK((x - floor(x)).range().lo() >= -1e-12);
    CHECK((x - floor(x)).range().hi() <= 1 + 1e-12);
    CHECK(round(x).range().lo() == -3);
    CHECK(ceil(x).range().hi() == 3);
    // Past 2^52 every double is an integer: the form itself.
    Affine big = Affine::FromSymbol(0x1p60, 0x1p55, Affine::kSymbolV);
    CHECK(floor(big).coefficientOf(Affine::kSymbolV) == 0x1p55);
    CHECK(floor(big).center() == 0x1p60);
    // Interval steps are exact on the endpoints.
    CHECK(floor(Interval(-2.5, 3.5)).lo() == -3);
    CHECK(floor(Interval(-2.5, 3.5)).hi() == 3);
    CHECK(ceil(Interval(-2.5, 3.5)).lo() == -2);
    CHECK(round(Interval(-2.5, 2.5)).lo() == -3);
    CHECK(round(Interval(-2.5, 2.5)).hi() == 3);
}

TEST_CASE("correlated comparisons are decided and exact", "[vm][branch]") {
    Affine::BeginEvaluation();
    // A wide x with nonlinear terms: its range is much wider than 1.
    Affine u = Affine::FromSymbol(3.0, 1000.0, Affine::kSymbolU);
    Affine v = Affine::FromSymbol(-1.0, 0.5, Affine::kSymbolV);
    Affine x = u * v + sin(u) * 7.0;
    REQUIRE(x.range().width() > 100);
    auto isConst = [](const Affine& a, double c) { return a.isConstant() && a.center() == c; };
    CHECK(isConst(Less(x, x + 1.0), 1));
    CHECK(isConst(LessEq(x, x + 1.0), 1));
    CHECK(isConst(Less(x + 1.0, x), 0));
    CHECK(isConst(LessEq(x + 1.0, x), 0));
    CHECK(isConst(Equal(x, x + 1.0), 0));
    CHECK(isConst(NotEqual(x, x + 1.0), 1));
    CHECK(isConst(Less(x * 2.0, x * 2.0 + 0.5), 1));
    // Exact forms: u == u is decided, u < u is decided false.
    CHECK(isConst(Equal(u, u), 1));
    CHECK(isConst(NotEqual(u, u), 0));
    CHECK(isConst(Less(u, u), 0));
    CHECK(isConst(LessEq(u, u), 1));
    // Undecided: the range is [0, 1] exactly, on a fresh symbol.
    Affine w = Less(x, u);
    CHECK_FALSE(w.isConstant());
    CHECK(w.range().lo() == 0);
    CHECK(w.range().hi() == 1);
    CHECK(TruthOf(w) == Truth::Unknown);
    // Intervals cannot see the correlation.
    Interval xi = x.range();
    CHECK(TruthOf(Less(xi, xi + 1.0)) == Truth::Unknown);
    CHECK(TruthOf(Less(Interval(1, 2), Interval(3, 4))) == Truth::True);
    CHECK(TruthOf(Less(Interval(1, 3), Interval(3, 4))) == Truth::Unknown);
    CHECK(TruthOf(LessEq(Interval(1, 3), Interval(3, 4))) == Truth::True);
    CHECK(TruthOf(Equal(Interval(3), Interval(3))) == Truth::True);
    // Min and Max of decided pairs are the operand itself.
    Affine m = Min(x, x + 1.0);
    CHECK(m.center() == x.center());
    CHECK(m.coefficientOf(Affine::kSymbolU) == x.coefficientOf(Affine::kSymbolU));
    CHECK(Max(x, x - 2.0).center() == x.center());
    // Undecided Min keeps the shared symbols: Min(u, 3) - u / 2 has no eps_u left... only half.
    Affine mu = Min(u, Affine(3.0));
    CHECK(mu.coefficientOf(Affine::kSymbolU) == 500.0);
    CHECK(mu.range().hi() == 3.0);
    CHECK(mu.range().lo() == -997.0);
    // Doubles: IEEE comparisons, NaN false but for !=.
    CHECK(Less(1.0, 2.0) == 1);
    CHECK(Less(kNaN, 2.0) == 0);
    CHECK(LessEq(kNaN, kNaN) == 0);
    CHECK(Equal(kNaN, kNaN) == 0);
    CHECK(NotEqual(kNaN, kNaN) == 1);
    CHECK(Equal(0.0, -0.0) == 1);
    CHECK(Less(-0.0, 0.0) == 0);
    CHECK(And(kNaN, 1.0) == 1);
    CHECK(And(2.0, 0.0) == 0);
    CHECK(Or(0.0, -0.0) == 0);
    CHECK(Not(kNaN) == 0);
    CHECK(Not(0.0) == 1);
    CHECK(Min(kNaN, 2.0) == 2);
    CHECK(Max(1.0, kNaN) == 1);
    CHECK(TruthOf(kNaN) == Truth::True);
    CHECK(TruthOf(-0.0) == Truth::False);
}

TEST_CASE("logic and TruthOf follow three-valued rules", "[vm][branch]") {
    Affine::BeginEvaluation();
    Affine unknown = Affine::FromSymbol(0.0, 1.0, Affine::kSymbolU);
    Affine one(1.0), zero(0.0), two(-2.0);
    CHECK(TruthOf(zero) == Truth::False);
    CHECK(TruthOf(two) == Truth::True);
    CHECK(TruthOf(unknown) == Truth::Unknown);
    CHECK(TruthOf(Affine::FromSymbol(3.0, 1.0, Affine::kSymbolU)) == Truth::True);
    CHECK(TruthOf(Affine::Unbounded()) == Truth::Unknown);
    CHECK(TruthOf(Interval(0.0)) == Truth::False);
    CHECK(TruthOf(Interval(0.0, 1.0)) == Truth::Unknown);
    CHECK(TruthOf(Interval(-2.0, -1.0)) == Truth::True);
    CHECK(TruthOf(Interval::Unbounded()) == Truth::Unknown);
    // A decided operand decides where it alone can.
    CHECK(TruthOf(And(unknown, zero)) == Truth::False);
    CHECK(TruthOf(And(unknown, one)) == Truth::Unknown);
    CHECK(TruthOf(Or(unknown, two)) == Truth::True);
    CHECK(TruthOf(Or(unknown, zero)) == Truth::Unknown);
    CHECK(TruthOf(Not(unknown)) == Truth::Unknown);
    CHECK(Not(two).isConstant());
    CHECK(Not(two).center() == 0);
    CHECK(And(one, two).center() == 1);
    CHECK(TruthOf(And(Affine::Unbounded(), zero)) == Truth::False);
    CHECK(TruthOf(And(Interval::Unbounded(), Interval(1.0))) == Truth::Unknown);
    // Duals: the value's truth.
    CHECK(TruthOf(Dual<double>(0.0, 1.0, 1.0)) == Truth::False);
    CHECK(TruthOf(Dual<Affine>(unknown, 0.0, 0.0)) == Truth::Unknown);
}

TEST_CASE("Select with a decided condition returns the arm itself", "[vm][branch]") {
    Affine::BeginEvaluation();
    Affine u = Affine::FromSymbol(0.5, 0.25, Affine::kSymbolU);
    Affine v = Affine::FromSymbol(-3.0, 1.0, Affine::kSymbolV);
    Affine a = sin(u) * v, b = sqr(v) + u;
    auto same = [](const Affine& x, const Affine& y) { return x.toString() == y.toString(); };
    CHECK(same(Select(Less(u, u + 1.0), a, b), a));
    CHECK(same(Select(Less(u + 1.0, u), a, b), b));
    CHECK(same(Select(Affine(2.0), a, b), a));
    CHECK(same(Select(Affine(0.0), a, b), b));
    CHECK(same(Select(Less(v, u), a, b), a));  // v < u over the whole region
    // Undecided: the Join, containing both arms.
    Affine j = Select(Less(u, Affine(0.5)), a, b);
    CHECK(j.range().lo() <= std::fmin(a.range().lo(), b.range().lo()));
    CHECK(j.range().hi() >= std::fmax(a.range().hi(), b.range().hi()));
    CHECK(Select(1.0, 2.0, 3.0) == 2.0);
    CHECK(Select(kNaN, 2.0, 3.0) == 2.0);
    CHECK(Select(0.0, 2.0, 3.0) == 3.0);
    CHECK(Select(Interval(1, 2), Interval(5), Interval(7)).lo() == 5);
    CHECK(Select(Interval(0, 2), Interval(5), Interval(7)).hi() == 7);
    Dual<double> da(1.0, 2.0, 3.0), db(4.0, 5.0, 6.0);
    CHECK(Select(Dual<double>(1.0), da, db).du == 2.0);
    CHECK(Select(Dual<double>(0.0), da, db).dv == 6.0);
}

TEST_CASE("Unbounded operands never decide a comparison", "[vm][branch]") {
    Affine::BeginEvaluation();
    Affine U = Affine::Unbounded();
    Affine x = Affine::FromSymbol(0.5, 0.25, Affine::kSymbolU);
    for (const Affine& r :
         {Less(U, x), Less(x, U), LessEq(U, x), LessEq(x, U), Equal(U, U), Equal(U, x), NotEqual(U, x), NotEqual(U, U),
          Less(U, U), Not(U), And(U, Affine(1.0)), Or(U, Affine(0.0))}) {
        CHECK_FALSE(r.isUnbounded());
        CHECK(r.range().lo() == 0);
        CHECK(r.range().hi() == 1);
    }
    Interval UI = Interval::Unbounded();
    for (const Interval& r : {Less(UI, Interval(1)), LessEq(Interval(1), UI), Equal(UI, UI), NotEqual(UI, Interval(0)),
                              Not(UI), Or(UI, Interval(0.0))}) {
        CHECK(r.lo() == 0);
        CHECK(r.hi() == 1);
    }
    Dual<Affine> du(U, 0.0, 0.0), dx(x, 1.0, 0.0);
    CHECK(TruthOf(Less(du, dx)) == Truth::Unknown);
    CHECK(TruthOf(Equal(dx, du)) == Truth::Unknown);
    // Functions of Unbounded operands stay Unbounded.
    for (const Affine& r : {floor(U), ceil(U), round(U), asin(U), acos(U), atan(U), atan2(U, x), atan2(x, U), Min(U, x),
                            Max(x, U), Join(U, x)})
        CHECK(r.isUnbounded());
    for (const Interval& r : {floor(UI), asin(UI), atan(UI), atan2(UI, Interval(1)), Min(UI, UI), Max(Interval(1), UI),
                              Join(UI, Interval(1))})
        CHECK(r.isUnbounded());
}

TEST_CASE("inverse trigonometric edge cases", "[vm][branch]") {
    const double pi = 3.141592653589793;
    Affine::BeginEvaluation();
    // The whole domain of asin and acos, and just outside it.
    Affine whole = Affine::FromSymbol(0.0, 1.0, Affine::kSymbolU);
    CHECK(asin(whole).range().contains(pi / 2));
    CHECK(asin(whole).range().contains(-pi / 2));
    CHECK(asin(whole).evaluateAt(1, 0).contains(std::asin(1.0)));
    CHECK(acos(whole).evaluateAt(-1, 0).contains(std::acos(-1.0)));
    CHECK(acos(whole).range().lo() == 0);
    CHECK(asin(Affine::FromSymbol(0.5, 0.5 + 0x1p-40, Affine::kSymbolU)).isUnbounded());
    CHECK(acos(Affine(1.0 + 0x1p-52)).isUnbounded());
    CHECK(asin(Interval(-1, 1.0 + 0x1p-52)).isUnbounded());
    // asin keeps the correlation: asin(x) - x is much narrower than asin(x) on a small range.
    Affine small = Affine::FromSymbol(0.25, 0.01, Affine::kSymbolU);
    CHECK((asin(small) - small).range().width() < 0.1 * asin(small).range().width());
    CHECK((atan(small) - small).range().width() < 0.1 * atan(small).range().width());
    // atan2 at the branch cut: y may be -0 or +0 with x < 0, both -pi and pi.
    Interval cut = atan2(Interval(0.0, 1.0), Interval(-2.0, -1.0));
    CHECK(cut.contains(std::atan2(-0.0, -1.5)));
    CHECK(cut.contains(std::atan2(0.0, -1.5)));
    CHECK(atan2(Interval(0.0), Interval(-1.0, 0.0)).contains(-pi));
    Affine cutA =
        atan2(Affine::FromSymbol(0.0, 1.0, Affine::kSymbolU), Affine::FromSymbol(-1.0, 0.5, Affine::kSymbolV));
    CHECK(cutA.range().contains(std::atan2(-0.0, -1.0)));
    CHECK(cutA.range().contains(std::atan2(0.0, -1.0)));
    // Away from the cut the quadrants are narrow.
    Interval q2 = atan2(Interval(1.0, 2.0), Interval(-2.0, -1.0));
    CHECK(q2.lo() > pi / 2);
    CHECK(q2.hi() < pi);
    CHECK(q2.contains(std::atan2(1.0, -1.0)));
    Interval q4 = atan2(Interval(-2.0, -1.0), Interval(1.0, 2.0));
    CHECK(q4.contains(std::atan2(-1.0, 2.0)));
    CHECK(q4.contains(std::atan2(-2.0, 1.0)));
    CHECK(q4.hi() < 0);
    // atan2 keeps the correlation of y and x: atan2(u, 1 + v) - atan(u) is small for small v.
    Affine y = Affine::FromSymbol(0.5, 0.25, Affine::kSymbolU);
    Affine x = Affine::FromSymbol(2.0, 0.001, Affine::kSymbolV);
    Affine t = atan2(y, x);
    CHECK(t.coefficientOf(Affine::kSymbolU) > 0.05);
    CHECK(t.range().width() < 1.2 * atan2(y.range(), x.range()).width());
}

TEST_CASE("branch functions of dual numbers", "[vm][branch]") {
    using std::floor;
    Dual<double> x(2.5, 1.0, 0.0), y(1.0, 0.0, 1.0);
    CHECK(floor(x).v == 2);
    CHECK(floor(x).du == 0);
    CHECK(Min(x, y).v == 1);
    CHECK(Min(x, y).dv == 1);
    CHECK(Min(x, y).du == 0);
    CHECK(Max(x, y).du == 1);
    CHECK(Less(y, x).v == 1);
    CHECK(Less(y, x).du == 0);
    CHECK(Not(Less(y, x)).v == 0);
    // Dual<Affine> Min of an undecided pair joins the derivatives of both.
    Affine::BeginEvaluation();
    Affine u = Affine::FromSymbol(0.0, 1.0, Affine::kSymbolU);
    Dual<Affine> a(u, 2.0, 0.0), b(Affine(0.0), -1.0, 0.0);
    Dual<Affine> m = Min(a, b);
    CHECK(m.du.range().contains(2.0));
    CHECK(m.du.range().contains(-1.0));
    CHECK(m.v.range().hi() == 0.0);
    Dual<Affine> decided = Min(a, Dual<Affine>(Affine(5.0), 7.0, 0.0));
    CHECK(decided.du.isConstant());
    CHECK(decided.du.center() == 2.0);
}
