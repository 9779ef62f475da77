// tests/vm/numbers/affine_test.cpp: containment of every Affine operation, Stolfi's aavalid method.
// Operands are built from the region's exact symbols u = uc + ur*eps_u and v = vc + vr*eps_v by a
// random recipe, run once on doubles at a point (eps_u, eps_v) and once on Affine (and Interval):
// the double operand is then a value the operand form allows at that point, and the double result
// of the operation must lie in result.evaluateAt(eps_u, eps_v) (other symbols free) and in the
// interval result; a NaN/inf double result requires Unbounded. Region parameters and points are
// dyadic, so that u and v are exact doubles. AFFRAY_SAMPLES=N raises the samples per operation.
#include <catch2/catch.hpp>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <sstream>

#include "tests/test_random.h"
#include "tests/vm/numbers/aavalid.h"
#include "vm/numbers/number.h"

using namespace affray::vm;
using affray::test::Rng;
using affray::test::Samples;
using namespace affray::test::aavalid;

namespace {

/// Containment results of one operation.
struct Report {
    int samples = 0, failures = 0, bounded = 0, scalarFinite = 0;
    double worstRatio = 0;  // affine range width / interval width, for exact-symbol operands
    std::ostringstream first;

    void fail(const std::string& what) {
        if (failures++ < 4) first << what << "\n";
    }
};

std::string Describe(const char* what, double d, const Affine& a, const Interval& i) {
    std::ostringstream s;
    s.precision(17);
    s << what << ": double " << d << "\n  affine " << a.toString() << "\n  interval " << i.toString();
    return s.str();
}

// Checks the result triple of one sample; `exact` says whether the ratio check applies.
void CheckResult(Report& rep, const Region& g, double rd, const Affine& ra, const Interval& ri, bool exact) {
    rep.samples++;
    if (!std::isfinite(rd)) {
        if (!ra.isUnbounded() || !ri.isUnbounded()) rep.fail(Describe("NaN/inf not Unbounded", rd, ra, ri));
        return;
    }
    rep.scalarFinite++;
    if (!ra.isUnbounded()) {
        rep.bounded++;
        if (!ra.evaluateAt(g.eu, g.ev).contains(rd)) rep.fail(Describe("affine misses", rd, ra, ri));
        if (!ra.range().contains(rd)) rep.fail(Describe("affine range misses", rd, ra, ri));
        // Widths of a few ulps are all rounding slack: compare beyond 1e-14 of the magnitude.
        double allowance = 1e-14 * std::fmax(std::fabs(ri.lo()), std::fabs(ri.hi()));
        if (exact && !ri.isUnbounded() && ri.width() + allowance > 1e-300)
            rep.worstRatio = std::max(rep.worstRatio, ra.range().width() / (ri.width() + allowance));
    }
    if (!ri.contains(rd)) rep.fail(Describe("interval misses", rd, ra, ri));
}

struct Operands {
    Region g;
    Recipe rx, ry;
    double xd, yd;
    Affine xa, ya;
    Interval xi, yi;
    bool ok = true;
};

Operands MakeOperands(Rng& rng, const RegionConfig& gc, const RecipeConfig& xc, const RecipeConfig& yc, Report& rep) {
    Operands o;
    Affine::BeginEvaluation();
    o.g = RandomRegion(rng, gc);
    o.rx = RandomRecipe(rng, xc);
    o.ry = RandomRecipe(rng, yc);
    const Region& g = o.g;
    Affine ua = Affine::FromSymbol(g.uc, g.ur, Affine::kSymbolU);
    Affine va = Affine::FromSymbol(g.vc, g.vr, Affine::kSymbolV);
    Interval ui(g.uc - g.ur, g.uc + g.ur), vi(g.vc - g.vr, g.vc + g.vr);
    o.xd = Build(o.rx, g.u, g.v);
    o.yd = Build(o.ry, g.u, g.v);
    o.xa = Build(o.rx, ua, va);
    o.ya = Build(o.ry, ua, va);
    o.xi = Build(o.rx, ui, vi);
    o.yi = Build(o.ry, ui, vi);
    // The operands are themselves results of Affine operations: check them too.
    Report sub;
    CheckResult(sub, g, o.xd, o.xa, o.xi, false);
    CheckResult(sub, g, o.yd, o.ya, o.yi, false);
    if (sub.failures) rep.fail("operand: " + sub.first.str());
    o.ok = sub.failures == 0;
    return o;
}

template <class F>
Report CheckOp(uint64_t seed, int n, const RegionConfig& gc, const RecipeConfig& xc, const RecipeConfig& yc, F op) {
    Rng rng(seed);
    Report rep;
    for (int s = 0; s < n; ++s) {
        Operands o = MakeOperands(rng, gc, xc, yc, rep);
        if (!o.ok) continue;
        double rd = op(o.xd, o.yd);
        Affine ra = op(o.xa, o.ya);
        Interval ri = op(o.xi, o.yi);
        auto isExact = [](const Recipe& r) { return r.kind <= 1 && r.shift == 0 && r.scale == 1; };
        bool exact = isExact(o.rx) && isExact(o.ry);
        CheckResult(rep, o.g, rd, ra, ri, exact);
    }
    return rep;
}

// AFFRAY_VERBOSE=1 prints every report.
void Expect(const char* name, const Report& rep, double minBoundedFraction, double maxRatio) {
    if (std::getenv("AFFRAY_VERBOSE"))
        std::printf("%-20s %7d samples %7d finite %7d bounded  worst ratio %.4g  failures %d\n", name, rep.samples,
                    rep.scalarFinite, rep.bounded, rep.worstRatio, rep.failures);
    INFO(name << ": " << rep.samples << " samples, " << rep.bounded << " bounded of " << rep.scalarFinite
              << " finite, worst width ratio to interval " << rep.worstRatio << "\n"
              << rep.first.str());
    CHECK(rep.failures == 0);
    CHECK(rep.samples > 0);
    CHECK(rep.bounded >= minBoundedFraction * rep.scalarFinite);
    CHECK(rep.worstRatio <= maxRatio);
}

}  // namespace

// The shared sweeps (tests/vm/numbers/aavalid.h), with Affine's width ratio limits to the interval.
namespace {
const auto kAffineCheck = [](const auto&... args) { return CheckOp(args...); };
}  // namespace

TEST_CASE("affine arithmetic contains the scalar result", "[vm][affine]") {
    SweepArithmetic(kAffineCheck, Expect,
                    {.product = 1e300, .quotient = 1e300, .reciprocal = 2.01, .square = 2.01, .linear = 1.01});
}

TEST_CASE("affine functions contain the scalar result", "[vm][affine]") {
    SweepFunctions(kAffineCheck, Expect, {.smooth = 2.01, .piecewise = 1.01});
}

TEST_CASE("affine sin and cos over periods and far from 0", "[vm][affine]") {
    SweepSinCosPeriods(kAffineCheck, Expect, 2.01);
}

TEST_CASE("affine pow contains the scalar result", "[vm][affine]") { SweepPow(kAffineCheck, Expect); }

TEST_CASE("affine branch functions contain the scalar result", "[vm][affine]") {
    SweepBranches(kAffineCheck, Expect, {.atan2 = 1.01, .select = 1e300, .others = 1.01});
}

TEST_CASE("affine and interval contain random programs", "[vm][affine]") {
    Rng rng(70);
    Report rep;
    const int programs = Samples(20000) / 10;
    for (int p = 0; p < programs; ++p) {
        std::vector<Step> program = RandomSteps(rng);
        RegionConfig gc;
        gc.expLo = -12;
        gc.expHi = 1;
        Affine::BeginEvaluation();
        Region g = RandomRegion(rng, gc);
        auto ra = RunProgram(program, Affine::FromSymbol(g.uc, g.ur, Affine::kSymbolU),
                             Affine::FromSymbol(g.vc, g.vr, Affine::kSymbolV));
        auto ri = RunProgram(program, Interval(g.uc - g.ur, g.uc + g.ur), Interval(g.vc - g.vr, g.vc + g.vr));
        for (int point = 0; point < 8; ++point) {
            Region q = g;
            for (int k = 0; k < 20; ++k) {
                q.eu = rng.eps();
                q.ev = rng.eps();
                if (ExactSum(g.uc, g.ur, q.eu, &q.u) && ExactSum(g.vc, g.vr, q.ev, &q.v)) break;
                q.eu = q.ev = 0;
                q.u = g.uc;
                q.v = g.vc;
            }
            auto rd = RunProgram(program, q.u, q.v);
            for (size_t i = 2; i < rd.size(); ++i) CheckResult(rep, q, rd[i], ra[i], ri[i], false);
        }
    }
    Expect("random programs", rep, 0.3, 1e300);
}

TEST_CASE("affine is exact on linear correlations and tighter than intervals", "[vm][affine]") {
    Affine::BeginEvaluation();
    Affine u = Affine::FromSymbol(0.5, 0.5, Affine::kSymbolU);
    Affine v = Affine::FromSymbol(2.0, 0.25, Affine::kSymbolV);
    // Exact forms cancel exactly; computed ones keep only their independent rounding error e
    // (treated as independent of everything, itself included).
    // NOLINTNEXTLINE(misc-redundant-expression): the cancellation is what is tested
    Affine zero = u - u;
    CHECK(zero.isConstant());
    CHECK(zero.center() == 0);
    CHECK(zero.range().lo() == 0);
    CHECK(zero.range().hi() == 0);
    Affine x = u * 3.0 + v;
    // NOLINTNEXTLINE(misc-redundant-expression): the cancellation is what is tested
    Affine almostZero = x - x;
    CHECK(almostZero.termCount() == 0);
    CHECK(almostZero.center() == 0);
    CHECK(almostZero.range().width() < 1e-14);
    Interval ui(0, 1);
    Interval xi = ui * 3.0 + Interval(1.75, 2.25);
    CHECK((xi - xi).width() == 7.0);
    // (u + 1)(u - 1) = u^2 - 1 on [0, 1]: interval [-2, 0]; affine [-1.25, 0].
    Interval pi = (ui + 1.0) * (ui - 1.0);
    Interval pa = ((u + 1.0) * (u - 1.0)).range();
    CHECK(pa.width() < pi.width());
    CHECK(pa.lo() <= -1.0);
    CHECK(pa.hi() >= 0.0);
    // Affine and interval bounds of the same computation always intersect.
    Rng rng(50);
    RegionConfig g;
    RecipeConfig r;
    for (int s = 0; s < 2000; ++s) {
        Report rep;
        Operands o = MakeOperands(rng, g, r, r, rep);
        REQUIRE(o.ok);
        Interval a = o.xa.range(), i = o.xi;
        if (a.isUnbounded() || i.isUnbounded()) continue;
        CHECK(std::fmax(a.lo(), i.lo()) <= std::fmin(a.hi(), i.hi()));
    }
}

TEST_CASE("affine folds the smallest terms past capacity, never eps_u or eps_v", "[vm][affine]") {
    Affine::BeginEvaluation();
    Affine u = Affine::FromSymbol(0.5, 1e-12, Affine::kSymbolU);
    Affine v = Affine::FromSymbol(2.0, 1e-13, Affine::kSymbolV);
    Affine x = u + v;
    for (int k = 0; k < 3 * Affine::kCapacity; ++k) x = x + Affine::FromInterval(Interval(-1.0 - k, 1.0 + k));
    CHECK(x.termCount() == Affine::kCapacity);
    CHECK(x.coefficientOf(Affine::kSymbolU) == 1e-12);
    CHECK(x.coefficientOf(Affine::kSymbolV) == 1e-13);
    CHECK(x.error() > 0);
    // The largest fresh terms are the ones kept: 1 + k for the last kCapacity - 2 values of k.
    for (int i = 0; i < x.termCount(); ++i)
        if (x.termSymbol(i) >= Affine::kFirstFreshSymbol)
            CHECK(std::fabs(x.termCoef(i)) >= 3 * Affine::kCapacity - (Affine::kCapacity - 2));
    CHECK(x.error() >=
          0.5 * (3 * Affine::kCapacity - Affine::kCapacity + 2) * (3 * Affine::kCapacity - Affine::kCapacity + 3) - 1);
    // A computation with many nonlinear terms (recipe kind 6) still contains every sample.
    RegionConfig g;
    g.expHi = 2;
    RecipeConfig many;
    many.kindHi = 6;
    Rng rng(60);
    int checked = 0;
    for (int s = 0; s < Samples(20000) / 4; ++s) {
        Report rep;
        Operands o = MakeOperands(rng, g, many, many, rep);
        INFO(rep.first.str());
        REQUIRE(o.ok);
        if (o.rx.kind == 6) {
            checked++;
            CHECK(o.xa.termCount() <= Affine::kCapacity);
        }
    }
    CHECK(checked > 100);
}

// (Constants, the exact parameters, comparisons, Min and Max: tests/vm/numbers/affine_forms_test.cpp.)
TEST_CASE("affine basics", "[vm][affine]") {
    Affine::BeginEvaluation();
    Affine u = Affine::FromSymbol(1.0, 0.5, Affine::kSymbolU);
    CHECK(u.coefficientOf(Affine::kSymbolU) == 0.5);
    CHECK(u.toString() == "1 + 0.5*e0");
    Affine f = Affine::FromInterval(Interval(1, 3));
    CHECK(f.termSymbol(0) == Affine::kFirstFreshSymbol);
    CHECK(f.range().lo() <= 1);
    CHECK(f.range().hi() >= 3);
    // An undecided comparison is 0.5 +- 0.5 on a fresh symbol.
    Affine v = Affine::FromSymbol(2.0, 0.25, Affine::kSymbolV);
    Affine undecided = Less(u, v - 1.0);
    CHECK(undecided.termCount() == 1);
    CHECK(undecided.termSymbol(0) >= Affine::kFirstFreshSymbol);
    CHECK(undecided.termCoef(0) == 0.5);
    // Symbols are sorted, whatever the order they were made in.
    Affine::BeginEvaluation();
    Affine a = Affine::FromInterval(Interval(0, 1));  // symbol 2
    Affine b = Affine::FromSymbol(0, 1, 7) + Affine::FromSymbol(0, 1, 1) + a;
    for (int i = 1; i < b.termCount(); ++i) CHECK(b.termSymbol(i - 1) < b.termSymbol(i));
}
