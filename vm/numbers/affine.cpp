// vm/numbers/affine.cpp: the core of affine arithmetic: construction, ranges, term bookkeeping (merge,
// fold, fresh symbols), the linear operations, products, squares and ApplyFit, which turns any
// linear approximation alpha*x + zeta +- delta of a unary function into a form.
// Rounding (see vm/numbers/rounding.h): coefficients are computed rounded to nearest and a bound on each
// rounding error is added to the error; on top of that every operation adds u*max|result| for the
// rounding of the double (scalar) operation itself, since the scalar result is fl(x op y), not the
// exact value that the form encloses. Linear operations put their error into e; products and
// unary functions put theirs (input errors, the nonlinear remainder, all rounding) into a fresh
// symbol, so that later operations keep the correlation (Stolfi & de Figueiredo 1997, sec. 3.6).
#include "vm/numbers/affine.h"

#include <algorithm>
#include <atomic>
#include <cstdio>

namespace affray::vm {

namespace {

thread_local Affine::SymbolId t_nextSymbol = Affine::kFirstFreshSymbol;

// The active capacity. Atomic only so that a bench changing it is not a data race on paper: a
// relaxed load is a plain load on x86-64 and ARM, and each operation reads it once.
std::atomic<int> g_capacity{Affine::kCapacity};

// Error bounds of shared-term sums count at most this many roundings per term. Taken for the
// largest capacity, so they hold whatever the active one (the slack is a few ulps either way).
constexpr double kTermSlack = 2.0 * Affine::kMaxCapacity + 4.0;
// The product's remainder is computed in about 5*capacity + 12 roundings (the sums of up to
// capacity terms, then P - Q with Q <= P/2), which kSumSlack covers up to 256.
static_assert(5 * Affine::kMaxCapacity + 32 <= 256, "raise kSumSlack for this capacity");

}  // namespace

int Affine::Capacity() { return g_capacity.load(std::memory_order_relaxed); }

bool Affine::SetCapacity(int n) {
    if (n < 2 || n > kMaxCapacity) return false;
    g_capacity.store(n, std::memory_order_relaxed);
    return true;
}

// Where an operation writes its terms: straight into the result when they are sure to fit the
// active capacity (no copy), else into a scratch list long enough for a merge of two full forms
// plus a fresh term, which finish() folds down to the capacity.
struct Affine::Terms {
    static constexpr int kMax = 2 * kMaxCapacity + 2;
    SymbolId* symbols;
    double* coefs;
    int count = 0;
    int capacity;
    bool direct;
    SymbolId scratchSymbols[kMax];
    double scratchCoefs[kMax];

    Terms(Affine& result, int maxTerms)
        : capacity(g_capacity.load(std::memory_order_relaxed)), direct(maxTerms <= capacity) {
        symbols = direct ? result.m_symbols : scratchSymbols;
        coefs = direct ? result.m_coefs : scratchCoefs;
    }
    Terms(const Terms&) = delete;

    // Appends a term with a larger id than any so far; zero coefficients are dropped.
    void push(SymbolId s, double c) {
        symbols[count] = s;
        coefs[count] = c;
        count += (c != 0);
    }
    // Inserts a term with an id not yet present, keeping the ids sorted.
    void insert(SymbolId s, double c) {
        int i = count;
        while (i > 0 && symbols[i - 1] > s) {
            symbols[i] = symbols[i - 1];
            coefs[i] = coefs[i - 1];
            --i;
        }
        symbols[i] = s;
        coefs[i] = c;
        ++count;
    }
};

Affine Affine::Unbounded() {
    Affine r;
    r.m_error = kInfinity;
    return r;
}

void Affine::BeginEvaluation() { t_nextSymbol = kFirstFreshSymbol; }

Affine::SymbolId Affine::NewSymbol() { return t_nextSymbol++; }

Affine Affine::FromSymbol(double center, double radius, SymbolId id) {
    if (!std::isfinite(center) || !std::isfinite(radius)) return Unbounded();
    Affine r(center);
    r.m_symbols[0] = id;
    r.m_coefs[0] = radius;
    r.m_count = radius != 0;
    return r;
}

Affine Affine::UnboundedWithin(const Interval& range) {
    if (!range.isUnbounded()) return FromInterval(range);
    Affine r = Unbounded();
    r.m_lo = range.lo();
    r.m_hi = range.hi();
    r.m_rangeCached = true;  // marks the partial range as set (range())
    return r;
}

Affine Affine::FromInterval(const Interval& range) {
    if (range.isUnbounded()) return UnboundedWithin(range);
    if (range.isPoint()) return Affine(range.lo());
    Affine r(range.mid());
    r.m_symbols[0] = NewSymbol();
    r.m_coefs[0] = range.radius();
    r.m_count = 1;
    return r;
}

bool Affine::finish(double center, double error, Terms& terms) {
    if (!terms.direct) {
        // Fold the smallest terms other than eps_u and eps_v into the error until the rest fit.
        while (terms.count > terms.capacity) {
            int smallest = -1;
            for (int i = 0; i < terms.count; ++i) {
                if (terms.symbols[i] < kFirstFreshSymbol) continue;
                if (smallest < 0 || std::fabs(terms.coefs[i]) < std::fabs(terms.coefs[smallest])) smallest = i;
            }
            // Only eps_u and eps_v left over capacity: a capacity below 2 (SetCapacity refuses it).
            if (smallest < 0) return false;
            error = AddUp(error, std::fabs(terms.coefs[smallest]));
            for (int i = smallest + 1; i < terms.count; ++i) {
                terms.symbols[i - 1] = terms.symbols[i];
                terms.coefs[i - 1] = terms.coefs[i];
            }
            --terms.count;
        }
        for (int i = 0; i < terms.count; ++i) {
            m_symbols[i] = terms.symbols[i];
            m_coefs[i] = terms.coefs[i];
        }
    }
    m_center = center;
    m_error = error;
    m_count = terms.count;
    return std::fabs(center) <= kMaxFinite && error <= kMaxFinite;
}

double Affine::coefficientOf(SymbolId id) const {
    for (int i = 0; i < m_count; ++i)
        if (m_symbols[i] == id) return m_coefs[i];
    return 0.0;
}

double Affine::radius() const {
    if (isUnbounded()) return kInfinity;
    UpperSum r;
    r.add(m_error);
    for (int i = 0; i < m_count; ++i) r.add(std::fabs(m_coefs[i]));
    return r.value();
}

Interval Affine::range() const {
    if (isUnbounded()) return m_rangeCached ? Interval::Extended(m_lo, m_hi) : Interval::Unbounded();
    if (m_rangeCached) return Interval(m_lo, m_hi);
    double r = radius();
    double lo = SubDown(m_center, r), hi = AddUp(m_center, r);
    // Both bounds hold every scalar value, so they overlap; if rounding ever made them miss
    // each other, the form's own range is still valid.
    if (std::fmax(lo, m_lo) <= std::fmin(hi, m_hi)) return Interval(std::fmax(lo, m_lo), std::fmin(hi, m_hi));
    return Interval(lo, hi);
}

Affine Affine::Tighten(Affine r, const Interval& enclosure) {
    // An unbounded form knows nothing: the enclosure is all there is (partial, or finite again).
    if (r.isUnbounded()) return UnboundedWithin(enclosure);
    if (enclosure.isUnbounded()) return r;
    r.m_rangeCached = false;
    r.m_lo = std::fmax(r.m_lo, enclosure.lo());
    r.m_hi = std::fmin(r.m_hi, enclosure.hi());
    Interval full = r.range();
    r.m_lo = full.lo();
    r.m_hi = full.hi();
    r.m_rangeCached = true;
    return r;
}

Interval Affine::evaluateAt(double epsU, double epsV) const {
    if (isUnbounded()) return Interval::Unbounded();
    double lo = m_center, hi = m_center;
    UpperSum rest;
    rest.add(m_error);
    for (int i = 0; i < m_count; ++i) {
        double c = m_coefs[i];
        if (m_symbols[i] == kSymbolU || m_symbols[i] == kSymbolV) {
            double eps = m_symbols[i] == kSymbolU ? epsU : epsV;
            lo = AddDown(lo, MulDown(c, eps));
            hi = AddUp(hi, MulUp(c, eps));
        } else {
            rest.add(std::fabs(c));
        }
    }
    double r = rest.value();
    return Interval(SubDown(lo, r), AddUp(hi, r));
}

std::string Affine::toString() const {
    if (isUnbounded()) return "unbounded";
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.17g", m_center);
    std::string s = buf;
    for (int i = 0; i < m_count; ++i) {
        double c = m_coefs[i];
        std::snprintf(buf, sizeof buf, " %c %.17g*e%u", c < 0 ? '-' : '+', std::fabs(c),
                      static_cast<unsigned>(m_symbols[i]));
        s += buf;
    }
    if (m_error != 0) {
        std::snprintf(buf, sizeof buf, " +- %.17g", m_error);
        s += buf;
    }
    return s;
}

Affine Affine::withExtraError(double extra) const {
    if (isUnbounded()) return Unbounded();
    Affine r = *this;
    r.resetEnclosure();
    r.m_error = AddUp(m_error, extra);
    if (!(r.m_error <= kMaxFinite)) return Unbounded();
    return r;
}

Affine operator-(const Affine& x) {
    Affine r = x;
    r.m_lo = -x.m_hi;  // negation is exact: the enclosure negates too
    r.m_hi = -x.m_lo;
    r.m_center = -x.m_center;
    for (int i = 0; i < x.m_count; ++i) r.m_coefs[i] = -x.m_coefs[i];
    return r;
}

template <bool kSubtract>
Affine Affine::AddForms(const Affine& x, const Affine& y) {
    if (x.isUnbounded() || y.isUnbounded()) return Affine::Unbounded();
    const double sy = kSubtract ? -1.0 : 1.0;
    // Both exact constants: the scalar result is exactly this double.
    if (x.isConstant() && y.isConstant()) return Affine(x.center() + sy * y.center());
    Affine r;
    Terms t(r, x.m_count + y.m_count);
    // Locals, not t's members, in the loop: the stores through t.symbols could alias them.
    SymbolId* ts = t.symbols;
    double* tc = t.coefs;
    int n = 0;
    auto push = [&](SymbolId sym, double c) {
        ts[n] = sym;
        tc[n] = c;
        n += (c != 0);
    };
    double absSum = 0;
    int i = 0, j = 0;
    const int nx = x.m_count, ny = y.m_count;
    while (i < nx && j < ny) {
        SymbolId a = x.m_symbols[i], b = y.m_symbols[j];
        double c;
        if (a == b) {
            c = x.m_coefs[i++] + sy * y.m_coefs[j++];
        } else if (a < b) {
            c = x.m_coefs[i++];
            b = a;
        } else {
            c = sy * y.m_coefs[j++];
        }
        absSum += std::fabs(c);
        push(b, c);
    }
    for (; i < nx; ++i) {
        absSum += std::fabs(x.m_coefs[i]);
        push(x.m_symbols[i], x.m_coefs[i]);
    }
    for (; j < ny; ++j) {
        absSum += std::fabs(y.m_coefs[j]);
        push(y.m_symbols[j], sy * y.m_coefs[j]);
    }
    t.count = n;
    const double center = x.m_center + sy * y.m_center;
    absSum += std::fabs(center);
    if (!r.finish(center, LinearError(x.m_error + y.m_error, absSum), t)) r = Unbounded();
    return r;
}

Affine operator+(const Affine& x, const Affine& y) {
    return Affine::Tighten(Affine::AddForms<false>(x, y), x.range() + y.range());
}
Affine operator-(const Affine& x, const Affine& y) {
    return Affine::Tighten(Affine::AddForms<true>(x, y), x.range() - y.range());
}

Affine operator+(const Affine& x, double c) {
    if (x.isUnbounded() || !std::isfinite(c)) return Affine::Unbounded();
    return Affine::Tighten(Affine::AddConstantForm(x, c), x.range() + c);
}

Affine Affine::AddConstantForm(const Affine& x, double c) {
    if (c == 0) return x;
    if (x.isConstant()) return Affine(x.m_center + c);
    Affine r = x;
    r.resetEnclosure();
    r.m_center = x.m_center + c;
    double absSum = std::fabs(r.m_center);
    for (int i = 0; i < x.m_count; ++i) absSum += std::fabs(x.m_coefs[i]);
    r.m_error = LinearError(x.m_error, absSum);
    if (!(std::fabs(r.m_center) <= kMaxFinite && r.m_error <= kMaxFinite)) return Affine::Unbounded();
    return r;
}

Affine operator*(const Affine& x, double c) {
    if (x.isUnbounded() || !std::isfinite(c)) return Affine::Unbounded();
    return Affine::Tighten(Affine::MulConstantForm(x, c), x.range() * c);
}

Affine Affine::MulConstantForm(const Affine& x, double c) {
    if (c == 0) return Affine(0.0);
    if (c == 1) return x;
    if (c == -1) return -x;
    if (x.isConstant()) return Affine(x.m_center * c);
    return Affine::Scale(x, c, 1.0);
}

Affine Affine::Scale(const Affine& x, double c, double roundingFactor) {
    if (x.isUnbounded() || !std::isfinite(c)) return Unbounded();
    Affine r;
    r.m_center = x.m_center * c;
    double absSum = std::fabs(r.m_center);
    int n = 0;
    for (int i = 0; i < x.m_count; ++i) {
        // A product may underflow to 0: such a term is dropped (its rounding is in the slack).
        double z = x.m_coefs[i] * c;
        r.m_symbols[n] = x.m_symbols[i];
        r.m_coefs[n] = z;
        absSum += std::fabs(z);
        n += (z != 0);
    }
    r.m_count = n;
    double scaledError = std::fabs(c) * x.m_error * (1 + kEpsilon);
    r.m_error = LinearError(scaledError, absSum * roundingFactor) + kUnderflowSlack;
    if (!(std::fabs(r.m_center) <= kMaxFinite && r.m_error <= kMaxFinite)) return Unbounded();
    return r;
}

// (x0 + X + Ex)(y0 + Y + Ey) with X = sum xi*eps_i and |Ex| <= ex:
//   = x0*y0 + sum (x0*yi + y0*xi) eps_i + [x0*Ey + y0*Ex] + (X + Ex)(Y + Ey).
// In the quadratic part, the diagonal sum xi*yi*eps_i^2 lies in [min(0, .), max(0, .)] per term,
// so its midpoint (1/2) sum xi*yi moves to the center and the rest is bounded by
// (rx + ex)(ry + ey) - (1/2) sum |xi*yi| (the tighter product rule of AFFINE-NOTES).
Affine operator*(const Affine& x, const Affine& y) {
    if (x.isUnbounded() || y.isUnbounded()) return Affine::Unbounded();
    return Affine::Tighten(Affine::MulForms(x, y), x.range() * y.range());
}

Affine Affine::MulForms(const Affine& x, const Affine& y) {
    if (x.isConstant()) return y * x.m_center;
    if (y.isConstant()) return x * y.m_center;
    const double x0 = x.m_center, y0 = y.m_center;
    Affine r;
    Affine::Terms t(r, x.m_count + y.m_count + 1);
    Affine::SymbolId* ts = t.symbols;
    double* tc = t.coefs;
    int n = 0;
    auto push = [&](Affine::SymbolId sym, double c) {
        ts[n] = sym;
        tc[n] = c;
        n += (c != 0);
    };
    double rx = 0, ry = 0, diag = 0, absDiag = 0, absSum = 0;
    int i = 0, j = 0;
    while (i < x.m_count && j < y.m_count) {
        Affine::SymbolId a = x.m_symbols[i], b = y.m_symbols[j];
        double c;
        if (a == b) {
            double xi = x.m_coefs[i++], yi = y.m_coefs[j++];
            c = x0 * yi + y0 * xi;
            double p = xi * yi;
            diag += p;
            absDiag += std::fabs(p);
            rx += std::fabs(xi);
            ry += std::fabs(yi);
        } else if (a < b) {
            double xi = x.m_coefs[i++];
            c = y0 * xi;
            rx += std::fabs(xi);
            b = a;
        } else {
            double yi = y.m_coefs[j++];
            c = x0 * yi;
            ry += std::fabs(yi);
        }
        absSum += std::fabs(c);
        push(b, c);
    }
    for (; i < x.m_count; ++i) {
        double c = y0 * x.m_coefs[i];
        rx += std::fabs(x.m_coefs[i]);
        absSum += std::fabs(c);
        push(x.m_symbols[i], c);
    }
    for (; j < y.m_count; ++j) {
        double c = x0 * y.m_coefs[j];
        ry += std::fabs(y.m_coefs[j]);
        absSum += std::fabs(c);
        push(y.m_symbols[j], c);
    }
    t.count = n;
    const double center = x0 * y0 + 0.5 * diag;
    absSum += std::fabs(center);
    const double delta = ProductRemainder({x0, y0, rx, ry, x.m_error, y.m_error, diag, absDiag, absSum}, kTermSlack);
    if (!(delta <= kMaxFinite)) return Affine::Unbounded();
    t.insert(Affine::NewSymbol(), delta);
    if (!r.finish(center, 0.0, t)) r = Affine::Unbounded();
    return r;
}

// (x0 + X + E)^2 = x0^2 + 2*x0*X + 2*x0*E + (X + E)^2 with (X + E)^2 in [0, q], q = (r + e)^2.
Affine sqr(const Affine& x) {
    if (x.isUnbounded()) return Affine::Unbounded();
    return Affine::Tighten(Affine::SqrForm(x), sqr(x.range()));
}

Affine Affine::SqrForm(const Affine& x) {
    if (x.isConstant()) return Affine(x.m_center * x.m_center);
    const double x0 = x.m_center, twoX0 = 2 * x0;
    Affine result;
    Affine::Terms t(result, x.m_count + 1);
    double r = 0, absSum = 0;
    int n = 0;
    for (int i = 0; i < x.m_count; ++i) {
        double c = twoX0 * x.m_coefs[i];
        r += std::fabs(x.m_coefs[i]);
        absSum += std::fabs(c);
        t.symbols[n] = x.m_symbols[i];
        t.coefs[n] = c;
        n += (c != 0);
    }
    t.count = n;
    const SquareParts sq = SquareRemainder(x0, r, x.m_error, absSum, kTermSlack);
    if (!(sq.error <= kMaxFinite)) return Affine::Unbounded();
    t.insert(Affine::NewSymbol(), sq.error);
    if (!result.finish(sq.center, 0.0, t)) result = Affine::Unbounded();
    return result;
}

Affine Affine::ApplyFit(const Affine& x, double alpha, double gLo, double gHi) {
    if (x.isUnbounded() || !(gLo <= gHi) || !std::isfinite(alpha)) return Unbounded();
    const double zeta = 0.5 * gLo + 0.5 * gHi;
    const double delta0 = std::fmax(SubUp(gHi, zeta), SubUp(zeta, gLo));
    if (!(std::fabs(zeta) <= kMaxFinite && delta0 <= kMaxFinite)) return Unbounded();
    Affine r;
    Terms t(r, x.m_count + 1);
    if (alpha == 0) {
        // zeta +- delta0 exactly: no coefficient is computed, so nothing else is rounded.
        if (delta0 > 0) t.push(NewSymbol(), delta0);
        if (!r.finish(zeta, 0.0, t)) r = Unbounded();
        return r;
    }
    double absSum = 0;
    int n = 0;
    for (int i = 0; i < x.m_count; ++i) {
        double c = alpha * x.m_coefs[i];
        absSum += std::fabs(c);
        t.symbols[n] = x.m_symbols[i];
        t.coefs[n] = c;
        n += (c != 0);
    }
    t.count = n;
    const double ax0 = alpha * x.m_center;
    const double center = ax0 + zeta;
    absSum += std::fabs(ax0) + std::fabs(center);
    const double delta = (delta0 + std::fabs(alpha) * x.m_error + absSum * kEpsilon) * kSumSlack + kUnderflowSlack;
    if (!(delta <= kMaxFinite)) return Unbounded();
    t.insert(NewSymbol(), delta);
    if (!r.finish(center, 0.0, t)) r = Unbounded();
    return r;
}

}  // namespace affray::vm
