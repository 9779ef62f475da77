// scene/geometry/bicubic.h: RenderMan's bicubic patches as base surfaces over (u,v), for every number type.
// Owns the cubic bases of RI Spec 3.2 section 5.2 (RiBasis: bezier, b-spline, catmull-rom, hermite,
// power, or any 4x4 matrix) and the bicubic patch P(u,v) = U Mu G Mv^T V^T with U = [u^3 u^2 u 1].
// A patch is converted once, in doubles, to the power basis in world space; one template then
// evaluates P, dPdu and dPdv by Horner's rule in u and v at a double, bounds a region with
// Interval or Affine and gives exact derivatives with Dual<T>, so a bicubic patch is bounded by
// the same machinery as a displaced bilinear patch or quadric. Zero coefficients are skipped: a
// bicubic patch that is really bilinear costs about what a bilinear patch does.
#pragma once

#include <array>
#include <memory>
#include <optional>
#include <string>
#include <type_traits>

#include <glm/glm.hpp>

#include "scene/geometry/quadric.h"
#include "vm/numbers/reduced_affine.h"
#include "vm/numbers/vec3.h"

namespace affray::renderer {

/// The part [u0,u1] x [v0,v1] of a patch mesh's (u,v) that one of its patches covers (RI 3.2: u
/// and v run from 0 to 1 across the whole mesh); [0,1]^2 for a lone patch. The intersector walks
/// each patch's own [0,1]^2; the shader sees the mesh's (u,v), and its derivatives are along them.
struct ParameterRange {
    double u0 = 0, u1 = 1, v0 = 0, v1 = 1;
    bool unitP() const { return u0 == 0 && u1 == 1 && v0 == 0 && v1 == 1; }
    /// The mesh's (u,v) at the patch's own (s,t).
    double U(double s) const { return u0 + s * (u1 - u0); }
    double V(double t) const { return v0 + t * (v1 - v0); }
};

/// A cubic basis (RiBasis): the matrix M with which four control values g give the cubic
/// U M g (U = [u^3 u^2 u 1]), and the number of control points between a patch mesh's patches.
struct CubicBasis {
    std::array<double, 16> m{};  ///< Row-major, as RIB writes it: m[4 * row + column].
    int step = 3;
    std::string name;  ///< The predefined basis's RIB name, or "" for a matrix given by numbers.

    /// The predefined basis `name` ("bezier", "b-spline", "catmull-rom", "hermite", "power") with
    /// its RI step, or nothing if there is none of that name.
    static std::optional<CubicBasis> Named(const std::string& name);
    /// The RI default, "bezier" with step 3.
    static CubicBasis Bezier() { return *Named("bezier"); }
    /// The predefined names, for messages: "\"bezier\", \"b-spline\", ...".
    static const char* NameList();
};

/// "bezier 3", or the 16 numbers and the step.
std::string ToString(const CubicBasis& b);

struct PatchPoles;  // scene/geometry/pole.h

/// A bicubic patch in the power basis: P(u,v) = sum over i, j of c[4 i + j] u^i v^j, u and v in
/// [0, 1], in world space.
struct BicubicPatch {
    std::array<glm::dvec3, 16> c{};
    /// Edges collapsed to a point and the factor that gives the normal there (pole.h), or null.
    std::shared_ptr<const PatchPoles> poles;

    /// The patch of the 16 control points `points` (u varies fastest, RI order) with the bases
    /// `uBasis` and `vBasis`, placed by `objectToWorld` (affine). The transform is applied to the
    /// power-basis coefficients (the translation to the constant term only), which is right for
    /// every basis, also those whose control values are not all points (hermite, power).
    /// Coefficients within rounding noise of zero (relative to the patch's size) are set to zero
    /// so that they are skipped: a bezier patch that is bilinear then evaluates as one.
    static BicubicPatch FromControlPoints(const std::array<glm::dvec3, 16>& points, const CubicBasis& uBasis,
                                          const CubicBasis& vBasis, const glm::dmat4& objectToWorld);

    /// The point at (u, v), in doubles (for messages and tests).
    glm::dvec3 At(double u, double v) const;
    /// Whether every coefficient is finite.
    bool FiniteP() const;
};

/// The 16 coefficients, u^0 v^0 first.
std::string ToString(const BicubicPatch& p);

namespace bicubic_detail {

/// c[0] + c[1] x + ... + c[n] x^n by Horner's rule, zero coefficients skipped (leading zeros
/// lower the degree); the first product is by a double, which every T does exactly or tightly.
template <class T>
T Horner(const double* c, int n, const T& x) {
    while (n > 0 && c[n] == 0) --n;
    if (n == 0) return T(c[0]);
    T r = x * c[n];
    if (c[n - 1] != 0) r = r + c[n - 1];
    for (int k = n - 2; k >= 0; --k) {
        r = r * x;
        if (c[k] != 0) r = r + c[k];
    }
    return r;
}

/// a[0] + a[1] y + ... + a[n] y^n for T coefficients, with a[k] left out where zero[k] (known
/// to be 0 for every (u, v)); each a[k] is scaled by scale[k] (the factor of a derivative).
template <class T>
T Horner(const T* a, const bool* zero, const double* scale, int n, const T& y) {
    while (n >= 0 && zero[n]) --n;
    if (n < 0) return T(0.0);
    T r = scale[n] == 1 ? a[n] : a[n] * scale[n];
    for (int k = n - 1; k >= 0; --k) {
        r = r * y;
        if (!zero[k]) r = r + (scale[k] == 1 ? a[k] : a[k] * scale[k]);
    }
    return r;
}

/// P(u, v) with its tangents dP/du and dP/dv, written out by hand (Horner in u, then in v) rather
/// than through Dual<T>: a T that is itself a Dual (a shade program) gets the tangents' own
/// derivatives for free. No normal direction: the normal is dPdu x dPdv normalised.
template <class T>
SurfaceFrame<T> HornerFrame(const BicubicPatch& patch, const T& u, const T& v) {
    static constexpr double kOne[4] = {1, 1, 1, 1}, kPower[4] = {0, 1, 2, 3};
    SurfaceFrame<T> f;
    for (int axis = 0; axis < 3; ++axis) {
        // For each power of v, the cubic in u and its u-derivative (a quadratic).
        T a[4] = {T(0.0), T(0.0), T(0.0), T(0.0)}, da[4] = {T(0.0), T(0.0), T(0.0), T(0.0)};
        bool zero[4], dzero[4];
        for (int j = 0; j < 4; ++j) {
            double c[4], dc[3];
            for (int i = 0; i < 4; ++i) c[i] = patch.c[4 * i + j][axis];
            for (int i = 1; i < 4; ++i) dc[i - 1] = i * c[i];
            zero[j] = c[0] == 0 && c[1] == 0 && c[2] == 0 && c[3] == 0;
            dzero[j] = c[1] == 0 && c[2] == 0 && c[3] == 0;
            if (!zero[j]) a[j] = Horner(c, 3, u);
            if (!dzero[j]) da[j] = Horner(dc, 2, u);
        }
        f.P[axis] = Horner(a, zero, kOne, 3, v);
        f.dPdu[axis] = Horner(da, dzero, kOne, 3, v);
        // d/dv of sum a_j v^j = sum j a_j v^(j-1): the coefficients a_1..a_3 scaled by 1..3.
        f.dPdv[axis] = Horner(a + 1, zero + 1, kPower + 1, 2, v);
    }
    return f;
}

/// The frame over a region for reduced affine u and v that are the region's parameters exactly
/// (uc + ru eps_u and vc + rv eps_v, as SurfaceParameter makes them): each of P, dPdu and dPdv is
/// a polynomial in (eps_u, eps_v), whose coefficients in that local power basis are computed in
/// doubles; its constant and linear terms make the form, and its other terms (x^3 as 0.75 x +-
/// 0.25, even powers as 0.5 +- 0.5) its error, with the rounding of the coefficients and that
/// of HornerFrame<double> at any point of the region (which the bound must contain, as every
/// bound contains the scalar evaluation) bounded a priori. About ten times cheaper than
/// HornerFrame<ReducedAffine> and never looser in its first-order terms. False (nothing
/// written) when u or v is not of that shape.
bool RegionFrame(const BicubicPatch& patch, const vm::ReducedAffine& u, const vm::ReducedAffine& v,
                 SurfaceFrame<vm::ReducedAffine>* frame);

}  // namespace bicubic_detail

/// P(u, v) with its tangents dP/du and dP/dv: HornerFrame, or RegionFrame for the region bounds
/// of reduced affine arithmetic (the bound of most displaced bicubic and subdivision patches).
template <class T>
SurfaceFrame<T> BicubicFrame(const BicubicPatch& patch, const T& u, const T& v) {
    if constexpr (std::is_same_v<T, vm::ReducedAffine>) {
        SurfaceFrame<T> frame;
        if (bicubic_detail::RegionFrame(patch, u, v, &frame)) return frame;
    }
    return bicubic_detail::HornerFrame(patch, u, v);
}

}  // namespace affray::renderer
