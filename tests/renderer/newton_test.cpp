// tests/renderer/newton_test.cpp: certified Newton (renderer/newton.h) against exact answers and
// brute force. Krawczyk's test on linear maps, whose roots are known exactly, and on a map with
// two roots in the box; then CertifyRegion over every shader in shaders/, on rays aimed at known
// surface points: a region said to meet the ray once must hold the aimed point within the
// certified error and no second root on a dense grid; a region said to meet it never must not
// hold the aimed point.
#include <catch2/catch.hpp>

#include <filesystem>
#include <random>

#include "renderer/bound_tree.h"
#include "renderer/intersect.h"
#include "renderer/newton.h"
#include "tests/test_util.h"

using namespace affray;
using renderer::Box2;
using renderer::Roots;
using vm::Interval;

namespace {

/// A ray's frame as the intersector builds it.
renderer::RayFrame FrameOf(const glm::dvec3& origin, const glm::dvec3& dir) {
    const glm::dvec3 helper = std::abs(dir.x) < 0.6 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
    const glm::dvec3 n1 = glm::normalize(glm::cross(dir, helper));
    return {origin, {n1, glm::normalize(glm::cross(dir, n1)), dir}};
}

bool Holds(const Box2& b, double u, double v) { return b.x[0].contains(u) && b.x[1].contains(v); }

}  // namespace

TEST_CASE("newton: Krawczyk's verdicts on linear maps hold their exact root", "[renderer][newton]") {
    // G(x) = A (x - r): J is A exactly, G(c) is enclosed by interval arithmetic, and the one root
    // is r. One must mean r in X (and in K); None must mean r outside X; K always holds r if X does.
    std::mt19937_64 rng(31);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    int ones = 0, nones = 0;
    for (int trial = 0; trial < 4000; ++trial) {
        double A[2][2];
        for (auto& row : A)
            for (double& a : row) a = unit(rng);
        if (std::fabs(A[0][0] * A[1][1] - A[0][1] * A[1][0]) < 0.05) continue;
        const double r[2] = {unit(rng), unit(rng)};
        const double half = std::ldexp(1.0, -static_cast<int>(8 * (unit(rng) + 1)));
        const Box2 X{{Interval(r[0] + unit(rng) * 2 * half - half, r[0] + unit(rng) * 2 * half + half),
                      Interval(r[1] + unit(rng) * 2 * half - half, r[1] + unit(rng) * 2 * half + half)}};
        if (X.x[0].isUnbounded() || X.x[1].isUnbounded()) continue;
        const double c[2] = {X.x[0].mid() + 0.3 * unit(rng) * X.x[0].radius(),
                             X.x[1].mid() + 0.3 * unit(rng) * X.x[1].radius()};
        Interval g[2], J[2][2];
        for (int i = 0; i < 2; ++i) {
            g[i] = A[i][0] * (Interval(c[0]) - r[0]) + A[i][1] * (Interval(c[1]) - r[1]);
            for (int j = 0; j < 2; ++j) J[i][j] = Interval(A[i][j]);
        }
        Box2 K;
        const Roots verdict = renderer::Krawczyk(X, c, g, J, &K);
        const bool inside = Holds(X, r[0], r[1]);
        INFO("trial " << trial << " root (" << r[0] << ", " << r[1] << ") X " << ToString(X.x[0]) << " x "
                      << ToString(X.x[1]));
        if (inside) CHECK(Holds(K, r[0], r[1]));
        if (verdict == Roots::One) {
            ++ones;
            CHECK(inside);
        }
        if (verdict == Roots::None) {
            ++nones;
            CHECK_FALSE(inside);
        }
    }
    // With J exact the operator is sharp: most boxes are decided either way.
    CHECK(ones > 500);
    CHECK(nones > 500);
}

TEST_CASE("newton: a box with two roots is never proved to hold one", "[renderer][newton]") {
    // G(u, v) = (u^2 - a^2, v): roots (+-a, 0). J over X is [[2 U, 0], [0, 1]].
    for (double a : {0.001, 0.01, 0.1, 0.4}) {
        for (double spread : {1.01, 1.5, 3.0}) {
            const Box2 X{{Interval(-a * spread, a * spread * 0.9), Interval(-0.1, 0.2)}};
            const double c[2] = {a * 0.5, 0.01};
            const Interval J[2][2] = {{2 * X.x[0], Interval(0.0)}, {Interval(0.0), Interval(1.0)}};
            const Interval g[2] = {sqr(Interval(c[0])) - a * a, Interval(c[1])};
            Box2 K;
            INFO("a " << a << " spread " << spread);
            CHECK(renderer::Krawczyk(X, c, g, J, &K) != Roots::One);
            CHECK(Holds(K, a, 0.0));
            CHECK(Holds(K, -a, 0.0));
            // A small box around +a alone is proved to hold exactly one.
            const Box2 near{{Interval(a * 0.99, a * 1.01), Interval(-0.01, 0.01)}};
            const double cn[2] = {a, 0.0};
            const Interval Jn[2][2] = {{2 * near.x[0], Interval(0.0)}, {Interval(0.0), Interval(1.0)}};
            const Interval gn[2] = {sqr(Interval(a)) - a * a, Interval(0.0)};
            CHECK(renderer::Krawczyk(near, cn, gn, Jn, &K) == Roots::One);
            CHECK(Holds(K, a, 0.0));
        }
    }
}

TEST_CASE("newton: an image inside the box at one end only proves nothing", "[renderer][newton]") {
    // G(u, v) = (G0(u), v) with G0(0.5) = -0.5 and G0' anywhere in [0.5, 1.5] over X = [0, 1] x
    // [-1, 1], c = (0.5, 0). Y = I (J's midpoint), I - Y J = diag([-0.5, 0.5], 0), so by hand
    // K(X) = (0.5 + 0.5 + [-0.5, 0.5] (X0 - 0.5), 0) = ([0.75, 1.25], [0, 0]): inside X at u's
    // low end, past it at the high end. Such a G0 may have no root in X (slope 0.5: root 1.5) or
    // one (slope 1.5: root 5/6), so neither One nor None may be said.
    const Box2 X{{Interval(0.0, 1.0), Interval(-1.0, 1.0)}};
    const double c[2] = {0.5, 0.0};
    const Interval g[2] = {Interval(-0.5), Interval(0.0)};
    const Interval J[2][2] = {{Interval(0.5, 1.5), Interval(0.0)}, {Interval(0.0), Interval(1.0)}};
    Box2 K;
    CHECK(renderer::Krawczyk(X, c, g, J, &K) == Roots::Unknown);
    CHECK(K.x[0].lo() <= 0.75);
    CHECK(K.x[0].hi() >= 1.25);
    // The same past the low end ([-0.25, 0.25]: G0(0.5) = 0.5), and past v's high end (the
    // components swapped).
    const Interval gLow[2] = {Interval(0.5), Interval(0.0)};
    CHECK(renderer::Krawczyk(X, c, gLow, J, &K) == Roots::Unknown);
    const Box2 Xs{{Interval(-1.0, 1.0), Interval(0.0, 1.0)}};
    const double cs[2] = {0.0, 0.5};
    const Interval gs[2] = {Interval(0.0), Interval(-0.5)};
    const Interval Js[2][2] = {{Interval(1.0), Interval(0.0)}, {Interval(0.0), Interval(0.5, 1.5)}};
    CHECK(renderer::Krawczyk(Xs, cs, gs, Js, &K) == Roots::Unknown);
    // With G0(0.5) = -0.25 and G0' in [0.8, 1.2] every such G0 has its one root in [0.70, 0.82],
    // and K(X) = ([0.65, 0.85], [0, 0]) lies inside X: one root.
    const Interval gIn[2] = {Interval(-0.25), Interval(0.0)};
    const Interval JIn[2][2] = {{Interval(0.8, 1.2), Interval(0.0)}, {Interval(0.0), Interval(1.0)}};
    CHECK(renderer::Krawczyk(X, c, gIn, JIn, &K) == Roots::One);
}

namespace {

/// A plane P(u, v) = p0 + u a + v b with exact slopes, as an evaluator: CertifyRegion's own
/// arithmetic (slopes along the ray frame, G at Newton's point, the box) is all that is tested.
class PlaneEvaluator final : public renderer::RegionEvaluator {
  public:
    PlaneEvaluator(const glm::dvec3& p0, const glm::dvec3& a, const glm::dvec3& b) : m_p0(p0), m_a(a), m_b(b) {}
    renderer::RegionBound Bound(double u0, double u1, double v0, double v1) override {
        renderer::RegionBound out;
        for (int i = 0; i < 3; ++i) {
            const Interval x = m_p0[i] + m_a[i] * Interval(u0, u1) + m_b[i] * Interval(v0, v1);
            out.lo[i] = x.lo();
            out.hi[i] = x.hi();
            out.c[i] = x.mid();
            out.r[i] = x.radius();
        }
        out.boundedMask = 7;
        return out;
    }
    bool PointAt(double u, double v, glm::dvec3* p) override {
        *p = m_p0 + u * m_a + v * m_b;
        return true;
    }
    bool slopes() const override { return true; }
    bool Slopes(double, double, double, double, renderer::SlopeBound* out) override {
        *out = renderer::SlopeBound{};
        for (int i = 0; i < 3; ++i) {
            out->du.c[i] = out->du.lo[i] = out->du.hi[i] = m_a[i];
            out->dv.c[i] = out->dv.lo[i] = out->dv.hi[i] = m_b[i];
        }
        out->du.boundedMask = out->dv.boundedMask = 7;
        return true;
    }
    bool PointFrame(double u, double v, glm::dvec3* p, glm::dvec3* pu, glm::dvec3* pv) override {
        *p = m_p0 + u * m_a + v * m_b;
        *pu = m_a;
        *pv = m_b;
        return true;
    }

  private:
    glm::dvec3 m_p0, m_a, m_b;
};

}  // namespace

TEST_CASE("newton: a plane's region holds the ray's point exactly when it says so", "[renderer][newton]") {
    // The ray meets the plane at a known (u*, v*): a region holding it is proved to hold one
    // root, there; a region beside it (Newton's steps stop at its edge) is proved to hold none.
    std::mt19937_64 rng(37);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    int ones = 0, nones = 0;
    for (int trial = 0; trial < 2000; ++trial) {
        const glm::dvec3 a(0.5 + unit(rng), 0.8 * unit(rng) - 0.4, 0.3 * unit(rng));
        const glm::dvec3 b(0.6 * unit(rng) - 0.3, 0.2 + 2 * unit(rng), 0.3 * unit(rng) - 0.15);
        PlaneEvaluator plane(glm::dvec3(unit(rng), unit(rng), unit(rng)), a, b);
        const double us = unit(rng), vs = unit(rng);
        glm::dvec3 target;
        plane.PointAt(us, vs, &target);
        const glm::dvec3 normal = glm::normalize(glm::cross(a, b));
        glm::dvec3 dir = glm::normalize(-normal + 0.6 * glm::dvec3(unit(rng) - 0.5, unit(rng) - 0.5, unit(rng) - 0.5));
        const renderer::RayFrame frame = FrameOf(target - 2.0 * dir, dir);
        const double half = 0.01 + 0.05 * unit(rng);
        // Centred within 0.6 (holding the point) or 1.4 to 2 half-sides away (not holding it).
        const bool holds = trial % 2 == 0;
        const double du = (holds ? 0.6 : 1.4 + 0.6 * unit(rng)) * half * (unit(rng) < 0.5 ? -1 : 1);
        const double dv = (holds ? 0.6 * (2 * unit(rng) - 1) : 2 * unit(rng) - 1) * half;
        const double cu = us + du, cv = vs + dv;
        const renderer::NewtonHit hit = renderer::CertifyRegion(
            plane, frame, {cu - half, cu + half, cv - half, cv + half, cu - half, cu + half, cv - half, cv + half}, cu,
            cv);
        INFO("trial " << trial << " root (" << us << ", " << vs << ") centre (" << cu << ", " << cv << ") half "
                      << half);
        if (holds) {
            REQUIRE(hit.roots == Roots::One);
            ++ones;
            CHECK(std::fabs(hit.u - us) < 1e-12);
            CHECK(std::fabs(hit.v - vs) < 1e-12);
            CHECK(std::fabs(hit.t - 2.0) <= hit.error + 1e-15);
            CHECK(hit.error < 1e-12);
        } else {
            CHECK(hit.roots == Roots::None);
            nones += hit.roots == Roots::None;
        }
    }
    CHECK(ones == 1000);
    CHECK(nones == 1000);
}

TEST_CASE("newton: certified regions of every shader hold the aimed point and no second root", "[renderer][newton]") {
    const renderer::BilinearPatch square = renderer::BilinearPatch::UnitSquare();
    const renderer::BaseSurface surface(square);
    int certified = 0, excluded = 0, shadersCertified = 0;
    std::vector<double> errors;
    for (const std::string& path : test::AllShaders()) {
        compiler::CompileResult compiled = compiler::CompileFile(path);
        if (!compiled.ok()) continue;  // shaders that need a map or a parameter to compile
        const vm::Program& program = compiled.shader->bound;
        renderer::BoundTree tree(surface, program, glm::dvec3(0, 0, 5), renderer::BoundMode::Reduced, 24);
        auto evaluator = tree.MakeEvaluator();
        std::mt19937_64 rng(std::hash<std::string>()(std::filesystem::path(path).filename().string()) & 0xffff);
        std::uniform_real_distribution<double> unit(0.0, 1.0);
        int here = 0;
        for (int trial = 0; trial < 60; ++trial) {
            const double u = unit(rng), v = unit(rng);
            const glm::dvec3 target = test::PointOnSquare(program, u, v);
            const double z = 0.2 + 0.8 * unit(rng), phi = 2 * M_PI * unit(rng), s = std::sqrt(1 - z * z);
            const glm::dvec3 up(s * std::cos(phi), s * std::sin(phi), z);
            const glm::dvec3 origin = target + 3.0 * up;
            const renderer::RayFrame frame = FrameOf(origin, -up);
            // A region around the aimed point (or beside it), of size 2^-3 .. 2^-12: the part of
            // a larger one (its slopes those of the larger one) where the ray can meet it.
            const double half = std::ldexp(1.0, -3 - static_cast<int>(10 * unit(rng)));
            const double cu = std::clamp(u + (unit(rng) - 0.5) * 3 * half, half, 1 - half);
            const double cv = std::clamp(v + (unit(rng) - 0.5) * 3 * half, half, 1 - half);
            const double u0 = cu - half, u1 = cu + half, v0 = cv - half, v1 = cv + half;
            const renderer::NewtonHit hit =
                renderer::CertifyRegion(*evaluator, frame,
                                        {std::max(0.0, u0 - (trial % 2) * half), u1, v0,
                                         std::min(1.0, v1 + (trial % 3) * half), u0, u1, v0, v1},
                                        cu, cv);
            const bool aimedInside = u > u0 && u < u1 && v > v0 && v < v1;
            INFO(path << " trial " << trial << " aimed (" << u << ", " << v << ") region [" << u0 << ", " << u1
                      << "] x [" << v0 << ", " << v1 << "]");
            if (hit.roots == Roots::None) {
                ++excluded;
                CHECK_FALSE(aimedInside);
                continue;
            }
            if (hit.roots != Roots::One) continue;
            ++certified;
            ++here;
            errors.push_back(hit.error);
            // The certificate: the surface at (u, v) of the hit lies within its error of the point.
            const glm::dvec3 reported = origin - hit.t * up;
            const glm::dvec3 at = test::PointOnSquare(program, hit.u, hit.v);
            CHECK(glm::length(at - reported) <= hit.error * (1 + 1e-6) + 1e-13);
            CHECK(hit.tLo <= hit.t);
            CHECK(hit.t <= hit.tHi);
            // The one root: if the aimed point is in the region, it is the hit.
            if (aimedInside) CHECK(glm::length(target - reported) <= hit.error * (1 + 1e-6) + 1e-12);
            // No second root: on a 24 x 24 grid of the region, from every cell where both frame
            // components of P' - o change sign, Newton's steps reach no root but the hit.
            const int n = 24;
            std::vector<double> g0((n + 1) * (n + 1)), g1((n + 1) * (n + 1));
            for (int i = 0; i <= n; ++i)
                for (int j = 0; j <= n; ++j) {
                    const glm::dvec3 p =
                        test::PointOnSquare(program, u0 + (u1 - u0) * i / n, v0 + (v1 - v0) * j / n) - origin;
                    g0[i * (n + 1) + j] = glm::dot(frame.n[0], p);
                    g1[i * (n + 1) + j] = glm::dot(frame.n[1], p);
                }
            for (int i = 0; i < n; ++i)
                for (int j = 0; j < n; ++j) {
                    auto straddles = [&](const std::vector<double>& g) {
                        const double a = g[i * (n + 1) + j], b = g[(i + 1) * (n + 1) + j], c = g[i * (n + 1) + j + 1],
                                     d = g[(i + 1) * (n + 1) + j + 1];
                        return std::min({a, b, c, d}) <= 0 && std::max({a, b, c, d}) >= 0;
                    };
                    if (!straddles(g0) || !straddles(g1)) continue;
                    // A candidate: Newton's steps in doubles from its centre. A root they reach
                    // in the region away from the hit's is a second root.
                    double ru = u0 + (u1 - u0) * (i + 0.5) / n, rv = v0 + (v1 - v0) * (j + 0.5) / n;
                    double residual = INFINITY;
                    for (int step = 0; step < 40 && std::isfinite(ru + rv); ++step) {
                        glm::dvec3 p, pu, pv;
                        if (!evaluator->PointFrame(ru, rv, &p, &pu, &pv)) break;
                        const glm::dvec3 rel = p - origin;
                        const double G0 = glm::dot(frame.n[0], rel), G1 = glm::dot(frame.n[1], rel);
                        residual = std::max(std::fabs(G0), std::fabs(G1));
                        const double a = glm::dot(frame.n[0], pu), b = glm::dot(frame.n[0], pv);
                        const double c = glm::dot(frame.n[1], pu), d = glm::dot(frame.n[1], pv);
                        const double det = a * d - b * c;
                        ru -= (d * G0 - b * G1) / det;
                        rv -= (a * G1 - c * G0) / det;
                    }
                    const bool inRegion = ru >= u0 && ru <= u1 && rv >= v0 && rv <= v1;
                    const double apart = std::max(std::fabs(ru - hit.u), std::fabs(rv - hit.v)) / (u1 - u0);
                    INFO("Newton from cell (" << i << ", " << j << ") reaches (" << ru << ", " << rv << "), |G| "
                                              << residual << "; the hit is (" << hit.u << ", " << hit.v << ")");
                    CHECK_FALSE((inRegion && residual < 1e-12 && apart > 1e-6));
                }
        }
        if (here > 0) ++shadersCertified;
    }
    // Smooth shaders are certified in most aimed regions, to about rounding.
    CHECK(shadersCertified >= 10);
    CHECK(certified > 200);
    CHECK(excluded > 50);
    std::sort(errors.begin(), errors.end());
    REQUIRE_FALSE(errors.empty());
    CHECK(errors[errors.size() / 2] < 1e-9);
}

TEST_CASE("newton: a certified hit's error covers its spread along the ray", "[renderer][newton]") {
    // NewtonHit: the one meeting point has t somewhere in [tLo, tHi], and every point of the
    // final box lies within `error` of o + t d, so the error is at least the distance from t to
    // either end. A plane 1000 units up, hit straight down from 2 above: the point's rounding
    // (relative to its coordinates) is about 1e-11 along the ray and 1e-14 across it.
    PlaneEvaluator plane(glm::dvec3(0, 0, 1000), glm::dvec3(1, 0, 0), glm::dvec3(0, 1, 0));
    for (const double x : {0.3, 0.37, 0.41}) {
        const double y = 0.6;
        const renderer::RayFrame frame = FrameOf(glm::dvec3(x, y, 1002), glm::dvec3(0, 0, -1));
        const renderer::NewtonHit hit =
            renderer::CertifyRegion(plane, frame, {0.25, 0.5, 0.5, 0.75, 0.25, 0.5, 0.5, 0.75}, 0.375, 0.625);
        INFO("x " << x << " t [" << hit.tLo << ", " << hit.tHi << "] error " << hit.error);
        REQUIRE(hit.roots == Roots::One);
        // The meeting point is (x, y, 1000), at t = 2.
        CHECK(hit.tLo <= 2.0);
        CHECK(hit.tHi >= 2.0);
        CHECK(std::fabs(hit.u - x) < 1e-12);
        CHECK(std::fabs(hit.v - y) < 1e-12);
        CHECK(hit.error >= hit.t - hit.tLo);
        CHECK(hit.error >= hit.tHi - hit.t);
        CHECK(hit.error >= std::fabs(hit.t - 2.0));
    }
}
