// vm/numbers/affine.h: affine arithmetic (AA), the VM's main bounded number type.
// Owns class Affine: a fixed-capacity, allocation-free affine form
//     x = x0 + sum_i xi*eps_i + e*eps_err,     every eps in [-1, 1], e >= 0,
// where eps_u (kSymbolU) and eps_v (kSymbolV) stand for the surface parameters of the region being
// bounded, further symbols are made fresh by nonlinear operations (so that later operations still
// see their correlation), and e is an independent error term that is shared with nothing.
// Rules every operation keeps (tested in tests/vm/numbers/affine_test.cpp):
//  - Containment: for every assignment of the symbols, the double result of the same operation
//    (vm/numbers/number.h's scalar semantics) on any operand values the operand forms allow at that
//    assignment lies in the result form, rounding of both computations included (vm/numbers/rounding.h).
//  - Anything that can be NaN or infinite somewhere is unbounded: the explicit Unbounded value,
//    or a partial one whose range() is a partial Interval (vm/numbers/interval.h: an infinite end,
//    and maybe NaN), e.g. max(x, 0) for an Unbounded x. Functions take an unbounded operand as
//    Unbounded except where its interval rule keeps a side (Min, Max, abs, Join, negation...);
//    a result whose enclosure is finite is bounded again: that interval on a fresh symbol.
//  - Terms are kept sorted by symbol id with no zero coefficient; when they do not fit in the
//    active capacity (Capacity(), kCapacity unless a bench or test changed it), the smallest
//    terms other than eps_u and eps_v are folded into e.
//  - Every result also carries an *enclosure*: the interval-arithmetic result of the operation on
//    its operands' ranges (rounded outward). range() is the form's range intersected with it, so
//    affine bounds are never wider than interval ones, and a value known to be >= 0 (a square, a
//    sum of squares) stays >= 0 despite the rounding slack of its form: sqrt(x*x + y*y) is then
//    bounded even where x and y straddle 0. Sound because every scalar value lies in both (the
//    usual hybrid of affine and interval arithmetic; Stolfi & de Figueiredo 1997, sec. 3.10).
// Symbols are numbered per thread: BeginEvaluation() restarts the fresh ids, so forms from
// different evaluations (or threads) must never be combined.
// Linear operations and products live in affine.cpp, the nonlinear unary functions (Chebyshev
// and min-range approximations, whose math vm/numbers/affine_fit.cpp shares with vm::ReducedAffine) and
// atan2 in affine_functions.cpp, the piecewise-constant and branching ones (floor/ceil/round,
// Min/Max, comparisons, logic, TruthOf, Join) in affine_logic.cpp. Comparisons return the exact constant 1 or 0 where decided, decided from the
// range of the affine difference a - b (so correlations cancel), else 0.5 +- 0.5 on a fresh symbol.
// Sources: Stolfi & de Figueiredo, "Self-Validated Numerical Methods and Applications" (1997) and
// "Affine arithmetic: concepts and applications" (Numerical Algorithms, 2004); Heidrich & Seidel,
// "Ray-tracing procedural displacement shaders" (GI 1998); Heidrich, Slusallek & Seidel, "Sampling
// procedural shaders using affine arithmetic" (TOG 1998).
#pragma once

#include <cstdint>
#include <cstring>
#include <string>

#include "vm/numbers/interval.h"

namespace affray::vm {

struct AffineFit;

class Affine {
  public:
    using SymbolId = uint32_t;
    /// Term slots every form stores, eps_u and eps_v included: the largest capacity that
    /// SetCapacity accepts. Storage is fixed (no allocation) whatever the active capacity.
    static constexpr int kMaxCapacity = 32;
    /// The default active capacity, chosen from the capacity study in docs/bounds.md
    /// (affray_bench_bounds --capacity-study, every shader, regions of width 1/8 and 1/64): 12 is
    /// the knee. Below it bounds widen fast (at 8: strata 1/8 +24%, stucco 1/64 +5.6%, against
    /// capacity 32) for at most ~10% less time; at 12 the mean z width is within 0.5% of capacity
    /// 32's (worst shader: strata at 1/8, +6.5%; every shader within 0.6% at 1/64); above it 12
    /// of 17 shaders gain nothing, and those that do pay per term kept (strata at 1/8: +7% time
    /// at 16 for -3.6% width, +19% at 32 for -6%).
    static constexpr int kCapacity = 12;
    static constexpr SymbolId kSymbolU = 0;
    static constexpr SymbolId kSymbolV = 1;
    /// BeginEvaluation() restarts fresh symbols here.
    static constexpr SymbolId kFirstFreshSymbol = 2;
    static_assert(2 <= kCapacity && kCapacity <= kMaxCapacity, "eps_u and eps_v must always fit");

    /// The active capacity: how many terms (eps_u and eps_v included) a result keeps before its
    /// smallest fresh terms are folded into e. Process-wide; kCapacity unless changed.
    static int Capacity();
    /// Sets the active capacity for every later operation in every thread, and returns true; or
    /// returns false and changes nothing if n is outside [2, kMaxCapacity]. Only for benches and
    /// tests that measure tightness against capacity: call it while no evaluation runs, since
    /// forms of one evaluation are meant to share one capacity. (Forms made earlier keep their
    /// terms, as do negation, scaling and adding a constant, until an operation that merges
    /// terms folds them; every bound stays valid either way.)
    static bool SetCapacity(int n);

    /// The exact constant 0.
    Affine() = default;
    /// Copies copy only the terms in use: the storage is sized for kMaxCapacity, and the
    /// interpreter copies a result into its register on every instruction.
    Affine(const Affine& x) { copyFrom(x); }
    Affine& operator=(const Affine& x) {
        if (this != &x) copyFrom(x);
        return *this;
    }
    /// The exact constant c; NaN or infinite c gives Unbounded.
    Affine(double c) : m_center(c) {  // NOLINT: implicit by design (Number API)
        if (!std::isfinite(c)) *this = Unbounded();
    }
    /// center + radius*eps_id exactly (radius may be negative; 0 gives the constant). Ids from
    /// kFirstFreshSymbol on are the fresh symbols': a caller using them must keep them apart.
    static Affine FromSymbol(double center, double radius, SymbolId id);
    /// A form with the range of `range` on a fresh symbol (a constant for a point).
    static Affine FromInterval(const Interval& range);
    /// The explicit "unknown" value.
    static Affine Unbounded();
    /// An unbounded value known to lie in `range` (a partial interval: [lo, hi] or NaN), or, if
    /// `range` is bounded, that range on a fresh symbol.
    static Affine UnboundedWithin(const Interval& range);
    /// Restarts this thread's fresh symbols at kFirstFreshSymbol. Call before bounding a region.
    static void BeginEvaluation();
    /// A fresh symbol id, unused in this evaluation on this thread.
    static SymbolId NewSymbol();

    double center() const { return m_center; }
    /// The independent error e >= 0 (infinite for Unbounded).
    double error() const { return m_error; }
    int termCount() const { return m_count; }
    SymbolId termSymbol(int i) const { return m_symbols[i]; }
    double termCoef(int i) const { return m_coefs[i]; }
    /// The coefficient of symbol `id`, 0 if absent.
    double coefficientOf(SymbolId id) const;
    bool isUnbounded() const { return !(m_error <= kMaxFinite); }
    /// No terms and no error: an exact double.
    bool isConstant() const { return m_count == 0 && m_error == 0; }
    /// The range [x0 - r, x0 + r] with r = sum |xi| + e, rounded outward; for an unbounded form,
    /// Unbounded or its partial range.
    Interval range() const;
    /// sum |xi| + e, rounded up.
    double radius() const;
    /// The range with eps_u = epsU and eps_v = epsV fixed and every other symbol free.
    Interval evaluateAt(double epsU, double epsV) const;
    /// "c + a*e0 - b*e7 +- e" with round-trip precision, or "unbounded".
    std::string toString() const;

    // Linear operations and products (affine.cpp).
    friend Affine operator-(const Affine& x);
    friend Affine operator+(const Affine& x, const Affine& y);
    friend Affine operator-(const Affine& x, const Affine& y);
    friend Affine operator*(const Affine& x, const Affine& y);
    friend Affine operator+(const Affine& x, double c);
    friend Affine operator+(double c, const Affine& x) { return x + c; }
    friend Affine operator-(const Affine& x, double c) { return x + (-c); }
    friend Affine operator-(double c, const Affine& x) { return (-x) + c; }
    friend Affine operator*(const Affine& x, double c);
    friend Affine operator*(double c, const Affine& x) { return x * c; }
    /// x*x by the square rule: center x0^2 + r^2/2, coefficients 2*x0*xi, error r^2/2.
    friend Affine sqr(const Affine& x);

    // Division and nonlinear functions (affine_functions.cpp; the fits in affine_fit.cpp).
    /// x * (1/y) by a Chebyshev 1/y; Unbounded when the divisor's range contains 0.
    friend Affine operator/(const Affine& x, const Affine& y);
    friend Affine operator/(const Affine& x, double c);
    friend Affine operator/(double c, const Affine& x);
    /// Chebyshev; Unbounded if the range has negative values.
    friend Affine sqrt(const Affine& x);
    /// Chebyshev with the slope capped to keep the form positive; Unbounded on overflow.
    friend Affine exp(const Affine& x);
    /// Chebyshev; Unbounded unless the range is > 0.
    friend Affine log(const Affine& x);
    /// Secant slope with every stationary point of the remainder visited; [-1, 1] on a fresh
    /// symbol past a width of 2*pi or beyond |x| = 1e8.
    friend Affine sin(const Affine& x);
    friend Affine cos(const Affine& x);
    /// Secant slope with the remainder bounded by a tangent line on each side of tan's zero;
    /// Unbounded where a pole may lie in the range (as Interval's tan).
    friend Affine tan(const Affine& x);
    /// x or -x where the sign is decided, else min-range [0, max|x|] on a fresh symbol.
    friend Affine abs(const Affine& x);
    /// 1, -1 or 0 where decided, else the hull of the possible signs on a fresh symbol.
    friend Affine sign(const Affine& x);
    /// std::pow's semantics: integer constant exponents by repeated squaring, other constants by
    /// Chebyshev on x >= 0, varying ones by exp(y*log(x)) on x > 0, else interval bounds;
    /// Unbounded wherever std::pow can be NaN or infinite.
    friend Affine pow(const Affine& x, const Affine& y);
    /// Secant slope with g bounded at the endpoints, at 0 and by a tangent line at the point of
    /// each convex or concave side where f' = alpha; asin and acos Unbounded outside [-1, 1].
    friend Affine asin(const Affine& x);
    friend Affine acos(const Affine& x);
    friend Affine atan(const Affine& x);
    /// atan(y/x) where x > 0, +-pi/2 - atan(x/y) where y > 0 or y < 0 (the narrower), plus the
    /// difference between those and glibc's atan2; else the interval atan2 on a fresh symbol.
    friend Affine atan2(const Affine& y, const Affine& x);

    // Piecewise-constant functions, min/max, comparisons and logic (affine_logic.cpp).
    /// The exact constant where the range lies in one integer cell (or past 2^52, x itself);
    /// else x - 1/2 +- 1/2 (floor), x + 1/2 +- 1/2 (ceil) or x +- 1/2 (round) on a fresh symbol.
    friend Affine floor(const Affine& x);
    friend Affine ceil(const Affine& x);
    friend Affine round(const Affine& x);
    /// std::fmin/fmax: the operand itself where a - b has a decided sign, else
    /// (a + b)/2 -+ abs(a - b)/2 plus the rounding of that formula.
    friend Affine Min(const Affine& a, const Affine& b);
    friend Affine Max(const Affine& a, const Affine& b);
    /// The exact constant 1 or 0 where decided, else 0.5 +- 0.5 on a fresh symbol (always so
    /// when an operand is Unbounded).
    friend Affine Less(const Affine& a, const Affine& b);
    friend Affine LessEq(const Affine& a, const Affine& b);
    friend Affine Equal(const Affine& a, const Affine& b);
    friend Affine NotEqual(const Affine& a, const Affine& b);
    friend Affine And(const Affine& a, const Affine& b);
    friend Affine Or(const Affine& a, const Affine& b);
    friend Affine Not(const Affine& a);
    /// True if the range excludes 0, False if it is exactly [0, 0], else (Unbounded too) Unknown.
    friend Truth TruthOf(const Affine& x);
    /// A form containing both, for an undecided condition: (a + b)/2 with the shared symbols,
    /// plus max |a - b|/2 of independent error; within the hull of the ranges.
    friend Affine Join(const Affine& a, const Affine& b);

    // Number API (vm/numbers/number.h).
    /// An affine form carries no derivatives: the "unknown" value.
    friend Affine DerivU(const Affine&) { return Unbounded(); }
    friend Affine DerivV(const Affine&) { return Unbounded(); }
    friend Interval RangeOf(const Affine& x) { return x.range(); }
    friend bool IsUnbounded(const Affine& x) { return x.isUnbounded(); }
    friend bool IsExactlyZero(const Affine& x) { return x.isConstant() && x.m_center == 0; }
    friend std::string ToString(const Affine& x) { return x.toString(); }

  private:
    /// `r` with its enclosure narrowed to `enclosure` (a valid interval bound of the same
    /// scalar values) and its range cached; an unbounded form becomes UnboundedWithin(enclosure)
    /// (bounded again, on a fresh symbol, if the enclosure is finite).
    static Affine Tighten(Affine r, const Interval& enclosure);
    void copyFrom(const Affine& x) {
        m_center = x.m_center;
        m_error = x.m_error;
        m_lo = x.m_lo;
        m_hi = x.m_hi;
        m_rangeCached = x.m_rangeCached;
        m_count = x.m_count;
        // memcpy of the used prefix: GCC 12 at -O1 cannot see that a loop over i < m_count reads
        // only written slots and reports the rest as uninitialised.
        std::memcpy(m_symbols, x.m_symbols, sizeof(SymbolId) * static_cast<size_t>(m_count));
        std::memcpy(m_coefs, x.m_coefs, sizeof(double) * static_cast<size_t>(m_count));
    }
    /// Forgets the enclosure (after the form was changed in place).
    void resetEnclosure() {
        m_lo = -kInfinity;
        m_hi = kInfinity;
        m_rangeCached = false;
    }
    // The operations on forms alone; the public operators add the enclosure (Tighten).
    static Affine AddConstantForm(const Affine& x, double c);
    static Affine MulConstantForm(const Affine& x, double c);
    static Affine MulForms(const Affine& x, const Affine& y);
    static Affine SqrForm(const Affine& x);
    static Affine DivForms(const Affine& x, const Affine& y);
    static Affine DivConstantForm(const Affine& x, double c);
    static Affine ConstantDivForm(double c, const Affine& x);
    static Affine SqrtForm(const Affine& x);
    static Affine ExpForm(const Affine& x);
    static Affine LogForm(const Affine& x);
    static Affine AbsForm(const Affine& x);
    static Affine SignForm(const Affine& x);
    static Affine PowForms(const Affine& x, const Affine& y);

    struct Terms;  // the term list an operation writes (affine.cpp)

    /// Completes this result of an operation: the terms folded to the capacity if they were
    /// written to scratch, then center and error (already rounded up). False if anything is
    /// not finite (the caller returns Unbounded).
    bool finish(double center, double error, Terms& terms);
    /// alpha*x + zeta +- delta on a fresh symbol, where g(t) = f(t) - alpha*t lies in [gLo, gHi]
    /// for every t in x's range (f's glibc rounding included): the result of any unary f.
    static Affine ApplyFit(const Affine& x, double alpha, double gLo, double gHi);
    /// The form of a shared fit of a unary function over x's range: vm/numbers/affine_fit.h's
    /// FormOfFit with ApplyFit (affine_functions.cpp).
    static Affine FromFit(const Affine& x, const AffineFit& fit);
    /// x + y or x - y by a sorted merge of the terms (affine.cpp).
    template <bool kSubtract>
    static Affine AddForms(const Affine& x, const Affine& y);
    /// x*c with the coefficient rounding bound scaled by `roundingFactor` (2 when c is a rounded
    /// reciprocal), and the scalar product's rounding included (affine.cpp).
    static Affine Scale(const Affine& x, double c, double roundingFactor);
    /// x with `extra` (>= 0, rounded up) more independent error.
    Affine withExtraError(double extra) const;
    /// 1/x; Unbounded if the range of x contains 0 (affine_functions.cpp).
    static Affine Reciprocal(const Affine& x);
    /// sin or cos (affine_functions.cpp).
    static Affine SinOrCos(const Affine& x, bool isCos);
    /// tan (affine_functions.cpp).
    static Affine TanForm(const Affine& x);
    /// x^n for an integer 1 <= n by repeated squaring.
    static Affine IntegerPower(const Affine& x, int n);
    /// x^p for a constant p that is not a small integer (or x constant): PowConstantFit.
    static Affine PowConstant(const Affine& x, double p);
    /// asin (0), acos (1) or atan (2) (affine_functions.cpp).
    static Affine InverseTrigForm(const Affine& x, int which);
    static Affine Atan2Forms(const Affine& y, const Affine& x);
    /// floor, ceil or round: f(t) - t lies in [gLo, gHi] (affine_logic.cpp).
    static Affine StepForm(const Affine& x, double (*f)(double), double gLo, double gHi);
    /// 1, 0 or 0.5 +- 0.5 on a fresh symbol (affine_logic.cpp).
    static Affine FromTruth(Truth t);

    double m_center = 0;
    double m_error = 0;
    // The enclosure [m_lo, m_hi] (see the head comment); when m_rangeCached it is the whole
    // range() already intersected with the form's range.
    double m_lo = -kInfinity;
    double m_hi = kInfinity;
    bool m_rangeCached = false;
    int m_count = 0;
    SymbolId m_symbols[kMaxCapacity];
    double m_coefs[kMaxCapacity];
};

}  // namespace affray::vm
