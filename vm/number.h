// vm/number.h: the Number concept: what the interpreter (and every templated built-in or base
// surface) may ask of a number type, and nothing more.
// Owns the concept, the double overloads that make double a Number (double is the scalar
// semantics every other type bounds: sqr(x) = x*x, sqrt/exp/log/sin/cos/pow = std's, abs =
// std::fabs, sign in {-1, 0, 1}, IEEE division), and NumberTraits for every type the VM is
// instantiated on. To add a number type: give it these functions as free functions with the same
// names (found by ADL), a NumberTraits specialisation and a static_assert below.
// Include this header, not vm/dual.h: Dual<double> needs the double overloads declared first.
#pragma once

#include <cmath>
#include <concepts>
#include <cstdio>
#include <limits>
#include <string>

#include "vm/affine.h"
#include "vm/interval.h"

namespace affray::vm {

// The scalar semantics of double are std's: make them visible to unqualified calls made inside
// affray::vm, where the Interval/Affine/Dual overloads would otherwise hide them.
using std::abs;
using std::cos;
using std::exp;
using std::log;
using std::pow;
using std::sin;
using std::sqrt;

/// x*x.
inline double sqr(double x) { return x * x; }
/// -1, 0 or 1 (a signed zero stays as it is; NaN stays NaN).
inline double sign(double x) { return x > 0 ? 1.0 : x < 0 ? -1.0 : x; }
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
#include "vm/dual.h"

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
struct NumberTraits<Dual<Interval>> {
    static constexpr const char* kName = "dual-interval";
    static constexpr bool kHasDerivatives = true;
};

/// What the interpreter uses: construction from a double constant, copies, arithmetic (also
/// mixed with double on either side), the built-in functions, derivatives (the "unknown" value
/// for types without them), the range of a value, and the traits.
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
                     { abs(a) } -> std::same_as<T>;
                     { sign(a) } -> std::same_as<T>;
                     { pow(a, b) } -> std::same_as<T>;
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
static_assert(Number<Dual<double>>);
static_assert(Number<Dual<Affine>>);
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

}  // namespace affray::vm
