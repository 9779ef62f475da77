// vm/numbers/affine_functions.cpp: division and the nonlinear functions of affine arithmetic.
// Every unary f over the input range becomes alpha*x + zeta +- delta (Affine::ApplyFit), or the
// interval range on a fresh symbol, as the shared approximation math of vm/numbers/affine_fit.cpp decides
// from the range (Affine::FromFit); what remains here is how Affine composes them: division as a
// product with 1/y, pow by repeated squaring or exp(y*log(x)), atan2 by its identities with atan.
// atan2 composes atan with a quotient and adds the (tiny) difference between that composition and
// glibc's atan2 (kAtan2Slack).
// Sources: Stolfi & de Figueiredo (1997), sec. 3.7-3.9 (Chebyshev and min-range approximations);
// Heidrich & Seidel (GI 1998) for the use in displacement shaders; AFFINE-NOTES.md for the pitfalls
// (a delta taken at sample points only, or delta = 0, is not conservative).
#include "vm/numbers/affine.h"
#include "vm/numbers/affine_fit.h"

namespace affray::vm {

Affine Affine::FromFit(const Affine& x, const AffineFit& fit) { return FormOfFit(x, fit, ApplyFit); }

// --- 1/x and division ---------------------------------------------------------------------------

// ReciprocalFit on a range > 0; a range < 0 by 1/x = -(1/(-x)). Encloses the real 1/t (callers
// add the rounding of their scalar division).
Affine Affine::Reciprocal(const Affine& x) {
    if (x.isUnbounded()) return Affine::Unbounded();
    Interval range = x.range();
    if (!(range.lo() > 0 || range.hi() < 0)) return Unbounded();
    if (range.hi() < 0) return -Reciprocal(-x);
    return FromFit(x, ReciprocalFit(range));
}

Affine Affine::DivForms(const Affine& x, const Affine& y) {
    if (x.isUnbounded() || y.isUnbounded()) return Affine::Unbounded();
    if (y.isConstant()) return x / y.m_center;
    if (x.isConstant()) return x.m_center / y;
    // The product adds u*max|x/y|, the rounding of the scalar division.
    return x * Affine::Reciprocal(y);
}

Affine Affine::DivConstantForm(const Affine& x, double c) {
    if (x.isUnbounded() || !std::isfinite(c) || c == 0) return Affine::Unbounded();
    if (x.isConstant()) return Affine(x.m_center / c);
    if (c == 1) return x;
    if (c == -1) return -x;
    const double inv = 1.0 / c;
    // fl(1/c) is within u of 1/c unless it is subnormal; then multiply by an enclosure instead.
    if (MayUnderflow(inv)) return x * Affine::FromInterval(Interval(DivDown(1, c), DivUp(1, c)));
    return Affine::Scale(x, inv, 2.0);
}

Affine Affine::ConstantDivForm(double c, const Affine& x) {
    if (x.isUnbounded() || !std::isfinite(c)) return Affine::Unbounded();
    if (x.isConstant()) return Affine(c / x.m_center);
    // Scaling adds u*max|c/x|, the rounding of the scalar division.
    return Affine::Reciprocal(x) * c;
}

// --- sqrt, exp, log, sin, cos, abs, sign: the shared fits ----------------------------------------

Affine Affine::SqrtForm(const Affine& x) {
    if (x.isUnbounded()) return Affine::Unbounded();
    if (x.isConstant()) return Affine(x.m_center < 0 ? 0.0 : std::sqrt(x.m_center));  // vm::sqrt, exact
    return FromFit(x, SqrtFit(x.range()));
}

Affine Affine::ExpForm(const Affine& x) {
    if (x.isUnbounded()) return Affine::Unbounded();
    return FromFit(x, ExpFit(x.range()));
}

Affine Affine::LogForm(const Affine& x) {
    if (x.isUnbounded()) return Affine::Unbounded();
    return FromFit(x, LogFit(x.range()));
}

Affine Affine::SinOrCos(const Affine& x, bool isCos) {
    if (x.isUnbounded()) return Affine::Unbounded();
    return FromFit(x, SinCosFit(x.range(), isCos));
}

Affine sin(const Affine& x) { return Affine::Tighten(Affine::SinOrCos(x, false), sin(x.range())); }
Affine cos(const Affine& x) { return Affine::Tighten(Affine::SinOrCos(x, true), cos(x.range())); }

Affine Affine::TanForm(const Affine& x) {
    if (x.isUnbounded()) return Affine::Unbounded();
    return FromFit(x, TanFit(x.range()));
}

Affine tan(const Affine& x) { return Affine::Tighten(Affine::TanForm(x), tan(x.range())); }

Affine Affine::AbsForm(const Affine& x) {
    if (x.isUnbounded()) return Affine::Unbounded();
    return FromFit(x, AbsFit(x.range()));
}

Affine Affine::SignForm(const Affine& x) {
    if (x.isUnbounded()) return Affine::Unbounded();
    return FromFit(x, SignFit(x.range()));
}

// --- pow ----------------------------------------------------------------------------------------

Affine Affine::IntegerPower(const Affine& x, int n) { return PowerBySquaring(x, n); }

Affine Affine::PowConstant(const Affine& x, double p) { return FromFit(x, PowConstantFit(x.range(), p)); }

// A constant integer exponent |n| <= 64: repeated squaring (of 1/x for n < 0), plus glibc's
// rounding of pow. Another constant: PowConstant. A varying exponent on x > 0: exp(y*log(x)).
// Anything else, or any of these going Unbounded: the interval range of std::pow, which is itself
// Unbounded wherever pow can be NaN or infinite (0 to a negative power, negative base to a
// non-integer power, overflow).
Affine Affine::PowForms(const Affine& x, const Affine& y) {
    if (x.isUnbounded() || y.isUnbounded()) return Affine::Unbounded();
    if (y.isConstant()) {
        const double p = y.m_center;
        if (p == 0) return Affine(1.0);  // std::pow(x, 0) is 1 for every x
        if (std::floor(p) == p && std::fabs(p) <= kMaxIntegerPower && !x.isConstant()) {
            Affine base = p > 0 ? x : Affine::Reciprocal(x);
            if (!base.isUnbounded()) {
                Affine r = Affine::IntegerPower(base, static_cast<int>(std::fabs(p)));
                if (!r.isUnbounded()) return r.withExtraError(PowSlack(r.radius(), r.m_center));
            }
            return Affine::FromInterval(pow(x.range(), Interval(p)));
        }
        return Affine::PowConstant(x, p);
    }
    Interval rx = x.range();
    if (rx.lo() > 0) {
        Affine r = exp(y * log(x));
        if (!r.isUnbounded()) return r.withExtraError(PowSlack(r.radius(), r.m_center));
    }
    return Affine::FromInterval(pow(rx, y.range()));
}

// --- asin, acos, atan ---------------------------------------------------------------------------

Affine Affine::InverseTrigForm(const Affine& x, int which) {
    if (x.isUnbounded()) return Affine::Unbounded();
    return FromFit(x, InverseTrigFit(x.range(), which));
}

// --- atan2 --------------------------------------------------------------------------------------

// atan2(y, x) = atan(y/x) for x > 0, and pi/2 - atan(x/y) for y > 0, -pi/2 - atan(x/y) for y < 0
// (exact identities); each keeps the correlation of y and x through the quotient. Where two
// apply, the one with less uncorrelated remainder (error plus the terms on symbols made while
// computing it): the radius alone would prefer a fresh-symbol interval fallback of about the same
// width to a fit that follows y and x. Elsewhere (x <= 0 possible and y across 0: the branch cut,
// where atan2 jumps between -pi and pi) the interval atan2 on a fresh symbol.
Affine Affine::Atan2Forms(const Affine& y, const Affine& x) {
    if (y.isUnbounded() || x.isUnbounded()) return Unbounded();
    Interval ry = y.range(), rx = x.range();
    // Symbols made from here on are fresh to the candidates (ids increase).
    const SymbolId marker = NewSymbol();
    auto remainder = [marker](const Affine& r) {
        UpperSum sum;
        sum.add(r.m_error);
        for (int i = 0; i < r.m_count; ++i)
            if (r.m_symbols[i] > marker) sum.add(std::fabs(r.m_coefs[i]));
        return sum.value();
    };
    Affine best = Unbounded();
    if (rx.lo() > 0) best = atan(y / x);
    if (ry.lo() > 0 || ry.hi() < 0) {
        Affine other = Affine(ry.lo() > 0 ? kHalfPi : -kHalfPi) - atan(x / y);
        if (best.isUnbounded() || (!other.isUnbounded() && remainder(other) < remainder(best))) best = other;
    }
    if (best.isUnbounded()) return FromInterval(atan2(ry, rx));
    return best.withExtraError(kAtan2Slack);
}

// --- The public functions: the form, then its enclosure (Affine::Tighten) -------------------------

Affine operator/(const Affine& x, const Affine& y) {
    return Affine::Tighten(Affine::DivForms(x, y), x.range() / y.range());
}

Affine operator/(const Affine& x, double c) { return Affine::Tighten(Affine::DivConstantForm(x, c), x.range() / c); }

Affine operator/(double c, const Affine& x) { return Affine::Tighten(Affine::ConstantDivForm(c, x), c / x.range()); }

Affine sqrt(const Affine& x) { return Affine::Tighten(Affine::SqrtForm(x), sqrt(x.range())); }

Affine exp(const Affine& x) { return Affine::Tighten(Affine::ExpForm(x), exp(x.range())); }

Affine log(const Affine& x) { return Affine::Tighten(Affine::LogForm(x), log(x.range())); }

Affine abs(const Affine& x) { return Affine::Tighten(Affine::AbsForm(x), abs(x.range())); }

Affine sign(const Affine& x) { return Affine::Tighten(Affine::SignForm(x), sign(x.range())); }

Affine pow(const Affine& x, const Affine& y) {
    return Affine::Tighten(Affine::PowForms(x, y), pow(x.range(), y.range()));
}

Affine asin(const Affine& x) { return Affine::Tighten(Affine::InverseTrigForm(x, 0), asin(x.range())); }

Affine acos(const Affine& x) { return Affine::Tighten(Affine::InverseTrigForm(x, 1), acos(x.range())); }

Affine atan(const Affine& x) { return Affine::Tighten(Affine::InverseTrigForm(x, 2), atan(x.range())); }

Affine atan2(const Affine& y, const Affine& x) {
    return Affine::Tighten(Affine::Atan2Forms(y, x), atan2(y.range(), x.range()));
}

}  // namespace affray::vm
