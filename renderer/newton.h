// renderer/newton.h: certified Newton hits (issue 31). Krawczyk's test proves that a region of a
// displaced surface meets a ray exactly once, or never, and Newton's iteration then finds that
// point to rounding error, where subdivision alone would stop at the pixel tolerance.
//
// The ray o + t d meets the surface P'(u, v) where G(u, v) = (n1 . (P' - o), n2 . (P' - o)) = 0
// (n1, n2, d an orthonormal frame), at t = d . (P' - o). Over a box X of (u, v), let J be an
// interval matrix that holds every Jacobian of G over X and c any point of X. Krawczyk's operator
//     K(X) = c - Y G(c) + (I - Y J) (X - c),    Y the inverse of J's midpoint (any Y is sound),
// holds every root of G in X: at a root x, G(x) - G(c) = A (x - c) for some A in J (the mean value
// theorem), so x = x - Y G(x) lies in K(X). If K(X) lies in the interior of X, X holds exactly one
// root (Krawczyk 1969, Moore 1977: existence by Brouwer's fixed point theorem; uniqueness because
// every matrix of J is then non-singular). If K(X) and X are disjoint, X holds none. Neumaier,
// "Interval Methods for Systems of Equations" (1990), ch. 5; Toth (1985) used it to ray trace
// parametric surfaces.
// The mean value step needs G continuous over X, with derivative bounds that bound its change:
// the evaluator gives slopes only where the shader cannot jump (RegionEvaluator::Slopes). A kink
// (abs, min, max) is fine: its derivative bound joins both sides, which holds the generalised
// gradient of a Lipschitz function, and the mean value theorem holds for those (Clarke 1983).
#pragma once

#include <glm/glm.hpp>

#include "renderer/bound_tree.h"
#include "vm/numbers/interval.h"

namespace affray::renderer {

/// A box of the two parameters (u, v).
struct Box2 {
    vm::Interval x[2];
};

/// What Krawczyk's test proves about a box.
enum class Roots { None, One, Unknown };

/// Krawczyk's test of the box `X` for G = 0, with `c` a point (in X or not: the mean value step
/// only needs J to hold G's Jacobians between c and X's points), `g` an enclosure of G(c) and `J`
/// of every Jacobian of G over the hull of X and c. Sets *image to K(X) (rounded outward), which
/// holds every root in X whatever the answer. One: K(X) lies in X's interior; None: K(X) misses X.
Roots Krawczyk(const Box2& X, const double (&c)[2], const vm::Interval (&g)[2], const vm::Interval (&J)[2][2],
               Box2* image);

/// A ray's orthonormal frame: n[0], n[1] across the ray, n[2] its direction; `origin` its origin.
struct RayFrame {
    glm::dvec3 origin;
    glm::dvec3 n[3];
};

/// What certifying a region gave: Roots::One with the ray parameter t of its one meeting point in
/// [tLo, tHi], at the surface parameters (u, v), every surface point of the final box lying within
/// `error` of o + t d; None (the region never meets the ray's line); or Unknown (subdivide).
struct NewtonHit {
    Roots roots = Roots::Unknown;
    double t = 0, tLo = 0, tHi = 0;
    double u = 0, v = 0;
    double error = 0;
};

/// A region [u0,u1] x [v0,v1] of the surface's own parameters (what the intersector splits) and
/// the part of it where the ray can meet the surface, [ru0,ru1] x [rv0,rv1].
struct NewtonRegion {
    double u0, u1, v0, v1;
    double ru0, ru1, rv0, rv1;
};

/// Certifies where the ray's line meets the displaced surface over the reachable part of the
/// region: the region's slopes (RegionEvaluator::Slopes), restricted to that part; Newton's steps
/// in doubles from (uStart, vStart) within it; Krawczyk's test at their end, and on success a
/// second test of a box of about the root's rounding (no further evaluation).
NewtonHit CertifyRegion(RegionEvaluator& evaluator, const RayFrame& ray, const NewtonRegion& region, double uStart,
                        double vStart);

}  // namespace affray::renderer
