// vm/numbers/rounding.h: outward rounding and error bounds for the bounded number types (Interval, Affine,
// ReducedAffine).
// Owns the error model; every constant that a containment proof relies on is defined here, once.
//
// Error model (round-to-nearest-even doubles, the default; nothing here calls fesetround):
//  - One +, -, *, / or sqrt of doubles is correctly rounded: |exact - fl(exact)| <= u*|fl(exact)|
//    with u = 2^-53, except that a product or quotient falling below 2^-1022 may lose up to
//    2^-1075 absolutely (a sum or difference that underflows is exact).
//  - NextUp/NextDown step one ulp or more outward; AddUp ... DivDown are the directed roundings of
//    one operation, exact results kept exact (error-free transforms: TwoSum, and std::fma for the
//    residual of a product, quotient or root, as in Stolfi & de Figueiredo's rounding discussion).
//  - glibc's exp, log, sin, cos, pow, acos and asin are documented within 1-2 ulp on x86_64
//    (glibc's libm-test-ulps). We allow kLibmUlps = 4 ulps (2^-50 relative, plus 16 subnormal
//    steps), which covers the error of the value at an endpoint and of the value at any point
//    inside (2 ulps together) with room to spare. LibmDown/LibmUp apply it.
//  - A bound built from a chain of k <= 256 roundings of non-negative values (or of a difference
//    P - Q with Q <= P/2, which at most triples the relative error) is at most (1+u)^k too small;
//    multiplying by kSumSlack = 1 + 2^-45 = 1 + 256u covers that.
// Sources: Stolfi & de Figueiredo, "Self-Validated Numerical Methods and Applications" (1997),
// ch. 3-4 on rounding in AA; Heidrich & Seidel, "Ray-tracing procedural displacement shaders",
// GI 1998. Everything assumes IEEE binary64 with no x87 excess precision (x86-64 SSE2).
#pragma once

#include <cmath>
#include <limits>

namespace affray::vm {

/// Unit roundoff u: the relative error of one correctly rounded operation.
inline constexpr double kUnitRoundoff = 0x1p-53;
/// 2u: one ulp of any double >= 1, and an upper bound of ulp(x)/|x| for normal x.
inline constexpr double kEpsilon = 0x1p-52;
/// The smallest positive (subnormal) double.
inline constexpr double kMinSubnormal = 0x1p-1074;
/// Below this, products and quotients may lose absolute (not relative) accuracy.
inline constexpr double kUnderflowLimit = 0x1p-960;
/// Absolute slack that covers every underflow of one Affine or ReducedAffine operation (<= 2^14
/// products).
inline constexpr double kUnderflowSlack = 0x1p-1060;
/// Relative slack for a glibc transcendental: 4 ulps (see the head comment).
inline constexpr double kLibmRel = 0x1p-50;
/// Absolute slack for a glibc transcendental whose result is subnormal.
inline constexpr double kLibmAbs = 0x1p-1070;
/// Factor that covers the rounding of a chain of up to 256 operations on non-negative values.
inline constexpr double kSumSlack = 1.0 + 0x1p-45;
inline constexpr double kMaxFinite = std::numeric_limits<double>::max();
inline constexpr double kInfinity = std::numeric_limits<double>::infinity();

/// A double >= the next double above x (x finite; NextUp(+inf) = +inf, NextUp(-inf) is NaN).
inline double NextUp(double x) { return x + (std::fabs(x) * kEpsilon + kMinSubnormal); }
/// A double <= the next double below x.
inline double NextDown(double x) { return x - (std::fabs(x) * kEpsilon + kMinSubnormal); }

/// The exact rounding error of s = fl(a + b): a + b = s + TwoSumError(a, b, s) (Knuth's TwoSum).
/// NaN when the sum overflowed.
inline double TwoSumError(double a, double b, double s) {
    double bb = s - a;
    return (a - (s - bb)) + (b - bb);
}

inline double AddUp(double a, double b) {
    double s = a + b;
    return TwoSumError(a, b, s) > 0 ? NextUp(s) : s;
}
inline double AddDown(double a, double b) {
    double s = a + b;
    return TwoSumError(a, b, s) < 0 ? NextDown(s) : s;
}
inline double SubUp(double a, double b) { return AddUp(a, -b); }
inline double SubDown(double a, double b) { return AddDown(a, -b); }

/// True when the residual of a product, quotient or root near p cannot be trusted (underflow).
inline bool MayUnderflow(double p) { return std::fabs(p) < kUnderflowLimit; }

inline double MulUp(double a, double b) {
    double p = a * b;
    if (MayUnderflow(p)) return (a == 0 || b == 0) ? p : NextUp(p);
    return std::fma(a, b, -p) > 0 ? NextUp(p) : p;
}
inline double MulDown(double a, double b) {
    double p = a * b;
    if (MayUnderflow(p)) return (a == 0 || b == 0) ? p : NextDown(p);
    return std::fma(a, b, -p) < 0 ? NextDown(p) : p;
}

/// Directed quotients; b != 0. The residual a - q*b has the sign of (a/b - q)*b.
inline double DivUp(double a, double b) {
    double q = a / b;
    if (MayUnderflow(q) || MayUnderflow(a)) return a == 0 ? q : NextUp(q);
    double r = std::fma(-q, b, a);
    return (b > 0 ? r > 0 : r < 0) ? NextUp(q) : q;
}
inline double DivDown(double a, double b) {
    double q = a / b;
    if (MayUnderflow(q) || MayUnderflow(a)) return a == 0 ? q : NextDown(q);
    double r = std::fma(-q, b, a);
    return (b > 0 ? r < 0 : r > 0) ? NextDown(q) : q;
}

/// Directed square roots; x >= 0.
inline double SqrtUp(double x) {
    double s = std::sqrt(x);
    if (MayUnderflow(x)) return x == 0 ? s : NextUp(s);
    return std::fma(s, s, -x) < 0 ? NextUp(s) : s;
}
inline double SqrtDown(double x) {
    double s = std::sqrt(x);
    if (MayUnderflow(x)) return x == 0 ? s : NextDown(s);
    return std::fma(s, s, -x) > 0 ? NextDown(s) : s;
}

/// Lower/upper bounds of both the true f(t) and glibc's f at any t near an endpoint where glibc
/// returned r (kLibmUlps of slack; the final subtraction loses at most half an ulp of it).
inline double LibmDown(double r) { return r - (std::fabs(r) * kLibmRel + kLibmAbs); }
inline double LibmUp(double r) { return r + (std::fabs(r) * kLibmRel + kLibmAbs); }

/// An upper bound of a sum of non-negative terms: exact when every partial sum was exact.
class UpperSum {
  public:
    void add(double x) {
        double s = m_sum + x;
        m_err += std::fabs(TwoSumError(m_sum, x, s));
        m_sum = s;
    }
    double value() const { return m_err == 0 ? m_sum : NextUp(m_sum + m_err); }

  private:
    double m_sum = 0;
    double m_err = 0;
};

/// The error of a linear operation on affine forms (a sum, a difference, a scaling, a constant
/// added): the operands' errors `inputError`, plus the rounding of every coefficient (<= u*A, with
/// A = `absSum` = |z0| + sum |zi| of the result) and of the scalar operation (<= u*max|result| <=
/// u*(A + E)), rounded up.
inline double LinearError(double inputError, double absSum) {
    return (inputError + (absSum + inputError) * kEpsilon) * kSumSlack;
}

/// The sums an affine product x * y accumulates while it forms its terms (x0 + sum xi ei + ex) *
/// (y0 + sum yi ei + ey), whatever the representation of the forms (Affine, ReducedAffine, noise's
/// LocalForm).
struct ProductSums {
    double x0 = 0, y0 = 0;  // centres
    double rx = 0, ry = 0;  // sum |xi|, sum |yi|
    double ex = 0, ey = 0;  // independent errors
    double diag = 0;        // sum xi yi over shared symbols (half of it goes to the centre)
    double absDiag = 0;     // sum |xi yi|
    double absSum = 0;      // sum of |terms| of the result, centre included, as rounded
};

/// The error term of the product: the quadratic remainder (X + ex)(Y + ey) less the part of the
/// shared squares moved into the centre, the linear terms of the errors, and the rounding of
/// every term, centre and remainder, for up to `termSlack` / 2 - 2 terms. (Stolfi & de
/// Figueiredo's multiplication, with its rounding made explicit.)
inline double ProductRemainder(const ProductSums& s, double termSlack) {
    const double p0 = s.x0 * s.y0;
    // The nonlinear remainder is >= half of (rx+ex)(ry+ey), so its relative rounding is small.
    const double quad = (s.rx + s.ex) * (s.ry + s.ey) - 0.5 * s.absDiag;
    const double linear = std::fabs(s.x0) * s.ey + std::fabs(s.y0) * s.ex;
    const double maxResult = (std::fabs(s.x0) + s.rx + s.ex) * (std::fabs(s.y0) + s.ry + s.ey);
    const double rounding = (std::fabs(s.x0) * s.ry + std::fabs(s.y0) * s.rx + std::fabs(p0) + termSlack * s.absDiag +
                             s.absSum + maxResult) *
                            kEpsilon;
    return (quad + linear + rounding) * kSumSlack + kUnderflowSlack;
}

/// The centre and error term of the square of an affine form x0 + X + E (X = sum xi ei with
/// r = sum |xi|, |E| <= e): (x0 + X + E)^2 = x0^2 + 2*x0*X + 2*x0*E + (X + E)^2 with (X + E)^2 in
/// [0, q], q = (r + e)^2, so the centre is x0^2 + q/2 and the error q/2 + |2*x0|*e plus the
/// rounding of everything (`coefAbsSum` = sum |2*x0*xi| as rounded, `termSlack` as in
/// ProductRemainder).
struct SquareParts {
    double center, error;
};
inline SquareParts SquareRemainder(double x0, double r, double e, double coefAbsSum, double termSlack) {
    const double q = (r + e) * (r + e);
    const double p0 = x0 * x0;
    const double center = p0 + 0.5 * q;
    const double absSum = coefAbsSum + std::fabs(center);
    const double linear = std::fabs(2 * x0) * e;
    const double maxResult = (std::fabs(x0) + r + e) * (std::fabs(x0) + r + e);
    const double rounding = (p0 + termSlack * q + absSum + maxResult) * kEpsilon;
    return {center, (0.5 * q + linear + rounding) * kSumSlack + kUnderflowSlack};
}

}  // namespace affray::vm
