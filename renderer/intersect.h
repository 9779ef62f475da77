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
#include "renderer/camera.h"
#include "renderer/surface.h"
#include "vm/program.h"

namespace affray::renderer {

/// How small a region's bound must be to count as a hit at distance t: base + slope * t.
/// Camera rays use slope = pixel angle * tolerance in pixels; secondary rays a cone.
struct Tolerance {
    double base = 0;
    double slope = 0;
    double At(double t) const { return base + slope * std::max(t, 0.0); }
};

struct Hit {
    double t = 0;
    double u = 0, v = 0;  // where the ray meets the bound of the final region (its centre if unknown)
    double error = 0;     // certified: every surface point of the region lies this close to the hit
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
    double maxHitError = 0;

    void Merge(const IntersectStats& o);
};

/// Intersects rays with one displaced surface. Holds an interpreter, so make one per thread.
class SurfaceIntersector {
  public:
    virtual ~SurfaceIntersector() = default;

    /// The nearest hit with t in [tMin, tMax], or false. With `anyHit`, stops at the first hit
    /// found (for shadow rays).
    virtual bool Intersect(const Ray& ray, double tMin, double tMax, const Tolerance& tolerance, bool anyHit,
                           Hit* hit, IntersectStats& stats) = 0;
};

/// Regions one ray may test before the search stops with an uncertified possible hit: a bound
/// on the time of any ray. The stiff scenes of docs/stiff.md need at most a few thousand.
inline constexpr uint64_t kDefaultRegionBudget = 1u << 18;

/// An intersector for one thread walking `tree` (shared with other threads; it must outlive the
/// intersector). Its hits do not depend on what the tree held before.
std::unique_ptr<SurfaceIntersector> MakeSurfaceIntersector(BoundTree& tree,
                                                           uint64_t regionBudget = kDefaultRegionBudget);

/// An intersector with a bound hierarchy of its own, for `surface` displaced by `boundProgram`
/// (which outputs P, and must outlive the intersector), bounded in `mode` (or its dual if the
/// program takes derivatives), at most `maxDepth` levels deep (2^-maxDepth of the domain per side;
/// regions that reach it are counted and taken as hits).
std::unique_ptr<SurfaceIntersector> MakeSurfaceIntersector(const BaseSurface& surface, const vm::Program& boundProgram,
                                                           const glm::dvec3& eye, BoundMode mode, int maxDepth,
                                                           uint64_t regionBudget = kDefaultRegionBudget);

}  // namespace affray::renderer
