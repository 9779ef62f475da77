// vm/numbers/affine_fit.h: the approximation math of affine arithmetic, shared by every affine form type
// (vm::Affine and vm::ReducedAffine): for each nonlinear unary function, what its result is over
// an input range, computed from that range alone, and the error slacks of the composite functions.
// Owns struct AffineFit, the *Fit functions and FormOfFit, which turns a fit into a form of any
// affine type (the type's FromFit): a Line becomes alpha*x + zeta +- delta (the type's ApplyFit,
// which keeps x's symbols and adds the rounding of the form's coefficients), a Range the interval
// on its own (FromInterval), Same/Negated x or -x exactly, Unbounded the explicit unknown value.
// How a form keeps the new error (a fresh symbol in Affine, the one independent error term in
// ReducedAffine) is the type's business; what the error is, is decided here, once. So are the
// comparisons of forms and the form of Min and Max (SignOfDifference, CompareForms, MinMaxOfForms).
// Rules every fit keeps (tests: tests/vm/numbers/affine_test.cpp, tests/vm/numbers/reduced_affine_test.cpp): for
// every t in the input range, glibc's f(t) (the scalar result) lies in alpha*t + [lo, hi], the
// rounding of every computation here included; Unbounded wherever f(t) can be NaN or infinite.
// The functions are explained in vm/numbers/affine_fit.cpp.
// Sources: Stolfi & de Figueiredo (1997), sec. 3.7-3.9 (Chebyshev and min-range approximations);
// AFFINE-NOTES.md for the pitfalls (a delta taken at sample points only, or delta = 0, is not
// conservative).
#pragma once

#include <cstdint>

#include "vm/numbers/interval.h"

namespace affray::vm {

/// What a unary function gives over an input range (see the head comment).
struct AffineFit {
    enum class Kind : uint8_t {
        Line,       ///< alpha*x + [lo, hi]: g(t) = f(t) - alpha*t lies in [lo, hi] on the range
        Range,      ///< `range` on its own (a point: that exact constant)
        Same,       ///< x itself
        Negated,    ///< -x
        Unbounded,  ///< f can be NaN or infinite on the range
    };
    Kind kind = Kind::Unbounded;
    double alpha = 0, lo = 0, hi = 0;
    /// Range: the result. Line: the interval result of f over the input range (exactly what
    /// vm/numbers/interval.h's f gives for it) where the fit computed it, else Unbounded; a form type may
    /// take it as its enclosure instead of computing it again. Also taken instead of the line when
    /// the line's radius |alpha|*radius(x) + (hi - lo)/2 exceeds `lineLimit` (a line that follows
    /// f poorly over a wide range).
    Interval range = Interval::Unbounded();
    double lineLimit = kInfinity;

    static AffineFit Line(double alpha, double lo, double hi) {
        AffineFit f;
        f.kind = Kind::Line;
        f.alpha = alpha;
        f.lo = lo;
        f.hi = hi;
        return f;
    }
    /// A Line with the interval result `all` of f (see `range`).
    static AffineFit Line(double alpha, double lo, double hi, const Interval& all) {
        AffineFit f = Line(alpha, lo, hi);
        f.range = all;
        return f;
    }
    static AffineFit RangeOf(const Interval& r) {
        AffineFit f;
        f.kind = Kind::Range;
        f.range = r;
        return f;
    }
    static AffineFit Of(Kind kind) {
        AffineFit f;
        f.kind = kind;
        return f;
    }
    /// Whether the line must be compared with `range` at all (lineTooWide).
    bool hasLineLimit() const { return lineLimit < kInfinity; }
    /// Whether a Line over an input form of radius `formRadius` should give way to `range`.
    bool lineTooWide(double formRadius) const { return std::fabs(alpha) * formRadius + 0.5 * (hi - lo) > lineLimit; }
};

/// The form of a fit for any affine form type F (F::FromFit): `apply`(x, alpha, lo, hi), F's own
/// ApplyFit, for a Line (F::FromInterval of the fit's range for a Line wider than its
/// lineLimit), F::FromInterval for a Range, x, -x, or F::Unbounded().
template <class F, class Apply>
F FormOfFit(const F& x, const AffineFit& fit, Apply apply) {
    switch (fit.kind) {
        case AffineFit::Kind::Line:
            if (fit.hasLineLimit() && fit.lineTooWide(x.radius())) return F::FromInterval(fit.range);
            return apply(x, fit.alpha, fit.lo, fit.hi);
        case AffineFit::Kind::Range: return F::FromInterval(fit.range);
        case AffineFit::Kind::Same: return x;
        case AffineFit::Kind::Negated: return -x;
        default: return F::Unbounded();
    }
}

// Each takes the (bounded) range of the input form, already intersected with its enclosure.
/// 1/t on a range > 0 (callers handle a range < 0 by symmetry, and 0 in the range).
AffineFit ReciprocalFit(const Interval& range);
/// sqrt (Unbounded if the range has negative values).
AffineFit SqrtFit(const Interval& range);
AffineFit ExpFit(const Interval& range);
/// log (Unbounded unless the range is > 0).
AffineFit LogFit(const Interval& range);
AffineFit SinCosFit(const Interval& range, bool isCos);
/// tan (Unbounded where a pole may lie in the range, as Interval's tan).
AffineFit TanFit(const Interval& range);
AffineFit AbsFit(const Interval& range);
AffineFit SignFit(const Interval& range);
/// t^p for a constant p that is not a small integer (or a constant base).
AffineFit PowConstantFit(const Interval& range, double p);
/// asin (which = 0), acos (1) or atan (2).
AffineFit InverseTrigFit(const Interval& range, int which);
/// floor, ceil or round (`f`), where f(t) - t lies in [gLo, gHi].
AffineFit StepFit(const Interval& range, double (*f)(double), double gLo, double gHi);

/// Integer exponents of pow up to this magnitude go by repeated squaring.
inline constexpr int kMaxIntegerPower = 64;
/// x^n for an integer 1 <= n by repeated squaring, in any affine type F (its product and sqr).
template <class F>
F PowerBySquaring(const F& x, int n) {
    F result, base = x;
    bool have = false;
    while (n > 0) {
        if (n & 1) {
            result = have ? result * base : base;
            have = true;
        }
        n >>= 1;
        if (n > 0) base = sqr(base);
    }
    return result;
}
/// The error to add to a form of radius `radius` and centre `center` that composes pow (repeated
/// squaring, exp(y*log(x))): glibc's rounding of pow itself.
inline double PowSlack(double radius, double center) {
    return AddUp(MulUp(radius, kLibmRel), MulUp(std::fabs(center), kLibmRel)) + kLibmAbs;
}
/// pi/2 rounded to nearest, for atan2's identities.
inline constexpr double kHalfPi = 1.5707963267948966;
/// Bound of |glibc atan2(y, x) - T|, T the scalar value of atan(y/x) or +-pi/2 - atan(x/y) as
/// computed by the forms (|theta| <= pi, each glibc call within kLibmRel*|f| + kLibmAbs):
/// atan2's own error (pi*kLibmRel), atan's at fl(q) (pi/2*kLibmRel), atan(fl(q)) - atan(q) <=
/// |fl(q) - q|/(1 + q^2) <= u, pi/2 - fl(pi/2) < u/2, the rounding of +-pi/2 - A (<= pi*u):
/// under 5.4*kLibmRel + 2*kLibmAbs in all.
inline constexpr double kAtan2Slack = 8 * kLibmRel + 4 * kLibmAbs;

inline double MaxAbs(const Interval& r) { return std::fmax(std::fabs(r.lo()), std::fabs(r.hi())); }

/// min/max(a, b) computed as (a + b)/2 -+ |a - b|/2: the error to add for the difference
/// between that formula's scalar value and std::fmin/fmax's, with a, b in these ranges.
/// The forms contain C = fl(fl(fl(a + b)*0.5) -+ fl(|fl(a - b)|*0.5)), not the exact result M.
/// With R >= |a|, |b|: the two halved roundings are <= u*R each, the last <= u*|C| <= u*R(1 + 2u),
/// and halving may lose 2^-1075 twice below 2^-1022: |C - M| <= 3.01*u*R + 2^-1074, covered by
/// 2*kEpsilon*R = 4u*R plus kUnderflowSlack.
inline double MinMaxSlack(const Interval& a, const Interval& b) {
    const double bound = std::fmax(MaxAbs(a), MaxAbs(b));
    return AddUp(MulUp(bound, 2 * kEpsilon), kUnderflowSlack);
}
/// Join(a, b) as m = (a + b)/2 plus independent error: with h = (a - b)/2, every scalar a or b
/// lies within D = max|h| of (a + b)/2. The form m contains the scalar fl(fl(a + b)*0.5), within
/// u*|a + b|/2 + 2^-1075 of (a + b)/2, and h's range the scalar fl(fl(a - b)*0.5), so
/// |(a - b)/2| <= D(1 + u) + 2^-1075: m plus D + kEpsilon*(M + D) (M = max|m|), slack included.
inline double JoinSlack(double dMax, double mMax) {
    return AddUp(MulUp(AddUp(dMax, MulUp(AddUp(mMax, dMax), kEpsilon)), kSumSlack), kUnderflowSlack);
}

// --- Comparisons, Min and Max ----------------------------------------------------------------------

/// The sign of a - b for every pair of scalar values that forms a and b of an affine type F allow,
/// as the range of the form a - b (or, if that form is Unbounded, e.g. by overflow, of the interval
/// difference of the ranges); Unbounded if an operand is (it may be NaN: every comparison false
/// but !=).
/// Why the range of the *rounded* difference decides the double comparison: the form contains the
/// scalar fl(a - b) for each pair, and for finite doubles fl(a - b) has the sign of a - b and is 0
/// exactly when a == b. Rounding to nearest is monotone and maps 0 to 0, so it keeps the sign
/// (possibly giving 0 from a nonzero value only if |a - b| < 2^-1075), and a - b is a multiple of
/// 2^-1074 (both are), so a nonzero difference is at least the smallest subnormal and rounds to
/// itself or beyond (gradual underflow: a difference in the subnormal range is exact). An
/// overflowed difference would be +-inf with the right sign, but then the form is Unbounded and
/// the interval difference (directed, never overflowing silently) is used instead.
template <class F>
Interval SignOfDifference(const F& a, const F& b) {
    if (a.isUnbounded() || b.isUnbounded()) return Interval::Unbounded();
    const F d = a - b;
    return d.isUnbounded() ? a.range() - b.range() : d.range();
}

/// The comparisons of forms, decided by SignOfDifference.
enum class Comparison : uint8_t { Less, LessEq, Equal, NotEqual };

/// a < b, a <= b, a == b or a != b (`kComparison`) for forms of an affine type F: the interval
/// comparison (vm/numbers/interval.h) of SignOfDifference(a, b) with 0, as a truth value (the
/// type's FromTruth makes it a form).
template <Comparison kComparison, class F>
Truth CompareForms(const F& a, const F& b) {
    const Interval d = SignOfDifference(a, b), zero(0.0);
    if constexpr (kComparison == Comparison::Less)
        return TruthOf(Less(d, zero));
    else if constexpr (kComparison == Comparison::LessEq)
        return TruthOf(LessEq(d, zero));
    else if constexpr (kComparison == Comparison::Equal)
        return TruthOf(Equal(d, zero));
    else
        return TruthOf(NotEqual(d, zero));
}

/// std::fmin (isMax false) or std::fmax of forms of an affine type F, without the enclosure: where
/// the sign of a - b is decided, the operand itself (exactly, correlations and all); otherwise
/// min/max(a, b) = (a + b)/2 -+ |a - b|/2 exactly in reals, plus the difference between that
/// formula's scalar value and std::fmin's (MinMaxSlack) as independent error, which F's
/// `withExtraError` (x with that much more error, >= 0 and rounded up) adds.
template <class F>
F MinMaxOfForms(const F& a, const F& b, bool isMax, F (F::*withExtraError)(double) const) {
    if (a.isUnbounded() || b.isUnbounded()) return F::Unbounded();
    // a <= b for every pair: fmin is a (or b, if equal: the same value), fmax is b; and so on.
    const Interval d = SignOfDifference(a, b);
    if (!d.isUnbounded()) {
        if (d.hi() <= 0) return isMax ? b : a;
        if (d.lo() >= 0) return isMax ? a : b;
    }
    const F mid = (a + b) * 0.5;
    const F half = abs(a - b) * 0.5;
    const F r = isMax ? mid + half : mid - half;
    const double extra = MinMaxSlack(a.range(), b.range());
    if (r.isUnbounded() || !(extra <= kMaxFinite)) return F::Unbounded();
    return (r.*withExtraError)(extra);
}

}  // namespace affray::vm
