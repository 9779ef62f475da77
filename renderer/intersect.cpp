// renderer/intersect.cpp: the ray test of a cached region bound and the nearest-first walk of the
// bound hierarchy.
//
// The test (docs/design.md, decision 5): pick two unit normals n1, n2 perpendicular to the ray and to each
// other; the planes through the ray origin with these normals both contain the ray. Over a region,
// d1 = n1.(P'-o), d2 = n2.(P'-o) and t = dir.(P'-o) are affine in (eps_u, eps_v) up to a radius
// (Measure, from the node's RegionBound); a surface point on the ray needs d1 = d2 = 0, so if either
// range excludes 0 the region is missed. Beyond that:
//  - zonotope edges: in the plane across the ray, (d1, d2) spans a zonotope whose longest edges are
//    the generators of eps_u, eps_v (and the segment eps_w); a line along one of them may separate
//    it from the origin (steep walls seen obliquely: docs/stiff.md, amplitude 1000 at 60 degrees);
//  - the parallelogram: where the (d1, d2) part of (eps_u, eps_v) is invertible, the parameters at
//    which the thickened parallelogram can meet the ray lie in a small box E around the solution
//    of d1 = d2 = 0. The region's bound restricted to E is what the ray can reach: if it is empty
//    the region is missed, and if it is smaller than the tolerance the region is a hit there,
//    certified by that size, without subdividing further ("affine leaves": a smooth surface stops
//    levels earlier, since the parallelogram's thickness shrinks quadratically with the region).
//    Where bounds are costly (BoundTree::costlyBounds), a child's bound is evaluated only if
//    the parent's, restricted to the child's part of E, can still meet the ray (ChildrenMissed):
//    the parent's bound holds the child's points at their own parameters. Subdivision scene of
//    bench/real: 6 % fewer bounds evaluated; on the wave (one sine, 3.6 regions per ray) the
//    check, about a test per split, made the render 1.17 times slower, so cheap bounds skip it.
// Every quantity carries its rounding (kSlack, renderer/measure.h): a region is discarded only
// when its bound provably misses the ray.
//
// Coherent rays (RayGroup): the camera rays of a block of pixels lie between four planes. A node
// whose bound lies wholly outside one of them meets none of those rays, so the walk of the top
// levels is done once per block and primitive (BuildFrontier) and each ray of the block starts
// from the frontier it leaves, instead of from the root.
#include "renderer/intersect.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "renderer/measure.h"
#include "renderer/newton.h"

namespace affray::renderer {

void IntersectStats::Merge(const IntersectStats& o) {
    rays += o.rays;
    regionsBounded += o.regionsBounded;
    regionsEvaluated += o.regionsEvaluated;
    maxRegionsPerRay = std::max(maxRegionsPerRay, o.maxRegionsPerRay);
    depthLimitHits += o.depthLimitHits;
    budgetExhausted += o.budgetExhausted;
    parallelogramHits += o.parallelogramHits;
    newtonHits += o.newtonHits;
    newtonMisses += o.newtonMisses;
    newtonUnknown += o.newtonUnknown;
    maxHitError = std::max(maxHitError, o.maxHitError);
    frontiers += o.frontiers;
    frontierRegions += o.frontierRegions;
}

RayGroup RayGroup::FromCorners(const Ray (&corners)[4], uint64_t id) {
    RayGroup g;
    g.id = id;
    glm::dvec3 inside(0.0);
    for (const Ray& c : corners) {
        g.origin += 0.25 * c.origin;
        inside += 0.25 * (c.origin + c.dir);
    }
    g.spread0 = std::max(glm::length(corners[0].origin - corners[2].origin),
                         glm::length(corners[1].origin - corners[3].origin));
    g.spreadSlope =
        std::max(glm::length(corners[0].dir - corners[2].dir), glm::length(corners[1].dir - corners[3].dir));
    for (int i = 0; i < 4; ++i) {
        const Ray &a = corners[i], &b = corners[(i + 1) % 4];
        // The plane holding both rays: through a common origin (perspective) or along a common
        // direction (orthographic). Rays that share neither are skew: no plane, no culling.
        glm::dvec3 n(0.0);
        if (a.origin == b.origin)
            n = glm::cross(a.dir, b.dir);
        else if (a.dir == b.dir)
            n = glm::cross(a.dir, b.origin - a.origin);
        const double length = glm::length(n);
        if (!(length > 0) || !std::isfinite(length)) {
            for (int k = 0; k < 4; ++k) g.normal[k] = glm::dvec3(0.0), g.offset[k] = -INFINITY;
            return g;
        }
        n /= length;
        if (glm::dot(n, inside) < glm::dot(n, a.origin)) n = -n;
        g.normal[i] = n;
        g.offset[i] = glm::dot(n, a.origin);
    }
    return g;
}

bool RayGroup::Contains(const glm::dvec3& p, double slack) const {
    for (int i = 0; i < 4; ++i)
        if (glm::dot(normal[i], p) < offset[i] - slack) return false;
    return true;
}

namespace {

/// With certified Newton, a leaf it does not prove is a hit only below this fraction of the
/// tolerance (it is split until then).
constexpr double kUnprovedLeaf = 0.125;

/// Whether a line along the generator (p1, p2) of the (d1, d2) zonotope separates it from the
/// origin: the combination -p2 d1 + p1 d2 cancels that generator.
bool EdgeSeparates(const Measure& d1, const Measure& d2, double p1, double p2) {
    if (p1 == 0 && p2 == 0) return false;
    const double centre = -p2 * d1.c + p1 * d2.c;
    // The generator cancels exactly: -p2 * p1 + p1 * p2 == 0 in floating point too.
    const double gu = -p2 * d1.u + p1 * d2.u, gv = -p2 * d1.v + p1 * d2.v, gw = -p2 * d1.w + p1 * d2.w;
    const double a2 = std::fabs(p2), a1 = std::fabs(p1);
    const double rad = a2 * d1.rad + a1 * d2.rad;
    const double magnitude = a2 * (std::fabs(d1.c) + std::fabs(d1.u) + std::fabs(d1.v) + std::fabs(d1.w) + d1.rad) +
                             a1 * (std::fabs(d2.c) + std::fabs(d2.u) + std::fabs(d2.v) + std::fabs(d2.w) + d2.rad);
    const double spread = std::fabs(gu) + std::fabs(gv) + std::fabs(gw);
    const double total = spread + rad + 2 * kSlack * magnitude + 1e-300;
    return std::isfinite(total) && (centre - total > 0 || centre + total < 0);
}

/// The part [lo, hi] of [-1, 1] where eps can be; false if empty.
bool Clip(double centre, double radius, double* lo, double* hi) {
    *lo = std::max(-1.0, centre - radius);
    *hi = std::min(1.0, centre + radius);
    return *lo <= *hi;
}

/// The entry of the walk: a node with its region and its measure against the current ray.
struct Entry {
    BoundNode* node;
    double u0, u1, v0, v1;
    int levelU, levelV;  // times the region was halved along u and along v
    int axis;            // across which its children split it (SplitAxis of its bound)
    double tLo, tHi;
    double size;    // diagonal of the bound's reachable part in the ray frame; infinite if unbounded
    double hu, hv;  // where the ray meets the bound (parameters)
    bool narrowed;  // the parallelogram narrowed the reachable part below the whole region
    // The parameters where the ray can meet the surface within the region (the region itself
    // unless narrowed), widened by their rounding: children outside it are not looked at.
    double ru0, ru1, rv0, rv1;
    const RegionBound* bound;  // the bound it was measured with (valid for the rest of the ray)
};

/// The entry of the whole domain (not yet measured).
Entry RootEntry(BoundNode& root) {
    return Entry{&root, 0, 1, 0, 1, 0, 0, 0, 0, 0, 0, 0, 0, false, 0, 1, 0, 1, &root.bound};
}

/// How many children the split of `r` gives (2 across one parameter, 4 across both).
int ChildCount(const Entry& r) { return r.axis == kSplitBoth ? 4 : 2; }

/// Where child i of a region split by `axis` lies: which parameters the split halves and which
/// halves it takes. Child i: bit 0 the high half across the split parameter (u first), bit 1
/// high in v.
struct ChildSide {
    bool splitU, splitV, highU, highV;
};
ChildSide SideOf(int axis, int i) {
    const bool splitU = axis != kSplitV, splitV = axis != kSplitU;
    return {splitU, splitV, splitU && (i & 1), splitV && (splitU ? (i & 2) : (i & 1))};
}

/// Sets `c` to child i of `r` (SideOf): its node in `kids`, its region and levels (the rest is set
/// when it is measured).
void SetChild(const Entry& r, BoundNode* kids, int i, Entry* c) {
    const double uMid = 0.5 * (r.u0 + r.u1), vMid = 0.5 * (r.v0 + r.v1);
    const auto [splitU, splitV, highU, highV] = SideOf(r.axis, i);
    c->node = &kids[i];
    c->u0 = splitU && highU ? uMid : r.u0;
    c->u1 = splitU && !highU ? uMid : r.u1;
    c->v0 = splitV && highV ? vMid : r.v0;
    c->v1 = splitV && !highV ? vMid : r.v1;
    c->levelU = r.levelU + splitU;
    c->levelV = r.levelV + splitV;
}

/// Whether the bound lies wholly on the outer side of one of the group's planes: then no ray of
/// the group can meet it. Rounding makes it answer false, never a wrong true.
bool OutsideGroup(const RegionBound& b, const RayGroup& g) {
    for (int k = 0; k < 4; ++k) {
        const glm::dvec3& n = g.normal[k];
        if (!std::isfinite(g.offset[k])) return false;
        double boxHi = 0, centre = 0, rad = 0, nu = 0, nv = 0, nw = 0, magnitude = std::fabs(g.offset[k]);
        bool bounded = true;
        for (int i = 0; i < 3; ++i) {
            if (n[i] == 0) continue;
            if (!(b.boundedMask & (1u << i))) {
                bounded = false;
                break;
            }
            boxHi += n[i] > 0 ? n[i] * b.hi[i] : n[i] * b.lo[i];
            centre += n[i] * b.c[i];
            nu += n[i] * b.a[i];
            nv += n[i] * b.b[i];
            nw += n[i] * b.g[i];
            rad += std::fabs(n[i]) * b.r[i];
            magnitude += std::fabs(n[i]) * (std::fabs(b.lo[i]) + std::fabs(b.hi[i]) + std::fabs(b.c[i]) +
                                            std::fabs(b.a[i]) + std::fabs(b.b[i]) + std::fabs(b.g[i]) + b.r[i]);
        }
        if (!bounded) continue;
        const double formHi = centre + std::fabs(nu) + std::fabs(nv) + std::fabs(nw) + rad;
        const double most = std::min(boxHi, formHi) + kSlack * magnitude + 1e-300;
        if (std::isfinite(most) && most < g.offset[k]) return true;
    }
    return false;
}

/// The most nodes a group's frontier keeps: each of the group's rays tests all of them.
constexpr size_t kMaxFrontier = 32;

class TreeIntersector;

/// A node of a group's frontier: its entry (region, split) and its bound (a copy: the node's own
/// may be another thread's to publish).
struct FrontierNode {
    Entry entry;
    RegionBound bound;
};
}  // namespace

class IntersectWorkspace {
  public:
    std::vector<Entry> stack;  // a walk's, sized for the deepest tree of the thread
    std::shared_ptr<EvaluatorPool> pool = MakeEvaluatorPool();
    /// The ray group whose frontiers the thread's intersectors hold now, and those intersectors.
    /// A ray of another group releases them all: rays come block by block, so a thread keeps the
    /// frontiers of the primitives one block meets, not one per primitive its rays ever met
    /// (16,384 patches at 96x72, one thread: 5 MB less at the peak).
    uint64_t group = 0;
    std::vector<TreeIntersector*> holders;
    /// BuildFrontier's breadth-first queue, shared by the thread's intersectors.
    std::vector<FrontierNode> queue;
};

std::shared_ptr<IntersectWorkspace> MakeIntersectWorkspace() { return std::make_shared<IntersectWorkspace>(); }

namespace {

class TreeIntersector final : public SurfaceIntersector {
  public:
    TreeIntersector(BoundTree& tree, uint64_t budget, std::unique_ptr<BoundTree> owned = nullptr,
                    std::shared_ptr<IntersectWorkspace> workspace = nullptr)
        : m_owned(std::move(owned)),
          m_tree(tree),
          m_walker(tree),
          m_workspace(workspace ? std::move(workspace) : MakeIntersectWorkspace()),
          m_evaluator(tree.MakeEvaluator(m_workspace->pool)),
          m_budget(budget),
          m_stack(m_workspace->stack) {
        // Each of the at most 2 * maxDepth splits on a ray's path leaves at most 3 siblings behind.
        const size_t need = kMaxFrontier + 6 * static_cast<size_t>(std::max(tree.maxDepth(), 0)) + 8;
        if (m_stack.size() < need) m_stack.resize(need);
    }

    bool Intersect(const Ray& ray, double tMin, double tMax, const Tolerance& tolerance, bool anyHit, Hit* hit,
                   IntersectStats& stats, const RayGroup* group) override;

    ~TreeIntersector() override {
        std::vector<TreeIntersector*>& holders = m_workspace->holders;
        holders.erase(std::remove(holders.begin(), holders.end(), this), holders.end());
    }

    /// Frees the frontier (IntersectWorkspace::holders).
    void ReleaseFrontier() {
        m_frontier = {};
        m_groupId = 0;
    }

  private:
    /// The frontier of `group`: the nodes, at most kMaxFrontier, whose regions hold every point
    /// of the surface that a ray of the group can meet, found by splitting from the root while the
    /// group's planes cull children. A function of the group and the node bounds alone (whatever
    /// the cache held), so every ray's result is too. Built within a ray (the walker entered);
    /// its nodes stay valid for the group's later rays while the walker's epoch is the same, and
    /// it is built again otherwise.
    void BuildFrontier(const RayGroup& group, IntersectStats& stats);
    /// Measures the entry's bound `b` against the ray, its surface points on the ray known to lie
    /// at t >= from (the ray's start, or where its parent's begin): e.tLo and e.tHi are clipped to
    /// that, and are a function of the region and `from` alone. False if it provably misses, or
    /// if it lies beyond `best` (e.tLo > best: no hit in it or below it can be at best or nearer).
    bool Test(Entry& e, const RegionBound& b, double from, double best);
    /// The children of the measured entry `e`, split by e.axis, that the ray provably misses by
    /// e's bound over each child's part of the parameters where that bound can meet the ray (the
    /// bound holds every child's points at their own parameters), or that lie wholly beyond
    /// `best`: bit i for child i. Their bounds need not be evaluated. childLo[i] gets where the
    /// others' points on the ray begin, at least e.tLo.
    uint8_t ChildrenMissed(const Entry& e, double best, double childLo[4]) const;
    /// The ray's t range through the box of the bound's bounded coordinates, within [lo, hi]
    /// (narrowed); false if it misses.
    bool BoxRange(const RegionBound& b, double* lo, double* hi) const;

    std::unique_ptr<BoundTree> m_owned;  // the tree, when this intersector has one of its own
    BoundTree& m_tree;
    BoundTree::Walker m_walker;
    std::shared_ptr<IntersectWorkspace> m_workspace;
    std::unique_ptr<RegionEvaluator> m_evaluator;
    uint64_t m_budget;
    std::vector<Entry>& m_stack;  // the workspace's, [0, m_top) during a walk (entries not initialised)
    size_t m_top = 0;
    // The current ray's frame.
    glm::dvec3 m_origin, m_dir, m_n1, m_n2, m_invDir;
    glm::dvec3 m_frame[3];  // n1, n2, dir
    uint64_t m_tested = 0, m_evaluated = 0;
    // The current group's frontier.
    uint64_t m_groupId = 0, m_groupEpoch = 0;
    std::vector<FrontierNode> m_frontier;
};

void TreeIntersector::BuildFrontier(const RayGroup& group, IntersectStats& stats) {
    m_groupId = group.id;
    m_groupEpoch = m_walker.epoch();
    m_frontier.clear();
    std::vector<FrontierNode>& queue = m_workspace->queue;
    queue.clear();
    ++stats.frontiers;
    const int maxDepth = m_tree.maxDepth();
    Entry root = RootEntry(m_tree.root());
    const RegionBound& rootBound = m_tree.root().bound;
    root.axis = SplitAxis(rootBound, 0, 0, maxDepth);
    if (!OutsideGroup(rootBound, group)) queue.push_back({root, rootBound});
    // Breadth first: a node is split while its children fit in the frontier and it is wider than
    // the group where it lies (smaller nodes overlap the group's edges and cull little).
    for (size_t head = 0; head < queue.size(); ++head) {
        const FrontierNode n = queue[head];
        const Entry& e = n.entry;
        bool split = e.levelU < maxDepth || e.levelV < maxDepth;
        if (split && n.bound.bounded()) {
            const glm::dvec3 nearest = glm::clamp(group.origin, n.bound.lo, n.bound.hi);
            const double distance = glm::length(nearest - group.origin);
            const glm::dvec3 extent = n.bound.hi - n.bound.lo;
            const double width = std::max({extent.x, extent.y, extent.z});
            split = width > group.spread0 + group.spreadSlope * distance;
        }
        if (split) {
            BoundNode* kids = m_walker.Children(*e.node);
            FrontierNode kept[4];
            int nKept = 0;
            for (int i = 0; i < ChildCount(e); ++i) {
                Entry c = e;
                SetChild(e, kids, i, &c);
                const RegionBound& b = m_walker.Bound(kids[i], c.u0, c.u1, c.v0, c.v1, *m_evaluator, &m_evaluated);
                ++stats.frontierRegions;
                if (OutsideGroup(b, group)) continue;
                c.axis = SplitAxis(b, c.levelU, c.levelV, maxDepth);
                kept[nKept++] = {c, b};
            }
            if (m_frontier.size() + (queue.size() - head - 1) + size_t(nKept) <= kMaxFrontier) {
                for (int i = 0; i < nKept; ++i) queue.push_back(kept[i]);
                continue;
            }
        }
        m_frontier.push_back(n);
    }
}

bool TreeIntersector::BoxRange(const RegionBound& b, double* lo, double* hi) const {
    for (int i = 0; i < 3; ++i) {
        if (!(b.boundedMask & (1u << i))) continue;
        const double c0 = b.lo[i] - m_origin[i], c1 = b.hi[i] - m_origin[i];
        // The subtractions round: widen by an ulp of each operand.
        const double slack = 2 * kUlp * (std::fabs(b.lo[i]) + std::fabs(b.hi[i]) + std::fabs(m_origin[i]));
        if (m_dir[i] == 0) {
            if (c0 - slack > 0 || c1 + slack < 0) return false;
            continue;
        }
        double t0 = (c0 - slack) * m_invDir[i], t1 = (c1 + slack) * m_invDir[i];
        if (t0 > t1) std::swap(t0, t1);
        // Widened by a few ulps: the reciprocal and the products round (1.5 ulp at most).
        *lo = std::max(*lo, t0 - 4 * kUlp * std::fabs(t0));
        *hi = std::min(*hi, t1 + 4 * kUlp * std::fabs(t1));
    }
    return *lo <= *hi;
}

bool TreeIntersector::Test(Entry& e, const RegionBound& b, double from, double best) {
    ++m_tested;
    e.hu = 0.5 * (e.u0 + e.u1);
    e.hv = 0.5 * (e.v0 + e.v1);
    e.narrowed = false;
    e.ru0 = e.u0;
    e.ru1 = e.u1;
    e.rv0 = e.v0;
    e.rv1 = e.v1;
    // [lo, hi] narrows to where the region's points on the ray can be, never by `best`: the
    // region's range, and so its hit (Intersect), does not depend on the hits found before it
    // (in this primitive or, through tMax, in others). `best` only discards, where lo, which
    // every later value of e.tLo is at least, lies beyond it.
    double lo = from, hi = INFINITY;
    // The box first: cheap, and it may be tighter than the forms (it holds the bound's enclosure).
    if (!BoxRange(b, &lo, &hi) || lo > best) return false;
    Measure m[3];
    MeasureAlong<3>(b, m_origin, m_frame, m);
    const Measure &d1 = m[0], &d2 = m[1], &t = m[2];
    const Range r1 = Over(d1, 0, 1, 0, 1), r2 = Over(d2, 0, 1, 0, 1), rt = Over(t, 0, 1, 0, 1);
    // Each bounded measure may rule the region out on its own, even if another is unbounded.
    if ((d1.bounded && r1.excludesZero()) || (d2.bounded && r2.excludesZero())) return false;
    if (t.bounded) {
        lo = std::max(lo, rt.lo);
        hi = std::min(hi, rt.hi);
        if (lo > hi || lo > best) return false;
    }
    if (!d1.bounded || !d2.bounded || !t.bounded) {
        // Not ruled out by the ray frame: the coordinates that are still bounded give a box
        // (unbounded along the others), which the ray crosses over [lo, hi]: around a singular
        // point of the shader (log(0), 1/0) this keeps the regions that can still reach the ray
        // to the few it passes, instead of all of them.
        e.tLo = lo;
        e.tHi = hi;
        e.size = INFINITY;
        return true;
    }
    // The parallelogram: eps with |d1(eps)| <= R1 and |d2(eps)| <= R2 (eps_w and rad as radius).
    double cu = 0, ru = 1, cv = 0, rv = 1;
    double hitU = 0, hitV = 0;  // where the ray meets the parallelogram itself, within E
    const double det = d1.u * d2.v - d1.v * d2.u;
    const double scale = std::fabs(d1.u * d2.v) + std::fabs(d1.v * d2.u);
    const bool invertible = std::fabs(det) > 1e-6 * scale && std::isfinite(scale);
    // Where the parallelogram is not invertible across the ray, its zonotope edges may still
    // separate it (where it is, the parameter box below is the sharper test).
    if (!invertible) {
        for (auto [p1, p2] : {std::pair{d1.u, d2.u}, {d1.v, d2.v}, {d1.w, d2.w}})
            if (EdgeSeparates(d1, d2, p1, p2)) return false;
    } else {
        const double R1 = std::fabs(d1.w) + d1.rad, R2 = std::fabs(d2.w) + d2.rad;
        const double ad = std::fabs(det);
        const double su = -d1.c * d2.v + d2.c * d1.v, sv = -d2.c * d1.u + d1.c * d2.u;
        const double eu = su / det, ev = sv / det;
        // The solution rounds (numerator, determinant, division): first-order bounds, doubled.
        const double errU =
            2 * (2 * kUlp * (std::fabs(d1.c * d2.v) + std::fabs(d2.c * d1.v) + std::fabs(eu) * scale) / ad +
                 kUlp * std::fabs(eu));
        const double errV =
            2 * (2 * kUlp * (std::fabs(d2.c * d1.u) + std::fabs(d1.c * d2.u) + std::fabs(ev) * scale) / ad +
                 kUlp * std::fabs(ev));
        const double du = (std::fabs(d2.v) * R1 + std::fabs(d1.v) * R2) / ad * (1 + 1e-9) + errU + 1e-300;
        const double dv = (std::fabs(d2.u) * R1 + std::fabs(d1.u) * R2) / ad * (1 + 1e-9) + errV + 1e-300;
        double uLo, uHi, vLo, vHi;
        if (std::isfinite(du) && std::isfinite(dv) && std::isfinite(eu) && std::isfinite(ev)) {
            if (!Clip(eu, du, &uLo, &uHi) || !Clip(ev, dv, &vLo, &vHi)) return false;
            cu = 0.5 * (uLo + uHi);
            ru = (std::max(uHi - cu, cu - uLo)) * (1 + 4 * kUlp);
            cv = 0.5 * (vLo + vHi);
            rv = (std::max(vHi - cv, cv - vLo)) * (1 + 4 * kUlp);
            e.narrowed = ru < 1 || rv < 1;
            hitU = std::clamp(eu, uLo, uHi);
            hitV = std::clamp(ev, vLo, vHi);
        }
    }
    // eps_u = +-1 is u = pu +- pr (the evaluation's own mapping, surface.h).
    double pu, pr, pv, prv;
    RegionParameter(e.u0, e.u1, &pu, &pr);
    RegionParameter(e.v0, e.v1, &pv, &prv);
    Range e1 = r1, e2 = r2, et = rt;
    if (e.narrowed) {
        e1 = Over(d1, cu, ru, cv, rv);
        e2 = Over(d2, cu, ru, cv, rv);
        et = Over(t, cu, ru, cv, rv);
        if (e1.excludesZero() || e2.excludesZero() || et.hi < lo || et.lo > best) return false;
        // The reachable parameters: eps in [lo, hi] is u in pu + pr * [lo, hi], rounded outward.
        const double su = 4 * kUlp * (std::fabs(pu) + pr), sv = 4 * kUlp * (std::fabs(pv) + prv);
        e.ru0 = std::max(e.u0, pu + pr * (cu - ru) - su);
        e.ru1 = std::min(e.u1, pu + pr * (cu + ru) + su);
        e.rv0 = std::max(e.v0, pv + prv * (cv - rv) - sv);
        e.rv1 = std::min(e.v1, pv + prv * (cv + rv) + sv);
    } else {
        // The ray runs along the parallelogram (a silhouette), it is degenerate, or the ray can
        // reach all of it: should the region be a hit, its point nearest along the ray stands for
        // it, since at a silhouette
        // the side facing the ray comes first (the centre could lie on the far side).
        hitU = t.u > 0 ? -1 : t.u < 0 ? 1 : 0;
        hitV = t.v > 0 ? -1 : t.v < 0 ? 1 : 0;
    }
    e.hu = std::clamp(pu + pr * hitU, e.u0, e.u1);
    e.hv = std::clamp(pv + prv * hitV, e.v0, e.v1);
    e.tLo = std::max(et.lo, lo);
    e.tHi = std::min(et.hi, hi);
    if (e.tLo > e.tHi || e.tLo > best) return false;
    // The reachable part lies in the form's parallelogram and in the region's box as well: its
    // extent along each axis of the ray frame is the smaller of the two. (A form may be far wider
    // than its enclosure, e.g. after a steep fit whose interval range was clipped: the box then
    // certifies a small region that the form alone never would.)
    double w1 = e1.width(), w2 = e2.width(), wt = et.width();
    if (b.boundedMask == 7u) {
        const glm::dvec3 extent = b.hi - b.lo;
        auto across = [&](const glm::dvec3& axis) {
            return (std::fabs(axis.x) * extent.x + std::fabs(axis.y) * extent.y + std::fabs(axis.z) * extent.z) *
                   (1 + 8 * kUlp);
        };
        w1 = std::min(w1, across(m_n1));
        w2 = std::min(w2, across(m_n2));
        wt = std::min(wt, across(m_dir));
    }
    e.size = std::sqrt(w1 * w1 + w2 * w2 + wt * wt) * (1 + 1e-15);
    return true;
}

uint8_t TreeIntersector::ChildrenMissed(const Entry& e, double best, double childLo[4]) const {
    for (int i = 0; i < 4; ++i) childLo[i] = e.tLo;
    Measure m[3];
    MeasureAlong<3>(*e.bound, m_origin, m_frame, m);
    if (!m[0].bounded || !m[1].bounded || !m[2].bounded) return 0;
    // The parameters where the bound can meet the ray, and each child's part of them, in the
    // bound's eps (u = pu + pr eps_u, surface.h): (x - pu) / pr rounds twice, by an ulp of 1 at
    // most each, and a half's side at the split lies within a few ulps of u of eps = 0 (the
    // midpoint and pu round differently): the pads cover both many times over.
    double pu, pr, pv, prv;
    RegionParameter(e.u0, e.u1, &pu, &pr);
    RegionParameter(e.v0, e.v1, &pv, &prv);
    if (!(pr > 0 && prv > 0)) return 0;
    const double padU = 1e-12 + 8 * kUlp * (std::fabs(pu) + pr) / pr;
    const double padV = 1e-12 + 8 * kUlp * (std::fabs(pv) + prv) / prv;
    const double reachU0 = (e.ru0 - pu) / pr - padU, reachU1 = (e.ru1 - pu) / pr + padU;
    const double reachV0 = (e.rv0 - pv) / prv - padV, reachV1 = (e.rv1 - pv) / prv + padV;
    if (!std::isfinite(padU + padV + reachU0 + reachU1 + reachV0 + reachV1)) return 0;
    uint8_t missed = 0;
    for (int i = 0; i < ChildCount(e); ++i) {
        const auto [splitU, splitV, highU, highV] = SideOf(e.axis, i);
        double uLo = std::max(-1.0, reachU0), uHi = std::min(1.0, reachU1);
        double vLo = std::max(-1.0, reachV0), vHi = std::min(1.0, reachV1);
        if (splitU) {
            if (highU)
                uLo = std::max(uLo, -padU);
            else
                uHi = std::min(uHi, padU);
        }
        if (splitV) {
            if (highV)
                vLo = std::max(vLo, -padV);
            else
                vHi = std::min(vHi, padV);
        }
        if (uLo > uHi || vLo > vHi) {
            missed |= uint8_t(1u << i);
            continue;
        }
        const double cu = 0.5 * (uLo + uHi), ru = std::max(uHi - cu, cu - uLo) * (1 + 4 * kUlp);
        const double cv = 0.5 * (vLo + vHi), rv = std::max(vHi - cv, cv - vLo) * (1 + 4 * kUlp);
        const Range e1 = Over(m[0], cu, ru, cv, rv), e2 = Over(m[1], cu, ru, cv, rv), et = Over(m[2], cu, ru, cv, rv);
        // The child's points on the ray lie in e's bound over its part, at et and past e.tLo: the
        // child is measured from there (Test), so that it is discarded here exactly when its
        // measured range would lie beyond best.
        childLo[i] = std::max(e.tLo, et.lo);
        if (e1.excludesZero() || e2.excludesZero() || et.hi < e.tLo || childLo[i] > best) missed |= uint8_t(1u << i);
    }
    return missed;
}

bool TreeIntersector::Intersect(const Ray& ray, double tMin, double tMax, const Tolerance& tolerance, bool anyHit,
                                Hit* hit, IntersectStats& stats, const RayGroup* group) {
    m_origin = ray.origin;
    m_dir = ray.dir;
    // Any unit vector perpendicular to the ray, then a third completing the frame.
    const glm::dvec3 helper = std::abs(m_dir.x) < 0.6 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
    m_n1 = glm::normalize(glm::cross(m_dir, helper));
    m_n2 = glm::normalize(glm::cross(m_dir, m_n1));
    m_frame[0] = m_n1;
    m_frame[1] = m_n2;
    m_frame[2] = m_dir;
    for (int i = 0; i < 3; ++i) m_invDir[i] = m_dir[i] != 0 ? 1.0 / m_dir[i] : 0.0;
    m_tested = 0;
    m_evaluated = 0;
    m_top = 0;
    const bool newton = tolerance.newtonReach > 0 && m_evaluator->slopes();
    if (tolerance.certifiedOnly && !newton) {
        // Nothing can be proved on this surface (its shader may jump, or has no slopes): no hit.
        ++stats.rays;
        return false;
    }
    m_walker.Enter();
    if (group && (group->id != m_groupId || m_walker.epoch() != m_groupEpoch)) {
        IntersectWorkspace& w = *m_workspace;
        if (w.group != group->id) {
            for (TreeIntersector* holder : w.holders) holder->ReleaseFrontier();
            w.holders.clear();
            w.group = group->id;
        }
        if (m_groupId != group->id) w.holders.push_back(this);
        BuildFrontier(*group, stats);
    }

    // The hit is a function of the ray, tMin and the tolerance (and the group) alone: tMax
    // decides only whether it is reported (its t <= tMax) or not, never which it is. So a
    // region's range and its hit's t depend on its own bound and its ancestors' ranges (Test),
    // never on the best hit so far, which only discards regions that lie wholly beyond it; a
    // hit is kept at t <= best (inclusive), the last found of equal ones; and every hit a
    // region or its descendants can give lies in the region's [tLo, tHi] (children are
    // measured from their parent's tLo). Then the walk finds the same hit with any tMax at
    // least its t, and a caller may keep the nearest of several primitives' hits by t in any
    // order (renderer/render.cpp: TraceNearest). The region budget is the exception: a walk
    // given a nearer tMax tests fewer regions, so it may finish where a farther one ran out.
    double best = tMax;
    bool found = false;
    const int maxDepth = m_tree.maxDepth();
    const RayFrame frame{m_origin, {m_n1, m_n2, m_dir}};
    const BaseSurface& surface = m_tree.surface();
    // Measures the entry in the stack's next slot against the ray, with its bound `b`: it stays
    // on the stack if the ray can meet it.
    auto measure = [&](const RegionBound& b, double lo) {
        Entry& e = m_stack[m_top];
        if (!Test(e, b, lo, best)) return;
        e.axis = SplitAxis(b, e.levelU, e.levelV, maxDepth);
        e.bound = &b;
        ++m_top;
    };
    // Orders the entries from `first` up farthest first, so that they pop nearest first.
    auto sortFrom = [&](size_t first) {
        for (size_t i = first + 1; i < m_top; ++i)
            for (size_t j = i; j > first && m_stack[j - 1].tLo < m_stack[j].tLo; --j)
                std::swap(m_stack[j - 1], m_stack[j]);
    };
    if (group) {
        // A coherent ray starts from its group's frontier instead of the root.
        for (const FrontierNode& f : m_frontier) {
            m_stack[m_top] = f.entry;
            measure(f.bound, tMin);
        }
        sortFrom(0);
    } else {
        m_stack[m_top] = RootEntry(m_tree.root());
        measure(m_tree.root().bound, tMin);
    }

    while (m_top > 0) {
        if (m_tested >= m_budget && tolerance.certifiedOnly) {
            ++stats.budgetExhausted;
            break;
        }
        if (m_tested >= m_budget) {
            // Out of budget (a shader too stiff to resolve at this tolerance, or bounds that
            // overflow everywhere): the nearest region left is a possible hit, uncertified, unless
            // a hit already found is nearer. Better a counted, visible approximation than a hang.
            ++stats.budgetExhausted;
            const Entry* nearest = nullptr;
            for (size_t i = 0; i < m_top; ++i)
                if (const Entry& r = m_stack[i];
                    r.tLo <= best && (!nearest || r.tLo < nearest->tLo) && surface.KeptP(r.hu, r.hv))
                    nearest = &r;
            if (nearest) {
                best = std::max(nearest->tLo, tMin);
                found = true;
                *hit = Hit{best, nearest->hu, nearest->hv, nearest->size, true};
            }
            break;
        }
        const Entry r = m_stack[--m_top];
        if (r.tLo > best) continue;  // a nearer hit was found since this region was measured

        bool small = r.size <= tolerance.At(r.tLo);
        const bool atLimit = r.levelU >= maxDepth && r.levelV >= maxDepth;
        if (newton && std::isfinite(r.size) && r.size <= tolerance.newtonReach * tolerance.At(r.tLo)) {
            // Near the tolerance, Krawczyk's test may prove that the region meets the ray's line
            // exactly once (then Newton's point is the hit, certified to rounding) or never. It
            // never rules on another region: a nearer one still on the stack is still walked.
            const NewtonHit n =
                CertifyRegion(*m_evaluator, frame, {r.u0, r.u1, r.v0, r.v1, r.ru0, r.ru1, r.rv0, r.rv1}, r.hu, r.hv);
            ++m_evaluated;
            // A proved root is the region's hit: Newton's point, held to the region's range
            // (moving it by its rounding at most, which the error takes in) so that no hit below
            // a region lies nearer than its tLo. Whether it is past best is decided on that point
            // alone, not on the window around it, which best may cut: the same with any best.
            // (A root whose window straddles tMin is split as before, whatever best.)
            const double tHit = std::min(std::max(n.t, r.tLo), r.tHi);
            const bool proved = n.roots == Roots::One && n.tLo >= tMin;
            if (n.roots == Roots::None || (n.roots == Roots::One && n.tHi < tMin) || (proved && tHit > best)) {
                ++stats.newtonMisses;
                continue;
            }
            if (proved) {
                ++stats.newtonHits;
                // The region's one point is trimmed away: no hit in it.
                if (!surface.KeptP(n.u, n.v)) continue;
                best = tHit;
                found = true;
                *hit = Hit{tHit, n.u, n.v, n.error + std::fabs(tHit - n.t), false};
                if (anyHit) break;
                continue;
            }
            ++stats.newtonUnknown;
            // Not proved (a silhouette, a grazing ray, a crease): such a leaf is split further,
            // down to a fraction of the tolerance, where its bound may miss the ray or a
            // smaller region be proved.
            if (small && r.size > kUnprovedLeaf * tolerance.At(r.tLo)) small = false;
        }
        if (small || atLimit) {
            if (tolerance.certifiedOnly) continue;  // not proved: not a hit here
            // A trimmed NuPatch has no surface where the hit would be: the search goes on.
            if (!surface.KeptP(r.hu, r.hv)) continue;
            double tHit = 0, error = 0;
            if (std::isfinite(r.size)) {
                // The middle of the region's range (tMin <= tLo <= tHi: Test); kept only if
                // no hit found before is nearer.
                tHit = std::clamp(0.5 * (r.tLo + r.tHi), r.tLo, r.tHi);
                if (tHit > best) continue;
                error = r.size;
            } else {
                // Unbounded down to the depth limit: nothing rules a hit out, so this is a possible
                // hit (counted, with no certificate), placed where the ray passes the surface
                // point at the region's centre. Only rays that cross the box of the region's
                // bounded coordinates get here (Test), so around a singular point (log(0)) these
                // are the rays through its column, not every ray.
                glm::dvec3 p;
                if (!m_evaluator->PointAt(r.hu, r.hv, &p)) continue;
                ++m_evaluated;
                tHit = glm::dot(p - m_origin, m_dir);
                if (!std::isfinite(tHit) || tHit < tMin) continue;
                tHit = std::min(std::max(tHit, r.tLo), r.tHi);  // in the region's range, as every hit
                if (tHit > best) continue;
                error = INFINITY;
            }
            if (atLimit && !small) ++stats.depthLimitHits;
            if (small && r.narrowed) ++stats.parallelogramHits;
            best = tHit;
            found = true;
            *hit = Hit{tHit, r.hu, r.hv, error, atLimit && !small};
            if (anyHit) break;
            continue;
        }

        // The children that the ray can reach (their bounds evaluated now if no ray needed them
        // before), measured against the ray; the survivors pushed farthest first (popped nearest
        // first). A child outside the parameters where the parent's parallelogram meets the ray
        // is missed without being looked at.
        BoundNode* kids = m_walker.Children(*r.node);
        double childLo[4] = {r.tLo, r.tLo, r.tLo, r.tLo};
        const uint8_t missed = m_tree.costlyBounds() ? ChildrenMissed(r, best, childLo) : 0;
        const size_t first = m_top;
        for (int i = 0; i < ChildCount(r); ++i) {
            Entry& c = m_stack[m_top];
            SetChild(r, kids, i, &c);
            if (c.u1 < r.ru0 || c.u0 > r.ru1 || c.v1 < r.rv0 || c.v0 > r.rv1) continue;
            if (missed & (1u << i)) continue;
            measure(m_walker.Bound(kids[i], c.u0, c.u1, c.v0, c.v1, *m_evaluator, &m_evaluated), childLo[i]);
        }
        sortFrom(first);
    }
    m_walker.Leave();

    ++stats.rays;
    stats.regionsBounded += m_tested;
    stats.regionsEvaluated += m_evaluated;
    stats.maxRegionsPerRay = std::max(stats.maxRegionsPerRay, m_tested);
    if (found && std::isfinite(hit->error)) stats.maxHitError = std::max(stats.maxHitError, hit->error);
    return found;
}

}  // namespace

std::unique_ptr<SurfaceIntersector> MakeSurfaceIntersector(BoundTree& tree, uint64_t regionBudget,
                                                           std::shared_ptr<IntersectWorkspace> workspace) {
    return std::make_unique<TreeIntersector>(tree, regionBudget, nullptr, std::move(workspace));
}

std::unique_ptr<SurfaceIntersector> MakeSurfaceIntersector(const BaseSurface& surface, const vm::Program& boundProgram,
                                                           const glm::dvec3& eye, BoundMode mode, int maxDepth,
                                                           uint64_t regionBudget) {
    auto tree = std::make_unique<BoundTree>(surface, boundProgram, eye, mode, maxDepth);
    BoundTree& ref = *tree;
    return std::make_unique<TreeIntersector>(ref, regionBudget, std::move(tree));
}

}  // namespace affray::renderer
