// vm/numbers/dual.h: dual numbers, for exact derivatives of shader outputs with respect to the surface
// parameters u and v (forward-mode automatic differentiation).
// Owns the template Dual<T>: a value and its two partial derivatives, composed with any number
// type T (Dual<double> for shading normals, Dual<Affine>, Dual<ReducedAffine> and Dual<Interval>
// for bounds on derivatives). Every operation applies the chain rule once, in unqualified calls on
// T, so it is written once for all T (as OSL's dual.h does); the derivatives are then bounded (or
// not) exactly as T bounds the same expressions. Nothing here may special-case a T: type
// differences go in T's own functions.
// A chain-rule factor times an exactly zero derivative is exactly zero (ChainScale), even where
// the factor is infinite at the edge of a domain (sqrt at 0), instead of IEEE's inf*0 = NaN.
// Piecewise-constant functions (floor, ceil, round, comparisons, logic) have zero derivatives, the
// scalar derivative almost everywhere; Min and Max take the derivatives of the operand they pick,
// and their Join when T cannot decide which (Select's rule, vm/numbers/number.h).
// Include vm/numbers/number.h, not this file: Dual<double> needs the double overloads (sqr, sign,
// IsExactlyZero, ToString, the comparisons, TruthOf, Join) that number.h declares before
// including it.
// Sources: Piponi, "Automatic differentiation, C++ templates and photogrammetry" (JGT 2004);
// Griewank & Walther, "Evaluating Derivatives" (2008), ch. 3 (forward mode).
#pragma once

#include <cmath>
#include <string>

#include "vm/numbers/interval.h"

namespace affray::vm {

template <class T>
struct Dual {
    T v;   ///< the value
    T du;  ///< d value / du
    T dv;  ///< d value / dv

    /// The constant 0.
    Dual() : v(0.0), du(0.0), dv(0.0) {}
    /// A constant: zero derivatives.
    Dual(double c) : v(c), du(0.0), dv(0.0) {}  // NOLINT: implicit by design (Number API)
    Dual(T value, T dValueDu, T dValueDv) : v(value), du(dValueDu), dv(dValueDv) {}
};

template <class T>
Dual<T> operator-(const Dual<T>& a) {
    return {-a.v, -a.du, -a.dv};
}
template <class T>
Dual<T> operator+(const Dual<T>& a, const Dual<T>& b) {
    return {a.v + b.v, a.du + b.du, a.dv + b.dv};
}
template <class T>
Dual<T> operator-(const Dual<T>& a, const Dual<T>& b) {
    return {a.v - b.v, a.du - b.du, a.dv - b.dv};
}
/// (ab)' = a'b + ab'
template <class T>
Dual<T> operator*(const Dual<T>& a, const Dual<T>& b) {
    return {a.v * b.v, a.du * b.v + a.v * b.du, a.dv * b.v + a.v * b.dv};
}
/// (a/b)' = (a' - (a/b) b') / b, every quotient by T's Div (a zero divisor is +0).
template <class T>
Dual<T> operator/(const Dual<T>& a, const Dual<T>& b) {
    T q = Div(a.v, b.v);
    return {q, Div(a.du - q * b.du, b.v), Div(a.dv - q * b.dv, b.v)};
}

template <class T>
Dual<T> operator+(const Dual<T>& a, double c) {
    return {a.v + c, a.du, a.dv};
}
template <class T>
Dual<T> operator+(double c, const Dual<T>& a) {
    return {c + a.v, a.du, a.dv};
}
template <class T>
Dual<T> operator-(const Dual<T>& a, double c) {
    return {a.v - c, a.du, a.dv};
}
template <class T>
Dual<T> operator-(double c, const Dual<T>& a) {
    return {c - a.v, -a.du, -a.dv};
}
template <class T>
Dual<T> operator*(const Dual<T>& a, double c) {
    return {a.v * c, a.du * c, a.dv * c};
}
template <class T>
Dual<T> operator*(double c, const Dual<T>& a) {
    return {c * a.v, c * a.du, c * a.dv};
}
template <class T>
Dual<T> operator/(const Dual<T>& a, double c) {
    return {Div(a.v, c), Div(a.du, c), Div(a.dv, c)};
}
/// (c/b)' = -(c/b) b' / b
template <class T>
Dual<T> operator/(double c, const Dual<T>& b) {
    T q = Div(c, b.v);
    T k = Div(-q, b.v);
    return {q, k * b.du, k * b.dv};
}

/// k a' for the chain rule, but exactly 0 where a' is exactly 0 (a is locally constant in that
/// direction): an infinite k at the edge of a domain, as in sqrt(max(0, x)) where x < 0, then
/// gives 0 rather than inf*0 = NaN. Sound for bounded T: T's a' exactly 0 means every scalar a'
/// is 0, and then the scalar result is 0 too.
template <class T>
T ChainScale(const T& k, const T& aPrime) {
    return IsExactlyZero(aPrime) ? T(0.0) : k * aPrime;
}

/// (a^2)' = 2a a'
template <class T>
Dual<T> sqr(const Dual<T>& a) {
    T k = a.v * 2.0;
    return {sqr(a.v), k * a.du, k * a.dv};
}
/// sqrt(a)' = a' / (2 sqrt(a)): at a = 0 whatever T gives for 0.5/0 (inf, Unbounded), unless a'
/// is exactly 0 (ChainScale); 0 where a < 0 (the VM's sqrt is 0 there).
template <class T>
Dual<T> sqrt(const Dual<T>& a) {
    const T zero(0.0);
    T s = Sqrt(a.v);
    T k = Select(Less(a.v, zero), zero, Div(0.5, s));
    return {s, ChainScale(k, a.du), ChainScale(k, a.dv)};
}
template <class T>
Dual<T> exp(const Dual<T>& a) {
    using std::exp;
    T e = exp(a.v);
    return {e, e * a.du, e * a.dv};
}
template <class T>
Dual<T> log(const Dual<T>& a) {
    using std::log;
    return {log(a.v), a.du / a.v, a.dv / a.v};
}
template <class T>
Dual<T> sin(const Dual<T>& a) {
    using std::cos, std::sin;
    T c = cos(a.v);
    return {sin(a.v), c * a.du, c * a.dv};
}
template <class T>
Dual<T> cos(const Dual<T>& a) {
    using std::cos, std::sin;
    T s = -sin(a.v);
    return {cos(a.v), s * a.du, s * a.dv};
}
/// tan(a)' = a' / cos^2(a) = a' (1 + tan^2(a)), which reuses tan(a); exactly 0 where a' is
/// (ChainScale: a bound of tan may be Unbounded).
template <class T>
Dual<T> tan(const Dual<T>& a) {
    using std::tan;
    T t = tan(a.v);
    T k = 1.0 + sqr(t);
    return {t, ChainScale(k, a.du), ChainScale(k, a.dv)};
}
/// |a|' = sign(a) a'
template <class T>
Dual<T> abs(const Dual<T>& a) {
    using std::abs;
    T s = sign(a.v);
    return {abs(a.v), s * a.du, s * a.dv};
}
/// Piecewise constant: zero derivatives.
template <class T>
Dual<T> sign(const Dual<T>& a) {
    return {sign(a.v), T(0.0), T(0.0)};
}
/// (a^b)' = b a^(b-1) a' + a^b log(a) b'. The log term is left out where b' is exactly zero, so a
/// constant exponent never takes the log of a negative or zero base; the first term likewise
/// where a' is (ChainScale: pow(max(0, x), 0.5) at x < 0). Where a < 0 the VM's pow is constant
/// in a unless b is an integer, and its log term is taken as 0 (pow(0, b) for a non-integer b;
/// the derivative in b of a negative base to an integer power does not exist).
template <class T>
Dual<T> pow(const Dual<T>& a, const Dual<T>& b) {
    using std::log;
    const T zero(0.0);
    const T negative = Less(a.v, zero);
    T p = Pow(a.v, b.v);
    T k = b.v * Pow(a.v, b.v - 1.0);
    k = Select(negative, Select(Equal(floor(b.v), b.v), k, zero), k);
    T du = ChainScale(k, a.du), dv = ChainScale(k, a.dv);
    bool zu = IsExactlyZero(b.du), zv = IsExactlyZero(b.dv);
    if (!zu || !zv) {
        T pl = Select(negative, zero, p * log(a.v));
        if (!zu) du = du + pl * b.du;
        if (!zv) dv = dv + pl * b.dv;
    }
    return {p, du, dv};
}
template <class T>
Dual<T> pow(const Dual<T>& a, double b) {
    return pow(a, Dual<T>(b));
}
template <class T>
Dual<T> pow(double a, const Dual<T>& b) {
    return pow(Dual<T>(a), b);
}

/// Piecewise constant: zero derivatives.
template <class T>
Dual<T> floor(const Dual<T>& a) {
    using std::floor;
    return {floor(a.v), T(0.0), T(0.0)};
}
template <class T>
Dual<T> ceil(const Dual<T>& a) {
    using std::ceil;
    return {ceil(a.v), T(0.0), T(0.0)};
}
template <class T>
Dual<T> round(const Dual<T>& a) {
    using std::round;
    return {round(a.v), T(0.0), T(0.0)};
}
/// asin(a)' = a' / sqrt(1 - a^2) (inf or Unbounded at |a| = 1 unless a' is exactly 0).
template <class T>
Dual<T> asin(const Dual<T>& a) {
    using std::asin;
    T k = Div(1.0, Sqrt(1.0 - sqr(a.v)));
    return {asin(a.v), ChainScale(k, a.du), ChainScale(k, a.dv)};
}
/// acos(a)' = -a' / sqrt(1 - a^2).
template <class T>
Dual<T> acos(const Dual<T>& a) {
    using std::acos;
    T k = Div(-1.0, Sqrt(1.0 - sqr(a.v)));
    return {acos(a.v), ChainScale(k, a.du), ChainScale(k, a.dv)};
}
/// atan(a)' = a' / (1 + a^2).
template <class T>
Dual<T> atan(const Dual<T>& a) {
    using std::atan;
    T k = 1.0 / (1.0 + sqr(a.v));
    return {atan(a.v), k * a.du, k * a.dv};
}
/// The value `v` with the derivatives f(v) where `pick` is True, g(v) where False, and the Join of
/// both where Unknown (Select's rule, for a bound that cannot decide which formula a point uses).
template <class T, class F, class G>
Dual<T> WithDerivativesBy(const T& v, Truth pick, F f, G g) {
    if (pick == Truth::True) return f(v);
    if (pick == Truth::False) return g(v);
    return Join(f(v), g(v));
}
/// atan2(y, x)' = (x y' - y x') / (x^2 + y^2) where m = max(|x|, |y|) lies in [2^-480, 2^511],
/// so that x^2 + y^2 neither overflows nor falls below kUnderflowLimit. Elsewhere (x = 1e300, or
/// x and y 1e-200) the same divided through by the larger square, as hypot scales: with q = y/x,
/// (y' - q x') / (x (1 + q^2)) for |y| <= |x|; with q = x/y, (q y' - x') / (y (1 + q^2))
/// otherwise. Each choice is decided on T, so every point of a bound takes the formula its double
/// takes, or the bound joins both.
template <class T>
Dual<T> atan2(const Dual<T>& y, const Dual<T>& x) {
    using std::abs, std::atan2;
    const T ax = abs(x.v), ay = abs(y.v), m = Max(ax, ay);
    const Truth plain = TruthOf(And(LessEq(T(0x1p-480), m), LessEq(m, T(0x1p511))));
    auto bySquares = [&](const T& v) -> Dual<T> {
        const T r2 = sqr(x.v) + sqr(y.v);
        return {v, (x.v * y.du - y.v * x.du) / r2, (x.v * y.dv - y.v * x.dv) / r2};
    };
    auto overX = [&](const T& v) -> Dual<T> {  // |y| <= |x|
        const T q = y.v / x.v, k = 1.0 / (x.v * (1.0 + sqr(q)));
        return {v, (y.du - q * x.du) * k, (y.dv - q * x.dv) * k};
    };
    auto overY = [&](const T& v) -> Dual<T> {
        const T q = x.v / y.v, k = 1.0 / (y.v * (1.0 + sqr(q)));
        return {v, (q * y.du - x.du) * k, (q * y.dv - x.dv) * k};
    };
    auto scaled = [&](const T& v) { return WithDerivativesBy(v, TruthOf(LessEq(ay, ax)), overX, overY); };
    return WithDerivativesBy(atan2(y.v, x.v), plain, bySquares, scaled);
}
/// Componentwise: a value and derivatives that contain both operands' (vm/numbers/number.h's Join).
template <class T>
Dual<T> Join(const Dual<T>& a, const Dual<T>& b) {
    return {Join(a.v, b.v), Join(a.du, b.du), Join(a.dv, b.dv)};
}
/// The value `v` with a's derivatives where `pickA` is True, b's where False, their Join where
/// Unknown.
template <class T>
Dual<T> WithDerivativesOf(const T& v, Truth pickA, const Dual<T>& a, const Dual<T>& b) {
    if (pickA == Truth::True) return {v, a.du, a.dv};
    if (pickA == Truth::False) return {v, b.du, b.dv};
    return {v, Join(a.du, b.du), Join(a.dv, b.dv)};
}
/// std::fmin's value (T's Min), the derivatives of a where a <= b. (Where b is NaN fmin returns a
/// but the derivatives are b's: a NaN derivative next to a defined value, never a wrong number.)
template <class T>
Dual<T> Min(const Dual<T>& a, const Dual<T>& b) {
    return WithDerivativesOf(Min(a.v, b.v), TruthOf(LessEq(a.v, b.v)), a, b);
}
/// std::fmax's value, the derivatives of a where a >= b.
template <class T>
Dual<T> Max(const Dual<T>& a, const Dual<T>& b) {
    return WithDerivativesOf(Max(a.v, b.v), TruthOf(LessEq(b.v, a.v)), a, b);
}
/// Comparisons and logic on the values: 1 or 0 (or T's undecided value), zero derivatives.
template <class T>
Dual<T> Less(const Dual<T>& a, const Dual<T>& b) {
    return {Less(a.v, b.v), T(0.0), T(0.0)};
}
template <class T>
Dual<T> LessEq(const Dual<T>& a, const Dual<T>& b) {
    return {LessEq(a.v, b.v), T(0.0), T(0.0)};
}
template <class T>
Dual<T> Equal(const Dual<T>& a, const Dual<T>& b) {
    return {Equal(a.v, b.v), T(0.0), T(0.0)};
}
template <class T>
Dual<T> NotEqual(const Dual<T>& a, const Dual<T>& b) {
    return {NotEqual(a.v, b.v), T(0.0), T(0.0)};
}
template <class T>
Dual<T> And(const Dual<T>& a, const Dual<T>& b) {
    return {And(a.v, b.v), T(0.0), T(0.0)};
}
template <class T>
Dual<T> Or(const Dual<T>& a, const Dual<T>& b) {
    return {Or(a.v, b.v), T(0.0), T(0.0)};
}
template <class T>
Dual<T> Not(const Dual<T>& a) {
    return {Not(a.v), T(0.0), T(0.0)};
}
/// The truth of the value.
template <class T>
Truth TruthOf(const Dual<T>& a) {
    return TruthOf(a.v);
}

// Number API (vm/numbers/number.h).
/// The u-derivative as a value of its own (its own derivatives are not tracked: zero).
template <class T>
Dual<T> DerivU(const Dual<T>& a) {
    return {a.du, T(0.0), T(0.0)};
}
template <class T>
Dual<T> DerivV(const Dual<T>& a) {
    return {a.dv, T(0.0), T(0.0)};
}
template <class T>
Interval RangeOf(const Dual<T>& a) {
    return RangeOf(a.v);
}
/// True if the value or either derivative is unbounded.
template <class T>
bool IsUnbounded(const Dual<T>& a) {
    return IsUnbounded(a.v) || IsUnbounded(a.du) || IsUnbounded(a.dv);
}
template <class T>
bool IsExactlyZero(const Dual<T>& a) {
    return IsExactlyZero(a.v) && IsExactlyZero(a.du) && IsExactlyZero(a.dv);
}
/// "(v; du; dv)".
template <class T>
std::string ToString(const Dual<T>& a) {
    return "(" + ToString(a.v) + "; " + ToString(a.du) + "; " + ToString(a.dv) + ")";
}

}  // namespace affray::vm
