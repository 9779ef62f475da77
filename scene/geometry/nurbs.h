// scene/geometry/nurbs.h: rational patches (a rational Patch "bilinear"/"bicubic" and the spans
// of a NuPatch, RI Spec 3.2 section 5.3) as base surfaces over (u,v), for every number type, and
// the trim curves (TrimCurve) that cut NuPatches.
// A rational patch is kept, in doubles, as a tensor-product polynomial of any degree up to
// kMaxNurbsOrder - 1 in the power basis of its own [0,1]^2, with homogeneous coefficients
// (X, Y, Z, W) in world space: P = (X, Y, Z) / W. One template (RationalFrame) evaluates X..W and
// their derivatives by Horner's rule in s then t, divides once by W and forms the tangents by the
// quotient rule, so a double, an Interval, an affine form or a Dual gives the point, a bound or
// exact derivatives from the same code. A patch whose W is constant is divided out once when
// built and evaluated as a polynomial (no division): every non-rational patch and NuPatch.
// A NuPatch becomes one such patch per non-empty knot span (clipped to umin..umax, vmin..vmax),
// converted once by the Cox-de Boor recursion carried out on polynomials of the span's local
// parameter; each covers a ParameterRange of the NuPatch's (u,v), which are the knot parameters.
// Positive weights keep W > 0 over every span (the B-spline basis is a partition of unity), so
// the division stays bounded: non-positive weights are rejected where the patch is read.
#pragma once

#include <array>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "scene/geometry/bicubic.h"
#include "scene/geometry/primvar.h"
#include "scene/geometry/quadric.h"
#include "vm/numbers/vec3.h"

namespace affray::renderer {

/// The highest order (degree + 1) of a NuPatch or trim curve in either direction.
inline constexpr int kMaxNurbsOrder = 11;

/// A rational tensor-product patch over s, t in [0, 1]: P = (X, Y, Z) / W with each of X, Y, Z, W
/// the polynomial sum over i <= degreeU, j <= degreeV of c[(degreeV + 1) i + j] s^i t^j, world
/// space. Optional texture coordinates (s, t) of the same form (the RI primitive variable "st").
struct RationalPatch {
    int degreeU = 0, degreeV = 0;
    bool rational = false;       ///< W is not identically 1 (else its coefficients are 1, 0, ...)
    std::vector<glm::dvec4> c;   ///< (degreeU + 1) (degreeV + 1) homogeneous coefficients
    bool hasST = false;          ///< whether `st` holds the texture coordinates
    bool stHomogeneous = false;  ///< st is divided by W (vertex "st" of a rational NuPatch)
    std::vector<glm::dvec2> st;  ///< coefficients as c's (if hasST)
    /// Edges collapsed to a point and the factor that gives the normal there (pole.h), or null;
    /// set by Simplify.
    std::shared_ptr<const PatchPoles> poles;

    /// The patch of the 4 homogeneous corners `q` (world space; RenderMan order u0v0, u1v0, u0v1, u1v1).
    static RationalPatch Bilinear(const std::array<glm::dvec4, 4>& q);
    /// The bicubic patch of 16 homogeneous control points `points` (object space, u fastest, w
    /// in their 4th coordinate and x, y, z multiplied by it, as RI "Pw" gives them) with the
    /// given bases, placed by `objectToWorld` (affine).
    static RationalPatch Bicubic(const std::array<glm::dvec4, 16>& points, const CubicBasis& uBasis,
                                 const CubicBasis& vBasis, const glm::dmat4& objectToWorld);

    size_t Index(int i, int j) const {
        return static_cast<size_t>(degreeV + 1) * static_cast<size_t>(i) + static_cast<size_t>(j);
    }
    /// Zeroes coefficients within rounding noise of zero (relative to `size`, the sums of the
    /// terms' absolute values that made them) and, if W is then constant, divides it out.
    void Simplify(const std::vector<glm::dvec4>& size);
    /// The point at (s, t), in doubles (for messages and tests).
    glm::dvec3 At(double s, double t) const;
    /// Whether every coefficient is finite.
    bool FiniteP() const;
};

/// A homogeneous object-space point (x w, y w, z w, w) placed by an affine matrix: the linear part
/// acts on x, y, z and the translation is scaled by w.
glm::dvec4 PlaceHomogeneous(const glm::dmat4& m, const glm::dvec4& p);

/// "rational 3x3 [...]": the degrees and coefficients.
std::string ToString(const RationalPatch& p);

namespace nurbs_detail {

/// The polynomial of (degreeU, degreeV) whose coefficient (i, j) is coef(i, j), with its s and t
/// derivatives: Horner in s for each power of t, then in t (zero coefficients skipped, as
/// BicubicFrame does). `ds`, `dt` may be null.
template <class T, class Coef>
void Polynomial(int degreeU, int degreeV, const Coef& coef, const T& s, const T& t, T* value, T* ds, T* dt) {
    using bicubic_detail::Horner;
    static constexpr double kOne[kMaxNurbsOrder] = {1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1};
    static constexpr double kPower[kMaxNurbsOrder] = {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10};
    T a[kMaxNurbsOrder], da[kMaxNurbsOrder];
    bool zero[kMaxNurbsOrder], dzero[kMaxNurbsOrder];
    for (int j = 0; j <= degreeV; ++j) {
        double cs[kMaxNurbsOrder], dcs[kMaxNurbsOrder];
        zero[j] = dzero[j] = true;
        for (int i = 0; i <= degreeU; ++i) {
            cs[i] = coef(i, j);
            if (cs[i] != 0) zero[j] = false;
            if (i > 0) {
                dcs[i - 1] = i * cs[i];
                if (cs[i] != 0) dzero[j] = false;
            }
        }
        a[j] = zero[j] ? T(0.0) : Horner(cs, degreeU, s);
        da[j] = dzero[j] ? T(0.0) : Horner(dcs, degreeU - 1, s);
    }
    *value = Horner(a, zero, kOne, degreeV, t);
    if (ds) *ds = Horner(da, dzero, kOne, degreeV, t);
    // d/dt of sum a_j t^j = sum j a_j t^(j-1); 0 for a polynomial constant in t (Horner of degree -1,
    // and no degreeV - 1 to overflow, nor zero[j] read that the loop above did not set).
    if (dt) *dt = degreeV > 0 ? Horner(a + 1, zero + 1, kPower + 1, degreeV - 1, t) : T(0.0);
}

}  // namespace nurbs_detail

/// P(s, t) with its tangents: X..W and their derivatives by Horner's rule, then P = X / W and
/// dP/ds = (dX/ds - P dW/ds) / W (the quotient rule), one division for all. Exact derivatives
/// for T = Dual<...> come from the arithmetic itself (the tangents too, as in BicubicFrame).
template <class T>
SurfaceFrame<T> RationalFrame(const RationalPatch& p, const T& s, const T& t) {
    SurfaceFrame<T> f;
    T x[4], xs[4], xt[4];
    const int components = p.rational ? 4 : 3;
    for (int k = 0; k < components; ++k)
        nurbs_detail::Polynomial(
            p.degreeU, p.degreeV, [&](int i, int j) { return p.c[p.Index(i, j)][k]; }, s, t, &x[k], &xs[k], &xt[k]);
    if (!p.rational) {
        for (int k = 0; k < 3; ++k) f.P[k] = x[k], f.dPdu[k] = xs[k], f.dPdv[k] = xt[k];
        return f;
    }
    const T inverse = T(1.0) / x[3];
    for (int k = 0; k < 3; ++k) {
        f.P[k] = x[k] * inverse;
        f.dPdu[k] = (xs[k] - f.P[k] * xs[3]) * inverse;
        f.dPdv[k] = (xt[k] - f.P[k] * xt[3]) * inverse;
    }
    return f;
}

/// The texture coordinates of a patch with hasST at (s, t) (divided by W if stHomogeneous).
template <class T>
void RationalST(const RationalPatch& p, const T& s, const T& t, T* outS, T* outT) {
    T value[2];
    for (int k = 0; k < 2; ++k)
        nurbs_detail::Polynomial(
            p.degreeU, p.degreeV, [&](int i, int j) { return p.st[p.Index(i, j)][k]; }, s, t, &value[k],
            static_cast<T*>(nullptr), static_cast<T*>(nullptr));
    if (p.stHomogeneous) {
        T w;
        nurbs_detail::Polynomial(
            p.degreeU, p.degreeV, [&](int i, int j) { return p.c[p.Index(i, j)][3]; }, s, t, &w,
            static_cast<T*>(nullptr), static_cast<T*>(nullptr));
        const T inverse = T(1.0) / w;
        value[0] = value[0] * inverse;
        value[1] = value[1] * inverse;
    }
    *outS = value[0];
    *outT = value[1];
}

/// One direction of a NuPatch or a trim curve: n control points, the order, n + order knots
/// (nondecreasing) and the parameter range [min, max] used.
struct KnotVector {
    int n = 0, order = 0;
    std::vector<double> knots;
    double min = 0, max = 0;

    /// What is wrong with it ("" if nothing), naming the direction `name` ("u", "v", "trim curve 2").
    std::string Problem(const std::string& name) const;
    /// The non-empty spans within [min, max]: for each, the knot span index k (knots[k] <
    /// knots[k + 1]) and the clipped range [lo, hi].
    struct Span {
        int k;
        double lo, hi;
    };
    std::vector<Span> Spans() const;
    /// The `order` basis functions N_{k-order+1} ... N_k that are non-zero on span k, as
    /// polynomials (power basis, kMaxNurbsOrder coefficients each) of the local parameter x in
    /// [0, 1] of the clipped range [lo, hi]: u = lo + x (hi - lo).
    std::vector<std::array<double, kMaxNurbsOrder>> SpanBasis(const Span& span) const;
};

/// A primitive variable of a NuPatch that gives (s, t): its RI storage class and 2 values per
/// entry (constant: 1 entry; uniform: one per segment; varying: one per segment corner; vertex:
/// one per control point).
struct NurbsST {
    StorageClass storage = StorageClass::Vertex;  ///< never FaceVarying
    std::vector<glm::dvec2> values;
};

/// A colour primitive variable of a NuPatch ("Cs", "Os"): its storage class and one colour per
/// entry, counted as NurbsST's are.
struct NurbsColor {
    StorageClass storage = StorageClass::Vertex;  ///< never FaceVarying
    std::vector<glm::dvec3> values;
};

/// A NuPatch (object space): knot vectors in u and v, nu x nv homogeneous control points (u
/// fastest; x, y, z multiplied by w, as RI "Pw"), optional texture coordinates and colours.
struct NurbsSurface {
    KnotVector u, v;
    std::vector<glm::dvec4> points;
    std::optional<NurbsST> st;
    std::optional<NurbsColor> Cs, Os;
};

/// One span of a NuPatch: its patch over [0, 1]^2, the part of the NuPatch's (u,v) it covers,
/// and its Cs and Os over [0, 1]^2 if the surface has them (vertex values weighted and divided
/// by W as the points are, varying ones bilinear across their segment, as st's).
struct NurbsSpan {
    RationalPatch patch;
    ParameterRange range;
    std::optional<ColorField> Cs, Os;
};

/// The spans of `surface` (checked: KnotVector::Problem, positive weights, counts) placed by
/// `objectToWorld`, in v-major order.
std::vector<NurbsSpan> SplitNurbs(const NurbsSurface& surface, const glm::dmat4& objectToWorld);

/// The trim curves in effect for a NuPatch (TrimCurve, attribute state): closed polylines in the
/// NuPatch's (u,v), flattened from the NURBS trim curves. A point is inside when a ray from it
/// crosses the loops an odd number of times (RI 3.2's odd winding rule); inside is kept when
/// keepInside (Attribute "trimcurve" "sense" "inside", the default), else outside is kept.
struct TrimCurves {
    std::vector<std::vector<glm::dvec2>> loops;
    bool keepInside = true;

    /// Whether the surface at (u, v) is kept.
    bool KeptP(double u, double v) const;
    /// Whether the whole rectangle [u0,u1] x [v0,v1] is trimmed away: no loop segment comes
    /// near it and its centre is not kept.
    bool RemovedP(double u0, double u1, double v0, double v1) const;
};

/// Adds to *loop the polyline of one rational trim curve (knots `k`; homogeneous control points
/// u, v, w, each w > 0) over [k.min, k.max]: per span 16 * order points, each segment halved
/// while its midpoint is farther than `tolerance` from its chord (at most 12 times).
void FlattenTrimCurve(const KnotVector& k, const std::vector<glm::dvec3>& uvw, double tolerance,
                      std::vector<glm::dvec2>* loop);

}  // namespace affray::renderer
