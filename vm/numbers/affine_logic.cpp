// vm/numbers/affine_logic.cpp: the piecewise-constant and branching functions of affine arithmetic:
// floor, ceil, round, Min, Max, the comparisons, And/Or/Not, TruthOf and Join (the value of an
// undecided branch). Separate from affine_functions.cpp because none of them is a smooth fit:
// each is either decided over the whole region (an exact constant, or one operand itself) or
// bounded by a form that keeps the correlation with its operands plus a bounded jump.
// Comparisons are decided from the affine difference a - b, so that correlated operands decide
// where their ranges overlap (x < x + 1 for any x): see SignOfDifference (vm/numbers/affine_fit.h). An undecided
// comparison is 0.5 +- 0.5 on a fresh symbol (the step form of AFFINE-NOTES), never Unbounded.
// Sources: Stolfi & de Figueiredo (1997), sec. 3.10 (mixed affine-interval evaluation);
// AFFINE-NOTES.md ("Conditionals").
#include "vm/numbers/affine.h"
#include "vm/numbers/affine_fit.h"

namespace affray::vm {

Affine Affine::FromTruth(Truth t) {
    if (t == Truth::True) return Affine(1.0);
    if (t == Truth::False) return Affine(0.0);
    return FromSymbol(0.5, 0.5, NewSymbol());  // range exactly [0, 1]
}

// --- floor, ceil, round -------------------------------------------------------------------------

// StepFit (vm/numbers/affine_fit.cpp): the exact constant where the range lies in one integer cell, x
// itself past 2^52, else x plus the jump on a fresh symbol.
Affine Affine::StepForm(const Affine& x, double (*f)(double), double gLo, double gHi) {
    if (x.isUnbounded()) return Affine::Unbounded();
    return FromFit(x, StepFit(x.range(), f, gLo, gHi));
}

Affine floor(const Affine& x) {
    return Affine::Tighten(Affine::StepForm(
                               x, [](double t) { return std::floor(t); }, -1.0, 0.0),
                           floor(x.range()));
}

Affine ceil(const Affine& x) {
    return Affine::Tighten(Affine::StepForm(
                               x, [](double t) { return std::ceil(t); }, 0.0, 1.0),
                           ceil(x.range()));
}

// std::round rounds halves away from zero: round(t) - t lies in [-1/2, 1/2] either way.
Affine round(const Affine& x) {
    return Affine::Tighten(Affine::StepForm(
                               x, [](double t) { return std::round(t); }, -0.5, 0.5),
                           round(x.range()));
}

// --- Comparisons --------------------------------------------------------------------------------

// SignOfDifference, CompareForms (vm/numbers/affine_fit.h), as for every affine type.

Affine Less(const Affine& a, const Affine& b) { return Affine::FromTruth(CompareForms<Comparison::Less>(a, b)); }

Affine LessEq(const Affine& a, const Affine& b) { return Affine::FromTruth(CompareForms<Comparison::LessEq>(a, b)); }

Affine Equal(const Affine& a, const Affine& b) { return Affine::FromTruth(CompareForms<Comparison::Equal>(a, b)); }

Affine NotEqual(const Affine& a, const Affine& b) {
    return Affine::FromTruth(CompareForms<Comparison::NotEqual>(a, b));
}

// --- Logic --------------------------------------------------------------------------------------

Truth TruthOf(const Affine& x) { return TruthOf(x.range()); }

Affine And(const Affine& a, const Affine& b) { return Affine::FromTruth(TruthAnd(TruthOf(a), TruthOf(b))); }

Affine Or(const Affine& a, const Affine& b) { return Affine::FromTruth(TruthOr(TruthOf(a), TruthOf(b))); }

Affine Not(const Affine& a) { return Affine::FromTruth(TruthNot(TruthOf(a))); }

// --- Min, Max -----------------------------------------------------------------------------------

// MinMaxOfForms (vm/numbers/affine_fit.h): where the sign of a - b is decided, the operand itself
// (exactly, correlations and all). Otherwise the abs formula keeps the symbols of a and b in
// (a + b)/2; abs(a - b) is min-range (>= 0) on a fresh symbol. An unbounded operand leaves the form unknown, and the result is the
// interval rule's (fmin(NaN, b) = b): partial, or bounded again (min(max(x, 0), 1) in [0, 1]).
Affine Min(const Affine& a, const Affine& b) {
    return Affine::Tighten(MinMaxOfForms(a, b, false, &Affine::withExtraError), Min(a.range(), b.range()));
}

Affine Max(const Affine& a, const Affine& b) {
    return Affine::Tighten(MinMaxOfForms(a, b, true, &Affine::withExtraError), Max(a.range(), b.range()));
}

// --- Join ---------------------------------------------------------------------------------------

// With m = (a + b)/2 and h = (a - b)/2 as forms, every scalar a = (a + b)/2 + (a - b)/2 lies within
// D = max|h| (over h's whole range) of (a + b)/2, b likewise: m plus the independent error
// JoinSlack (vm/numbers/affine_fit.h) contains both.
Affine Join(const Affine& a, const Affine& b) {
    if (a.isUnbounded() || b.isUnbounded()) return Affine::UnboundedWithin(Hull(a.range(), b.range()));
    Interval hull = Hull(a.range(), b.range());
    Affine m = (a + b) * 0.5;
    Affine h = (a - b) * 0.5;
    if (m.isUnbounded() || h.isUnbounded()) return Affine::FromInterval(hull);
    const double extra = JoinSlack(MaxAbs(h.range()), MaxAbs(m.range()));
    if (!(extra <= kMaxFinite)) return Affine::FromInterval(hull);
    return Affine::Tighten(m.withExtraError(extra), hull);
}

}  // namespace affray::vm
