// vm/interval.h: interval arithmetic, the simplest bounded number type of the VM.
// Owns class Interval and its free functions (the Number API for intervals). Every result contains
// the double result of the same operation (vm/number.h's scalar semantics) at every point of the
// operands, including the rounding of that double computation: bounds round outward (vm/rounding.h)
// and transcendental bounds allow kLibmRel of slack. Anything that can be NaN or infinite somewhere
// in the operands is the explicit Unbounded value, and Unbounded propagates through every function.
// To add a function: derive its bounds from monotone pieces or exact extremum analysis, round
// outward, and add its containment test to tests/vm/interval_test.cpp.
// Sources: Moore, "Interval Analysis" (1966); Stolfi & de Figueiredo, "Self-Validated Numerical
// Methods and Applications" (1997), ch. 2.
#pragma once

#include <string>

#include "vm/rounding.h"

namespace affray::vm {

class Interval {
  public:
    /// [0, 0].
    Interval() = default;
    /// The point [c, c]; NaN or infinite c gives Unbounded.
    Interval(double c) : m_lo(c), m_hi(c) {  // NOLINT: implicit by design (Number API)
        if (!std::isfinite(c)) *this = Unbounded();
    }
    /// [lo, hi]; a NaN or infinite bound, or lo > hi, gives Unbounded.
    Interval(double lo, double hi) : m_lo(lo), m_hi(hi) {
        if (!(lo <= hi && lo >= -kMaxFinite && hi <= kMaxFinite)) *this = Unbounded();
    }
    /// The explicit "unknown" value: contains every double, NaN and infinities included.
    static Interval Unbounded() {
        Interval r;
        r.m_lo = -kInfinity;
        r.m_hi = kInfinity;
        return r;
    }

    double lo() const { return m_lo; }
    double hi() const { return m_hi; }
    /// The midpoint, rounded to nearest (no overflow); 0 for Unbounded.
    double mid() const;
    /// A radius r with [mid() - r, mid() + r] containing the interval (rounded up).
    double radius() const;
    /// hi - lo rounded up.
    double width() const { return SubUp(m_hi, m_lo); }
    bool isUnbounded() const { return !(m_hi <= kMaxFinite); }
    bool isPoint() const { return m_lo == m_hi; }
    /// NaN and infinities are contained only in Unbounded.
    bool contains(double x) const { return isUnbounded() || (x >= m_lo && x <= m_hi); }
    /// "[lo, hi]" with round-trip precision, or "unbounded".
    std::string toString() const;

    friend Interval operator-(const Interval& a) { return FromBounds(-a.m_hi, -a.m_lo); }
    friend Interval operator+(const Interval& a, const Interval& b) {
        return FromBounds(AddDown(a.m_lo, b.m_lo), AddUp(a.m_hi, b.m_hi));
    }
    friend Interval operator-(const Interval& a, const Interval& b) {
        return FromBounds(SubDown(a.m_lo, b.m_hi), SubUp(a.m_hi, b.m_lo));
    }
    friend Interval operator*(const Interval& a, const Interval& b);
    /// Unbounded when b contains 0.
    friend Interval operator/(const Interval& a, const Interval& b);
    friend Interval operator+(const Interval& a, double b) { return a + Interval(b); }
    friend Interval operator+(double a, const Interval& b) { return Interval(a) + b; }
    friend Interval operator-(const Interval& a, double b) { return a - Interval(b); }
    friend Interval operator-(double a, const Interval& b) { return Interval(a) - b; }
    friend Interval operator*(const Interval& a, double b) { return a * Interval(b); }
    friend Interval operator*(double a, const Interval& b) { return Interval(a) * b; }
    friend Interval operator/(const Interval& a, double b) { return a / Interval(b); }
    friend Interval operator/(double a, const Interval& b) { return Interval(a) / b; }

    /// x*x, never below 0.
    friend Interval sqr(const Interval& x);
    /// Unbounded if x has negative values.
    friend Interval sqrt(const Interval& x);
    /// Unbounded on overflow.
    friend Interval exp(const Interval& x);
    /// Unbounded unless x > 0.
    friend Interval log(const Interval& x);
    /// Exact extremum analysis within a period; [-1, 1] past 2*pi or beyond |x| = 1e8.
    friend Interval sin(const Interval& x);
    friend Interval cos(const Interval& x);
    friend Interval abs(const Interval& x);
    /// The hull of the signs (-1, 0, 1) of the values.
    friend Interval sign(const Interval& x);
    /// x^y as std::pow: a constant integer y allows negative x (and, if y < 0, x must exclude 0);
    /// otherwise x >= 0 (x > 0 if y can be <= 0). Unbounded elsewhere and on overflow.
    friend Interval pow(const Interval& x, const Interval& y);
    /// The smallest interval containing both.
    friend Interval Hull(const Interval& a, const Interval& b) {
        if (a.isUnbounded() || b.isUnbounded()) return Unbounded();
        return Interval(std::fmin(a.m_lo, b.m_lo), std::fmax(a.m_hi, b.m_hi));
    }

    // Number API (vm/number.h).
    /// An interval carries no derivatives: the "unknown" value.
    friend Interval DerivU(const Interval&) { return Unbounded(); }
    friend Interval DerivV(const Interval&) { return Unbounded(); }
    friend Interval RangeOf(const Interval& x) { return x; }
    friend bool IsUnbounded(const Interval& x) { return x.isUnbounded(); }
    friend bool IsExactlyZero(const Interval& x) { return x.m_lo == 0 && x.m_hi == 0; }
    friend std::string ToString(const Interval& x) { return x.toString(); }

  private:
    /// Like Interval(lo, hi), for bounds already rounded outward.
    static Interval FromBounds(double lo, double hi) { return Interval(lo, hi); }

    double m_lo = 0;
    double m_hi = 0;
};

}  // namespace affray::vm
