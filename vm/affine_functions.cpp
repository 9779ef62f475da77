// vm/affine_functions.cpp: division and the nonlinear functions of affine arithmetic.
// Every unary f over the input range [a, b] becomes alpha*x + zeta +- delta (Affine::ApplyFit):
// pick any slope alpha, then bound g(t) = f(t) - alpha*t over [a, b] rigorously: at the endpoints
// and at every stationary point of g inside (one closed-form extreme for convex or concave f,
// several for sin and cos), each evaluated in interval arithmetic so that the rounding of these
// very computations is covered, then widened by glibc's slack over the whole range (the scalar
// result is glibc's f(t), not the true one). Which alpha is a choice per function, explained at
// each; if anything goes non-finite, the function falls back to its interval range on a fresh
// symbol (alpha = 0), and to Unbounded only where the scalar result can be NaN or infinite.
// asin, acos and atan are convex on one side of 0 and concave on the other, so their g is bounded
// at the endpoints, at 0, and on each side by a tangent line of g (a rigorous bound wherever the
// tangent point is, tight near g's stationary point). atan2 composes atan with a quotient and adds
// the (tiny) difference between that composition and glibc's atan2.
// Sources: Stolfi & de Figueiredo (1997), sec. 3.7-3.9 (Chebyshev and min-range approximations);
// Heidrich & Seidel (GI 1998) for the use in displacement shaders; AFFINE-NOTES.md for the pitfalls
// (a delta taken at sample points only, or delta = 0, is not conservative).
#include <algorithm>

#include "vm/affine.h"

namespace affray::vm {

namespace {

constexpr double kTwoPi = 6.283185307179586;  // 2*pi rounded to nearest (below 2*pi)
constexpr double kPi = 3.141592653589793;     // pi rounded to nearest (below pi)
constexpr double kTwoPiBelow = 6.2831853;     // sin and cos cover [-1, 1] past this width
constexpr double kTrigAnalysisLimit = 1e8;    // beyond it, sin and cos are just [-1, 1]
constexpr int kMaxIntegerPower = 64;

// An enclosure of the true f(t), and of glibc's f near t, from glibc's value r = f(t).
Interval LibmAt(double r) {
    if (!std::isfinite(r)) return Interval::Unbounded();
    return Interval(LibmDown(r), LibmUp(r));
}

// An enclosure of g(t) = f(t) - alpha*t from an enclosure of f(t). The product is widened by a
// full ulp either way (cheaper than its exact directed roundings, and as good here).
Interval GAt(const Interval& f, double alpha, double t) {
    const double p = alpha * t;
    return Interval(SubDown(f.lo(), NextUp(p)), SubUp(f.hi(), NextDown(p)));
}

// The bounds [gLo - slack, gHi + slack] of g for ApplyFit, where `slack` bounds glibc's rounding
// of f anywhere in the range; `ok` is false if anything overflowed or alpha is unusable.
struct Fit {
    double alpha = 0, lo = 0, hi = 0;
    bool ok = false;
};

Fit MakeFit(double alpha, double gLo, double gHi, double maxAbsF, double relSlack) {
    double slack = AddUp(MulUp(maxAbsF, relSlack), kLibmAbs);
    Fit f{alpha, SubDown(gLo, slack), AddUp(gHi, slack), false};
    f.ok = std::isfinite(alpha) && std::isfinite(f.lo) && std::isfinite(f.hi) && f.lo <= f.hi;
    return f;
}

double MaxAbs(const Interval& r) { return std::fmax(std::fabs(r.lo()), std::fabs(r.hi())); }

}  // namespace

// --- 1/x and division ---------------------------------------------------------------------------

// Chebyshev for 1/t on [a, b], a > 0 (convex): alpha = -1/(ab), the secant; g(t) = 1/t + |alpha|t
// has its maximum 1/a + 1/b at both endpoints and its minimum 2*sqrt(|alpha|) at t = sqrt(ab).
// Encloses the real 1/t (callers add the rounding of their scalar division).
Affine Affine::Reciprocal(const Affine& x) {
    if (x.isUnbounded()) return x;
    Interval range = x.range();
    if (!(range.lo() > 0 || range.hi() < 0)) return Unbounded();
    if (range.hi() < 0) return -Reciprocal(-x);
    const double a = range.lo(), b = range.hi();
    Interval ra(DivDown(1.0, a), DivUp(1.0, a)), rb(DivDown(1.0, b), DivUp(1.0, b));
    Interval all = Hull(ra, rb);
    if (all.isUnbounded()) return Unbounded();
    if (a == b) return FromInterval(all);
    const double alpha = -(1.0 / a) / b;
    if (!(alpha < 0)) return FromInterval(all);
    Interval ga = GAt(ra, alpha, a), gb = GAt(rb, alpha, b);
    const double gMin = 2.0 * SqrtDown(-alpha);
    Fit f =
        MakeFit(alpha, std::min({ga.lo(), gb.lo(), gMin}), std::fmax(ga.hi(), gb.hi()), 0.0, 0.0);
    return f.ok ? ApplyFit(x, f.alpha, f.lo, f.hi) : FromInterval(all);
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

// --- sqrt, exp, log -----------------------------------------------------------------------------

// Chebyshev (alpha = 1/(sqrt(a) + sqrt(b)), the secant): sqrt is concave and increasing, so the
// lowest value of the form is sqrt(a) as with min-range (no dip below 0 but rounding), while the
// remainder delta is half of min-range's. g's maximum is 1/(4 alpha) at t = 1/(4 alpha^2).
Affine Affine::SqrtForm(const Affine& x) {
    if (x.isUnbounded()) return x;
    if (x.isConstant()) return Affine(std::sqrt(x.m_center));  // sqrt is correctly rounded
    Interval range = x.range();
    if (range.lo() < 0) return Affine::Unbounded();
    const double a = range.lo(), b = range.hi();
    Interval sa(SqrtDown(a), SqrtUp(a)), sb(SqrtDown(b), SqrtUp(b));
    Interval all(sa.lo(), sb.hi());
    const double alpha = 1.0 / (std::sqrt(a) + std::sqrt(b));
    if (a == b || !(alpha > 0)) return Affine::FromInterval(all);
    Interval ga = GAt(sa, alpha, a), gb = GAt(sb, alpha, b);
    const double gMax = DivUp(0.25, alpha);
    Fit f = MakeFit(alpha, std::fmin(ga.lo(), gb.lo()), std::max({ga.hi(), gb.hi(), gMax}), sb.hi(),
                    kEpsilon);
    return f.ok ? Affine::ApplyFit(x, f.alpha, f.lo, f.hi) : Affine::FromInterval(all);
}

// alpha = min(secant, e^(a + 1/2)). The secant (Chebyshev) is tightest on narrow ranges; on wide
// ones its tangent point ln(alpha) lies far from a and the form dips far below 0 (e.g. [0, 10]
// gives [-7400, 29000]). Capping alpha at e^(a + 1/2) keeps the form's lowest value at
// alpha*(1 + a - ln alpha) = e^(a + 1/2)/2 > 0.8 e^a (the min-range idea: exp stays positive) and
// on wide ranges it is narrower than the secant as well. g is convex: maximum at an endpoint,
// minimum alpha*(1 - ln alpha) at t = ln(alpha).
Affine Affine::ExpForm(const Affine& x) {
    if (x.isUnbounded()) return x;
    Interval range = x.range();
    const double a = range.lo(), b = range.hi();
    const double ea = std::exp(a), eb = std::exp(b);
    Interval fa = LibmAt(ea), fb = LibmAt(eb);
    if (fb.isUnbounded() || !(fb.hi() <= kMaxFinite)) return Affine::Unbounded();  // overflow
    Interval all(std::fmax(0.0, fa.lo()), fb.hi());
    if (a == b) return Affine::FromInterval(all);
    const double alpha = std::fmin((eb - ea) / (b - a), std::exp(a + 0.5));
    if (!(alpha > 0)) return Affine::FromInterval(all);
    Interval ga = GAt(fa, alpha, a), gb = GAt(fb, alpha, b);
    // alpha > 0: the lower bound of alpha*(1 - ln alpha) takes the upper bound of ln alpha.
    const double gMin = MulDown(alpha, SubDown(1.0, LibmUp(std::log(alpha))));
    Fit f = MakeFit(alpha, std::min({ga.lo(), gb.lo(), gMin}), std::fmax(ga.hi(), gb.hi()), fb.hi(),
                    kLibmRel);
    return f.ok ? Affine::ApplyFit(x, f.alpha, f.lo, f.hi) : Affine::FromInterval(all);
}

// Chebyshev (secant slope): log is concave and increasing, so the form's lowest value is log(a)
// and only the top overshoots. g's maximum is -ln(alpha) - 1 at t = 1/alpha.
Affine Affine::LogForm(const Affine& x) {
    if (x.isUnbounded()) return x;
    Interval range = x.range();
    if (!(range.lo() > 0)) return Affine::Unbounded();  // log(0) = -inf, log(<0) = NaN
    const double a = range.lo(), b = range.hi();
    const double la = std::log(a), lb = std::log(b);
    Interval fa = LibmAt(la), fb = LibmAt(lb);
    Interval all(fa.lo(), fb.hi());
    if (a == b) return Affine::FromInterval(all);
    const double alpha = (lb - la) / (b - a);
    if (!(alpha > 0)) return Affine::FromInterval(all);
    Interval ga = GAt(fa, alpha, a), gb = GAt(fb, alpha, b);
    const double gMax = SubUp(-LibmDown(std::log(alpha)), 1.0);
    Fit f = MakeFit(alpha, std::fmin(ga.lo(), gb.lo()), std::max({ga.hi(), gb.hi(), gMax}),
                    MaxAbs(all), kLibmRel);
    return f.ok ? Affine::ApplyFit(x, f.alpha, f.lo, f.hi) : Affine::FromInterval(all);
}

// --- sin, cos -----------------------------------------------------------------------------------

namespace {

// sin and cos over [a, b] (width below 2*pi, |a|, |b| <= 1e8) with the secant slope alpha.
// g(t) = f(t) - alpha*t is not convex, so every stationary point of g inside [a, b] is visited:
// f'(t) = alpha at t = base + 2*pi*k, with bases +-acos(alpha) for sin and -asin(alpha),
// pi + asin(alpha) for cos. A computed point xi is within E of the true one t* (acos/asin and the
// representation of pi and of k*2*pi, with a wide margin), so any point that may lie inside is
// evaluated at xi clamped to [a, b] (still within E of t*) and widened by E^2 >= E^2/2 max|g''|,
// Taylor's bound around a stationary point.
Fit TrigFit(double a, double b, bool isCos) {
    auto f = [isCos](double t) { return isCos ? std::cos(t) : std::sin(t); };
    const double fa = f(a), fb = f(b);
    const double alpha = std::clamp((fb - fa) / (b - a), -1.0, 1.0);
    Interval ia = LibmAt(fa), ib = LibmAt(fb);
    Interval ga = GAt(ia, alpha, a), gb = GAt(ib, alpha, b);
    double gLo = std::fmin(ga.lo(), gb.lo()), gHi = std::fmax(ga.hi(), gb.hi());
    double bases[2];
    if (isCos) {
        double s = std::asin(alpha);
        bases[0] = -s;
        bases[1] = kPi + s;
    } else {
        double c = std::acos(alpha);
        bases[0] = c;
        bases[1] = -c;
    }
    for (double base : bases) {
        double k0 = std::floor((a - base) / kTwoPi);
        for (double k = k0 - 2; k <= k0 + 3; k += 1) {
            double xi = base + k * kTwoPi;
            double err = 0x1p-47 * (std::fabs(base) + 8 * std::fabs(k) + std::fabs(xi) + 4);
            if (xi < a - err || xi > b + err) continue;
            double t = std::clamp(xi, a, b);
            Interval g = GAt(LibmAt(f(t)), alpha, t);
            // g'(t*) = 0 and |g''| = |f''| <= 1: g(t) is within err^2/2 of g(t*).
            double w = MulUp(err, err);
            gLo = std::fmin(gLo, SubDown(g.lo(), w));
            gHi = std::fmax(gHi, AddUp(g.hi(), w));
        }
    }
    // |f| <= 1, and |f(t)| <= |f(a)| + |t - a| (Lipschitz 1): a bound of max |f| on [a, b].
    double maxAbsF = std::fmin(1.0, AddUp(std::fmax(MaxAbs(ia), MaxAbs(ib)), b - a));
    return MakeFit(alpha, gLo, gHi, maxAbsF, kLibmRel);
}

}  // namespace

// Chebyshev-style fit with the secant slope, unless its radius exceeds the interval range's by a
// quarter (wide ranges, where a line follows sin poorly): then the interval range on a fresh
// symbol, as for widths past 2*pi (zeta = 0, delta = 1). Past |x| = 1e8 also [-1, 1]: the
// stationary-point enumeration would need ever more care for a range that is all noise anyway.
Affine Affine::SinOrCos(const Affine& x, bool isCos) {
    if (x.isUnbounded()) return x;
    Interval range = x.range();
    const double a = range.lo(), b = range.hi();
    if (b - a >= kTwoPiBelow || std::fmax(std::fabs(a), std::fabs(b)) > kTrigAnalysisLimit)
        return ApplyFit(x, 0.0, -1.0, 1.0);
    auto all = [&] { return isCos ? cos(range) : sin(range); };
    if (a == b) return FromInterval(all());
    Fit f = TrigFit(a, b, isCos);
    if (!f.ok) return FromInterval(all());
    // Below half a radian the line is never much worse than the interval: skip the comparison.
    if (b - a > 0.5) {
        Interval r = all();
        double fitRadius = std::fabs(f.alpha) * x.radius() + 0.5 * (f.hi - f.lo);
        if (fitRadius > 1.25 * r.radius()) return FromInterval(r);
    }
    return ApplyFit(x, f.alpha, f.lo, f.hi);
}

Affine sin(const Affine& x) { return Affine::Tighten(Affine::SinOrCos(x, false), sin(x.range())); }
Affine cos(const Affine& x) { return Affine::Tighten(Affine::SinOrCos(x, true), cos(x.range())); }

// --- abs, sign ----------------------------------------------------------------------------------

// Decided signs give x or -x exactly (fabs is exact). Across 0 this is min-range, not Chebyshev:
// the Chebyshev line through the kink (alpha = (a + b)/(b - a)) makes the form dip to alpha*a < 0,
// so sqrt(abs(x)) or pow(abs(x), y) would turn Unbounded. min-range for a non-monotone function
// is alpha = 0: m/2 +- m/2 on a fresh symbol, m = max(-a, b), whose range is exactly [0, m].
Affine Affine::AbsForm(const Affine& x) {
    if (x.isUnbounded()) return x;
    Interval range = x.range();
    if (range.lo() >= 0) return x;
    if (range.hi() <= 0) return -x;
    return Affine::ApplyFit(x, 0.0, 0.0, std::fmax(-range.lo(), range.hi()));
}

// Decided ranges give the exact constants; otherwise the hull of the possible signs, 0.5 +- 0.5,
// -0.5 +- 0.5 or 0 +- 1, on a fresh symbol.
Affine Affine::SignForm(const Affine& x) {
    if (x.isUnbounded()) return x;
    Interval range = x.range();
    if (range.lo() > 0) return Affine(1.0);
    if (range.hi() < 0) return Affine(-1.0);
    return Affine::ApplyFit(x, 0.0, range.lo() < 0 ? -1.0 : 0.0, range.hi() > 0 ? 1.0 : 0.0);
}

// --- pow ----------------------------------------------------------------------------------------

Affine Affine::IntegerPower(const Affine& x, int n) {
    Affine result, base = x;
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

// x^p for a constant p on x >= 0 (x > 0 if p < 0). Chebyshev with the secant slope: t^p is convex
// for p > 1 or p < 0 and concave for 0 < p < 1, and g(t) = t^p - alpha*t has its one stationary
// point at t = (alpha/p)^(1/(p-1)) with value (1 - p)*(alpha/p)^(p/(p-1)), bounded in interval
// arithmetic. Elsewhere (negative bases) the interval range of std::pow on a fresh symbol.
Affine Affine::PowConstant(const Affine& x, double p) {
    Interval range = x.range();
    const double a = range.lo(), b = range.hi();
    if (a < 0 || (a == 0 && p < 0)) return FromInterval(pow(range, Interval(p)));
    const double pa = std::pow(a, p), pb = std::pow(b, p);
    Interval fa = LibmAt(pa), fb = LibmAt(pb);
    Interval all = Hull(fa, fb);
    if (all.isUnbounded()) return Unbounded();  // overflow, or pow(0, p < 0)
    all = Interval(std::fmax(0.0, all.lo()), all.hi());
    if (a == b) return FromInterval(all);
    const double alpha = (pb - pa) / (b - a);
    // alpha/p > 0 in exact arithmetic (x^p increases for p > 0, decreases for p < 0).
    if (!(alpha / p > 0) || !std::isfinite(alpha)) return FromInterval(all);
    Interval ip(p);
    Interval gStat = (1.0 - ip) * pow(Interval(alpha) / ip, ip / (ip - 1.0));
    Interval ga = GAt(fa, alpha, a), gb = GAt(fb, alpha, b);
    double gLo = std::fmin(ga.lo(), gb.lo()), gHi = std::fmax(ga.hi(), gb.hi());
    if (p > 1 || p < 0)
        gLo = std::fmin(gLo, gStat.lo());  // convex: the stationary point is the minimum
    else
        gHi = std::fmax(gHi, gStat.hi());  // concave: the maximum
    Fit f = MakeFit(alpha, gLo, gHi, all.hi(), kLibmRel);
    return f.ok ? ApplyFit(x, f.alpha, f.lo, f.hi) : FromInterval(all);
}

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
                if (!r.isUnbounded())
                    return r.withExtraError(
                        AddUp(MulUp(r.radius(), kLibmRel), MulUp(std::fabs(r.m_center), kLibmRel)) +
                        kLibmAbs);
            }
            return Affine::FromInterval(pow(x.range(), Interval(p)));
        }
        return Affine::PowConstant(x, p);
    }
    Interval rx = x.range();
    if (rx.lo() > 0) {
        Affine r = exp(y * log(x));
        if (!r.isUnbounded())
            return r.withExtraError(
                AddUp(MulUp(r.radius(), kLibmRel), MulUp(std::fabs(r.m_center), kLibmRel)) +
                kLibmAbs);
    }
    return Affine::FromInterval(pow(rx, y.range()));
}

// --- asin, acos, atan ---------------------------------------------------------------------------

namespace {

// asin, acos and atan have one inflection point, 0: asin is concave on [-1, 0] and convex on
// [0, 1], acos and atan the other way round. f' is even, so f'(t) = alpha at t = +-tangent(alpha).
struct InverseTrig {
    double (*f)(double);               // glibc's
    Interval (*df)(const Interval& t);  // an enclosure of the true f' at t
    double (*tangent)(double alpha);   // the t >= 0 with f'(t) = alpha (NaN if there is none)
    bool convexAbove0;                 // f convex on [0, inf), concave on (-inf, 0]
};

Interval AsinDerivative(const Interval& t) { return 1.0 / sqrt(1.0 - sqr(t)); }
Interval AcosDerivative(const Interval& t) { return -AsinDerivative(t); }
Interval AtanDerivative(const Interval& t) { return 1.0 / (1.0 + sqr(t)); }
// 1/sqrt(1 - t^2) = |alpha| at t = sqrt(1 - 1/alpha^2); 1/(1 + t^2) = alpha at sqrt(1/alpha - 1).
double AsinTangent(double alpha) { return std::sqrt(1.0 - 1.0 / (alpha * alpha)); }
double AtanTangent(double alpha) { return std::sqrt(1.0 / alpha - 1.0); }

const InverseTrig kInverseTrig[3] = {
    {[](double t) { return std::asin(t); }, AsinDerivative, AsinTangent, true},
    {[](double t) { return std::acos(t); }, AcosDerivative, AsinTangent, false},
    {[](double t) { return std::atan(t); }, AtanDerivative, AtanTangent, false},
};

// On a side [p, q] of 0 where f, hence g(t) = f(t) - alpha*t, is convex,
// g(t) >= g(s) + g'(s)(t - s) for every s and t in [p, q] (concave: <=). Returns an enclosure of
// that tangent line over [p, q]: its lower bound bounds g from below on a convex side, its upper
// bound from above on a concave one. g(s) and g'(s) are enclosed in interval arithmetic (f(s)
// with glibc's slack, f' by its exact formula), so the bound holds wherever s is; s at g's
// stationary point (f'(s) = alpha, computed approximately) makes g'(s) ~ 0 and the bound as tight
// as the extreme itself.
Interval TangentBound(const InverseTrig& fn, double alpha, double s, double p, double q) {
    s = std::fmin(std::fmax(s, p), q);  // into the side (NaN: p)
    Interval gs = GAt(LibmAt(fn.f(s)), alpha, s);
    Interval slope = fn.df(Interval(s)) - alpha;
    return gs + Hull(slope * (Interval(p) - s), slope * (Interval(q) - s));
}

// The secant slope (Chebyshev's choice for a convex or concave f) over [a, b], a < b. g's extremes
// on a side of 0 are at the side's ends (endpoints, 0) or bounded by the side's tangent line.
Fit InverseTrigFit(const InverseTrig& fn, double a, double b) {
    const double fa = fn.f(a), fb = fn.f(b);
    const double alpha = (fb - fa) / (b - a);
    Interval ia = LibmAt(fa), ib = LibmAt(fb);
    Interval ga = GAt(ia, alpha, a), gb = GAt(ib, alpha, b);
    double gLo = std::fmin(ga.lo(), gb.lo()), gHi = std::fmax(ga.hi(), gb.hi());
    const double s = fn.tangent(alpha);
    if (b > 0) {
        Interval t = TangentBound(fn, alpha, s, std::fmax(a, 0.0), b);
        if (fn.convexAbove0)
            gLo = std::fmin(gLo, t.lo());
        else
            gHi = std::fmax(gHi, t.hi());
    }
    if (a < 0) {
        Interval t = TangentBound(fn, alpha, -s, a, std::fmin(b, 0.0));
        if (fn.convexAbove0)
            gHi = std::fmax(gHi, t.hi());
        else
            gLo = std::fmin(gLo, t.lo());
    }
    if (a < 0 && b > 0) {  // 0 ends both sides
        Interval g0 = GAt(LibmAt(fn.f(0.0)), alpha, 0.0);
        gLo = std::fmin(gLo, g0.lo());
        gHi = std::fmax(gHi, g0.hi());
    }
    // f is monotone: |f| is largest at an endpoint.
    return MakeFit(alpha, gLo, gHi, std::fmax(MaxAbs(ia), MaxAbs(ib)), kLibmRel);
}

}  // namespace

// Chebyshev (secant slope) rather than min-range for all three: min-range takes alpha = f' at an
// endpoint, which is infinite at +-1 for asin and acos and nearly 0 far out for atan (the form
// would then be the interval range); their results are bounded anyway, so no domain needs the
// min-range guarantee that the form stays inside [f(a), f(b)] (Tighten clips the range to it).
// As for sin and cos, a fit wider than the interval range by a quarter (wide atan ranges, where a
// line follows the arctangent poorly) gives the interval range on a fresh symbol instead.
Affine Affine::InverseTrigForm(const Affine& x, int which) {
    if (x.isUnbounded()) return x;
    Interval range = x.range();
    // asin and acos are NaN outside [-1, 1].
    if (which != 2 && (range.lo() < -1 || range.hi() > 1)) return Unbounded();
    auto all = [&] { return which == 0 ? asin(range) : which == 1 ? acos(range) : atan(range); };
    const double a = range.lo(), b = range.hi();
    if (a == b) return FromInterval(all());
    Fit f = InverseTrigFit(kInverseTrig[which], a, b);
    if (!f.ok) return FromInterval(all());
    Interval r = all();
    double fitRadius = std::fabs(f.alpha) * x.radius() + 0.5 * (f.hi - f.lo);
    if (fitRadius > 1.25 * r.radius()) return FromInterval(r);
    return ApplyFit(x, f.alpha, f.lo, f.hi);
}

// --- atan2 --------------------------------------------------------------------------------------

namespace {

constexpr double kHalfPi = 1.5707963267948966;  // pi/2 rounded to nearest
// Bound of |glibc atan2(y, x) - T|, T the scalar value of atan(y/x) or +-pi/2 - atan(x/y) as
// computed by the forms (|theta| <= pi, each glibc call within kLibmRel*|f| + kLibmAbs):
// atan2's own error (pi*kLibmRel), atan's at fl(q) (pi/2*kLibmRel), atan(fl(q)) - atan(q) <=
// |fl(q) - q|/(1 + q^2) <= u, pi/2 - fl(pi/2) < u/2, the rounding of +-pi/2 - A (<= pi*u):
// under 5.4*kLibmRel + 2*kLibmAbs in all.
constexpr double kAtan2Slack = 8 * kLibmRel + 4 * kLibmAbs;

}  // namespace

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
        if (best.isUnbounded() || (!other.isUnbounded() && remainder(other) < remainder(best)))
            best = other;
    }
    if (best.isUnbounded()) return FromInterval(atan2(ry, rx));
    return best.withExtraError(kAtan2Slack);
}

// --- The public functions: the form, then its enclosure (Affine::Tighten) -------------------------

Affine operator/(const Affine& x, const Affine& y) {
    return Affine::Tighten(Affine::DivForms(x, y), x.range() / y.range());
}

Affine operator/(const Affine& x, double c) {
    return Affine::Tighten(Affine::DivConstantForm(x, c), x.range() / c);
}

Affine operator/(double c, const Affine& x) {
    return Affine::Tighten(Affine::ConstantDivForm(c, x), c / x.range());
}

Affine sqrt(const Affine& x) {
    return Affine::Tighten(Affine::SqrtForm(x), sqrt(x.range()));
}

Affine exp(const Affine& x) {
    return Affine::Tighten(Affine::ExpForm(x), exp(x.range()));
}

Affine log(const Affine& x) {
    return Affine::Tighten(Affine::LogForm(x), log(x.range()));
}

Affine abs(const Affine& x) {
    return Affine::Tighten(Affine::AbsForm(x), abs(x.range()));
}

Affine sign(const Affine& x) {
    return Affine::Tighten(Affine::SignForm(x), sign(x.range()));
}

Affine pow(const Affine& x, const Affine& y) {
    return Affine::Tighten(Affine::PowForms(x, y), pow(x.range(), y.range()));
}

Affine asin(const Affine& x) {
    return Affine::Tighten(Affine::InverseTrigForm(x, 0), asin(x.range()));
}

Affine acos(const Affine& x) {
    return Affine::Tighten(Affine::InverseTrigForm(x, 1), acos(x.range()));
}

Affine atan(const Affine& x) {
    return Affine::Tighten(Affine::InverseTrigForm(x, 2), atan(x.range()));
}

Affine atan2(const Affine& y, const Affine& x) {
    return Affine::Tighten(Affine::Atan2Forms(y, x), atan2(y.range(), x.range()));
}

}  // namespace affray::vm
