// tests/vm/numbers/reduced_affine_test.cpp: containment of every ReducedAffine operation by Stolfi's aavalid
// method, edge cases, and containment of whole shaders.
// Operands are built from the region's exact u = uc + ur*eps_u and v = vc + vr*eps_v by random
// recipes (tests/vm/numbers/aavalid.h), once on doubles at a point (eps_u, eps_v) and once on
// ReducedAffine (and Affine, and Interval): the double result of the operation must lie in the
// reduced result's evaluateAt(eps_u, eps_v) (its error term free) and in its range; a NaN/inf
// double result requires Unbounded. Tightness is compared too: the reduced range is never wider
// than the interval result (its enclosure), and on operands that are u or v themselves it is as
// tight as Affine's (the same fits on the same ranges). AFFRAY_SAMPLES=N raises the samples.
#include <catch2/catch.hpp>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <sstream>
#include <type_traits>

#include "tests/test_random.h"
#include "tests/vm/numbers/aavalid.h"
#include "tests/vm/shader_containment.h"
#include "vm/numbers/number.h"

using namespace affray::vm;
using affray::test::Rng;
using affray::test::Samples;
using namespace affray::test::aavalid;

namespace {

/// Containment results of one operation.
struct Report {
    int samples = 0, failures = 0, bounded = 0, scalarFinite = 0;
    double worstToInterval = 0;  // reduced range width / interval width, every sample
    double worstToAffine = 0;    // reduced range width / affine range width, exact-symbol operands
    std::ostringstream first;

    void fail(const std::string& what) {
        if (failures++ < 4) first << what << "\n";
    }
};

std::string Describe(const char* what, double d, const ReducedAffine& r, const Affine& a, const Interval& i) {
    std::ostringstream s;
    s.precision(17);
    s << what << ": double " << d << "\n  reduced " << r.toString() << " " << r.range().toString() << "\n  affine "
      << a.toString() << "\n  interval " << i.toString();
    return s.str();
}

// Width ratio b/a beyond a few ulps of the magnitude (widths that small are all rounding slack).
double WidthRatio(const Interval& num, const Interval& den) {
    const double allowance = 1e-14 * std::fmax(std::fabs(den.lo()), std::fabs(den.hi()));
    if (den.isUnbounded() || num.isUnbounded() || den.width() + allowance <= 1e-300) return 0;
    return num.width() / (den.width() + allowance);
}

// Checks the results of one sample; `exact` says whether the operands are u or v themselves.
void CheckResult(Report& rep, const Region& g, double rd, const ReducedAffine& rr, const Affine& ra, const Interval& ri,
                 bool exact) {
    rep.samples++;
    if (!std::isfinite(rd)) {
        if (!rr.isUnbounded()) rep.fail(Describe("NaN/inf not Unbounded", rd, rr, ra, ri));
        return;
    }
    rep.scalarFinite++;
    if (rr.isUnbounded()) return;
    rep.bounded++;
    if (!rr.evaluateAt(g.eu, g.ev).contains(rd)) rep.fail(Describe("reduced misses", rd, rr, ra, ri));
    if (!rr.range().contains(rd)) rep.fail(Describe("reduced range misses", rd, rr, ra, ri));
    if (!(rr.error() >= 0)) rep.fail(Describe("negative error", rd, rr, ra, ri));
    rep.worstToInterval = std::max(rep.worstToInterval, WidthRatio(rr.range(), ri));
    if (exact) rep.worstToAffine = std::max(rep.worstToAffine, WidthRatio(rr.range(), ra.range()));
}

struct Operands {
    Region g;
    Recipe rx, ry;
    double xd, yd;
    ReducedAffine xr, yr;
    Affine xa, ya;
    Interval xi, yi;
    bool ok = true;
};

ReducedAffine U(const Region& g) { return ReducedAffine::FromSymbol(g.uc, g.ur, ReducedAffine::kSymbolU); }
ReducedAffine V(const Region& g) { return ReducedAffine::FromSymbol(g.vc, g.vr, ReducedAffine::kSymbolV); }

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
    o.xr = Build(o.rx, U(g), V(g));
    o.yr = Build(o.ry, U(g), V(g));
    o.xa = Build(o.rx, ua, va);
    o.ya = Build(o.ry, ua, va);
    o.xi = Build(o.rx, ui, vi);
    o.yi = Build(o.ry, ui, vi);
    // The operands are themselves results of ReducedAffine operations: check them too.
    Report sub;
    CheckResult(sub, g, o.xd, o.xr, o.xa, o.xi, false);
    CheckResult(sub, g, o.yd, o.yr, o.ya, o.yi, false);
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
        auto isExact = [](const Recipe& r) { return r.kind <= 1 && r.shift == 0 && r.scale == 1; };
        CheckResult(rep, o.g, op(o.xd, o.yd), op(o.xr, o.yr), op(o.xa, o.ya), op(o.xi, o.yi),
                    isExact(o.rx) && isExact(o.ry));
    }
    return rep;
}

// AFFRAY_VERBOSE=1 prints every report. `maxToAffine` bounds the width ratio to Affine on exact
// operands; the ratio to the interval result is always at most 1 (plus rounding).
void Expect(const char* name, const Report& rep, double minBoundedFraction, double maxToAffine = 1.01) {
    if (std::getenv("AFFRAY_VERBOSE"))
        std::printf("%-20s %7d samples %7d finite %7d bounded  worst /interval %.4g  /affine %.4g  failures %d\n", name,
                    rep.samples, rep.scalarFinite, rep.bounded, rep.worstToInterval, rep.worstToAffine, rep.failures);
    INFO(name << ": " << rep.samples << " samples, " << rep.bounded << " bounded of " << rep.scalarFinite
              << " finite, worst width ratio to interval " << rep.worstToInterval << ", to affine " << rep.worstToAffine
              << "\n"
              << rep.first.str());
    CHECK(rep.failures == 0);
    CHECK(rep.samples > 0);
    CHECK(rep.bounded >= minBoundedFraction * rep.scalarFinite);
    CHECK(rep.worstToInterval <= 1.0 + 1e-9);
    CHECK(rep.worstToAffine <= maxToAffine);
}

#define BINARY(expr) [](const auto& x, const auto& y) { return expr; }

}  // namespace

// The shared sweeps (tests/vm/numbers/aavalid.h), with ReducedAffine's width ratio limits to Affine.
namespace {
const auto kReducedCheck = [](const auto&... args) { return CheckOp(args...); };
}  // namespace

TEST_CASE("reduced affine arithmetic contains the scalar result", "[vm][reduced]") {
    SweepArithmetic(kReducedCheck, Expect, {.quotient = 1.5});
    const int n = Samples(20000);
    RegionConfig g;
    RecipeConfig r;
    Expect("x * x", CheckOp(12, n, g, r, r, BINARY(x * x + y)), 1.0);
}

TEST_CASE("reduced affine functions contain the scalar result", "[vm][reduced]") {
    SweepFunctions(kReducedCheck, Expect, {});
    // sqrt of a sum of squares across 0 stays bounded (the enclosure keeps it >= 0).
    const int n = Samples(20000);
    RegionConfig g;
    RecipeConfig r;
    Expect("sqrt(x^2 + y^2)", CheckOp(28, n, g, r, r, BINARY(Sqrt(sqr(x) + sqr(y)))), 1.0, 1.5);
}

TEST_CASE("reduced affine sin and cos over periods and far from 0", "[vm][reduced]") {
    SweepSinCosPeriods(kReducedCheck, Expect, 1.01);
}

// (Integer powers square: with one error term per value, a power of u alone keeps less correlation
// than Affine's fresh symbols do.)
TEST_CASE("reduced affine pow contains the scalar result", "[vm][reduced]") { SweepPow(kReducedCheck, Expect); }

TEST_CASE("reduced affine branch functions contain the scalar result", "[vm][reduced]") {
    SweepBranches(kReducedCheck, Expect, {.atan2 = 1.5, .select = 1.01, .others = 1.01});
}

TEST_CASE("reduced affine Join contains both operands", "[vm][reduced]") {
    const int n = Samples(20000) / 2;
    Rng rng(100);
    RegionConfig g;
    RecipeConfig r;
    Report rep;
    for (int s = 0; s < n; ++s) {
        Operands o = MakeOperands(rng, g, r, r, rep);
        if (!o.ok) continue;
        ReducedAffine j = Join(o.xr, o.yr);
        Interval hull = Hull(o.xr.range(), o.yr.range());
        for (double d : {o.xd, o.yd}) {
            rep.samples++;
            if (!std::isfinite(d)) continue;
            rep.scalarFinite++;
            if (j.isUnbounded()) continue;
            rep.bounded++;
            if (!j.evaluateAt(o.g.eu, o.g.ev).contains(d) || !j.range().contains(d))
                rep.fail(Describe("join misses", d, j, Affine(0.0), hull));
            if (!hull.isUnbounded() && (j.range().lo() < hull.lo() || j.range().hi() > hull.hi()))
                rep.fail(Describe("join leaves the hull", d, j, Affine(0.0), hull));
        }
    }
    Expect("Join", rep, 0.9);
    // A value joined with itself keeps its u and v terms.
    const Region reg{0.5, 0.25, 2.0, 0.5, 0, 0, 0.5, 2.0};
    ReducedAffine x = U(reg) * 3.0 + V(reg);
    ReducedAffine j = Join(x, x);
    CHECK(j.coefficientU() == x.coefficientU());
    CHECK(j.coefficientV() == x.coefficientV());
    CHECK(j.error() < 1e-14);
}

TEST_CASE("reduced affine contains random programs", "[vm][reduced]") {
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
        auto rr = RunProgram(program, U(g), V(g));
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
            for (size_t i = 2; i < rd.size(); ++i) CheckResult(rep, q, rd[i], rr[i], ra[i], ri[i], false);
        }
    }
    Expect("random programs", rep, 0.3);
}

// (Constants, the exact parameters, comparisons, Min and Max: tests/vm/numbers/affine_forms_test.cpp.)
TEST_CASE("reduced affine basics", "[vm][reduced]") {
    STATIC_REQUIRE(std::is_trivially_copyable_v<ReducedAffine>);
    STATIC_REQUIRE(sizeof(ReducedAffine) <= 6 * sizeof(double));
    CHECK(std::string(NumberTraits<ReducedAffine>::kName) == "reduced");
    CHECK(std::string(NumberTraits<Dual<ReducedAffine>>::kName) == "dual-reduced");
    CHECK_FALSE(NumberTraits<ReducedAffine>::kHasDerivatives);
    CHECK(IsExactlyZero(ReducedAffine()));
    ReducedAffine u = ReducedAffine::FromSymbol(1.0, 0.5, ReducedAffine::kSymbolU);
    ReducedAffine v = ReducedAffine::FromSymbol(2.0, 0.25, ReducedAffine::kSymbolV);
    CHECK(u.coefficientU() == 0.5);
    CHECK(u.coefficientV() == 0);
    CHECK(v.coefficientV() == 0.25);
    CHECK(u.error() == 0);
    CHECK(u.toString() == "1 + 0.5*eu");
    // (Linear operations add a bound on their rounding to e, even where nothing was rounded.)
    CHECK((u - v * 2.0).toString().rfind("-3 + 0.5*eu - 0.5*ev +- ", 0) == 0);
    // Linear functions of u and v are exact.
    ReducedAffine x = u * 3.0 + v;
    CHECK(x.coefficientU() == 1.5);
    CHECK(x.coefficientV() == 0.25);
    CHECK(x.range().width() < 2 * 1.75 + 1e-14);
    // The error term is independent per value: x - x keeps 2e (here only rounding, tiny), while a
    // nonlinear value minus itself keeps twice its remainder.
    CHECK((x - x).coefficientU() == 0);
    CHECK((x - x).range().width() < 1e-14);
    ReducedAffine s = sin(u);
    CHECK(s.error() > 0);
    CHECK((s - s).error() >= 2 * s.error());
    // Affine-style correlation beats intervals: (u + 1)(u - 1) on u in [0.5, 1.5].
    Interval ui(0.5, 1.5);
    CHECK(((u + 1.0) * (u - 1.0)).range().width() < ((ui + 1.0) * (ui - 1.0)).width());
    // An undecided comparison is 0.5 +- 0.5 in the error term.
    ReducedAffine undecided = Less(u, v - 1.0);  // u - v + 1 in [-1.25, 0.75]
    CHECK(undecided.error() == 0.5);
    CHECK(undecided.coefficientU() == 0);
    // Min decided by the difference returns the operand itself.
    CHECK(Min(u, u + 0.125).coefficientU() == 0.5);
    // Huge but finite values stay bounded.
    ReducedAffine big = u * 1e300;
    CHECK_FALSE(big.isUnbounded());
    CHECK(big.range().contains(1.5e300));
    CHECK_FALSE((big - big * 0.5).isUnbounded());
    // Dual<ReducedAffine> carries derivatives of forms.
    Dual<ReducedAffine> du(u, 1.0, 0.0);
    Dual<ReducedAffine> d2 = sqr(du);
    CHECK(d2.du.range().contains(2.0));
    CHECK(d2.du.range().lo() >= 1.0 - 1e-12);
    CHECK(d2.du.range().hi() <= 3.0 + 1e-12);
}

TEST_CASE("reduced affine: a form whose error outweighs its range gives way to the range", "[vm][reduced]") {
    const ReducedAffine u = ReducedAffine::FromSymbol(0.0, 1.0, ReducedAffine::kSymbolU);
    // A form of error 3 whose values are known to lie in [0, 1] (a clamp, an enclosure): the
    // range, 0.5 +- 0.5, says more.
    const ReducedAffine wide = ReducedAffine::FromForm(0.5, 0.25, 0.0, 3.0);
    const ReducedAffine narrow = ReducedAffine::Within(wide, Interval(0.0, 1.0));
    CHECK(narrow.coefficientU() == 0);
    CHECK(narrow.error() <= 0.5 + 1e-15);
    CHECK(narrow.range().lo() == 0.0);
    CHECK(narrow.range().hi() == 1.0);
    CHECK(ReducedAffine::RangeIfNarrower(narrow).error() == narrow.error());
    // Never wider than the form in a sum that cancels its linear part.
    CHECK((narrow - u * 0.25).range().width() <= (wide - u * 0.25).range().width());
    // A form whose slopes outweigh the excess stays: they may cancel later (x - floor(x)).
    const ReducedAffine steep =
        ReducedAffine::Within(ReducedAffine::FromForm(0.0, 10.0, 0.0, 0.6), Interval(-10.0, 10.0));
    CHECK(steep.coefficientU() == 10.0);
    CHECK(steep.error() == 0.6);
    // A point keeps its form; so does an unbounded value.
    const ReducedAffine point = ReducedAffine::Within(ReducedAffine::FromForm(2.0, 0.0, 0.0, 1e-15), Interval(2.0));
    CHECK(point.error() == 1e-15);
    CHECK(ReducedAffine::RangeIfNarrower(ReducedAffine::Unbounded()).isUnbounded());
}

TEST_CASE("containment: every shader's scalar P lies in its reduced affine bound", "[vm][reduced][containment]") {
    for (const std::string& path : affray::test::AllShaders()) {
        affray::compiler::CompileResult r = affray::compiler::CompileFile(path);
        INFO(path << "\n" << r.diagnostics);
        REQUIRE(r.ok());
        affray::test::CheckContainment<ReducedAffine>(path, r.shader->bound, 2000 / affray::test::kSanitizerDivisor, 24,
                                                      42);
        affray::test::CheckContainment<ReducedAffine>(path + " (shade)", r.shader->shade,
                                                      60 / affray::test::kSanitizerDivisor, 12, 43);
    }
}

TEST_CASE("containment: stiff parameters of wave.sl in reduced affine", "[vm][reduced][containment]") {
    const std::string path = affray::test::SourceDir() + "/shaders/wave.sl";
    const std::vector<std::vector<affray::compiler::ParamOverride>> cases = {
        {{"frequency", {1000}}},
        {{"Km", {1e3}}},
        {{"decay", {200}}, {"Km", {5}}},
        {{"centerS", {0}}, {"centerT", {0}}},
    };
    for (const auto& params : cases) {
        affray::compiler::CompileResult r = affray::compiler::CompileFile(path, params);
        REQUIRE(r.ok());
        affray::test::CheckContainment<ReducedAffine>(path + " " + params[0].name, r.shader->bound, 200, 16, 7);
    }
}
