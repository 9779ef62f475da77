// tests/vm/numbers/affine_forms_test.cpp: the tests that are the same for every affine form type,
// vm::Affine and vm::ReducedAffine, written once as template test cases over both: constants and
// the exact parameter forms, ranges that touch 0, where Unbounded comes from and how it
// propagates, and the comparisons, Min and Max decided from the difference form (one template for
// both types, vm/numbers/affine_fit.h). What a type does its own way (Affine's symbols and their
// capacity, ReducedAffine's one error term) is tested in tests/vm/numbers/affine_test.cpp and
// tests/vm/numbers/reduced_affine_test.cpp, as are the containment sweeps (tests/vm/numbers/
// aavalid.h), whose reports each compare with other types.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <type_traits>
#include <vector>

#include "vm/numbers/affine_fit.h"
#include "vm/numbers/number.h"

using namespace affray::vm;

namespace {

/// Starts an evaluation: Affine's fresh symbols restart (ReducedAffine has none).
template <class T>
void Begin() {
    if constexpr (std::is_same_v<T, Affine>) Affine::BeginEvaluation();
}

/// The exact form uc + ur*eps_u of u over [uc - ur, uc + ur].
template <class T>
T U(double uc, double ur) {
    return T::FromSymbol(uc, ur, T::kSymbolU);
}

}  // namespace

TEMPLATE_TEST_CASE("affine forms: constants and the parameters are exact", "[vm][affine][reduced]", Affine,
                   ReducedAffine) {
    using T = TestType;
    Begin<T>();
    T c(2.5);
    CHECK(c.isConstant());
    CHECK(c.range().lo() == 2.5);
    CHECK(c.range().hi() == 2.5);
    const T u = U<T>(1.0, 0.5);
    CHECK(u.center() == 1.0);
    CHECK(u.range().lo() == 0.5);
    CHECK(u.range().hi() == 1.5);
    CHECK(u.evaluateAt(1, 0).lo() == 1.5);
    CHECK(u.evaluateAt(1, 0).hi() == 1.5);
    CHECK(T::FromSymbol(3.0, 0.0, T::kSymbolU).isConstant());
    CHECK(T::FromInterval(Interval::Unbounded()).isUnbounded());
    // Constant arithmetic is the scalar result, exactly.
    CHECK((T(0.1) + T(0.2)).isConstant());
    CHECK((T(0.1) + T(0.2)).center() == 0.1 + 0.2);
    CHECK((T(3.0) * T(7.0)).center() == 21.0);
    CHECK((T(1.0) / T(3.0)).center() == 1.0 / 3.0);
    CHECK(sqrt(T(2.0)).center() == std::sqrt(2.0));
    CHECK(IsExactlyZero(T(0.0)));
    CHECK_FALSE(IsExactlyZero(u - 1.0));
    // The same exact form cancels exactly.
    // NOLINTNEXTLINE(misc-redundant-expression): the cancellation is what is tested
    const T zero = u - u;
    CHECK(zero.isConstant());
    CHECK(zero.center() == 0);
    // pow to 0 is the constant 1; pow at 0: pow(0, 0) = 1, pow(0, y > 0) = 0, pow(0, y < 0) = inf.
    CHECK(pow(u, T(0.0)).isConstant());
    CHECK(pow(T(0.0), T(0.0)).center() == 1.0);
    CHECK(pow(T(0.0), T(2.5)).range().contains(0.0));
    CHECK(pow(T(0.0), T(3.0)).range().contains(0.0));
    CHECK(pow(T(0.0), T(-1.0)).isUnbounded());
    CHECK(pow(T(0.0), T(-0.5)).isUnbounded());
    // Step functions within one integer cell are the exact constant.
    CHECK(floor(u * 0.25 + 3.0).isConstant());
    CHECK(floor(u * 0.25 + 3.0).center() == 3.0);
    // No derivatives: the unknown value.
    CHECK(DerivU(u).isUnbounded());
    CHECK(DerivV(u).isUnbounded());
}

TEMPLATE_TEST_CASE("affine forms: ranges touching 0", "[vm][affine][reduced]", Affine, ReducedAffine) {
    using T = TestType;
    Begin<T>();
    for (double r : {1e-6, 0.5, 3.0, 1e6}) {
        const T x = U<T>(r, r);  // [0, 2r], 0 at eps_u = -1
        CHECK(x.range().lo() == 0);
        const T s = sqrt(x);
        REQUIRE_FALSE(s.isUnbounded());
        CHECK(s.evaluateAt(-1, 0).contains(0.0));
        CHECK(s.evaluateAt(1, 0).contains(std::sqrt(2 * r)));
        CHECK(s.range().lo() >= 0);
        CHECK(log(x).isUnbounded());
        CHECK((1.0 / x).isUnbounded());
        CHECK((T(1.0) / x).isUnbounded());
        CHECK((x / (x - r)).isUnbounded());
        CHECK(pow(x, T(-1.0)).isUnbounded());
        CHECK(pow(x, T(-0.5)).isUnbounded());
        CHECK(pow(x, T(0.5)).evaluateAt(-1, 0).contains(0.0));
        const T a = abs(x - r);
        CHECK(a.range().lo() == 0);  // min-range abs stays >= 0 exactly
        CHECK_FALSE(sqrt(a).isUnbounded());
        // Squares across 0 stay >= 0 (the compiler makes x*x a square), so their sums have a
        // square root.
        const T c = x - r;  // [-r, r]
        CHECK(sqr(c).range().lo() == 0);
        CHECK_FALSE(sqrt(sqr(c) + sqr(c * 0.5)).isUnbounded());
    }
}

TEMPLATE_TEST_CASE("affine forms: Unbounded comes from every NaN/inf source and propagates", "[vm][affine][reduced]",
                   Affine, ReducedAffine) {
    using T = TestType;
    Begin<T>();
    const T u = U<T>(0.5, 0.5);
    const double inf = std::numeric_limits<double>::infinity();
    // clang-format off
    const std::vector<T> sources = {  // every way to NaN or infinity
        T(std::nan("")), T(inf), T(-inf), log(u), log(u - 1.0), 1.0 / (u - 0.5), u / (u - 0.25), u / 0.0,
        exp(u * 1000.0), exp(T(710.0)), pow(u - 0.5, T(-0.5)), pow(u, T(-1.0)), pow(u - 1.0, u),
        T(1e300) * T(1e300), u * 1e300 * 1e300, T(1.5e308) + 1.5e308, u * 1e308 + u * 1e308, sqr(u * 1e200),
        T::FromSymbol(1, inf, 0), T::FromSymbol(std::nan(""), 1, 1), asin(u * 3.0), acos(u + 0.75),
        T::FromInterval(Interval::Unbounded()), T::Unbounded()};
    const T U = T::Unbounded();
    const std::vector<T> results = {  // every operation, U in every operand position
        U + u, u + U, U - u, u - U, U * u, u * U, U / (u + 1.0), u / U, U + 1.0, 1.0 - U, U * 0.0, 2.0 / U,
        U / 2.0, -U, sqr(U), sqrt(U), exp(U), log(U), sin(U), cos(U), abs(U), sign(U), pow(U, u), pow(u, U),
        pow(U, T(0.0)), pow(U, T(2.0)), floor(U), ceil(U), round(U), asin(U), acos(U), atan(U), atan2(U, u),
        atan2(u, U), Min(U, u), Max(u, U), Join(U, u), Join(u, U), DerivU(u), DerivV(u), u + 1.0 / 0.0};
    // clang-format on
    for (size_t i = 0; i < sources.size(); ++i) {
        INFO("source " << i << ": " << sources[i].toString());
        CHECK(sources[i].isUnbounded());
        CHECK(RangeOf(sources[i]).isUnbounded());
    }
    for (size_t i = 0; i < results.size(); ++i) {
        INFO("result " << i);
        CHECK(results[i].isUnbounded());
    }
    // Comparisons and logic on Unbounded are undecided, never Unbounded (NaN compares false).
    for (const T& c : {Less(U, u), LessEq(u, U), Equal(U, U), NotEqual(U, u), And(U, u), Or(u, U), Not(U)}) {
        CHECK(TruthOf(c) == Truth::Unknown);
        CHECK(c.range().lo() == 0);
        CHECK(c.range().hi() == 1);
    }
    CHECK(U.range().isUnbounded());
    CHECK(U.evaluateAt(0, 0).isUnbounded());
    CHECK(U.toString() == "unbounded");
    CHECK(IsUnbounded(U));
}

TEMPLATE_TEST_CASE("affine forms: comparisons, Min and Max decide from the difference form", "[vm][affine][reduced]",
                   Affine, ReducedAffine) {
    using T = TestType;
    Begin<T>();
    const T u = U<T>(1.0, 0.5);
    const T v = T::FromSymbol(2.0, 0.25, T::kSymbolV);
    // Correlated operands whose ranges overlap are decided: the exact constant 1 or 0.
    CHECK(Less(u, u + 0.25).isConstant());
    CHECK(Less(u, u + 0.25).center() == 1.0);
    CHECK(LessEq(u * 2.0 + v, u * 2.0 + v - 1e-9).center() == 0.0);
    CHECK(Equal(u, u).center() == 1.0);
    CHECK(NotEqual(u, u + 1e-6).center() == 1.0);
    CHECK(Equal(u, u + 1e-6).center() == 0.0);
    CHECK(LessEq(u, u).center() == 1.0);
    CHECK(Less(u, u).center() == 0.0);
    // Undecided: 0.5 +- 0.5, exactly [0, 1].
    const T undecided = Less(u, v - 1.0);  // u - v + 1 in [-1.25, 0.75]
    CHECK(TruthOf(undecided) == Truth::Unknown);
    CHECK(undecided.center() == 0.5);
    CHECK(undecided.range().lo() == 0);
    CHECK(undecided.range().hi() == 1);
    CHECK(TruthOf(Equal(u, v - 1.0)) == Truth::Unknown);
    CHECK(TruthOf(NotEqual(u, v - 1.0)) == Truth::Unknown);
    CHECK(And(Less(u, u + 1.0), Less(v, v + 1.0)).center() == 1.0);
    CHECK(Not(Less(u, u + 1.0)).center() == 0.0);
    CHECK(TruthOf(Or(undecided, T(0.0))) == Truth::Unknown);
    // Min and Max decided by the difference return the operand itself.
    CHECK(Min(u, u + 0.125).toString() == u.toString());
    CHECK(Max(u, u - 0.125).toString() == u.toString());
    CHECK(Max(u, u + 0.125).center() == 1.125);
    // Undecided: a bound of both, within the hull of the ranges, never Unbounded.
    const T low = Min(u, v - 1.0), high = Max(u, v - 1.0);
    REQUIRE_FALSE(low.isUnbounded());
    REQUIRE_FALSE(high.isUnbounded());
    for (double eu : {-1.0, 0.0, 1.0})
        for (double ev : {-1.0, 0.0, 1.0}) {
            const double a = 1.0 + 0.5 * eu, b = 2.0 + 0.25 * ev - 1.0;
            CHECK(low.evaluateAt(eu, ev).contains(std::fmin(a, b)));
            CHECK(high.evaluateAt(eu, ev).contains(std::fmax(a, b)));
        }
    CHECK(low.range().lo() >= 0.5);
    CHECK(high.range().hi() <= 1.5);
}

TEST_CASE("affine fits: the lines of 1/x and exp have the error the calculus gives, no wider", "[vm][affine]") {
    // Containment does not see a fit that is sound but loose: these pin [lo, hi] of
    // g(t) = f(t) - alpha t to its extremes, worked out by hand, up to rounding.
    // 1/x on [1, 4]: alpha is the chord's slope -1/(1 * 4); g(t) = 1/t + t/4 is 1.25 at both ends
    // and least at t = 2, where it is 2 sqrt(-alpha) = 1.
    const AffineFit r = ReciprocalFit(Interval(1.0, 4.0));
    REQUIRE(r.kind == AffineFit::Kind::Line);
    CHECK(r.alpha == -0.25);
    CHECK(r.lo <= 1.0);
    CHECK(r.lo == Approx(1.0).epsilon(1e-12));
    CHECK(r.hi >= 1.25);
    CHECK(r.hi == Approx(1.25).epsilon(1e-12));
    // exp on [0, 1]: alpha is the chord's slope e - 1, capped at exp(1/2) (vm/numbers/affine_fit.cpp);
    // g(t) = e^t - alpha t is 1 at 0 and e - alpha at 1, and least where e^t = alpha, at
    // t = log(alpha) in (0, 1): alpha (1 - log(alpha)).
    const AffineFit e = ExpFit(Interval(0.0, 1.0));
    REQUIRE(e.kind == AffineFit::Kind::Line);
    const double alpha = std::fmin(std::exp(1.0) - 1.0, std::exp(0.5));
    CHECK(e.alpha == Approx(alpha).epsilon(1e-15));
    const double least = alpha * (1.0 - std::log(alpha)), most = std::fmax(1.0, std::exp(1.0) - alpha);
    CHECK(e.lo <= least);
    CHECK(e.lo == Approx(least).epsilon(1e-12));
    CHECK(e.hi >= most);
    CHECK(e.hi == Approx(most).epsilon(1e-12));
}
