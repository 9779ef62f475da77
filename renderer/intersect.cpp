// renderer/intersect.cpp: region subdivision, the bound-versus-ray test and the nearest-first
// traversal, written once for every bounding number type.
//
// The test (DESIGN.md, decision 5): pick two unit normals n1, n2 perpendicular to the ray and to
// each other; the planes through the ray origin with these normals both contain the ray. For the
// displaced point P' over a region, d1 = n1.(P'-o), d2 = n2.(P'-o) and t = d.(P'-o) are affine
// forms; a surface point on the ray needs d1 = d2 = 0, so if either range excludes 0 the region
// is missed. Because the forms share the symbols of u and v, a smooth surface gives much tighter
// d1, d2 than an axis-aligned box of P' would.
//
// Tape pruning (DESIGN.md, decision 3): each region on the stack names the program valid over it,
// the one its children are bounded with: the program its parent used, or that program pruned by
// what the region's own bound decided. Programs live in a pool of slots reused across rays, with
// a count of the regions naming them; a region is a subset of its parent, so a program pruned for
// it stays valid for all its descendants.
#include "renderer/intersect.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "vm/prune.h"

namespace affray::renderer {

void IntersectStats::Merge(const IntersectStats& o) {
    rays += o.rays;
    regionsBounded += o.regionsBounded;
    maxRegionsPerRay = std::max(maxRegionsPerRay, o.maxRegionsPerRay);
    depthLimitHits += o.depthLimitHits;
    budgetExhausted += o.budgetExhausted;
    maxHitError = std::max(maxHitError, o.maxHitError);
    instructionsBounded += o.instructionsBounded;
    programsPruned += o.programsPruned;
}

PruneOptions PruneOptions::FromEnvironment() {
    PruneOptions options;
    if (const char* on = std::getenv("AFFRAY_PRUNE")) options.enabled = std::strcmp(on, "0") != 0;
    if (const char* depth = std::getenv("AFFRAY_PRUNE_DEPTH")) options.minDepth = std::atoi(depth);
    return options;
}

namespace {

/// A region with its bound, measured in the ray's frame.
struct Region {
    double u0, u1, v0, v1;
    int depth;
    double tLo, tHi;
    double size;  // diagonal of the bound in the ray frame; infinite if unbounded
    int program;  // slot of the program valid over the region (kRootProgram: the full one)
};

constexpr int kRootProgram = -1;
constexpr int kNoProgram = -2;

template <class N>
class SurfaceIntersectorT final : public SurfaceIntersector {
  public:
    SurfaceIntersectorT(const BaseSurface& surface, const vm::Program& program, const glm::dvec3& eye, int maxDepth,
                        const PruneOptions& prune, uint64_t budget)
        : m_surface(surface),
          m_root(&program),
          m_interp(program),
          m_output(program.findOutput("P") - program.outputs.data()),
          m_eye(eye),
          m_maxDepth(maxDepth),
          m_budget(budget),
          m_prune(prune) {
        m_stack.reserve(4 * static_cast<size_t>(maxDepth) + 8);
    }

    bool Intersect(const Ray& ray, double tMin, double tMax, const Tolerance& tolerance, bool anyHit, Hit* hit,
                   IntersectStats& stats) override;

  private:
    /// Bounds the region and measures it against the ray; false if it provably misses.
    bool BoundRegion(Region& r, double tMin, double tMax);
    /// The ray parameter of the point of the ray nearest to the surface point at (u, v); false if
    /// the surface is undefined (not finite) there.
    bool PointAlongRay(double u, double v, double* t);

    const vm::Program& ProgramOf(int slot) const { return slot == kRootProgram ? *m_root : m_pool[slot]->program; }
    /// Makes the interpreter run the program in `slot`.
    void Use(int slot);
    /// The program for the children of `r`, just bounded by the program in `parent`: a new slot
    /// pruned by the decisions of that bound if worthwhile, else `parent`; held once more.
    int ProgramFor(const Region& r, int parent, const Tolerance& tolerance);
    void Hold(int slot) {
        if (slot != kRootProgram) ++m_pool[slot]->holders;
    }
    void Release(int slot) {
        if (slot != kRootProgram && --m_pool[slot]->holders == 0) m_free.push_back(slot);
    }

    BaseSurface m_surface;
    const vm::Program* m_root;
    vm::Interpreter<N> m_interp;
    ptrdiff_t m_output;  // index of P among the outputs, the same in every pruned program
    glm::dvec3 m_eye;
    int m_maxDepth;
    uint64_t m_budget;
    std::vector<Region> m_stack;
    // The current ray's frame.
    glm::dvec3 m_origin, m_dir, m_n1, m_n2;
    uint64_t m_bounded = 0;
    // Tape pruning: the pool of pruned programs (kept across rays, so that their vectors keep
    // their capacity), the free slots, the slot the interpreter runs.
    struct Slot {
        vm::Program program;
        int holders = 0;
    };
    PruneOptions m_prune;
    vm::Pruner m_pruner;
    std::vector<std::unique_ptr<Slot>> m_pool;
    std::vector<int> m_free;
    int m_current = kRootProgram;
    uint64_t m_instructions = 0, m_pruned = 0;
};

template <class N>
void SurfaceIntersectorT<N>::Use(int slot) {
    if (slot == m_current) return;
    m_interp.SetProgram(ProgramOf(slot));
    m_current = slot;
}

template <class N>
int SurfaceIntersectorT<N>::ProgramFor(const Region& r, int parent, const Tolerance& tolerance) {
    // A region that will not be split needs no program of its own.
    const bool leaf = r.size <= tolerance.At(r.tLo) || r.depth >= m_maxDepth;
    const vm::Program& from = ProgramOf(parent);
    if (!m_prune.enabled || leaf || r.depth < m_prune.minDepth || m_interp.decisions().usefulCount(from) == 0) {
        Hold(parent);
        return parent;
    }
    if (m_free.empty()) {
        m_pool.push_back(std::make_unique<Slot>());
        m_free.push_back(static_cast<int>(m_pool.size()) - 1);
    }
    const int slot = m_free.back();
    vm::Program& pruned = m_pool[slot]->program;
    m_pruner.Prune(from, m_interp.decisions(), &pruned);
    if (slot == m_current) m_current = kNoProgram;  // its program changed under the interpreter
    if (static_cast<double>(pruned.code.size()) > m_prune.keepRatio * static_cast<double>(from.code.size())) {
        Hold(parent);
        return parent;
    }
    m_free.pop_back();
    m_pool[slot]->holders = 1;
    ++m_pruned;
    return slot;
}

template <class N>
bool SurfaceIntersectorT<N>::BoundRegion(Region& r, double tMin, double tMax) {
    ++m_bounded;
    m_instructions += m_interp.program().code.size();
    m_interp.SetRecording(m_prune.enabled && r.depth >= m_prune.minDepth);
    Vec3<N> p = EvaluateOnSurface(m_interp, m_surface, r.u0, r.u1, r.v0, r.v1, m_eye, m_interp.program().outputs[m_output]);
    using T = std::decay_t<decltype(vm::ValueOf(p.x))>;
    Vec3<T> rel{vm::ValueOf(p.x) - m_origin.x, vm::ValueOf(p.y) - m_origin.y, vm::ValueOf(p.z) - m_origin.z};
    // n.(P' - o), leaving out the components n does not weigh: an unbounded coordinate along
    // which the ray frame does not measure must not make the others unmeasurable.
    auto along = [&](const glm::dvec3& n) {
        T sum(0.0);
        for (int i = 0; i < 3; ++i)
            if (n[i] != 0) sum = sum + rel[i] * n[i];
        return sum;
    };
    const T d1Form = along(m_n1), d2Form = along(m_n2);
    vm::Interval d1 = RangeOf(d1Form), d2 = RangeOf(d2Form), t = RangeOf(along(m_dir));
    // Each bounded measure may rule the region out on its own, even if another is unbounded.
    auto excludesZero = [](const vm::Interval& d) { return !d.isUnbounded() && (d.lo() > 0 || d.hi() < 0); };
    if (excludesZero(d1) || excludesZero(d2)) return false;
    if constexpr (std::is_same_v<T, vm::Affine>) {
        // In the plane across the ray, (d1, d2) spans a zonotope whose longest edges are the
        // generators of eps_u and eps_v; the ray misses the region if a line along one of them
        // separates the zonotope from the origin. Steep walls seen obliquely give long thin
        // zonotopes that the two fixed axes d1, d2 cannot separate until the regions are tiny
        // (docs/stiff.md: amplitude 1000 at 60 degrees, 24689 regions per ray without this).
        if (!d1.isUnbounded() && !d2.isUnbounded())
            for (vm::Affine::SymbolId symbol : {vm::Affine::kSymbolU, vm::Affine::kSymbolV}) {
                const double a = d1Form.coefficientOf(symbol), b = d2Form.coefficientOf(symbol);
                if (a == 0 && b == 0) continue;
                if (excludesZero(RangeOf(d1Form * (-b) + d2Form * a))) return false;
            }
    }
    if (!t.isUnbounded() && (t.hi() < tMin || t.lo() > tMax)) return false;
    if (d1.isUnbounded() || d2.isUnbounded() || t.isUnbounded()) {
        // Not ruled out by the ray frame. The coordinates of P' that are still bounded give a
        // box (unbounded along the others), which the ray crosses over a range of t or misses:
        // around a singular point of the shader (log(0), 1/0) this keeps the regions that can
        // still reach the ray to the few it passes, instead of all of them.
        double lo = t.isUnbounded() ? tMin : std::max(t.lo(), tMin);
        double hi = t.isUnbounded() ? tMax : std::min(t.hi(), tMax);
        for (int i = 0; i < 3; ++i) {
            vm::Interval c = RangeOf(rel[i]);  // the coordinate relative to the ray's origin
            if (c.isUnbounded()) continue;
            if (m_dir[i] == 0) {
                if (c.lo() > 0 || c.hi() < 0) return false;
                continue;
            }
            double t0 = c.lo() / m_dir[i], t1 = c.hi() / m_dir[i];
            if (t0 > t1) std::swap(t0, t1);
            // Widened by a few ulps: the divisions round.
            lo = std::max(lo, t0 - 4e-16 * std::fabs(t0));
            hi = std::min(hi, t1 + 4e-16 * std::fabs(t1));
        }
        if (lo > hi) return false;
        r.tLo = lo;
        r.tHi = hi;
        r.size = INFINITY;
        return true;
    }
    r.tLo = t.lo();
    r.tHi = t.hi();
    double w1 = d1.hi() - d1.lo(), w2 = d2.hi() - d2.lo(), wt = t.hi() - t.lo();
    r.size = std::sqrt(w1 * w1 + w2 * w2 + wt * wt) * (1 + 1e-15);
    return true;
}

template <class N>
bool SurfaceIntersectorT<N>::PointAlongRay(double u, double v, double* t) {
    // The full program, so that this fallback does not depend on pruning.
    Use(kRootProgram);
    Vec3<N> p = EvaluateOnSurface(m_interp, m_surface, u, u, v, v, m_eye, m_interp.program().outputs[m_output]);
    glm::dvec3 center;
    for (int i = 0; i < 3; ++i) {
        vm::Interval r = RangeOf(vm::ValueOf(p[i]));
        if (r.isUnbounded()) return false;
        center[i] = r.mid();
    }
    *t = glm::dot(center - m_origin, m_dir);
    return std::isfinite(*t);
}

template <class N>
bool SurfaceIntersectorT<N>::Intersect(const Ray& ray, double tMin, double tMax, const Tolerance& tolerance,
                                     bool anyHit, Hit* hit, IntersectStats& stats) {
    m_origin = ray.origin;
    m_dir = ray.dir;
    // Any unit vector perpendicular to the ray, then a third completing the frame.
    glm::dvec3 helper = std::abs(m_dir.x) < 0.6 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
    m_n1 = glm::normalize(glm::cross(m_dir, helper));
    m_n2 = glm::normalize(glm::cross(m_dir, m_n1));
    m_bounded = 0;
    m_instructions = 0;
    m_pruned = 0;
    m_stack.clear();
    // Every program of the last ray is free again (an early exit leaves regions unreleased).
    m_free.clear();
    for (int i = static_cast<int>(m_pool.size()) - 1; i >= 0; --i) {
        m_pool[i]->holders = 0;
        m_free.push_back(i);
    }

    double best = tMax;
    bool found = false;
    Region root{0, 1, 0, 1, 0, 0, 0, 0, kRootProgram};
    Use(kRootProgram);
    if (BoundRegion(root, tMin, best)) {
        root.program = ProgramFor(root, kRootProgram, tolerance);
        m_stack.push_back(root);
    }

    while (!m_stack.empty()) {
        if (m_bounded >= m_budget) {
            // Out of budget (a shader too stiff to resolve at this tolerance, or bounds that
            // overflow everywhere): the nearest region left is a possible hit, uncertified, unless
            // a hit already found is nearer. Better a counted, visible approximation than a hang.
            ++stats.budgetExhausted;
            const Region* nearest = nullptr;
            for (const Region& r : m_stack)
                if (r.tLo <= best && (!nearest || r.tLo < nearest->tLo)) nearest = &r;
            if (nearest) {
                best = std::max(nearest->tLo, tMin);
                found = true;
                *hit = Hit{best, 0.5 * (nearest->u0 + nearest->u1), 0.5 * (nearest->v0 + nearest->v1), nearest->size,
                           true};
            }
            break;
        }
        Region r = m_stack.back();
        m_stack.pop_back();
        if (r.tLo > best) {  // a nearer hit was found since this region was bounded
            Release(r.program);
            continue;
        }

        bool small = r.size <= tolerance.At(r.tLo);
        bool atLimit = r.depth >= m_maxDepth;
        if (small || atLimit) {
            Release(r.program);
            double uc = 0.5 * (r.u0 + r.u1), vc = 0.5 * (r.v0 + r.v1);
            double tHit, error;
            if (std::isfinite(r.size)) {
                // The bound's t range meets [tMin, best] (checked when bounded and popped).
                tHit = std::clamp(0.5 * (r.tLo + r.tHi), std::max(r.tLo, tMin), std::min(r.tHi, best));
                error = r.size;
            } else {
                // Unbounded down to the depth limit: nothing rules a hit out, so this is a possible
                // hit (counted, with no certificate), placed where the ray passes the surface
                // point at the region's centre. Only rays that cross the box of the region's
                // bounded coordinates get here (BoundRegion), so around a singular point (log(0))
                // these are the rays through its column, not every ray.
                if (!PointAlongRay(uc, vc, &tHit) || tHit < tMin || tHit > best) continue;
                error = INFINITY;
            }
            if (atLimit && !small) ++stats.depthLimitHits;
            best = tHit;
            found = true;
            *hit = Hit{tHit, uc, vc, error, atLimit && !small};
            if (anyHit) break;
            continue;
        }

        // Split in four, bound each child with the region's program (each child's own program
        // is chosen right after its bound, while the decisions are those of that bound), push the
        // survivors farthest first (popped nearest first).
        Use(r.program);
        double uMid = 0.5 * (r.u0 + r.u1), vMid = 0.5 * (r.v0 + r.v1);
        const int d = r.depth + 1;
        Region children[4] = {{r.u0, uMid, r.v0, vMid, d, 0, 0, 0, kRootProgram},
                              {uMid, r.u1, r.v0, vMid, d, 0, 0, 0, kRootProgram},
                              {r.u0, uMid, vMid, r.v1, d, 0, 0, 0, kRootProgram},
                              {uMid, r.u1, vMid, r.v1, d, 0, 0, 0, kRootProgram}};
        Region kept[4];
        int nKept = 0;
        for (Region& c : children)
            if (BoundRegion(c, tMin, best)) {
                c.program = ProgramFor(c, r.program, tolerance);
                kept[nKept++] = c;
            }
        Release(r.program);
        // Insertion sort, farthest first (four elements at most).
        for (int i = 1; i < nKept; ++i)
            for (int j = i; j > 0 && kept[j - 1].tLo < kept[j].tLo; --j) std::swap(kept[j - 1], kept[j]);
        for (int i = 0; i < nKept; ++i) m_stack.push_back(kept[i]);
    }

    ++stats.rays;
    stats.regionsBounded += m_bounded;
    stats.instructionsBounded += m_instructions;
    stats.programsPruned += m_pruned;
    stats.maxRegionsPerRay = std::max(stats.maxRegionsPerRay, m_bounded);
    if (found && std::isfinite(hit->error)) stats.maxHitError = std::max(stats.maxHitError, hit->error);
    return found;
}

}  // namespace

std::unique_ptr<SurfaceIntersector> MakeSurfaceIntersector(const BaseSurface& patch, const vm::Program& boundProgram,
                                                       const glm::dvec3& eye, BoundMode mode, int maxDepth,
                                                       const PruneOptions& prune, uint64_t regionBudget) {
    bool dual = boundProgram.usesDerivatives();
    if (mode == BoundMode::Affine) {
        if (dual)
            return std::make_unique<SurfaceIntersectorT<vm::Dual<vm::Affine>>>(patch, boundProgram, eye, maxDepth, prune, regionBudget);
        return std::make_unique<SurfaceIntersectorT<vm::Affine>>(patch, boundProgram, eye, maxDepth, prune, regionBudget);
    }
    if (dual)
        return std::make_unique<SurfaceIntersectorT<vm::Dual<vm::Interval>>>(patch, boundProgram, eye, maxDepth, prune, regionBudget);
    return std::make_unique<SurfaceIntersectorT<vm::Interval>>(patch, boundProgram, eye, maxDepth, prune, regionBudget);
}

}  // namespace affray::renderer
