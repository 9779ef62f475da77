// vm/numbers/reduced_affine.cpp: reduced affine arithmetic beyond the inline linear operations: division,
// the nonlinear functions (the fits of vm/numbers/affine_fit.cpp applied to the form), pow and atan2 by
// their compositions, and the piecewise-constant and branching functions. Each is vm::Affine's
// rule (vm/numbers/affine_functions.cpp, vm/numbers/affine_logic.cpp, explained there) with the new error put
// into e instead of on a fresh symbol; each public function then narrows its result to the
// interval result of the same function on the operands' ranges (Tighten), which most fits have
// computed already (AffineFit::range) and which then costs nothing more.
#include "vm/numbers/reduced_affine.h"

#include <cstdio>

#include "vm/numbers/affine_fit.h"

namespace affray::vm {

// --- Construction, range, printing --------------------------------------------------------------

ReducedAffine ReducedAffine::FromSymbol(double center, double radius, int axis) {
    if (!std::isfinite(center) || !std::isfinite(radius)) return Unbounded();
    return Make(center, axis == kSymbolU ? radius : 0.0, axis == kSymbolV ? radius : 0.0, 0.0);
}

ReducedAffine ReducedAffine::UnboundedWithin(const Interval& range) {
    if (!range.isUnbounded()) return FromInterval(range);
    ReducedAffine r = Unbounded();
    r.m_lo = range.lo();
    r.m_hi = range.hi();
    return r;
}

ReducedAffine ReducedAffine::FromInterval(const Interval& range) {
    if (range.isUnbounded()) return UnboundedWithin(range);
    if (range.isPoint()) return ReducedAffine(range.lo());
    ReducedAffine r = Make(range.mid(), 0.0, 0.0, range.radius());
    if (r.isUnbounded()) return r;
    r.m_lo = range.lo();  // the interval itself bounds every value, more tightly than mid +- radius
    r.m_hi = range.hi();
    return r;
}

double ReducedAffine::radius() const {
    if (isUnbounded()) return kInfinity;
    UpperSum r;
    r.add(std::fabs(m_u));
    r.add(std::fabs(m_v));
    r.add(m_error);
    return r.value();
}

Interval ReducedAffine::evaluateAt(double epsU, double epsV) const {
    if (isUnbounded()) return Interval::Unbounded();
    double lo = AddDown(AddDown(m_center, MulDown(m_u, epsU)), MulDown(m_v, epsV));
    double hi = AddUp(AddUp(m_center, MulUp(m_u, epsU)), MulUp(m_v, epsV));
    return Interval(SubDown(lo, m_error), AddUp(hi, m_error));
}

std::string ReducedAffine::toString() const {
    if (isUnbounded()) return "unbounded";
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.17g", m_center);
    std::string s = buf;
    const double coefs[2] = {m_u, m_v};
    const char* names[2] = {"eu", "ev"};
    for (int i = 0; i < 2; ++i) {
        if (coefs[i] == 0) continue;
        std::snprintf(buf, sizeof buf, " %c %.17g*%s", coefs[i] < 0 ? '-' : '+', std::fabs(coefs[i]), names[i]);
        s += buf;
    }
    if (m_error != 0) {
        std::snprintf(buf, sizeof buf, " +- %.17g", m_error);
        s += buf;
    }
    return s;
}

ReducedAffine ReducedAffine::withExtraError(double extra) const {
    if (isUnbounded()) return Unbounded();
    return Make(m_center, m_u, m_v, AddUp(m_error, extra));
}

// --- Fits ---------------------------------------------------------------------------------------

// alpha*x + zeta +- delta: the coefficients alpha*a and alpha*b keep x's correlation with u and v;
// delta is the fit's half-gap, x's error times |alpha| and the rounding of every coefficient and of
// the centre (vm/numbers/affine.cpp's ApplyFit, with delta in e).
ReducedAffine ReducedAffine::ApplyFit(const ReducedAffine& x, double alpha, double gLo, double gHi) {
    if (x.isUnbounded() || !(gLo <= gHi) || !std::isfinite(alpha)) return Unbounded();
    const double zeta = 0.5 * gLo + 0.5 * gHi;
    const double delta0 = std::fmax(SubUp(gHi, zeta), SubUp(zeta, gLo));
    if (!(std::fabs(zeta) <= kMaxFinite && delta0 <= kMaxFinite)) return Unbounded();
    // zeta +- delta0 exactly: no coefficient is computed, so nothing else is rounded.
    if (alpha == 0) return Make(zeta, 0.0, 0.0, delta0);
    const double a = alpha * x.m_u, b = alpha * x.m_v;
    const double ax0 = alpha * x.m_center;
    const double center = ax0 + zeta;
    const double absSum = std::fabs(a) + std::fabs(b) + std::fabs(ax0) + std::fabs(center);
    const double delta = (delta0 + std::fabs(alpha) * x.m_error + absSum * kEpsilon) * kSumSlack + kUnderflowSlack;
    if (!(delta <= kMaxFinite)) return Unbounded();
    return Make(center, a, b, delta);
}

ReducedAffine ReducedAffine::FromFit(const ReducedAffine& x, const AffineFit& fit) {
    return FormOfFit(x, fit, ApplyFit);
}

template <class F>
ReducedAffine ReducedAffine::FromFitTight(const ReducedAffine& x, const AffineFit& fit, F interval) {
    return Tighten(FromFit(x, fit), fit.range.isUnbounded() ? interval(x.range()) : fit.range);
}

// --- Division -----------------------------------------------------------------------------------

// The real 1/x (callers add the rounding of their scalar division); Unbounded across 0.
ReducedAffine ReducedAffine::Reciprocal(const ReducedAffine& x) {
    if (x.isUnbounded()) return ReducedAffine::Unbounded();
    const Interval range = x.range();
    if (!(range.lo() > 0 || range.hi() < 0)) return Unbounded();
    if (range.hi() < 0) return -Reciprocal(-x);
    return FromFit(x, ReciprocalFit(range));
}

ReducedAffine ReducedAffine::DivForms(const ReducedAffine& x, const ReducedAffine& y) {
    if (x.isUnbounded() || y.isUnbounded()) return Unbounded();
    if (y.isConstant()) return x / y.m_center;
    if (x.isConstant()) return x.m_center / y;
    // The product adds u*max|x/y|, the rounding of the scalar division.
    return x * Reciprocal(y);
}

ReducedAffine ReducedAffine::DivConstantForm(const ReducedAffine& x, double c) {
    if (x.isUnbounded() || !std::isfinite(c) || c == 0) return Unbounded();
    if (x.isConstant()) return ReducedAffine(x.m_center / c);
    if (c == 1) return x;
    if (c == -1) return -x;
    const double inv = 1.0 / c;
    // fl(1/c) is within u of 1/c unless it is subnormal; then multiply by an enclosure instead.
    if (MayUnderflow(inv)) return x * FromInterval(Interval(DivDown(1, c), DivUp(1, c)));
    return Scale(x, inv, 2.0);
}

ReducedAffine ReducedAffine::ConstantDivForm(double c, const ReducedAffine& x) {
    if (x.isUnbounded() || !std::isfinite(c)) return Unbounded();
    if (x.isConstant()) return ReducedAffine(c / x.m_center);
    // Scaling adds u*max|c/x|, the rounding of the scalar division.
    return Reciprocal(x) * c;
}

// Exact constants divide as doubles (the scalar result itself; a non-finite one is Unbounded).
ReducedAffine operator/(const ReducedAffine& x, const ReducedAffine& y) {
    if (x.isConstant() && y.isConstant()) return ReducedAffine(x.m_center / y.m_center);
    return ReducedAffine::Tighten(ReducedAffine::DivForms(x, y), x.range() / y.range());
}

ReducedAffine operator/(const ReducedAffine& x, double c) {
    if (x.isConstant()) return ReducedAffine(x.m_center / c);
    return ReducedAffine::Tighten(ReducedAffine::DivConstantForm(x, c), x.range() / c);
}

ReducedAffine operator/(double c, const ReducedAffine& x) {
    if (x.isConstant()) return ReducedAffine(c / x.m_center);
    return ReducedAffine::Tighten(ReducedAffine::ConstantDivForm(c, x), c / x.range());
}

// --- sqrt, exp, log, sin, cos, abs, sign, asin, acos, atan: the shared fits ----------------------

ReducedAffine sqrt(const ReducedAffine& x) {
    if (x.isUnbounded()) return ReducedAffine::Unbounded();
    if (x.isConstant()) return ReducedAffine(x.m_center < 0 ? 0.0 : std::sqrt(x.m_center));  // vm::sqrt, exact
    return ReducedAffine::FromFitTight(x, SqrtFit(x.range()), [](const Interval& r) { return sqrt(r); });
}

ReducedAffine exp(const ReducedAffine& x) {
    if (x.isUnbounded()) return ReducedAffine::Unbounded();
    return ReducedAffine::FromFitTight(x, ExpFit(x.range()), [](const Interval& r) { return exp(r); });
}

ReducedAffine log(const ReducedAffine& x) {
    if (x.isUnbounded()) return ReducedAffine::Unbounded();
    return ReducedAffine::FromFitTight(x, LogFit(x.range()), [](const Interval& r) { return log(r); });
}

ReducedAffine sin(const ReducedAffine& x) {
    if (x.isUnbounded()) return ReducedAffine::Unbounded();
    return ReducedAffine::FromFitTight(x, SinCosFit(x.range(), false), [](const Interval& r) { return sin(r); });
}

ReducedAffine cos(const ReducedAffine& x) {
    if (x.isUnbounded()) return ReducedAffine::Unbounded();
    return ReducedAffine::FromFitTight(x, SinCosFit(x.range(), true), [](const Interval& r) { return cos(r); });
}

ReducedAffine tan(const ReducedAffine& x) {
    if (x.isUnbounded()) return ReducedAffine::Unbounded();
    return ReducedAffine::FromFitTight(x, TanFit(x.range()), [](const Interval& r) { return tan(r); });
}

ReducedAffine abs(const ReducedAffine& x) {
    if (x.isUnbounded()) return ReducedAffine::UnboundedWithin(abs(x.range()));
    return ReducedAffine::FromFitTight(x, AbsFit(x.range()), [](const Interval& r) { return abs(r); });
}

ReducedAffine sign(const ReducedAffine& x) {
    if (x.isUnbounded()) return ReducedAffine::Unbounded();
    return ReducedAffine::FromFitTight(x, SignFit(x.range()), [](const Interval& r) { return sign(r); });
}

ReducedAffine asin(const ReducedAffine& x) {
    if (x.isUnbounded()) return ReducedAffine::Unbounded();
    return ReducedAffine::FromFitTight(x, InverseTrigFit(x.range(), 0), [](const Interval& r) { return asin(r); });
}

ReducedAffine acos(const ReducedAffine& x) {
    if (x.isUnbounded()) return ReducedAffine::Unbounded();
    return ReducedAffine::FromFitTight(x, InverseTrigFit(x.range(), 1), [](const Interval& r) { return acos(r); });
}

ReducedAffine atan(const ReducedAffine& x) {
    if (x.isUnbounded()) return ReducedAffine::Unbounded();
    return ReducedAffine::FromFitTight(x, InverseTrigFit(x.range(), 2), [](const Interval& r) { return atan(r); });
}

// --- pow ----------------------------------------------------------------------------------------

ReducedAffine ReducedAffine::IntegerPower(const ReducedAffine& x, int n) { return PowerBySquaring(x, n); }

// vm::Affine's PowForms: a constant integer exponent |n| <= 64 by repeated squaring (of 1/x for
// n < 0) plus glibc's rounding of pow; another constant by PowConstantFit; a varying exponent on
// x > 0 by exp(y*log(x)); anything else the interval range of std::pow.
ReducedAffine ReducedAffine::PowForms(const ReducedAffine& x, const ReducedAffine& y) {
    if (x.isUnbounded() || y.isUnbounded()) return Unbounded();
    if (y.isConstant()) {
        const double p = y.m_center;
        if (p == 0) return ReducedAffine(1.0);  // std::pow(x, 0) is 1 for every x
        if (std::floor(p) == p && std::fabs(p) <= kMaxIntegerPower && !x.isConstant()) {
            ReducedAffine base = p > 0 ? x : Reciprocal(x);
            if (!base.isUnbounded()) {
                ReducedAffine r = IntegerPower(base, static_cast<int>(std::fabs(p)));
                if (!r.isUnbounded()) return r.withExtraError(PowSlack(r.radius(), r.m_center));
            }
            return FromInterval(pow(x.range(), Interval(p)));
        }
        return FromFit(x, PowConstantFit(x.range(), p));
    }
    const Interval rx = x.range();
    if (rx.lo() > 0) {
        ReducedAffine r = exp(y * log(x));
        if (!r.isUnbounded()) return r.withExtraError(PowSlack(r.radius(), r.m_center));
    }
    return FromInterval(pow(rx, y.range()));
}

ReducedAffine pow(const ReducedAffine& x, const ReducedAffine& y) {
    return ReducedAffine::Tighten(ReducedAffine::PowForms(x, y), pow(x.range(), y.range()));
}

// --- atan2 --------------------------------------------------------------------------------------

// vm::Affine's identities: atan(y/x) where x > 0, +-pi/2 - atan(x/y) where y > 0 or y < 0, the
// one with less error e where both apply (the uncorrelated remainder: everything but the eps_u and
// eps_v terms), plus kAtan2Slack; elsewhere (the branch cut) the interval atan2.
ReducedAffine ReducedAffine::Atan2Forms(const ReducedAffine& y, const ReducedAffine& x) {
    if (y.isUnbounded() || x.isUnbounded()) return Unbounded();
    const Interval ry = y.range(), rx = x.range();
    ReducedAffine best = Unbounded();
    if (rx.lo() > 0) best = atan(y / x);
    if (ry.lo() > 0 || ry.hi() < 0) {
        ReducedAffine other = ReducedAffine(ry.lo() > 0 ? kHalfPi : -kHalfPi) - atan(x / y);
        if (best.isUnbounded() || (!other.isUnbounded() && other.m_error < best.m_error)) best = other;
    }
    if (best.isUnbounded()) return FromInterval(atan2(ry, rx));
    return best.withExtraError(kAtan2Slack);
}

ReducedAffine atan2(const ReducedAffine& y, const ReducedAffine& x) {
    return ReducedAffine::Tighten(ReducedAffine::Atan2Forms(y, x), atan2(y.range(), x.range()));
}

// --- floor, ceil, round -------------------------------------------------------------------------

ReducedAffine floor(const ReducedAffine& x) {
    if (x.isUnbounded()) return ReducedAffine::Unbounded();
    auto f = [](double t) { return std::floor(t); };
    return ReducedAffine::FromFitTight(x, StepFit(x.range(), f, -1.0, 0.0), [](const Interval& r) { return floor(r); });
}

ReducedAffine ceil(const ReducedAffine& x) {
    if (x.isUnbounded()) return ReducedAffine::Unbounded();
    auto f = [](double t) { return std::ceil(t); };
    return ReducedAffine::FromFitTight(x, StepFit(x.range(), f, 0.0, 1.0), [](const Interval& r) { return ceil(r); });
}

// std::round rounds halves away from zero: round(t) - t lies in [-1/2, 1/2] either way.
ReducedAffine round(const ReducedAffine& x) {
    if (x.isUnbounded()) return ReducedAffine::Unbounded();
    auto f = [](double t) { return std::round(t); };
    return ReducedAffine::FromFitTight(x, StepFit(x.range(), f, -0.5, 0.5), [](const Interval& r) { return round(r); });
}

// --- Comparisons and logic ----------------------------------------------------------------------

ReducedAffine ReducedAffine::FromTruth(Truth t) {
    if (t == Truth::True) return ReducedAffine(1.0);
    if (t == Truth::False) return ReducedAffine(0.0);
    return Make(0.5, 0.0, 0.0, 0.5);  // range exactly [0, 1]
}

// SignOfDifference, CompareForms (vm/numbers/affine_fit.h), as for every affine type.

ReducedAffine Less(const ReducedAffine& a, const ReducedAffine& b) {
    return ReducedAffine::FromTruth(CompareForms<Comparison::Less>(a, b));
}

ReducedAffine LessEq(const ReducedAffine& a, const ReducedAffine& b) {
    return ReducedAffine::FromTruth(CompareForms<Comparison::LessEq>(a, b));
}

ReducedAffine Equal(const ReducedAffine& a, const ReducedAffine& b) {
    return ReducedAffine::FromTruth(CompareForms<Comparison::Equal>(a, b));
}

ReducedAffine NotEqual(const ReducedAffine& a, const ReducedAffine& b) {
    return ReducedAffine::FromTruth(CompareForms<Comparison::NotEqual>(a, b));
}

ReducedAffine And(const ReducedAffine& a, const ReducedAffine& b) {
    return ReducedAffine::FromTruth(TruthAnd(TruthOf(a), TruthOf(b)));
}

ReducedAffine Or(const ReducedAffine& a, const ReducedAffine& b) {
    return ReducedAffine::FromTruth(TruthOr(TruthOf(a), TruthOf(b)));
}

ReducedAffine Not(const ReducedAffine& a) { return ReducedAffine::FromTruth(TruthNot(TruthOf(a))); }

// --- Min, Max, Join -----------------------------------------------------------------------------

// MinMaxOfForms (vm/numbers/affine_fit.h): the operand itself where the sign of a - b is decided;
// else (a + b)/2 -+ abs(a - b)/2 plus MinMaxSlack.
ReducedAffine Min(const ReducedAffine& a, const ReducedAffine& b) {
    return ReducedAffine::Tighten(MinMaxOfForms(a, b, false, &ReducedAffine::withExtraError),
                                  Min(a.range(), b.range()));
}

ReducedAffine Max(const ReducedAffine& a, const ReducedAffine& b) {
    return ReducedAffine::Tighten(MinMaxOfForms(a, b, true, &ReducedAffine::withExtraError), Max(a.range(), b.range()));
}

// A value in a or in b, at each point: m = (a + b)/2 on the linear parts, and the error
// max(ea, eb) + max |a - b|/2 over the linear parts (|x - m| <= |a_lin - m_lin| + ea where x is in
// a), plus the rounding of m's terms and of that maximum; within the hull of the ranges. (Taking
// (a + b)/2 and (a - b)/2 as reduced affine operations would count both errors twice over:
// ea + eb + max |a_lin - b_lin|/2, about twice as wide when the errors are alike, which is the case
// of noise joined over the lattice cells a region straddles.)
ReducedAffine Join(const ReducedAffine& a, const ReducedAffine& b) {
    if (a.isUnbounded() || b.isUnbounded()) return ReducedAffine::UnboundedWithin(Hull(a.range(), b.range()));
    const Interval hull = Hull(a.range(), b.range());
    const double c = 0.5 * (a.center() + b.center()), u = 0.5 * (a.coefficientU() + b.coefficientU()),
                 v = 0.5 * (a.coefficientV() + b.coefficientV());
    const double spread = std::fabs(a.center() - b.center()) + std::fabs(a.coefficientU() - b.coefficientU()) +
                          std::fabs(a.coefficientV() - b.coefficientV());
    const double error = (std::fmax(a.error(), b.error()) + 0.5 * spread +
                          (std::fabs(c) + std::fabs(u) + std::fabs(v) + spread) * kEpsilon) *
                             kSumSlack +
                         kUnderflowSlack;
    if (!(error <= kMaxFinite) || !std::isfinite(c) || !std::isfinite(u) || !std::isfinite(v))
        return ReducedAffine::FromInterval(hull);
    return ReducedAffine::Tighten(ReducedAffine::FromForm(c, u, v, error), hull);
}

}  // namespace affray::vm
