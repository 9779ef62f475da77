// tests/vm/numbers/partial_bounds_test.cpp: partial (one-sided) unbounded values (issue 12) in
// every bounded type. A value that may be NaN or infinite keeps the finite side that its scalar
// semantics guarantee through Min, Max, abs, negation, Join and log/exp at their limits, and a
// clamp makes it bounded again. aavalid-style: operands built from intervals that reach the
// trouble spots, the scalar operation run on chosen operand values (endpoints, signed zeros,
// NaN and infinities where the operand may take them), every result contained.
#include <catch2/catch.hpp>
#include <cmath>
#include <functional>
#include <limits>
#include <string>
#include <type_traits>
#include <vector>

#include "tests/test_util.h"
#include "vm/numbers/number.h"

using namespace affray::vm;

namespace {

const double kInf = std::numeric_limits<double>::infinity();
const double kNaN = std::numeric_limits<double>::quiet_NaN();

/// A bound and scalar values it must contain.
template <class T>
struct Sample {
    std::string name;
    T bound;
    std::vector<double> values;
};

/// [lo, hi], independent of every other operand (a fresh symbol, or the independent error).
template <class T>
T Over(double lo, double hi) {
    return T::FromInterval(Interval(lo, hi));
}
template <>
Interval Over<Interval>(double lo, double hi) {
    return Interval(lo, hi);
}

template <class T>
Sample<T> Apply(const std::string& name, const Sample<T>& x, T (*f)(const T&), double (*g)(double)) {
    Sample<T> r{name + "(" + x.name + ")", f(x.bound), {}};
    for (double v : x.values) r.values.push_back(g(v));
    return r;
}

template <class T>
Sample<T> Apply2(const std::string& name, const Sample<T>& a, const Sample<T>& b, T (*f)(const T&, const T&),
                 double (*g)(double, double)) {
    Sample<T> r{name + "(" + a.name + ", " + b.name + ")", f(a.bound, b.bound), {}};
    for (double x : a.values)
        for (double y : b.values) r.values.push_back(g(x, y));
    return r;
}

template <class T>
T TMin(const T& a, const T& b) {
    return Min(a, b);
}
template <class T>
T TMax(const T& a, const T& b) {
    return Max(a, b);
}
template <class T>
T TAbs(const T& a) {
    return abs(a);
}
template <class T>
T TNeg(const T& a) {
    return -a;
}
template <class T>
T TLog(const T& a) {
    return log(a);
}
template <class T>
T TExp(const T& a) {
    return exp(a);
}
template <class T>
T TDiv(const T& a, const T& b) {
    return Div(a, b);
}
template <class T>
T TSqrt(const T& a) {
    return Sqrt(a);
}
template <class T>
T TPow(const T& a, const T& b) {
    return Pow(a, b);
}
template <class T>
T TMul(const T& a, const T& b) {
    return a * b;
}
template <class T>
T TAdd(const T& a, const T& b) {
    return a + b;
}
double DMin(double a, double b) { return Min(a, b); }
double DMax(double a, double b) { return Max(a, b); }
double DAbs(double a) { return std::fabs(a); }
double DNeg(double a) { return -a; }
double DLog(double a) { return std::log(a); }
double DExp(double a) { return std::exp(a); }
double DDiv(double a, double b) { return Div(a, b); }
double DSqrt(double a) { return Sqrt(a); }
double DPow(double a, double b) { return Pow(a, b); }
double DMul(double a, double b) { return a * b; }
double DAdd(double a, double b) { return a + b; }

/// Bounded and unbounded operands: the trouble spots of division, log and exp, the explicit
/// Unbounded, and bounded ones; then everything one Min, Max, abs, negation or log of them gives.
template <class T>
std::vector<Sample<T>> Operands() {
    const std::vector<double> anything = {kNaN, -kInf, kInf, -1e300, -3, -0.0, 0.0, 2.5, 1e300};
    std::vector<Sample<T>> base = {
        {"U", T::Unbounded(), anything},
        {"[-1,2]", Over<T>(-1, 2), {-1, -0.0, 0.0, 0.5, 2}},
        {"[0.5,3]", Over<T>(0.5, 3), {0.5, 1, 3}},
        {"0", T(0.0), {0.0}},
        {"1", T(1.0), {1.0}},
    };
    const Sample<T> zeroToFour{"[0,4]", Over<T>(0, 4), {-0.0, 0.0, 1e-300, 1, 4}};
    const Sample<T> acrossZero{"[-1,4]", Over<T>(-1, 4), {-1, -0.0, 0.0, 1e-300, 4}};
    const Sample<T> large{"[0,1024]", Over<T>(0, 1024), {0, 1, 709, 710, 1024}};
    base.push_back(Apply<T>("log", zeroToFour, TLog<T>, DLog));
    base.push_back(Apply<T>("log", acrossZero, TLog<T>, DLog));
    base.push_back(Apply<T>("exp", large, TExp<T>, DExp));
    base.push_back(Apply2<T>("div", base[4], zeroToFour, TDiv<T>, DDiv));
    base.push_back(Apply2<T>("div", base[1], acrossZero, TDiv<T>, DDiv));
    base.push_back(Apply<T>("sqrt", acrossZero, TSqrt<T>, DSqrt));
    std::vector<Sample<T>> all = base;
    for (const auto& x : base) {
        all.push_back(Apply<T>("abs", x, TAbs<T>, DAbs));
        all.push_back(Apply<T>("neg", x, TNeg<T>, DNeg));
        for (const auto& y : base) {
            all.push_back(Apply2<T>("min", x, y, TMin<T>, DMin));
            all.push_back(Apply2<T>("max", x, y, TMax<T>, DMax));
        }
    }
    return all;
}

template <class T>
void CheckContains(const Sample<T>& s) {
    const Interval r = RangeOf(s.bound);
    for (double v : s.values) {
        INFO(s.name << " = " << ToString(s.bound) << " (range " << r.toString() << ") should contain " << v);
        CHECK(r.contains(v));
    }
}

}  // namespace

TEMPLATE_TEST_CASE("partial bounds contain every scalar result, NaN and infinities included", "[vm][partial]", Interval,
                   Affine, ReducedAffine) {
    using T = TestType;
    if constexpr (std::is_same_v<T, Affine>) T::BeginEvaluation();
    // Two independent sets, so that a binary operation's operands share no symbol (every pair of
    // their values is possible).
    const std::vector<Sample<T>> operands = Operands<T>(), others = Operands<T>();
    for (size_t i = 0; i < operands.size(); ++i) {
        const auto& x = operands[i];
        CheckContains(x);
        CheckContains(Apply<T>("abs", x, TAbs<T>, DAbs));
        CheckContains(Apply<T>("neg", x, TNeg<T>, DNeg));
        CheckContains(Apply<T>("log", x, TLog<T>, DLog));
        CheckContains(Apply<T>("exp", x, TExp<T>, DExp));
        CheckContains(Apply<T>("sqrt", x, TSqrt<T>, DSqrt));
        if (i % 5 == 0)  // (a subset: the operands' value lists are long)
            for (double p : {0.5, -0.5, 3.0, -2.0, 2.5})
                CheckContains(Apply2<T>("pow", x, Sample<T>{ToString(p), T(p), {p}}, TPow<T>, DPow));
    }
    // Binary operations on a subset (the full square is large).
    // (Under the sanitizers, a quarter of that subset.)
    for (size_t i = 0; i < operands.size(); i += affray::test::kSanitized ? 18 : 9)
        for (size_t j = 0; j < others.size(); j += affray::test::kSanitized ? 26 : 13) {
            const auto &a = operands[i], &b = others[j];
            CheckContains(Apply2<T>("min", a, b, TMin<T>, DMin));
            CheckContains(Apply2<T>("max", a, b, TMax<T>, DMax));
            CheckContains(Apply2<T>("add", a, b, TAdd<T>, DAdd));
            CheckContains(Apply2<T>("mul", a, b, TMul<T>, DMul));
            CheckContains(Apply2<T>("div", a, b, TDiv<T>, DDiv));
            // Join contains both operands' values.
            Sample<T> joined{"join(" + a.name + ", " + b.name + ")", Join(a.bound, b.bound), a.values};
            joined.values.insert(joined.values.end(), b.values.begin(), b.values.end());
            CheckContains(joined);
        }
}

TEMPLATE_TEST_CASE("a clamp makes an unbounded value bounded again", "[vm][partial]", Interval, Affine, ReducedAffine,
                   Dual<Interval>, Dual<Affine>, Dual<ReducedAffine>) {
    using T = TestType;
    const T u = T(kNaN);  // Unbounded
    REQUIRE(IsUnbounded(u));
    auto range = [](const T& x) { return RangeOf(ValueOf(x)); };
    // max(x, 0) is >= 0 whatever x (fmax drops NaN), and min of that with 1 is in [0, 1].
    const T lower = Max(u, T(0.0));
    CHECK(range(lower).isUnbounded());
    CHECK(range(lower).lo() == 0);
    const T clamped = Min(lower, T(1.0));
    CHECK_FALSE(range(clamped).isUnbounded());
    CHECK(range(clamped).lo() == 0);
    CHECK(range(clamped).hi() == 1);
    // The other order, and the other side.
    CHECK(range(Max(Min(u, T(1.0)), T(-1.0))).lo() == -1);
    CHECK(range(Max(Min(u, T(1.0)), T(-1.0))).hi() == 1);
    // min(a, b) is at most the bounded side; abs of a one-sided value keeps its side.
    const Interval upper = range(Min(u, T(2.0)));
    CHECK(upper.isUnbounded());
    CHECK(upper.hi() == 2);
    CHECK(upper.contains(-kInf));
    CHECK(upper.contains(kNaN));
    CHECK_FALSE(upper.contains(2.5));
    CHECK(range(abs(Min(u, T(-2.0)))).lo() == 2);
    CHECK(range(Min(abs(Min(u, T(-2.0))), T(5.0))).hi() == 5);
    CHECK_FALSE(range(Min(abs(Min(u, T(-2.0))), T(5.0))).isUnbounded());
    // abs(u) is >= 0 or NaN, and fmax(NaN, -1) is -1: the NaN side joins the other operand.
    CHECK(range(Max(abs(u), T(-1.0))).lo() == -1);
    CHECK(range(Min(-abs(u), T(1.0))).hi() == 1);
    CHECK(range(Max(T(-1.0), abs(u))).lo() == -1);
    // A clamp of a product or sum of unbounded values: nothing survives but the clamp.
    const T wild = (u + T(1.0)) * u;
    CHECK(range(Min(Max(wild, T(-0.5)), T(0.25))).lo() == -0.5);
    CHECK(range(Min(Max(wild, T(-0.5)), T(0.25))).hi() == 0.25);
}

TEMPLATE_TEST_CASE("log near 0 keeps its bounded side", "[vm][partial]", Interval, Affine, ReducedAffine) {
    using T = TestType;
    if constexpr (std::is_same_v<T, Affine>) T::BeginEvaluation();
    const T x = Over<T>(0, 4);
    const Interval l = RangeOf(log(x));
    CHECK(l.isUnbounded());
    CHECK(l.lo() == -kInf);
    CHECK(l.hi() >= std::log(4.0));
    CHECK(l.hi() < 1.4);
    // max(log(x), -10) is bounded again: [-10, log 4].
    const Interval m = RangeOf(Max(log(x), T(-10.0)));
    CHECK_FALSE(m.isUnbounded());
    CHECK(m.lo() == -10);
    CHECK(m.hi() < 1.4);
    // exp overflow keeps its low side.
    const Interval e = RangeOf(exp(Over<T>(0, 1024)));
    CHECK(e.isUnbounded());
    CHECK(e.lo() >= 0.99);
    CHECK(e.lo() <= 1);
}

TEST_CASE("the scalar sqrt, pow and division are defined where C's give NaN or a sign by chance", "[vm][partial]") {
    CHECK(Sqrt(-4.0) == 0);
    CHECK(Sqrt(4.0) == 2);
    CHECK(std::signbit(Sqrt(-0.0)));
    CHECK(std::isnan(Sqrt(kNaN)));
    CHECK(Sqrt(-kInf) == 0);
    CHECK(Pow(-4.0, 0.5) == 0);
    CHECK(Pow(-4.0, -0.5) == kInf);
    CHECK(Pow(-2.0, 3.0) == -8);
    CHECK(Pow(-2.0, -2.0) == 0.25);
    CHECK(Pow(-2.0, kInf) == kInf);
    CHECK(Pow(4.0, 0.5) == 2);
    CHECK(std::isnan(Pow(kNaN, 0.5)));
    CHECK(std::isnan(Pow(-1.0, kNaN)));
    CHECK(Div(1.0, -0.0) == kInf);
    CHECK(Div(-1.0, -0.0) == -kInf);
    CHECK(Div(1.0, 0.0) == kInf);
    CHECK(std::signbit(Div(-0.0, 2.0)));
    CHECK(std::isnan(Div(0.0, -0.0)));
    CHECK(Div(1.0, -2.0) == -0.5);
}

TEMPLATE_TEST_CASE("sqrt and pow below 0, and a quotient by a range that reaches 0, stay bounded", "[vm][partial]",
                   Interval, Affine, ReducedAffine, Dual<Interval>, Dual<Affine>) {
    using T = TestType;
    Affine::BeginEvaluation();
    auto over = [](double lo, double hi) {
        if constexpr (std::is_same_v<T, Interval> || std::is_same_v<T, Affine> || std::is_same_v<T, ReducedAffine>)
            return Over<T>(lo, hi);
        else {
            using V = std::decay_t<decltype(ValueOf(T()))>;
            return T(Over<V>(lo, hi), V(1.0), V(0.0));  // varies in u
        }
    };
    auto range = [](const T& x) { return RangeOf(ValueOf(x)); };
    // The dome of a rivet in the untaken arm: sqrt of [-1, 4] is [0, 2].
    const Interval s = range(Sqrt(over(-1, 4)));
    CHECK_FALSE(s.isUnbounded());
    CHECK(s.lo() == 0);
    CHECK(s.hi() >= 2);
    CHECK(s.hi() < 2.001);
    CHECK(range(Sqrt(over(-3, -1))).hi() == 0);
    // pow of a negative base to a non-integer constant: the base taken as 0.
    const Interval p = range(Pow(over(-1, 4), T(0.5)));
    CHECK_FALSE(p.isUnbounded());
    CHECK(p.lo() == 0);
    CHECK(p.hi() < 2.001);
    CHECK(range(Pow(over(-1, 4), T(-0.5))).isUnbounded());  // pow(0, -0.5) = inf
    // The pimple: 0.05 / d for d in [0, 0.5] is [0.1, +inf] (a zero divisor is +0), and capped by
    // min it is bounded again.
    const Interval q = range(Div(T(0.05), over(0, 0.5)));
    CHECK(q.isUnbounded());
    CHECK(q.lo() <= 0.1);
    CHECK(q.lo() > 0.0999);
    CHECK(q.hi() == kInf);
    const Interval capped = range(Min(Div(T(0.05), over(0, 0.5)), T(1.0)));
    CHECK_FALSE(capped.isUnbounded());
    CHECK(capped.lo() > 0.0999);
    CHECK(capped.hi() >= 1);
    CHECK(capped.hi() < 1.000001);
    CHECK(range(Div(T(-1.0), over(0, 2))).hi() <= -0.5);
    CHECK(range(Div(T(-1.0), over(0, 2))).lo() == -kInf);
    CHECK(range(Div(over(-1, 1), over(0, 2))).lo() == -kInf);  // 0/0 is NaN
    CHECK(range(Div(T(1.0), over(-2, 0))).isUnbounded());
}

TEST_CASE("partial intervals: construction, containment, printing", "[vm][partial]") {
    const Interval p = Interval::Extended(0, kInf);
    CHECK(p.isUnbounded());
    CHECK(p.contains(kInf));
    CHECK(p.contains(kNaN));
    CHECK(p.contains(0));
    CHECK_FALSE(p.contains(-1));
    CHECK_FALSE(p.contains(-kInf));
    CHECK(p.toString() == "[0, inf] or NaN");
    CHECK(Interval::Unbounded().toString() == "unbounded");
    CHECK_FALSE(Interval::Extended(1, 2).isUnbounded());
    CHECK(Interval::Extended(kNaN, 2).lo() == -kInf);
    CHECK(Interval::Extended(3, 2).hi() == kInf);
    CHECK(Interval::Extended(kInf, kInf).lo() == -kInf);
    CHECK((-p).hi() == 0);
    CHECK((-p).lo() == -kInf);
    CHECK(Hull(p, Interval(-1, 1)).lo() == -1);
    // Arithmetic that could lose the side gives Unbounded, never a wrong side.
    CHECK((p + Interval(1)).toString() == "unbounded");
    CHECK(sin(p).toString() == "unbounded");
    CHECK(sqr(-p).toString() == "unbounded");
}
