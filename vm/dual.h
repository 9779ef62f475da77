// vm/dual.h: dual numbers, for exact derivatives of shader outputs with respect to the surface
// parameters u and v (forward-mode automatic differentiation).
// Owns the template Dual<T>: a value and its two partial derivatives, composed with any number
// type T (Dual<double> for shading normals, Dual<Affine> and Dual<Interval> for bounds on
// derivatives). Every operation applies the chain rule once, in unqualified calls on T, so it is
// written once for all T (as OSL's dual.h does); the derivatives are then bounded (or not) exactly
// as T bounds the same expressions. Nothing here may special-case a T: type differences go in
// T's own functions.
// Include vm/number.h, not this file: Dual<double> needs the double overloads (sqr, sign,
// IsExactlyZero, ToString) that number.h declares before including it.
// Sources: Piponi, "Automatic differentiation, C++ templates and photogrammetry" (JGT 2004);
// Griewank & Walther, "Evaluating Derivatives" (2008), ch. 3 (forward mode).
#pragma once

#include <cmath>
#include <string>

#include "vm/interval.h"

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
/// (a/b)' = (a' - (a/b) b') / b
template <class T>
Dual<T> operator/(const Dual<T>& a, const Dual<T>& b) {
    T q = a.v / b.v;
    return {q, (a.du - q * b.du) / b.v, (a.dv - q * b.dv) / b.v};
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
    return {a.v / c, a.du / c, a.dv / c};
}
/// (c/b)' = -(c/b) b' / b
template <class T>
Dual<T> operator/(double c, const Dual<T>& b) {
    T q = c / b.v;
    T k = -q / b.v;
    return {q, k * b.du, k * b.dv};
}

/// (a^2)' = 2a a'
template <class T>
Dual<T> sqr(const Dual<T>& a) {
    T k = a.v * 2.0;
    return {sqr(a.v), k * a.du, k * a.dv};
}
/// sqrt(a)' = a' / (2 sqrt(a)): at a = 0 whatever T gives for 0.5/0 (inf, Unbounded).
template <class T>
Dual<T> sqrt(const Dual<T>& a) {
    using std::sqrt;
    T s = sqrt(a.v);
    T k = 0.5 / s;
    return {s, k * a.du, k * a.dv};
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
/// constant exponent never takes the log of a negative or zero base.
template <class T>
Dual<T> pow(const Dual<T>& a, const Dual<T>& b) {
    using std::log, std::pow;
    T p = pow(a.v, b.v);
    T k = b.v * pow(a.v, b.v - 1.0);
    T du = k * a.du, dv = k * a.dv;
    bool zu = IsExactlyZero(b.du), zv = IsExactlyZero(b.dv);
    if (!zu || !zv) {
        T pl = p * log(a.v);
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

// Number API (vm/number.h).
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
