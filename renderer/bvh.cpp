// renderer/bvh.cpp: building the top-level hierarchy and the slab test (renderer/bvh.h).
#include "renderer/bvh.h"

#include <algorithm>
#include <cfloat>
#include <cmath>

namespace affray::renderer {

bool Box::Clip(const Ray& ray, double* t0, double* t1) const {
    if (empty()) return false;
    double lo = *t0, hi = *t1;
    for (int i = 0; i < 3; ++i) {
        const double o = ray.origin[i], d = ray.dir[i];
        if (d == 0) {
            if (o < this->lo[i] || o > this->hi[i]) return false;
            continue;
        }
        // Infinite box sides give infinite slab ends, which is right: a box unbounded along an
        // axis limits nothing there. 0 * inf cannot occur: d != 0.
        double a = (this->lo[i] - o) / d, b = (this->hi[i] - o) / d;
        if (a > b) std::swap(a, b);
        // The subtraction and division each round by half an ulp: widen by a few.
        if (std::isfinite(a)) a -= 4e-16 * std::fabs(a) + 1e-300;
        if (std::isfinite(b)) b += 4e-16 * std::fabs(b) + 1e-300;
        lo = std::max(lo, a);
        hi = std::min(hi, b);
        if (lo > hi) return false;
    }
    *t0 = lo;
    *t1 = hi;
    return true;
}

Bvh::Bvh(const std::vector<Box>& boxes) {
    for (int i = 0; i < static_cast<int>(boxes.size()); ++i)
        if (!boxes[i].empty()) m_items.push_back(i);
    m_items.shrink_to_fit();
    // Exactly the nodes Build makes (a vector grown by doubling held up to twice as many).
    auto nodes = [](auto&& self, size_t n) -> size_t {
        return n <= size_t(kLeafPrimitives) ? 1 : 1 + self(self, n / 2) + self(self, n - n / 2);
    };
    if (!m_items.empty()) m_nodes.reserve(nodes(nodes, m_items.size()));
    if (!m_items.empty()) m_root = Build(0, static_cast<int>(m_items.size()), boxes);
    m_itemBoxes.resize(m_items.size());
    for (size_t k = 0; k < m_items.size(); ++k) m_itemBoxes[k] = FloatBox::FromBox(boxes[size_t(m_items[k])]);
}

Bvh::FloatBox Bvh::FloatBox::FromBox(const Box& b) {
    // Rounded outwards (infinite sides stay infinite; a side past float's range is the infinity
    // beyond it or float's largest on its side, whichever keeps the box a superset: converting
    // such a double is undefined).
    auto down = [](double x) {
        if (x > FLT_MAX) return FLT_MAX;
        if (!(x >= -FLT_MAX)) return -INFINITY;
        const float f = static_cast<float>(x);
        return double(f) > x ? std::nextafter(f, -INFINITY) : f;
    };
    auto up = [](double x) {
        if (x < -FLT_MAX) return -FLT_MAX;
        if (!(x <= FLT_MAX)) return INFINITY;
        const float f = static_cast<float>(x);
        return double(f) < x ? std::nextafter(f, INFINITY) : f;
    };
    FloatBox f;
    for (int i = 0; i < 3; ++i) {
        f.lo[i] = down(b.lo[i]);
        f.hi[i] = up(b.hi[i]);
    }
    return f;
}

int Bvh::Build(int begin, int end, const std::vector<Box>& boxes) {
    Box box;
    for (int i = begin; i < end; ++i) box.Extend(boxes[m_items[i]]);
    const int index = static_cast<int>(m_nodes.size());
    m_nodes.push_back({FloatBox::FromBox(box)});
    if (end - begin <= kLeafPrimitives) {
        m_nodes[index].a = begin;
        m_nodes[index].b = begin - end;
        return index;
    }
    // Split at the median of the centres along their longest axis. Infinite boxes have no
    // finite centre: they sort by their finite sides (or last), which only costs balance.
    Box centres;
    auto centre = [&](int item) {
        glm::dvec3 c = 0.5 * (boxes[item].lo + boxes[item].hi);
        for (int i = 0; i < 3; ++i)
            if (!std::isfinite(c[i])) c[i] = std::isfinite(boxes[item].lo[i]) ? boxes[item].lo[i] : 0.0;
        return c;
    };
    for (int i = begin; i < end; ++i) centres.Extend(centre(m_items[i]));
    const glm::dvec3 extent = centres.hi - centres.lo;
    const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
    const int mid = (begin + end) / 2;
    std::nth_element(m_items.begin() + begin, m_items.begin() + mid, m_items.begin() + end,
                     [&](int a, int b) { return centre(a)[axis] < centre(b)[axis]; });
    const int left = Build(begin, mid, boxes);
    const int right = Build(mid, end, boxes);
    m_nodes[index].a = left;
    m_nodes[index].b = right;
    return index;
}

}  // namespace affray::renderer
