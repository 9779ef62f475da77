// scene/geometry/pole.h: the normal of a patch at an edge collapsed to a point (a pole).
// The classic teapot's lid knob and bottom, a NURBS sphere's caps and every surface of revolution
// that closes on its axis have an edge whose control points coincide: along it one tangent
// vanishes, so dPdu x dPdv is zero there and its direction, the normal a displacement follows,
// is undefined; over a region touching the edge a bound of normalize(dPdu x dPdv) is unbounded,
// and the intersector can only subdivide to its depth limit. RenderMan renderers take the limit
// of the normal at the pole; affray does the same, exactly and for every number type:
//
// Write the patch as homogeneous polynomials X(s, t) (x, y, z, w; w = 1 for a polynomial patch)
// with P = X.xyz / X.w. If the edge t = e collapses to the point C, then X.xyz - C X.w vanishes
// at t = e for every s, so it has the factor (t - e):
//     X.xyz - L(t) X.w = D(t) Y(s, t),    P = L + D Y / W,
// with L = C and D = t - e for one collapsed edge, or L the line from C0 to C1 and D = t (t - 1)
// when both edges t = 0 and t = 1 collapse (a spindle). Then dP/ds = D d(Y/W)/ds, so
//     dP/ds x dP/dt = D (Q x dP/dt),    Q = d(Y/W)/ds = (dY/ds - (Y/W) dW/ds) / W,
// and sign(D) Q x dP/dt is a positive multiple of dP/ds x dP/dt that does not vanish at the
// pole (its limit there is the tangent of the edge's first-order ring times the radial tangent).
// Edges s = e are the same with s and t exchanged: sign(D) dP/ds x R, R = d(Z/W)/dt.
// An edge counts as collapsed when its points agree to 1e-5 of the patch's size: exporters print
// 6 or 7 significant digits, so a rational patch's collapsed edge (x w, y w, z w, w) is a point
// only to about 1e-6 once divided by w. P is left exactly as given; only the normal's definition
// changes, by the dropped remainder, and only next to the edge, where the tangents' cross product
// is at the scale of the file's rounding and its direction is noise.
// Y is computed once, in doubles, by synthetic division (the remainder is dropped); the normal direction is then a polynomial
// expression in s, t evaluated by the same template for a double, a bound or a dual, so the
// shader sees the same N at a point as its bound contains over a region.
#pragma once

#include <memory>
#include <vector>

#include <glm/glm.hpp>

#include "scene/geometry/bicubic.h"
#include "scene/geometry/nurbs.h"
#include "scene/geometry/quadric.h"
#include "vm/numbers/vec3.h"

namespace affray::renderer {

/// The factor Y of a patch with collapsed edges (see the head comment).
struct PatchPoles {
    int axis = 1;               ///< 1: edges t = 0 and/or t = 1 collapse; 0: edges s = 0 and/or s = 1
    double sign = 1;            ///< the sign of D inside the patch (+1 for t, -1 for t - 1 and t (t - 1))
    int degreeU = 0;            ///< Y's degree in s
    int degreeV = 0;            ///< and in t
    std::vector<glm::dvec3> y;  ///< Y's coefficients, of s^i t^j at (degreeV + 1) i + j
};

/// The poles of a bicubic patch, or null if no edge collapses. An edge collapses when its points
/// agree with its first to 1e-5 of the patch's size (see the head comment).
std::shared_ptr<const PatchPoles> FindPatchPoles(const BicubicPatch& patch);
/// The poles of a rational patch (a NuPatch span), or null.
std::shared_ptr<const PatchPoles> FindPatchPoles(const RationalPatch& patch);

/// Sets frame->normalDirection for a patch with `poles` at (s, t): `w`, `ws` and `wt` are W and
/// its derivatives there (1, 0, 0 for a polynomial patch); frame's tangents are the patch's own.
template <class T>
void PoleNormalDirection(const PatchPoles& poles, const T& s, const T& t, const T& w, const T& ws, const T& wt,
                         bool rational, SurfaceFrame<T>* frame) {
    vm::Vec3<T> y, yd;  // Y, and its derivative along the collapsed edges
    for (int k = 0; k < 3; ++k) {
        T value, ds, dt;
        nurbs_detail::Polynomial(
            poles.degreeU, poles.degreeV, [&](int i, int j) { return poles.y[(poles.degreeV + 1) * i + j][k]; }, s, t,
            &value, poles.axis == 1 ? &ds : nullptr, poles.axis == 0 ? &dt : nullptr);
        y[k] = value;
        yd[k] = poles.axis == 1 ? ds : dt;
    }
    vm::Vec3<T> q = yd;
    if (rational) {
        const T inverse = T(1.0) / w;
        const T& wd = poles.axis == 1 ? ws : wt;
        for (int k = 0; k < 3; ++k) q[k] = (yd[k] - y[k] * inverse * wd) * inverse;
    }
    vm::Vec3<T> n = poles.axis == 1 ? vm::Cross(q, frame->dPdv) : vm::Cross(frame->dPdu, q);
    if (poles.sign < 0) n = vm::Vec3<T>{-n.x, -n.y, -n.z};
    frame->normalDirection = n;
    frame->hasNormalDirection = true;
}

/// Sets frame->normalDirection of a bicubic patch with poles at (s, t) (its own parameters).
template <class T>
void PoleNormalDirection(const BicubicPatch& patch, const T& s, const T& t, SurfaceFrame<T>* frame) {
    PoleNormalDirection(*patch.poles, s, t, T(1.0), T(0.0), T(0.0), false, frame);
}

/// Sets frame->normalDirection of a rational patch (a NuPatch span) with poles at (s, t).
template <class T>
void PoleNormalDirection(const RationalPatch& patch, const T& s, const T& t, SurfaceFrame<T>* frame) {
    T w(1.0), ws(0.0), wt(0.0);
    if (patch.rational)
        nurbs_detail::Polynomial(
            patch.degreeU, patch.degreeV, [&](int i, int j) { return patch.c[patch.Index(i, j)].w; }, s, t, &w, &ws,
            &wt);
    PoleNormalDirection(*patch.poles, s, t, w, ws, wt, patch.rational, frame);
}

}  // namespace affray::renderer
