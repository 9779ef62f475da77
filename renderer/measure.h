// renderer/measure.h: a region's bound (RegionBound) measured along directions, in doubles with
// every rounding bounded. The intersector measures bounds along the ray's frame (n1, n2, dir) to
// discard regions and to find where the ray can reach them; certified Newton measures slope
// bounds and a point's box along the same frame. Both use these, so that one rounding argument
// covers them: the sums and products here are a few terms long, and kSlack, an eight-fold margin
// over the gamma_n bounds of their error (n <= 6 operations in a chain), is added on the
// magnitudes of every term.
#pragma once

#include <cmath>
#include <glm/glm.hpp>

#include "renderer/bound_tree.h"

namespace affray::renderer {

/// The unit roundoff of round-to-nearest doubles.
inline constexpr double kUlp = 0x1p-53;
/// The relative rounding slack of the few-term sums and products of a measure (see above).
inline constexpr double kSlack = 4e-15;

/// A bound measured along a unit direction n: c + u eps_u + v eps_v + w eps_w, plus or minus rad.
/// It contains n . (P' - o) for every displaced point of the region, rounding included.
struct Measure {
    double c = 0, u = 0, v = 0, w = 0, rad = 0;
    bool bounded = true;  ///< false if a coordinate n weighs is unbounded, or the sums overflow
};

/// The measures of bound `b` relative to the point `o` along the directions n[0..kCount), in one
/// pass over the coordinates.
template <int kCount>
void MeasureAlong(const RegionBound& b, const glm::dvec3& o, const glm::dvec3 (&n)[kCount], Measure (&m)[kCount]) {
    double magnitude[kCount] = {};
    for (int i = 0; i < 3; ++i) {
        const bool bounded = b.boundedMask & (1u << i);
        const double rel = b.c[i] - o[i];
        const double size =
            std::fabs(b.c[i]) + std::fabs(o[i]) + std::fabs(b.a[i]) + std::fabs(b.b[i]) + std::fabs(b.g[i]) + b.r[i];
        for (int k = 0; k < kCount; ++k) {
            const double nk = n[k][i];
            // A coordinate n does not weigh cannot make the measure unbounded.
            if (nk == 0) continue;
            if (!bounded) {
                m[k].bounded = false;
                continue;
            }
            m[k].c += nk * rel;
            m[k].u += nk * b.a[i];
            m[k].v += nk * b.b[i];
            m[k].w += nk * b.g[i];
            const double an = std::fabs(nk);
            m[k].rad += an * b.r[i];
            magnitude[k] += an * size;
        }
    }
    for (int k = 0; k < kCount; ++k) {
        m[k].rad += kSlack * magnitude[k] + 1e-300;
        if (!std::isfinite(m[k].rad) || !std::isfinite(m[k].c)) m[k].bounded = false;
    }
}

/// A closed range [lo, hi].
struct Range {
    double lo, hi;
    bool excludesZero() const { return lo > 0 || hi < 0; }
    double width() const { return hi - lo; }
};

/// The range of a measure with eps_u in cu +- ru and eps_v in cv +- rv (eps_w free).
inline Range Over(const Measure& m, double cu, double ru, double cv, double rv) {
    const double mid = m.c + m.u * cu + m.v * cv;
    double rad = std::fabs(m.u) * ru + std::fabs(m.v) * rv + std::fabs(m.w) + m.rad;
    rad += kSlack * (std::fabs(m.c) + std::fabs(m.u * cu) + std::fabs(m.v * cv) + rad);
    return {mid - rad, mid + rad};
}

/// Over a box [eu0, eu1] x [ev0, ev1] of eps (its centre and radius rounded outwards).
inline Range OverBox(const Measure& m, double eu0, double eu1, double ev0, double ev1) {
    const double cu = 0.5 * (eu0 + eu1), ru = 0.5 * (eu1 - eu0) * (1 + 4 * kUlp);
    const double cv = 0.5 * (ev0 + ev1), rv = 0.5 * (ev1 - ev0) * (1 + 4 * kUlp);
    return Over(m, cu, ru, cv, rv);
}

}  // namespace affray::renderer
