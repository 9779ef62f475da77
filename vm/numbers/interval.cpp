// vm/numbers/interval.cpp: the non-trivial interval functions (products, quotients, transcendentals).
// Each bound is either a directed rounding of an exact extreme (arithmetic, sqrt) or a glibc value
// at an extreme widened by LibmDown/LibmUp (see vm/numbers/rounding.h for why that also contains glibc's
// value at every inner point). Extremes come from monotone pieces: endpoints, plus the stationary
// points that lie inside (sin, cos) or 0 (sqr, abs, even powers); atan2 from the corners of its
// quadrant. Also the exact step functions (floor, ceil, round), min/max, comparisons and logic.
#include "vm/numbers/interval.h"

#include <algorithm>
#include <cstdio>

namespace affray::vm {

namespace {

constexpr double kInvPi = 0.31830988618379067154;  // 1/pi rounded to nearest
// Width past which sin and cos take every value of [-1, 1] (a little below 2*pi).
constexpr double kTwoPiBelow = 6.2831853;
// Beyond this magnitude the period analysis is skipped: sin and cos are simply [-1, 1].
constexpr double kTrigAnalysisLimit = 1e8;

// The true f(t) and glibc's f at points near t lie within the slack of glibc's value r.
Interval LibmEnclosure(double r) {
    if (!std::isfinite(r)) return Interval::Unbounded();
    return Interval(LibmDown(r), LibmUp(r));
}

// The integers k with t = (k + phase) * pi possibly in [a, b] (finite, a <= b): kLo..kHi. t/pi is
// computed with a relative error below 4u, so a tolerance of 2^-40 (1 + |t/pi|) cannot exclude
// a k whose t is inside; including one that is just outside is harmless.
void MultiplesOfPi(double a, double b, double phase, double* kLo, double* kHi) {
    double ta = a * kInvPi - phase;
    double tb = b * kInvPi - phase;
    *kLo = std::ceil(ta - 0x1p-40 * (1 + std::fabs(ta)));
    *kHi = std::floor(tb + 0x1p-40 * (1 + std::fabs(tb)));
}

// Bounds of sin (phase 0.5) or cos (phase 0) over [a, b] (finite, a <= b): the values at the
// endpoints, plus +-1 for every extremum t = (k + phase) * pi that may lie inside, k even giving
// +1.
Interval TrigRange(double a, double b, double fa, double fb, double phase) {
    if (b - a >= kTwoPiBelow || std::fmax(std::fabs(a), std::fabs(b)) > kTrigAnalysisLimit) return Interval(-1.0, 1.0);
    double lo = std::fmin(LibmDown(fa), LibmDown(fb));
    double hi = std::fmax(LibmUp(fa), LibmUp(fb));
    double kLo, kHi;
    MultiplesOfPi(a, b, phase, &kLo, &kHi);
    for (int step = 0; step <= 2 && kLo + step <= kHi; ++step) {
        const double k = kLo + step;
        if (std::fmod(k, 2.0) == 0)
            hi = 1.0;
        else
            lo = -1.0;
    }
    // glibc's sin and cos never leave [-1, 1].
    return Interval(std::fmax(lo, -1.0), std::fmin(hi, 1.0));
}

bool IsInteger(double y) { return std::isfinite(y) && std::floor(y) == y; }

}  // namespace

double Interval::mid() const {
    if (isUnbounded()) return 0.0;
    return 0.5 * m_lo + 0.5 * m_hi;  // no overflow; exact halves unless subnormal
}

double Interval::radius() const {
    if (isUnbounded()) return kInfinity;
    double m = mid();
    return std::fmax(SubUp(m_hi, m), SubUp(m, m_lo));
}

std::string Interval::toString() const {
    char buf[96];
    if (m_lo == -kInfinity && m_hi == kInfinity) return "unbounded";
    if (isUnbounded()) {
        std::snprintf(buf, sizeof buf, "[%.17g, %.17g] or NaN", m_lo, m_hi);
        return buf;
    }
    std::snprintf(buf, sizeof buf, "[%.17g, %.17g]", m_lo, m_hi);
    return buf;
}

Interval operator*(const Interval& a, const Interval& b) {
    if (a.isUnbounded() || b.isUnbounded()) return Interval::Unbounded();
    // By the signs of the operands, as in Moore's table: two directed products, four if both
    // straddle 0.
    const double al = a.m_lo, ah = a.m_hi, bl = b.m_lo, bh = b.m_hi;
    if (al >= 0) {
        if (bl >= 0) return Interval(MulDown(al, bl), MulUp(ah, bh));
        if (bh <= 0) return Interval(MulDown(ah, bl), MulUp(al, bh));
        return Interval(MulDown(ah, bl), MulUp(ah, bh));
    }
    if (ah <= 0) {
        if (bl >= 0) return Interval(MulDown(al, bh), MulUp(ah, bl));
        if (bh <= 0) return Interval(MulDown(ah, bh), MulUp(al, bl));
        return Interval(MulDown(al, bh), MulUp(al, bl));
    }
    if (bl >= 0) return Interval(MulDown(al, bh), MulUp(ah, bh));
    if (bh <= 0) return Interval(MulDown(ah, bl), MulUp(al, bl));
    return Interval(std::fmin(MulDown(al, bh), MulDown(ah, bl)), std::fmax(MulUp(al, bl), MulUp(ah, bh)));
}

Interval operator/(const Interval& a, const Interval& b) {
    if (a.isUnbounded() || b.isUnbounded()) return Interval::Unbounded();
    // A divisor [0, hi]: its zero is +0 (vm::Div), so a quotient of one sign keeps its finite side,
    // x / hi, and reaches the infinity of its own sign. Otherwise x/0 is +-inf or NaN.
    if (b.m_lo == 0 && b.m_hi > 0) {
        if (a.m_lo > 0) return Interval::Extended(DivDown(a.m_lo, b.m_hi), kInfinity);
        if (a.m_hi < 0) return Interval::Extended(-kInfinity, DivUp(a.m_hi, b.m_hi));
        return Interval::Unbounded();
    }
    if (b.m_lo <= 0 && b.m_hi >= 0) return Interval::Unbounded();
    // x/y is monotone in x and in y on each side of 0, so the extremes are the corners that the
    // signs pick (Moore's table): two directed quotients. A bound that is a zero keeps the scan of
    // all four corners below, whose choice among equal +0 and -0 quotients is its own.
    const double al = a.m_lo, ah = a.m_hi, bl = b.m_lo, bh = b.m_hi;
    if (al != 0 && ah != 0) {
        if (bl > 0) return Interval(DivDown(al, al > 0 ? bh : bl), DivUp(ah, ah > 0 ? bl : bh));
        return Interval(DivDown(ah, ah > 0 ? bh : bl), DivUp(al, al > 0 ? bl : bh));
    }
    double lo =
        std::min({DivDown(a.m_lo, b.m_lo), DivDown(a.m_lo, b.m_hi), DivDown(a.m_hi, b.m_lo), DivDown(a.m_hi, b.m_hi)});
    double hi = std::max({DivUp(a.m_lo, b.m_lo), DivUp(a.m_lo, b.m_hi), DivUp(a.m_hi, b.m_lo), DivUp(a.m_hi, b.m_hi)});
    return Interval(lo, hi);
}

Interval sqr(const Interval& x) {
    if (x.isUnbounded()) return Interval::Unbounded();
    if (x.m_lo >= 0) return Interval(MulDown(x.m_lo, x.m_lo), MulUp(x.m_hi, x.m_hi));
    if (x.m_hi <= 0) return Interval(MulDown(x.m_hi, x.m_hi), MulUp(x.m_lo, x.m_lo));
    double m = std::fmax(-x.m_lo, x.m_hi);
    return Interval(0.0, MulUp(m, m));
}

// The scalar sqrt is 0 below 0 (vm/numbers/number.h): a negative part of the range adds 0. A
// partial [lo, +inf] keeps its low side.
Interval sqrt(const Interval& x) {
    if (x.isUnbounded()) {
        if (!(x.m_lo >= -kMaxFinite)) return Interval::Unbounded();
        return Interval::Extended(x.m_lo < 0 ? 0.0 : SqrtDown(x.m_lo), kInfinity);
    }
    if (x.m_hi < 0) return Interval(0.0);
    return Interval(x.m_lo < 0 ? 0.0 : SqrtDown(x.m_lo), SqrtUp(x.m_hi));
}

Interval exp(const Interval& x) {
    if (x.isUnbounded()) return Interval::Unbounded();
    double hi = LibmUp(std::exp(x.m_hi));
    const double lo = std::fmax(0.0, LibmDown(std::exp(x.m_lo)));
    if (!(hi <= kMaxFinite)) return Interval::Extended(lo, kInfinity);  // overflow: keep the low side
    return Interval(lo, hi);
}

Interval log(const Interval& x) {
    // log(0) = -inf, log(negative) = NaN: the partial [-inf, log(hi)] where x reaches 0.
    if (x.isUnbounded() || !(x.m_hi > 0)) return Interval::Unbounded();
    if (!(x.m_lo > 0)) return Interval::Extended(-kInfinity, LibmUp(std::log(x.m_hi)));
    return Interval(LibmDown(std::log(x.m_lo)), LibmUp(std::log(x.m_hi)));
}

Interval sin(const Interval& x) {
    if (x.isUnbounded()) return Interval::Unbounded();
    return TrigRange(x.m_lo, x.m_hi, std::sin(x.m_lo), std::sin(x.m_hi), 0.5);
}

Interval cos(const Interval& x) {
    if (x.isUnbounded()) return Interval::Unbounded();
    return TrigRange(x.m_lo, x.m_hi, std::cos(x.m_lo), std::cos(x.m_hi), 0.0);
}

Interval SinCosFromEnds(double a, double b, double fa, double fb, bool isCos) {
    return TrigRange(a, b, fa, fb, isCos ? 0.0 : 0.5);
}

// tan increases on each branch ((k - 1/2) pi, (k + 1/2) pi), so over a range holding no pole
// (k + 1/2) pi (sin's extrema, found the same way) the scalar tan lies within glibc's slack of
// [tan(lo), tan(hi)]. A pole may lie inside: Unbounded (the doubles nearest a pole have tangents
// near +-1.6e16, and either sign). A point is its own branch at any magnitude.
Interval tan(const Interval& x) {
    if (x.isUnbounded()) return Interval::Unbounded();
    if (x.isPoint()) return LibmEnclosure(std::tan(x.m_lo));
    if (std::fmax(std::fabs(x.m_lo), std::fabs(x.m_hi)) > kTrigAnalysisLimit) return Interval::Unbounded();
    double kLo, kHi;
    MultiplesOfPi(x.m_lo, x.m_hi, 0.5, &kLo, &kHi);
    if (kLo <= kHi) return Interval::Unbounded();
    return Interval(LibmDown(std::tan(x.m_lo)), LibmUp(std::tan(x.m_hi)));
}

Interval abs(const Interval& x) {
    // |t| is monotone on each side of 0, and |+-inf| = inf keeps a partial x partial.
    if (x.m_lo >= 0) return x;
    if (x.m_hi <= 0) return -x;
    return Interval::Extended(0.0, std::fmax(-x.m_lo, x.m_hi));
}

Interval sign(const Interval& x) {
    if (x.isUnbounded()) return Interval::Unbounded();
    auto s = [](double t) { return t > 0 ? 1.0 : t < 0 ? -1.0 : 0.0; };
    return Interval(s(x.m_lo), s(x.m_hi));
}

Interval pow(const Interval& x, const Interval& y) {
    if (x.isUnbounded() || y.isUnbounded()) return Interval::Unbounded();
    auto boundOf = [](double r) { return LibmEnclosure(r); };
    if (y.isPoint() && IsInteger(y.m_lo)) {
        // Integer exponent: x^n is monotone on each side of 0 (std::pow(x, 0) is 1 even at 0).
        double n = y.m_lo;
        if (n == 0) return Interval(1.0);
        bool straddles = x.m_lo < 0 && x.m_hi > 0;
        if (n < 0 && x.m_lo <= 0 && x.m_hi >= 0) return Interval::Unbounded();
        Interval r = Hull(boundOf(std::pow(x.m_lo, n)), boundOf(std::pow(x.m_hi, n)));
        if (r.isUnbounded()) return r;
        bool even = std::fmod(n, 2.0) == 0;
        if (straddles) r = Hull(r, Interval(0.0));
        if (even) r = Interval(std::fmax(r.m_lo, 0.0), r.m_hi);
        return r;
    }
    // Real exponent: the scalar pow takes a negative base as 0 for a non-integer exponent
    // (vm/numbers/number.h), so a constant one bounds pow over [max(lo, 0), max(hi, 0)]; a varying
    // one may be an integer somewhere, where a negative base keeps its sign: Unbounded.
    // For x >= 0, x^y is monotone in x for fixed y and in y for fixed x, so the corners bound it;
    // x > 0 is needed where y can be < 0 (pow(0, y < 0) = inf).
    if (x.m_lo < 0 && y.isPoint()) return pow(Interval(0.0, std::fmax(x.m_hi, 0.0)), y);
    if (x.m_lo < 0 || (x.m_lo == 0 && y.m_lo < 0)) return Interval::Unbounded();
    Interval r = Hull(Hull(boundOf(std::pow(x.m_lo, y.m_lo)), boundOf(std::pow(x.m_lo, y.m_hi))),
                      Hull(boundOf(std::pow(x.m_hi, y.m_lo)), boundOf(std::pow(x.m_hi, y.m_hi))));
    if (r.isUnbounded()) return r;
    return Interval(std::fmax(r.m_lo, 0.0), r.m_hi);
}

// --- floor, ceil, round --------------------------------------------------------------------------

// Monotone and exact on doubles: the images of the endpoints are the bounds.
Interval floor(const Interval& x) {
    if (x.isUnbounded()) return Interval::Unbounded();
    return Interval(std::floor(x.m_lo), std::floor(x.m_hi));
}

Interval ceil(const Interval& x) {
    if (x.isUnbounded()) return Interval::Unbounded();
    return Interval(std::ceil(x.m_lo), std::ceil(x.m_hi));
}

Interval round(const Interval& x) {
    if (x.isUnbounded()) return Interval::Unbounded();
    return Interval(std::round(x.m_lo), std::round(x.m_hi));
}

// --- asin, acos, atan, atan2 --------------------------------------------------------------------

namespace {

// pi rounded to nearest (below pi); LibmUp(kPi) is above pi and above glibc's atan2 everywhere.
constexpr double kPi = 3.141592653589793;

}  // namespace

// Increasing on [-1, 1]; asin(+-1) = +-pi/2, outside NaN.
Interval asin(const Interval& x) {
    if (x.isUnbounded() || x.m_lo < -1 || x.m_hi > 1) return Interval::Unbounded();
    return Interval(LibmDown(std::asin(x.m_lo)), LibmUp(std::asin(x.m_hi)));
}

// Decreasing on [-1, 1], >= 0 (acos(1) = +0: the slack would only reach below 0).
Interval acos(const Interval& x) {
    if (x.isUnbounded() || x.m_lo < -1 || x.m_hi > 1) return Interval::Unbounded();
    return Interval(std::fmax(0.0, LibmDown(std::acos(x.m_hi))), LibmUp(std::acos(x.m_lo)));
}

Interval atan(const Interval& x) {
    if (x.isUnbounded()) return Interval::Unbounded();
    return Interval(LibmDown(std::atan(x.m_lo)), LibmUp(std::atan(x.m_hi)));
}

// The angle of (x, y) over a box. For y > 0 it lies in (0, pi), continuous in x and y, decreasing
// in x, increasing in y where x > 0 and decreasing where x < 0 (constant pi/2 at x = +-0): the
// smallest angle is at the right edge x = xh (with y = yl if xh > 0, else yh), the largest at the
// left edge x = xl (with y = yh if xl > 0, else yl). y < 0 mirrors it: atan2(-y, x) = -atan2(y, x).
// Where y can be 0: with x > 0 the angle lies in (-pi/2, pi/2) and increases with y and with |y|/x
// decreasing, so the corners (yl, xl) and (yh, xl) bound it; with x able to be <= 0 the box meets
// the branch cut (atan2(+-0, x < 0) = +-pi, atan2(+-0, -0) = +-pi): [-pi, pi]. glibc's atan2 is
// within 1 ulp (libm-test-ulps), so the corner values widened by LibmDown/LibmUp hold it at every
// inner point (vm/numbers/rounding.h).
Interval atan2(const Interval& y, const Interval& x) {
    if (y.isUnbounded() || x.isUnbounded()) return Interval::Unbounded();
    if (y.m_hi < 0) return -atan2(-y, x);
    if (y.m_lo > 0) {
        const double lo = std::atan2(x.m_hi > 0 ? y.m_lo : y.m_hi, x.m_hi);
        const double hi = std::atan2(x.m_lo > 0 ? y.m_hi : y.m_lo, x.m_lo);
        return Interval(LibmDown(lo), LibmUp(hi));
    }
    if (x.m_lo > 0) return Interval(LibmDown(std::atan2(y.m_lo, x.m_lo)), LibmUp(std::atan2(y.m_hi, x.m_lo)));
    return Interval(-LibmUp(kPi), LibmUp(kPi));
}

// --- Min, Max -----------------------------------------------------------------------------------

// Min and Max are exact, and monotone in each operand, infinities included. An unbounded operand
// may also be NaN, where fmin/fmax give the other operand: its whole range joins the result. The
// result may be NaN only where both may be, and then it is partial (both have an infinite end).
Interval Min(const Interval& a, const Interval& b) {
    double lo = std::fmin(a.m_lo, b.m_lo), hi = std::fmin(a.m_hi, b.m_hi);
    if (a.isUnbounded()) hi = std::fmax(hi, b.m_hi);
    if (b.isUnbounded()) hi = std::fmax(hi, a.m_hi);
    return Interval::Extended(lo, hi);
}

Interval Max(const Interval& a, const Interval& b) {
    double lo = std::fmax(a.m_lo, b.m_lo), hi = std::fmax(a.m_hi, b.m_hi);
    if (a.isUnbounded()) lo = std::fmin(lo, b.m_lo);
    if (b.isUnbounded()) lo = std::fmin(lo, a.m_lo);
    return Interval::Extended(lo, hi);
}

// --- Comparisons and logic ----------------------------------------------------------------------

// An Unbounded operand may be NaN (every comparison false but !=) or anything: undecided.
Interval Less(const Interval& a, const Interval& b) {
    if (a.isUnbounded() || b.isUnbounded()) return Interval::FromTruth(Truth::Unknown);
    if (a.m_hi < b.m_lo) return Interval::FromTruth(Truth::True);
    if (a.m_lo >= b.m_hi) return Interval::FromTruth(Truth::False);
    return Interval::FromTruth(Truth::Unknown);
}

Interval LessEq(const Interval& a, const Interval& b) {
    if (a.isUnbounded() || b.isUnbounded()) return Interval::FromTruth(Truth::Unknown);
    if (a.m_hi <= b.m_lo) return Interval::FromTruth(Truth::True);
    if (a.m_lo > b.m_hi) return Interval::FromTruth(Truth::False);
    return Interval::FromTruth(Truth::Unknown);
}

// Equal points are equal (-0 == +0); disjoint ranges are not.
Interval Equal(const Interval& a, const Interval& b) {
    if (a.isUnbounded() || b.isUnbounded()) return Interval::FromTruth(Truth::Unknown);
    if (a.isPoint() && b.isPoint() && a.m_lo == b.m_lo) return Interval::FromTruth(Truth::True);
    if (a.m_hi < b.m_lo || b.m_hi < a.m_lo) return Interval::FromTruth(Truth::False);
    return Interval::FromTruth(Truth::Unknown);
}

Interval NotEqual(const Interval& a, const Interval& b) { return Interval::FromTruth(TruthNot(TruthOf(Equal(a, b)))); }

Interval And(const Interval& a, const Interval& b) { return Interval::FromTruth(TruthAnd(TruthOf(a), TruthOf(b))); }

Interval Or(const Interval& a, const Interval& b) { return Interval::FromTruth(TruthOr(TruthOf(a), TruthOf(b))); }

Interval Not(const Interval& a) { return Interval::FromTruth(TruthNot(TruthOf(a))); }

}  // namespace affray::vm
