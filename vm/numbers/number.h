// vm/numbers/number.h: the Number concept: what the interpreter (and every templated built-in or base
// surface) may ask of a number type, and nothing more.
// Owns the concept, the double overloads that make double a Number (double is the scalar
// semantics every other type bounds: sqr(x) = x*x, exp/log/sin/cos/tan/floor/ceil/round/asin/acos/
// atan/atan2 = std's, abs = std::fabs, sign in {-1, 0, 1}, Min/Max = std::fmin/fmax with the
// first operand on a tie (-0, +0); three rules are the shading language's own, defined where
// C leaves a NaN or a sign to chance (RSL leaves them undefined; OSL makes the same kind of
// choice): sqrt(x < 0) = 0, pow(x < 0, non-integer y) = pow(0, y), and division by a zero
// divisor takes it as +0 (Div). Each keeps a bound finite where the mathematics is: a sqrt in
// the untaken arm of an undecided branch, a quotient by a distance that reaches 0 (issue 12).
// Also NumberTraits for every type the VM is instantiated on.
// Booleans are numbers of the same type: comparisons give 1 (true) or 0 (false), IEEE style (any
// comparison with NaN is false except NotEqual); And/Or/Not read a value as true where it is != 0
// (NaN too, as in C). A bounded type gives the exact 1 or 0 where decided over its whole range and
// a value with range [0, 1] where not; TruthOf says which (Truth, vm/numbers/interval.h), Join(a, b)
// contains both a and b, and Select(c, a, b) (defined once, below) is a, b or their Join.
// To add a number type: give it these functions as free functions with the same names (found by
// ADL), a NumberTraits specialisation and a static_assert below.
// Include this header, not vm/numbers/dual.h: Dual<double> needs the double overloads declared first.
#pragma once

#include <bit>
#include <cmath>
#include <concepts>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <string>

#include "vm/numbers/affine.h"
#include "vm/numbers/interval.h"
#include "vm/numbers/reduced_affine.h"

namespace affray::vm {

// The scalar semantics of double are std's: make them visible to unqualified calls made inside
// affray::vm, where the Interval/Affine/ReducedAffine/Dual overloads would otherwise hide them.
using std::abs;
using std::acos;
using std::asin;
using std::atan;
using std::atan2;
using std::ceil;
using std::cos;
using std::exp;
using std::floor;
using std::log;
using std::pow;
using std::round;
using std::sin;
using std::sqrt;
using std::tan;

/// x*x.
inline double sqr(double x) { return x * x; }
/// The VM's sqrt, pow and division (the Sqrt, Pow, PowRR/RK, Div* opcodes): for double the rules
/// below, for every other type its own sqrt, pow and operator/, which bound these rules.
/// std::sqrt, but 0 for x < 0 (-0 and NaN stay as they are).
inline double Sqrt(double x) { return x < 0 ? 0.0 : std::sqrt(x); }
/// std::pow, but a negative base with a non-integer exponent is taken as +0: Pow(-4, 0.5) = 0,
/// Pow(-4, -0.5) = +inf. An integer exponent (infinities count as integers) keeps std's sign rules.
inline double Pow(double x, double y) { return x < 0 && std::floor(y) != y ? std::pow(0.0, y) : std::pow(x, y); }
/// IEEE division, but a zero divisor is +0 whatever its sign: Div(1, -0) = +inf. A bound whose
/// divisor range is [0, hi] then keeps its finite side (1 / [0, 2] is [0.5, +inf]).
inline double Div(double a, double b) { return a / (b + 0.0); }
template <class T>
T Sqrt(const T& x) {
    return sqrt(x);
}
template <class A, class B>
auto Pow(const A& x, const B& y) {
    return pow(x, y);
}
template <class A, class B>
auto Div(const A& a, const B& b) {
    return a / b;
}
template <class C, class T>
T Select(const C& c, const T& a, const T& b);
/// -1, 0 or 1 (a signed zero stays as it is; NaN stays NaN).
inline double sign(double x) { return x > 0 ? 1.0 : x < 0 ? -1.0 : x; }
/// std::fmin/fmax (a NaN operand gives the other one), and where the operands compare equal (-0
/// and +0) the first one. Written out rather than calling fmin/fmax: C leaves the zero of
/// fmin(-0, +0) open, and GCC, taking fmin and fmax as commutative, may swap the operands of the
/// call, so the scalar VM, Dual<double> and the constant folder gave different zeros.
inline double Min(double a, double b) { return b < a || std::isnan(a) ? b : a; }
inline double Max(double a, double b) { return a < b || std::isnan(a) ? b : a; }
/// 1 or 0; comparisons with NaN are false, except NotEqual.
inline double Less(double a, double b) { return a < b ? 1.0 : 0.0; }
inline double LessEq(double a, double b) { return a <= b ? 1.0 : 0.0; }
inline double Equal(double a, double b) { return a == b ? 1.0 : 0.0; }
inline double NotEqual(double a, double b) { return a != b ? 1.0 : 0.0; }
/// On truth values: != 0 is true, NaN included.
inline double And(double a, double b) { return a != 0 && b != 0 ? 1.0 : 0.0; }
inline double Or(double a, double b) { return a != 0 || b != 0 ? 1.0 : 0.0; }
inline double Not(double a) { return a != 0 ? 0.0 : 1.0; }
/// Never Unknown: a double is one value.
inline Truth TruthOf(double x) { return x != 0 ? Truth::True : Truth::False; }
/// a if a and b are the same double (bit for bit, or both NaN), else NaN: a double cannot hold
/// two values. (The interpreter never joins doubles: TruthOf(double) is never Unknown.)
inline double Join(double a, double b) {
    const bool same = std::bit_cast<uint64_t>(a) == std::bit_cast<uint64_t>(b);
    return same || (std::isnan(a) && std::isnan(b)) ? a : std::numeric_limits<double>::quiet_NaN();
}
/// A double carries no derivatives: the "unknown" value, NaN.
inline double DerivU(double) { return std::numeric_limits<double>::quiet_NaN(); }
inline double DerivV(double) { return std::numeric_limits<double>::quiet_NaN(); }
/// [x, x]; Unbounded for NaN or infinities.
inline Interval RangeOf(double x) { return Interval(x); }
inline bool IsUnbounded(double x) { return !std::isfinite(x); }
inline bool IsExactlyZero(double x) { return x == 0; }
/// Round-trip precision.
inline std::string ToString(double x) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.17g", x);
    return buf;
}

}  // namespace affray::vm

// After the double overloads: Dual<double>'s templates call them unqualified.
#include "vm/numbers/dual.h"

namespace affray::vm {

/// Per-type facts, so that code never tests for a type by name.
template <class T>
struct NumberTraits;

template <>
struct NumberTraits<double> {
    static constexpr const char* kName = "scalar";
    static constexpr bool kHasDerivatives = false;
};
template <>
struct NumberTraits<Interval> {
    static constexpr const char* kName = "interval";
    static constexpr bool kHasDerivatives = false;
};
template <>
struct NumberTraits<Affine> {
    static constexpr const char* kName = "affine";
    static constexpr bool kHasDerivatives = false;
};
template <>
struct NumberTraits<ReducedAffine> {
    static constexpr const char* kName = "reduced";
    static constexpr bool kHasDerivatives = false;
};
template <>
struct NumberTraits<Dual<double>> {
    static constexpr const char* kName = "dual";
    static constexpr bool kHasDerivatives = true;
};
template <>
struct NumberTraits<Dual<Affine>> {
    static constexpr const char* kName = "dual-affine";
    static constexpr bool kHasDerivatives = true;
};
template <>
struct NumberTraits<Dual<ReducedAffine>> {
    static constexpr const char* kName = "dual-reduced";
    static constexpr bool kHasDerivatives = true;
};
template <>
struct NumberTraits<Dual<Interval>> {
    static constexpr const char* kName = "dual-interval";
    static constexpr bool kHasDerivatives = true;
};

/// The value of `c ? a : b` for any number types: a where c is true over its whole range, b where
/// false, a value containing both (Join) where undecided.
template <class C, class T>
T Select(const C& c, const T& a, const T& b) {
    switch (TruthOf(c)) {
        case Truth::True: return a;
        case Truth::False: return b;
        default: return Join(a, b);
    }
}

/// What the interpreter uses: construction from a double constant, copies, arithmetic (also
/// mixed with double on either side), the built-in functions, comparisons and logic as numbers,
/// branches (TruthOf, Join, Select), derivatives (the "unknown" value for types without them),
/// the range of a value, and the traits.
// (clang-format 14 garbles requires-expressions.)
// clang-format off
template <class T>
concept Number = std::copyable<T> && std::convertible_to<double, T> &&
                 requires(T a, T b, double d) {
                     { a + b } -> std::same_as<T>;
                     { a - b } -> std::same_as<T>;
                     { a * b } -> std::same_as<T>;
                     { a / b } -> std::same_as<T>;
                     { -a } -> std::same_as<T>;
                     { a + d } -> std::same_as<T>;
                     { d + a } -> std::same_as<T>;
                     { a - d } -> std::same_as<T>;
                     { d - a } -> std::same_as<T>;
                     { a * d } -> std::same_as<T>;
                     { d * a } -> std::same_as<T>;
                     { a / d } -> std::same_as<T>;
                     { d / a } -> std::same_as<T>;
                     { sqr(a) } -> std::same_as<T>;
                     { sqrt(a) } -> std::same_as<T>;
                     { exp(a) } -> std::same_as<T>;
                     { log(a) } -> std::same_as<T>;
                     { sin(a) } -> std::same_as<T>;
                     { cos(a) } -> std::same_as<T>;
                     { tan(a) } -> std::same_as<T>;
                     { abs(a) } -> std::same_as<T>;
                     { sign(a) } -> std::same_as<T>;
                     { pow(a, b) } -> std::same_as<T>;
                     { floor(a) } -> std::same_as<T>;
                     { ceil(a) } -> std::same_as<T>;
                     { round(a) } -> std::same_as<T>;
                     { asin(a) } -> std::same_as<T>;
                     { acos(a) } -> std::same_as<T>;
                     { atan(a) } -> std::same_as<T>;
                     { atan2(a, b) } -> std::same_as<T>;
                     { Min(a, b) } -> std::same_as<T>;
                     { Max(a, b) } -> std::same_as<T>;
                     { Less(a, b) } -> std::same_as<T>;
                     { LessEq(a, b) } -> std::same_as<T>;
                     { Equal(a, b) } -> std::same_as<T>;
                     { NotEqual(a, b) } -> std::same_as<T>;
                     { And(a, b) } -> std::same_as<T>;
                     { Or(a, b) } -> std::same_as<T>;
                     { Not(a) } -> std::same_as<T>;
                     { TruthOf(a) } -> std::same_as<Truth>;
                     { Join(a, b) } -> std::same_as<T>;
                     { Select(a, a, b) } -> std::same_as<T>;
                     { DerivU(a) } -> std::same_as<T>;
                     { DerivV(a) } -> std::same_as<T>;
                     { RangeOf(a) } -> std::same_as<Interval>;
                     { IsUnbounded(a) } -> std::same_as<bool>;
                     { NumberTraits<T>::kName } -> std::convertible_to<const char*>;
                     { NumberTraits<T>::kHasDerivatives } -> std::convertible_to<bool>;
                 };
// clang-format on

static_assert(Number<double>);
static_assert(Number<Interval>);
static_assert(Number<Affine>);
static_assert(Number<ReducedAffine>);
static_assert(Number<Dual<double>>);
static_assert(Number<Dual<Affine>>);
static_assert(Number<Dual<ReducedAffine>>);
static_assert(Number<Dual<Interval>>);

/// The value part of a number: the number itself, or a dual number's value (its derivatives
/// dropped). Code that bounds or measures results uses it to serve plain and dual types alike.
template <class T>
const T& ValueOf(const T& x) {
    return x;
}
template <class T>
const T& ValueOf(const Dual<T>& x) {
    return x.v;
}

/// A T holding the range r: on a fresh symbol for Affine, so that the bound stays correlated with
/// itself wherever a shader reuses it; in the error term for ReducedAffine; the value r with
/// unknown (Unbounded) derivatives for a Dual. Unbounded r gives the unknown value, derivatives
/// included; a double, which holds one value, is r if r is a point, else NaN (the paths that
/// spread a range never run on a double).
template <class T>
struct Spread;
template <>
struct Spread<double> {
    static double Of(const Interval& r) {
        return r.isPoint() && !r.isUnbounded() ? r.lo() : std::numeric_limits<double>::quiet_NaN();
    }
};
template <>
struct Spread<Interval> {
    static Interval Of(const Interval& r) { return r; }
};
template <>
struct Spread<Affine> {
    static Affine Of(const Interval& r) { return Affine::FromInterval(r); }
};
template <>
struct Spread<ReducedAffine> {
    static ReducedAffine Of(const Interval& r) { return ReducedAffine::FromInterval(r); }
};
template <class B>
struct Spread<Dual<B>> {
    static Dual<B> Of(const Interval& r) {
        const B unknown = Spread<B>::Of(Interval::Unbounded());
        return {Spread<B>::Of(r), unknown, unknown};
    }
};
template <class T>
T SpreadOf(const Interval& r) {
    return Spread<T>::Of(r);
}

}  // namespace affray::vm
