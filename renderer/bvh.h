// renderer/bvh.h: the top-level bounding volume hierarchy over a scene's primitives. Each primitive
// is boxed by its whole-domain bound (the displaced surface's bound over all of (u,v),
// renderer/render.cpp), so a ray only starts the guaranteed intersector of the primitives whose
// boxes it crosses, nearest box first. The boxes are conservative (a primitive's points lie inside
// its box), and so is the slab test (widened for rounding): the hierarchy never hides a hit.
//
// Built top-down with a binned surface-area heuristic (SAH): a node's primitives are put in 16 bins
// along each axis of their centres' extent, and split between two bins where the sum over the two
// sides of (box area x primitives) is least (MacDonald and Booth 1990, "Heuristics for ray tracing
// using space subdivision": a ray crossing a box crosses a box inside it with a chance near the
// ratio of their areas; binning: Wald 2007, "On fast construction of SAH-based bounding volume
// hierarchies"). Where no split separates the centres (they coincide, or every finite split has an
// infinite side) the node splits at the median of the centres' longest axis, as the whole build did
// before. Leaves hold at most kLeafPrimitives primitives, each with its box in floats (rounded
// outwards, so still conservative), and each node's box is the union of its primitives' float boxes
// (the same as rounding their union outwards): a node is 32 bytes and there are between n - 1 and
// 2n - 1 of them (1.12n to 1.19n on the benchmark's inputs), a leaf's primitive 28 bytes: some 64
// bytes a primitive. Leaves of two visit their primitives nearest entry first, as a leaf per
// primitive did. The order a tree visits primitives in does not change the image (issue 32: before,
// where two surfaces' hits lay within the tolerance of each other, the one met second was kept, and
// the SAH tree changed 7 of the 18 scenes, scenes/mixed.rib by RMSE 3e-3 where the cone stands on
// the displaced floor): renderer/render.cpp's TraceNearest keeps the nearest hit (equal ones in an
// order of their own), searching each primitive from its box's entry, which Traverse passes; a
// node's entry is never past its primitives' (the union of their float boxes, and the slab test
// is monotone in a box's sides), so skipping boxes entered beyond tMax skips no hit at tMax or
// nearer.
//
// Why SAH: a median split cuts clusters and long thin primitives wherever the count says, so its
// nodes overlap and a ray tests more boxes; SAH puts the cut where the empty space is. It does not
// change how many primitives' boxes a ray crosses (each is tested before its intersector starts),
// only how many node boxes it tests to find them, and how soon the nearest hit prunes the rest: a
// closest-hit search through a million clustered boxes took 2.4 times less time (SAH cost 321
// against 573), through a height field's faces, which the median already cuts well, the same (198
// against 212).
// Cost: a pass over a node's primitives to bin them and one to partition them, O(n log n) in all: a
// million boxes in 1.0 to 1.3 s on one core (bench/bvh_bench.cpp, a height field's faces and
// clusters), about what the median build it replaces took (1.2 to 2.2 s: nth_element through
// indices into the double boxes), and 0.7 to 0.9 s on two. With a ThreadPool the top levels bin
// their primitives on all threads until there are 4 subtrees a thread, then the subtrees are built
// on the threads at once, each into its own nodes, and copied into one exact vector in the order a
// serial build makes: the tree is the same, node for node, for any number of threads.
//
// Depth: Traverse's stack holds 64 entries, enough for leaves at depth 63 at most (a node at depth
// d leaves at most d pending siblings below its two children). SAH can build deep chains
// (primitives peeled off a few at a time: points spaced geometrically over float's range went 76
// deep), so a split is taken only if median splits below it would still end within depth 63
// (kMaxDepth); otherwise the node splits at the median.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "diag/check.h"
#include "scene/geometry/camera.h"

namespace affray::renderer {

class ThreadPool;

/// An axis-aligned box; empty if lo > hi on any axis. An infinite box (from a bound that
/// overflows) is crossed by every ray.
struct Box {
    glm::dvec3 lo{INFINITY}, hi{-INFINITY};

    bool empty() const { return lo.x > hi.x || lo.y > hi.y || lo.z > hi.z; }
    void Extend(const Box& b) {
        lo = glm::min(lo, b.lo);
        hi = glm::max(hi, b.hi);
    }
    void Extend(const glm::dvec3& p) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    /// The range [*t0, *t1] of t over which origin + t dir is inside the box, clipped to the
    /// given range; false if it is empty. Conservative: widened for the rounding of the slabs.
    bool Clip(const Ray& ray, double* t0, double* t1) const;
};

class Bvh {
  public:
    /// How a node's primitives are split between its children.
    enum class Split {
        kSah,     ///< the binned surface-area heuristic (the median where it finds no split)
        kMedian,  ///< always the median of the centres' longest axis (for comparison)
    };

    /// Builds over `boxes`; primitive i is boxes[i]. Empty boxes are left out (never visited).
    /// With a pool the build runs on its threads (a build from inside a job of the pool runs on
    /// the calling thread); the tree is the same for any pool or none.
    explicit Bvh(const std::vector<Box>& boxes, ThreadPool* pool = nullptr, Split split = Split::kSah);

    /// Calls visit(i, tEntry) for every primitive whose box the ray crosses within [tMin, *tMax],
    /// nearer leaves first (by entry; a leaf's primitives in its order), skipping boxes entered
    /// beyond *tMax, which `visit` may lower (to the nearest hit so far) through the caller's
    /// variable; Traverse only reads it. visit returns false to stop the traversal (any-hit).
    /// tEntry, at least tMin, is where the ray enters i's box: a function of the ray, tMin and
    /// that box alone (not of *tMax or the tree), at or before every point of the box on the ray.
    template <class Visit>
    void Traverse(const Ray& ray, double tMin, const double* tMax, Visit&& visit) const;

    int nodeCount() const { return static_cast<int>(m_nodes.size()); }
    /// The memory the hierarchy holds.
    size_t bytes() const {
        return m_nodes.capacity() * sizeof(Node) + m_items.capacity() * (sizeof(int) + sizeof(FloatBox));
    }

    /// The tree's surface-area cost: the number of boxes Traverse tests, on average over the rays
    /// that cross the root's box (uniformly distributed lines), if no hit lowers tMax: the root's,
    /// then for each inner node the ray crosses its children's, for each leaf its primitives'. A
    /// node's chance is its area over the root's (MacDonald and Booth 1990). Infinite if the
    /// root's box is; 0 for an empty hierarchy.
    double SahCost() const;
    /// The depth of the deepest leaf (the root's is 0), at most kMaxDepth; -1 if empty.
    int depth() const;
    /// The same tree over the same primitives, node for node (the build is deterministic).
    friend bool operator==(const Bvh&, const Bvh&) = default;

    static constexpr int kLeafPrimitives = 2;
    /// The deepest a leaf may be: Traverse's stack of 64 entries holds every pending node then.
    static constexpr int kMaxDepth = 63;

  private:
    /// A box in floats, rounded outwards (FromBox): a superset of the box it was made from.
    struct FloatBox {
        float lo[3], hi[3];
        static FloatBox FromBox(const Box& b);
        Box ToBox() const { return {{lo[0], lo[1], lo[2]}, {hi[0], hi[1], hi[2]}}; }
        bool operator==(const FloatBox&) const = default;
    };
    struct Node {
        FloatBox box;
        /// An inner node's children are nodes a and b; a leaf (b < 0) holds the -b primitives
        /// m_items[a .. a - b).
        int32_t a = -1, b = 0;
        bool operator==(const Node&) const = default;
    };
    struct Builder;  // the build's state and steps (renderer/bvh.cpp)

    std::vector<Node> m_nodes;
    std::vector<int> m_items;           // the primitives, leaf by leaf
    std::vector<FloatBox> m_itemBoxes;  // their boxes
    int m_root = -1;
};

template <class Visit>
void Bvh::Traverse(const Ray& ray, double tMin, const double* tMax, Visit&& visit) const {
    if (m_root < 0) return;
    struct Entry {
        int node;  // a node, or in a leaf a primitive
        double tEntry;
    };
    Entry stack[64];
    int top = 0;
    double t0 = tMin, t1 = *tMax;
    if (!m_nodes[m_root].box.ToBox().Clip(ray, &t0, &t1)) return;
    stack[top++] = {m_root, t0};
    while (top > 0) {
        const Entry e = stack[--top];
        if (e.tEntry > *tMax) continue;
        const Node& node = m_nodes[e.node];
        if (node.b < 0) {
            // The leaf's primitives whose boxes the ray crosses, nearest entry first.
            Entry hits[kLeafPrimitives];
            int n = 0;
            for (int k = node.a; k < node.a - node.b; ++k) {
                double c0 = tMin, c1 = *tMax;
                if (!m_itemBoxes[k].ToBox().Clip(ray, &c0, &c1)) continue;
                int j = n++;
                for (; j > 0 && hits[j - 1].tEntry > c0; --j) hits[j] = hits[j - 1];
                hits[j] = {m_items[k], c0};
            }
            for (int j = 0; j < n; ++j)
                if (hits[j].tEntry <= *tMax && !visit(hits[j].node, hits[j].tEntry)) return;
            continue;
        }
        Entry children[2];
        int n = 0;
        for (int child : {node.a, node.b}) {
            double c0 = tMin, c1 = *tMax;
            if (m_nodes[child].box.ToBox().Clip(ray, &c0, &c1)) children[n++] = {child, c0};
        }
        // Push the farther first, so that the nearer is visited first.
        if (n == 2 && children[0].tEntry < children[1].tEntry) std::swap(children[0], children[1]);
        // At most one entry per level below the root is pending (kMaxDepth): never full.
        AFFRAY_DCHECK_LE(top + n, 64);
        for (int i = 0; i < n && top < 64; ++i) stack[top++] = children[i];
    }
}

}  // namespace affray::renderer
