// vm/numbers/quad_form.h: QuadForm, a second-order Taylor model on a region's two symbols, for
// bounds that must keep their curvature until the end (vm/numbers/noise.h bounds one noise cell
// with it over a reduced affine region).
//
//     x(u, v) = c0 + cu u + cv v + cuu u^2 + cuv u v + cvv v^2 +- r,     u, v in [-1, 1], r >= 0,
//
// u and v standing for eps_u and eps_v of vm::ReducedAffine. Reduced affine arithmetic keeps the
// linear part of a value and folds everything else into one error; a product of two such values
// then loses the quadratic terms of both, and a chain of products (the lerps of a noise cell)
// compounds the loss. A QuadForm keeps the quadratic part exactly through sums and products;
// only the cubic and quartic terms of a product are reduced, each monomial to its best
// approximation of lower degree on [-1, 1] plus a remainder (u^3 = 0.75 u +- 0.25, u^2 v =
// 0.5 v +- 0.5, u^4 = u^2 - 0.125 +- 0.125, ...), so that their linear and quadratic parts keep
// their correlation. At the end (ToReduced) the quadratic part's exact range over the square
// becomes the reduced affine centre and error.
//
// Contract (that of vm::Affine and vm::ReducedAffine, vm/numbers/rounding.h's error formulas):
// for every (u, v) in the square, the double result of the same operation on any operand values
// that the operand forms allow at (u, v) lies in the result form at (u, v), the rounding of the
// coefficients and of the double operation both included. Tested in
// tests/vm/numbers/noise_test.cpp (the noise bounds, and the operations against random operands).
#pragma once

#include <cmath>

#include "vm/numbers/rounding.h"

namespace affray::vm {

struct QuadForm {
    enum { k0, kU, kV, kUU, kUV, kVV, kCount };
    /// Symbols of the caller's own, each a function of the point with values in [-1, 1] (noise:
    /// per coordinate, the part of its fade beyond second order and the coordinate's own error),
    /// carried linearly so that their contributions cancel where the caller's operations make
    /// them cancel.
    static constexpr int kOwn = 8;
    // No initialisers: an array of forms is left uninitialised (a noise call holds dozens),
    // and QuadForm{} is zero.
    double c[kCount];
    double o[kOwn];
    double r;

    QuadForm() = default;
    /// The exact constant c0 (as the cell polynomial's template makes its zero).
    explicit QuadForm(double c0) : c{c0}, o{}, r(0) {}

    /// c0 + cu u + cv v +- r exactly.
    static QuadForm Linear(double c0, double cu, double cv, double r) {
        QuadForm x{};
        x.c[k0] = c0;
        x.c[kU] = cu;
        x.c[kV] = cv;
        x.r = r;
        return x;
    }
    // The sums below are summed pairwise, in an order the compiler keeps in vector registers: a
    // running sum is a chain of dependent additions, and these sums are called about 60 times
    // per noise cell (a tenth of the instructions tracing bench/real's subdivision scene runs;
    // pairwise, 1.3 % fewer in all). Any order's rounding is within the slack callers add.
    /// sum |o_k| (rounded to nearest; callers add slack).
    double ownSum() const {
        static_assert(kOwn == 8);
        double half[4];
        for (int k = 0; k < 4; ++k) half[k] = std::fabs(o[k]) + std::fabs(o[k + 4]);
        return (half[0] + half[2]) + (half[1] + half[3]);
    }
    /// sum |c_k| (rounded to nearest; callers add slack).
    double polynomialSum() const {
        static_assert(kCount == 6);
        double half[3];
        for (int k = 0; k < 3; ++k) half[k] = std::fabs(c[k]) + std::fabs(c[k + 3]);
        return (half[0] + half[2]) + half[1];
    }
    /// sum |c_k| + sum |o_k| (rounded to nearest; callers add slack).
    double coefficientSum() const { return polynomialSum() + ownSum(); }
    /// The range of the quadratic part cuu u^2 + cuv u v + cvv v^2 over the square, exactly
    /// (as rounded: callers add slack): its extremes are at the centre (0), the vertices, or the
    /// critical points of the edges.
    void quadraticRange(double* lo, double* hi) const {
        const double a = c[kUU], b = c[kUV], d = c[kVV];
        double l = 0, h = 0;
        const auto take = [&](double x) {  // (a NaN coefficient shows in the error: see callers)
            l = x < l ? x : l;
            h = x > h ? x : h;
        };
        take(a + d + b);
        take(a + d - b);
        // On u = +-1: a +- b v + d v^2, critical at v = -+b/(2d) when that is inside [-1, 1].
        if (d != 0 && std::fabs(b) <= 2 * std::fabs(d)) take(a - b * b / (4 * d));
        if (a != 0 && std::fabs(b) <= 2 * std::fabs(a)) take(d - b * b / (4 * a));
        *lo = l;
        *hi = h;
    }
};

/// -x (exact).
inline QuadForm operator-(const QuadForm& x) {
    QuadForm z{};
    for (int k = 0; k < QuadForm::kCount; ++k) z.c[k] = -x.c[k];
    for (int k = 0; k < QuadForm::kOwn; ++k) z.o[k] = -x.o[k];
    z.r = x.r;
    return z;
}

/// x + y (x - y with kSubtract): coefficient by coefficient, LinearError's rounding.
/// The coefficients of x + y (x - y with kSubtract), as rounded; the remainder left 0 for the
/// caller.
template <bool kSubtract>
QuadForm AddCoefficients(const QuadForm& x, const QuadForm& y) {
    QuadForm z{};
    for (int k = 0; k < QuadForm::kCount; ++k) z.c[k] = kSubtract ? x.c[k] - y.c[k] : x.c[k] + y.c[k];
    for (int k = 0; k < QuadForm::kOwn; ++k) z.o[k] = kSubtract ? x.o[k] - y.o[k] : x.o[k] + y.o[k];
    return z;
}

template <bool kSubtract>
QuadForm Add(const QuadForm& x, const QuadForm& y) {
    QuadForm z = AddCoefficients<kSubtract>(x, y);
    z.r = LinearError(x.r + y.r, z.coefficientSum());
    return z;
}
inline QuadForm operator+(const QuadForm& x, const QuadForm& y) { return Add<false>(x, y); }
inline QuadForm operator-(const QuadForm& x, const QuadForm& y) { return Add<true>(x, y); }

/// x + k for a double k.
inline QuadForm operator+(const QuadForm& x, double k) {
    QuadForm z = x;
    z.c[QuadForm::k0] = x.c[QuadForm::k0] + k;
    z.r = LinearError(x.r, z.coefficientSum());
    return z;
}

inline QuadForm operator-(const QuadForm& x, double k) { return x + (-k); }

/// k * x for a double k (vm/numbers/affine.cpp's Scale).
inline QuadForm operator*(const QuadForm& x, double k) {
    QuadForm z{};
    for (int i = 0; i < QuadForm::kCount; ++i) z.c[i] = x.c[i] * k;
    for (int i = 0; i < QuadForm::kOwn; ++i) z.o[i] = x.o[i] * k;
    z.r = LinearError(std::fabs(k) * x.r * (1 + kEpsilon), z.coefficientSum()) + kUnderflowSlack;
    return z;
}
inline QuadForm operator*(double k, const QuadForm& x) { return x * k; }

/// The sums of a form's coefficients that its products and lerps need: sum |c_k| and sum |o_k|
/// (as QuadForm::polynomialSum and ownSum compute them, so that a caller holding them spares
/// computing them again).
struct QuadSums {
    double polynomial, own;
    double all() const { return polynomial + own; }
};
inline QuadSums SumsOf(const QuadForm& x) { return {x.polynomialSum(), x.ownSum()}; }

/// x * y, given their sums (SumsOf). The product's terms of degree 3 and 4 are reduced monomial
/// by monomial (the head comment); the rest of the error: |x's polynomial| ry + |y's| rx + rx ry,
/// the rounding of every coefficient (each a sum of at most eight terms: 16 u of the terms'
/// magnitudes) and that of the double product (u of the largest |x y|).
inline QuadForm Multiply(const QuadForm& x, const QuadSums& xs, const QuadForm& y, const QuadSums& ys) {
    enum { k0 = QuadForm::k0, kU = QuadForm::kU, kV = QuadForm::kV, kUU = QuadForm::kUU };
    enum { kUV = QuadForm::kUV, kVV = QuadForm::kVV };
    const double* a = x.c;
    const double* b = y.c;
    // The degree 3 and 4 coefficients of the exact product.
    const double uuu = a[kU] * b[kUU] + a[kUU] * b[kU];
    const double uuv = a[kU] * b[kUV] + a[kUV] * b[kU] + a[kV] * b[kUU] + a[kUU] * b[kV];
    const double uvv = a[kU] * b[kVV] + a[kVV] * b[kU] + a[kV] * b[kUV] + a[kUV] * b[kV];
    const double vvv = a[kV] * b[kVV] + a[kVV] * b[kV];
    const double uuuu = a[kUU] * b[kUU];
    const double uuuv = a[kUU] * b[kUV] + a[kUV] * b[kUU];
    const double uuvv = a[kUU] * b[kVV] + a[kVV] * b[kUU] + a[kUV] * b[kUV];
    const double uvvv = a[kUV] * b[kVV] + a[kVV] * b[kUV];
    const double vvvv = a[kVV] * b[kVV];
    QuadForm z{};
    double* c = z.c;
    // u^4 = u^2 - 1/8 +- 1/8, v^4 likewise, u^2 v^2 = 1/2 +- 1/2.
    c[k0] = a[k0] * b[k0] - 0.125 * (uuuu + vvvv) + 0.5 * uuvv;
    // u^3 = 3/4 u +- 1/4, u v^2 = 1/2 u +- 1/2.
    c[kU] = a[k0] * b[kU] + a[kU] * b[k0] + 0.75 * uuu + 0.5 * uvv;
    c[kV] = a[k0] * b[kV] + a[kV] * b[k0] + 0.75 * vvv + 0.5 * uuv;
    c[kUU] = a[k0] * b[kUU] + a[kUU] * b[k0] + a[kU] * b[kU] + uuuu;
    // u^3 v = 3/4 u v +- 1/4, u v^3 likewise.
    c[kUV] = a[k0] * b[kUV] + a[kUV] * b[k0] + a[kU] * b[kV] + a[kV] * b[kU] + 0.75 * (uuuv + uvvv);
    c[kVV] = a[k0] * b[kVV] + a[kVV] * b[k0] + a[kV] * b[kV] + vvvv;
    const double reduced = 0.25 * (std::fabs(uuu) + std::fabs(vvv)) + 0.5 * (std::fabs(uuv) + std::fabs(uvv)) +
                           0.125 * (std::fabs(uuuu) + std::fabs(vvvv)) + 0.5 * std::fabs(uuvv) +
                           0.25 * (std::fabs(uuuv) + std::fabs(uvvv));
    // The own symbols: times the other's constant they stay; times anything else they are
    // remainder (each symbol and monomial in [-1, 1]).
    for (int k = 0; k < QuadForm::kOwn; ++k) z.o[k] = a[k0] * y.o[k] + b[k0] * x.o[k];
    const double ox = xs.own, oy = ys.own;
    const double ax = xs.polynomial + ox, ay = ys.polynomial + oy;
    const double owned = ox * (ay - std::fabs(b[k0])) + oy * (ax - std::fabs(a[k0]));  // ox oy twice
    const double crossed = ax * y.r + ay * x.r + x.r * y.r;
    // Every product a_i b_j is a term of some coefficient (sum |a_i| |b_j| = ax ay), scaled by at
    // most 1 on its way there.
    const double rounding = (16 * ax * ay + (ax + x.r) * (ay + y.r)) * kEpsilon;
    z.r = (reduced + (owned > 0 ? owned : 0.0) + crossed + rounding) * kSumSlack + kUnderflowSlack;
    return z;
}

/// x * y (Multiply).
inline QuadForm operator*(const QuadForm& x, const QuadForm& y) { return Multiply(x, SumsOf(x), y, SumsOf(y)); }

/// v0 + s (v1 - v0), as the double computes it, for an s whose double values at the points that
/// matter lie in [0, 1] (up to 2^-40: a noise fade at a local coordinate in [0, 1]); elsewhere the
/// result holds nothing. The same real number is (1 - s) v0 + s v1, so the remainders of v0 and
/// v1 weigh 1 - s and s, a convex combination: max(r0, r1), where the product of forms would
/// count r0 twice (in v0 and in v1 - v0) and a chain of lerps compound it. The rest: the product
/// s (v1 - v0) of the polynomial parts (its reductions, s's remainder, the roundings of the
/// difference's coefficients), the sum's roundings, and the three roundings of the double lerp
/// against the real one, at most 3.01 u (|v0| + |v1|). The operands' sums are given (SumsOf) and
/// the result's returned in zs, for the next lerp of a chain.
inline QuadForm Lerp(const QuadForm& v0, const QuadSums& v0s, const QuadForm& v1, const QuadSums& v1s,
                     const QuadForm& s, const QuadSums& ss, QuadSums* zs) {
    QuadForm d = AddCoefficients<true>(v1, v0);
    const QuadSums ds = SumsOf(d);
    d.r = LinearError(0.0, ds.all());
    const QuadForm p = Multiply(s, ss, d, ds);
    QuadForm z = AddCoefficients<false>(v0, p);
    *zs = SumsOf(z);
    const double magnitudes = v0s.all() + v0.r + v1s.all() + v1.r;
    const double convex = (v0.r > v1.r ? v0.r : v1.r) * (1 + 0x1p-38);
    z.r = (LinearError(p.r, zs->all()) + convex + 2 * kEpsilon * magnitudes) * kSumSlack + kUnderflowSlack;
    return z;
}
inline QuadForm Lerp(const QuadForm& v0, const QuadForm& v1, const QuadForm& s) {
    QuadSums zs;
    return Lerp(v0, SumsOf(v0), v1, SumsOf(v1), s, SumsOf(s), &zs);
}

}  // namespace affray::vm
