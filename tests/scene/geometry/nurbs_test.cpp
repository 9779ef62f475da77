// tests/scene/geometry/nurbs_test.cpp: rational patches and NuPatch spans
// (scene/geometry/nurbs.h): span patches against a direct Cox-de Boor evaluation of the NURBS
// at random points (orders 2 to 11, random non-uniform knots with repeats, random positive
// weights, clipped ranges); an exact rational circle; rational bilinear and bicubic patches
// against their defining formula; tangents and Dual derivatives against finite differences;
// containment of displaced spans in every bounding type; seams between spans; trim curves
// (KeptP, RemovedP) and the intersector's trim hook (camera and shadow rays through a hole).
#include <catch2/catch.hpp>

#include <glm/gtc/matrix_transform.hpp>

#include "renderer/intersect.h"
#include "scene/geometry/nurbs.h"
#include "scene/geometry/surface.h"
#include "tests/test_random.h"
#include "tests/test_util.h"
#include "tests/vm/shader_containment.h"

using namespace affray;
using renderer::KnotVector;
using renderer::NurbsSurface;
using renderer::RationalPatch;

namespace {

/// N_{i,order}(u) by the Cox-de Boor recursion, with the span of u chosen as the last non-empty
/// span starting at or before u (so u = the last knot of the range belongs to the last span).
double Basis(const std::vector<double>& t, int i, int order, double u, int span) {
    if (order == 1) return i == span ? 1.0 : 0.0;
    double sum = 0;
    const double left = t[i + order - 1] - t[i], right = t[i + order] - t[i + 1];
    if (left > 0) sum += (u - t[i]) / left * Basis(t, i, order - 1, u, span);
    if (right > 0) sum += (t[i + order] - u) / right * Basis(t, i + 1, order - 1, u, span);
    return sum;
}

int SpanOf(const KnotVector& k, double u) {
    int span = k.order - 1;
    for (int i = k.order - 1; i < k.n; ++i)
        if (k.knots[i] < k.knots[i + 1] && k.knots[i] <= u) span = i;
    return span;
}

/// The NURBS point at (u, v), straight from the definition sum N N Pw / sum N N w.
glm::dvec3 Reference(const NurbsSurface& s, double u, double v) {
    const int su = SpanOf(s.u, u), sv = SpanOf(s.v, v);
    glm::dvec4 sum(0.0);
    for (int j = 0; j < s.v.n; ++j) {
        const double nv = Basis(s.v.knots, j, s.v.order, v, sv);
        if (nv == 0) continue;
        for (int i = 0; i < s.u.n; ++i)
            sum += Basis(s.u.knots, i, s.u.order, u, su) * nv * s.points[size_t(j) * size_t(s.u.n) + size_t(i)];
    }
    return glm::dvec3(sum) / sum.w;
}

/// A random knot vector of n + order knots with some repeated interior knots, and a range.
KnotVector RandomKnots(test::Rng& rng, int n, int order, bool clip) {
    KnotVector k{n, order, {}, 0, 0};
    double x = rng.uniform(-2, 2);
    for (int i = 0; i < n + order; ++i) {
        k.knots.push_back(x);
        if (rng.chance(0.7)) x += rng.uniform(0.1, 1.0);
    }
    // Clamped ends sometimes (the common case), open ends otherwise.
    if (rng.chance(0.5))
        for (int i = 0; i < order; ++i) k.knots[i] = k.knots[order - 1], k.knots[n + i] = k.knots[n];
    double lo = k.knots[order - 1], hi = k.knots[n];
    if (!(lo < hi)) {
        hi = lo + 1;
        for (int i = n; i < n + order; ++i) k.knots[i] = hi;
    }
    k.min = lo, k.max = hi;
    if (clip) k.min = lo + 0.2 * (hi - lo), k.max = hi - 0.1 * (hi - lo);
    return k;
}

NurbsSurface RandomSurface(test::Rng& rng, int orderU, int orderV, bool rational, bool clip) {
    NurbsSurface s;
    s.u = RandomKnots(rng, orderU + rng.integer(0, 4), orderU, clip);
    s.v = RandomKnots(rng, orderV + rng.integer(0, 3), orderV, clip);
    for (int j = 0; j < s.v.n; ++j)
        for (int i = 0; i < s.u.n; ++i) {
            const double w = rational ? rng.uniform(0.3, 3) : 1.0;
            const double x = i + rng.uniform(-0.3, 0.3);  // drawn in this order whatever the compiler
            const double z = rng.uniform(-1, 1);
            s.points.emplace_back(glm::dvec3(x, j, z) * w, w);
        }
    return s;
}

const glm::dmat4 kPlace = glm::translate(glm::dmat4(1.0), glm::dvec3(1, -2, 3)) *
                          glm::rotate(glm::dmat4(1.0), 0.4, glm::dvec3(1, 1, 0)) *
                          glm::scale(glm::dmat4(1.0), glm::dvec3(2, 1, 0.5));

glm::dvec3 Place(const glm::dvec3& p) { return glm::dvec3(kPlace * glm::dvec4(p, 1.0)); }

/// The span holding (u, v) and the span's own (s, t) there.
const renderer::NurbsSpan* Locate(const std::vector<renderer::NurbsSpan>& spans, double u, double v, double* s,
                                  double* t) {
    for (const renderer::NurbsSpan& span : spans) {
        const renderer::ParameterRange& g = span.range;
        if (u >= g.u0 && u <= g.u1 && v >= g.v0 && v <= g.v1) {
            *s = (u - g.u0) / (g.u1 - g.u0);
            *t = (v - g.v0) / (g.v1 - g.v0);
            return &span;
        }
    }
    return nullptr;
}

/// The unit cylinder x^2 + y^2 = 1, 0 <= z <= height: the exact rational quadratic circle in u
/// (9 points, weights 1 and sqrt(2)/2), linear in v.
NurbsSurface Cylinder(double height = 1) {
    NurbsSurface s;
    s.u = KnotVector{9, 3, {0, 0, 0, 0.25, 0.25, 0.5, 0.5, 0.75, 0.75, 1, 1, 1}, 0, 1};
    s.v = KnotVector{2, 2, {0, 0, 1, 1}, 0, 1};
    const double r = std::sqrt(0.5);
    const double xy[9][2] = {{1, 0}, {1, 1}, {0, 1}, {-1, 1}, {-1, 0}, {-1, -1}, {0, -1}, {1, -1}, {1, 0}};
    for (int j = 0; j < 2; ++j)
        for (int i = 0; i < 9; ++i) {
            const double w = i % 2 ? r : 1.0;
            s.points.emplace_back(xy[i][0] * w, xy[i][1] * w, j * height * w, w);
        }
    return s;
}

}  // namespace

TEST_CASE("nurbs: span patches equal the Cox-de Boor definition, every order, rational or not", "[renderer][nurbs]") {
    test::Rng rng(31);
    const int orders[][2] = {{2, 2}, {3, 2}, {4, 4}, {3, 5}, {5, 3}, {6, 6}, {8, 4}, {11, 11}, {2, 11}};
    for (const auto& order : orders)
        for (int variant = 0; variant < 4; ++variant) {
            const bool rational = variant & 1, clip = variant & 2;
            const NurbsSurface s = RandomSurface(rng, order[0], order[1], rational, clip);
            INFO("orders " << order[0] << " " << order[1] << (rational ? " rational" : "") << (clip ? " clipped" : ""));
            REQUIRE(s.u.Problem("u").empty());
            REQUIRE(s.v.Problem("v").empty());
            const std::vector<renderer::NurbsSpan> spans = renderer::SplitNurbs(s, kPlace);
            REQUIRE(!spans.empty());
            for (const renderer::NurbsSpan& span : spans) CHECK(span.patch.rational == rational);
            for (int k = 0; k < 40; ++k) {
                const double u = k < 4 ? (k & 1 ? s.u.max : s.u.min) : rng.uniform(s.u.min, s.u.max);
                const double v = k < 4 ? (k >> 1 ? s.v.max : s.v.min) : rng.uniform(s.v.min, s.v.max);
                double ls = 0, lt = 0;
                const renderer::NurbsSpan* span = Locate(spans, u, v, &ls, &lt);
                REQUIRE(span);
                const glm::dvec3 want = Place(Reference(s, u, v)), got = span->patch.At(ls, lt);
                INFO("(u, v) = (" << u << ", " << v << ")");
                CHECK(glm::length(got - want) <= 1e-9 * (1 + glm::length(want)));
            }
        }
}

TEST_CASE("nurbs: a rational quadratic circle has radius 1 to rounding", "[renderer][nurbs]") {
    const std::vector<renderer::NurbsSpan> spans = renderer::SplitNurbs(Cylinder(), glm::dmat4(1.0));
    REQUIRE(spans.size() == 4);
    test::Rng rng(32);
    double worst = 0;
    for (const renderer::NurbsSpan& span : spans) {
        CHECK(span.patch.rational);
        CHECK(span.patch.degreeU == 2);
        CHECK(span.patch.degreeV == 1);
        for (int k = 0; k < 200; ++k) {
            const glm::dvec3 p = span.patch.At(rng.uniform(0, 1), rng.uniform(0, 1));
            worst = std::max(worst, std::fabs(std::hypot(p.x, p.y) - 1));
        }
    }
    INFO("largest radius error " << worst);
    CHECK(worst <= 4e-16);
    // The spans' u ranges are the quarter turns, in the knot parameters.
    CHECK(spans[1].range.u0 == 0.25);
    CHECK(spans[1].range.u1 == 0.5);
}

TEST_CASE("nurbs: tangents by the quotient rule and Dual derivatives against finite differences", "[renderer][nurbs]") {
    test::Rng rng(33);
    using D = vm::Dual<double>;
    for (int trial = 0; trial < 20; ++trial) {
        const int orderU = rng.integer(2, 6);
        const int orderV = rng.integer(2, 6);  // drawn after orderU whatever the compiler
        const NurbsSurface s = RandomSurface(rng, orderU, orderV, trial % 2 == 0, false);
        for (const renderer::NurbsSpan& span : renderer::SplitNurbs(s, kPlace)) {
            const double a = rng.uniform(0.1, 0.9), b = rng.uniform(0.1, 0.9), h = 1e-6;
            const renderer::SurfaceFrame<double> f = renderer::RationalFrame<double>(span.patch, a, b);
            const glm::dvec3 du = (span.patch.At(a + h, b) - span.patch.At(a - h, b)) / (2 * h);
            const glm::dvec3 dv = (span.patch.At(a, b + h) - span.patch.At(a, b - h)) / (2 * h);
            const auto fd = renderer::RationalFrame<D>(span.patch, D(a, 1.0, 0.0), D(b, 0.0, 1.0));
            for (int c = 0; c < 3; ++c) {
                const double scale = 1 + std::fabs(du[c]) + std::fabs(dv[c]);
                CHECK(std::fabs(f.dPdu[c] - du[c]) <= 1e-5 * scale);
                CHECK(std::fabs(f.dPdv[c] - dv[c]) <= 1e-5 * scale);
                CHECK(fd.P[c].v == f.P[c]);
                CHECK(std::fabs(fd.P[c].du - f.dPdu[c]) <= 1e-10 * scale);
                CHECK(std::fabs(fd.P[c].dv - f.dPdv[c]) <= 1e-10 * scale);
                // The tangents' own derivatives (a shade program's second order) agree too.
                const renderer::SurfaceFrame<double> f2 = renderer::RationalFrame<double>(span.patch, a + h, b);
                CHECK(std::fabs(fd.dPdu[c].du - (f2.dPdu[c] - f.dPdu[c]) / h) <= 1e-3 * (scale + 1));
            }
        }
    }
}

TEST_CASE("nurbs: rational bilinear and bicubic patches are sum(w B P) / sum(w B)", "[renderer][nurbs]") {
    test::Rng rng(34);
    // Bilinear: corners P_i with weights w_i, homogeneous (w P, w).
    std::array<glm::dvec4, 4> q;
    std::array<glm::dvec3, 4> p;
    std::array<double, 4> w;
    for (int i = 0; i < 4; ++i) {
        p[i] = glm::dvec3(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
        w[i] = rng.uniform(0.2, 4);
        q[i] = renderer::PlaceHomogeneous(kPlace, glm::dvec4(p[i] * w[i], w[i]));
    }
    const RationalPatch bilinear = RationalPatch::Bilinear(q);
    CHECK(bilinear.rational);
    // Bicubic bezier: 16 points with weights.
    std::array<glm::dvec4, 16> g;
    std::array<glm::dvec3, 16> gp;
    std::array<double, 16> gw;
    for (int i = 0; i < 16; ++i) {
        gp[i] = glm::dvec3(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
        gw[i] = rng.uniform(0.2, 4);
        g[i] = glm::dvec4(gp[i] * gw[i], gw[i]);
    }
    const renderer::CubicBasis bezier = renderer::CubicBasis::Bezier();
    const RationalPatch bicubic = RationalPatch::Bicubic(g, bezier, bezier, kPlace);
    auto bern = [](int i, double x) {
        const double c[4] = {1, 3, 3, 1};
        return c[i] * std::pow(x, i) * std::pow(1 - x, 3 - i);
    };
    for (int k = 0; k < 50; ++k) {
        const double s = rng.uniform(0, 1), t = rng.uniform(0, 1);
        const double b[4] = {(1 - s) * (1 - t), s * (1 - t), (1 - s) * t, s * t};
        glm::dvec3 num(0.0);
        double den = 0;
        for (int i = 0; i < 4; ++i) num += b[i] * w[i] * p[i], den += b[i] * w[i];
        CHECK(glm::length(bilinear.At(s, t) - Place(num / den)) <= 1e-12);
        num = glm::dvec3(0.0);
        den = 0;
        for (int j = 0; j < 4; ++j)
            for (int i = 0; i < 4; ++i) {
                const double weight = bern(i, s) * bern(j, t) * gw[4 * j + i];
                num += weight * gp[4 * j + i];
                den += weight;
            }
        CHECK(glm::length(bicubic.At(s, t) - Place(num / den)) <= 1e-12);
    }
    // Every w equal (here 2): W is constant, divided out once, and the patch is polynomial.
    for (glm::dvec4& x : q) x = glm::dvec4(glm::dvec3(x) / x.w * 2.0, 2.0);
    const RationalPatch flat = RationalPatch::Bilinear(q);
    CHECK_FALSE(flat.rational);
}

namespace {

/// The range of a bound's value, for every bounding type and its Dual.
template <class T>
vm::Interval Range(const T& x) {
    return RangeOf(vm::ValueOf(x));
}

/// Checks that RationalFrame<T> over random regions of `patch` contains the double frame at
/// points of the region (corners, centre, random), P and both tangents.
template <class T>
int FrameContainmentFailures(const RationalPatch& patch, test::Rng& rng, int regions) {
    int failures = 0;
    for (int r = 0; r < regions; ++r) {
        const double w = std::pow(10.0, -rng.uniform(0, 6));
        const double s0 = rng.uniform(0, 1 - w), t0 = rng.uniform(0, 1 - w), s1 = s0 + w, t1 = t0 + w;
        if constexpr (std::is_same_v<T, vm::Affine> || std::is_same_v<T, vm::Dual<vm::Affine>>)
            vm::Affine::BeginEvaluation();
        const T s = renderer::SurfaceParameterOf<T>::Make(s0, s1, 0),
                t = renderer::SurfaceParameterOf<T>::Make(t0, t1, 1);
        const renderer::SurfaceFrame<T> bound = renderer::RationalFrame<T>(patch, s, t);
        for (int k = 0; k < 7; ++k) {
            const double a = k < 4 ? (k & 1 ? s1 : s0) : k == 4 ? 0.5 * (s0 + s1) : rng.uniform(s0, s1);
            const double b = k < 4 ? (k >> 1 ? t1 : t0) : k == 4 ? 0.5 * (t0 + t1) : rng.uniform(t0, t1);
            const renderer::SurfaceFrame<double> f = renderer::RationalFrame<double>(patch, a, b);
            for (int c = 0; c < 3; ++c)
                failures += !Range(bound.P[c]).contains(f.P[c]) + !Range(bound.dPdu[c]).contains(f.dPdu[c]) +
                            !Range(bound.dPdv[c]).contains(f.dPdv[c]);
        }
    }
    return failures;
}

}  // namespace

TEST_CASE("nurbs: frame bounds of rational spans contain the scalar frame in every number type",
          "[renderer][nurbs][containment]") {
    test::Rng rng(38);
    std::vector<RationalPatch> patches;
    for (const renderer::NurbsSpan& span : renderer::SplitNurbs(Cylinder(2), kPlace)) patches.push_back(span.patch);
    for (int order : {2, 3, 5, 8})
        for (const renderer::NurbsSpan& span : renderer::SplitNurbs(RandomSurface(rng, order, 3, true, true), kPlace))
            patches.push_back(span.patch);
    for (size_t i = 0; i < patches.size(); ++i) {
        INFO("patch " << i << ": " << ToString(patches[i]));
        CHECK(FrameContainmentFailures<vm::Interval>(patches[i], rng, 20) == 0);
        CHECK(FrameContainmentFailures<vm::Affine>(patches[i], rng, 20) == 0);
        CHECK(FrameContainmentFailures<vm::ReducedAffine>(patches[i], rng, 20) == 0);
        CHECK(FrameContainmentFailures<vm::Dual<vm::Interval>>(patches[i], rng, 10) == 0);
        CHECK(FrameContainmentFailures<vm::Dual<vm::Affine>>(patches[i], rng, 10) == 0);
    }
}

TEST_CASE("nurbs: displaced span bounds contain the scalar values in every type", "[renderer][nurbs][containment]") {
    const std::string path = test::SourceDir() + "/shaders/wave.sl";
    compiler::CompileResult r = compiler::CompileFile(path);
    INFO(r.diagnostics);
    REQUIRE(r.ok());
    test::Rng rng(35);
    const int regions = test::Samples(80);
    std::vector<renderer::NurbsSpan> spans = renderer::SplitNurbs(Cylinder(2), kPlace);
    for (const renderer::NurbsSpan& span : renderer::SplitNurbs(RandomSurface(rng, 4, 3, true, true), kPlace))
        spans.push_back(span);
    for (const renderer::NurbsSpan& span : renderer::SplitNurbs(RandomSurface(rng, 7, 2, false, false), kPlace))
        spans.push_back(span);
    for (size_t i = 0; i < spans.size(); i += 2) {
        const renderer::BaseSurface base(spans[i].patch, i % 4 == 0, spans[i].range);
        const std::string name = "wave.sl on span " + std::to_string(i) + " " + ToString(spans[i].patch);
        test::CheckContainmentOn<vm::Affine, vm::Interval>(name, r.shader->bound, base, regions, 10, 70 + i);
        test::CheckContainmentOn<vm::ReducedAffine>(name, r.shader->bound, base, regions, 10, 80 + i);
        test::CheckContainmentOn<vm::Affine>(name + " (shade)", r.shader->shade, base, regions / 4, 6, 90 + i);
    }
}

TEST_CASE("nurbs: neighbouring spans meet at their seams", "[renderer][nurbs]") {
    test::Rng rng(36);
    for (int trial = 0; trial < 10; ++trial) {
        const int orderU = rng.integer(2, 5);
        const int orderV = rng.integer(2, 5);
        const NurbsSurface s = RandomSurface(rng, orderU, orderV, trial % 2 == 1, false);
        INFO("trial " << trial << ", orders " << orderU << " x " << orderV);
        const std::vector<renderer::NurbsSpan> spans = renderer::SplitNurbs(s, kPlace);
        for (const renderer::NurbsSpan& a : spans)
            for (const renderer::NurbsSpan& b : spans) {
                if (a.range.u1 != b.range.u0 || a.range.v0 != b.range.v0) continue;
                // A knot repeated order times is a break in the surface itself: no seam to meet.
                if (std::count(s.u.knots.begin(), s.u.knots.end(), a.range.u1) >= s.u.order) continue;
                for (int k = 0; k <= 4; ++k) {
                    const glm::dvec3 pa = a.patch.At(1, k / 4.0), pb = b.patch.At(0, k / 4.0);
                    CHECK(glm::length(pa - pb) <= 1e-12 * (1 + glm::length(pa)));
                }
            }
    }
}

TEST_CASE("nurbs: trim curves keep the odd-winding side, flattened within their tolerance", "[renderer][nurbs]") {
    // A circle of radius 0.25 about (0.5, 0.5): the exact rational quadratic circle in (u, v).
    const NurbsSurface c = Cylinder();
    std::vector<glm::dvec3> uvw;
    for (int i = 0; i < 9; ++i) {
        const glm::dvec4 p = c.points[size_t(i)];
        uvw.emplace_back(0.5 * p.w + 0.25 * p.x, 0.5 * p.w + 0.25 * p.y, p.w);
    }
    renderer::TrimCurves trim;
    trim.loops.emplace_back();
    renderer::FlattenTrimCurve(c.u, uvw, 1e-7, &trim.loops[0]);
    double worst = 0;
    for (const glm::dvec2& p : trim.loops[0]) worst = std::max(worst, std::fabs(glm::length(p - 0.5) - 0.25));
    CHECK(worst <= 1e-15);
    // Chords: the midpoint of every segment within the tolerance of the circle.
    for (size_t i = 0; i + 1 < trim.loops[0].size(); ++i) {
        const glm::dvec2 m = 0.5 * (trim.loops[0][i] + trim.loops[0][i + 1]);
        CHECK(0.25 - glm::length(m - 0.5) <= 1e-7);
    }
    // "inside" (the default) keeps the disc; "outside" keeps the rest.
    CHECK(trim.KeptP(0.5, 0.5));
    CHECK(trim.KeptP(0.7, 0.5));
    CHECK_FALSE(trim.KeptP(0.76, 0.5));
    CHECK_FALSE(trim.KeptP(0.1, 0.1));
    CHECK(trim.RemovedP(0.0, 0.2, 0.0, 0.2));
    CHECK_FALSE(trim.RemovedP(0.4, 0.6, 0.4, 0.6));
    CHECK_FALSE(trim.RemovedP(0.0, 0.5, 0.0, 0.5));
    trim.keepInside = false;
    CHECK_FALSE(trim.KeptP(0.5, 0.5));
    CHECK(trim.KeptP(0.1, 0.1));
    CHECK(trim.RemovedP(0.45, 0.55, 0.45, 0.55));
}

TEST_CASE("nurbs: rays through a trimmed hole miss, beside it hit, shadow rays pass the hole", "[renderer][nurbs]") {
    // The unit square z = 0 as a degree (1, 1) NuPatch, and a hole of radius 0.25 at its centre.
    NurbsSurface square;
    square.u = square.v = KnotVector{2, 2, {0, 0, 1, 1}, 0, 1};
    for (int j = 0; j < 2; ++j)
        for (int i = 0; i < 2; ++i) square.points.emplace_back(i, j, 0, 1);
    const std::vector<renderer::NurbsSpan> spans = renderer::SplitNurbs(square, glm::dmat4(1.0));
    REQUIRE(spans.size() == 1);
    auto trim = std::make_shared<renderer::TrimCurves>();
    trim->keepInside = false;
    trim->loops.emplace_back();
    for (int i = 0; i < 256; ++i) {
        const double a = 2 * M_PI * i / 256;
        trim->loops[0].emplace_back(0.5 + 0.25 * std::cos(a), 0.5 + 0.25 * std::sin(a));
    }
    const compiler::CompiledShader bump =
        test::CompileOrThrow("displacement d() { P += 0.05 * sin(20 * u) * sin(20 * v) * normalize(N); }");
    const renderer::BaseSurface base(spans[0].patch, false, spans[0].range, trim);
    auto intersector =
        renderer::MakeSurfaceIntersector(base, bump.bound, glm::dvec3(0, 0, 3), renderer::BoundMode::Affine, 24);
    renderer::IntersectStats stats;
    renderer::Hit hit;
    auto cast = [&](double x, double y, bool anyHit) {
        const renderer::Ray ray{{x, y, 3}, {0, 0, -1}};
        return intersector->Intersect(ray, 0, INFINITY, {1e-4, 0}, anyHit, &hit, stats);
    };
    for (bool anyHit : {false, true}) {
        INFO((anyHit ? "shadow rays" : "camera rays"));
        CHECK_FALSE(cast(0.5, 0.5, anyHit));
        CHECK_FALSE(cast(0.6, 0.45, anyHit));
        CHECK_FALSE(cast(0.5 + 0.24, 0.5, anyHit));
        CHECK(cast(0.5 + 0.26, 0.5, anyHit));
        CHECK(cast(0.1, 0.1, anyHit));
        CHECK(cast(0.9, 0.6, anyHit));
    }
    // A ray that crosses the hole at a slant hits the far rim beyond it.
    const renderer::Ray slant{{0.5, 0.5, 1}, glm::normalize(glm::dvec3(0.3, 0, -1))};
    REQUIRE(intersector->Intersect(slant, 0, INFINITY, {1e-4, 0}, false, &hit, stats));
    CHECK(std::hypot(hit.u - 0.5, hit.v - 0.5) >= 0.25);
}

TEST_CASE("nurbs: rays aimed at the seams of a displaced NuPatch hit", "[renderer][nurbs]") {
    // A wavy b-spline sheet of 5 x 4 spans, displaced by ripples of P (the same from both sides
    // of a seam, where the surface is C2): rays aimed exactly at the seams' points must hit.
    NurbsSurface s;
    s.u = KnotVector{8, 4, {0, 0, 0, 0, 0.2, 0.4, 0.6, 0.8, 1, 1, 1, 1}, 0, 1};
    s.v = KnotVector{7, 4, {0, 0, 0, 0, 0.25, 0.5, 0.75, 1, 1, 1, 1}, 0, 1};
    test::Rng rng(37);
    for (int j = 0; j < 7; ++j)
        for (int i = 0; i < 8; ++i) s.points.emplace_back(i / 7.0, j / 6.0, rng.uniform(-0.1, 0.1), 1);
    const std::vector<renderer::NurbsSpan> spans = renderer::SplitNurbs(s, glm::dmat4(1.0));
    REQUIRE(spans.size() == 20);
    const compiler::CompiledShader ripple =
        test::CompileOrThrow("displacement d() { P += 0.02 * sin(30 * xcomp(P)) * normalize(N); }");
    std::vector<std::unique_ptr<renderer::SurfaceIntersector>> intersectors;
    intersectors.reserve(spans.size());
    for (const renderer::NurbsSpan& span : spans)
        intersectors.push_back(renderer::MakeSurfaceIntersector(renderer::BaseSurface(span.patch, false, span.range),
                                                                ripple.bound, glm::dvec3(0.5, 0.5, 3),
                                                                renderer::BoundMode::Reduced, 24));
    int missed = 0, aimed = 0;
    for (const renderer::NurbsSpan& span : spans) {
        if (span.range.u1 >= 1) continue;
        for (int k = 0; k <= 8; ++k) {
            // The displaced point on the seam u = u1 at the span's t = k / 8.
            const renderer::BaseSurface base(span.patch, false, span.range);
            const glm::dvec3 target = test::PointOnSurface(ripple.bound, base, 1.0, k / 8.0);
            const glm::dvec3 from(0.5, 0.5, 3);
            const renderer::Ray ray{from, glm::normalize(target - from)};
            bool hitAny = false;
            for (auto& intersector : intersectors) {
                renderer::IntersectStats stats;
                renderer::Hit hit;
                hitAny = hitAny || intersector->Intersect(ray, 0, INFINITY, {1e-5, 0}, false, &hit, stats);
            }
            ++aimed;
            missed += !hitAny;
        }
    }
    CHECK(aimed == 16 * 9);
    CHECK(missed == 0);
}
