// scene/geometry/surface.h: base surfaces and the shader globals they supply, for every number type.
// A new base surface kind gets its frame template in its own header (quadric.h, bicubic.h), an
// alternative of BaseSurface::Shape (with its Kind and accessor) and a case in SetSurfaceGlobals;
// the scene (scene.h) holds BaseSurfaces as they are.
// A base surface is evaluated over a (u,v) *region* with the same templated code whatever the
// number type: doubles at a point, intervals or affine forms over a region (a bound), duals for
// exact derivatives. So the displaced point P' = shader(base(u,v)) is bounded by one machinery.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <memory>
#include <variant>
#include <vector>

#include <glm/glm.hpp>

#include "scene/geometry/bicubic.h"
#include "scene/geometry/mesh.h"
#include "scene/geometry/nurbs.h"
#include "scene/geometry/pole.h"
#include "scene/geometry/quadric.h"
#include "scene/geometry/subdivision.h"
#include "vm/interpreter.h"
#include "vm/numbers/number.h"
#include "vm/numbers/vec3.h"

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
/// derivative `rate` along its own axis for Dual<T> (1: the parameter itself; a patch of a mesh
/// gives its own parameter the rate ds/du of the mesh's, PatchParameters).
template <class T>
struct SurfaceParameterOf;

template <>
struct SurfaceParameterOf<double> {
    static double Make(double lo, double, int, double = 1) { return lo; }
};

template <>
struct SurfaceParameterOf<Interval> {
    static Interval Make(double lo, double hi, int, double = 1) { return Interval(lo, hi); }
};

/// The centre c and radius r with which a region's parameter [lo, hi] becomes c + r * eps: both
/// rounded, the radius widened until [c - r, c + r] covers [lo, hi]. Every affine type and the
/// intersector (which maps eps back to u and v) share it.
inline void RegionParameter(double lo, double hi, double* c, double* r) {
    *c = 0.5 * lo + 0.5 * hi;
    *r = std::max(hi - *c, *c - lo);
    while (*c - *r > lo || *c + *r < hi) *r = std::nextafter(*r, INFINITY);
}

template <>
struct SurfaceParameterOf<Affine> {
    static Affine Make(double lo, double hi, int axis, double = 1) {
        double c, r;
        RegionParameter(lo, hi, &c, &r);
        return Affine::FromSymbol(c, r, axis == 0 ? Affine::kSymbolU : Affine::kSymbolV);
    }
};

template <>
struct SurfaceParameterOf<vm::ReducedAffine> {
    static vm::ReducedAffine Make(double lo, double hi, int axis, double = 1) {
        double c, r;
        RegionParameter(lo, hi, &c, &r);
        using vm::ReducedAffine;
        return ReducedAffine::FromSymbol(c, r, axis == 0 ? ReducedAffine::kSymbolU : ReducedAffine::kSymbolV);
    }
};

template <class T>
struct SurfaceParameterOf<Dual<T>> {
    static Dual<T> Make(double lo, double hi, int axis, double rate = 1) {
        return Dual<T>(SurfaceParameterOf<T>::Make(lo, hi, axis), T(axis == 0 ? rate : 0.0), T(axis == 1 ? rate : 0.0));
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

/// ds/du and dt/dv of a patch that covers `range` of its mesh, as PatchParameters seeds them (the
/// one definition: ConstantGlobals, renderer/prepare.cpp, scales the tangents by it too).
inline double PatchRate(const ParameterRange& range, int axis) {
    if (range.unitP()) return 1.0;
    return axis == 0 ? 1.0 / (range.u1 - range.u0) : 1.0 / (range.v1 - range.v0);
}

/// The parameters of the region [s0,s1] x [t0,t1] of a patch that covers `range` of its mesh:
/// the patch's own s, t (what the patch is evaluated at, on the symbols eps_u, eps_v exactly as
/// RegionParameter maps the region, which the intersector relies on) and the mesh's u, v (what
/// the shader reads; Dual derivatives are along them), with ds/du and dt/dv to carry the
/// patch's tangents to the mesh's parameters. For a lone patch u is s and v is t.
template <class T>
struct PatchParameters {
    double dsdu, dtdv;
    T s, t, u, v;

    PatchParameters(const ParameterRange& range, double s0, double s1, double t0, double t1)
        : dsdu(PatchRate(range, 0)),
          dtdv(PatchRate(range, 1)),
          s(SurfaceParameterOf<T>::Make(s0, s1, 0, dsdu)),
          t(SurfaceParameterOf<T>::Make(t0, t1, 1, dtdv)),
          u(s),
          v(t) {
        if (range.unitP()) return;
        // u = u0 + s (u1 - u0): affine in s, so an affine u keeps s's symbol (with the rounding
        // in its error term) and a dual u has derivative (u1 - u0) ds/du = 1 (up to rounding).
        u = s * (range.u1 - range.u0) + range.u0;
        v = t * (range.v1 - range.v0) + range.v0;
    }
};

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

/// Whether `program` reads the normal (N or Ng), which is then worth computing.
inline bool ReadsNormal(const vm::Program& program) {
    return program.readsGlobal(vm::Global::N) || program.readsGlobal(vm::Global::Ng);
}

/// Writes the globals of one surface evaluation that `interp`'s program reads: the parameters
/// u, v (also s, t), the frame P, dPdu, dPdv, the normal and E, I from `eye`. The normal is
/// `flatNormal` if the surface has one normal everywhere (a constant keeps its bound exact), else
/// the frame's normal direction, else dPdu ^ dPdv, normalised; negated if `flipNormal`
/// (RenderMan's Orientation and ReverseOrientation, scene.h).
template <class T>
void SetFrameGlobals(vm::Interpreter<T>& interp, const T& u, const T& v, const SurfaceFrame<T>& frame,
                     const glm::dvec3* flatNormal, const glm::dvec3& eye, bool flipNormal = false) {
    using vm::Global;
    const vm::Program& program = interp.program();
    interp.SetGlobal(Global::P, frame.P);
    interp.SetGlobal(Global::u, u);
    interp.SetGlobal(Global::v, v);
    interp.SetGlobal(Global::s, u);
    interp.SetGlobal(Global::t, v);
    interp.SetGlobal(Global::du, T(kParametricStep));
    interp.SetGlobal(Global::dv, T(kParametricStep));
    // The default shutter's (0 0); a render binds its scene's as constants (ConstantGlobals).
    interp.SetGlobal(Global::time, T(0.0));
    interp.SetGlobal(Global::dtime, T(0.0));
    interp.SetGlobal(Global::dPdu, frame.dPdu);
    interp.SetGlobal(Global::dPdv, frame.dPdv);
    if (ReadsNormal(program)) {
        Vec3<T> N;
        if (flatNormal)
            N = Constant<T>(flipNormal ? -*flatNormal : *flatNormal);
        else {
            N = vm::Normalize(frame.hasNormalDirection ? frame.normalDirection : vm::Cross(frame.dPdu, frame.dPdv));
            if (flipNormal) N = Vec3<T>{-N.x, -N.y, -N.z};
        }
        interp.SetGlobal(Global::N, N);
        interp.SetGlobal(Global::Ng, N);
    }
    if (program.readsGlobal(Global::E)) interp.SetGlobal(Global::E, Constant<T>(eye));
    if (program.readsGlobal(Global::I)) interp.SetGlobal(Global::I, frame.P - Constant<T>(eye));
}

/// Starts a new evaluation for the interpreter `interp` over the patch region [u0,u1] x [v0,v1]
/// (a point when the bounds are equal) of a patch that covers `range` of its mesh: writes the
/// globals its program reads; `eye` is the camera position E. For affine types this restarts the
/// fresh symbols, so the values of an earlier evaluation must not be combined with this one's.
template <class T>
void SetPatchGlobals(vm::Interpreter<T>& interp, const BilinearPatch& patch, double u0, double u1, double v0, double v1,
                     const glm::dvec3& eye, bool flipNormal = false, const ParameterRange& range = {}) {
    if constexpr (std::is_same_v<T, Affine> || std::is_same_v<T, Dual<Affine>>) Affine::BeginEvaluation();
    const PatchParameters<T> param(range, u0, u1, v0, v1);
    const T& s = param.s;
    const T& t = param.t;
    // P = c0 + a*s + b*t + d*s*t, each coordinate a combination with double coefficients (zero
    // terms skipped: for an axis-aligned patch most are, and every skipped product is work saved
    // in every region bound). The tangents along the mesh's u, v are those along s, t times
    // ds/du, dt/dv (1 for a lone patch).
    const glm::dvec3 c0 = patch.corners[0], a = patch.a() * param.dsdu, b = patch.b() * param.dtdv,
                     d = patch.d() * param.dsdu, e = patch.d() * param.dtdv;
    const bool twisted = !patch.flat();
    T st = twisted ? s * t : T(0.0);
    auto combine = [](double k0, double ku, const T& x, double kv, const T& y) {
        T r(k0);
        if (ku != 0) r = r + x * ku;
        if (kv != 0) r = r + y * kv;
        return r;
    };
    SurfaceFrame<T> frame;
    for (int i = 0; i < 3; ++i) {
        frame.P[i] = combine(c0[i], patch.a()[i], s, patch.b()[i], t);
        if (twisted && patch.d()[i] != 0) frame.P[i] = frame.P[i] + st * patch.d()[i];
        frame.dPdu[i] = twisted ? combine(a[i], d[i], t, 0.0, t) : T(a[i]);
        frame.dPdv[i] = twisted ? combine(b[i], e[i], s, 0.0, s) : T(b[i]);
    }
    // A flat patch has one normal: computed in doubles, so its bound stays exact.
    const glm::dvec3 flatNormal = patch.flatNormal();
    SetFrameGlobals(interp, param.u, param.v, frame, twisted ? nullptr : &flatNormal, eye, flipNormal);
}

/// Sets s and t from a primitive's own "st", computed by st(&s, &t) only if the program reads
/// either (they replace the u, v that SetFrameGlobals gave them).
template <class T, class ST>
void SetSTGlobals(vm::Interpreter<T>& interp, ST&& st) {
    const vm::Program& program = interp.program();
    if (!program.readsGlobal(vm::Global::s) && !program.readsGlobal(vm::Global::t)) return;
    T s, t;
    st(&s, &t);
    interp.SetGlobal(vm::Global::s, s);
    interp.SetGlobal(vm::Global::t, t);
}

/// SetPatchGlobals for a bicubic patch, or a rational patch (or a NuPatch span), that covers
/// `range` of its mesh or surface's (u,v): its frame from BicubicFrame or RationalFrame; a rational
/// patch's s and t are its "st" if it has one, else u and v.
template <class T, class Patch>
requires std::is_same_v<Patch, BicubicPatch> || std::is_same_v<Patch, RationalPatch>
void SetCurvedPatchGlobals(vm::Interpreter<T>& interp, const Patch& patch, double u0, double u1, double v0, double v1,
                           const glm::dvec3& eye, bool flipNormal = false, const ParameterRange& range = {}) {
    constexpr bool kRational = std::is_same_v<Patch, RationalPatch>;
    if constexpr (std::is_same_v<T, Affine> || std::is_same_v<T, Dual<Affine>>) Affine::BeginEvaluation();
    const PatchParameters<T> param(range, u0, u1, v0, v1);
    SurfaceFrame<T> frame = [&] {
        if constexpr (kRational)
            return RationalFrame(patch, param.s, param.t);
        else
            return BicubicFrame(patch, param.s, param.t);
    }();
    if (patch.poles && ReadsNormal(interp.program())) PoleNormalDirection(patch, param.s, param.t, &frame);
    if (param.dsdu != 1) frame.dPdu = frame.dPdu * param.dsdu;
    if (param.dtdv != 1) frame.dPdv = frame.dPdv * param.dtdv;
    SetFrameGlobals(interp, param.u, param.v, frame, nullptr, eye, flipNormal);
    if constexpr (kRational)
        if (patch.hasST) SetSTGlobals(interp, [&](T* s, T* t) { RationalST(patch, param.s, param.t, s, t); });
}

/// A quadric placed in the world by an affine object-to-world matrix (GLM's column-major).
struct PlacedQuadric {
    Quadric quadric;
    glm::dmat4 objectToWorld{1.0};
};

/// The matrix that carries a normal direction n of object space to world space so that it stays
/// a positive multiple of the world dPdu ^ dPdv: (Ma) ^ (Mb) = cof(M) (a ^ b), with the cofactor
/// matrix cof(M) = det(M) M^-T of the linear part (no division: exact for any invertible M).
inline glm::dmat3 NormalToWorld(const glm::dmat4& objectToWorld) {
    const glm::dmat3 m(objectToWorld);
    glm::dmat3 cof;
    for (int c = 0; c < 3; ++c)
        for (int r = 0; r < 3; ++r) {
            // Cofactor (r, c): the 2x2 minor without row r and column c, with its sign folded
            // into the cyclic order of the remaining indices.
            const int r1 = (r + 1) % 3, r2 = (r + 2) % 3, c1 = (c + 1) % 3, c2 = (c + 2) % 3;
            cof[c][r] = m[c1][r1] * m[c2][r2] - m[c2][r1] * m[c1][r2];
        }
    return cof;
}

/// SetPatchGlobals for a region of a quadric: its frame in object space, carried to the world.
template <class T>
void SetQuadricGlobals(vm::Interpreter<T>& interp, const PlacedQuadric& placed, double u0, double u1, double v0,
                       double v1, const glm::dvec3& eye, bool flipNormal = false) {
    if constexpr (std::is_same_v<T, Affine> || std::is_same_v<T, Dual<Affine>>) Affine::BeginEvaluation();
    const T u = SurfaceParameter<T>(u0, u1, 0);
    const T v = SurfaceParameter<T>(v0, v1, 1);
    const SurfaceFrame<T> local = QuadricFrame(placed.quadric, u, v);
    const glm::dmat4& m = placed.objectToWorld;
    // x -> M x, with w = 1 for the point and 0 for the tangents; zero entries skipped.
    auto map = [&](const Vec3<T>& x, bool point) {
        Vec3<T> out;
        for (int row = 0; row < 3; ++row) {
            T sum(point ? m[3][row] : 0.0);
            for (int column = 0; column < 3; ++column)
                if (m[column][row] != 0) sum = sum + x[column] * m[column][row];
            out[row] = sum;
        }
        return out;
    };
    SurfaceFrame<T> world{map(local.P, true), map(local.dPdu, false), map(local.dPdv, false), {}, false};
    if (local.hasNormalDirection && ReadsNormal(interp.program())) {
        const glm::dmat3 cof = NormalToWorld(m);
        for (int row = 0; row < 3; ++row) {
            T sum(0.0);
            for (int column = 0; column < 3; ++column)
                if (cof[column][row] != 0) sum = sum + local.normalDirection[column] * cof[column][row];
            world.normalDirection[row] = sum;
        }
        world.hasNormalDirection = true;
    }
    SetFrameGlobals(interp, u, v, world, nullptr, eye, flipNormal);
}

/// SetPatchGlobals for a region of a polygon mesh's piece (scene/geometry/mesh.h). N is the
/// normalised interpolated vertex normal if the mesh has "N" (never flipped by the orientation:
/// the user's normals say where the outside is), else the face normal; Ng is the face normal.
template <class T>
void SetMeshPieceGlobals(vm::Interpreter<T>& interp, const MeshPiece& piece, double u0, double u1, double v0, double v1,
                         const glm::dvec3& eye, bool flipNormal = false) {
    if constexpr (std::is_same_v<T, Affine> || std::is_same_v<T, Dual<Affine>>) Affine::BeginEvaluation();
    const T u = SurfaceParameter<T>(u0, u1, 0);
    const T v = SurfaceParameter<T>(v0, v1, 1);
    const SurfaceFrame<T> frame = MeshPieceFrame(piece, u, v);
    SetFrameGlobals(interp, u, v, frame, piece.hasNormals ? nullptr : &piece.faceNormal, eye,
                    !piece.hasNormals && flipNormal);
    if (piece.hasST) SetSTGlobals(interp, [&](T* s, T* t) { MeshPieceST(piece, u, v, s, t); });
    if (piece.hasNormals && interp.program().readsGlobal(vm::Global::Ng))
        interp.SetGlobal(vm::Global::Ng, Constant<T>(flipNormal ? -piece.faceNormal : piece.faceNormal));
}

/// SetPatchGlobals for a region of a subdivision mesh's patch (scene/geometry/subdivision.h):
/// N is the geometric normal of a regular patch, the shared normal field of an approximated one,
/// both flipped by the orientation; s, t are the mesh's "st" if it has one, else u, v.
template <class T>
void SetSubdivGlobals(vm::Interpreter<T>& interp, const SubdivPatch& patch, double u0, double u1, double v0, double v1,
                      const glm::dvec3& eye, bool flipNormal = false) {
    if constexpr (std::is_same_v<T, Affine> || std::is_same_v<T, Dual<Affine>>) Affine::BeginEvaluation();
    const T u = SurfaceParameter<T>(u0, u1, 0);
    const T v = SurfaceParameter<T>(v0, v1, 1);
    SetFrameGlobals(interp, u, v, SubdivPatchFrame(patch, u, v), nullptr, eye, flipNormal);
    if (patch.hasST) SetSTGlobals(interp, [&](T* s, T* t) { SubdivPatchST(patch, u, v, s, t); });
}

/// One piece of a shared polygon mesh: the mesh and the piece's index in it.
struct MeshPieceRef {
    std::shared_ptr<const PieceMesh> mesh;
    uint32_t index = 0;
};

/// One patch of a shared subdivision mesh's patches: the patches and the patch's index.
struct SubdivPatchRef {
    std::shared_ptr<const SubdivPatches> patches;
    uint32_t index = 0;
};

/// A base surface for the intersector and the shading: a bilinear or bicubic patch (with the part
/// of its mesh's (u,v) it covers), a placed quadric, a polygon mesh's piece or a subdivision
/// mesh's patch, with the orientation of its normal. One sum type with one dispatch
/// (SetSurfaceGlobals); the shape itself is shared and immutable, so copying a BaseSurface
/// copies a handle (a mesh's piece or a subdivision patch is its mesh and an index, not a copy).
class BaseSurface {
  public:
    /// In the order of the alternatives of Shape.
    enum class Kind { BilinearPatch, Quadric, BicubicPatch, MeshPiece, RationalPatch, SubdivPatch };
    using Shape = std::variant<std::shared_ptr<const BilinearPatch>, std::shared_ptr<const PlacedQuadric>,
                               std::shared_ptr<const BicubicPatch>, MeshPieceRef, std::shared_ptr<const RationalPatch>,
                               SubdivPatchRef>;

    /// NuPatch spans only: the trim curves (in the range's (u,v)) whose trimmed side the
    /// intersector never reports a hit on; null if untrimmed.
    std::shared_ptr<const TrimCurves> trim;
    ParameterRange range{};  ///< Patches only; a quadric's or mesh piece's (u,v) is always [0,1]^2.
    bool flipNormal = false;
    /// RenderMan's TextureCoordinates (s1 t1 s2 t2 s3 t3 s4 t4 at (u,v) = (0,0), (1,0), (0,1),
    /// (1,1)): s and t bilinear in u, v instead of u, v themselves, for quadrics and patches
    /// without an "st" of their own (meshes and subdivision surfaces keep theirs). Null: none.
    std::shared_ptr<const std::array<double, 8>> textureCoordinates;

    /// The unit square's bilinear patch (BilinearPatch::UnitSquare), one shared by every default.
    BaseSurface() : m_shape(UnitSquareShape()) {}
    // Implicit on purpose: a patch is a base surface (as in every caller of the intersector).
    BaseSurface(const BilinearPatch& p, bool flip = false, const ParameterRange& r = {})
        : range(r), flipNormal(flip), m_shape(std::make_shared<const BilinearPatch>(p)) {}
    BaseSurface(const PlacedQuadric& q, bool flip = false)
        : flipNormal(flip), m_shape(std::make_shared<const PlacedQuadric>(q)) {}
    BaseSurface(const BicubicPatch& p, bool flip = false, const ParameterRange& r = {})
        : range(r), flipNormal(flip), m_shape(std::make_shared<const BicubicPatch>(p)) {}
    /// A lone piece (tests): a mesh of its own.
    BaseSurface(const MeshPiece& m, bool flip = false);
    BaseSurface(MeshPieceRef m, bool flip = false) : flipNormal(flip), m_shape(std::move(m)) {}
    BaseSurface(const RationalPatch& p, bool flip = false, const ParameterRange& r = {},
                std::shared_ptr<const TrimCurves> t = nullptr)
        : trim(std::move(t)), range(r), flipNormal(flip), m_shape(std::make_shared<const RationalPatch>(p)) {}
    BaseSurface(const SubdivPatch& p, bool flip = false)
        : flipNormal(flip),
          m_shape(SubdivPatchRef{std::make_shared<const SubdivPatches>(SubdivPatches{{p}, {}, {}}), 0}) {}
    BaseSurface(SubdivPatchRef p, bool flip = false) : flipNormal(flip), m_shape(std::move(p)) {}

    Kind kind() const { return static_cast<Kind>(m_shape.index()); }
    /// The shape, for its kind only.
    const BilinearPatch& patch() const { return *std::get<0>(m_shape); }
    const PlacedQuadric& quadric() const { return *std::get<1>(m_shape); }
    const BicubicPatch& bicubic() const { return *std::get<2>(m_shape); }
    /// A mesh piece's corner values, gathered from its mesh (PieceMesh::Piece).
    MeshPiece piece() const {
        const MeshPieceRef& r = std::get<3>(m_shape);
        return r.mesh->Piece(r.index);
    }
    const MeshPieceRef& pieceRef() const { return std::get<3>(m_shape); }
    const RationalPatch& rational() const { return *std::get<4>(m_shape); }
    const SubdivPatch& subdiv() const {
        const SubdivPatchRef& r = std::get<5>(m_shape);
        return r.patches->patches[r.index];
    }
    const SubdivPatchRef& subdivRef() const { return std::get<5>(m_shape); }

    /// Element `i` of a mesh's pieces or patches counted from this one (the next piece or patch
    /// of the same mesh for i = 1); any other shape is its only element (i = 0).
    BaseSurface Element(uint32_t i) const {
        BaseSurface e(*this);
        if (auto* piece = std::get_if<MeshPieceRef>(&e.m_shape))
            piece->index += i;
        else if (auto* patch = std::get_if<SubdivPatchRef>(&e.m_shape))
            patch->index += i;
        return e;
    }

    /// Whether s and t come from textureCoordinates.
    bool TextureCoordinatesP() const {
        const Kind k = kind();
        return textureCoordinates && (k == Kind::BilinearPatch || k == Kind::BicubicPatch || k == Kind::Quadric ||
                                      (k == Kind::RationalPatch && !rational().hasST));
    }
    /// The rate with which Dual derivatives run along the surface's own parameter `axis` (what
    /// the intersector splits): a patch's derivatives are along its mesh's (u,v) (PatchRate),
    /// every other surface's along its own. A derivative along the region's parameter is the
    /// Dual's divided by it.
    double DualRate(int axis) const {
        const Kind k = kind();
        const bool patchOfMesh = k == Kind::BilinearPatch || k == Kind::BicubicPatch || k == Kind::RationalPatch;
        return patchOfMesh ? PatchRate(range, axis) : 1.0;
    }
    /// Whether the surface is kept at the point (s, t) of its own [0,1]^2 (false where trimmed).
    bool KeptP(double s, double t) const { return !trim || trim->KeptP(range.U(s), range.V(t)); }

  private:
    static const std::shared_ptr<const BilinearPatch>& UnitSquareShape() {
        static const std::shared_ptr<const BilinearPatch> square =
            std::make_shared<const BilinearPatch>(BilinearPatch::UnitSquare());
        return square;
    }
    Shape m_shape;
};

inline BaseSurface::BaseSurface(const MeshPiece& m, bool flip) : flipNormal(flip) {
    // A mesh of the piece alone: its corners as four points, four face corners, one face.
    auto mesh = std::make_shared<PieceMesh>();
    PolygonMesh& p = mesh->mesh;
    p.points.assign(m.P.begin(), m.P.end());
    p.corners = {0, 1, 2, 3};
    if (m.hasNormals) {
        MeshVariable n{StorageClass::Vertex, 3, {}};
        for (const glm::dvec3& v : m.N) n.values.insert(n.values.end(), {v.x, v.y, v.z});
        p.normals = std::move(n);
    }
    if (m.hasST) {
        MeshVariable st{StorageClass::Vertex, 2, {}};
        for (const glm::dvec2& v : m.st) st.values.insert(st.values.end(), {v.x, v.y});
        p.st = std::move(st);
    }
    // Its face normal as given (a test's may not be its corners' Newell normal).
    mesh->faceNormals = {m.faceNormal};
    mesh->pieces.push_back({{0, 1, 2, m.triangle ? 2 : 3}, m.face, 0});
    m_shape = MeshPieceRef{std::move(mesh), 0};
}

/// SetPatchGlobals, SetCurvedPatchGlobals (bicubic and rational patches), SetQuadricGlobals,
/// SetMeshPieceGlobals or SetSubdivGlobals, as `surface` is.
template <class T>
void SetSurfaceGlobals(vm::Interpreter<T>& interp, const BaseSurface& surface, double u0, double u1, double v0,
                       double v1, const glm::dvec3& eye) {
    switch (surface.kind()) {
        case BaseSurface::Kind::BilinearPatch:
            SetPatchGlobals(interp, surface.patch(), u0, u1, v0, v1, eye, surface.flipNormal, surface.range);
            break;
        case BaseSurface::Kind::BicubicPatch:
            SetCurvedPatchGlobals(interp, surface.bicubic(), u0, u1, v0, v1, eye, surface.flipNormal, surface.range);
            break;
        case BaseSurface::Kind::Quadric:
            SetQuadricGlobals(interp, surface.quadric(), u0, u1, v0, v1, eye, surface.flipNormal);
            break;
        case BaseSurface::Kind::MeshPiece:
            SetMeshPieceGlobals(interp, surface.piece(), u0, u1, v0, v1, eye, surface.flipNormal);
            break;
        case BaseSurface::Kind::RationalPatch:
            SetCurvedPatchGlobals(interp, surface.rational(), u0, u1, v0, v1, eye, surface.flipNormal, surface.range);
            break;
        case BaseSurface::Kind::SubdivPatch:
            SetSubdivGlobals(interp, surface.subdiv(), u0, u1, v0, v1, eye, surface.flipNormal);
            break;
    }
    if (surface.TextureCoordinatesP())
        SetSTGlobals(interp, [&](T* s, T* t) {
            // u, v as the surface's setter made them (a quadric's range is the unit square).
            const PatchParameters<T> param(surface.range, u0, u1, v0, v1);
            const std::array<double, 8>& c = *surface.textureCoordinates;
            auto bilinear = [&](int i) {
                const double k0 = c[i], ku = c[2 + i] - c[i], kv = c[4 + i] - c[i],
                             kuv = c[i] - c[2 + i] - c[4 + i] + c[6 + i];
                T x(k0);
                if (ku != 0) x = x + param.u * ku;
                if (kv != 0) x = x + param.v * kv;
                if (kuv != 0) x = x + param.u * param.v * kuv;
                return x;
            };
            *s = bilinear(0);
            *t = bilinear(1);
        });
}

/// The side of `surface` that dPdu x dPdv points to at (u, v): +1 where it is the side of the
/// geometric normal Ng (N's side, the orientation applied), -1 where it is the other. Ng is
/// dPdu x dPdv (or the frame's normal direction, which points the same way) flipped by the
/// orientation, except on a mesh piece, whose Ng is its face's normal (the winding's) flipped.
/// So Ng of the displaced surface is this sign times dP'/du x dP'/dv.
inline double ParametricSide(const BaseSurface& surface, double u, double v) {
    double side = surface.flipNormal ? -1.0 : 1.0;
    if (surface.kind() == BaseSurface::Kind::MeshPiece) {
        const MeshPiece piece = surface.piece();
        const SurfaceFrame<double> frame = MeshPieceFrame(piece, u, v);
        const glm::dvec3 cross = glm::cross(glm::dvec3(frame.dPdu.x, frame.dPdu.y, frame.dPdu.z),
                                            glm::dvec3(frame.dPdv.x, frame.dPdv.y, frame.dPdv.z));
        if (glm::dot(cross, piece.faceNormal) < 0) side = -side;
    }
    return side;
}

/// Runs `interp`'s program over the region [u0,u1] x [v0,v1] of `surface` and returns its triple
/// output `output`.
template <class T>
Vec3<T> EvaluateOnSurface(vm::Interpreter<T>& interp, const BaseSurface& surface, double u0, double u1, double v0,
                          double v1, const glm::dvec3& eye, const vm::ProgramOutput& output) {
    SetSurfaceGlobals(interp, surface, u0, u1, v0, v1, eye);
    interp.Run();
    return interp.OutputTriple(output);
}

/// EvaluateOnSurface for a patch (tests, benches and `affray eval`).
template <class T>
Vec3<T> EvaluateOnPatch(vm::Interpreter<T>& interp, const BilinearPatch& patch, double u0, double u1, double v0,
                        double v1, const glm::dvec3& eye, const vm::ProgramOutput& output) {
    return EvaluateOnSurface(interp, BaseSurface(patch), u0, u1, v0, v1, eye, output);
}

// The surface setters for the VM's eight number types are compiled once, in surface.cpp, not in
// every file that sets or evaluates a surface (the renderer, the CLI and some thirty test files):
// the frames of six surface kinds in eight types were up to 60 % of such a file's compile time.
// Another type (a test's) still instantiates them from the templates above.
#define AFFRAY_SURFACE_INSTANCES(EXTERN, T)                                                                            \
    EXTERN template void SetSurfaceGlobals<T>(vm::Interpreter<T>&, const BaseSurface&, double, double, double, double, \
                                              const glm::dvec3&);                                                      \
    EXTERN template Vec3<T> EvaluateOnSurface<T>(vm::Interpreter<T>&, const BaseSurface&, double, double, double,      \
                                                 double, const glm::dvec3&, const vm::ProgramOutput&);                 \
    EXTERN template Vec3<T> EvaluateOnPatch<T>(vm::Interpreter<T>&, const BilinearPatch&, double, double, double,      \
                                               double, const glm::dvec3&, const vm::ProgramOutput&);
// (clang-format's layout of this list is not stable from one run to the next.)
// clang-format off
#define AFFRAY_SURFACE_NUMBER_TYPES(X, EXTERN) \
    X(EXTERN, double) X(EXTERN, vm::Interval) X(EXTERN, vm::Affine) X(EXTERN, vm::ReducedAffine) \
    X(EXTERN, vm::Dual<double>) X(EXTERN, vm::Dual<vm::Interval>) X(EXTERN, vm::Dual<vm::Affine>) \
    X(EXTERN, vm::Dual<vm::ReducedAffine>)
// clang-format on
AFFRAY_SURFACE_NUMBER_TYPES(AFFRAY_SURFACE_INSTANCES, extern)

}  // namespace affray::renderer
