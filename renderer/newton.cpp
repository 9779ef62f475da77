// renderer/newton.cpp: Krawczyk's test and the certified Newton hit of a region (newton.h).
#include "renderer/newton.h"

#include "renderer/measure.h"

#include <algorithm>
#include <cmath>

namespace affray::renderer {

namespace {

using vm::Interval;

/// The part of `a` in `b`; false if they are disjoint.
bool Intersect(const Interval& a, const Interval& b, Interval* out) {
    const double lo = std::max(a.lo(), b.lo()), hi = std::min(a.hi(), b.hi());
    if (lo > hi) return false;
    *out = Interval(lo, hi);
    return true;
}

/// The largest |x| over `a`.
double Magnitude(const Interval& a) { return std::max(std::fabs(a.lo()), std::fabs(a.hi())); }

/// n . x over the points x of the bound `b` whose eps lie in [eu0, eu1] x [ev0, ev1] (within
/// [-1, 1]), rounding included (renderer/measure.h); unbounded if b is along n.
Interval Along(const RegionBound& b, const glm::dvec3& n, double eu0, double eu1, double ev0, double ev1) {
    const glm::dvec3 direction[1] = {n};
    Measure m[1];
    MeasureAlong<1>(b, glm::dvec3(0.0), direction, m);
    if (!m[0].bounded) return Interval::Unbounded();
    const Range r = OverBox(m[0], eu0, eu1, ev0, ev1);
    return Interval(r.lo, r.hi);
}

/// Newton's steps for G = 0 in doubles from (u, v), kept within the region: where they end. They
/// need not converge: Krawczyk's test decides, and its box narrows to rounding only if they did.
void NewtonSteps(RegionEvaluator& evaluator, const RayFrame& ray, double u0, double u1, double v0, double v1, double* u,
                 double* v) {
    const double scaleU = std::fabs(u0) + std::fabs(u1), scaleV = std::fabs(v0) + std::fabs(v1);
    for (int step = 0; step < 8; ++step) {
        glm::dvec3 p, pu, pv;
        if (!evaluator.PointFrame(*u, *v, &p, &pu, &pv)) return;
        const glm::dvec3 rel = p - ray.origin;
        const double g0 = glm::dot(ray.n[0], rel), g1 = glm::dot(ray.n[1], rel);
        const double a = glm::dot(ray.n[0], pu), b = glm::dot(ray.n[0], pv);
        const double c = glm::dot(ray.n[1], pu), d = glm::dot(ray.n[1], pv);
        const double det = a * d - b * c;
        if (!(std::fabs(det) > 0) || !std::isfinite(det)) return;
        const double du = (d * g0 - b * g1) / det, dv = (a * g1 - c * g0) / det;
        if (!std::isfinite(du) || !std::isfinite(dv)) return;
        *u = std::clamp(*u - du, u0, u1);
        *v = std::clamp(*v - dv, v0, v1);
        if (std::fabs(du) <= 0x1p-50 * scaleU && std::fabs(dv) <= 0x1p-50 * scaleV) return;
    }
}

/// Krawczyk's operator for one G(c) and J: K(X) = c - Y G(c) + M (X - c), M = I - Y J, with
/// Y G(c) and M computed once for every box it is applied to.
class KrawczykMap {
  public:
    KrawczykMap(const Interval (&g)[2], const Interval (&J)[2][2]) {
        for (int i = 0; i < 2; ++i)
            if (g[i].isUnbounded() || J[i][0].isUnbounded() || J[i][1].isUnbounded()) return;
        // Y: the inverse of J's midpoint, in doubles (its rounding only makes it a slightly
        // different preconditioner; the operator is sound for any Y).
        const double m00 = J[0][0].mid(), m01 = J[0][1].mid(), m10 = J[1][0].mid(), m11 = J[1][1].mid();
        const double det = m00 * m11 - m01 * m10;
        if (!(std::fabs(det) > 0) || !std::isfinite(det)) return;
        const double Y[2][2] = {{m11 / det, -m01 / det}, {-m10 / det, m00 / det}};
        for (int i = 0; i < 2; ++i) {
            if (!std::isfinite(Y[i][0]) || !std::isfinite(Y[i][1])) return;
            m_yg[i] = Y[i][0] * g[0] + Y[i][1] * g[1];
            for (int j = 0; j < 2; ++j)
                m_m[i][j] = Interval(i == j ? 1.0 : 0.0) - (Y[i][0] * J[0][j] + Y[i][1] * J[1][j]);
        }
        m_valid = true;
    }
    bool valid() const { return m_valid; }
    /// K(X), every operation rounded outward; false if unbounded.
    bool Apply(const Box2& X, const double (&c)[2], Box2* k) const {
        const Interval d[2] = {X.x[0] - c[0], X.x[1] - c[1]};
        for (int i = 0; i < 2; ++i) {
            k->x[i] = Interval(c[i]) - m_yg[i] + m_m[i][0] * d[0] + m_m[i][1] * d[1];
            if (k->x[i].isUnbounded()) return false;
        }
        return true;
    }
    /// |Y G(c)| and |M|, for sizing a box (not for proofs).
    double offset(int i) const { return Magnitude(m_yg[i]); }
    double contraction(int i, int j) const { return Magnitude(m_m[i][j]); }

  private:
    bool m_valid = false;
    Interval m_yg[2], m_m[2][2];
};

/// What K = K(X) proves about X (Krawczyk's test).
Roots Verdict(const Box2& X, const Box2& K) {
    bool inside = true;
    for (int i = 0; i < 2; ++i) {
        if (K.x[i].hi() < X.x[i].lo() || K.x[i].lo() > X.x[i].hi()) return Roots::None;
        inside = inside && K.x[i].lo() > X.x[i].lo() && K.x[i].hi() < X.x[i].hi();
    }
    return inside ? Roots::One : Roots::Unknown;
}

/// A box of about the root's rounding around c, within X, that the operator proves holds the
/// root (K(box) in its interior, with X's J), into *box; false if none was found. With c fixed,
/// K(c + [-r, r]) lies within c - Y G(c) + |M| r [-1, 1], so the radius r = (I - |M|)^-1 |Y G(c)|
/// maps into itself where |M| contracts; it is doubled for the operator's own rounding.
bool TightBox(const KrawczykMap& map, const Box2& X, const double (&c)[2], Box2* box) {
    const double off0 = map.offset(0), off1 = map.offset(1);
    const double a = 1 - map.contraction(0, 0), b = map.contraction(0, 1);
    const double cc = map.contraction(1, 0), d = 1 - map.contraction(1, 1);
    const double det = a * d - b * cc;
    if (!(a > 0 && d > 0 && det > 0)) return false;
    const double r0 = 2 * (d * off0 + b * off1) / det + 0x1p-60 * std::fabs(c[0]) + 1e-300;
    const double r1 = 2 * (a * off1 + cc * off0) / det + 0x1p-60 * std::fabs(c[1]) + 1e-300;
    const Box2 tight{{Interval(c[0] - r0, c[0] + r0), Interval(c[1] - r1, c[1] + r1)}};
    for (int i = 0; i < 2; ++i)
        if (tight.x[i].isUnbounded() || tight.x[i].lo() < X.x[i].lo() || tight.x[i].hi() > X.x[i].hi()) return false;
    Box2 k;
    if (!map.Apply(tight, c, &k) || Verdict(tight, k) != Roots::One) return false;
    *box = k;
    return true;
}

}  // namespace

Roots Krawczyk(const Box2& X, const double (&c)[2], const Interval (&g)[2], const Interval (&J)[2][2], Box2* image) {
    *image = X;
    const KrawczykMap map(g, J);
    if (!map.valid()) return Roots::Unknown;
    for (int i = 0; i < 2; ++i)
        if (X.x[i].isUnbounded()) return Roots::Unknown;
    if (!map.Apply(X, c, image)) {
        *image = X;
        return Roots::Unknown;
    }
    return Verdict(X, *image);
}

NewtonHit CertifyRegion(RegionEvaluator& evaluator, const RayFrame& ray, const NewtonRegion& region, double uStart,
                        double vStart) {
    NewtonHit hit;
    SlopeBound slopes;
    if (!evaluator.Slopes(region.u0, region.u1, region.v0, region.v1, &slopes)) return hit;
    const double u0 = region.ru0, u1 = region.ru1, v0 = region.rv0, v1 = region.rv1;
    // The reachable part in the region's eps (u = pu + pr eps_u, surface.h), padded for the
    // rounding of the division (as the intersector's child cull pads it).
    double pu, pr, pv, prv;
    RegionParameter(region.u0, region.u1, &pu, &pr);
    RegionParameter(region.v0, region.v1, &pv, &prv);
    if (!(pr > 0 && prv > 0)) return hit;
    const double padU = 1e-12 + 8 * kUlp * (std::fabs(pu) + pr) / pr;
    const double padV = 1e-12 + 8 * kUlp * (std::fabs(pv) + prv) / prv;
    const double eu0 = std::max(-1.0, (u0 - pu) / pr - padU), eu1 = std::min(1.0, (u1 - pu) / pr + padU);
    const double ev0 = std::max(-1.0, (v0 - pv) / prv - padV), ev1 = std::min(1.0, (v1 - pv) / prv + padV);
    if (!(eu0 <= eu1 && ev0 <= ev1)) return hit;
    // S[k][j]: n_k . dP'/d(u, v)_j over the reachable part.
    Interval S[3][2];
    for (int k = 0; k < 3; ++k)
        for (int j = 0; j < 2; ++j) {
            S[k][j] = Along(j == 0 ? slopes.du : slopes.dv, ray.n[k], eu0, eu1, ev0, ev1);
            if (slopes.rate[j] != 1) S[k][j] = S[k][j] / Interval(slopes.rate[j]);
            if (S[k][j].isUnbounded()) return hit;
        }
    double c[2] = {std::clamp(uStart, u0, u1), std::clamp(vStart, v0, v1)};
    NewtonSteps(evaluator, ray, u0, u1, v0, v1, &c[0], &c[1]);
    // G(c), rounding included: the bound of the surface at the point c, along the frame.
    const RegionBound at = evaluator.Bound(c[0], c[0], c[1], c[1]);
    if (!at.bounded()) return hit;
    // n_k . (P'(c) - o): the point's box relative to o, as a bound of centre and radius only.
    RegionBound rel;
    rel.boundedMask = 7;
    for (int i = 0; i < 3; ++i) {
        rel.c[i] = 0.5 * at.lo[i] + 0.5 * at.hi[i] - ray.origin[i];
        const double r = std::max(at.hi[i] - ray.origin[i] - rel.c[i], rel.c[i] - (at.lo[i] - ray.origin[i]));
        rel.r[i] = r * (1 + 4 * kUlp) + kSlack * (std::fabs(at.lo[i]) + std::fabs(at.hi[i]) + std::fabs(ray.origin[i]));
    }
    Interval q[3];
    for (int k = 0; k < 3; ++k) q[k] = Along(rel, ray.n[k], 0, 0, 0, 0);
    const Interval g[2] = {q[0], q[1]};
    const Interval J[2][2] = {{S[0][0], S[0][1]}, {S[1][0], S[1][1]}};
    const Box2 X{{Interval(u0, u1), Interval(v0, v1)}};
    const KrawczykMap map(g, J);
    Box2 K;
    if (!map.valid() || !map.Apply(X, c, &K)) return hit;
    hit.roots = Verdict(X, K);
    if (hit.roots != Roots::One) return hit;
    // The root lies in K(X) and in X; a box of about its rounding around c, if the operator
    // proves it holds a root (the one root of X), is the certificate.
    Box2 box;
    if (!TightBox(map, X, c, &box))
        for (int i = 0; i < 2; ++i) Intersect(K.x[i], X.x[i], &box.x[i]);
    // Over the box, n_k . (P' - o) lies in q_k + S_k . (box - c): the frame coordinates of the
    // meeting point, t among them.
    Interval frame[3];
    for (int k = 0; k < 3; ++k) frame[k] = q[k] + S[k][0] * (box.x[0] - c[0]) + S[k][1] * (box.x[1] - c[1]);
    for (const Interval& f : frame)
        if (f.isUnbounded()) {
            hit.roots = Roots::Unknown;
            return hit;
        }
    hit.tLo = frame[2].lo();
    hit.tHi = frame[2].hi();
    hit.t = frame[2].mid();
    hit.u = box.x[0].mid();
    hit.v = box.x[1].mid();
    const double along = std::max(hit.t - hit.tLo, hit.tHi - hit.t);
    const double a0 = Magnitude(frame[0]), a1 = Magnitude(frame[1]);
    hit.error = std::sqrt(a0 * a0 + a1 * a1 + along * along) * (1 + 1e-15);
    return hit;
}

}  // namespace affray::renderer
