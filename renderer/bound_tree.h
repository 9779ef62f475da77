// renderer/bound_tree.h: one bound hierarchy per displaced surface, built lazily and shared by
// every ray of every thread.
//
// The bound of a region of the (u,v) domain does not depend on the ray, so it is computed once: a
// quadtree over (u,v) whose nodes keep what a ray test needs (RegionBound). A ray walks the cached
// nodes (renderer/intersect.cpp); the shader runs only when a ray reaches a node whose bound has
// not been computed yet. A node's four children are allocated together when a ray first needs to
// look below it (published with one compare-and-swap), but each child's bound is evaluated only
// when a ray can reach that child: one whose region the ray provably cannot meet (outside the
// parent's parallelogram test) costs nothing. The first thread to claim a child publishes its bound;
// a thread that finds it claimed but not ready computes a private copy instead of waiting. The
// bounds are the same either way, since a node's bound is a function of its region alone; so the
// image does not depend on the thread count, the tile order or what the cache held.
//
// Memory: the trees of a render keep within one budget (CacheBudget), which counts the trees
// themselves as well as their blocks. When a new block or tree takes them past it, one thread
// evicts the subtrees no ray has entered for the longest time, whichever trees hold them (each
// node keeps the budget's clock at its last expansion by a ray), and whole trees no walker holds
// (BoundForest), and they are rebuilt on demand. Evicted blocks are freed only once every thread
// that could still hold a pointer into them has finished its ray (epoch-based reclamation: each
// walker announces the epoch in which its ray started); retired trees likewise, once no thread
// that looked one up can still be about to walk it.
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <vector>

#include <glm/glm.hpp>

#include "scene/geometry/surface.h"
#include "vm/program.h"

namespace affray::renderer {

/// The arithmetic that bounds regions: full affine forms (every symbol kept, up to the capacity),
/// reduced affine forms (centre, eps_u, eps_v and one error term: vm/numbers/reduced_affine.h) or intervals.
enum class BoundMode { Affine, Reduced, Interval };

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

/// The slopes of the displaced surface over a region, for certified Newton (renderer/newton.h):
/// du holds dP'/du * rate[0] and dv holds dP'/dv * rate[1] at every point of the region, in the
/// form of a RegionBound over the region's (eps_u, eps_v) (u, v the region's own parameters, as
/// the intersector splits them; `rate` the Dual's rate along them, BaseSurface::DualRate). They
/// bound how far P' moves across the region as well (the mean value theorem).
struct SlopeBound {
    RegionBound du, dv;
    double rate[2] = {1, 1};
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

    /// Whether Slopes can ever answer (the program's derivative bounds can bound how far P'
    /// moves: vm::SlopesCanBound, and it takes no derivatives itself).
    virtual bool slopes() const { return false; }
    /// The slopes of the displaced surface over [u0,u1] x [v0,v1] (one Dual bound evaluation,
    /// kept in the thread's pool for the next ray that needs the same region). False where they
    /// do not bound how far P' moves: the shader may jump within the region (vm::JumpsDecided), or
    /// a bound is not finite.
    virtual bool Slopes(double, double, double, double, SlopeBound*) { return false; }
    /// P' and its derivatives along the region's parameters at (u, v), in doubles (Dual<double>,
    /// not bounded): for Newton's steps. False if not finite.
    virtual bool PointFrame(double, double, glm::dvec3*, glm::dvec3*, glm::dvec3*) { return false; }
};

/// A node of the hierarchy: the bound of its region and, once some ray needed them, its children
/// (a block of kBlockNodes): the quadrants of its region, in the order (u low, v low), (u high,
/// v low), (u low, v high), (u high, v high); or the two halves across u or across v, low half
/// first, in the first two nodes of the block (SplitAxis).
struct BoundNode {
    RegionBound bound;  // valid once state is kReady
    std::atomic<BoundNode*> children{nullptr};
    static constexpr uint8_t kEmpty = 0, kClaimed = 1, kReady = 2;
    std::atomic<uint8_t> state{kEmpty};
    /// The budget's clock when a ray last expanded this node (for eviction).
    std::atomic<uint32_t> stamp{0};
};

/// Nodes allocated together as the children of one node.
inline constexpr int kBlockNodes = 4;
/// How a node's region is split: across u, across v, or both (quadrants).
inline constexpr int kSplitU = 0, kSplitV = 1, kSplitBoth = 2;
/// Halvings along one parameter, at most, beyond those along the other.
inline constexpr int kMaxImbalance = 24;

/// How a node is split, from its bound and the times its region was halved along u and along v
/// (`maxDepth` at most): across the parameter along which the surface stretches most over the
/// region (by the parallelogram's generators), when it clearly does (twice as far) and the
/// generators are not dwarfed by the rest of the bound; else into quadrants, or across the
/// parameter halved fewer times until they are even again. A steep wall along v gets split across u only, down to its width,
/// instead of into 4^depth squares. A function of the bound alone, so every thread agrees.
int SplitAxis(const RegionBound& b, int levelU, int levelV, int maxDepth);

class BoundTree;

/// What owns hierarchies that may be retired whole (BoundForest): CacheBudget hands it a tree no
/// walker holds and no ray has entered for longest, under the budget's mutex; the owner unlinks
/// it and frees it once no thread can still reach it.
class TreeOwner {
  public:
    virtual ~TreeOwner() = default;
    /// Called under the budget's mutex: may not take it, nor free the tree.
    virtual void Retire(BoundTree* tree) = 0;
};

/// The memory budget that the hierarchies of one render share (`affray render --cache-mb`), and
/// the clock their nodes are stamped with. It counts the blocks of children and, since a scene of
/// a million faces reaches a million hierarchies, the hierarchies themselves (BoundTree::kBytes,
/// and each walker's announcement). When the trees together hold more than `limit`, one thread
/// evicts what was used longest ago across all of them until they hold half of it: blocks
/// (root blocks included) and, where an owner can retire them, whole idle trees. A scene of
/// thousands of primitives keeps within the budget as one of a single primitive does.
class CacheBudget {
  public:
    explicit CacheBudget(size_t limitBytes) : limit(limitBytes) {}
    CacheBudget(const CacheBudget&) = delete;
    CacheBudget& operator=(const CacheBudget&) = delete;

    const size_t limit;
    std::atomic<uint64_t> bytes{0};      // held now by all the trees
    std::atomic<uint64_t> peakBytes{0};  // the most ever held
    void Add(uint64_t n);
    void Sub(uint64_t n) { bytes.fetch_sub(n, std::memory_order_relaxed); }
    /// Times the limit was enforced.
    uint64_t passes() const { return m_passes.load(std::memory_order_relaxed); }
    /// Of `bytes`, those in blocks evicted but not yet freed (rays under way may still hold them),
    /// and in trees retired but not yet freed.
    uint64_t retiredBytes() const { return m_retiredBytes.load(std::memory_order_relaxed); }
    /// Lets `owner` retire idle trees whole (null: never; trees are then freed by whoever made them).
    void SetOwner(TreeOwner* owner);
    /// Trees handed to the owner.
    uint64_t treesRetired() const { return m_treesRetired.load(std::memory_order_relaxed); }

  private:
    friend class BoundTree;
    /// Enforces the limit over every registered tree; a thread that finds another at it returns.
    void Enforce();

    /// Ticks once every 64 rays a thread starts in any tree: the stamps of all trees compare.
    std::atomic<uint32_t> m_clock{1};
    std::atomic<uint64_t> m_passes{0};
    std::atomic<uint64_t> m_retiredBytes{0};  // written under m_mutex
    std::mutex m_mutex;                       // held by the thread enforcing the budget, and to register
    std::vector<BoundTree*> m_trees;          // under m_mutex; a tree knows its index (m_budgetIndex)
    std::vector<BoundTree*> m_retiring;       // under m_mutex: the trees with blocks retired, not freed
    TreeOwner* m_owner = nullptr;
    std::atomic<uint64_t> m_treesRetired{0};
};

struct BoundTreeStats {
    uint64_t nodes = 0;           // nodes held now (root included)
    uint64_t bytes = 0;           // bytes held now by blocks of children
    uint64_t blocksBuilt = 0;     // blocks of children allocated
    uint64_t evaluations = 0;     // bounds evaluated (private copies included)
    uint64_t privateCopies = 0;   // bounds evaluated by a thread that found them claimed, not ready
    uint64_t lookups = 0;         // a ray asking for the bound of a child
    uint64_t evictions = 0;       // blocks evicted
    uint64_t evictionPasses = 0;  // times the budget was enforced (of one tree: passes that evicted from it)
    uint64_t trees = 0;           // hierarchies made (a retired one made again counts again)
    uint64_t treesRetired = 0;    // hierarchies retired whole (CacheBudget::treesRetired)
    double buildSeconds = 0;      // thread-seconds spent evaluating bounds (the price of a cold cache)

    /// Sums (the figures of several trees).
    void Merge(const BoundTreeStats& o);
};

/// The default memory budget of a hierarchy (`affray render --cache-mb`), shared by all the
/// surfaces of a scene.
inline constexpr size_t kDefaultCacheBytes = size_t(256) << 20;

/// The interpreters one thread's region evaluators share, one per number type, made on first use
/// (bound_tree.cpp). A thread bounds one region at a time, so they can.
class EvaluatorPool;
std::shared_ptr<EvaluatorPool> MakeEvaluatorPool();

class BoundTree {
  public:
    /// The hierarchy of `surface` displaced by `boundProgram` (which outputs P; it must outlive the
    /// tree), seen from `eye`, bounded in `mode` (or its dual if the program takes derivatives).
    /// Nodes go `maxDepth` levels deep at most. `budget` (shared with other trees; null: a budget
    /// of kDefaultCacheBytes of its own) must outlive the tree.
    BoundTree(const BaseSurface& surface, const vm::Program& boundProgram, const glm::dvec3& eye, BoundMode mode,
              int maxDepth, CacheBudget* budget = nullptr);
    /// What a tree counts against its budget besides its blocks: itself (the root's bound, the
    /// surface's handle, counters) and an announcement per walker thread.
    static constexpr size_t kBytes = 576, kWalkerBytes = 64;
    ~BoundTree();
    BoundTree(const BoundTree&) = delete;
    BoundTree& operator=(const BoundTree&) = delete;

    /// The surface the hierarchy bounds.
    const BaseSurface& surface() const { return m_surface; }
    /// A new evaluator for this surface, for one thread. With `pool` (that thread's), it borrows
    /// the pool's interpreter for each bound instead of holding registers of its own, so a thread
    /// walking thousands of primitives keeps one interpreter per number type, not one each.
    std::unique_ptr<RegionEvaluator> MakeEvaluator(const std::shared_ptr<EvaluatorPool>& pool = nullptr) const;

    BoundNode& root() { return m_root; }
    int maxDepth() const { return m_maxDepth; }
    /// Whether a bound costs far more than testing one against a ray (the program calls noise or
    /// texture, or runs 64 instructions or more): then a walk spends tests to spare evaluations.
    bool costlyBounds() const { return m_costlyBounds; }

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
        /// The epoch announced by the last Enter(). Nodes reached in an earlier ray stay valid in
        /// this one if the epoch is the same: no eviction has finished unlinking in between, and
        /// blocks an eviction is unlinking now are not freed before this ray leaves.
        uint64_t epoch() const { return m_epoch; }
        /// The block of children of `node` (allocated now if absent; their bounds not yet evaluated).
        BoundNode* Children(BoundNode& node);
        /// The bound of `child` (one of a node's children) over its region [u0,u1] x [v0,v1],
        /// evaluated with `evaluator` if no thread published it yet (then `*evaluated` grows).
        /// Valid until the next Enter().
        const RegionBound& Bound(BoundNode& child, double u0, double u1, double v0, double v1,
                                 RegionEvaluator& evaluator, uint64_t* evaluated);

      private:
        BoundTree& m_tree;
        Slot* m_slot;
        uint32_t m_clock = 0;
        uint64_t m_lookups = 0, m_built = 0, m_evaluations = 0, m_private = 0;
        // The private copies of this ray (see Bound), kept to its end: a deque keeps them in place.
        std::deque<RegionBound> m_privateBounds;
        double m_buildSeconds = 0;
        uint64_t m_epoch = 0;
    };

    /// The figures so far (exact once no walker is active).
    BoundTreeStats stats() const;
    /// Whether no walker holds the tree (its owner may free it then). Sequentially consistent.
    bool Idle() const;

  private:
    friend class Walker;
    static constexpr size_t kBlockBytes = kBlockNodes * sizeof(BoundNode);

    Slot* RegisterWalker();
    /// Publishes `block` as the children of `node`; false if another thread did first.
    bool Publish(BoundNode& node, BoundNode* block);
    friend class CacheBudget;
    /// Appends the stamps of the nodes whose children are held (the root's included).
    void CollectStamps(std::vector<uint32_t>* stamps);
    /// Unlinks the blocks of children of nodes stamped at or before `threshold`: rays under way
    /// may still hold them, so they are freed once those rays have finished (Reclaim). Under the
    /// budget's mutex.
    void EvictExpandedBefore(uint32_t threshold);
    /// Frees retired blocks that no active walker can still hold. Under the budget's mutex.
    void Reclaim();
    /// Deletes a block and every block below it; returns the nodes freed.
    static uint64_t FreeSubtree(BoundNode* block);
    /// The nodes of a block and every block below it.
    static uint64_t CountSubtree(const BoundNode* block);

    BaseSurface m_surface;
    const vm::Program* m_program;
    glm::dvec3 m_eye;
    BoundMode m_mode;
    int m_maxDepth;
    bool m_costlyBounds = false;
    std::unique_ptr<CacheBudget> m_ownBudget;
    CacheBudget* m_budget;
    BoundNode m_root;

    std::atomic<uint64_t> m_nodes{1};  // the root and every block's nodes
    std::atomic<uint64_t> m_lookups{0}, m_blocksBuilt{0}, m_evaluations{0}, m_private{0}, m_evictions{0}, m_passes{0};
    std::atomic<double> m_buildSeconds{0};
    std::atomic<uint64_t> m_epoch{1};

    std::atomic<Slot*> m_slots{nullptr};

    size_t m_budgetIndex = 0;  // in m_budget->m_trees
    /// The budget's clock when a ray last entered the tree (for retiring it whole).
    std::atomic<uint32_t> m_lastUse{0};
    /// What the tree counts against the budget besides its blocks (kBytes and its walkers').
    std::atomic<uint64_t> m_ownBytes{kBytes};
    bool m_wholeRetired = false;     // handed to the owner (under the budget's mutex)
    uint64_t m_retiredOwnBytes = 0;  // m_ownBytes then, counted in the budget's retired bytes

  public:
    /// Where the owner keeps the tree (BoundForest: the primitive's index).
    size_t ownerIndex = 0;
    /// Set by the owner once it holds the tree: only then may the budget retire it.
    std::atomic<bool> retirable{false};

  private:
    struct Retired {
        BoundNode* block;
        uint64_t epoch;
        uint64_t bytes;  // of the subtree when it was retired (it may grow until freed)
    };
    std::vector<Retired> m_retired;  // under the budget's mutex
};

/// The bound hierarchies of a scene's primitives, shared by every thread and ray of a render:
/// primitive i's is made when a ray first meets the primitive, by whichever thread that is, so a
/// scene of a million faces pays only for the faces its rays reach. Under the budget's pressure a
/// hierarchy no walker holds is retired whole (CacheBudget) and made again when a ray needs it;
/// it is freed once no thread can still be about to use it (epoch-based, as blocks are: each
/// thread announces the epoch in which it looked the tree up until its walker holds it). The
/// image does not depend on any of this: a hierarchy made again has the same bounds.
class BoundForest : public TreeOwner {
  public:
    /// Makes primitive i's hierarchy on `budget`.
    using Maker = std::function<std::unique_ptr<BoundTree>(size_t i, CacheBudget* budget)>;
    /// `count` primitives; `budget` must outlive the forest, which becomes its owner.
    BoundForest(size_t count, CacheBudget& budget, Maker make);
    ~BoundForest() override;
    BoundForest(const BoundForest&) = delete;
    BoundForest& operator=(const BoundForest&) = delete;

    /// One thread's announcement (RegisterThread); kept by the thread for the forest's life.
    struct alignas(64) ThreadSlot {
        std::atomic<uint64_t> epoch{0};  // 0: not looking a tree up
        ThreadSlot* next = nullptr;
    };
    ThreadSlot* RegisterThread();

    /// use(tree) with primitive i's hierarchy (made now if absent), which stays alive while `use`
    /// runs; it must hold the tree by a walker (BoundTree::Walker) to keep it past that.
    template <class Use>
    auto With(ThreadSlot* slot, size_t i, Use&& use) {
        slot->epoch.store(m_epoch.load());  // sequentially consistent: before the tree is read
        struct Clear {
            ThreadSlot* s;
            ~Clear() { s->epoch.store(0); }
        } clear{slot};
        if (m_pending.load(std::memory_order_relaxed) != 0) Collect();
        return use(Tree(i));
    }

    /// The statistics summed over the hierarchies made, those freed included (`trees`: how many
    /// were made).
    void Merge(BoundTreeStats* stats);

    void Retire(BoundTree* tree) override;

  private:
    BoundTree& Tree(size_t i);
    /// Frees the retired trees no thread can reach; returns without waiting if another thread is at it.
    void Collect();

    CacheBudget& m_budget;
    Maker m_make;
    std::vector<std::atomic<BoundTree*>> m_trees;
    std::atomic<uint64_t> m_epoch{1};
    std::atomic<ThreadSlot*> m_threads{nullptr};
    std::atomic<uint64_t> m_made{0};
    struct RetiredTree {
        BoundTree* tree;
        uint64_t epoch;  // threads announcing it or earlier may still be about to use the tree
    };
    std::mutex m_incomingMutex;             // Retire's queue (taken last: never held while taking another)
    std::vector<RetiredTree> m_incoming;    // under m_incomingMutex
    std::atomic<uint64_t> m_pending{0};     // trees retired and not freed
    std::mutex m_collectMutex;              // the thread freeing trees (taken before the budget's)
    std::vector<RetiredTree> m_collecting;  // under m_collectMutex
    BoundTreeStats m_freedStats;            // under m_collectMutex
};

}  // namespace affray::renderer
