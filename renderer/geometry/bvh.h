// renderer/geometry/bvh.h: the top-level bounding volume hierarchy over a scene's primitives.
// Each primitive is boxed by its whole-domain bound (the displaced surface's bound over all of
// (u,v), renderer/render.cpp), so a ray only starts the guaranteed intersector of the primitives
// whose boxes it crosses, nearest box first. The boxes are conservative (a primitive's points lie
// inside its box), and so is the slab test (widened for rounding): the hierarchy never hides a hit.
// Built by splitting at the median of the longest axis of the box centres (nth_element: O(n log n)).
// A scene's primitives are its quadrics, patches and mesh pieces: thousands, not the millions of a
// tessellation, and the time goes into bounding the displaced surfaces, not into this tree: a
// surface-area heuristic would buy little here.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "renderer/geometry/camera.h"

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
    /// nearer boxes first (by entry), skipping boxes entered beyond *tMax, which `visit` may
    /// lower (to the nearest hit so far) through the caller's variable; Traverse only reads it. visit returns false to stop the traversal (any-hit).
    template <class Visit>
    void Traverse(const Ray& ray, double tMin, const double* tMax, Visit&& visit) const;

    int nodeCount() const { return static_cast<int>(m_nodes.size()); }

  private:
    struct Node {
        Box box;
        int left = -1, right = -1;  // children; -1 -1 for a leaf
        int primitive = -1;         // a leaf's primitive
    };
    int Build(std::vector<int>& items, int begin, int end, const std::vector<Box>& boxes);

    std::vector<Node> m_nodes;
    int m_root = -1;
};

template <class Visit>
void Bvh::Traverse(const Ray& ray, double tMin, const double* tMax, Visit&& visit) const {
    if (m_root < 0) return;
    struct Entry {
        int node;
        double tEntry;
    };
    Entry stack[64];
    int top = 0;
    double t0 = tMin, t1 = *tMax;
    if (!m_nodes[m_root].box.Clip(ray, &t0, &t1)) return;
    stack[top++] = {m_root, t0};
    while (top > 0) {
        const Entry e = stack[--top];
        if (e.tEntry > *tMax) continue;
        const Node& node = m_nodes[e.node];
        if (node.left < 0) {
            if (!visit(node.primitive, e.tEntry)) return;
            continue;
        }
        Entry children[2];
        int n = 0;
        for (int child : {node.left, node.right}) {
            double c0 = tMin, c1 = *tMax;
            if (m_nodes[child].box.Clip(ray, &c0, &c1)) children[n++] = {child, c0};
        }
        // Push the farther first, so that the nearer is visited first.
        if (n == 2 && children[0].tEntry < children[1].tEntry) std::swap(children[0], children[1]);
        for (int i = 0; i < n && top < 64; ++i) stack[top++] = children[i];
    }
}

}  // namespace affray::renderer
