// vm/texture_lookup.h: the texture opcodes (Texture2, Texture8) on every number type, from the
// double lookups and ranges of texture/texture.h.
//  - double: texture::Sample (SampleQuad): the reference value.
//  - Dual<double>: the same value, bit for bit, with the chain rule through SampleGrad's partial
//    derivatives in s and t (one-sided at a texel boundary, as a kink of min or floor is).
//  - a bound type: the range RangeOver gives for the ranges of s and t, which contains the double
//    lookup at every double point of the region (texture/texture.h derives it), on a fresh
//    symbol (SpreadOf): a texel pattern has no useful linear part over a region, and a fresh
//    symbol keeps the value correlated with itself where a shader reuses it.
//  - Dual<bound>: that value, and derivatives bounded by SlopeOver's bounds on the partial
//    derivatives times the bounds of s's and t's (a term is exactly 0 where s or t does not move
//    in that direction, so a constant coordinate costs nothing).
// The four-corner form (Texture8) averages lookups over the quadrilateral its corners span: its
// value and bound are SampleQuad's and RangeOverQuad's, its derivatives SampleQuadGrad's at a
// point and bounded likewise over a region (below).
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

#include "texture/texture.h"
#include "vm/numbers/number.h"
#include "vm/program.h"

namespace affray::vm {

namespace texture_detail {

inline texture::Range RangeFrom(const Interval& r) { return {r.lo(), r.hi()}; }

/// The largest |x| of a bounded range.
inline double Magnitude(const Interval& r) { return std::max(std::fabs(r.lo()), std::fabs(r.hi())); }

/// `range` narrowed by the lookup's Lipschitz bound about the region's centre (s and t within
/// sMagnitude and tMagnitude of 0): with |df/ds| <=
/// sSlope and |df/dt| <= tSlope over the (convex) region, f lies within sSlope * sRadius + tSlope *
/// tRadius of its value `centre` at the centre. The texels' range alone does not shrink below a
/// texel, so a region smaller than a texel needs this to converge on the surface. The products are
/// widened by 2^-40 for their rounding, and by 2^-40 of the texels' magnitude for the lookups'
/// (as RangeOver is, texture/texture.h).
inline texture::Range Narrowed(texture::Range range, double centre, double sSlope, double sRadius, double tSlope,
                               double tRadius, double sMagnitude, double tMagnitude) {
    // The double lookup at s computes its texel coordinate s * size - 0.5 (and a four-corner tap
    // its place) with rounding: as if at a coordinate a few ulps of |s| + 1 away.
    sRadius += 0x1p-48 * (sMagnitude + 1);
    tRadius += 0x1p-48 * (tMagnitude + 1);
    const double reach = (sSlope * sRadius + tSlope * tRadius) * (1 + 0x1p-40) +
                         0x1p-40 * std::max(std::fabs(range.lo), std::fabs(range.hi)) + 0x1p-1000;
    if (!(reach < std::numeric_limits<double>::infinity()) || !std::isfinite(centre)) return range;
    return {std::max(range.lo, centre - reach), std::min(range.hi, centre + reach)};
}

/// d * slope-bound term of the chain rule for a bound B: 0 where d is exactly 0.
template <class B>
B SlopeTerm(double slope, const B& d) {
    if (IsExactlyZero(d)) return B(0.0);
    return SpreadOf<B>(Interval::Extended(-slope, slope)) * d;
}

}  // namespace texture_detail

inline double TextureLookup(const TextureSlot& slot, double s, double t) {
    return texture::Sample(slot.map.get(), slot.options, 0, s, t);
}

inline Dual<double> TextureLookup(const TextureSlot& slot, const Dual<double>& s, const Dual<double>& t) {
    double ds = 0, dt = 0;
    const double v = texture::SampleGrad(slot.map.get(), slot.options, 0, s.v, t.v, &ds, &dt);
    // A coordinate that does not move contributes nothing, even where the slope is infinite.
    auto term = [](double slope, double d) { return d == 0 ? 0.0 : slope * d; };
    return {v, term(ds, s.du) + term(dt, t.du), term(ds, s.dv) + term(dt, t.dv)};
}

template <class B>
B TextureLookup(const TextureSlot& slot, const B& s, const B& t) {
    const Interval rs = RangeOf(s), rt = RangeOf(t);
    const texture::Range srange = texture_detail::RangeFrom(rs), trange = texture_detail::RangeFrom(rt);
    texture::Range r = texture::RangeOver(slot.map.get(), slot.options, 0, srange, trange);
    if (!rs.isUnbounded() && !rt.isUnbounded()) {
        double sSlope = 0, tSlope = 0;
        texture::SlopeOver(slot.map.get(), slot.options, 0, srange, trange, &sSlope, &tSlope);
        const double centre = texture::Sample(slot.map.get(), slot.options, 0, rs.mid(), rt.mid());
        r = texture_detail::Narrowed(r, centre, sSlope, rs.radius(), tSlope, rt.radius(), texture_detail::Magnitude(rs),
                                     texture_detail::Magnitude(rt));
    }
    return SpreadOf<B>(Interval(r.lo, r.hi));
}

template <class B>
Dual<B> TextureLookup(const TextureSlot& slot, const Dual<B>& s, const Dual<B>& t) {
    const B value = TextureLookup(slot, s.v, t.v);
    double sSlope = 0, tSlope = 0;
    texture::SlopeOver(slot.map.get(), slot.options, 0, texture_detail::RangeFrom(RangeOf(s.v)),
                       texture_detail::RangeFrom(RangeOf(t.v)), &sSlope, &tSlope);
    using texture_detail::SlopeTerm;
    return {value, SlopeTerm(sSlope, s.du) + SlopeTerm(tSlope, t.du),
            SlopeTerm(sSlope, s.dv) + SlopeTerm(tSlope, t.dv)};
}

/// The four-corner lookup; c holds s1, t1, s2, t2, s3, t3, s4, t4 (the operand order).
inline double TextureLookupQuad(const TextureSlot& slot, const double* c) {
    const double s[4] = {c[0], c[2], c[4], c[6]}, t[4] = {c[1], c[3], c[5], c[7]};
    return texture::SampleQuad(slot.map.get(), slot.options, 0, s, t);
}

/// Over a region the taps stay within the box of the corners' ranges, and each tap, a convex
/// combination of the corners, moves from its place at the corners' centres by at most the
/// largest corner radius per coordinate: the Lipschitz narrowing of TextureLookup applies with
/// those radii.
template <class B>
B TextureLookupQuad(const TextureSlot& slot, const B* c) {
    texture::Range s[4], t[4];
    double sc[4], tc[4], sRadius = 0, tRadius = 0;
    Interval sBox, tBox;
    bool bounded = true;
    for (size_t i = 0; i < 4; ++i) {
        const Interval rs = RangeOf(c[2 * i]), rt = RangeOf(c[2 * i + 1]);
        s[i] = texture_detail::RangeFrom(rs);
        t[i] = texture_detail::RangeFrom(rt);
        bounded = bounded && !rs.isUnbounded() && !rt.isUnbounded();
        sc[i] = rs.mid();
        tc[i] = rt.mid();
        sRadius = std::max(sRadius, rs.radius());
        tRadius = std::max(tRadius, rt.radius());
        sBox = i == 0 ? rs : Join(sBox, rs);
        tBox = i == 0 ? rt : Join(tBox, rt);
    }
    texture::Range r = texture::RangeOverQuad(slot.map.get(), slot.options, 0, s, t);
    if (bounded) {
        double sSlope = 0, tSlope = 0;
        texture::SlopeOver(slot.map.get(), slot.options, 0, texture_detail::RangeFrom(sBox),
                           texture_detail::RangeFrom(tBox), &sSlope, &tSlope);
        const double centre = texture::SampleQuad(slot.map.get(), slot.options, 0, sc, tc);
        r = texture_detail::Narrowed(r, centre, sSlope, sRadius, tSlope, tRadius, texture_detail::Magnitude(sBox),
                                     texture_detail::Magnitude(tBox));
    }
    return SpreadOf<B>(Interval(r.lo, r.hi));
}

/// Duals of the four-corner form: the chain rule through each corner's partial derivatives.
inline Dual<double> TextureLookupQuad(const TextureSlot& slot, const Dual<double>* c) {
    const double s[4] = {c[0].v, c[2].v, c[4].v, c[6].v}, t[4] = {c[1].v, c[3].v, c[5].v, c[7].v};
    double dS[4], dT[4];
    const double v = texture::SampleQuadGrad(slot.map.get(), slot.options, 0, s, t, dS, dT);
    auto term = [](double slope, double d) { return d == 0 ? 0.0 : slope * d; };
    double du = 0, dv = 0;
    for (size_t i = 0; i < 4; ++i) {
        du += term(dS[i], c[2 * i].du) + term(dT[i], c[2 * i + 1].du);
        dv += term(dS[i], c[2 * i].dv) + term(dT[i], c[2 * i + 1].dv);
    }
    return {v, du, dv};
}

/// Over a region: the value's derivative is the mean over the taps of the lookup's gradient at
/// the tap times the tap's movement, a convex combination (the bilinear weights) of the corners'
/// movements; so it lies in the slope bounds over the corners' box times the Join of the
/// corners' derivatives, per coordinate.
template <class B>
Dual<B> TextureLookupQuad(const TextureSlot& slot, const Dual<B>* c) {
    B values[8];
    for (int i = 0; i < 8; ++i) values[i] = c[i].v;
    texture::Range box[2];
    for (int k = 0; k < 2; ++k) {
        Interval r = RangeOf(c[k].v);
        for (int i = 1; i < 4; ++i) r = Join(r, RangeOf(c[2 * i + k].v));
        box[k] = texture_detail::RangeFrom(r);
    }
    double sSlope = 0, tSlope = 0;
    texture::SlopeOver(slot.map.get(), slot.options, 0, box[0], box[1], &sSlope, &tSlope);
    auto movement = [&](int k, bool u) {
        B m = u ? c[k].du : c[k].dv;
        for (int i = 1; i < 4; ++i) m = Join(m, u ? c[2 * i + k].du : c[2 * i + k].dv);
        return m;
    };
    using texture_detail::SlopeTerm;
    return {TextureLookupQuad(slot, values),
            SlopeTerm(sSlope, movement(0, true)) + SlopeTerm(tSlope, movement(1, true)),
            SlopeTerm(sSlope, movement(0, false)) + SlopeTerm(tSlope, movement(1, false))};
}

}  // namespace affray::vm
