// renderer/bound_tree.h: one bound hierarchy per displaced surface, built lazily and shared by
// every ray of every thread.
//
// The bound of a region of the (u,v) domain does not depend on the ray, so it is computed once: a
// quadtree over (u,v) whose nodes keep what a ray test needs (RegionBound). A ray walks the cached
// nodes (renderer/intersect.cpp); the shader runs only when a ray reaches a node whose children do
// not exist yet, and the thread that reaches it first publishes them with one compare-and-swap
// (a thread that loses the race drops its copy: the bounds are the same, since a node's bound is a
// function of its region alone). So the image does not depend on the thread count, the tile order
// or what the cache held.
//
// Memory: the tree keeps within a budget. When a new block of children takes it past the budget,
// one thread evicts the subtrees no ray has entered for the longest time (each node keeps the
// clock of its last expansion by a ray), and they are rebuilt on demand. Evicted blocks are freed
// only once every thread that could still hold a pointer into them has finished its ray
// (epoch-based reclamation: each walker announces the epoch in which its ray started).
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <mutex>
#include <vector>

#include <glm/glm.hpp>

#include "renderer/surface.h"
#include "vm/program.h"

namespace affray::renderer {

enum class BoundMode { Affine, Interval };

/// What a ray needs of the displaced surface over one region, reduced from the shader's bound.
/// With (eps_u, eps_v) in [-1, 1]^2 the region's (u, v) (u = uc + ru * eps_u, RegionParameter),
/// every displaced point P'(u, v) lies in
///     c + a * eps_u + b * eps_v + g * eps_w + [-r, r]      for some eps_w in [-1, 1],
/// a certified parallelogram (the eps_u and eps_v generators) thickened by a segment g (the
/// largest shared direction of the form's other terms: a displacement along N keeps its
/// correlation across coordinates) and the box r of everything else, rounding included; and it
/// lies in the box [lo, hi] (the bound's own ranges, which may be tighter). Coordinates whose bound
/// is not finite are left out of `boundedMask`; for them only lo = -inf, hi = +inf is meaningful.
/// An interval bound has a = b = g = 0.
struct RegionBound {
    glm::dvec3 c{0.0}, a{0.0}, b{0.0}, g{0.0}, r{0.0};
    glm::dvec3 lo{0.0}, hi{0.0};
    uint8_t boundedMask = 0;
    bool bounded() const { return boundedMask == 7; }
};

/// Bounds regions of one displaced surface; one per thread (it holds an interpreter).
class RegionEvaluator {
  public:
    virtual ~RegionEvaluator() = default;
    /// The bound of the displaced surface over [u0,u1] x [v0,v1].
    virtual RegionBound Bound(double u0, double u1, double v0, double v1) = 0;
    /// The displaced point at (u, v), evaluated in the bounding type (the middle of its bound);
    /// false if it is not finite.
    virtual bool PointAt(double u, double v, glm::dvec3* p) = 0;
};

/// A node of the hierarchy: the bound of its region and, once some ray needed them, its four
/// children (quadrants in the order (u low, v low), (u high, v low), (u low, v high), (u high,
/// v high)).
struct BoundNode {
    RegionBound bound;
    std::atomic<BoundNode*> children{nullptr};
    /// The tree's clock when a ray last expanded this node (for eviction).
    std::atomic<uint32_t> stamp{0};
};

/// The memory budget that the hierarchies of one render share (`affray render --cache-mb`).
struct CacheBudget {
    explicit CacheBudget(size_t limitBytes) : limit(limitBytes) {}
    const size_t limit;
    std::atomic<uint64_t> bytes{0};      // held now by all the trees
    std::atomic<uint64_t> peakBytes{0};  // the most ever held
    void Add(uint64_t n);
    void Sub(uint64_t n) { bytes.fetch_sub(n, std::memory_order_relaxed); }
};

struct BoundTreeStats {
    uint64_t nodes = 0;           // nodes held now (root included)
    uint64_t bytes = 0;           // bytes held now by blocks of children
    uint64_t peakBytes = 0;       // the most this tree held
    uint64_t blocksBuilt = 0;     // blocks of four children evaluated (races lost included)
    uint64_t blocksLost = 0;      // blocks evaluated by a thread that lost the race to publish
    uint64_t lookups = 0;         // a ray asking for the children of a node
    uint64_t evictions = 0;       // blocks evicted
    uint64_t evictionPasses = 0;  // times the budget was enforced
    double buildSeconds = 0;      // thread-seconds spent evaluating bounds (the price of a cold cache)
};

/// The default memory budget of a hierarchy (`affray render --cache-mb`), shared by all the
/// surfaces of a scene.
inline constexpr size_t kDefaultCacheBytes = size_t(256) << 20;

class BoundTree {
  public:
    /// The hierarchy of `surface` displaced by `boundProgram` (which outputs P; it must outlive the
    /// tree), seen from `eye`, bounded in `mode` (or its dual if the program takes derivatives).
    /// Nodes go `maxDepth` levels deep at most. `budget` (shared with other trees; null: a budget
    /// of kDefaultCacheBytes of its own) must outlive the tree.
    BoundTree(const BaseSurface& surface, const vm::Program& boundProgram, const glm::dvec3& eye, BoundMode mode,
              int maxDepth, CacheBudget* budget = nullptr);
    ~BoundTree();
    BoundTree(const BoundTree&) = delete;
    BoundTree& operator=(const BoundTree&) = delete;

    /// A new evaluator for this surface, for one thread.
    std::unique_ptr<RegionEvaluator> MakeEvaluator() const;

    BoundNode& root() { return m_root; }
    int maxDepth() const { return m_maxDepth; }

  private:
    /// A walker's announcement, one cache line each; never freed before the tree (a list that
    /// only grows at its head, so the evictor can scan it while walkers register).
    struct alignas(64) Slot {
        std::atomic<uint64_t> epoch{0};  // 0: not in a ray; else the epoch in which its ray began
        std::atomic<bool> used{false};
        Slot* next = nullptr;
    };

  public:
    /// A thread walking the tree: between Enter() and Leave() the nodes it reached stay valid.
    class Walker {
      public:
        explicit Walker(BoundTree& tree);
        ~Walker();
        Walker(const Walker&) = delete;
        Walker& operator=(const Walker&) = delete;
        void Enter();
        void Leave();
        /// The children of `node`, whose region is [u0,u1] x [v0,v1], built with `evaluator` if
        /// absent. Counts the lookup and, if this thread built them, `*evaluated` += 4.
        BoundNode* Children(BoundNode& node, double u0, double u1, double v0, double v1,
                                  RegionEvaluator& evaluator, uint64_t* evaluated);

      private:
        BoundTree& m_tree;
        Slot* m_slot;
        uint32_t m_clock = 0;
        uint64_t m_lookups = 0, m_built = 0, m_lost = 0;
        double m_buildSeconds = 0;
        uint32_t m_raysSinceTick = 0;
    };

    /// The figures so far (exact once no walker is active).
    BoundTreeStats stats() const;

  private:
    friend class Walker;
    static constexpr size_t kBlockBytes = 4 * sizeof(BoundNode);

    Slot* RegisterWalker();
    /// Publishes `block` as the children of `node`; false if another thread did first.
    bool Publish(BoundNode& node, BoundNode* block);
    /// Evicts the least recently expanded subtrees until the tree holds half its budget, and
    /// frees what no walker can reach any more. One thread at a time; others carry on.
    void Evict();
    /// Frees retired blocks that no active walker can still hold.
    void Reclaim();
    /// Deletes a block and every block below it; returns the nodes freed.
    static uint64_t FreeSubtree(BoundNode* block);

    BaseSurface m_surface;
    const vm::Program* m_program;
    glm::dvec3 m_eye;
    BoundMode m_mode;
    int m_maxDepth;
    std::unique_ptr<CacheBudget> m_ownBudget;
    CacheBudget* m_budget;
    BoundNode m_root;

    std::atomic<uint64_t> m_bytes{0}, m_nodes{1}, m_peakBytes{0};
    std::atomic<uint64_t> m_lookups{0}, m_blocksBuilt{0}, m_blocksLost{0}, m_evictions{0}, m_passes{0};
    std::atomic<double> m_buildSeconds{0};
    std::atomic<uint32_t> m_clock{1};
    std::atomic<uint64_t> m_epoch{1};

    std::atomic<Slot*> m_slots{nullptr};

    std::mutex m_evictMutex;
    struct Retired {
        BoundNode* block;
        uint64_t epoch;
    };
    std::vector<Retired> m_retired;  // under m_evictMutex
};

}  // namespace affray::renderer
