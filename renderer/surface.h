// renderer/surface.h: base surfaces and the shader globals they supply, for every number type.
// A base surface is evaluated over a (u,v) *region* with the same templated code whatever the
// number type: doubles at a point, intervals or affine forms over a region (a bound), duals for
// exact derivatives. So the displaced point P' = shader(base(u,v)) is bounded by one machinery.
#pragma once

#include <array>
#include <cmath>

#include <glm/glm.hpp>

#include "vm/interpreter.h"
#include "vm/number.h"
#include "vm/vec3.h"

namespace affray::renderer {

using vm::Affine;
using vm::Dual;
using vm::Interval;
using vm::Vec3;

/// RenderMan's du and dv: the parametric distance between shading samples. affray fixes them per
/// surface (they must be the same for bounding and for shading, or the surface bounded would not
/// be the surface shaded).
inline constexpr double kParametricStep = 1.0 / 1024.0;

/// The value of the surface parameter `axis` (0 = u, 1 = v) over [lo, hi] as a T: a point for
/// double (lo == hi), the range for Interval, lo..hi on the symbol of u or v for Affine, and with
/// unit derivative along its own axis for Dual<T>.
template <class T>
struct SurfaceParameterOf;

template <>
struct SurfaceParameterOf<double> {
    static double Make(double lo, double, int) { return lo; }
};

template <>
struct SurfaceParameterOf<Interval> {
    static Interval Make(double lo, double hi, int) { return Interval(lo, hi); }
};

template <>
struct SurfaceParameterOf<Affine> {
    static Affine Make(double lo, double hi, int axis) {
        // The centre and radius are rounded; widen the radius until [c - r, c + r] covers [lo, hi].
        double c = 0.5 * lo + 0.5 * hi;
        double r = std::max(hi - c, c - lo);
        while (c - r > lo || c + r < hi) r = std::nextafter(r, INFINITY);
        return Affine::FromSymbol(c, r, axis == 0 ? Affine::kSymbolU : Affine::kSymbolV);
    }
};

template <class T>
struct SurfaceParameterOf<Dual<T>> {
    static Dual<T> Make(double lo, double hi, int axis) {
        return Dual<T>(SurfaceParameterOf<T>::Make(lo, hi, axis), T(axis == 0 ? 1.0 : 0.0), T(axis == 1 ? 1.0 : 0.0));
    }
};

template <class T>
T SurfaceParameter(double lo, double hi, int axis) {
    return SurfaceParameterOf<T>::Make(lo, hi, axis);
}

template <class T>
Vec3<T> Constant(const glm::dvec3& p) {
    return {T(p.x), T(p.y), T(p.z)};
}

/// RenderMan's bilinear patch: corners in the order (u0,v0), (u1,v0), (u0,v1), (u1,v1).
struct BilinearPatch {
    std::array<glm::dvec3, 4> corners;

    /// The unit square P = (u, v, 0), as `affray eval` uses.
    static BilinearPatch UnitSquare() {
        return {{glm::dvec3(0, 0, 0), glm::dvec3(1, 0, 0), glm::dvec3(0, 1, 0), glm::dvec3(1, 1, 0)}};
    }

    // P(u,v) = c0 + a*u + b*v + d*u*v
    glm::dvec3 a() const { return corners[1] - corners[0]; }
    glm::dvec3 b() const { return corners[2] - corners[0]; }
    glm::dvec3 d() const { return corners[0] - corners[1] - corners[2] + corners[3]; }
    /// A flat patch (d = 0) has the same tangents a, b and normal everywhere.
    bool flat() const { return d() == glm::dvec3(0.0); }
    /// The normal of a flat patch, normalize(a ^ b) (not finite if the patch is degenerate).
    glm::dvec3 flatNormal() const { return glm::normalize(glm::cross(a(), b())); }
};

/// Starts a new evaluation for the interpreter `interp` over the patch region [u0,u1] x [v0,v1]
/// (a point when the bounds are equal): writes the globals its program reads; `eye` is the
/// camera position E. For affine types this restarts the fresh symbols, so the values of an
/// earlier evaluation must not be combined with this one's.
template <class T>
void SetPatchGlobals(vm::Interpreter<T>& interp, const BilinearPatch& patch, double u0, double u1, double v0,
                     double v1, const glm::dvec3& eye) {
    using vm::Global;
    if constexpr (std::is_same_v<T, Affine> || std::is_same_v<T, Dual<Affine>>) Affine::BeginEvaluation();
    const vm::Program& program = interp.program();
    T u = SurfaceParameter<T>(u0, u1, 0);
    T v = SurfaceParameter<T>(v0, v1, 1);
    // P = c0 + a*u + b*v + d*u*v, each coordinate a combination with double coefficients (zero
    // terms skipped: for an axis-aligned patch most are, and every skipped product is work saved
    // in every region bound).
    const glm::dvec3 c0 = patch.corners[0], a = patch.a(), b = patch.b(), d = patch.d();
    const bool twisted = !patch.flat();
    T uv = twisted ? u * v : T(0.0);
    auto combine = [](double k0, double ku, const T& x, double kv, const T& y) {
        T r(k0);
        if (ku != 0) r = r + x * ku;
        if (kv != 0) r = r + y * kv;
        return r;
    };
    Vec3<T> P, dPdu, dPdv;
    for (int i = 0; i < 3; ++i) {
        P[i] = combine(c0[i], a[i], u, b[i], v);
        if (twisted && d[i] != 0) P[i] = P[i] + uv * d[i];
        dPdu[i] = twisted ? combine(a[i], d[i], v, 0.0, v) : T(a[i]);
        dPdv[i] = twisted ? combine(b[i], d[i], u, 0.0, u) : T(b[i]);
    }
    interp.SetGlobal(Global::P, P);
    interp.SetGlobal(Global::u, u);
    interp.SetGlobal(Global::v, v);
    interp.SetGlobal(Global::s, u);
    interp.SetGlobal(Global::t, v);
    interp.SetGlobal(Global::du, T(kParametricStep));
    interp.SetGlobal(Global::dv, T(kParametricStep));
    interp.SetGlobal(Global::dPdu, dPdu);
    interp.SetGlobal(Global::dPdv, dPdv);
    if (program.readsGlobal(Global::N) || program.readsGlobal(Global::Ng)) {
        // A flat patch has one normal: compute it in doubles and pass it as a constant, so its
        // bound stays exact; only a twisted patch needs the normal per region.
        Vec3<T> N = twisted ? vm::Normalize(vm::Cross(dPdu, dPdv))
                            : Constant<T>(patch.flatNormal());
        interp.SetGlobal(Global::N, N);
        interp.SetGlobal(Global::Ng, N);
    }
    if (program.readsGlobal(Global::E)) interp.SetGlobal(Global::E, Constant<T>(eye));
    if (program.readsGlobal(Global::I)) interp.SetGlobal(Global::I, P - Constant<T>(eye));
}

/// Runs `interp`'s program over the patch region [u0,u1] x [v0,v1] (see SetPatchGlobals) and
/// returns its triple output `output`.
template <class T>
Vec3<T> EvaluateOnPatch(vm::Interpreter<T>& interp, const BilinearPatch& patch, double u0, double u1, double v0,
                        double v1, const glm::dvec3& eye, const vm::ProgramOutput& output) {
    SetPatchGlobals(interp, patch, u0, u1, v0, v1, eye);
    interp.Run();
    return interp.OutputTriple(output);
}

}  // namespace affray::renderer
