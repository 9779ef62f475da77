// scene/geometry/pole.cpp: finding a patch's collapsed edges and dividing out their factor
// (scene/geometry/pole.h). Runs once per patch, in doubles.
#include "scene/geometry/pole.h"

#include <algorithm>
#include <cmath>

namespace affray::renderer {

namespace {

/// An edge collapses when its points agree to this fraction of the patch's size. Exported files
/// print 6 or 7 significant digits, so the points of a collapsed edge of a rational patch (x w,
/// y w, z w, w, with w 0.8047) agree only to about 1e-6 of their size once divided by w.
constexpr double kCollapsed = 1e-5;

/// Collapsed edges are found along parameter `axis` of a patch whose homogeneous coefficients
/// coef(i, j) (of s^i t^j) are given by degree along and across that parameter: `along` is the
/// parameter of the collapsed edges' ends (1 = t), so an edge is {along = e}.
template <class Coef>
std::shared_ptr<const PatchPoles> FindAlong(int axis, int degreeU, int degreeV, const Coef& coef) {
    // Re-index so that `a` runs along the edge (the other parameter) and `b` across (the
    // parameter whose ends may collapse): coefficient (a, b).
    const int degreeA = axis == 1 ? degreeU : degreeV, degreeB = axis == 1 ? degreeV : degreeU;
    auto at = [&](int a, int b) { return axis == 1 ? coef(a, b) : coef(b, a); };
    double size = 0;
    for (int a = 0; a <= degreeA; ++a)
        for (int b = 0; b <= degreeB; ++b) {
            const glm::dvec4 x = at(a, b);
            size = std::max({size, std::fabs(x.x), std::fabs(x.y), std::fabs(x.z)});
        }
    if (!(size > 0) || !std::isfinite(size)) return nullptr;
    // The edge b = e as a polynomial in a: H_a = sum_b coef(a, b) e^b; it collapses to C = H_0 / w.
    bool collapsed[2];
    glm::dvec3 point[2];
    double scale = size;
    for (int e = 0; e < 2; ++e) {
        std::vector<glm::dvec4> h(static_cast<size_t>(degreeA) + 1, glm::dvec4(0.0));
        for (int a = 0; a <= degreeA; ++a)
            for (int b = 0; b <= (e == 0 ? 0 : degreeB); ++b) h[a] += at(a, b);  // X(s, e): e^b is 0 or 1
        collapsed[e] = h[0].w > 0;
        if (!collapsed[e]) continue;
        point[e] = glm::dvec3(h[0]) / h[0].w;
        scale = std::max(scale, glm::length(point[e]));
        for (int a = 1; a <= degreeA; ++a) {
            const glm::dvec3 rest = glm::dvec3(h[a]) - point[e] * h[a].w;
            if (!(std::max({std::fabs(rest.x), std::fabs(rest.y), std::fabs(rest.z)}) <= kCollapsed * scale))
                collapsed[e] = false;
        }
    }
    if (!collapsed[0] && !collapsed[1]) return nullptr;
    // G = X - L W with L = C0 + (C1 - C0) b (C1 - C0 = 0 unless both collapse), degree in b one
    // more than X's when both collapse; then G / D by synthetic division in b, per a.
    const bool both = collapsed[0] && collapsed[1];
    const glm::dvec3 c0 = collapsed[0] ? point[0] : point[1];
    const glm::dvec3 slope = both ? point[1] - point[0] : glm::dvec3(0.0);
    const int degreeG = degreeB + (both ? 1 : 0);
    const int degreeY = degreeG - (both ? 2 : 1);
    if (degreeY < 0) return nullptr;
    auto poles = std::make_shared<PatchPoles>();
    poles->axis = axis;
    poles->sign = collapsed[0] && !both ? 1.0 : -1.0;
    std::vector<glm::dvec3> y(static_cast<size_t>(degreeA + 1) * static_cast<size_t>(degreeY + 1));
    for (int a = 0; a <= degreeA; ++a) {
        std::vector<glm::dvec3> g(static_cast<size_t>(degreeG) + 1, glm::dvec3(0.0));
        for (int b = 0; b <= degreeB; ++b) {
            const glm::dvec4 x = at(a, b);
            g[b] += glm::dvec3(x) - c0 * x.w;
            if (both) g[b + 1] -= slope * x.w;
        }
        // Divide by (b - r) for each root r of D: 0 if the edge b = 0 collapses, 1 if b = 1 does.
        for (int e = 0; e < 2; ++e) {
            if (!collapsed[e]) continue;
            const double r = e;
            std::vector<glm::dvec3> q(g.size() - 1, glm::dvec3(0.0));
            glm::dvec3 carry(0.0);
            for (int k = static_cast<int>(g.size()) - 1; k >= 1; --k) {
                carry = g[k] + r * carry;
                q[k - 1] = carry;
            }
            g = q;  // the remainder g[0] + r q[0] (the edge's extent, below kCollapsed) is dropped
        }
        for (int b = 0; b <= degreeY; ++b) {
            const int i = axis == 1 ? a : b, j = axis == 1 ? b : a;
            const int degreeVOfY = axis == 1 ? degreeY : degreeA;
            y[static_cast<size_t>(degreeVOfY + 1) * i + j] = g[b];
        }
    }
    poles->degreeU = axis == 1 ? degreeA : degreeY;
    poles->degreeV = axis == 1 ? degreeY : degreeA;
    poles->y = std::move(y);
    return poles;
}

template <class Coef>
std::shared_ptr<const PatchPoles> Find(int degreeU, int degreeV, const Coef& coef) {
    if (auto poles = FindAlong(1, degreeU, degreeV, coef)) return poles;
    return FindAlong(0, degreeU, degreeV, coef);
}

}  // namespace

std::shared_ptr<const PatchPoles> FindPatchPoles(const BicubicPatch& patch) {
    return Find(3, 3, [&](int i, int j) { return glm::dvec4(patch.c[4 * i + j], i == 0 && j == 0 ? 1.0 : 0.0); });
}

std::shared_ptr<const PatchPoles> FindPatchPoles(const RationalPatch& patch) {
    return Find(patch.degreeU, patch.degreeV, [&](int i, int j) {
        glm::dvec4 x = patch.c[patch.Index(i, j)];
        if (!patch.rational) x.w = i == 0 && j == 0 ? 1.0 : 0.0;
        return x;
    });
}

}  // namespace affray::renderer
