// renderer/render.cpp: scene preparation and the tile loop.
// Each thread owns its intersectors and shading interpreters (they hold registers), takes tiles
// from a shared counter, traces the samples the film asks for (renderer/film.h) and resolves
// only its tile's pixels: the image does not depend on the thread count or the tile order, and
// the statistics are sums and maxima, which do not either. Tiles a TileStore holds (a resumed
// render's checkpoint) are copied in instead of rendered, each finished tile is handed to it, and
// the stop flag (a signal) is checked between samples: a tile stopped part way is dropped whole.
#include "renderer/render.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <stdexcept>
#include <thread>
#include <unordered_map>
#include <unordered_set>

#include <sys/resource.h>
#include <unistd.h>

#include "compiler/shader_cache.h"
#include "diag/limits.h"
#include "renderer/film.h"
#include "renderer/shade.h"
#include "renderer/thread_pool.h"
#include "scene/geometry/camera.h"
#include "scene/refine.h"
#include "texture/texture.h"

namespace affray::renderer {

std::vector<compiler::ConstantGlobal> ConstantGlobals(const BaseSurface& base, const glm::dvec3& eye) {
    using vm::Global;
    std::vector<compiler::ConstantGlobal> out = {{Global::E, {eye.x, eye.y, eye.z}},
                                                 {Global::du, {kParametricStep, 0, 0}},
                                                 {Global::dv, {kParametricStep, 0, 0}}};
    if (base.kind() != BaseSurface::Kind::BilinearPatch) return out;
    const BilinearPatch& patch = base.patch();
    // The tangents along the mesh's (u,v), as SetPatchGlobals scales them.
    const double dsdu = base.range.unitP() ? 1.0 : 1.0 / (base.range.u1 - base.range.u0);
    const double dtdv = base.range.unitP() ? 1.0 : 1.0 / (base.range.v1 - base.range.v0);
    glm::dvec3 a = patch.a() * dsdu, b = patch.b() * dtdv, n = patch.flatNormal();
    if (base.flipNormal) n = -n;
    if (patch.flat() && std::isfinite(glm::dot(n, n))) {
        // The same tangents and normal everywhere, the values SetPatchGlobals would give.
        out.push_back({Global::dPdu, {a.x, a.y, a.z}});
        out.push_back({Global::dPdv, {b.x, b.y, b.z}});
        out.push_back({Global::N, {n.x, n.y, n.z}});
        out.push_back({Global::Ng, {n.x, n.y, n.z}});
    }
    return out;
}

namespace {

/// NAME.sl or, failing that, NAME.afb (compiled), in the first directory that has either. A name
/// given with a compiled shader's extension, as scenes exported for one renderer name them
/// (prman's .slo, BMRT's .slc, 3Delight's .sdl, Aqsis's .slx, Pixie's .sdr) or with .sl, is the
/// shader of its stem.
std::string FindShader(const std::string& name, const std::vector<std::string>& paths) {
    for (const std::string& dir : paths) {
        for (const char* extension : {".sl", ".afb"}) {
            std::filesystem::path candidate = std::filesystem::path(dir) / (name + extension);
            std::error_code ec;
            if (std::filesystem::is_regular_file(candidate, ec)) return candidate.string();
        }
    }
    const std::string extension = std::filesystem::path(name).extension().string();
    for (const char* compiled : {".sl", ".slo", ".slc", ".sdl", ".slx", ".sdr"})
        if (extension == compiled) return FindShader(name.substr(0, name.size() - extension.size()), paths);
    return {};
}

/// The bound hierarchy of each primitive (renderer/bound_tree.h), shared by every thread and ray of
/// a render, made when a ray first meets the primitive, by whichever thread that is: a scene of a
/// million faces pays only for the faces its rays reach (a hierarchy evaluates its root's bound
/// when made, and holds some 0.5 KB).
class LazyTrees {
  public:
    LazyTrees(const PreparedScene& scene, const RenderOptions& options, const glm::dvec3& eye, CacheBudget* budget)
        : m_scene(scene), m_options(options), m_eye(eye), m_budget(budget), m_trees(scene.primitives.size()) {}
    ~LazyTrees() {
        for (std::atomic<BoundTree*>& tree : m_trees) delete tree.load();
    }
    LazyTrees(const LazyTrees&) = delete;
    LazyTrees& operator=(const LazyTrees&) = delete;

    BoundTree& operator[](size_t i) {
        BoundTree* tree = m_trees[i].load(std::memory_order_acquire);
        if (tree) return *tree;
        const Primitive& prim = m_scene.primitives[i];
        auto made = std::make_unique<BoundTree>(prim.base(), prim.bound(), m_eye, m_options.bounds, m_options.maxDepth,
                                                m_budget);
        // Another thread may have made it meanwhile: the first made is kept (both are the same).
        if (m_trees[i].compare_exchange_strong(tree, made.get(), std::memory_order_acq_rel)) return *made.release();
        return *tree;
    }

    /// The statistics summed over the hierarchies made.
    void Merge(BoundTreeStats* stats) const {
        for (const std::atomic<BoundTree*>& tree : m_trees)
            if (const BoundTree* t = tree.load()) stats->Merge(t->stats());
    }

  private:
    const PreparedScene& m_scene;
    const RenderOptions& m_options;
    glm::dvec3 m_eye;
    CacheBudget* m_budget;
    std::vector<std::atomic<BoundTree*>> m_trees;
};

/// Everything one thread needs: per primitive an intersector (a walker over the primitive's shared
/// bound hierarchy) and a shading interpreter.
struct ThreadState {
    IntersectStats cameraStats, shadowStats;
    uint64_t cameraRays = 0;

    /// Per primitive, the factor its tolerance is scaled by (ToleranceScales).
    const std::vector<double>& toleranceScale;

    ThreadState(const PreparedScene& scene, const RenderOptions& options, LazyTrees& trees,
                const std::vector<double>& scales)
        : toleranceScale(scales),
          m_scene(scene),
          m_options(options),
          m_trees(trees),
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
                            : MakeSurfaceIntersector(m_trees[i], m_options.regionBudget, m_workspace);
        m_slotOf[i] = slot;
        return *k.intersector;
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
    static constexpr size_t kKeptIntersectors = 2048;
    struct Kept {
        std::unique_ptr<SurfaceIntersector> intersector;
        int primitive = -1;
        bool used = false;  // tested since the clock hand last passed
    };

    const PreparedScene& m_scene;
    const RenderOptions& m_options;
    LazyTrees& m_trees;
    std::shared_ptr<IntersectWorkspace> m_workspace;
    std::vector<int> m_slotOf;  // per primitive, its place in m_kept or -1
    std::vector<Kept> m_kept;
    size_t m_hand = 0;
    std::unique_ptr<vm::Interpreter<vm::Dual<double>>> m_shared;
    std::unordered_map<const vm::Program*, std::unique_ptr<vm::Interpreter<vm::Dual<double>>>> m_ownShaders;
};

/// The factor each primitive's tolerance is scaled by: its scene's coarser level of detail
/// (PrimitiveAttributes::sceneTolerance) over the render's tolerance, at least 1; all 1 when the
/// tolerance was given by the user.
std::vector<double> ToleranceScales(const PreparedScene& scene, const RenderOptions& options) {
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
    if (!std::isfinite(glm::dot(h.P, h.P))) h.P = ray.origin + nh.hit.t * ray.dir;
    double lengthN = glm::length(h.N);
    h.N = lengthN > 0 && std::isfinite(lengthN) ? h.N / lengthN : -ray.dir;
    return h;
}

/// The nearest hit along `ray` in [tMin, tMax] over the primitives the BVH offers. A one-sided
/// primitive (Sides 1) seen from behind (its geometric normal away from the ray) is not hit: the
/// search goes on past it.
NearestHit TraceNearest(const PreparedScene& scene, ThreadState& ts, const Ray& ray, double tMin, double tMax,
                        const Tolerance& tol, IntersectStats& stats, const glm::dvec3& eye, const RayGroup* group) {
    constexpr int kMaxBackFaces = 16;
    for (int attempt = 0; attempt <= kMaxBackFaces; ++attempt) {
        NearestHit nearest;
        double best = tMax;
        scene.bvh->Traverse(ray, tMin, &best, [&](int i, double) {
            if (!scene.primitives[i].cameraVisible()) return true;  // Attribute "visibility" "camera" 0
            Hit hit;
            if (ts.Intersector(i).Intersect(ray, tMin, best, ToleranceOf(ts, i, tol), false, &hit, stats, group)) {
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
        // Seen from behind: look again beyond this hit's certified error.
        tMin = Beyond(nearest.hit, tol);
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
        blocked = ts.Intersector(i).Intersect(ray, tMin, tMax, ToleranceOf(ts, i, tol), true, &hit, ts.shadowStats);
        return !blocked;
    });
    if (blocked) return glm::dvec3(0.0);
    glm::dvec3 through(1.0);
    if (!partly) return through;
    tEnd = tMax;
    scene.bvh->Traverse(ray, tMin, &tEnd, [&](int i, double) {
        const Primitive& prim = scene.primitives[i];
        if (prim.transmission() != Transmission::Opacity || prim.OpaqueP()) return true;
        double from = tMin;
        for (int layer = 0; layer < kMaxLayers; ++layer) {
            Hit hit;
            if (!ts.Intersector(i).Intersect(ray, from, tMax, ToleranceOf(ts, i, tol), false, &hit, ts.shadowStats))
                return true;
            through *= 1.0 - prim.OpacityAt(hit.u, hit.v);
            if (through == glm::dvec3(0.0)) return false;
            from = Beyond(hit, tol);
        }
        through = glm::dvec3(0.0);
        return false;
    });
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
        blocked = ts.Intersector(i).Intersect(ray, tMin, tMax, ToleranceOf(ts, i, tol), true, &hit, ts.shadowStats);
        return !blocked;
    });
    return blocked;
}

/// Shades the nearest hit of a camera ray: the surface model at P, N (EvaluateHit) with Cs at
/// the hit and shadow rays through the same intersector. The colour is not yet multiplied by Os.
glm::dvec3 ShadeHit(const PreparedScene& scene, ThreadState& ts, const Ray& ray, const NearestHit& nh,
                    const HitPoint& at, const Tolerance& tol) {
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
        Ray shadowRay{sp.P + sp.Nf * offset, toLight};
        double tMax = std::isfinite(distance) ? distance - offset : INFINITY;
        const glm::dvec3 through = ShadowTransmission(scene, ts, shadowRay, offset, tMax, shadowTol);
        if (!searchNear || through == glm::dvec3(0.0)) return through;
        const Ray nearRay{sp.P + sp.Nf * nearOffset, toLight};
        const double nearEnd = std::isfinite(distance) ? distance - nearOffset : INFINITY;
        return ProvedBlocked(scene, ts, nearRay, nearOffset, nearEnd, nearTol) ? glm::dvec3(0.0) : through;
    };
    return ShadeSurface(prim.surface(), prim.ColorAt(nh.hit.u, nh.hit.v), sp, scene.lightSets[prim.lightSet],
                        transmitted);
}

/// The largest magnitude a bound of P may reach for the intersector to measure it: the ray-frame
/// test squares widths, which overflow past about 1e154.
constexpr double kMeasurableLimit = 1e150;

/// The ranges of P's coordinates over the cells of an n x n grid of a primitive's domain.
using CellRanges = std::vector<std::array<vm::Interval, 3>>;

/// The cells bounded with number type N.
template <class N>
CellRanges BoundCells(const Primitive& prim, const glm::dvec3& eye, int n) {
    vm::Interpreter<N> interp(prim.bound());
    const vm::ProgramOutput& output = *prim.bound().findOutput("P");
    CellRanges cells;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            Vec3<N> p = EvaluateOnSurface(interp, prim.base(), double(i) / n, double(i + 1) / n, double(j) / n,
                                          double(j + 1) / n, eye, output);
            cells.push_back({RangeOf(vm::ValueOf(p.x)), RangeOf(vm::ValueOf(p.y)), RangeOf(vm::ValueOf(p.z))});
        }
    return cells;
}

/// The cells bounded with B (Affine or Interval), or its dual if the bound program takes
/// derivatives.
template <class B>
CellRanges BoundCellsIn(const Primitive& prim, const glm::dvec3& eye, int n) {
    return prim.bound().usesDerivatives() ? BoundCells<vm::Dual<B>>(prim, eye, n) : BoundCells<B>(prim, eye, n);
}

/// The grid the PrepareScene checks and the BVH boxes use: kGridCells across for a scene of a few
/// primitives, coarser for many (a mesh of thousands of faces), so that the whole scene costs
/// about kGridCells^2 * kGridPrimitives bounds, and never fewer than 2 x 2 cells per primitive up
/// to kOneCellPrimitives primitives, one cell past them (a mesh of a million faces costs a million
/// bounds). The subdivision scene of bench/real (26,560 patches) renders 9 % slower with one cell
/// per patch (its boxes looser), which its 4 x 26,560 box bounds do not pay for.
/// A coarser grid only loosens a primitive's box (its bound's union over fewer cells), never the
/// bounds the intersector tests.
constexpr int kGridCells = 8;
constexpr size_t kGridPrimitives = 64;
constexpr size_t kOneCellPrimitives = size_t{1} << 17;
int GridCellsFor(size_t primitives) {
    if (primitives <= kGridPrimitives) return kGridCells;
    if (primitives > kOneCellPrimitives) return 1;
    const double n = kGridCells * std::sqrt(double(kGridPrimitives) / double(primitives));
    return std::max(2, static_cast<int>(n));
}

/// Whether P's bound is measurable (finite, within kMeasurableLimit) over at least one cell.
bool MeasurableSomewhere(const CellRanges& cells) {
    for (const auto& cell : cells) {
        bool measurable = true;
        for (const vm::Interval& r : cell)
            measurable = measurable && !r.isUnbounded() && std::fabs(r.lo()) < kMeasurableLimit &&
                         std::fabs(r.hi()) < kMeasurableLimit;
        if (measurable) return true;
    }
    return false;
}

/// The finest grid UnboundedEverywhere tries (64 x 64: 4096 cells per bounding mode, evaluated only
/// for a surface that no coarser grid could bound).
constexpr int kFinestCheckCells = 64;

/// An error if no cell of the grids of the patch, `cells` across and then twice, four and eight...
/// times finer up to kFinestCheckCells, has a measurable bound in either bounding mode
/// (`intervalCells` are the interval bounds of the first grid, looked at first as they are already
/// paid for): every region would then survive the ray test down to the depth
/// limit, 4^depth regions per ray, a render that never ends. A shader whose bound is unbounded
/// where a region straddles a branch (a square root on the side not taken) is bounded on finer
/// cells, so one grid is not enough. Names the instance's parameters that are large enough to be
/// the cause. Empty if the surface can be bounded somewhere.
std::string UnboundedEverywhere(const Primitive& prim, const ShaderRef& ref, const glm::dvec3& eye, int cells,
                                const CellRanges& intervalCells) {
    if (MeasurableSomewhere(intervalCells)) return {};
    for (int n = cells; n <= kFinestCheckCells; n *= 2) {
        if (MeasurableSomewhere(BoundCellsIn<vm::Affine>(prim, eye, n))) return {};
        if (n != cells && MeasurableSomewhere(BoundCellsIn<vm::Interval>(prim, eye, n))) return {};
    }
    std::string culprits;
    for (const ParamValue& p : ref.params)
        for (double x : p.numbers)
            if (std::fabs(x) >= 1e100) {
                char value[32];
                std::snprintf(value, sizeof value, "%g", x);
                culprits += std::string(culprits.empty() ? "" : ", ") + "'" + p.name + "' = " + value;
                break;
            }
    std::string message = "the displaced surface of shader '" + ref.name +
                          "' cannot be bounded over any part of the patch (NaN, infinity or values past 1e150 in "
                          "every region), so no ray could finish";
    if (!culprits.empty()) message += "; parameter " + culprits + " is too large";
    return message;
}

/// The box of the displaced surface over its whole domain: the union of the bounds of the cells
/// of a grid (tighter than one bound over everything). Infinite if any cell's bound is unbounded:
/// the BVH then offers the primitive to every ray.
Box UnionBox(const CellRanges& cells) {
    Box box;
    for (const auto& cell : cells)
        for (int c = 0; c < 3; ++c) {
            const vm::Interval& r = cell[c];
            if (r.isUnbounded()) {
                box.lo[c] = -INFINITY;
                box.hi[c] = INFINITY;
            } else {
                box.lo[c] = std::min(box.lo[c], r.lo());
                box.hi[c] = std::max(box.hi[c], r.hi());
            }
        }
    return box;
}

compiler::Matrix4 RowMajor(const glm::dmat4& m) {
    compiler::Matrix4 out{};
    for (int row = 0; row < 4; ++row)
        for (int col = 0; col < 4; ++col) out[4 * row + col] = m[col][row];  // glm is column-major
    return out;
}

bool IsAffine(const compiler::Matrix4& m) { return m[12] == 0 && m[13] == 0 && m[14] == 0 && m[15] == 1; }

/// The spaces a shader on `patch` sees. "current" is world space: P is computed there.
compiler::Spaces SpacesOf(const SceneDesc& scene, const PrimitiveAttributes& patch) {
    const CameraDesc& camera = scene.camera;
    auto space = [](const glm::dmat4& toWorld) {
        return compiler::SpaceTransform{RowMajor(toWorld), RowMajor(glm::inverse(toWorld))};
    };
    compiler::Spaces spaces;
    for (const auto& [name, toWorld] : scene.coordinateSystems) spaces[name] = space(toWorld);
    if (patch.scopedSpaces)
        for (const auto& [name, toWorld] : *patch.scopedSpaces) spaces[name] = space(toWorld);
    spaces["world"] = compiler::SpaceTransform{};
    spaces["object"] = space(patch.objectToWorld);
    spaces["shader"] = space(patch.displacement ? patch.displacement->shaderToWorld : patch.objectToWorld);
    spaces["camera"] = space(glm::inverse(camera.worldToCamera));
    return spaces;
}

/// `path` as the scene names it: as written if absolute, else from the RIB file's directory.
std::string FromSceneDir(const SceneDesc& scene, const std::string& path) {
    const std::filesystem::path p(path);
    return p.is_absolute() ? path : (std::filesystem::path(scene.path).parent_path() / p).string();
}

/// The options and attributes a shader on `patch` may query (option(), attribute(), depth()):
/// those of RI Spec 3.2 tables 15.4 and 15.5 that the scene holds.
compiler::SceneFacts FactsOf(const SceneDesc& scene, const PrimitiveAttributes& patch) {
    const CameraDesc& camera = scene.camera;
    const double frameAspect = camera.frameAspectRatio.value_or(camera.xres * camera.pixelAspect / camera.yres);
    compiler::SceneFacts facts;
    auto numbers = [](std::vector<double> values) { return compiler::FactValue{std::move(values), std::nullopt}; };
    facts.options["Format"] = numbers({double(camera.xres), double(camera.yres), camera.pixelAspect});
    facts.options["DeviceResolution"] = facts.options["Format"];
    facts.options["FrameAspectRatio"] = numbers({frameAspect});
    const glm::dvec4& crop = camera.cropWindow;
    facts.options["CropWindow"] = numbers({crop[0], crop[1], crop[2], crop[3]});
    facts.options["Clipping"] = numbers({camera.nearClip, camera.farClip});
    facts.attributes["Sides"] = numbers({patch.twoSided ? 2.0 : 1.0});
    // Option "searchpath" "texture", relative directories taken from the RIB file's, then that
    // directory itself.
    for (const std::string& dir : scene.textureSearchPath) facts.textureSearchPath.push_back(FromSceneDir(scene, dir));
    facts.textureSearchPath.push_back(std::filesystem::path(scene.path).parent_path().string());
    return facts;
}

/// The scene's MakeTexture requests, in order (relative paths from the RIB file's directory); a
/// texture newer than its picture is kept, as make would.
void MakeTextures(const SceneDesc& desc, diag::Report* report) {
    namespace fs = std::filesystem;
    for (const SceneDesc::MakeTextureDesc& m : desc.makeTextures) {
        const fs::path picture = FromSceneDir(desc, m.picture), texture = FromSceneDir(desc, m.texture);
        std::error_code ec, ec2;
        const auto made = fs::last_write_time(texture, ec), source = fs::last_write_time(picture, ec2);
        if (!ec && !ec2 && made >= source) continue;
        texture::Wrap swrap = texture::Wrap::Periodic, twrap = texture::Wrap::Periodic;
        texture::ParseWrap(m.swrap, &swrap);
        texture::ParseWrap(m.twrap, &twrap);
        std::string error;
        // As a renderer's texture maker does, a failure is reported and the render goes on: a
        // shader that reads the texture then fails to compile, naming the file.
        if (!texture::MakeTexture(picture.string(), texture.string(), swrap, twrap, &error) && report) {
            const std::string& file = m.file.empty() ? desc.path : m.file;
            report->warning({file, m.line, m.column, diag::ReadLine(file, m.line)}, error);
        }
    }
}

}  // namespace

uint64_t SceneBytes(const PreparedScene& scene, int threads) {
    uint64_t bytes = scene.primitives.capacity() * sizeof(Primitive) +
                     scene.desc.primitives.capacity() * sizeof(PrimitiveDesc) + (scene.bvh ? scene.bvh->bytes() : 0);
    // Per primitive in a render: LazyTrees's slot, and per thread ThreadState's intersector slot.
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

Box DisplacedBox(const Primitive& prim, const glm::dvec3& eye, int cells) {
    return UnionBox(BoundCellsIn<vm::Interval>(prim, eye, cells));
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
        "\"cache\":{\"budget_mb\":%.1f,\"peak_mb\":%.2f,\"final_mb\":%.2f,\"nodes\":%llu,"
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
        static_cast<unsigned long long>(cache.nodes), static_cast<unsigned long long>(cache.lookups), hitRate,
        static_cast<unsigned long long>(cache.evaluations), static_cast<unsigned long long>(cache.privateCopies),
        static_cast<unsigned long long>(cache.evictions), static_cast<unsigned long long>(cache.evictionPasses),
        cache.buildSeconds, double(residentAtStartBytes) / (1 << 20), double(peakResidentBytes) / (1 << 20),
        double(sceneBytes) / (1 << 20), static_cast<unsigned long long>(primitives),
        primitives ? double(sceneBytes) / double(primitives) : 0.0, readSeconds, prepareSeconds);
    return buf;
}

namespace {

/// The image-pixels, pixel-samples and film-mb limits (diag/limits.h) for `camera`'s image with
/// the channels `displayMode` asks for; "" or the error.
std::string CheckImageLimits(const CameraDesc& camera, const std::string& displayMode) {
    using diag::Limit;
    const int64_t pixels = int64_t{camera.xres} * camera.yres;
    if (pixels > diag::LimitValue(Limit::ImagePixels))
        return "the image of " + std::to_string(camera.xres) + "x" + std::to_string(camera.yres) +
               " pixels is too large " + diag::LimitNote(Limit::ImagePixels);
    if (std::max(camera.xsamples, camera.ysamples) > diag::LimitValue(Limit::PixelSamples))
        return "the image has " + std::to_string(camera.xsamples) + "x" + std::to_string(camera.ysamples) +
               " samples per pixel, more than allowed " + diag::LimitNote(Limit::PixelSamples);
    DisplayChannels channels;
    std::string ignored;  // an unknown mode is reported where the image is made
    ParseDisplayMode(displayMode, &channels, &ignored);
    const int64_t floats = 4 + static_cast<int64_t>(ChannelNames(channels).size());
    const int64_t mb = (pixels * floats * int64_t{sizeof(float)} + (int64_t{1} << 20) - 1) >> 20;
    if (mb > diag::LimitValue(Limit::FilmMb))
        return "the film needs " + std::to_string(mb) + " MiB for " + std::to_string(pixels) + " pixels of " +
               std::to_string(floats) + " channels " + diag::LimitNote(Limit::FilmMb);
    return {};
}

}  // namespace

bool PrepareScene(SceneDesc input, const std::vector<std::string>& shaderPaths,
                  const lang::PreprocessOptions& preprocess, PreparedScene* out, diag::Report* report, int threads) {
    // The meshes as read split and refined (scene/refine.h), several at once, before anything else.
    if (ThreadPool pool(threads); !RefineScene(&input, report, [&](size_t n, const std::function<void(size_t)>& body) {
            pool.ForEach(n, [&](size_t i, int) { body(i); });
        }))
        return false;
    auto fail = [&](const diag::Location& where, std::string message) {
        if (report) report->error(where, std::move(message));
        return false;
    };
    // Before anything is compiled or allocated.
    if (std::string problem = CheckImageLimits(input.camera, input.displayMode); !problem.empty())
        return fail({input.path}, std::move(problem));
    // Moved, not copied: a mesh of thousands of faces is as many PrimitiveDescs.
    out->desc = std::move(input);
    const SceneDesc& desc = out->desc;
    out->primitives.clear();
    out->programs.clear();  // (a PreparedScene prepared again holds only its new programs)
    out->identityDigest.clear();
    MakeTextures(desc, report);
    const glm::dvec3 eye = Camera(desc.camera).Position();
    compiler::ShaderCache cache;
    // The scene's search path first, relative directories taken from the RIB file's.
    std::vector<std::string> searchPath;
    for (const std::string& dir : desc.shaderSearchPath) searchPath.push_back(FromSceneDir(desc, dir));
    searchPath.insert(searchPath.end(), shaderPaths.begin(), shaderPaths.end());
    // The distinct light lists of the primitives (Illuminate), numbered in order of first use
    // after set 0, every light.
    std::map<std::vector<int>, int> lightSetKeys;
    std::vector<int> allLights(desc.lights.size());
    for (size_t i = 0; i < allLights.size(); ++i) allLights[i] = static_cast<int>(i);
    lightSetKeys[allLights] = 0;
    auto lightSetOf = [&](const PrimitiveAttributes& p) {
        if (!p.lights) return 0;
        std::vector<int> key;
        for (int light : *p.lights)
            if (light >= 0 && static_cast<size_t>(light) < desc.lights.size()) key.push_back(light);
        std::sort(key.begin(), key.end());
        key.erase(std::unique(key.begin(), key.end()), key.end());
        return lightSetKeys.emplace(key, static_cast<int>(lightSetKeys.size())).first->second;
    };
    std::map<std::string, std::string> shaderFiles;  // shader name -> its file ("" if not found)
    // Where a Displacement request is in the RIB file (its line is read again only for a message).
    auto requestAt = [&](const ShaderRef& ref) {
        const std::string& file = ref.file.empty() ? desc.path : ref.file;
        return diag::Location(file, ref.line, ref.column, diag::ReadLine(file, ref.line));
    };
    // Each request's attributes (shared by its primitives: a mesh's faces) are looked at once:
    // the shader instance compiled, its generic programs and the lights.
    struct Instance {
        std::shared_ptr<const compiler::CompiledShader> shader;  // null: no displacement (the identity)
        int lightSet = 0;
        /// The programs of the primitives whose surfaces have no constants beyond E, du, dv
        /// (every kind but the bilinear patch), once made.
        const PrimitivePrograms* general = nullptr;
    };
    std::unordered_map<const PrimitiveAttributes*, Instance> instances;
    const vm::Program identity = vm::IdentityProgram();
    // Specialising a program for a surface's constant globals (below) gives the same program for
    // every surface with the same constants (E, du and dv for all but flat bilinear patches): made
    // once per shader instance and constants, shared by the others.
    std::map<std::pair<const void*, std::vector<uint64_t>>, const PrimitivePrograms*> specialised;
    auto specialise = [&](const Instance& instance, const BaseSurface& base) {
        const std::vector<compiler::ConstantGlobal> constants = ConstantGlobals(base, eye);
        // (The values by their bits: the same bits fold to the same program, a NaN included.)
        std::pair<const void*, std::vector<uint64_t>> key{instance.shader.get(), {}};
        for (const compiler::ConstantGlobal& c : constants) {
            key.second.push_back(static_cast<uint64_t>(c.global));
            for (double x : c.value) key.second.push_back(std::bit_cast<uint64_t>(x));
        }
        auto [found, added] = specialised.try_emplace(std::move(key), nullptr);
        if (added) {
            std::vector<std::string> unused;  // no overrides here: nothing can go wrong
            const vm::Program& bound = instance.shader ? instance.shader->bound : identity;
            const vm::Program& shade = instance.shader ? instance.shader->shade : identity;
            out->programs.push_back({instance.shader, *compiler::Specialise(bound, {}, &unused, constants),
                                     *compiler::Specialise(shade, {}, &unused, constants)});
            found->second = &out->programs.back();
        }
        return found->second;
    };
    size_t elements = 0;
    for (const PrimitiveDesc& p : desc.primitives) elements += p.elements;
    out->primitives.reserve(elements);
    for (const PrimitiveDesc& patch : desc.primitives) {
        if (patch.unrefined) throw std::logic_error("PrepareScene: a mesh left unrefined (RefineScene)");
        const PrimitiveAttributes& attributes = *patch.attributes;
        auto [entry, newAttributes] = instances.try_emplace(&attributes);
        Instance& instance = entry->second;
        if (newAttributes) {
            instance.lightSet = lightSetOf(attributes);
            // The shader's file, looked up once per name; a shader that is not found leaves the
            // surface undisplaced, as prman does, with one warning per name (a scene exported with
            // shaders its renderer had but this machine has not).
            std::string path;
            if (attributes.displacement) {
                const ShaderRef& ref = *attributes.displacement;
                auto [known, added] = shaderFiles.try_emplace(ref.name);
                if (added) {
                    known->second = FindShader(ref.name, searchPath);
                    if (known->second.empty() && report) {
                        std::string searched;
                        for (const std::string& p : searchPath) searched += (searched.empty() ? "" : ", ") + p;
                        report->warning(requestAt(ref), "shader '" + ref.name + "' not found (searched " + searched +
                                                            "); its surfaces render undisplaced");
                    }
                }
                path = known->second;
            }
            if (!path.empty()) {
                const ShaderRef& ref = *attributes.displacement;
                auto where = [&] { return requestAt(ref); };
                std::vector<compiler::ParamOverride> overrides;
                for (const ParamValue& p : ref.params) {
                    if (p.strings.size() > 1)
                        return fail(where(), "parameter '" + p.name + "' takes one string, got " +
                                                 std::to_string(p.strings.size()));
                    if (p.strings.empty())
                        overrides.emplace_back(p.name, p.numbers);
                    else
                        overrides.push_back(compiler::ParamOverride::String(p.name, p.strings[0]));
                }
                const compiler::Spaces spaces = SpacesOf(desc, attributes);
                const compiler::SceneFacts facts = FactsOf(desc, attributes);
                compiler::CompileResult result = cache.Load(path, overrides, preprocess, &spaces, &facts);
                // The shader's own diagnostics (its warnings too), then what the scene asked of it.
                if (report) report->add(result.diagnostics);
                if (!result.ok()) {
                    for (const std::string& e : result.paramErrors) fail(where(), e);
                    if (result.paramErrors.empty()) fail(where(), "cannot compile shader '" + ref.name + "'");
                    return false;
                }
                instance.shader = result.shader;
                for (const std::string& name : instance.shader->genericBound.spaces) {
                    if (spaces.count(name) && !IsAffine(spaces.at(name).toCurrent))
                        return fail(where(), "shader '" + ref.name + "' uses coordinate space '" + name +
                                                 "', which the scene makes projective (not supported)");
                }
            }
        }
        Primitive prim;
        prim.desc = &patch;
        prim.lightSet = instance.lightSet;
        if (patch.base.kind() == BaseSurface::Kind::BilinearPatch) {
            prim.programs = specialise(instance, patch.base);
        } else {
            if (!instance.general) instance.general = specialise(instance, patch.base);
            prim.programs = instance.general;
        }
        // A mesh's pieces or patches: one primitive each, the same but for the element.
        for (uint32_t e = 0; e < patch.elements; ++e) {
            prim.element = e;
            out->primitives.push_back(prim);
        }
    }

    // Each primitive's box, and the check that its displaced surface can be bounded somewhere:
    // a shader run over a grid of cells per primitive, the costly part of preparing a scene of
    // many primitives, spread over the machine's threads (each primitive on its own).
    const int cells = GridCellsFor(out->primitives.size());
    std::vector<std::string> problems(out->primitives.size());
    std::vector<Box> boxes(out->primitives.size());
    std::atomic<size_t> next{0};
    auto boxWorker = [&] {
        for (size_t i = next++; i < out->primitives.size(); i = next++) {
            Primitive& prim = out->primitives[i];
            const CellRanges intervalCells = BoundCellsIn<vm::Interval>(prim, eye, cells);
            if (prim.shader())  // a displacement whose shader was found
                problems[i] = UnboundedEverywhere(prim, *prim.attributes().displacement, eye, cells, intervalCells);
            boxes[i] = UnionBox(intervalCells);
        }
    };
    const size_t cores = threads > 0 ? size_t(threads) : std::max(1u, std::thread::hardware_concurrency());
    const size_t nThreads = std::min<size_t>(cores, std::max<size_t>(1, out->primitives.size() / 16));
    std::vector<std::thread> workers;
    for (size_t t = 1; t < nThreads; ++t) workers.emplace_back(boxWorker);
    boxWorker();
    for (std::thread& t : workers) t.join();
    for (size_t i = 0; i < problems.size(); ++i) {
        if (problems[i].empty()) continue;
        return fail(requestAt(*out->primitives[i].attributes().displacement), problems[i]);
    }
    out->bvh = std::make_unique<Bvh>(boxes);
    out->shadersCompiled = cache.misses();
    out->shadersReused = cache.hits();
    out->lights = desc.lights;
    out->lightSets.resize(lightSetKeys.size());
    for (const auto& [key, index] : lightSetKeys)
        for (int light : key) out->lightSets[static_cast<size_t>(index)].push_back(desc.lights[size_t(light)]);
    if (out->lights.empty()) {
        // No lights: a key light from behind the camera, and a little ambient, so that something shows.
        glm::dmat4 cameraToWorld = glm::inverse(desc.camera.worldToCamera);
        glm::dvec3 eye = glm::dvec3(cameraToWorld * glm::dvec4(0, 0, 0, 1));
        glm::dvec3 forward = glm::dvec3(cameraToWorld * glm::dvec4(0, 0, 1, 0));
        LightDesc key;
        key.kind = LightDesc::Kind::Distant;
        key.castShadows = true;  // affray's own light, not a RenderMan one: it keeps the shadows it always had
        key.from = eye;
        key.to = eye + forward;
        out->lights.push_back(key);
        LightDesc ambient;
        ambient.kind = LightDesc::Kind::Ambient;
        ambient.intensity = 0.05;
        out->lights.push_back(ambient);
        out->lightSets = {out->lights};  // for every primitive, whatever its Illuminate said
    }
    return true;
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

SampleValue TraceSample(const PreparedScene& scene, ThreadState& ts, const Camera& camera, const glm::dvec2& raster,
                        const Tolerance& tol, const glm::dvec3& eye, const RayGroup* group) {
    SampleValue value;
    const Ray ray = camera.GenerateRay(raster.x, raster.y);
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
    for (int layer = 0; layer < kMaxLayers; ++layer) {
        const NearestHit nh = TraceNearest(scene, ts, ray, tMin, tMax, tol, ts.cameraStats, eye, group);
        if (nh.primitive < 0) break;
        const Primitive& prim = scene.primitives[nh.primitive];
        const HitPoint at = EvaluateHit(scene, ts, ray, nh, eye);
        const glm::dvec3 Os = prim.OpacityAt(nh.hit.u, nh.hit.v);
        value.rgb += through * Os * ShadeHit(scene, ts, ray, nh, at, tol);
        through *= 1.0 - Os;
        if (layer == 0) {
            value.z = (scene.desc.camera.worldToCamera * glm::dvec4(ray.origin + nh.hit.t * ray.dir, 1.0)).z;
            value.N = at.N;
            value.P = at.P;
            // The mesh's (u,v), which the shader saw: the hit's are the patch's own.
            const ParameterRange range = prim.desc->base.range;  // a patch's: never an element's own
            value.st = {range.U(nh.hit.u), range.V(nh.hit.v)};
            value.err = nh.hit.error;
        }
        if (through == glm::dvec3(0.0)) break;
        tMin = Beyond(nh.hit, tol);
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

int RenderThreads(const RenderOptions& options) {
    return options.threads > 0 ? options.threads : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
}

}  // namespace

int RenderTileSize(const CameraDesc& camera, const RenderOptions& options) {
    int tileSize = std::max(1, options.tileSize);
    if (options.fixedTileSize) return tileSize;
    // Smaller tiles for small images, so that every thread gets work (four tiles each at least),
    // down to 8 pixels: below that the filter margins each tile traces again cost too much.
    const Film film(camera);
    const int nThreads = RenderThreads(options);
    while (tileSize > 8 && static_cast<int>(film.Tiles(tileSize).size()) < 4 * nThreads) tileSize /= 2;
    return tileSize;
}

void RenderImage(const PreparedScene& scene, const RenderOptions& options, image::ImageBuffer* image,
                 RenderStats* stats) {
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
    const int nThreads = RenderThreads(options);
    std::vector<PixelRange> tiles = film.Tiles(RenderTileSize(cam, options));
    if (options.reverseTileOrder) std::reverse(tiles.begin(), tiles.end());
    if (options.progress) options.progress->Begin(static_cast<int>(tiles.size()));
    // Tiles an interrupted render finished come back from the store, and are not rendered again.
    int restored = 0;
    if (options.tileStore)
        std::erase_if(tiles, [&](const PixelRange& tile) {
            if (!options.tileStore->Restore(tile, image)) return false;
            ++restored;
            if (options.progress) options.progress->TileDone();
            return true;
        });
    auto stopped = [&] { return options.stop && options.stop->load(std::memory_order_relaxed); };

    std::atomic<size_t> nextTile{0}, tilesDone{0};
    std::vector<IntersectStats> cameraStats(nThreads), shadowStats(nThreads);
    std::vector<uint64_t> cameraRays(nThreads);
    // One bound hierarchy per primitive, shared by every thread and ray of this render.
    CacheBudget budget(options.cacheBytes);
    LazyTrees trees(scene, options, eye, &budget);
    const std::vector<double> toleranceScales = ToleranceScales(scene, options);
    const int side = options.rayGroupPixels;
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
                    values[k] = TraceSample(scene, ts, camera, samples[k].raster, tol, eye, nullptr);
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
                    values[k] = TraceSample(scene, ts, camera, p, tol, eye, inBlock ? &group : nullptr);
                }
            }
            // A stopped tile's samples are incomplete: it is left out, neither resolved nor kept.
            if (stopped()) break;
            film.ResolveTile(tiles[i], samples, values, image);
            if (options.tileStore) options.tileStore->Finished(tiles[i], *image);
            ++tilesDone;
            if (options.progress) options.progress->TileDone();
        }
        cameraStats[index] = ts.cameraStats;
        shadowStats[index] = ts.shadowStats;
        cameraRays[index] = ts.cameraRays;
    };
    std::vector<std::thread> threads;
    for (int i = 1; i < nThreads; ++i) threads.emplace_back(worker, i);
    worker(0);
    for (std::thread& t : threads) t.join();
    if (options.progress) options.progress->Finish();

    *stats = RenderStats();
    trees.Merge(&stats->cache);
    stats->cache.evictionPasses = budget.passes();  // one pass serves every tree (none if none was made)
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
