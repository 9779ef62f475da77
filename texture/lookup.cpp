// texture/lookup.cpp: the lookups of texture.h (bilinear and Catmull-Rom taps, blur grids, the
// four-corner form) with their analytic derivatives, and the bounds over regions (RangeOver,
// RangeOverQuad, SlopeOver) derived from the same double expressions, plus the names of wrap
// modes and filters.
#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <limits>

#include "texture/texture_impl.h"

namespace affray::texture {

using namespace detail;

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
/// Rounding slack of a bound, relative to its magnitude, and an absolute one for ranges at zero.
constexpr double kSlack = 0x1p-40;
constexpr double kTiny = 1e-300;
/// Catmull-Rom's negative weights sum to at most 9/32 (texture.h), and the positive weights of
/// its derivative, times the absolute sum of the other axis's weights, to less than 2.
constexpr double kCatromLobes = 9.0 / 32.0;
constexpr double kCatromSlope = 2.0;

/// A blur's taps along one axis, as fractions of the blur width, and their normalised weights.
struct BlurTable {
    std::array<double, kBlurTaps> fraction{}, weight{};
};

const BlurTable& Blur(Filter filter) {
    static const std::array<BlurTable, 3> tables = [] {
        std::array<BlurTable, 3> t;
        for (int f = 0; f < 3; ++f) {
            double sum = 0;
            for (int i = 0; i < kBlurTaps; ++i) {
                const double x = (i + 0.5) / kBlurTaps - 0.5;  // centred cells across [-1/2, 1/2]
                const double w = f == 0 ? 1.0 : f == 1 ? 1.0 - std::fabs(x) / 0.5 : std::exp(-8.0 * x * x);
                t[f].fraction[i] = x;
                t[f].weight[i] = w;
                sum += w;
            }
            for (double& w : t[f].weight) w /= sum;
        }
        return t;
    }();
    // Catmull-Rom taps are averaged with box weights.
    return tables[filter == Filter::CatmullRom ? 0 : static_cast<int>(filter)];
}

/// What one lookup call fixes: the map, the channel, the wrap, and the blur taps.
struct Lookup {
    const MapImpl* map = nullptr;
    int c = 0, width = 0, height = 0;
    Wrap swrap = Wrap::Periodic, twrap = Wrap::Periodic;
    bool catrom = false;
    double fill = 0;
    int nS = 1, nT = 1;
    std::array<double, kBlurTaps> offS{}, offT{}, wS{}, wT{};
};

/// False (only the fill value) without a map or the channel.
bool Prepare(const TextureMap* map, const LookupOptions& o, int offset, Lookup* k) {
    k->fill = o.fill;
    if (!map) return false;
    const int64_t c = static_cast<int64_t>(o.channel) + offset;
    if (c < 0 || c >= map->channels()) return false;
    k->map = &MapImpl::Of(*map);
    k->c = static_cast<int>(c);
    k->width = map->width();
    k->height = map->height();
    k->swrap = o.swrap;
    k->twrap = o.twrap;
    k->catrom = o.filter == Filter::CatmullRom;
    const BlurTable& table = Blur(o.filter);
    auto axis = [&](double blur, int* n, std::array<double, kBlurTaps>& off, std::array<double, kBlurTaps>& w) {
        if (blur == 0) {
            *n = 1;
            off[0] = 0;
            w[0] = 1;
            return;
        }
        *n = kBlurTaps;
        for (int i = 0; i < kBlurTaps; ++i) {
            off[i] = blur * table.fraction[i];
            w[i] = table.weight[i];
        }
    };
    axis(o.sblur, &k->nS, k->offS, k->wS);
    axis(o.tblur, &k->nT, k->offT, k->wT);
    return true;
}

/// Whether a texel-space coordinate is near enough to the image to be looked up (false for NaN).
inline bool InReach(double x, int size) { return x >= -kMaxTexelCoordinate && x <= size + kMaxTexelCoordinate; }

/// An index through a wrap mode; -1 for a black texel outside.
inline int64_t WrapIndex(int64_t i, int size, Wrap wrap) {
    if (i >= 0 && i < size) return i;
    switch (wrap) {
        case Wrap::Black: return -1;
        case Wrap::Clamp: return i < 0 ? 0 : size - 1;
        case Wrap::Periodic: break;
    }
    const int64_t m = i % size;
    return m < 0 ? m + size : m;
}

inline double Fetch(const Lookup& k, int64_t x, int64_t y) {
    const int64_t xi = WrapIndex(x, k.width, k.swrap), yi = WrapIndex(y, k.height, k.twrap);
    if (xi < 0 || yi < 0) return 0;
    return k.map->texel(static_cast<int>(xi), static_cast<int>(yi), k.c);
}

/// Catmull-Rom weights of the four texels around a fraction f in [0, 1), and their derivatives.
inline void CatromWeights(double f, double w[4]) {
    const double f2 = f * f, f3 = f2 * f;
    w[0] = 0.5 * (-f3 + 2 * f2 - f);
    w[1] = 0.5 * (3 * f3 - 5 * f2 + 2);
    w[2] = 0.5 * (-3 * f3 + 4 * f2 + f);
    w[3] = 0.5 * (f3 - f2);
}
inline void CatromDerivatives(double f, double d[4]) {
    const double f2 = f * f;
    d[0] = 0.5 * (-3 * f2 + 4 * f - 1);
    d[1] = 0.5 * (9 * f2 - 10 * f);
    d[2] = 0.5 * (-9 * f2 + 8 * f + 1);
    d[3] = 0.5 * (3 * f2 - 2 * f);
}

/// One bilinear or Catmull-Rom tap at (s, t); with Grad, its derivatives in s and t.
template <bool Grad>
double Tap(const Lookup& k, double s, double t, double* ds, double* dt) {
    const double x = s * k.width, y = t * k.height;
    if (!InReach(x, k.width) || !InReach(y, k.height)) {
        if constexpr (Grad) *ds = *dt = 0;
        return k.fill;
    }
    const double fx = x - 0.5, fy = y - 0.5;
    const double fx0 = std::floor(fx), fy0 = std::floor(fy);
    const double a = fx - fx0, b = fy - fy0;
    const int64_t x0 = static_cast<int64_t>(fx0), y0 = static_cast<int64_t>(fy0);
    if (!k.catrom) {
        const double t00 = Fetch(k, x0, y0), t10 = Fetch(k, x0 + 1, y0);
        const double t01 = Fetch(k, x0, y0 + 1), t11 = Fetch(k, x0 + 1, y0 + 1);
        if constexpr (Grad) {
            *ds = ((1 - b) * (t10 - t00) + b * (t11 - t01)) * k.width;
            *dt = ((1 - a) * (t01 - t00) + a * (t11 - t10)) * k.height;
        }
        return (1 - b) * ((1 - a) * t00 + a * t10) + b * ((1 - a) * t01 + a * t11);
    }
    double wx[4], wy[4];
    CatromWeights(a, wx);
    CatromWeights(b, wy);
    double dwx[4] = {0, 0, 0, 0}, dwy[4] = {0, 0, 0, 0};
    if constexpr (Grad) {
        CatromDerivatives(a, dwx);
        CatromDerivatives(b, dwy);
    }
    double v = 0, gs = 0, gt = 0;
    for (int j = 0; j < 4; ++j) {
        double row = 0, rowS = 0;
        for (int i = 0; i < 4; ++i) {
            const double texel = Fetch(k, x0 - 1 + i, y0 - 1 + j);
            row += wx[i] * texel;
            if constexpr (Grad) rowS += dwx[i] * texel;
        }
        v += wy[j] * row;
        if constexpr (Grad) {
            gs += wy[j] * rowS;
            gt += dwy[j] * row;
        }
    }
    if constexpr (Grad) {
        *ds = gs * k.width;
        *dt = gt * k.height;
    }
    return v;
}

/// The (blurred) lookup at (s, t), the fill value where (s, t) is not finite or out of reach.
template <bool Grad>
double Evaluate(const Lookup& k, double s, double t, double* ds, double* dt) {
    if (!InReach(s * k.width, k.width) || !InReach(t * k.height, k.height)) {
        if constexpr (Grad) *ds = *dt = 0;
        return k.fill;
    }
    if (k.nS == 1 && k.nT == 1) return Tap<Grad>(k, s, t, ds, dt);
    double v = 0, gs = 0, gt = 0;
    for (int j = 0; j < k.nT; ++j) {
        const double tj = t + k.offT[j];
        double row = 0, rowS = 0, rowT = 0;
        for (int i = 0; i < k.nS; ++i) {
            double a = 0, b = 0;
            const double tap = Tap<Grad>(k, s + k.offS[i], tj, &a, &b);
            row += k.wS[i] * tap;
            if constexpr (Grad) {
                rowS += k.wS[i] * a;
                rowT += k.wS[i] * b;
            }
        }
        v += k.wT[j] * row;
        if constexpr (Grad) {
            gs += k.wT[j] * rowS;
            gt += k.wT[j] * rowT;
        }
    }
    if constexpr (Grad) {
        *ds = gs;
        *dt = gt;
    }
    return v;
}

/// Where the taps of lookups over a coordinate range fall along one axis: the texel indices they
/// may read, whether some tap may be out of reach (the fill value), and whether any is within.
struct Span {
    bool fill = false, any = true;
    int64_t lo = 0, hi = 0;
};

/// Every expression is the one Evaluate and Tap compute, applied to the range's ends: rounding is
/// monotone, so the taps of every coordinate in the range land between.
Span AxisSpan(double lo, double hi, const std::array<double, kBlurTaps>& off, int n, int size, bool catrom) {
    double xlo = kInf, xhi = -kInf;
    for (int i = 0; i < n; ++i) {
        xlo = std::min(xlo, (lo + off[i]) * size);
        xhi = std::max(xhi, (hi + off[i]) * size);
    }
    Span span;
    const double reachLo = -kMaxTexelCoordinate, reachHi = size + kMaxTexelCoordinate;
    span.fill = xlo < reachLo || xhi > reachHi;
    xlo = std::max(xlo, reachLo);
    xhi = std::min(xhi, reachHi);
    if (xlo > xhi) {
        span.any = false;
        return span;
    }
    // Texels with non-zero weight: floor(fx) .. floor(fx) + 1 (Catmull-Rom one more each side),
    // where an integer fx reads only floor(fx).
    span.lo = static_cast<int64_t>(std::floor(xlo - 0.5)) - (catrom ? 1 : 0);
    span.hi = static_cast<int64_t>(std::ceil(xhi - 0.5)) + (catrom ? 1 : 0);
    return span;
}

inline Range Join(Range r, double v) { return {std::min(r.lo, v), std::max(r.hi, v)}; }

inline Range Widen(Range r) {
    const double d = std::max(std::fabs(r.lo), std::fabs(r.hi)) * kSlack + kTiny;
    return {r.lo - d, r.hi + d};
}

inline Range CatromWiden(Range r) {
    const double d = (r.hi - r.lo) * kCatromLobes;
    return {r.lo - d, r.hi + d};
}

/// Every value a lookup of the map can take, and the fill value.
Range Everything(const Lookup& k) {
    Range r = k.map->RangeOfTexels(-1, k.width, -1, k.height, k.c, k.swrap, k.twrap);
    if (k.catrom) r = CatromWiden(r);
    return Widen(Join(r, k.fill));
}

bool Finite(Range r) { return std::isfinite(r.lo) && std::isfinite(r.hi); }
bool NotNaN(Range r) { return !std::isnan(r.lo) && !std::isnan(r.hi); }

}  // namespace

bool ParseWrap(const std::string& name, Wrap* wrap) {
    std::string n = name;
    for (char& ch : n) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
    if (n == "black")
        *wrap = Wrap::Black;
    else if (n == "clamp")
        *wrap = Wrap::Clamp;
    else if (n == "periodic" || n == "repeat")
        *wrap = Wrap::Periodic;
    else
        return false;
    return true;
}

bool ParseFilter(const std::string& name, Filter* filter) {
    std::string n = name;
    for (char& ch : n) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
    if (n == "box")
        *filter = Filter::Box;
    else if (n == "triangle")
        *filter = Filter::Triangle;
    else if (n == "gaussian")
        *filter = Filter::Gaussian;
    else if (n == "catmull-rom" || n == "catrom" || n == "bicubic")
        *filter = Filter::CatmullRom;
    else
        return false;
    return true;
}

const char* WrapName(Wrap w) {
    switch (w) {
        case Wrap::Black: return "black";
        case Wrap::Clamp: return "clamp";
        case Wrap::Periodic: return "periodic";
    }
    return "periodic";
}

const char* FilterName(Filter f) {
    switch (f) {
        case Filter::Box: return "box";
        case Filter::Triangle: return "triangle";
        case Filter::Gaussian: return "gaussian";
        case Filter::CatmullRom: return "catmull-rom";
    }
    return "box";
}

double Sample(const TextureMap* map, const LookupOptions& options, int offset, double s, double t) {
    Lookup k;
    if (!Prepare(map, options, offset, &k)) return options.fill;
    return Evaluate<false>(k, s, t, nullptr, nullptr);
}

double SampleGrad(const TextureMap* map, const LookupOptions& options, int offset, double s, double t, double* dds,
                  double* ddt) {
    double ds = 0, dt = 0, v = options.fill;
    Lookup k;
    if (Prepare(map, options, offset, &k)) v = Evaluate<true>(k, s, t, &ds, &dt);
    if (dds) *dds = ds;
    if (ddt) *ddt = dt;
    return v;
}

double SampleQuad(const TextureMap* map, const LookupOptions& options, int offset, const double s[4],
                  const double t[4]) {
    Lookup k;
    if (!Prepare(map, options, offset, &k)) return options.fill;
    double sum = 0;
    detail::ForEachQuadTap(
        s, t, [&](double ps, double pt, const double*) { sum += Evaluate<false>(k, ps, pt, nullptr, nullptr); });
    return sum / (kQuadTaps * kQuadTaps);
}

Range RangeOver(const TextureMap* map, const LookupOptions& options, int offset, Range s, Range t) {
    Lookup k;
    if (!Prepare(map, options, offset, &k)) return {options.fill, options.fill};
    if (!NotNaN(s) || !NotNaN(t) || !std::isfinite(options.sblur) || !std::isfinite(options.tblur))
        return Everything(k);
    const Span x = AxisSpan(s.lo, s.hi, k.offS, k.nS, k.width, k.catrom);
    const Span y = AxisSpan(t.lo, t.hi, k.offT, k.nT, k.height, k.catrom);
    if (!x.any || !y.any) return Widen({k.fill, k.fill});
    Range r = k.map->RangeOfTexels(x.lo, x.hi, y.lo, y.hi, k.c, k.swrap, k.twrap);
    if (k.catrom) r = CatromWiden(r);
    if (x.fill || y.fill) r = Join(r, k.fill);
    return Widen(r);
}

Range RangeOverQuad(const TextureMap* map, const LookupOptions& options, int offset, const Range s[4],
                    const Range t[4]) {
    // The grid points are convex combinations of the corners: they lie in the box of the corner
    // ranges, up to the rounding of the combination (a few units in the last place).
    auto box = [](const Range r[4]) {
        Range b = r[0];
        for (int i = 0; i < 4; ++i) {
            if (!NotNaN(r[i])) return Range{std::nan(""), std::nan("")};
            b.lo = std::min(b.lo, r[i].lo);
            b.hi = std::max(b.hi, r[i].hi);
        }
        const double d = std::max(std::fabs(b.lo), std::fabs(b.hi)) * 0x1p-48 + kTiny;
        return Range{b.lo - d, b.hi + d};
    };
    return RangeOver(map, options, offset, box(s), box(t));
}

void SlopeOver(const TextureMap* map, const LookupOptions& options, int offset, Range s, Range t, double* sSlope,
               double* tSlope) {
    *sSlope = *tSlope = 0;
    Lookup k;
    if (!Prepare(map, options, offset, &k)) return;  // the fill value everywhere
    if (!Finite(s) || !Finite(t) || !std::isfinite(options.sblur) || !std::isfinite(options.tblur)) {
        *sSlope = *tSlope = kInf;
        return;
    }
    const Span x = AxisSpan(s.lo, s.hi, k.offS, k.nS, k.width, k.catrom);
    const Span y = AxisSpan(t.lo, t.hi, k.offT, k.nT, k.height, k.catrom);
    if (!x.any || !y.any) return;  // every tap is the fill value
    if (x.fill || y.fill) {
        // A tap crossing the edge of reach jumps to the fill value.
        *sSlope = *tSlope = kInf;
        return;
    }
    // Derivatives at a kink read the texel past the value's: one more each side.
    const Range r = k.map->RangeOfTexels(x.lo - 1, x.hi + 1, y.lo - 1, y.hi + 1, k.c, k.swrap, k.twrap);
    const double factor = k.catrom ? kCatromSlope : 1.0;
    // The rounding of the weights (Catmull-Rom's derivative weights sum to 0 only up to it) costs
    // a little of the texels' magnitude.
    const double spread = (r.hi - r.lo) * (1 + kSlack) + std::max(std::fabs(r.lo), std::fabs(r.hi)) * kSlack + kTiny;
    *sSlope = spread * factor * k.width;
    *tSlope = spread * factor * k.height;
}

}  // namespace affray::texture
