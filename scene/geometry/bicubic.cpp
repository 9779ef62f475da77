// scene/geometry/bicubic.cpp: the predefined cubic bases and the conversion of a bicubic patch's
// control points to the power basis (scene/geometry/bicubic.h).
#include "scene/geometry/bicubic.h"

#include "scene/geometry/pole.h"
#include "scene/number_text.h"

#include <cmath>
#include <sstream>

namespace affray::renderer {

namespace {

struct NamedBasis {
    const char* name;
    int step;
    double scale;
    std::array<double, 16> m;  // times scale
};

// RI 3.2 section 5.2 (RiBezierBasis ... RiPowerBasis), with the steps its table gives. The hermite
// matrix takes the geometry (point0, vector0, point1, vector1), so that step 2 walks a mesh.
const NamedBasis kBases[] = {
    {"bezier", 3, 1.0, {-1, 3, -3, 1, 3, -6, 3, 0, -3, 3, 0, 0, 1, 0, 0, 0}},
    {"b-spline", 1, 1.0 / 6.0, {-1, 3, -3, 1, 3, -6, 3, 0, -3, 0, 3, 0, 1, 4, 1, 0}},
    {"catmull-rom", 1, 0.5, {-1, 3, -3, 1, 2, -5, 4, -1, -1, 0, 1, 0, 0, 2, 0, 0}},
    {"hermite", 2, 1.0, {2, 1, -2, 1, -3, -2, 3, -1, 0, 1, 0, 0, 1, 0, 0, 0}},
    {"power", 4, 1.0, {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}},
};

}  // namespace

std::optional<CubicBasis> CubicBasis::Named(const std::string& name) {
    for (const NamedBasis& b : kBases) {
        if (name != b.name) continue;
        CubicBasis out;
        for (int i = 0; i < 16; ++i) out.m[i] = b.m[i] * b.scale;
        out.step = b.step;
        out.name = b.name;
        return out;
    }
    return std::nullopt;
}

const char* CubicBasis::NameList() { return "\"bezier\", \"b-spline\", \"catmull-rom\", \"hermite\" or \"power\""; }

std::string ToString(const CubicBasis& b) {
    std::ostringstream out;
    if (!b.name.empty()) {
        out << b.name;
    } else {
        out << '[';
        for (int i = 0; i < 16; ++i) out << (i ? " " : "") << b.m[i];
        out << ']';
    }
    out << ' ' << b.step;
    return out.str();
}

BicubicPatch BicubicPatch::FromControlPoints(const std::array<glm::dvec3, 16>& points, const CubicBasis& uBasis,
                                             const CubicBasis& vBasis, const glm::dmat4& objectToWorld) {
    // C = Mu G Mv^T, with G[a][b] the control point of u index a and v index b (points[4 b + a]);
    // C[a][b] is then the coefficient of u^(3-a) v^(3-b). The same product of absolute values
    // bounds the size of the terms each coefficient sums, for the noise floor below.
    std::array<glm::dvec3, 16> mg{}, mgAbs{};  // Mu G, |Mu| |G|
    for (int a = 0; a < 4; ++a)
        for (int b = 0; b < 4; ++b) {
            glm::dvec3 sum(0.0), sumAbs(0.0);
            for (int k = 0; k < 4; ++k) {
                sum += uBasis.m[4 * a + k] * points[4 * b + k];
                sumAbs += std::fabs(uBasis.m[4 * a + k]) * glm::abs(points[4 * b + k]);
            }
            mg[4 * a + b] = sum;
            mgAbs[4 * a + b] = sumAbs;
        }
    const glm::dmat3 linear(objectToWorld);
    glm::dmat3 linearAbs;
    for (int col = 0; col < 3; ++col) linearAbs[col] = glm::abs(linear[col]);
    const glm::dvec3 translation(objectToWorld[3]);
    BicubicPatch patch;
    for (int a = 0; a < 4; ++a)
        for (int b = 0; b < 4; ++b) {
            glm::dvec3 sum(0.0), sumAbs(0.0);
            for (int k = 0; k < 4; ++k) {
                sum += mg[4 * a + k] * vBasis.m[4 * b + k];
                sumAbs += mgAbs[4 * a + k] * std::fabs(vBasis.m[4 * b + k]);
            }
            glm::dvec3 c = linear * sum;
            const glm::dvec3 size = linearAbs * sumAbs;
            // A coefficient that cancels in exact arithmetic (a bezier patch whose control points
            // lie on a bilinear surface has no u^2, u^3, v^2, v^3 terms) is left with rounding
            // noise of a few ulps of the terms summed: zero it, so that the evaluation skips it.
            // The surface moves by less than 1e-14 of the terms' size, far below any tolerance.
            for (int i = 0; i < 3; ++i)
                if (std::fabs(c[i]) <= 1e-14 * size[i]) c[i] = 0;
            if (a == 3 && b == 3) c += translation;  // the u^0 v^0 term: the only point among them
            patch.c[4 * (3 - a) + (3 - b)] = c;
        }
    patch.poles = FindPatchPoles(patch);
    return patch;
}

glm::dvec3 BicubicPatch::At(double u, double v) const {
    const SurfaceFrame<double> f = BicubicFrame<double>(*this, u, v);
    return {f.P.x, f.P.y, f.P.z};
}

bool BicubicPatch::FiniteP() const {
    for (const glm::dvec3& x : c)
        for (int i = 0; i < 3; ++i)
            if (!std::isfinite(x[i])) return false;
    return true;
}

namespace bicubic_detail {

namespace {

using vm::kUnitRoundoff;

/// The powers of x in (c + r x)^i: m[i][k] = C(i, k) c^(i - k) r^k for k <= i (0 above), and
/// their magnitudes. Each entry is a product of at most six roundings of the exact one.
struct LocalShift {
    double m[4][4] = {};
    double a[4][4] = {};

    LocalShift(double c, double r) {
        static constexpr double kBinomial[4][4] = {{1, 0, 0, 0}, {1, 1, 0, 0}, {1, 2, 1, 0}, {1, 3, 3, 1}};
        const double cp[4] = {1, c, c * c, c * c * c}, rp[4] = {1, r, r * r, r * r * r};
        for (int i = 0; i < 4; ++i)
            for (int k = 0; k <= i; ++k) {
                m[i][k] = kBinomial[i][k] * cp[i - k] * rp[k];
                a[i][k] = std::fabs(m[i][k]);
            }
    }
};

/// Relative bound on the rounding of a local coefficient: two shifts' entries (six roundings
/// each), two products and two sums of four terms make at most 20 roundings of the sum of the
/// magnitudes of its terms (gamma_20 < 21 u), computed itself with as many: 32 u covers both.
constexpr double kCoefficientSlack = 32 * kUnitRoundoff;
/// Relative bound on the rounding of HornerFrame<double>: Horner in u (degree 3: six roundings),
/// then in v over the rounded rows (six more, and a scale by 1..3 for dPdv; dPdu's coefficients
/// i * c_i are the same doubles here as there) is within gamma_14 < 15 u of the exact polynomial,
/// relative to sum |c_ij| |u|^i |v|^j; 32 u covers the rounding of that sum too.
constexpr double kScalarSlack = 32 * kUnitRoundoff;
/// Absolute bound on what underflow adds, with |u|, |v| <= 4 (RegionFrame): each product that
/// underflows is off by 2^-1075 at most, carried by factors below 2^8 through two shifts (and
/// likewise in HornerFrame<double>), far below 2^-1040 in all.
constexpr double kUnderflow = 0x1p-1040;

/// The coefficients l[k][j] of x^k y^j of a polynomial over the region u = uc + ru x, v = vc + rv y
/// (x, y in [-1, 1]), and the magnitudes la of their terms, which bound their rounding
/// (kCoefficientSlack * la).
struct LocalPolynomial {
    double l[4][4] = {};
    double la[4][4] = {};
};

/// The polynomial sum of p[i][j] u^i v^j over i <= nu, j <= nv (one coordinate; the degrees are
/// template arguments so that the loops unroll) in the region's local power basis.
template <int nu, int nv>
LocalPolynomial Localise(const double (&p)[4][4], const LocalShift& su, const LocalShift& sv) {
    // W = P Mv (the shift in v of each row), then L = Mu^T W; with the magnitudes alongside.
    double w[4][4] = {}, wa[4][4] = {};
    for (int i = 0; i <= nu; ++i)
        for (int j = 0; j <= nv; ++j) {
            const double pij = p[i][j], aij = std::fabs(pij);
            for (int l = 0; l <= j; ++l) {
                w[i][l] += pij * sv.m[j][l];
                wa[i][l] += aij * sv.a[j][l];
            }
        }
    LocalPolynomial out;
    for (int i = 0; i <= nu; ++i)
        for (int k = 0; k <= i; ++k)
            for (int j = 0; j <= nv; ++j) {
                out.l[k][j] += su.m[i][k] * w[i][j];
                out.la[k][j] += su.a[i][k] * wa[i][j];
            }
    return out;
}

/// sum |p_ij| uMax^i vMax^j over i <= nu, j <= nv: what HornerFrame<double>'s rounding is relative to.
template <int nu, int nv>
double ScalarMagnitude(const double (&p)[4][4], const double (&uPow)[4], const double (&vPow)[4]) {
    double sum = 0;
    for (int i = 0; i <= nu; ++i)
        for (int j = 0; j <= nv; ++j) sum += std::fabs(p[i][j]) * uPow[i] * vPow[j];
    return sum;
}

/// The reduced affine form of the local polynomial l over [-1, 1]^2, with `coefficientError`
/// (the rounding of l) and `scalar` (ScalarMagnitude) added to its error: it contains both the
/// exact polynomial and its Horner evaluation in doubles at every point of the region.
vm::ReducedAffine FormOf(const double (&l)[4][4], double coefficientError, double scalar) {
    // x^k y^j over [-1, 1]^2 as its affine part and error: each power is 1, x, 0.5 +- 0.5 (squares)
    // or 0.75 x +- 0.25 (cubes, the Chebyshev fit); an odd power of one parameter times an even
    // power of the other keeps its fit times the even power's middle (x y^2 = 0.5 x +- 0.5), a
    // product of even powers is 0.5 +- 0.5, and of odd powers 0 +- 1.
    static constexpr double kSlope[4] = {0, 1, 0, 0.75}, kFitError[4] = {0, 0, 0, 0.25};
    static constexpr double kMiddle[4] = {1, 0, 0.5, 0}, kHalfRange[4] = {0, 0, 0.5, 0};
    double centre = 0, du = 0, dv = 0, termSum = 0, nonlinear = 0;
    for (int k = 0; k < 4; ++k)
        for (int j = 0; j < 4; ++j) {
            const double c = l[k][j], ac = std::fabs(c);
            if (c == 0) continue;
            const bool oddK = k % 2 == 1, oddJ = j % 2 == 1;
            if (oddK && !oddJ) {
                du += c * (kSlope[k] * kMiddle[j]);
                termSum += ac * (kSlope[k] * kMiddle[j]);
                nonlinear += ac * (kSlope[k] * kHalfRange[j] + kFitError[k]);
            } else if (!oddK && oddJ) {
                dv += c * (kSlope[j] * kMiddle[k]);
                termSum += ac * (kSlope[j] * kMiddle[k]);
                nonlinear += ac * (kSlope[j] * kHalfRange[k] + kFitError[j]);
            } else if (!oddK) {
                const double middle = k + j == 0 ? 1 : 0.5;
                centre += c * middle;
                termSum += ac * middle;
                nonlinear += ac * (1 - middle);
            } else {
                nonlinear += ac;
            }
        }
    // The sums of four terms above (each a product by an exact constant) round by gamma_4 < 8 u
    // of their magnitudes; the nonnegative sums of the error by far less than the final factor.
    const double error =
        (nonlinear + coefficientError + kScalarSlack * scalar + 8 * kUnitRoundoff * termSum + kUnderflow) *
        (1 + 0x1p-40);
    return vm::ReducedAffine::FromForm(centre, du, dv, error);
}

/// The sum of la's entries times kCoefficientSlack: the rounding of all of l's coefficients.
double CoefficientError(const LocalPolynomial& q) {
    double sum = 0;
    for (int k = 0; k < 4; ++k)
        for (int j = 0; j < 4; ++j) sum += q.la[k][j];
    return kCoefficientSlack * sum;
}

/// The local polynomial of a tangent from P's: dP/du = (1/ru) dQ/dx for Q(x, y) = P(uc + ru x,
/// vc + rv y), so its coefficient of x^k y^j is (k + 1) l[k + 1][j] / ru (alongU; along v, the
/// same with the roles swapped); the rounding of P's coefficients carries over scaled the same
/// way, and the product and quotient round each coefficient by 2 u at most (4 u taken).
vm::ReducedAffine TangentForm(const LocalPolynomial& q, double radius, bool alongU, double scalar) {
    double d[4][4] = {};
    double error = 0;
    const double scale = 1 / std::fabs(radius);
    for (int k = 0; k < 3; ++k)
        for (int j = 0; j < 4; ++j) {
            const int a = alongU ? k + 1 : j, b = alongU ? j : k + 1;
            const double factor = k + 1;
            double& out = alongU ? d[k][j] : d[j][k];
            out = factor * q.l[a][b] / radius;
            error += factor * kCoefficientSlack * q.la[a][b] * scale + 4 * kUnitRoundoff * std::fabs(out);
        }
    return FormOf(d, error * (1 + 0x1p-40), scalar);
}

}  // namespace

bool RegionFrame(const BicubicPatch& patch, const vm::ReducedAffine& u, const vm::ReducedAffine& v,
                 SurfaceFrame<vm::ReducedAffine>* frame) {
    if (u.isUnbounded() || v.isUnbounded() || u.error() != 0 || v.error() != 0 || u.coefficientV() != 0 ||
        v.coefficientU() != 0)
        return false;
    const double uc = u.center(), ru = u.coefficientU(), vc = v.center(), rv = v.coefficientV();
    // |u| and |v| anywhere in the region, rounded up.
    const double uMax = (std::fabs(uc) + std::fabs(ru)) * (1 + 4 * kUnitRoundoff);
    const double vMax = (std::fabs(vc) + std::fabs(rv)) * (1 + 4 * kUnitRoundoff);
    // The relative rounding bounds need parameters of moderate size (a patch's are in [0, 1]):
    // then no product underflows by more than kUnderflow covers, and the shifts stay below 2^8.
    const auto tiny = [](double x) { return x != 0 && std::fabs(x) < 0x1p-300; };
    if (!(uMax <= 4 && vMax <= 4) || tiny(uc) || tiny(ru) || tiny(vc) || tiny(rv)) return false;
    const LocalShift su(uc, ru), sv(vc, rv);
    const double uPow[4] = {1, uMax, uMax * uMax, uMax * uMax * uMax};
    const double vPow[4] = {1, vMax, vMax * vMax, vMax * vMax * vMax};
    for (int axis = 0; axis < 3; ++axis) {
        // P, and the coefficients of dP/du and dP/dv as HornerFrame forms them (i * c_i).
        double p[4][4], pu[4][4] = {}, pv[4][4] = {};
        for (int i = 0; i < 4; ++i)
            for (int j = 0; j < 4; ++j) p[i][j] = patch.c[4 * i + j][axis];
        for (int i = 1; i < 4; ++i)
            for (int j = 0; j < 4; ++j) pu[i - 1][j] = i * p[i][j];
        for (int i = 0; i < 4; ++i)
            for (int j = 1; j < 4; ++j) pv[i][j - 1] = j * p[i][j];
        const LocalPolynomial q = Localise<3, 3>(p, su, sv);
        frame->P[axis] = FormOf(q.l, CoefficientError(q), ScalarMagnitude<3, 3>(p, uPow, vPow));
        // The tangents from P's local polynomial where the region has a width along the
        // parameter; a region of one u (or v) localises the tangent's own polynomial.
        const double su3 = ScalarMagnitude<2, 3>(pu, uPow, vPow), sv3 = ScalarMagnitude<3, 2>(pv, uPow, vPow);
        if (ru != 0) {
            frame->dPdu[axis] = TangentForm(q, ru, true, su3);
        } else {
            const LocalPolynomial d = Localise<2, 3>(pu, su, sv);
            frame->dPdu[axis] = FormOf(d.l, CoefficientError(d), su3);
        }
        if (rv != 0) {
            frame->dPdv[axis] = TangentForm(q, rv, false, sv3);
        } else {
            const LocalPolynomial d = Localise<3, 2>(pv, su, sv);
            frame->dPdv[axis] = FormOf(d.l, CoefficientError(d), sv3);
        }
    }
    return true;
}

}  // namespace bicubic_detail

std::string ToString(const BicubicPatch& p) {
    std::string out = "bicubic [";
    for (int k = 0; k < 16; ++k) {
        out += k ? " [" : "[";
        for (int i = 0; i < 3; ++i) {
            if (i) out += ' ';
            AppendNumber(out, p.c[k][i]);
        }
        out += ']';
    }
    out += ']';
    return out;
}

}  // namespace affray::renderer
