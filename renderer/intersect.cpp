// renderer/intersect.cpp: region subdivision, the bound-versus-ray test and the nearest-first
// traversal, written once for every bounding number type.
//
// The test (DESIGN.md, decision 5): pick two unit normals n1, n2 perpendicular to the ray and to
// each other; the planes through the ray origin with these normals both contain the ray. For the
// displaced point P' over a region, d1 = n1.(P'-o), d2 = n2.(P'-o) and t = d.(P'-o) are affine
// forms; a surface point on the ray needs d1 = d2 = 0, so if either range excludes 0 the region
// is missed. Because the forms share the symbols of u and v, a smooth surface gives much tighter
// d1, d2 than an axis-aligned box of P' would.
#include "renderer/intersect.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace affray::renderer {

void IntersectStats::Merge(const IntersectStats& o) {
    rays += o.rays;
    regionsBounded += o.regionsBounded;
    maxRegionsPerRay = std::max(maxRegionsPerRay, o.maxRegionsPerRay);
    depthLimitHits += o.depthLimitHits;
    maxHitError = std::max(maxHitError, o.maxHitError);
}

namespace {

/// A region with its bound, measured in the ray's frame.
struct Region {
    double u0, u1, v0, v1;
    int depth;
    double tLo, tHi;
    double size;  // diagonal of the bound in the ray frame; infinite if unbounded
};

template <class N>
class PatchIntersectorT final : public PatchIntersector {
  public:
    PatchIntersectorT(const BilinearPatch& patch, const vm::Program& program, const glm::dvec3& eye, int maxDepth)
        : m_patch(patch), m_interp(program), m_output(program.findOutput("P")), m_eye(eye), m_maxDepth(maxDepth) {
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

    BilinearPatch m_patch;
    vm::Interpreter<N> m_interp;
    const vm::ProgramOutput* m_output;
    glm::dvec3 m_eye;
    int m_maxDepth;
    std::vector<Region> m_stack;
    // The current ray's frame.
    glm::dvec3 m_origin, m_dir, m_n1, m_n2;
    uint64_t m_bounded = 0;
};

template <class N>
bool PatchIntersectorT<N>::BoundRegion(Region& r, double tMin, double tMax) {
    ++m_bounded;
    Vec3<N> p = EvaluateOnPatch(m_interp, m_patch, r.u0, r.u1, r.v0, r.v1, m_eye, *m_output);
    using T = std::decay_t<decltype(vm::ValueOf(p.x))>;
    Vec3<T> rel{vm::ValueOf(p.x) - m_origin.x, vm::ValueOf(p.y) - m_origin.y, vm::ValueOf(p.z) - m_origin.z};
    // n.(P' - o), leaving out the components n does not weigh: an unbounded coordinate along
    // which the ray frame does not measure must not make the others unmeasurable.
    auto along = [&](const glm::dvec3& n) {
        T sum(0.0);
        for (int i = 0; i < 3; ++i)
            if (n[i] != 0) sum = sum + rel[i] * n[i];
        return RangeOf(sum);
    };
    vm::Interval d1 = along(m_n1), d2 = along(m_n2), t = along(m_dir);
    // Each bounded measure may rule the region out on its own, even if another is unbounded.
    auto excludesZero = [](const vm::Interval& d) { return !d.isUnbounded() && (d.lo() > 0 || d.hi() < 0); };
    if (excludesZero(d1) || excludesZero(d2)) return false;
    if (!t.isUnbounded() && (t.hi() < tMin || t.lo() > tMax)) return false;
    if (d1.isUnbounded() || d2.isUnbounded() || t.isUnbounded()) {
        // Not ruled out, not measurable: keep it, to be subdivided.
        r.tLo = t.isUnbounded() ? tMin : std::max(t.lo(), tMin);
        r.tHi = t.isUnbounded() ? tMax : t.hi();
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
bool PatchIntersectorT<N>::PointAlongRay(double u, double v, double* t) {
    Vec3<N> p = EvaluateOnPatch(m_interp, m_patch, u, u, v, v, m_eye, *m_output);
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
bool PatchIntersectorT<N>::Intersect(const Ray& ray, double tMin, double tMax, const Tolerance& tolerance,
                                     bool anyHit, Hit* hit, IntersectStats& stats) {
    m_origin = ray.origin;
    m_dir = ray.dir;
    // Any unit vector perpendicular to the ray, then a third completing the frame.
    glm::dvec3 helper = std::abs(m_dir.x) < 0.6 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
    m_n1 = glm::normalize(glm::cross(m_dir, helper));
    m_n2 = glm::normalize(glm::cross(m_dir, m_n1));
    m_bounded = 0;
    m_stack.clear();

    double best = tMax;
    bool found = false;
    Region root{0, 1, 0, 1, 0, 0, 0, 0};
    if (BoundRegion(root, tMin, best)) m_stack.push_back(root);

    while (!m_stack.empty()) {
        Region r = m_stack.back();
        m_stack.pop_back();
        if (r.tLo > best) continue;  // a nearer hit was found since this region was bounded

        bool small = r.size <= tolerance.At(r.tLo);
        bool atLimit = r.depth >= m_maxDepth;
        if (small || atLimit) {
            double uc = 0.5 * (r.u0 + r.u1), vc = 0.5 * (r.v0 + r.v1);
            double tHit, error;
            if (std::isfinite(r.size)) {
                // The bound's t range meets [tMin, best] (checked when bounded and popped).
                tHit = std::clamp(0.5 * (r.tLo + r.tHi), std::max(r.tLo, tMin), std::min(r.tHi, best));
                error = r.size;
            } else {
                // Unbounded down to the depth limit: nothing rules a hit out, so this is a possible
                // hit (counted, with no certificate), placed where the ray passes the surface
                // point at the region's centre.
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

        // Split in four, bound each child, push the survivors farthest first (popped nearest first).
        double uMid = 0.5 * (r.u0 + r.u1), vMid = 0.5 * (r.v0 + r.v1);
        Region children[4] = {{r.u0, uMid, r.v0, vMid, r.depth + 1, 0, 0, 0},
                              {uMid, r.u1, r.v0, vMid, r.depth + 1, 0, 0, 0},
                              {r.u0, uMid, vMid, r.v1, r.depth + 1, 0, 0, 0},
                              {uMid, r.u1, vMid, r.v1, r.depth + 1, 0, 0, 0}};
        Region kept[4];
        int nKept = 0;
        for (Region& c : children)
            if (BoundRegion(c, tMin, best)) kept[nKept++] = c;
        // Insertion sort, farthest first (four elements at most).
        for (int i = 1; i < nKept; ++i)
            for (int j = i; j > 0 && kept[j - 1].tLo < kept[j].tLo; --j) std::swap(kept[j - 1], kept[j]);
        for (int i = 0; i < nKept; ++i) m_stack.push_back(kept[i]);
    }

    ++stats.rays;
    stats.regionsBounded += m_bounded;
    stats.maxRegionsPerRay = std::max(stats.maxRegionsPerRay, m_bounded);
    if (found && std::isfinite(hit->error)) stats.maxHitError = std::max(stats.maxHitError, hit->error);
    return found;
}

}  // namespace

std::unique_ptr<PatchIntersector> MakePatchIntersector(const BilinearPatch& patch, const vm::Program& boundProgram,
                                                       const glm::dvec3& eye, BoundMode mode, int maxDepth) {
    bool dual = boundProgram.usesDerivatives();
    if (mode == BoundMode::Affine) {
        if (dual) return std::make_unique<PatchIntersectorT<vm::Dual<vm::Affine>>>(patch, boundProgram, eye, maxDepth);
        return std::make_unique<PatchIntersectorT<vm::Affine>>(patch, boundProgram, eye, maxDepth);
    }
    if (dual) return std::make_unique<PatchIntersectorT<vm::Dual<vm::Interval>>>(patch, boundProgram, eye, maxDepth);
    return std::make_unique<PatchIntersectorT<vm::Interval>>(patch, boundProgram, eye, maxDepth);
}

}  // namespace affray::renderer
