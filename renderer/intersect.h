// renderer/intersect.h: the guaranteed intersector of Heidrich & Seidel (GI 1998), over a shared
// bound hierarchy (renderer/bound_tree.h).
// For a ray and a displaced surface, the nodes of the surface's (u,v) quadtree are tested against
// the ray nearest first, with early exit past the best hit; a node is discarded only when its
// bound provably misses the ray, and expanded (its children built on first use, by whichever ray
// needs them first) otherwise. A node is a hit once the part of its bound that can meet the ray,
// measured in the ray's frame, is smaller than the tolerance at its distance; the size of that
// part is the hit's certified error.
#pragma once

#include <cstdint>
#include <memory>

#include "renderer/bound_tree.h"
#include "scene/geometry/camera.h"
#include "scene/geometry/surface.h"
#include "vm/program.h"

namespace affray::renderer {

/// How small a region's bound must be to count as a hit at distance t: base + slope * t.
/// Camera rays use slope = pixel angle * tolerance in pixels; secondary rays a cone.
struct Tolerance {
    double base = 0;
    double slope = 0;
    /// Certified Newton (renderer/newton.h) is tried on a region whose reachable part is within
    /// this many tolerances (size <= newtonReach * At(t)): 1 at the leaves only; 0 never (the
    /// hit is the leaf region, certified by its size).
    double newtonReach = 0;
    /// Report only hits certified by Newton (a proved root): leaves, depth-limit and budget hits
    /// are not hits. For shadow rays that start close to the surface they leave, where a leaf
    /// may be that surface itself (render.cpp: ShadeHit).
    bool certifiedOnly = false;
    double At(double t) const { return base + slope * std::max(t, 0.0); }
};

struct Hit {
    double t = 0;
    double u = 0, v = 0;        // where the ray meets the bound of the final region (its centre if unknown)
    double error = 0;           // certified: every surface point of the region lies this close to the hit
    bool depthLimited = false;  // not certified: the depth limit or the region budget ended the search
};

struct IntersectStats {
    uint64_t rays = 0;
    /// Region bounds tested against rays (cached or not), and bounds evaluated by running the
    /// shader (the hierarchy's nodes this thread built).
    uint64_t regionsBounded = 0;
    uint64_t regionsEvaluated = 0;
    uint64_t maxRegionsPerRay = 0;
    uint64_t depthLimitHits = 0;
    /// Rays that ran out of their region budget (their result is an uncertified possible hit).
    uint64_t budgetExhausted = 0;
    /// Hits resolved by the parallelogram of a node's affine bound before its box was small.
    uint64_t parallelogramHits = 0;
    /// Certified Newton: hits it proved (one root, found to rounding), regions it proved the
    /// ray's line never meets (or meets once outside the ray's segment), and tries that proved
    /// nothing (the region is then split or a leaf, as without it).
    uint64_t newtonHits = 0;
    uint64_t newtonMisses = 0;
    uint64_t newtonUnknown = 0;
    double maxHitError = 0;
    /// Coherent rays (RayGroup): frontiers built, and the region bounds tested to build them
    /// (shared by the group's rays, so not in regionsBounded).
    uint64_t frontiers = 0;
    uint64_t frontierRegions = 0;

    void Merge(const IntersectStats& o);
};

/// A convex set that holds every ray of a group (the camera rays through one block of pixels,
/// bounded by the four planes through its corner rays), so that the walk of the hierarchy's top
/// levels is done once for all of them: a node whose bound lies wholly outside one plane cannot
/// meet any of the rays. `id` names the group within a render: equal ids, equal groups.
struct RayGroup {
    uint64_t id = 0;
    glm::dvec3 normal[4];  // a point x is inside when dot(normal[i], x) >= offset[i] for all i
    double offset[4] = {0, 0, 0, 0};
    glm::dvec3 origin{0.0};  // the centre ray's origin
    /// The group's width at distance t from its origin: at most spread0 + spreadSlope * t.
    double spread0 = 0, spreadSlope = 0;

    /// The group of the rays between four corner rays, given in order around the block (the rays
    /// through a convex quadrilateral of the image: all of one perspective or orthographic
    /// camera). Every ray through the quadrilateral lies inside.
    static RayGroup FromCorners(const Ray (&corners)[4], uint64_t id);
    /// Whether the point p lies inside, within `slack` (a distance along the normals).
    bool Contains(const glm::dvec3& p, double slack = 0) const;
};

/// Intersects rays with one displaced surface. Holds an interpreter, so make one per thread.
class SurfaceIntersector {
  public:
    virtual ~SurfaceIntersector() = default;

    /// The nearest hit with t in [tMin, tMax], or false. With `anyHit`, stops at the first hit
    /// found (for shadow rays). A ray of a `group` (it must lie inside it) shares the walk of the
    /// top levels with the group's other rays; its result is a function of the ray and the group,
    /// whichever rays came before.
    /// Without `anyHit` the hit does not depend on tMax: it is the hit the search up to any farther
    /// tMax finds, or none if that lies beyond tMax (outside the region budget, which a nearer tMax
    /// may not exhaust). A caller may so search several surfaces, each up to the nearest hit so
    /// far, and keep the nearest in any order (renderer/render.cpp: TraceNearest).
    virtual bool Intersect(const Ray& ray, double tMin, double tMax, const Tolerance& tolerance, bool anyHit, Hit* hit,
                           IntersectStats& stats, const RayGroup* group = nullptr) = 0;
};

/// Regions one ray may test before the search stops with an uncertified possible hit: a bound
/// on the time of any ray. The stiff scenes of docs/stiff.md need at most a few thousand.
inline constexpr uint64_t kDefaultRegionBudget = 1u << 18;

/// What one thread's intersectors share: the walk's stack and the interpreters that bound regions
/// (an EvaluatorPool). A thread runs one walk at a time, so its intersectors need not each hold
/// them, and their memory does not grow with the number of primitives (about 25 KB of stack and
/// an interpreter's registers each, before).
class IntersectWorkspace;
std::shared_ptr<IntersectWorkspace> MakeIntersectWorkspace();

/// An intersector for one thread walking `tree` (shared with other threads; it must outlive the
/// intersector). Its hits do not depend on what the tree held before. With `workspace` (the
/// thread's), it uses the workspace's stack and interpreters; without, its own.
std::unique_ptr<SurfaceIntersector> MakeSurfaceIntersector(BoundTree& tree,
                                                           uint64_t regionBudget = kDefaultRegionBudget,
                                                           std::shared_ptr<IntersectWorkspace> workspace = nullptr);

/// An intersector with a bound hierarchy of its own, for `surface` displaced by `boundProgram`
/// (which outputs P, and must outlive the intersector), bounded in `mode` (or its dual if the
/// program takes derivatives), at most `maxDepth` levels deep (2^-maxDepth of the domain per side;
/// regions that reach it are counted and taken as hits).
std::unique_ptr<SurfaceIntersector> MakeSurfaceIntersector(const BaseSurface& surface, const vm::Program& boundProgram,
                                                           const glm::dvec3& eye, BoundMode mode, int maxDepth,
                                                           uint64_t regionBudget = kDefaultRegionBudget);

}  // namespace affray::renderer
