// vm/numbers/affine_fit.cpp: the approximation math of affine arithmetic (vm/numbers/affine_fit.h), for every
// affine form type. Every unary f over the input range [a, b] becomes alpha*x + zeta +- delta:
// pick any slope alpha, then bound g(t) = f(t) - alpha*t over [a, b] rigorously: at the endpoints
// and at every stationary point of g inside (one closed-form extreme for convex or concave f,
// several for sin and cos), each evaluated in interval arithmetic so that the rounding of these
// very computations is covered, then widened by glibc's slack over the whole range (the scalar
// result is glibc's f(t), not the true one). Which alpha is a choice per function, explained at
// each; if anything goes non-finite, the function falls back to its interval range (a Range fit),
// and to Unbounded only where the scalar result can be NaN or infinite.
// asin, acos and atan are convex on one side of 0 and concave on the other, so their g is bounded
// at the endpoints, at 0, and on each side by a tangent line of g (a rigorous bound wherever the
// tangent point is, tight near g's stationary point).
// Sources: Stolfi & de Figueiredo (1997), sec. 3.7-3.9 (Chebyshev and min-range approximations);
// Heidrich & Seidel (GI 1998) for the use in displacement shaders; AFFINE-NOTES.md for the pitfalls
// (a delta taken at sample points only, or delta = 0, is not conservative).
#include "vm/numbers/affine_fit.h"

#include <algorithm>

namespace affray::vm {

namespace {

constexpr double kTwoPi = 6.283185307179586;     // 2*pi rounded to nearest (below 2*pi)
constexpr double kPi = 3.141592653589793;        // pi rounded to nearest (below pi)
constexpr double kPiAbove = 3.1415926535897936;  // the next double (above pi)
constexpr double kTwoPiBelow = 6.2831853;        // sin and cos cover [-1, 1] past this width
constexpr double kTrigAnalysisLimit = 1e8;       // beyond it, sin and cos are just [-1, 1]

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

// The bounds [gLo - slack, gHi + slack] of g for a Line, where `slack` bounds glibc's rounding
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

// The Line of a usable fit, else the range `all` (f's interval result, kept with the Line too).
AffineFit LineOr(const Fit& f, const Interval& all) {
    return f.ok ? AffineFit::Line(f.alpha, f.lo, f.hi, all) : AffineFit::RangeOf(all);
}

}  // namespace

// --- 1/x ----------------------------------------------------------------------------------------

// Chebyshev for 1/t on [a, b], a > 0 (convex): alpha = -1/(ab), the secant; g(t) = 1/t + |alpha|t
// has its maximum 1/a + 1/b at both endpoints and its minimum 2*sqrt(|alpha|) at t = sqrt(ab).
// Encloses the real 1/t (callers add the rounding of their scalar division).
AffineFit ReciprocalFit(const Interval& range) {
    const double a = range.lo(), b = range.hi();
    Interval ra(DivDown(1.0, a), DivUp(1.0, a)), rb(DivDown(1.0, b), DivUp(1.0, b));
    Interval all = Hull(ra, rb);
    if (all.isUnbounded()) return AffineFit::Of(AffineFit::Kind::Unbounded);
    if (a == b) return AffineFit::RangeOf(all);
    const double alpha = -(1.0 / a) / b;
    if (!(alpha < 0)) return AffineFit::RangeOf(all);
    Interval ga = GAt(ra, alpha, a), gb = GAt(rb, alpha, b);
    const double gMin = 2.0 * SqrtDown(-alpha);
    return LineOr(MakeFit(alpha, std::min({ga.lo(), gb.lo(), gMin}), std::fmax(ga.hi(), gb.hi()), 0.0, 0.0), all);
}

// --- sqrt, exp, log -----------------------------------------------------------------------------

// Chebyshev (alpha = 1/(sqrt(a) + sqrt(b)), the secant): sqrt is concave and increasing, so the
// lowest value of the form is sqrt(a) as with min-range (no dip below 0 but rounding), while the
// remainder delta is half of min-range's. g's maximum is 1/(4 alpha) at t = 1/(4 alpha^2).
AffineFit SqrtFit(const Interval& range) {
    if (range.lo() < 0) return AffineFit::Of(AffineFit::Kind::Unbounded);
    const double a = range.lo(), b = range.hi();
    Interval sa(SqrtDown(a), SqrtUp(a)), sb(SqrtDown(b), SqrtUp(b));
    Interval all(sa.lo(), sb.hi());
    const double alpha = 1.0 / (std::sqrt(a) + std::sqrt(b));
    if (a == b || !(alpha > 0)) return AffineFit::RangeOf(all);
    Interval ga = GAt(sa, alpha, a), gb = GAt(sb, alpha, b);
    const double gMax = DivUp(0.25, alpha);
    return LineOr(MakeFit(alpha, std::fmin(ga.lo(), gb.lo()), std::max({ga.hi(), gb.hi(), gMax}), sb.hi(), kEpsilon),
                  all);
}

// alpha = min(secant, e^(a + 1/2)). The secant (Chebyshev) is tightest on narrow ranges; on wide
// ones its tangent point ln(alpha) lies far from a and the form dips far below 0 (e.g. [0, 10]
// gives [-7400, 29000]). Capping alpha at e^(a + 1/2) keeps the form's lowest value at
// alpha*(1 + a - ln alpha) = e^(a + 1/2)/2 > 0.8 e^a (the min-range idea: exp stays positive) and
// on wide ranges it is narrower than the secant as well. g is convex: maximum at an endpoint,
// minimum alpha*(1 - ln alpha) at t = ln(alpha).
AffineFit ExpFit(const Interval& range) {
    const double a = range.lo(), b = range.hi();
    const double ea = std::exp(a), eb = std::exp(b);
    Interval fa = LibmAt(ea), fb = LibmAt(eb);
    if (fb.isUnbounded() || !(fb.hi() <= kMaxFinite)) return AffineFit::Of(AffineFit::Kind::Unbounded);  // overflow
    Interval all(std::fmax(0.0, fa.lo()), fb.hi());
    if (a == b) return AffineFit::RangeOf(all);
    const double alpha = std::fmin((eb - ea) / (b - a), std::exp(a + 0.5));
    if (!(alpha > 0)) return AffineFit::RangeOf(all);
    Interval ga = GAt(fa, alpha, a), gb = GAt(fb, alpha, b);
    // alpha > 0: the lower bound of alpha*(1 - ln alpha) takes the upper bound of ln alpha.
    const double gMin = MulDown(alpha, SubDown(1.0, LibmUp(std::log(alpha))));
    return LineOr(MakeFit(alpha, std::min({ga.lo(), gb.lo(), gMin}), std::fmax(ga.hi(), gb.hi()), fb.hi(), kLibmRel),
                  all);
}

// Chebyshev (secant slope): log is concave and increasing, so the form's lowest value is log(a)
// and only the top overshoots. g's maximum is -ln(alpha) - 1 at t = 1/alpha.
AffineFit LogFit(const Interval& range) {
    if (!(range.lo() > 0)) return AffineFit::Of(AffineFit::Kind::Unbounded);  // log(0) = -inf, log(<0) = NaN
    const double a = range.lo(), b = range.hi();
    const double la = std::log(a), lb = std::log(b);
    Interval fa = LibmAt(la), fb = LibmAt(lb);
    Interval all(fa.lo(), fb.hi());
    if (a == b) return AffineFit::RangeOf(all);
    const double alpha = (lb - la) / (b - a);
    if (!(alpha > 0)) return AffineFit::RangeOf(all);
    Interval ga = GAt(fa, alpha, a), gb = GAt(fb, alpha, b);
    const double gMax = SubUp(-LibmDown(std::log(alpha)), 1.0);
    return LineOr(
        MakeFit(alpha, std::fmin(ga.lo(), gb.lo()), std::max({ga.hi(), gb.hi(), gMax}), MaxAbs(all), kLibmRel), all);
}

// --- sin, cos -----------------------------------------------------------------------------------

namespace {

// sin and cos over [a, b] (width below 2*pi, |a|, |b| <= 1e8) with the secant slope alpha.
// g(t) = f(t) - alpha*t is not convex, so every stationary point of g inside [a, b] is visited:
// f'(t) = alpha at t = base + 2*pi*k, with bases +-acos(alpha) for sin and -asin(alpha),
// pi + asin(alpha) for cos. A computed point xi is within E of the true one t* (acos/asin and the
// representation of pi and of k*2*pi, with a wide margin), so any point that may lie inside is
// evaluated at xi clamped to [a, b] (still within E of t*) and widened by E^2 >= E^2/2 max|g''|,
// Taylor's bound around a stationary point. Also returns glibc's f(a) and f(b).
Fit TrigFit(double a, double b, bool isCos, double* faOut, double* fbOut) {
    auto f = [isCos](double t) { return isCos ? std::cos(t) : std::sin(t); };
    const double fa = f(a), fb = f(b);
    *faOut = fa;
    *fbOut = fb;
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
        // k runs over k0 - 2 ... k0 + 3 (integers, exact: |k0| < 2^53 past the analysis limit).
        for (int step = -2; step <= 3; ++step) {
            const double k = k0 + step;
            double xi = base + k * kTwoPi;
            double err = 0x1p-47 * (std::fabs(base) + 8 * std::fabs(k) + std::fabs(xi) + 4);
            // xi grows by 2*pi per k, err by under 1e-12: past b once, past b for every later k.
            if (xi > b + err) break;
            if (xi < a - err) continue;
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
// quarter (wide ranges, where a line follows sin poorly): then the interval range, as for widths
// past 2*pi (zeta = 0, delta = 1). Past |x| = 1e8 also [-1, 1]: the stationary-point enumeration
// would need ever more care for a range that is all noise anyway.
AffineFit SinCosFit(const Interval& range, bool isCos) {
    const double a = range.lo(), b = range.hi();
    if (b - a >= kTwoPiBelow || std::fmax(std::fabs(a), std::fabs(b)) > kTrigAnalysisLimit)
        return AffineFit::Line(0.0, -1.0, 1.0, Interval(-1.0, 1.0));
    if (a == b) return AffineFit::RangeOf(isCos ? cos(range) : sin(range));
    double fa, fb;
    Fit f = TrigFit(a, b, isCos, &fa, &fb);
    const Interval all = SinCosFromEnds(a, b, fa, fb, isCos);  // sin(range) or cos(range)
    if (!f.ok) return AffineFit::RangeOf(all);
    AffineFit fit = AffineFit::Line(f.alpha, f.lo, f.hi, all);
    // Below half a radian the line is never much worse than the interval: skip the comparison.
    if (b - a > 0.5) fit.lineLimit = 1.25 * all.radius();
    return fit;
}

// --- abs, sign ----------------------------------------------------------------------------------

// Decided signs give x or -x exactly (fabs is exact). Across 0 this is min-range, not Chebyshev:
// the Chebyshev line through the kink (alpha = (a + b)/(b - a)) makes the form dip to alpha*a < 0,
// so sqrt(abs(x)) or pow(abs(x), y) would turn Unbounded. min-range for a non-monotone function
// is alpha = 0: m/2 +- m/2, m = max(-a, b), whose range is exactly [0, m].
AffineFit AbsFit(const Interval& range) {
    if (range.lo() >= 0) return AffineFit::Of(AffineFit::Kind::Same);
    if (range.hi() <= 0) return AffineFit::Of(AffineFit::Kind::Negated);
    const double m = std::fmax(-range.lo(), range.hi());
    return AffineFit::Line(0.0, 0.0, m, Interval(0.0, m));
}

// Decided ranges give the exact constants; otherwise the hull of the possible signs, 0.5 +- 0.5,
// -0.5 +- 0.5 or 0 +- 1.
AffineFit SignFit(const Interval& range) {
    if (range.lo() > 0) return AffineFit::RangeOf(Interval(1.0));
    if (range.hi() < 0) return AffineFit::RangeOf(Interval(-1.0));
    return AffineFit::Line(0.0, range.lo() < 0 ? -1.0 : 0.0, range.hi() > 0 ? 1.0 : 0.0);
}

// --- pow ----------------------------------------------------------------------------------------

// x^p for a constant p on x >= 0 (x > 0 if p < 0). Chebyshev with the secant slope: t^p is convex
// for p > 1 or p < 0 and concave for 0 < p < 1, and g(t) = t^p - alpha*t has its one stationary
// point at t = (alpha/p)^(1/(p-1)) with value (1 - p)*(alpha/p)^(p/(p-1)), bounded in interval
// arithmetic. Elsewhere (negative bases) the interval range of std::pow.
AffineFit PowConstantFit(const Interval& range, double p) {
    const double a = range.lo(), b = range.hi();
    if (a < 0 || (a == 0 && p < 0)) return AffineFit::RangeOf(pow(range, Interval(p)));
    const double pa = std::pow(a, p), pb = std::pow(b, p);
    Interval fa = LibmAt(pa), fb = LibmAt(pb);
    Interval all = Hull(fa, fb);
    if (all.isUnbounded()) return AffineFit::Of(AffineFit::Kind::Unbounded);  // overflow, or pow(0, p < 0)
    all = Interval(std::fmax(0.0, all.lo()), all.hi());
    if (a == b) return AffineFit::RangeOf(all);
    const double alpha = (pb - pa) / (b - a);
    // alpha/p > 0 in exact arithmetic (x^p increases for p > 0, decreases for p < 0).
    if (!(alpha / p > 0) || !std::isfinite(alpha)) return AffineFit::RangeOf(all);
    Interval ip(p);
    Interval gStat = (1.0 - ip) * pow(Interval(alpha) / ip, ip / (ip - 1.0));
    Interval ga = GAt(fa, alpha, a), gb = GAt(fb, alpha, b);
    double gLo = std::fmin(ga.lo(), gb.lo()), gHi = std::fmax(ga.hi(), gb.hi());
    if (p > 1 || p < 0)
        gLo = std::fmin(gLo, gStat.lo());  // convex: the stationary point is the minimum
    else
        gHi = std::fmax(gHi, gStat.hi());  // concave: the maximum
    return LineOr(MakeFit(alpha, gLo, gHi, all.hi(), kLibmRel), all);
}

// --- asin, acos, atan ---------------------------------------------------------------------------

namespace {

// asin, acos and atan have one inflection point, 0: asin is concave on [-1, 0] and convex on
// [0, 1], acos and atan the other way round. f' is even, so f'(t) = alpha at t = +-tangent(alpha).
struct InverseTrig {
    double (*f)(double);                // glibc's
    Interval (*df)(const Interval& t);  // an enclosure of the true f' at t
    double (*tangent)(double alpha);    // the t >= 0 with f'(t) = alpha (NaN if there is none)
    bool convexAbove0;                  // f convex on [0, inf), concave on (-inf, 0]
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
Fit SecantInverseTrigFit(const InverseTrig& fn, double a, double b) {
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
// min-range guarantee that the form stays inside [f(a), f(b)] (the enclosure clips the range to
// it). As for sin and cos, a fit wider than the interval range by a quarter (wide atan ranges,
// where a line follows the arctangent poorly) gives the interval range instead.
AffineFit InverseTrigFit(const Interval& range, int which) {
    // asin and acos are NaN outside [-1, 1].
    if (which != 2 && (range.lo() < -1 || range.hi() > 1)) return AffineFit::Of(AffineFit::Kind::Unbounded);
    auto all = [&] { return which == 0 ? asin(range) : which == 1 ? acos(range) : atan(range); };
    const double a = range.lo(), b = range.hi();
    if (a == b) return AffineFit::RangeOf(all());
    Fit f = SecantInverseTrigFit(kInverseTrig[which], a, b);
    if (!f.ok) return AffineFit::RangeOf(all());
    AffineFit fit = AffineFit::Line(f.alpha, f.lo, f.hi, all());
    fit.lineLimit = 1.25 * fit.range.radius();
    return fit;
}

// --- tan ----------------------------------------------------------------------------------------

namespace {

// tan' = 1 + tan^2 (= 1/cos^2), from an enclosure of tan.
Interval TanDerivative(const Interval& t) { return 1.0 + sqr(tan(t)); }
// For TangentBound: tan is convex where it is >= 0 (tan'' = 2 tan tan'), on the right half of
// its branch.
const InverseTrig kTan = {[](double t) { return std::tan(t); }, TanDerivative, nullptr, true};

}  // namespace

// Secant slope (Chebyshev's choice) over [a, b] within one branch ((n - 1/2) pi, (n + 1/2) pi):
// tan is concave left of its zero n*pi and convex right of it, known only to an enclosure Z of
// n*pi. So g(t) = tan(t) - alpha*t is bounded at the endpoints, on the concave side [a, Z.lo]
// from above and on the convex side [Z.hi, b] from below by the tangent line at the point where
// tan' = alpha (tan = -+sqrt(alpha - 1), so t = n*pi -+ atan(sqrt(alpha - 1))), and over the part
// of Z in [a, b] (a sliver of a few ulps of n*pi, where the side is unknown; it holds the sides'
// inner ends) in interval arithmetic. A pole may lie in the range: Unbounded, as Interval's tan.
// As for atan, a fit wider than the interval range by a quarter gives the interval range.
AffineFit TanFit(const Interval& range) {
    const Interval all = tan(range);
    if (all.isUnbounded()) return AffineFit::Of(AffineFit::Kind::Unbounded);
    const double a = range.lo(), b = range.hi();
    if (a == b) return AffineFit::RangeOf(all);
    // The branch: n from the midpoint, kept only if both ends lie clearly inside it.
    const double n = std::round((0.5 * a + 0.5 * b) / kPi);
    const double ta = a / kPi - n, tb = b / kPi - n;
    if (!(ta > -0.5 + 0x1p-30 * (1 + std::fabs(n)) && tb < 0.5 - 0x1p-30 * (1 + std::fabs(n))))
        return AffineFit::RangeOf(all);
    const double fa = std::tan(a), fb = std::tan(b);
    const double alpha = (fb - fa) / (b - a);
    if (!(alpha > 0) || !std::isfinite(alpha)) return AffineFit::RangeOf(all);
    Interval ga = GAt(LibmAt(fa), alpha, a), gb = GAt(LibmAt(fb), alpha, b);
    double gLo = std::fmin(ga.lo(), gb.lo()), gHi = std::fmax(ga.hi(), gb.hi());
    const Interval zero = Interval(n) * Interval(kPi, kPiAbove);
    const double offset = std::atan(std::sqrt(std::fmax(alpha - 1.0, 0.0)));
    if (a < zero.lo())  // concave
        gHi = std::fmax(gHi, TangentBound(kTan, alpha, n * kPi - offset, a, std::fmin(b, zero.lo())).hi());
    if (b > zero.hi())  // convex
        gLo = std::fmin(gLo, TangentBound(kTan, alpha, n * kPi + offset, std::fmax(a, zero.hi()), b).lo());
    const double p = std::fmax(a, zero.lo()), q = std::fmin(b, zero.hi());
    if (p <= q) {
        const Interval t(p, q);
        const Interval g = tan(t) - alpha * t;
        gLo = std::fmin(gLo, g.lo());
        gHi = std::fmax(gHi, g.hi());
    }
    // tan is monotone: |tan| is largest at an endpoint.
    const Fit f = MakeFit(alpha, gLo, gHi, MaxAbs(all), kLibmRel);
    if (!f.ok) return AffineFit::RangeOf(all);
    AffineFit fit = AffineFit::Line(f.alpha, f.lo, f.hi, all);
    fit.lineLimit = 1.25 * all.radius();
    return fit;
}

// --- floor, ceil, round -------------------------------------------------------------------------

// f is monotone, so where f(lo) == f(hi) every value of the range maps to that one double. Past
// 2^52 every double is an integer and f(t) = t: x itself. Otherwise f(t) = t + g with g in
// [gLo, gHi] exactly (floor: [-1, 0], ceil: [0, 1], round: [-1/2, 1/2]); the Line with alpha = 1
// keeps every symbol of x and adds the jump (the scalar f is exact, so there is no libm slack).
AffineFit StepFit(const Interval& range, double (*f)(double), double gLo, double gHi) {
    const double fa = f(range.lo()), fb = f(range.hi());
    if (fa == fb) return AffineFit::RangeOf(Interval(fa));
    if (range.lo() >= 0x1p52 || range.hi() <= -0x1p52) return AffineFit::Of(AffineFit::Kind::Same);
    return AffineFit::Line(1.0, gLo, gHi, Interval(fa, fb));
}

}  // namespace affray::vm
