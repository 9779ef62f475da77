// renderer/intersect.h: the guaranteed intersector of Heidrich & Seidel (GI 1998).
// For a ray and a displaced patch, the (u,v) domain is subdivided hierarchically; each region is
// bounded by running the shader's bound program over it in affine (or interval) arithmetic, and
// a region is discarded only when its bound provably misses the ray. Children are visited
// nearest first, with early exit past the best hit. A region is a hit once its bound, measured
// in the ray's frame, is smaller than the tolerance at its distance; the size of that bound is
// the hit's certified error.
#pragma once

#include <cstdint>
#include <memory>

#include "renderer/camera.h"
#include "renderer/surface.h"
#include "vm/program.h"

namespace affray::renderer {

enum class BoundMode { Affine, Interval };

/// How small a region's bound must be to count as a hit at distance t: base + slope * t.
/// Camera rays use slope = pixel angle * tolerance in pixels; secondary rays a cone.
struct Tolerance {
    double base = 0;
    double slope = 0;
    double At(double t) const { return base + slope * std::max(t, 0.0); }
};

struct Hit {
    double t = 0;
    double u = 0, v = 0;  // centre of the final region
    double error = 0;     // certified: every surface point of the region lies this close to the hit
    bool depthLimited = false;  // not certified: the depth limit or the region budget ended the search
};

struct IntersectStats {
    uint64_t rays = 0;
    uint64_t regionsBounded = 0;
    uint64_t maxRegionsPerRay = 0;
    uint64_t depthLimitHits = 0;
    /// Rays that ran out of their region budget (their result is an uncertified possible hit).
    uint64_t budgetExhausted = 0;
    double maxHitError = 0;
    /// Instructions of the programs that bounded the regions (pruned ones counted as run), and
    /// the pruned programs built (see PruneOptions).
    uint64_t instructionsBounded = 0;
    uint64_t programsPruned = 0;

    void Merge(const IntersectStats& o);
};

/// Intersects rays with one displaced patch. Holds an interpreter, so make one per thread.
class SurfaceIntersector {
  public:
    virtual ~SurfaceIntersector() = default;

    /// The nearest hit with t in [tMin, tMax], or false. With `anyHit`, stops at the first hit
    /// found (for shadow rays).
    virtual bool Intersect(const Ray& ray, double tMin, double tMax, const Tolerance& tolerance, bool anyHit,
                           Hit* hit, IntersectStats& stats) = 0;
};

/// Tape pruning (vm/prune.h): a region whose bound decided choices of the program has its
/// children bounded by the program pruned for it, if that is at most `keepRatio` of the size of
/// the program that bounded it. A pruned program gives the same scalar results over the region,
/// so hits stay guaranteed; bounds may get tighter (a floor split the full program had no budget
/// left for), so regions per ray may differ slightly from an unpruned traversal.
/// Off by default: it cuts the instructions of regions from depth 5 or so by 2 to 10 times, but
/// a ray's time goes mostly to its shallow regions, where little is decided: renders of tiles,
/// bricks, cellular, ridged and wave at 96x72 took 0.96 to 1.07 times as long with minDepth 0,
/// 0.975 to 1.02 times with minDepth 4, for the same images.
struct PruneOptions {
    bool enabled = false;
    double keepRatio = 0.9;
    /// Regions shallower than this record nothing: over a wide region few choices are decided,
    /// and recording costs a little on every instruction.
    int minDepth = 4;
    /// The defaults, changed by the environment: AFFRAY_PRUNE=1 turns pruning on (=0 off), and
    /// AFFRAY_PRUNE_DEPTH=N sets minDepth.
    static PruneOptions FromEnvironment();
};

/// Regions one ray may bound before the search stops with an uncertified possible hit: a bound
/// on the time of any ray (about a second in affine arithmetic for a short shader). The stiff
/// scenes of docs/stiff.md need at most a few thousand.
inline constexpr uint64_t kDefaultRegionBudget = 1u << 18;

/// An intersector for `surface` displaced by `boundProgram` (which outputs P), bounding regions in
/// `mode`. If the program takes derivatives, the dual of the mode's number type is used. The
/// program must outlive the intersector. Subdivision stops at `maxDepth` levels (2^-maxDepth of
/// the domain per side); regions that reach it are counted and taken as hits.
std::unique_ptr<SurfaceIntersector> MakeSurfaceIntersector(const BaseSurface& surface, const vm::Program& boundProgram,
                                                       const glm::dvec3& eye, BoundMode mode, int maxDepth,
                                                       const PruneOptions& prune = PruneOptions::FromEnvironment(),
                                                       uint64_t regionBudget = kDefaultRegionBudget);

}  // namespace affray::renderer
