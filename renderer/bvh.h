// renderer/bvh.h: the top-level bounding volume hierarchy over a scene's primitives.
// Each primitive is boxed by its whole-domain bound (the displaced surface's bound over all of
// (u,v), renderer/render.cpp), so a ray only starts the guaranteed intersector of the primitives
// whose boxes it crosses, nearest box first. The boxes are conservative (a primitive's points lie
// inside its box), and so is the slab test (widened for rounding): the hierarchy never hides a hit.
// Built by splitting at the median of the longest axis of the box centres (nth_element: O(n log n)),
// down to leaves of at most kLeafPrimitives primitives, each with its box in floats (rounded
// outwards, so still conservative), and each node's box in floats likewise: a node is 32 bytes
// and there are about n of them, a leaf's primitive 28 bytes, so a mesh of a million faces costs
// some 60 bytes per face here (a leaf per primitive with its box in doubles cost 128). Leaves of two visit their primitives in the order a
// leaf per primitive did (nearest entry first), so images do not change; leaves of four did
// change them within the tolerance (a different one of two overlapping hits found first: the
// showcase's RMSE 6e-4). A surface-area heuristic would buy little: the time goes into bounding the
// displaced surfaces.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "scene/geometry/camera.h"

namespace affray::renderer {

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
    /// Builds over `boxes`; primitive i is boxes[i]. Empty boxes are left out (never visited).
    explicit Bvh(const std::vector<Box>& boxes);

    /// Calls visit(i, tEntry) for every primitive whose box the ray crosses within [tMin, *tMax],
    /// nearer leaves first (by entry; a leaf's primitives in its order), skipping boxes entered
    /// beyond *tMax, which `visit` may lower (to the nearest hit so far) through the caller's
    /// variable; Traverse only reads it. visit returns false to stop the traversal (any-hit).
    template <class Visit>
    void Traverse(const Ray& ray, double tMin, const double* tMax, Visit&& visit) const;

    int nodeCount() const { return static_cast<int>(m_nodes.size()); }
    /// The memory the hierarchy holds.
    size_t bytes() const {
        return m_nodes.capacity() * sizeof(Node) + m_items.capacity() * (sizeof(int) + sizeof(FloatBox));
    }

    static constexpr int kLeafPrimitives = 2;

  private:
    /// A box in floats, rounded outwards (FromBox): a superset of the box it was made from.
    struct FloatBox {
        float lo[3], hi[3];
        static FloatBox FromBox(const Box& b);
        Box ToBox() const { return {{lo[0], lo[1], lo[2]}, {hi[0], hi[1], hi[2]}}; }
    };
    struct Node {
        FloatBox box;
        /// An inner node's children are nodes a and b; a leaf (b < 0) holds the -b primitives
        /// m_items[a .. a - b).
        int32_t a = -1, b = 0;
    };

    int Build(int begin, int end, const std::vector<Box>& boxes);

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
        for (int i = 0; i < n && top < 64; ++i) stack[top++] = children[i];
    }
}

}  // namespace affray::renderer
