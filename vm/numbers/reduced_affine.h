// vm/numbers/reduced_affine.h: reduced affine arithmetic, the lean bounded number type of the VM.
// Owns class ReducedAffine: an affine form on the two symbols of the region being bounded and one
// independent error term,
//     x = x0 + a*eps_u + b*eps_v + e*eps_err,     every eps in [-1, 1], e >= 0,
// stored as four doubles plus the enclosure [lo, hi] (below): no symbol ids, no capacity, no
// allocation, trivially copyable (Gamito & Maddock 2007 call it reduced affine arithmetic; Knoll
// et al. 2009 use it to ray-trace implicit surfaces). eps_u and eps_v stand for the surface
// parameters u and v of the region (scene/geometry/surface.h), so every linear function of u and v is
// bounded exactly, as in vm::Affine; every nonlinear operation folds its new error into e, which
// is shared with nothing (x - x keeps 2e of error: the price of the lean form).
// Rules every operation keeps (tested in tests/vm/numbers/reduced_affine_test.cpp), those of vm::Affine:
//  - Containment: for every eps_u and eps_v, the double result of the same operation (vm/numbers/number.h's
//    scalar semantics) on any operand values the operand forms allow there lies in the result
//    form there, rounding of both computations included (vm/numbers/rounding.h).
//  - Anything that can be NaN or infinite somewhere is unbounded: Unbounded, or partial (an
//    Unbounded whose [lo, hi] has a finite side, range() a partial Interval), as in vm::Affine.
//  - Every result carries an *enclosure*: the interval-arithmetic result of the operation on its
//    operands' ranges, rounded outward, intersected with the form's own range. range() is that
//    intersection, computed once per operation and stored (m_lo, m_hi), so it costs nothing to
//    read, and a square or sum of squares stays >= 0 despite the rounding slack of its form
//    (sqrt(x*x + y*y) bounded where x and y straddle 0), as in vm::Affine.
// The approximation math of the nonlinear functions is vm::Affine's (vm/numbers/affine_fit.h): the same
// fit from the input range, applied to this form (FromFit). Comparisons are decided from the range
// of the form a - b (correlations through eps_u and eps_v cancel); undecided ones are 0.5 +- 0.5.
// The arithmetic that every instruction of a shader uses is inline below; the rest lives in
// reduced_affine.cpp.
// Sources: Gamito & Maddock, "Ray casting implicit fractal surfaces with reduced affine
// arithmetic" (The Visual Computer, 2007); Knoll, Hijazi, Kensler, Schott, Hansen & Hagen, "Fast
// ray tracing of arbitrary implicit surfaces with interval and affine arithmetic" (CGF 2009);
// Stolfi & de Figueiredo (1997) for the operations and their rounding.
#pragma once

#include <string>
#include <type_traits>

#include "vm/numbers/interval.h"

namespace affray::vm {

struct AffineFit;

class ReducedAffine {
  public:
    /// The axes FromSymbol takes: eps_u and eps_v (the numbering of Affine::kSymbolU/V).
    static constexpr int kSymbolU = 0;
    static constexpr int kSymbolV = 1;

    /// The exact constant 0.
    ReducedAffine() = default;
    /// The exact constant c; NaN or infinite c gives Unbounded.
    ReducedAffine(double c) : m_center(c), m_lo(c), m_hi(c) {  // NOLINT: implicit by design (Number API)
        if (!std::isfinite(c)) *this = Unbounded();
    }
    /// center + radius*eps_axis exactly (axis kSymbolU or kSymbolV; radius may be negative, 0
    /// gives the constant); Unbounded if either is not finite.
    static ReducedAffine FromSymbol(double center, double radius, int axis);
    /// center + u*eps_u + v*eps_v +- error with the form's own range, for a bound computed outside
    /// this class (scene/geometry/bicubic.cpp): `error` >= 0 must already hold every rounding
    /// of the caller's computation. Unbounded if anything is not finite.
    static ReducedAffine FromForm(double center, double u, double v, double error) {
        if (!(error >= 0)) return Unbounded();
        return Make(center, u, v, error);
    }
    /// `r` with its enclosure narrowed to `enclosure`, which must hold every scalar value r
    /// holds (Join's hull of the operands' ranges, say).
    static ReducedAffine Within(const ReducedAffine& r, const Interval& enclosure) { return Tighten(r, enclosure); }
    /// center +- radius(range) in the error term, with the range as enclosure (a point gives the
    /// constant).
    static ReducedAffine FromInterval(const Interval& range);
    /// x, or its range as FromInterval where x's error exceeds the range's radius plus x's own
    /// eps_u and eps_v coefficients: then the range says more than the form wherever it is
    /// used next (in any sum with a form M the form gives a width of at least |L + M| + e >=
    /// |M| - |L| + e, L its linear part and e its error, the range |M| + radius).
    static ReducedAffine RangeIfNarrower(const ReducedAffine& x) {
        if (x.isUnbounded() || !(x.m_lo < x.m_hi)) return x;
        if (x.m_error > 0.5 * (x.m_hi - x.m_lo) + std::fabs(x.m_u) + std::fabs(x.m_v))
            return FromInterval(Interval(x.m_lo, x.m_hi));
        return x;
    }
    /// An unbounded value known to lie in `range` (partial), or `range` itself if bounded.
    static ReducedAffine UnboundedWithin(const Interval& range);
    /// The explicit "unknown" value.
    static ReducedAffine Unbounded() {
        ReducedAffine r;
        r.m_error = kInfinity;
        r.m_lo = -kInfinity;
        r.m_hi = kInfinity;
        return r;
    }

    double center() const { return m_center; }
    double coefficientU() const { return m_u; }
    double coefficientV() const { return m_v; }
    /// The independent error e >= 0 (infinite for Unbounded).
    double error() const { return m_error; }
    bool isUnbounded() const { return !(m_error <= kMaxFinite); }
    /// No terms and no error: an exact double.
    bool isConstant() const { return m_u == 0 && m_v == 0 && m_error == 0; }
    /// The form's range [x0 - r, x0 + r] (r = |a| + |b| + e, rounded outward) intersected with
    /// the enclosure.
    /// The enclosure; for an unbounded form, Unbounded or its partial range.
    Interval range() const { return isUnbounded() ? Interval::Extended(m_lo, m_hi) : Interval(m_lo, m_hi); }
    /// |a| + |b| + e, rounded up.
    double radius() const;
    /// The range of the form with eps_u = epsU and eps_v = epsV fixed, eps_err free.
    Interval evaluateAt(double epsU, double epsV) const;
    /// "c + a*eu - b*ev +- e" with round-trip precision, or "unbounded".
    std::string toString() const;

    // Linear operations, products and squares (inline, below).
    friend ReducedAffine operator-(const ReducedAffine& x) {
        ReducedAffine r = x;
        r.m_center = -x.m_center;
        r.m_u = -x.m_u;
        r.m_v = -x.m_v;
        r.m_lo = -x.m_hi;  // exact: the range negates too
        r.m_hi = -x.m_lo;
        return r;
    }
    friend ReducedAffine operator+(const ReducedAffine& x, const ReducedAffine& y) { return AddForms<false>(x, y); }
    friend ReducedAffine operator-(const ReducedAffine& x, const ReducedAffine& y) { return AddForms<true>(x, y); }
    friend ReducedAffine operator+(const ReducedAffine& x, double c);
    friend ReducedAffine operator+(double c, const ReducedAffine& x) { return x + c; }
    friend ReducedAffine operator-(const ReducedAffine& x, double c) { return x + (-c); }
    friend ReducedAffine operator-(double c, const ReducedAffine& x) { return (-x) + c; }
    friend ReducedAffine operator*(const ReducedAffine& x, double c);
    friend ReducedAffine operator*(double c, const ReducedAffine& x) { return x * c; }
    friend ReducedAffine operator*(const ReducedAffine& x, const ReducedAffine& y);
    /// x*x by the square rule: center x0^2 + r^2/2, coefficients 2*x0*a and 2*x0*b, error r^2/2.
    friend ReducedAffine sqr(const ReducedAffine& x);

    // Division and nonlinear functions (reduced_affine.cpp): vm::Affine's rules, documented in
    // vm/numbers/affine.h, with every new error in e.
    friend ReducedAffine operator/(const ReducedAffine& x, const ReducedAffine& y);
    friend ReducedAffine operator/(const ReducedAffine& x, double c);
    friend ReducedAffine operator/(double c, const ReducedAffine& x);
    friend ReducedAffine sqrt(const ReducedAffine& x);
    friend ReducedAffine exp(const ReducedAffine& x);
    friend ReducedAffine log(const ReducedAffine& x);
    friend ReducedAffine sin(const ReducedAffine& x);
    friend ReducedAffine cos(const ReducedAffine& x);
    friend ReducedAffine tan(const ReducedAffine& x);
    friend ReducedAffine abs(const ReducedAffine& x);
    friend ReducedAffine sign(const ReducedAffine& x);
    friend ReducedAffine pow(const ReducedAffine& x, const ReducedAffine& y);
    friend ReducedAffine asin(const ReducedAffine& x);
    friend ReducedAffine acos(const ReducedAffine& x);
    friend ReducedAffine atan(const ReducedAffine& x);
    friend ReducedAffine atan2(const ReducedAffine& y, const ReducedAffine& x);
    friend ReducedAffine floor(const ReducedAffine& x);
    friend ReducedAffine ceil(const ReducedAffine& x);
    friend ReducedAffine round(const ReducedAffine& x);
    friend ReducedAffine Min(const ReducedAffine& a, const ReducedAffine& b);
    friend ReducedAffine Max(const ReducedAffine& a, const ReducedAffine& b);
    /// The exact constant 1 or 0 where decided by the range of a - b, else 0.5 +- 0.5 (always so
    /// when an operand is Unbounded).
    friend ReducedAffine Less(const ReducedAffine& a, const ReducedAffine& b);
    friend ReducedAffine LessEq(const ReducedAffine& a, const ReducedAffine& b);
    friend ReducedAffine Equal(const ReducedAffine& a, const ReducedAffine& b);
    friend ReducedAffine NotEqual(const ReducedAffine& a, const ReducedAffine& b);
    friend ReducedAffine And(const ReducedAffine& a, const ReducedAffine& b);
    friend ReducedAffine Or(const ReducedAffine& a, const ReducedAffine& b);
    friend ReducedAffine Not(const ReducedAffine& a);
    /// True if the range excludes 0, False if it is exactly [0, 0], else (Unbounded too) Unknown.
    friend Truth TruthOf(const ReducedAffine& x) { return TruthOf(x.range()); }
    /// A form containing both: (a + b)/2 with its eps_u and eps_v terms, plus max |a - b|/2 of
    /// error; within the hull of the ranges.
    friend ReducedAffine Join(const ReducedAffine& a, const ReducedAffine& b);

    // Number API (vm/numbers/number.h).
    /// A reduced affine form carries no derivatives: the "unknown" value.
    friend ReducedAffine DerivU(const ReducedAffine&) { return Unbounded(); }
    friend ReducedAffine DerivV(const ReducedAffine&) { return Unbounded(); }
    friend Interval RangeOf(const ReducedAffine& x) { return x.range(); }
    friend bool IsUnbounded(const ReducedAffine& x) { return x.isUnbounded(); }
    friend bool IsExactlyZero(const ReducedAffine& x) { return x.isConstant() && x.m_center == 0; }
    friend std::string ToString(const ReducedAffine& x) { return x.toString(); }

  private:
    /// The form x0 + a*eps_u + b*eps_v +- e with its own range (no enclosure yet); Unbounded if
    /// that range is not finite.
    static ReducedAffine Make(double x0, double a, double b, double e) {
        ReducedAffine r;
        r.m_center = x0;
        r.m_u = a;
        r.m_v = b;
        r.m_error = e;
        if (a == 0 && b == 0) {
            // x0 +- e (a constant, an interval, a truth value, a fit of slope 0): exact bounds.
            r.m_lo = SubDown(x0, e);
            r.m_hi = AddUp(x0, e);
        } else if (e == 0) {
            // An exact form (u, v): bounds exact wherever they are representable.
            UpperSum radius;
            radius.add(std::fabs(a));
            radius.add(std::fabs(b));
            const double rad = radius.value();
            r.m_lo = SubDown(x0, rad);
            r.m_hi = AddUp(x0, rad);
        } else {
            // The sum of three non-negative terms in two roundings is at most 2u too small, which
            // the factor covers (its own rounding included; subnormal sums are exact). With e > 0
            // the range is no point anyway, so one ulp more of outward rounding costs nothing
            // that matters, and it is much cheaper than exact directed sums.
            const double rad = (std::fabs(a) + std::fabs(b) + e) * (1 + 0x1p-50);
            r.m_lo = NextDown(x0 - rad);
            r.m_hi = NextUp(x0 + rad);
        }
        if (!(r.m_lo >= -kMaxFinite && r.m_hi <= kMaxFinite)) return Unbounded();
        return r;
    }
    /// `r` with its range narrowed to [lo, hi], a valid bound of the same scalar values (an
    /// interval result, infinite ends allowed); an Unbounded r becomes UnboundedWithin([lo, hi]):
    /// that interval if bounded, else partial. A form the narrowed range outweighs gives way to
    /// it (RangeIfNarrower): a clamp or a min of a wide form (a normalized component, a noise
    /// straying past [0, 1]) then carries its range, not its error, into every later operation
    /// (bench/real's subdivision scene: 52 regions a camera ray down to 31).
    static ReducedAffine Tighten(ReducedAffine r, double lo, double hi) {
        if (r.isUnbounded()) return UnboundedWithin(Interval::Extended(lo, hi));
        // (Comparisons, not std::fmax and fmin, which GCC calls in libm; no bound here is NaN.)
        lo = lo > r.m_lo ? lo : r.m_lo;
        hi = hi < r.m_hi ? hi : r.m_hi;
        // Both hold every scalar value, so they overlap; should rounding ever make them miss each
        // other, the form's own range stays.
        if (lo <= hi) {
            r.m_lo = lo;
            r.m_hi = hi;
            return RangeIfNarrower(r);
        }
        return r;
    }
    static ReducedAffine Tighten(const ReducedAffine& r, const Interval& enclosure) {
        return Tighten(r, enclosure.lo(), enclosure.hi());
    }
    /// x + y or x - y, enclosure included.
    template <bool kSubtract>
    static ReducedAffine AddForms(const ReducedAffine& x, const ReducedAffine& y) {
        if (x.isUnbounded() || y.isUnbounded()) return Unbounded();
        const double sy = kSubtract ? -1.0 : 1.0;
        // An exact constant operand: the cheaper x + c (which returns x itself for c = 0).
        if (y.isConstant()) return x + sy * y.m_center;
        if (x.isConstant()) return (kSubtract ? -y : y) + x.m_center;
        const double x0 = x.m_center + sy * y.m_center;
        const double a = x.m_u + sy * y.m_u, b = x.m_v + sy * y.m_v;
        const double absSum = std::fabs(x0) + std::fabs(a) + std::fabs(b);
        ReducedAffine r = Make(x0, a, b, LinearError(x.m_error + y.m_error, absSum));
        if (kSubtract) return Tighten(r, SubDown(x.m_lo, y.m_hi), SubUp(x.m_hi, y.m_lo));
        return Tighten(r, AddDown(x.m_lo, y.m_lo), AddUp(x.m_hi, y.m_hi));
    }
    /// x*c with the coefficient rounding bound scaled by `roundingFactor` (2 when c is a rounded
    /// reciprocal), and the scalar product's rounding included; no enclosure (c may not be the
    /// scalar operation's operand).
    static ReducedAffine Scale(const ReducedAffine& x, double c, double roundingFactor) {
        if (x.isUnbounded() || !std::isfinite(c)) return Unbounded();
        const double x0 = x.m_center * c, a = x.m_u * c, b = x.m_v * c;
        const double absSum = std::fabs(x0) + std::fabs(a) + std::fabs(b);
        const double scaledError = std::fabs(c) * x.m_error * (1 + kEpsilon);
        return Make(x0, a, b, LinearError(scaledError, absSum * roundingFactor) + kUnderflowSlack);
    }
    static ReducedAffine MulForms(const ReducedAffine& x, const ReducedAffine& y);
    static ReducedAffine SqrForm(const ReducedAffine& x);
    /// alpha*x + zeta +- delta, where g(t) = f(t) - alpha*t lies in [gLo, gHi] for every t in x's
    /// range (f's glibc rounding included): the result of any unary f; no enclosure.
    static ReducedAffine ApplyFit(const ReducedAffine& x, double alpha, double gLo, double gHi);
    /// The form of a shared fit over x's range: vm/numbers/affine_fit.h's FormOfFit with ApplyFit;
    /// no enclosure.
    static ReducedAffine FromFit(const ReducedAffine& x, const AffineFit& fit);
    /// FromFit narrowed to f's interval result over x's range: the fit's own (fit.range) where it
    /// computed it, else interval(x.range()) (reduced_affine.cpp).
    template <class F>
    static ReducedAffine FromFitTight(const ReducedAffine& x, const AffineFit& fit, F interval);
    /// x with `extra` (>= 0, rounded up) more error; its own range (no enclosure).
    ReducedAffine withExtraError(double extra) const;
    static ReducedAffine Reciprocal(const ReducedAffine& x);
    static ReducedAffine DivForms(const ReducedAffine& x, const ReducedAffine& y);
    static ReducedAffine DivConstantForm(const ReducedAffine& x, double c);
    static ReducedAffine ConstantDivForm(double c, const ReducedAffine& x);
    static ReducedAffine IntegerPower(const ReducedAffine& x, int n);
    static ReducedAffine PowForms(const ReducedAffine& x, const ReducedAffine& y);
    static ReducedAffine Atan2Forms(const ReducedAffine& y, const ReducedAffine& x);
    /// 1, 0 or 0.5 +- 0.5.
    static ReducedAffine FromTruth(Truth t);

    // The form (centre, coefficients of eps_u and eps_v, error), then range() = [m_lo, m_hi].
    double m_center = 0;
    double m_u = 0;
    double m_v = 0;
    double m_error = 0;
    double m_lo = 0;
    double m_hi = 0;
};

static_assert(std::is_trivially_copyable_v<ReducedAffine>);
static_assert(sizeof(ReducedAffine) == 6 * sizeof(double));

inline ReducedAffine operator+(const ReducedAffine& x, double c) {
    if (x.isUnbounded() || !std::isfinite(c)) return ReducedAffine::Unbounded();
    if (c == 0) return x;
    if (x.isConstant()) return ReducedAffine(x.m_center + c);
    const double x0 = x.m_center + c;
    const double absSum = std::fabs(x0) + std::fabs(x.m_u) + std::fabs(x.m_v);
    ReducedAffine r = ReducedAffine::Make(x0, x.m_u, x.m_v, LinearError(x.m_error, absSum));
    return ReducedAffine::Tighten(r, AddDown(x.m_lo, c), AddUp(x.m_hi, c));
}

inline ReducedAffine operator*(const ReducedAffine& x, double c) {
    if (x.isUnbounded() || !std::isfinite(c)) return ReducedAffine::Unbounded();
    if (c == 0) return ReducedAffine(0.0);
    if (c == 1) return x;
    if (c == -1) return -x;
    if (x.isConstant()) return ReducedAffine(x.m_center * c);
    ReducedAffine r = ReducedAffine::Scale(x, c, 1.0);
    if (c > 0) return ReducedAffine::Tighten(r, MulDown(x.m_lo, c), MulUp(x.m_hi, c));
    return ReducedAffine::Tighten(r, MulDown(x.m_hi, c), MulUp(x.m_lo, c));
}

inline ReducedAffine operator*(const ReducedAffine& x, const ReducedAffine& y) {
    if (x.isUnbounded() || y.isUnbounded()) return ReducedAffine::Unbounded();
    if (x.isConstant()) return y * x.m_center;
    if (y.isConstant()) return x * y.m_center;
    return ReducedAffine::Tighten(ReducedAffine::MulForms(x, y), x.range() * y.range());
}

// (x0 + X + Ex)(y0 + Y + Ey) with X = a*eps_u + b*eps_v: ProductRemainder (vm/numbers/rounding.h) with the
// two shared symbols; the whole remainder goes to e.
inline ReducedAffine ReducedAffine::MulForms(const ReducedAffine& x, const ReducedAffine& y) {
    // Roundings per term of the sums of two terms, doubled (as vm/numbers/affine.cpp's kTermSlack).
    constexpr double kTermSlack = 2.0 * 2 + 4.0;
    const double x0 = x.m_center, y0 = y.m_center;
    const double a = x0 * y.m_u + y0 * x.m_u, b = x0 * y.m_v + y0 * x.m_v;
    const double pu = x.m_u * y.m_u, pv = x.m_v * y.m_v;
    const double diag = pu + pv, absDiag = std::fabs(pu) + std::fabs(pv);
    const double rx = std::fabs(x.m_u) + std::fabs(x.m_v), ry = std::fabs(y.m_u) + std::fabs(y.m_v);
    const double center = x0 * y0 + 0.5 * diag;
    const double absSum = std::fabs(a) + std::fabs(b) + std::fabs(center);
    const double delta = ProductRemainder({x0, y0, rx, ry, x.m_error, y.m_error, diag, absDiag, absSum}, kTermSlack);
    if (!(delta <= kMaxFinite)) return Unbounded();
    return Make(center, a, b, delta);
}

inline ReducedAffine sqr(const ReducedAffine& x) {
    if (x.isUnbounded()) return ReducedAffine::Unbounded();
    if (x.isConstant()) return ReducedAffine(x.m_center * x.m_center);
    return ReducedAffine::Tighten(ReducedAffine::SqrForm(x), sqr(x.range()));
}

inline ReducedAffine ReducedAffine::SqrForm(const ReducedAffine& x) {
    constexpr double kTermSlack = 2.0 * 2 + 4.0;
    const double twoX0 = 2 * x.m_center;
    const double a = twoX0 * x.m_u, b = twoX0 * x.m_v;
    const SquareParts sq = SquareRemainder(x.m_center, std::fabs(x.m_u) + std::fabs(x.m_v), x.m_error,
                                           std::fabs(a) + std::fabs(b), kTermSlack);
    if (!(sq.error <= kMaxFinite)) return Unbounded();
    return Make(sq.center, a, b, sq.error);
}

}  // namespace affray::vm
