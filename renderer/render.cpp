// renderer/render.cpp: scene preparation and the tile loop.
// Each thread owns its intersectors and shading interpreters (they hold registers), takes tiles
// from a shared counter, traces the samples the film asks for (renderer/film.h) and resolves
// only its tile's pixels: the image does not depend on the thread count or the tile order, and
// the statistics are sums and maxima, which do not either. Tiles a TileStore holds (a resumed
// render's checkpoint) are copied in instead of rendered, each finished tile is handed to it, and
// the stop flag (a signal) is checked between samples: a tile stopped part way is dropped whole.
#include "renderer/renderer.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <tuple>
#include <unordered_map>
#include <unordered_set>

#include <sys/resource.h>
#include <unistd.h>

#include "renderer/film.h"
#include "renderer/shade.h"
#include "scene/geometry/camera.h"

namespace affray::renderer {

namespace {

/// Everything one thread needs: per primitive an intersector (a walker over the primitive's shared
/// bound hierarchy) and a shading interpreter.
struct ThreadState {
    IntersectStats cameraStats, shadowStats;
    uint64_t cameraRays = 0;
    /// ShadowTransmission's scratch: the partly transparent primitives a shadow ray passes.
    std::vector<std::pair<int, glm::dvec3>> shadowShares;
    /// How deep in trace() calls shading is (0: a camera ray's hit), and the deepest it goes:
    /// past it trace() sees black. Each depth has its own shading state, since a trace() shades
    /// while the shading that called it is halfway through its program.
    static constexpr int kMaxTraceDepth = 3;
    int depth = 0;
    /// Per depth: a light set's lights at a ray's time (ShadeHit), if any moves, and a surface
    /// program's lights at the point it shades.
    std::array<std::vector<LightDesc>, kMaxTraceDepth + 1> movedLights;
    std::array<ShadingLights, kMaxTraceDepth + 1> shadingLights;

    /// The interpreter of number type T running surface program `program` (ShadeHit).
    template <class T>
    vm::Interpreter<T>& Surface(const vm::Program& program) {
        std::unique_ptr<vm::Interpreter<T>>& own =
            std::get<std::unique_ptr<vm::Interpreter<T>>>(m_surfaces[static_cast<size_t>(depth)]);
        if (!own)
            own = std::make_unique<vm::Interpreter<T>>(program);
        else if (&own->program() != &program)
            own->SetProgram(program);
        return *own;
    }

    /// Per primitive, the factor its tolerance is scaled by (ToleranceScales).
    const std::vector<double>& toleranceScale;

    ThreadState(const PreparedScene& scene, const Options& options, BoundForest& trees,
                const std::vector<double>& scales)
        : toleranceScale(scales),
          m_scene(scene),
          m_options(options),
          m_trees(trees),
          m_forestSlot(trees.RegisterThread()),
          m_workspace(MakeIntersectWorkspace()),
          m_slotOf(scene.primitives.size(), -1) {}

    /// The intersector of primitive i, made when a ray of this thread first tests the primitive.
    /// At most kKeptIntersectors are kept, the least recently used (by the clock algorithm) made
    /// again when needed: each holds a walker, an evaluator and a frontier (about 0.8 KB), so that
    /// a thread's state grows with the primitives its rays meet at a time, not with the scene's
    /// (16,384 patches took 13 MB per thread). What an intersector finds does not depend on
    /// what it held before, so neither does the image.
    SurfaceIntersector& Intersector(int i) {
        int slot = m_slotOf[i];
        if (slot >= 0) {
            m_kept[slot].used = true;
            return *m_kept[slot].intersector;
        }
        if (m_kept.size() < kKeptIntersectors) {
            slot = static_cast<int>(m_kept.size());
            m_kept.emplace_back();
        } else {
            while (m_kept[m_hand].used) {
                m_kept[m_hand].used = false;
                m_hand = (m_hand + 1) % m_kept.size();
            }
            slot = static_cast<int>(m_hand);
            m_hand = (m_hand + 1) % m_kept.size();
            m_slotOf[m_kept[slot].primitive] = -1;
            m_kept[slot].intersector.reset();
        }
        Kept& k = m_kept[slot];
        k.primitive = i;
        k.used = true;
        k.intersector = m_options.intersectorFactory
                            ? m_options.intersectorFactory(m_scene.primitives[i], i)
                            : m_trees.With(m_forestSlot, size_t(i), [&](BoundTree& tree) {
                                  return MakeSurfaceIntersector(tree, m_options.regionBudget, m_workspace);
                              });
        m_slotOf[i] = slot;
        return *k.intersector;
    }

    /// Whether `ray` meets primitive i in [tMin, tMax] (its Intersector). A moving primitive's
    /// geometry stands where its path's first time placed it: the ray is carried there from
    /// its own time (the primitive's motion undone) and its hit's distances back. Ray groups
    /// bound rays in world space only, so such a primitive takes each ray alone.
    bool Intersect(int i, const Ray& ray, double tMin, double tMax, const Tolerance& tol, bool anyHit, Hit* hit,
                   IntersectStats& stats, const RayGroup* group = nullptr) {
        const MotionPath* path = m_scene.primitives[i].attributes().motion.get();
        if (!path) return Intersector(i).Intersect(ray, tMin, tMax, tol, anyHit, hit, stats, group);
        const MotionFrame& f = FrameAt(*path, ray.time);
        const glm::dvec3 dir = f.toPlaced * ray.dir;
        const double scale = glm::length(dir);  // placed distance per world distance
        if (!(scale > 0) || !std::isfinite(scale)) return false;
        const Ray placed{glm::dvec3(f.toPlacedPoint * glm::dvec4(ray.origin, 1.0)), dir / scale, ray.time};
        if (!Intersector(i).Intersect(placed, tMin * scale, tMax * scale, tol, anyHit, hit, stats, nullptr))
            return false;
        hit->t /= scale;
        hit->error /= scale;
        return true;
    }

    /// A moving primitive's frames at one time: world at that time -> where its geometry is
    /// placed (its path's first time), and back (points; directions; normals).
    struct MotionFrame {
        const MotionPath* path = nullptr;
        double time = 0;
        glm::dmat4 toPlacedPoint{1.0}, toWorldPoint{1.0};
        glm::dmat3 toPlaced{1.0}, toWorld{1.0}, normalToWorld{1.0};
    };
    /// The frames of `path` at `time`: kept for the last path and time asked (a sample's camera
    /// and shadow rays share a time, a mesh's elements a path).
    const MotionFrame& FrameAt(const MotionPath& path, double time) {
        if (m_frame.path == &path && m_frame.time == time) return m_frame;
        m_frame.path = &path;
        m_frame.time = time;
        // At the placement's own matrix (a shutter closed at the first time) exactly the identity:
        // the image of a still shutter is the still scene's, bit for bit.
        const glm::dmat4 m = path.At(time);
        m_frame.toWorldPoint = m == path.matrices.front() ? glm::dmat4(1.0) : m * glm::inverse(path.matrices.front());
        m_frame.toPlacedPoint = glm::inverse(m_frame.toWorldPoint);
        m_frame.toWorld = glm::dmat3(m_frame.toWorldPoint);
        m_frame.toPlaced = glm::dmat3(m_frame.toPlacedPoint);
        m_frame.normalToWorld = glm::transpose(m_frame.toPlaced);
        return m_frame;
    }

    /// The shading interpreter of primitive i, running its shade program. A program without
    /// parameters (every specialised one) runs on the thread's one interpreter, pointed at it;
    /// one with parameters gets an interpreter of its own, made on first use (one per program,
    /// which the primitives that share it share).
    vm::Interpreter<vm::Dual<double>>& Shader(int i) {
        const vm::Program& program = m_scene.primitives[i].shade();
        if (!program.params.empty()) {
            std::unique_ptr<vm::Interpreter<vm::Dual<double>>>& own = m_ownShaders[&program];
            if (!own) own = std::make_unique<vm::Interpreter<vm::Dual<double>>>(program);
            return *own;
        }
        if (!m_shared)
            m_shared = std::make_unique<vm::Interpreter<vm::Dual<double>>>(program);
        else if (&m_shared->program() != &program)
            m_shared->SetProgram(program);
        return *m_shared;
    }

  private:
    std::array<std::tuple<std::unique_ptr<vm::Interpreter<double>>, std::unique_ptr<vm::Interpreter<vm::Dual<double>>>>,
               kMaxTraceDepth + 1>
        m_surfaces;
    static constexpr size_t kKeptIntersectors = 2048;
    struct Kept {
        std::unique_ptr<SurfaceIntersector> intersector;
        int primitive = -1;
        bool used = false;  // tested since the clock hand last passed
    };

    const PreparedScene& m_scene;
    const Options& m_options;
    BoundForest& m_trees;
    BoundForest::ThreadSlot* m_forestSlot;
    std::shared_ptr<IntersectWorkspace> m_workspace;
    std::vector<int> m_slotOf;  // per primitive, its place in m_kept or -1
    std::vector<Kept> m_kept;
    size_t m_hand = 0;
    std::unique_ptr<vm::Interpreter<vm::Dual<double>>> m_shared;
    MotionFrame m_frame;
    std::unordered_map<const vm::Program*, std::unique_ptr<vm::Interpreter<vm::Dual<double>>>> m_ownShaders;
};

/// The factor each primitive's tolerance is scaled by: its scene's coarser level of detail
/// (PrimitiveAttributes::sceneTolerance) over the render's tolerance, at least 1; all 1 when the
/// tolerance was given by the user.
std::vector<double> ToleranceScales(const PreparedScene& scene, const Options& options) {
    std::vector<double> scales(scene.primitives.size(), 1.0);
    if (!options.sceneTolerance) return scales;
    for (size_t i = 0; i < scales.size(); ++i)
        scales[i] = std::max(1.0, scene.primitives[i].sceneTolerance() / options.tolerancePixels);
    return scales;
}

/// `tol` for primitive i of the thread's scene.
Tolerance ToleranceOf(const ThreadState& ts, int i, const Tolerance& tol) {
    const double k = ts.toleranceScale[i];
    return k == 1 ? tol : Tolerance{tol.base * k, tol.slope * k, tol.newtonReach};
}

/// Where a search for the next surface along a ray starts after `hit`: past its certified error
/// (or the tolerance, if larger or the error unknown) twice, so it cannot find the same region.
double Beyond(const Hit& hit, const Tolerance& tol) {
    const double error = std::isfinite(hit.error) ? hit.error : tol.At(hit.t);
    return hit.t + 2 * std::max(error, tol.At(hit.t));
}

glm::dvec3 ToGlm(const vm::Vec3<vm::Dual<double>>& v) { return {v.x.v, v.y.v, v.z.v}; }

/// The displaced point and its unit normal at a hit, from the shade program in dual numbers, and
/// the displaced point's derivatives along the surface's parameters (for its geometric normal).
struct HitPoint {
    glm::dvec3 P, N, dPdu, dPdv;
};

/// The nearest hit of a search, on primitive number `primitive` (-1: none); `point` its
/// EvaluateHit if the search needed it (a one-sided primitive's facing), so it is not run twice.
struct NearestHit {
    Hit hit;
    int primitive = -1;
    std::optional<HitPoint> point;
};

HitPoint EvaluateHit(const PreparedScene& scene, ThreadState& ts, const Ray& ray, const NearestHit& nh,
                     const glm::dvec3& eye) {
    if (nh.point) return *nh.point;
    const Primitive& prim = scene.primitives[nh.primitive];
    vm::Interpreter<vm::Dual<double>>& interp = ts.Shader(nh.primitive);
    const double u = nh.hit.u, v = nh.hit.v;
    HitPoint h;
    const vm::Vec3<vm::Dual<double>> p =
        EvaluateOnSurface(interp, prim.base(), u, u, v, v, eye, *prim.shade().findOutput("P"));
    h.P = ToGlm(p);
    h.N = ToGlm(interp.OutputTriple(*prim.shade().findOutput("N")));
    h.dPdu = glm::dvec3(p.x.du, p.y.du, p.z.du);
    h.dPdv = glm::dvec3(p.x.dv, p.y.dv, p.z.dv);
    if (const MotionPath* path = prim.attributes().motion.get()) {
        // Evaluated where the geometry is placed: carried to where it is at the ray's time.
        const auto& f = ts.FrameAt(*path, ray.time);
        h.P = glm::dvec3(f.toWorldPoint * glm::dvec4(h.P, 1.0));
        h.dPdu = f.toWorld * h.dPdu;
        h.dPdv = f.toWorld * h.dPdv;
        h.N = f.normalToWorld * h.N;
    }
    if (!std::isfinite(glm::dot(h.P, h.P))) h.P = ray.origin + nh.hit.t * ray.dir;
    double lengthN = glm::length(h.N);
    h.N = lengthN > 0 && std::isfinite(lengthN) ? h.N / lengthN : -ray.dir;
    return h;
}

/// Whether hit a on primitive ia is kept before hit b on primitive ib: the nearer; of hits at the
/// same t (two surfaces' regions whose ranges along the ray are the same, as a surface and its
/// copy moved along z give where the x and y sides of their bounds bound the range), the one
/// with the smaller certified error, then the smaller (u, v): an order of the hits themselves,
/// so that the scene's order of primitives decides only between hits the same in all of these.
bool Before(const Hit& a, int ia, const Hit& b, int ib) {
    if (a.t != b.t) return a.t < b.t;
    if (a.error != b.error) return a.error < b.error;
    if (a.u != b.u) return a.u < b.u;
    if (a.v != b.v) return a.v < b.v;
    return ia < ib;
}

/// The hits a camera ray has gone past (surfaces seen from behind, partly transparent layers),
/// each primitive's latest: that primitive is searched again only beyond the hit's certified
/// error (Beyond), the others from the hit on, so that a surface within that error behind it (a
/// one-sided solid's back face meeting its front face at the silhouette, a face just behind a
/// one-sided decal or a veil) is still found. Once full, the next search starts beyond the last
/// hit for every primitive, as with no list.
struct PassedHits {
    static constexpr int kCapacity = 32;
    std::pair<int, double> from[kCapacity];  // (primitive, where its search starts again)
    int count = 0;

    /// Where primitive i's search starts, at least `t`.
    double From(int i, double t) const {
        for (int k = 0; k < count; ++k)
            if (from[k].first == i) return std::max(t, from[k].second);
        return t;
    }
    /// Goes past `hit` on primitive i; returns where the ray's next search starts.
    double Pass(int i, const Hit& hit, const Tolerance& tol) {
        const double beyond = Beyond(hit, tol);
        int k = 0;
        while (k < count && from[k].first != i) ++k;
        if (k == kCapacity) return beyond;
        if (k == count) ++count;
        from[k] = {i, beyond};
        return hit.t;
    }
};

/// The nearest hit along `ray` in [tMin, tMax] over the primitives the BVH offers. A one-sided
/// primitive (Sides 1) seen from behind (its geometric normal away from the ray) is not hit: the
/// search goes on past it (`passed` holds it and the hits the ray went past before: PassedHits).
/// The hit kept is a function of the ray and the scene's primitives, whatever the BVH's shape or
/// the order it offers them in (issue 32): each primitive's hit does not depend on the tMax it is
/// searched with (SurfaceIntersector::Intersect), only whether it is reported; it lies past
/// where the ray enters the primitive's box (the search starts there), so the BVH skips only
/// boxes entered beyond a hit already found; and of hits at the same t one is kept by an order
/// of the hits themselves (Before). Two surfaces whose hits lie within the tolerance of each other (a
/// cone standing on a displaced floor) are then told apart by the same rule on every BVH.
NearestHit TraceNearest(const PreparedScene& scene, ThreadState& ts, const Ray& ray, double tMin, double tMax,
                        const Tolerance& tol, IntersectStats& stats, const glm::dvec3& eye, const RayGroup* group,
                        PassedHits* passed) {
    constexpr int kMaxBackFaces = 16;
    for (int attempt = 0; attempt <= kMaxBackFaces; ++attempt) {
        NearestHit nearest;
        double best = tMax;
        scene.bvh->Traverse(ray, tMin, &best, [&](int i, double tEntry) {
            if (!scene.primitives[i].cameraVisible()) return true;  // Attribute "visibility" "camera" 0
            // From the box's entry (at least tMin, and a function of the ray and the primitive's
            // box alone): every surface point lies past it, and so then does the hit, which the
            // BVH would otherwise skip, its box entered beyond a nearer hit's t.
            const double from = passed->From(i, tEntry);
            if (from > best) return true;
            Hit hit;
            if (ts.Intersect(i, ray, from, best, ToleranceOf(ts, i, tol), false, &hit, stats, group) &&
                (nearest.primitive < 0 || Before(hit, i, nearest.hit, nearest.primitive))) {
                best = hit.t;
                nearest = {hit, i, std::nullopt};
            }
            return true;
        });
        if (nearest.primitive < 0 || scene.primitives[nearest.primitive].twoSided()) return nearest;
        // Facing is the geometric normal's (RI 3.2, 4.2), whatever N says: Ng = dP'/du x dP'/dv on
        // the side ParametricSide says (the derivatives' rates along the surface's parameters are
        // positive: they keep the sign); N only where the tangents are parallel (a pole) and Ng is
        // undefined.
        const HitPoint& at = *(nearest.point = EvaluateHit(scene, ts, ray, nearest, eye));
        const glm::dvec3 ng = ParametricSide(scene.primitives[nearest.primitive].base(), nearest.hit.u, nearest.hit.v) *
                              glm::cross(at.dPdu, at.dPdv);
        const double length = glm::length(ng);
        const glm::dvec3 facing = length > 0 && std::isfinite(length) ? ng / length : at.N;
        if (glm::dot(facing, ray.dir) < 0) return nearest;
        // Seen from behind: look again, this primitive beyond its hit's certified error.
        tMin = passed->Pass(nearest.primitive, nearest.hit, tol);
    }
    return {};
}

/// Partly transparent surfaces one ray passes through at most: a camera ray's layers, and a
/// shadow ray's hits on one primitive. What lies beyond the last is taken as black (camera) or
/// blocked (shadow).
constexpr int kMaxLayers = 64;

/// The light that gets through the segment of `ray` from tMin to tMax past the primitives that
/// cast shadows (transmission): 0 if an opaque one blocks it, else the product of 1 - Os over
/// the hits on the partly transparent ones (transmission "Os": each hit found nearest first,
/// the next search beyond it).
glm::dvec3 ShadowTransmission(const PreparedScene& scene, ThreadState& ts, const Ray& ray, double tMin, double tMax,
                              const Tolerance& tol) {
    using Transmission = PrimitiveDesc::Transmission;
    bool blocked = false, partly = false;
    double tEnd = tMax;
    scene.bvh->Traverse(ray, tMin, &tEnd, [&](int i, double) {
        const Primitive& prim = scene.primitives[i];
        if (prim.transmission() == Transmission::Transparent) return true;
        if (prim.transmission() == Transmission::Opacity && !prim.OpaqueP()) {
            partly = true;  // in the second pass
            return true;
        }
        Hit hit;
        blocked = ts.Intersect(i, ray, tMin, tMax, ToleranceOf(ts, i, tol), true, &hit, ts.shadowStats);
        return !blocked;
    });
    if (blocked) return glm::dvec3(0.0);
    if (!partly) return glm::dvec3(1.0);
    // Each partly transparent primitive's share, the product over its hits nearest first; the
    // shares multiplied in primitive order after, not in the BVH's (products round differently
    // in another order).
    std::vector<std::pair<int, glm::dvec3>>& shares = ts.shadowShares;
    shares.clear();
    bool dark = false;
    tEnd = tMax;
    scene.bvh->Traverse(ray, tMin, &tEnd, [&](int i, double) {
        const Primitive& prim = scene.primitives[i];
        if (prim.transmission() != Transmission::Opacity || prim.OpaqueP()) return true;
        glm::dvec3 share(1.0);
        double from = tMin;
        for (int layer = 0; layer < kMaxLayers; ++layer) {
            Hit hit;
            if (!ts.Intersect(i, ray, from, tMax, ToleranceOf(ts, i, tol), false, &hit, ts.shadowStats)) {
                shares.emplace_back(i, share);
                return true;
            }
            share *= 1.0 - prim.OpacityAt(hit.u, hit.v);
            if (share == glm::dvec3(0.0)) break;
            from = Beyond(hit, tol);
        }
        dark = true;  // blocked, or more layers than kMaxLayers: taken as blocked
        return false;
    });
    if (dark) return glm::dvec3(0.0);
    std::sort(shares.begin(), shares.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    glm::dvec3 through(1.0);
    for (const auto& [i, share] : shares) through *= share;
    return through;
}

/// Whether a surface that casts shadows and is opaque to them has a root proved by certified
/// Newton (Tolerance::certifiedOnly) on the segment [tMin, tMax] of `ray`.
bool ProvedBlocked(const PreparedScene& scene, ThreadState& ts, const Ray& ray, double tMin, double tMax,
                   const Tolerance& tol) {
    using Transmission = PrimitiveDesc::Transmission;
    bool blocked = false;
    double tEnd = tMax;
    scene.bvh->Traverse(ray, tMin, &tEnd, [&](int i, double) {
        const Primitive& prim = scene.primitives[i];
        if (prim.transmission() == Transmission::Transparent) return true;
        if (prim.transmission() == Transmission::Opacity && !prim.OpaqueP()) return true;
        Hit hit;
        blocked = ts.Intersect(i, ray, tMin, tMax, ToleranceOf(ts, i, tol), true, &hit, ts.shadowStats);
        return !blocked;
    });
    return blocked;
}

/// What a surface gives a camera ray: Ci (premultiplied by the opacity, as RenderMan's shaders
/// leave it) and Oi.
struct Shaded {
    glm::dvec3 Ci, Oi;
};

/// Runs the surface program `program` at the hit (P, N, dPdu, dPdv as EvaluateHit gives them,
/// in world space at the ray's time; the other globals from the primitive's base surface at the
/// hit's (u, v), as the displacement saw them), its light loops answered by ts.shadingLights.
/// T is double, or Dual<double> for a program that takes derivatives (Du, Dv, calculatenormal,
/// area): P then carries dPdu and dPdv as its derivatives.
template <class T>
Shaded RunSurface(const vm::Program& program, ThreadState& ts, const PreparedScene& scene, const Primitive& prim,
                  const Ray& ray, const NearestHit& nh, const HitPoint& at, const glm::dvec3& Cs,
                  const glm::dvec3& Os) {
    using vm::Global;
    vm::Interpreter<T>& interp = ts.Surface<T>(program);
    interp.SetLights(&ts.shadingLights[static_cast<size_t>(ts.depth)]);
    // The parameters (u, v, s, t, du, dv) are the base surface's, set with its frame (whose P,
    // N and tangents are replaced below): only for a shader that reads them.
    bool parameters = false;
    for (Global g : {Global::u, Global::v, Global::s, Global::t, Global::du, Global::dv})
        parameters = parameters || program.readsGlobal(g);
    if (parameters) SetSurfaceGlobals(interp, prim.base(), nh.hit.u, nh.hit.u, nh.hit.v, nh.hit.v, ray.origin);
    vm::Vec3<T> P;
    for (int i = 0; i < 3; ++i) {
        if constexpr (std::is_same_v<T, double>)
            P[i] = at.P[i];
        else
            P[i] = T(at.P[i], at.dPdu[i], at.dPdv[i]);
    }
    // Ng: the displaced surface's, dPdu x dPdv, on N's side (N where the tangents are parallel).
    glm::dvec3 Ng = glm::cross(at.dPdu, at.dPdv);
    const double lengthNg = glm::length(Ng);
    Ng = lengthNg > 0 && std::isfinite(lengthNg) ? Ng / lengthNg : at.N;
    if (glm::dot(Ng, at.N) < 0) Ng = -Ng;
    interp.SetGlobal(Global::P, P);
    interp.SetGlobal(Global::N, Constant<T>(at.N));
    interp.SetGlobal(Global::Ng, Constant<T>(Ng));
    interp.SetGlobal(Global::E, Constant<T>(ray.origin));
    interp.SetGlobal(Global::I, P - Constant<T>(ray.origin));
    interp.SetGlobal(Global::dPdu, Constant<T>(at.dPdu));
    interp.SetGlobal(Global::dPdv, Constant<T>(at.dPdv));
    interp.SetGlobal(Global::time, T(ray.time));
    interp.SetGlobal(Global::dtime, T(scene.desc.camera.shutterClose - scene.desc.camera.shutterOpen));
    interp.SetGlobal(Global::Cs, Constant<T>(Cs));
    interp.SetGlobal(Global::Os, Constant<T>(Os));
    interp.Run();
    // A component that is not finite (a shader's 0/0) is 0: one pixel's NaN would otherwise
    // spread through the filter to its neighbours and into every later composite.
    auto output = [&](const char* name) {
        const vm::Vec3<T> x = interp.OutputTriple(*program.findOutput(name));
        glm::dvec3 c(vm::ValueOf(x.x), vm::ValueOf(x.y), vm::ValueOf(x.z));
        for (int i = 0; i < 3; ++i)
            if (!std::isfinite(c[i])) c[i] = 0;
        return c;
    };
    return {output("Ci"), output("Oi")};
}

/// Shades the nearest hit of a camera ray: the surface shader or the built-in surface model at
/// P, N (EvaluateHit) with Cs and Os at the hit and shadow rays through the same intersector.
Shaded ShadeHit(const PreparedScene& scene, ThreadState& ts, const Ray& ray, const NearestHit& nh, const HitPoint& at,
                const Tolerance& tol) {
    const Primitive& prim = scene.primitives[nh.primitive];
    ShadingPoint sp;
    sp.P = at.P;
    sp.V = -ray.dir;
    sp.Nf = glm::dot(at.N, sp.V) < 0 ? -at.N : at.N;  // faceforward
    // Shadow rays start above the surface by more than the hit's certified error and the
    // tolerance, so they cannot find the region they left (no acne).
    double footprint = tol.At(nh.hit.t);
    double offset =
        2.0 * std::max(std::isfinite(nh.hit.error) ? nh.hit.error : footprint, footprint) + 1e-9 * glm::length(at.P);
    // A cone: as wide as the camera ray's footprint where it left, widening at the pixel's angle,
    // so an occluder is resolved no finer than the pixel that sees its shadow needs.
    Tolerance shadowTol{footprint, tol.slope, tol.newtonReach};
    // With certified Newton, each shadow ray is searched again from just above the hit (twice its
    // certified error): there only a root Krawczyk's test proves blocks the light, since a leaf
    // may be the surface the ray leaves, whose own root the test places before the start. Such a
    // root is a surface point on the ray: the light the offset let past a nearby crest is blocked
    // (the terminators of the default scene move by the offset without it).
    const double nearOffset = 2.0 * nh.hit.error + 1e-9 * glm::length(at.P);
    const bool searchNear = tol.newtonReach > 0 && std::isfinite(nh.hit.error) && nearOffset < offset;
    Tolerance nearTol = shadowTol;
    nearTol.certifiedOnly = true;
    auto transmitted = [&](const glm::dvec3& toLight, double distance) {
        Ray shadowRay{sp.P + sp.Nf * offset, toLight, ray.time};
        double tMax = std::isfinite(distance) ? distance - offset : INFINITY;
        const glm::dvec3 through = ShadowTransmission(scene, ts, shadowRay, offset, tMax, shadowTol);
        if (!searchNear || through == glm::dvec3(0.0)) return through;
        const Ray nearRay{sp.P + sp.Nf * nearOffset, toLight, ray.time};
        const double nearEnd = std::isfinite(distance) ? distance - nearOffset : INFINITY;
        return ProvedBlocked(scene, ts, nearRay, nearOffset, nearEnd, nearTol) ? glm::dvec3(0.0) : through;
    };
    // Lights that move (LightDesc::motion) stand where they are at the ray's time; the shadow rays
    // toward them keep that time too.
    const std::vector<LightDesc>* lights = &scene.lightSets[prim.lightSet];
    if (std::any_of(lights->begin(), lights->end(), [](const LightDesc& l) { return l.motion != nullptr; })) {
        std::vector<LightDesc>& moved = ts.movedLights[static_cast<size_t>(ts.depth)];
        moved.clear();
        for (const LightDesc& light : *lights) moved.push_back(LightAt(light, ray.time));
        lights = &moved;
    }
    const glm::dvec3 Cs = prim.ColorAt(nh.hit.u, nh.hit.v), Os = prim.OpacityAt(nh.hit.u, nh.hit.v);
    const ShadowTest shadow = transmitted;
    // trace(P, R): the colour the surface seen along R shows, shaded one level deeper; rays
    // start off the surface on R's side by the shadow rays' offset.
    const std::function<glm::dvec3(const glm::dvec3&)> trace = [&](const glm::dvec3& R) {
        const double length = glm::length(R);
        if (ts.depth >= ThreadState::kMaxTraceDepth || !(length > 0) || !std::isfinite(length)) return glm::dvec3(0.0);
        const glm::dvec3 d = R / length;
        const Ray traced{sp.P + (glm::dot(d, sp.Nf) < 0 ? -offset : offset) * sp.Nf, d, ray.time};
        PassedHits passed;
        const NearestHit hit =
            TraceNearest(scene, ts, traced, 0.0, INFINITY, shadowTol, ts.cameraStats, traced.origin, nullptr, &passed);
        if (hit.primitive < 0) return glm::dvec3(0.0);
        const HitPoint where = EvaluateHit(scene, ts, traced, hit, traced.origin);
        ++ts.depth;
        const Shaded seen = ShadeHit(scene, ts, traced, hit, where, shadowTol);
        --ts.depth;
        return seen.Ci;
    };
    ShadingLights& shading = ts.shadingLights[static_cast<size_t>(ts.depth)];
    shading.Reset(*lights, sp.P, &shadow, ray.origin, &trace);
    if (const std::shared_ptr<const compiler::CompiledShader>& surface = prim.programs->surface) {
        const vm::Program& program = surface->surface;
        return surface->surfaceDerivatives ? RunSurface<vm::Dual<double>>(program, ts, scene, prim, ray, nh, at, Cs, Os)
                                           : RunSurface<double>(program, ts, scene, prim, ray, nh, at, Cs, Os);
    }
    return {Os * ShadeSurface(prim.surface(), Cs, sp, *lights, shadow, &shading), Os};
}

}  // namespace

uint64_t SceneBytes(const PreparedScene& scene, int threads) {
    uint64_t bytes = scene.primitives.capacity() * sizeof(Primitive) +
                     scene.desc.primitives.capacity() * sizeof(PrimitiveDesc) + (scene.bvh ? scene.bvh->bytes() : 0);
    // Per primitive in a render: BoundForest's slot, and per thread ThreadState's intersector slot.
    bytes += scene.primitives.size() * (sizeof(void*) + size_t(threads) * sizeof(int));
    // What primitives share is counted once (a set of the shared objects met, which the
    // previous primitive's mostly answers); a patch's or quadric's shape, its own, once each.
    std::unordered_set<const void*> seen;
    const void* previous[3] = {nullptr, nullptr, nullptr};  // attributes, colour fields, meshes
    auto once = [&](int kind, const void* p) {
        if (!p || p == previous[kind]) return false;
        previous[kind] = p;
        return seen.insert(p).second;
    };
    auto vectorBytes = [](const auto& v) { return uint64_t(v.capacity()) * sizeof(v[0]); };
    for (const PrimitiveDesc& p : scene.desc.primitives) {
        if (once(0, p.attributes.get())) bytes += sizeof(PrimitiveAttributes);
        for (const ColorField* f : {p.colorField.get(), p.opacityField.get()})
            if (once(1, f)) bytes += sizeof(ColorField) + vectorBytes(f->c) + vectorBytes(f->w);
        const BaseSurface& b = p.base;
        switch (b.kind()) {
            case BaseSurface::Kind::BilinearPatch: bytes += sizeof(BilinearPatch); break;
            case BaseSurface::Kind::Quadric: bytes += sizeof(PlacedQuadric); break;
            case BaseSurface::Kind::BicubicPatch: bytes += sizeof(BicubicPatch); break;
            case BaseSurface::Kind::RationalPatch: bytes += sizeof(RationalPatch); break;
            case BaseSurface::Kind::MeshPiece:
                if (const PieceMesh& m = *b.pieceRef().mesh; once(2, &m)) {
                    bytes += sizeof(PieceMesh);
                    m.ForEachArray(
                        [&](const char*, const auto& values, const std::string&) { bytes += vectorBytes(values); });
                }
                break;
            case BaseSurface::Kind::SubdivPatch:
                if (const SubdivPatches& m = *b.subdivRef().patches; once(2, &m)) {
                    bytes += sizeof(SubdivPatches) + vectorBytes(m.patches);
                    for (int k = 0; k < 2; ++k) {
                        if (m.colors[k]) bytes += vectorBytes(m.colors[k]->values);
                        bytes += vectorBytes(m.colorFields[k]);
                    }
                }
                break;
        }
    }
    return bytes;
}

std::string RenderStats::ToJson() const {
    auto perRay = [](uint64_t n, uint64_t rays) { return rays ? double(n) / double(rays) : 0.0; };
    // A lookup that had to evaluate the bound is a miss.
    const double hitRate = cache.lookups ? 1.0 - double(cache.evaluations) / double(cache.lookups) : 0.0;
    char buf[2048];
    std::snprintf(
        buf, sizeof buf,
        "{\"wall_seconds\":%.3f,\"width\":%d,\"height\":%d,\"camera_rays\":%llu,"
        "\"regions_per_ray_mean\":%.2f,\"regions_per_ray_max\":%llu,\"evaluations_per_ray_mean\":%.3f,"
        "\"depth_limit_hits\":%llu,\"max_certified_error\":%.6g,\"parallelogram_hits\":%llu,"
        "\"shadow_rays\":%llu,\"shadow_regions_per_ray_mean\":%.2f,\"shadow_evaluations_per_ray_mean\":%.3f,"
        "\"budget_exhausted_rays\":%llu,\"frontiers\":%llu,\"frontier_regions_mean\":%.2f,"
        "\"newton\":{\"camera_hits\":%llu,\"shadow_hits\":%llu,\"misses\":%llu,\"unknown\":%llu},"
        "\"cache\":{\"budget_mb\":%.1f,\"peak_mb\":%.2f,\"final_mb\":%.2f,\"nodes\":%llu,\"trees\":%llu,"
        "\"trees_retired\":%llu,"
        "\"lookups\":%llu,\"hit_rate\":%.4f,\"evaluations\":%llu,\"private_copies\":%llu,"
        "\"evictions\":%llu,\"eviction_passes\":%llu,\"build_thread_seconds\":%.3f},"
        "\"memory\":{\"resident_at_start_mb\":%.1f,\"peak_resident_mb\":%.1f,\"scene_mb\":%.1f,"
        "\"primitives\":%llu,\"bytes_per_primitive\":%.0f},\"read_seconds\":%.3f,\"prepare_seconds\":%.3f}",
        wallSeconds, width, height, static_cast<unsigned long long>(cameraRays),
        perRay(camera.regionsBounded, cameraRays), static_cast<unsigned long long>(camera.maxRegionsPerRay),
        perRay(camera.regionsEvaluated, cameraRays),
        static_cast<unsigned long long>(camera.depthLimitHits) + shadow.depthLimitHits,
        std::max(camera.maxHitError, 0.0),
        static_cast<unsigned long long>(camera.parallelogramHits) + shadow.parallelogramHits,
        static_cast<unsigned long long>(shadow.rays), perRay(shadow.regionsBounded, shadow.rays),
        perRay(shadow.regionsEvaluated, shadow.rays),
        static_cast<unsigned long long>(camera.budgetExhausted) + shadow.budgetExhausted,
        static_cast<unsigned long long>(camera.frontiers), perRay(camera.frontierRegions, camera.frontiers),
        static_cast<unsigned long long>(camera.newtonHits), static_cast<unsigned long long>(shadow.newtonHits),
        static_cast<unsigned long long>(camera.newtonMisses) + shadow.newtonMisses,
        static_cast<unsigned long long>(camera.newtonUnknown) + shadow.newtonUnknown,
        double(cacheBudgetBytes) / (1 << 20), double(cachePeakBytes) / (1 << 20), double(cache.bytes) / (1 << 20),
        static_cast<unsigned long long>(cache.nodes), static_cast<unsigned long long>(cache.trees),
        static_cast<unsigned long long>(cache.treesRetired), static_cast<unsigned long long>(cache.lookups), hitRate,
        static_cast<unsigned long long>(cache.evaluations), static_cast<unsigned long long>(cache.privateCopies),
        static_cast<unsigned long long>(cache.evictions), static_cast<unsigned long long>(cache.evictionPasses),
        cache.buildSeconds, double(residentAtStartBytes) / (1 << 20), double(peakResidentBytes) / (1 << 20),
        double(sceneBytes) / (1 << 20), static_cast<unsigned long long>(primitives),
        primitives ? double(sceneBytes) / double(primitives) : 0.0, readSeconds, prepareSeconds);
    return buf;
}

namespace {

/// The range of t over which a camera ray lies between the clipping planes (camera-space depths
/// near and far); empty if the ray runs parallel to them outside.
void ClipRange(const CameraDesc& camera, const Ray& ray, double* tMin, double* tMax) {
    const double z0 = (camera.worldToCamera * glm::dvec4(ray.origin, 1.0)).z;
    const double dz = (camera.worldToCamera * glm::dvec4(ray.dir, 0.0)).z;
    if (dz > 0) {
        *tMin = std::max(0.0, (camera.nearClip - z0) / dz);
        *tMax = (camera.farClip - z0) / dz;
    } else {
        // Along the image plane (orthographic edge cases): all or nothing.
        const bool inside = z0 >= camera.nearClip && z0 <= camera.farClip;
        *tMin = 0;
        *tMax = inside ? INFINITY : -1;
    }
}

/// Traces and shades one camera sample.
/// The group of the camera rays through the pixels of block (bx, by) of side `side` (a block of
/// the whole image's pixel grid, whatever the tile), grown by a quarter pixel so that rounding
/// cannot put a ray of the block outside.
RayGroup BlockGroup(const Camera& camera, int side, int bx, int by, int blocksX) {
    constexpr double kMargin = 0.25;
    const double x0 = bx * side - kMargin, x1 = (bx + 1) * side + kMargin;
    const double y0 = by * side - kMargin, y1 = (by + 1) * side + kMargin;
    const Ray corners[4] = {camera.GenerateRay(x0, y0), camera.GenerateRay(x1, y0), camera.GenerateRay(x1, y1),
                            camera.GenerateRay(x0, y1)};
    return RayGroup::FromCorners(corners, 1 + uint64_t(by) * uint64_t(blocksX) + uint64_t(bx));
}

/// An atmosphere shader (AtmosphereDesc) on what a camera ray from `eye` sees at `p` (world space):
/// I and depth(P) are taken in camera space, as the shader sees them.
void ApplyAtmosphere(const AtmosphereDesc& atmosphere, const CameraDesc& camera, const glm::dvec3& eye,
                     const glm::dvec3& p, glm::dvec3* Ci, glm::dvec3* Oi) {
    const glm::dvec3 pc(camera.worldToCamera * glm::dvec4(p, 1.0));
    double d;
    if (atmosphere.kind == AtmosphereDesc::Kind::Fog) {
        const glm::dvec3 ec(camera.worldToCamera * glm::dvec4(eye, 1.0));
        d = 1.0 - std::exp(-glm::length(pc - ec) / atmosphere.distance);
    } else {
        const double depth = (pc.z - camera.nearClip) / (camera.farClip - camera.nearClip);
        d = std::clamp((depth - atmosphere.minDistance) / (atmosphere.maxDistance - atmosphere.minDistance), 0.0, 1.0);
    }
    *Ci = glm::mix(*Ci, atmosphere.background, d);
    *Oi = glm::mix(*Oi, glm::dvec3(1.0), d);
}

SampleValue TraceSample(const PreparedScene& scene, ThreadState& ts, const Camera& camera, const Sample& sample,
                        const Tolerance& tol, const glm::dvec3& eye, const RayGroup* group) {
    SampleValue value;
    const CameraDesc& cam = scene.desc.camera;
    const double time = cam.shutterOpen + (cam.shutterClose - cam.shutterOpen) * sample.time;
    const Ray ray = camera.GenerateRay(sample.raster.x, sample.raster.y, sample.lens, time);
    double tMin, tMax;
    ClipRange(scene.desc.camera, ray, &tMin, &tMax);
    ++ts.cameraRays;
    if (!(tMin <= tMax)) return value;
    const uint64_t before = ts.cameraStats.regionsBounded;
    // Front to back through partly transparent surfaces (Os < 1): each layer adds its colour
    // times its opacity times what the layers in front let through (RenderMan's Ci = Os * ...,
    // composited over what lies behind); an opaque layer ends the ray. The AOVs are the nearest
    // surface's; alpha is the coverage, 1 - the mean of what gets through.
    glm::dvec3 through(1.0);
    PassedHits passed;
    for (int layer = 0; layer < kMaxLayers; ++layer) {
        const NearestHit nh = TraceNearest(scene, ts, ray, tMin, tMax, tol, ts.cameraStats, eye, group, &passed);
        if (nh.primitive < 0) break;
        const Primitive& prim = scene.primitives[nh.primitive];
        const HitPoint at = EvaluateHit(scene, ts, ray, nh, eye);
        // Ci and Oi as RenderMan's shaders leave them: premultiplied colour, then the atmosphere.
        auto [Ci, Oi] = ShadeHit(scene, ts, ray, nh, at, tol);
        if (const std::optional<AtmosphereDesc>& atmosphere = prim.desc->attr().atmosphere)
            ApplyAtmosphere(*atmosphere, scene.desc.camera, ray.origin, ray.origin + nh.hit.t * ray.dir, &Ci, &Oi);
        value.rgb += through * Ci;
        through *= 1.0 - Oi;
        if (layer == 0) {
            const glm::dmat4 worldToCamera = MatrixAt(cam.motion.get(), cam.worldToCamera, time);
            value.z = (worldToCamera * glm::dvec4(ray.origin + nh.hit.t * ray.dir, 1.0)).z;
            value.N = at.N;
            value.P = at.P;
            // The mesh's (u,v), which the shader saw: the hit's are the patch's own.
            const ParameterRange range = prim.desc->base.range;  // a patch's: never an element's own
            value.st = {range.U(nh.hit.u), range.V(nh.hit.v)};
            value.err = nh.hit.error;
        }
        if (through == glm::dvec3(0.0)) break;
        tMin = passed.Pass(nh.primitive, nh.hit, tol);
    }
    value.alpha = 1.0 - (through.x + through.y + through.z) / 3.0;
    value.cost = static_cast<int64_t>(ts.cameraStats.regionsBounded - before);
    return value;
}

/// The process's resident memory now (/proc/self/statm), 0 where unknown.
uint64_t ResidentBytes() {
    std::ifstream statm("/proc/self/statm");
    uint64_t pages = 0, resident = 0;
    if (!(statm >> pages >> resident)) return 0;
    return resident * static_cast<uint64_t>(sysconf(_SC_PAGESIZE));
}

/// The process's peak resident memory so far (getrusage: ru_maxrss in KiB), 0 where unknown.
uint64_t PeakResidentBytes() {
    rusage usage{};
    return getrusage(RUSAGE_SELF, &usage) == 0 ? static_cast<uint64_t>(usage.ru_maxrss) * 1024 : 0;
}

}  // namespace

Renderer::Renderer(Options options) : m_options(std::move(options)), m_pool(m_options.threads) {}

int Renderer::TileSize(const CameraDesc& camera) const {
    int tileSize = std::max(1, m_options.tileSize);
    // Smaller tiles for small images, so that every thread gets work (four tiles each at least),
    // down to 8 pixels: below that the filter margins each tile traces again cost too much.
    const Film film(camera);
    while (tileSize > 8 && static_cast<int>(film.Tiles(tileSize).size()) < 4 * threads()) tileSize /= 2;
    return tileSize;
}

void Renderer::Render(const PreparedScene& scene, image::ImageBuffer* image, RenderStats* stats,
                      const RenderControl& control) const {
    const Options& options = m_options;
    auto start = std::chrono::steady_clock::now();
    const uint64_t residentAtStart = ResidentBytes();
    const CameraDesc& cam = scene.desc.camera;
    const Camera camera(cam);
    const glm::dvec3 eye = camera.Position();
    DisplayChannels channels;
    std::string modeError;
    ParseDisplayMode(scene.desc.displayMode, &channels, &modeError);  // checked by the RIB reader
    const Film film(cam, channels);
    *image = film.MakeImage();
    const Tolerance tol{options.tolerancePixels * camera.PixelWidth(), options.tolerancePixels * camera.PixelAngle(),
                        options.newton ? 1.0 : 0.0};
    const int nThreads = threads();
    std::vector<PixelRange> tiles = film.Tiles(control.tileSize > 0 ? control.tileSize : TileSize(cam));
    if (options.reverseTileOrder) std::reverse(tiles.begin(), tiles.end());
    if (control.progress) control.progress->Begin(static_cast<int>(tiles.size()));
    // Tiles an interrupted render finished come back from the store, and are not rendered again.
    int restored = 0;
    if (control.tileStore)
        std::erase_if(tiles, [&](const PixelRange& tile) {
            if (!control.tileStore->Restore(tile, image)) return false;
            ++restored;
            if (control.progress) control.progress->TileDone();
            return true;
        });
    auto stopped = [&] { return control.stop && control.stop->load(std::memory_order_relaxed); };

    std::atomic<size_t> nextTile{0}, tilesDone{0};
    std::vector<IntersectStats> cameraStats(nThreads), shadowStats(nThreads);
    std::vector<uint64_t> cameraRays(nThreads);
    // One bound hierarchy per primitive, shared by every thread and ray of this render, made when a
    // ray first meets the primitive (a hierarchy evaluates its root's bound when made).
    CacheBudget budget(options.cacheBytes);
    BoundForest trees(scene.primitives.size(), budget, [&](size_t i, CacheBudget* b) {
        const Primitive& prim = scene.primitives[i];
        return std::make_unique<BoundTree>(prim.base(), prim.bound(), eye, options.bounds, options.maxDepth, b);
    });
    const std::vector<double> toleranceScales = ToleranceScales(scene, options);
    // Ray groups bound camera rays from one eye; through a lens (depth of field) or from a moving
    // camera rays start in different places, so each goes alone.
    const int side = camera.HasLens() || cam.motion ? 0 : options.rayGroupPixels;
    const int blocksX = side > 0 ? (cam.xres + side - 1) / side : 0;
    auto worker = [&](int index) {
        ThreadState ts(scene, options, trees, toleranceScales);
        std::vector<Sample> samples;
        std::vector<SampleValue> values;
        std::vector<std::pair<int64_t, uint32_t>> order;  // (block, sample index)
        RayGroup group;
        for (size_t i = nextTile++; i < tiles.size() && !stopped(); i = nextTile++) {
            film.TileSamples(tiles[i], &samples);
            values.resize(samples.size());
            if (side <= 0) {
                for (size_t k = 0; k < samples.size() && !stopped(); ++k)
                    values[k] = TraceSample(scene, ts, camera, samples[k], tol, eye, nullptr);
            } else {
                // Block by block (the tile's margin reaches into its neighbours' blocks).
                order.clear();
                for (size_t k = 0; k < samples.size(); ++k)
                    order.emplace_back(int64_t(samples[k].py / side) * blocksX + samples[k].px / side, uint32_t(k));
                std::sort(order.begin(), order.end());
                for (const auto& [block, k] : order) {
                    if (stopped()) break;
                    const int bx = int(block % blocksX), by = int(block / blocksX);
                    if (group.id != uint64_t(block) + 1) group = BlockGroup(camera, side, bx, by, blocksX);
                    // A sample outside its pixel (never, with the film's stratified samples) goes alone.
                    const glm::dvec2 p = samples[k].raster;
                    const bool inBlock =
                        p.x >= bx * side && p.x <= (bx + 1) * side && p.y >= by * side && p.y <= (by + 1) * side;
                    values[k] = TraceSample(scene, ts, camera, samples[k], tol, eye, inBlock ? &group : nullptr);
                }
            }
            // A stopped tile's samples are incomplete: it is left out, neither resolved nor kept.
            if (stopped()) break;
            film.ResolveTile(tiles[i], samples, values, image);
            if (control.tileStore) control.tileStore->Finished(tiles[i], *image);
            ++tilesDone;
            if (control.progress) control.progress->TileDone();
        }
        cameraStats[index] = ts.cameraStats;
        shadowStats[index] = ts.shadowStats;
        cameraRays[index] = ts.cameraRays;
    };
    m_pool.Run(nThreads, worker);
    if (control.progress) control.progress->Finish();

    *stats = RenderStats();
    trees.Merge(&stats->cache);
    stats->cache.evictionPasses = budget.passes();  // one pass serves every tree (none if none was made)
    stats->cache.treesRetired = budget.treesRetired();
    stats->cacheBudgetBytes = options.cacheBytes;
    stats->cachePeakBytes = budget.peakBytes.load();
    for (int i = 0; i < nThreads; ++i) {
        stats->camera.Merge(cameraStats[i]);
        stats->shadow.Merge(shadowStats[i]);
        stats->cameraRays += cameraRays[i];
    }
    // A stop after the last tile stops nothing: the image is whole.
    stats->stopped = tilesDone != tiles.size();
    stats->tilesRestored = restored;
    stats->width = cam.xres;
    stats->height = cam.yres;
    stats->wallSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    stats->residentAtStartBytes = residentAtStart;
    stats->peakResidentBytes = PeakResidentBytes();
    stats->sceneBytes = SceneBytes(scene, nThreads);
    stats->primitives = scene.primitives.size();
}

}  // namespace affray::renderer
