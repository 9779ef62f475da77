// vm/numbers/interval.h: interval arithmetic, the simplest bounded number type of the VM.
// Owns class Interval and its free functions (the Number API for intervals). Every result contains
// the double result of the same operation (vm/numbers/number.h's scalar semantics) at every point of the
// operands, including the rounding of that double computation: bounds round outward (vm/numbers/rounding.h)
// and transcendental bounds allow kLibmRel of slack. Anything that can be NaN or infinite somewhere
// in the operands is unbounded: the explicit Unbounded value [-inf, +inf], or a *partial* one
// (Extended) whose range [lo, hi] has an infinite end and which may also be NaN, e.g. [0, +inf]
// for max(anything, 0). Most functions take any unbounded operand as Unbounded; those whose
// scalar result keeps a side whatever their operand (Min, Max, abs, log and exp near their
// limits, negation, Hull) keep the finite side, so that a later clamp (min(max(x, 0), 1), where
// fmin/fmax drop a NaN operand) makes the value bounded again (issue 12).
// Also owns enum Truth (the answer of TruthOf for every number type, here because every number
// header includes this one) and its three-valued And/Or/Not. Comparisons and logic return the
// point 1 or 0 where decided over the whole operand ranges, else [0, 1] (tests/vm/branch_test.cpp).
// To add a function: derive its bounds from monotone pieces or exact extremum analysis, round
// outward, and add its containment test to tests/vm/numbers/interval_test.cpp.
// Sources: Moore, "Interval Analysis" (1966); Stolfi & de Figueiredo, "Self-Validated Numerical
// Methods and Applications" (1997), ch. 2.
#pragma once

#include <string>

#include "vm/numbers/rounding.h"

namespace affray::vm {

/// The truth of a condition (a number, true where != 0, NaN included, as in C) over every value
/// a bounded number stands for: True for all of them, False for all (the number is exactly 0),
/// or Unknown. A double is never Unknown.
enum class Truth { False, True, Unknown };

/// Three-valued (Kleene) logic: decided wherever the decided operands alone decide.
inline Truth TruthAnd(Truth a, Truth b) {
    if (a == Truth::False || b == Truth::False) return Truth::False;
    return a == Truth::True && b == Truth::True ? Truth::True : Truth::Unknown;
}
inline Truth TruthOr(Truth a, Truth b) {
    if (a == Truth::True || b == Truth::True) return Truth::True;
    return a == Truth::False && b == Truth::False ? Truth::False : Truth::Unknown;
}
inline Truth TruthNot(Truth a) {
    return a == Truth::True ? Truth::False : a == Truth::False ? Truth::True : Truth::Unknown;
}

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
    /// [lo, hi] where lo may be -inf and hi +inf: a finite [lo, hi] is the usual interval; one
    /// with an infinite end is unbounded (*partial*: it stands for [lo, hi] and NaN). NaN bounds,
    /// lo > hi, lo = +inf or hi = -inf give Unbounded.
    static Interval Extended(double lo, double hi) {
        if (!(lo <= hi && lo < kInfinity && hi > -kInfinity)) return Unbounded();
        Interval r;
        r.m_lo = lo;
        r.m_hi = hi;
        return r;
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
    /// Unbounded or partial: an infinite end (the value may then also be NaN).
    bool isUnbounded() const { return !(m_hi <= kMaxFinite && m_lo >= -kMaxFinite); }
    bool isPoint() const { return m_lo == m_hi; }
    /// NaN is contained only in an unbounded interval, an infinity only in one with that end.
    bool contains(double x) const { return std::isnan(x) ? isUnbounded() : x >= m_lo && x <= m_hi; }
    /// "[lo, hi]" with round-trip precision, "unbounded", or "[lo, inf] or NaN" (partial).
    std::string toString() const;

    /// Exact; a partial interval stays partial.
    friend Interval operator-(const Interval& a) { return Extended(-a.m_hi, -a.m_lo); }
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
    /// [exp(lo), +inf] (partial) on overflow.
    friend Interval exp(const Interval& x);
    /// [log(lo), log(hi)] for x > 0; [-inf, log(hi)] (partial: log(0) = -inf, log(x < 0) = NaN)
    /// for a bounded x with hi > 0; else Unbounded.
    friend Interval log(const Interval& x);
    /// Exact extremum analysis within a period; [-1, 1] past 2*pi or beyond |x| = 1e8.
    friend Interval sin(const Interval& x);
    friend Interval cos(const Interval& x);
    /// Increasing between poles: [tan(lo), tan(hi)] where no pole k*pi + pi/2 may lie in x, else
    /// Unbounded (as past |x| = 1e8, except for a point).
    friend Interval tan(const Interval& x);
    /// Partial operands keep their finite side: abs([-inf, -2]) = [2, +inf].
    friend Interval abs(const Interval& x);
    /// The hull of the signs (-1, 0, 1) of the values.
    friend Interval sign(const Interval& x);
    /// x^y as std::pow: a constant integer y allows negative x (and, if y < 0, x must exclude 0);
    /// otherwise x >= 0 (x > 0 if y can be <= 0). Unbounded elsewhere and on overflow.
    friend Interval pow(const Interval& x, const Interval& y);
    /// The smallest interval containing both (partial if either is).
    friend Interval Hull(const Interval& a, const Interval& b) {
        return Extended(std::fmin(a.m_lo, b.m_lo), std::fmax(a.m_hi, b.m_hi));
    }

    // Rounding, inverse trigonometry, min/max, comparisons and logic (interval.cpp).
    /// [f(lo), f(hi)]: std::floor, ceil and round (half away from zero) are monotone and exact.
    friend Interval floor(const Interval& x);
    friend Interval ceil(const Interval& x);
    friend Interval round(const Interval& x);
    /// Monotone; Unbounded if x leaves [-1, 1] (the scalar result is NaN there).
    friend Interval asin(const Interval& x);
    friend Interval acos(const Interval& x);
    friend Interval atan(const Interval& x);
    /// std::atan2(y, x) by quadrants: monotone in y and x away from the branch cut; [-pi, pi]
    /// (rounded outward) wherever y can be 0 and x <= 0 (a signed zero reaches both -pi and pi).
    friend Interval atan2(const Interval& y, const Interval& x);
    /// std::fmin and std::fmax, endpoint by endpoint; an unbounded operand may be NaN, where the
    /// result is the other operand: min(Unbounded, [0, 1]) = [-inf, 1] (partial),
    /// min([0, +inf], [0, 1]) = [0, 1] (bounded again).
    friend Interval Min(const Interval& a, const Interval& b);
    friend Interval Max(const Interval& a, const Interval& b);
    /// The point 1 (true) or 0 (false) where decided for every pair of values, else [0, 1];
    /// always [0, 1] when an operand is Unbounded (it may be NaN).
    friend Interval Less(const Interval& a, const Interval& b);
    friend Interval LessEq(const Interval& a, const Interval& b);
    friend Interval Equal(const Interval& a, const Interval& b);
    friend Interval NotEqual(const Interval& a, const Interval& b);
    /// Logic on truth values (TruthOf of the operands): 1, 0 or [0, 1].
    friend Interval And(const Interval& a, const Interval& b);
    friend Interval Or(const Interval& a, const Interval& b);
    friend Interval Not(const Interval& a);
    /// True if the range excludes 0, False if it is exactly [0, 0], else (Unbounded too) Unknown.
    friend Truth TruthOf(const Interval& x) {
        if (x.isUnbounded()) return Truth::Unknown;
        if (x.m_lo > 0 || x.m_hi < 0) return Truth::True;
        return x.m_lo == 0 && x.m_hi == 0 ? Truth::False : Truth::Unknown;
    }
    /// A value containing both (for an undecided condition): the hull.
    friend Interval Join(const Interval& a, const Interval& b) { return Hull(a, b); }
    /// 1, 0 or [0, 1].
    static Interval FromTruth(Truth t) {
        if (t == Truth::Unknown) return Interval(0.0, 1.0);
        return Interval(t == Truth::True ? 1.0 : 0.0);
    }

    // Number API (vm/numbers/number.h).
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

/// sin (isCos false) or cos over [a, b] (finite, a <= b) from glibc's values fa and fb at its
/// ends: exactly what sin and cos of Interval(a, b) give, for callers that have those values
/// already (the affine fits, vm/numbers/affine_fit.cpp).
Interval SinCosFromEnds(double a, double b, double fa, double fb, bool isCos);

}  // namespace affray::vm
