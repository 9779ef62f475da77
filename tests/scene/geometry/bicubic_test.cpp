// tests/scene/geometry/bicubic_test.cpp: bicubic patches (scene/geometry/bicubic.h): the
// power-basis evaluation against the basis-matrix formula evaluated directly, for every basis, in
// every number type; containment of displaced bicubic patches (and of patches that cover a part of
// a mesh's (u,v)) in Interval, Affine and ReducedAffine; tangents against finite differences.
#include <catch2/catch.hpp>

#include <sstream>
#include <tuple>

#include <glm/gtc/matrix_transform.hpp>

#include "scene/geometry/bicubic.h"
#include "scene/geometry/surface.h"
#include "tests/test_random.h"
#include "tests/test_util.h"
#include "tests/vm/shader_containment.h"

using namespace affray;
using Catch::Matchers::WithinAbs;
using renderer::BicubicPatch;
using renderer::CubicBasis;

namespace {

/// Every predefined basis and a random matrix (with step 1).
std::vector<CubicBasis> AllBases(test::Rng& rng) {
    std::vector<CubicBasis> out;
    for (const char* name : {"bezier", "b-spline", "catmull-rom", "hermite", "power"})
        out.push_back(*CubicBasis::Named(name));
    CubicBasis random;
    for (double& x : random.m) x = rng.uniform(-2, 2);
    random.step = 1;
    out.push_back(random);
    return out;
}

std::array<glm::dvec3, 16> RandomPoints(test::Rng& rng) {
    std::array<glm::dvec3, 16> g;
    for (glm::dvec3& p : g) p = glm::dvec3(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
    return g;
}

/// The RI formula U Mu G Mv^T V^T evaluated directly, with U (or V) replaced by its derivative
/// [3u^2 2u 1 0] for du (dv), then placed by `m` (a point for P, a vector for the tangents).
glm::dvec3 Direct(const std::array<glm::dvec3, 16>& g, const CubicBasis& bu, const CubicBasis& bv, const glm::dmat4& m,
                  double u, double v, int du, int dv) {
    const double U[4] = {u * u * u, u * u, u, 1}, Ud[4] = {3 * u * u, 2 * u, 1, 0};
    const double V[4] = {v * v * v, v * v, v, 1}, Vd[4] = {3 * v * v, 2 * v, 1, 0};
    const double* uw = du ? Ud : U;
    const double* vw = dv ? Vd : V;
    double wu[4] = {0, 0, 0, 0}, wv[4] = {0, 0, 0, 0};  // U Mu and V Mv: the weights of the points
    for (int k = 0; k < 4; ++k)
        for (int a = 0; a < 4; ++a) {
            wu[k] += uw[a] * bu.m[4 * a + k];
            wv[k] += vw[a] * bv.m[4 * a + k];
        }
    glm::dvec3 p(0.0);
    for (int a = 0; a < 4; ++a)
        for (int b = 0; b < 4; ++b) p += wu[a] * wv[b] * g[4 * b + a];
    return glm::dvec3(m * glm::dvec4(p, du || dv ? 0.0 : 1.0));
}

void CheckNear(const glm::dvec3& got, const glm::dvec3& want, double scale) {
    INFO("got (" << got.x << ", " << got.y << ", " << got.z << "), want (" << want.x << ", " << want.y << ", " << want.z
                 << ")");
    for (int i = 0; i < 3; ++i) CHECK_THAT(got[i], WithinAbs(want[i], 1e-12 * scale));
}

glm::dvec3 Glm(const vm::Vec3<double>& v) { return {v.x, v.y, v.z}; }

const glm::dmat4 kPlace = glm::translate(glm::dmat4(1.0), glm::dvec3(1, -2, 3)) *
                          glm::rotate(glm::dmat4(1.0), 0.4, glm::dvec3(1, 1, 0)) *
                          glm::scale(glm::dmat4(1.0), glm::dvec3(2, 1, 0.5));

}  // namespace

TEST_CASE("bicubic: P, dPdu, dPdv in every number type equal the basis-matrix formula", "[renderer][bicubic]") {
    test::Rng rng(21);
    const std::vector<CubicBasis> bases = AllBases(rng);
    for (const CubicBasis& bu : bases)
        for (const CubicBasis& bv : bases) {
            INFO("u basis " << ToString(bu) << ", v basis " << ToString(bv));
            const std::array<glm::dvec3, 16> g = RandomPoints(rng);
            for (const glm::dmat4& m : {glm::dmat4(1.0), kPlace}) {
                const BicubicPatch patch = BicubicPatch::FromControlPoints(g, bu, bv, m);
                for (int k = 0; k < 6; ++k) {
                    const double u = k < 4 ? (k & 1) : rng.uniform(0, 1), v = k < 4 ? (k >> 1) : rng.uniform(0, 1);
                    INFO("(u, v) = (" << u << ", " << v << ")");
                    const renderer::SurfaceFrame<double> f = renderer::BicubicFrame<double>(patch, u, v);
                    CheckNear(Glm(f.P), Direct(g, bu, bv, m, u, v, 0, 0), 100);
                    CheckNear(Glm(f.dPdu), Direct(g, bu, bv, m, u, v, 1, 0), 100);
                    CheckNear(Glm(f.dPdv), Direct(g, bu, bv, m, u, v, 0, 1), 100);
                    CHECK(patch.At(u, v) == Glm(f.P));
                    // The bounding types at a point contain the double evaluation.
                    const auto fi = renderer::BicubicFrame<vm::Interval>(patch, vm::Interval(u), vm::Interval(v));
                    vm::Affine::BeginEvaluation();
                    const auto fa = renderer::BicubicFrame<vm::Affine>(patch, vm::Affine(u), vm::Affine(v));
                    const auto fr =
                        renderer::BicubicFrame<vm::ReducedAffine>(patch, vm::ReducedAffine(u), vm::ReducedAffine(v));
                    for (int c = 0; c < 3; ++c) {
                        CHECK(fi.P[c].contains(f.P[c]));
                        CHECK(fi.dPdu[c].contains(f.dPdu[c]));
                        CHECK(fi.dPdv[c].contains(f.dPdv[c]));
                        CHECK(RangeOf(fa.P[c]).contains(f.P[c]));
                        CHECK(RangeOf(fa.dPdv[c]).contains(f.dPdv[c]));
                        CHECK(RangeOf(fr.P[c]).contains(f.P[c]));
                        CHECK(RangeOf(fr.dPdu[c]).contains(f.dPdu[c]));
                    }
                    // Duals: the value is the double's, the derivatives the hand-written tangents'.
                    using D = vm::Dual<double>;
                    const auto fd = renderer::BicubicFrame<D>(patch, D(u, 1.0, 0.0), D(v, 0.0, 1.0));
                    for (int c = 0; c < 3; ++c) {
                        CHECK(fd.P[c].v == f.P[c]);
                        CHECK_THAT(fd.P[c].du, WithinAbs(f.dPdu[c], 1e-12 * 100));
                        CHECK_THAT(fd.P[c].dv, WithinAbs(f.dPdv[c], 1e-12 * 100));
                    }
                }
            }
        }
}

TEST_CASE("bicubic: a bezier patch on a bilinear surface keeps only bilinear terms", "[renderer][bicubic]") {
    // Control points at (i/3, j/3) of a twisted bilinear patch: the cubic terms cancel, up to
    // rounding noise that FromControlPoints zeroes, so the evaluation skips them.
    const renderer::BilinearPatch bilinear{
        {glm::dvec3(0, 0, 0), glm::dvec3(1, 0, 0.3), glm::dvec3(0.1, 1, 0), glm::dvec3(1.2, 0.9, 1)}};
    std::array<glm::dvec3, 16> g;
    auto at = [&](double u, double v) {
        return bilinear.corners[0] + bilinear.a() * u + bilinear.b() * v + bilinear.d() * (u * v);
    };
    for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 4; ++i) g[4 * j + i] = at(i / 3.0, j / 3.0);
    const BicubicPatch patch =
        BicubicPatch::FromControlPoints(g, CubicBasis::Bezier(), CubicBasis::Bezier(), glm::dmat4(1.0));
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) {
            INFO("u^" << i << " v^" << j);
            if (i > 1 || j > 1) CHECK(patch.c[4 * i + j] == glm::dvec3(0.0));
        }
    CheckNear(patch.At(0.3, 0.7), at(0.3, 0.7), 1);
}

TEST_CASE("bicubic: displaced bicubic patches are contained in Interval, Affine and ReducedAffine bounds",
          "[renderer][bicubic][containment]") {
    const std::string path = test::SourceDir() + "/shaders/wave.sl";
    compiler::CompileResult r = compiler::CompileFile(path);
    INFO(r.diagnostics);
    REQUIRE(r.ok());
    test::Rng rng(22);
    const std::vector<CubicBasis> bases = AllBases(rng);
    const int regions = test::Samples(150);
    for (size_t b = 0; b < bases.size(); ++b) {
        const CubicBasis& basis = bases[b];
        // A wavy sheet: a grid with random heights, placed.
        std::array<glm::dvec3, 16> g;
        for (int j = 0; j < 4; ++j)
            for (int i = 0; i < 4; ++i) g[4 * j + i] = glm::dvec3(i / 3.0, j / 3.0, rng.uniform(-0.5, 0.5));
        const BicubicPatch patch = BicubicPatch::FromControlPoints(g, basis, bases[(b + 1) % bases.size()], kPlace);
        const std::string name = "wave.sl on a " + ToString(basis) + " patch";
        test::CheckContainmentOn<vm::Affine, vm::Interval>(name, r.shader->bound, patch, regions, 12, 30 + b);
        test::CheckContainmentOn<vm::ReducedAffine>(name, r.shader->bound, patch, regions, 12, 40 + b);
        // The same patch as the middle of a 3 x 2 mesh, with its flipped normal.
        const renderer::BaseSurface part(patch, true, renderer::ParameterRange{1.0 / 3, 2.0 / 3, 0.5, 1});
        test::CheckContainmentOn<vm::Affine, vm::Interval>(name + " (part of a mesh)", r.shader->bound, part, regions,
                                                           12, 50 + b);
        test::CheckContainmentOn<vm::Affine>(name + " (shade)", r.shader->shade, part, regions / 4, 8, 60 + b);
    }
}

TEST_CASE("bicubic: on part of a mesh, u and v are the mesh's and the tangents are along them", "[renderer][bicubic]") {
    const compiler::CompiledShader shader =
        test::CompileOrThrow("displacement d() { P += 0.1 * sin(7 * s) * cos(5 * t) * normalize(N); }");
    test::Rng rng(23);
    const std::array<glm::dvec3, 16> g = RandomPoints(rng);
    const BicubicPatch patch = BicubicPatch::FromControlPoints(g, CubicBasis::Bezier(), CubicBasis::Bezier(), kPlace);
    const renderer::ParameterRange range{0.25, 0.5, 0.6, 0.8};
    const renderer::BaseSurface whole(patch), part(patch, false, range);
    // The undisplaced surface: the part's (s,t) is the patch's own.
    const compiler::CompiledShader flat = test::CompileOrThrow("displacement d() { P += 0 * N; }");
    CheckNear(test::PointOnSurface(flat.bound, part, 0.3, 0.4), test::PointOnSurface(flat.bound, whole, 0.3, 0.4), 1);
    // The shader reads the mesh's u, v, and Du(P) along them is the patch's tangent / (u1 - u0).
    const compiler::CompiledShader uv = test::CompileOrThrow("displacement d() { P = point(u, v, 0); }");
    CheckNear(test::PointOnSurface(uv.bound, part, 0.5, 1.0), glm::dvec3(0.375, 0.8, 0), 1);
    const vm::Vec3<vm::Dual<double>> p = test::EvalOnSurface<vm::Dual<double>>(flat.shade, part, 0.3, 0.3, 0.4, 0.4);
    const renderer::SurfaceFrame<double> f = renderer::BicubicFrame<double>(patch, 0.3, 0.4);
    for (int c = 0; c < 3; ++c) {
        CHECK_THAT(p[c].du, WithinAbs(f.dPdu[c] / 0.25, 1e-9));
        CHECK_THAT(p[c].dv, WithinAbs(f.dPdv[c] / 0.2, 1e-9));
    }
}

TEST_CASE("bicubic: the predefined bases are RenderMan's", "[renderer][bicubic]") {
    // Along u with the other direction's basis "power" and points on its constant term: the curve
    // U M g of four control values g. Each basis is pinned by what it interpolates.
    auto curve = [](const CubicBasis& b, const double g[4], double u, int derivative) {
        const double U[4] = {u * u * u, u * u, u, 1}, Ud[4] = {3 * u * u, 2 * u, 1, 0};
        double sum = 0;
        for (int a = 0; a < 4; ++a)
            for (int k = 0; k < 4; ++k) sum += (derivative ? Ud : U)[a] * b.m[4 * a + k] * g[k];
        return sum;
    };
    const double g[4] = {1.5, -2, 4, 0.25};
    const CubicBasis bezier = *CubicBasis::Named("bezier"), bspline = *CubicBasis::Named("b-spline"),
                     catmull = *CubicBasis::Named("catmull-rom"), hermite = *CubicBasis::Named("hermite"),
                     power = *CubicBasis::Named("power");
    CHECK(bezier.step == 3);
    CHECK(bspline.step == 1);
    CHECK(catmull.step == 1);
    CHECK(hermite.step == 2);
    CHECK(power.step == 4);
    CHECK_FALSE(CubicBasis::Named("bspline"));
    // Bezier: the end points, and the end tangents 3 (g1 - g0), 3 (g3 - g2).
    CHECK(curve(bezier, g, 0, 0) == Approx(g[0]));
    CHECK(curve(bezier, g, 1, 0) == Approx(g[3]));
    CHECK(curve(bezier, g, 0, 1) == Approx(3 * (g[1] - g[0])));
    CHECK(curve(bezier, g, 1, 1) == Approx(3 * (g[3] - g[2])));
    // B-spline: (g0 + 4 g1 + g2) / 6 at 0, and the next such average at 1.
    CHECK(curve(bspline, g, 0, 0) == Approx((g[0] + 4 * g[1] + g[2]) / 6));
    CHECK(curve(bspline, g, 1, 0) == Approx((g[1] + 4 * g[2] + g[3]) / 6));
    CHECK(curve(bspline, g, 0, 1) == Approx((g[2] - g[0]) / 2));
    // Catmull-Rom: through g1 and g2, with tangents (g2 - g0) / 2 and (g3 - g1) / 2.
    CHECK(curve(catmull, g, 0, 0) == Approx(g[1]));
    CHECK(curve(catmull, g, 1, 0) == Approx(g[2]));
    CHECK(curve(catmull, g, 0, 1) == Approx((g[2] - g[0]) / 2));
    CHECK(curve(catmull, g, 1, 1) == Approx((g[3] - g[1]) / 2));
    // Hermite on RI's (point0, vector0, point1, vector1).
    CHECK(curve(hermite, g, 0, 0) == Approx(g[0]));
    CHECK(curve(hermite, g, 0, 1) == Approx(g[1]));
    CHECK(curve(hermite, g, 1, 0) == Approx(g[2]));
    CHECK(curve(hermite, g, 1, 1) == Approx(g[3]));
    // Power: the coefficients of u^3, u^2, u, 1.
    CHECK(curve(power, g, 0.5, 0) == Approx(g[0] / 8 + g[1] / 4 + g[2] / 2 + g[3]));
}

TEST_CASE("bicubic: reduced affine region frames contain the double frame at every point, thinner than Horner's",
          "[renderer][bicubic][containment]") {
    // RegionFrame (the reduced affine bound of P, dPdu and dPdv) against HornerFrame<double>, the
    // scalar evaluation every bound must contain: at the corners and random points of random
    // regions, as a range and as the form at the point's own (eps_u, eps_v), on patches of every
    // basis from 2^-60 to 2^60 units. Its radius is compared with HornerFrame<ReducedAffine>'s.
    test::Rng rng(24);
    const std::vector<CubicBasis> bases = AllBases(rng);
    test::Tally tally;
    int wider = 0, compared = 0;
    const int regions = test::Samples(40);
    for (int scaleExp : {-60, -8, 0, 8, 60})
        for (const CubicBasis& bu : bases)
            for (const CubicBasis& bv : bases) {
                std::array<glm::dvec3, 16> g = RandomPoints(rng);
                for (glm::dvec3& p : g) p *= std::ldexp(1.0, scaleExp);
                const glm::dmat4 m = rng.chance(0.5) ? glm::dmat4(1.0) : kPlace;
                const BicubicPatch patch = BicubicPatch::FromControlPoints(g, bu, bv, m);
                for (int k = 0; k < regions; ++k) {
                    // Regions from the whole patch down to 2^-30 of it, and single points.
                    const double wu = k == 0 ? 1 : std::ldexp(1.0, -rng.integer(0, 30)) * (k % 7 == 0 ? 0 : 1);
                    const double wv = k == 0 ? 1 : std::ldexp(1.0, -rng.integer(0, 30)) * (k % 11 == 0 ? 0 : 1);
                    const double u0 = rng.uniform(0, 1 - wu), v0 = rng.uniform(0, 1 - wv);
                    const double u1 = u0 + wu, v1 = v0 + wv;
                    const auto u = renderer::SurfaceParameter<vm::ReducedAffine>(u0, u1, 0);
                    const auto v = renderer::SurfaceParameter<vm::ReducedAffine>(v0, v1, 1);
                    renderer::SurfaceFrame<vm::ReducedAffine> fr;
                    REQUIRE(renderer::bicubic_detail::RegionFrame(patch, u, v, &fr));
                    const auto fh = renderer::bicubic_detail::HornerFrame(patch, u, v);
                    // Compared where the nonlinear terms outweigh rounding: regions at least 2^-10 of
                    // the patch wide each way, and thicker than 2^-40 of their size.
                    for (int c = 0; c < 3 && wu >= 0x1p-10 && wv >= 0x1p-10; ++c)
                        for (const auto& [region, horner] :
                             {std::pair{fr.P[c], fh.P[c]}, {fr.dPdu[c], fh.dPdu[c]}, {fr.dPdv[c], fh.dPdv[c]}}) {
                            if (region.isUnbounded() || horner.isUnbounded()) continue;
                            const double size = std::fabs(horner.center()) + std::fabs(horner.coefficientU()) +
                                                std::fabs(horner.coefficientV());
                            if (horner.error() <= 0x1p-40 * size) continue;  // rounding, not curvature
                            ++compared;
                            if (region.error() > horner.error() * 1.01) ++wider;
                        }
                    for (int s = 0; s < 12; ++s) {
                        const double ud = s < 4 ? ((s & 1) ? u1 : u0) : rng.uniform(u0, u1);
                        const double vd = s < 4 ? ((s & 2) ? v1 : v0) : rng.uniform(v0, v1);
                        const renderer::SurfaceFrame<double> f = renderer::BicubicFrame<double>(patch, ud, vd);
                        const double eu = u.coefficientU() != 0 ? (ud - u.center()) / u.coefficientU() : 0;
                        const double ev = v.coefficientV() != 0 ? (vd - v.center()) / v.coefficientV() : 0;
                        for (int c = 0; c < 3; ++c)
                            for (const auto& [form, value, what] : {std::tuple{fr.P[c], f.P[c], "P"},
                                                                    {fr.dPdu[c], f.dPdu[c], "dPdu"},
                                                                    {fr.dPdv[c], f.dPdv[c], "dPdv"}}) {
                                ++tally.samples;
                                if (form.isUnbounded()) continue;
                                // eps_u, eps_v are rounded: widen the form at them by that much.
                                const vm::Interval at =
                                    form.evaluateAt(std::clamp(eu, -1.0, 1.0), std::clamp(ev, -1.0, 1.0));
                                const double slack = 4 * vm::kEpsilon *
                                                     (std::fabs(form.coefficientU()) + std::fabs(form.coefficientV()));
                                const bool inRange = form.range().contains(value);
                                const bool atPoint = at.lo() - slack <= value && value <= at.hi() + slack;
                                if (!inRange || !atPoint) {
                                    std::ostringstream out;
                                    out << what << "[" << c << "] = " << value << " at (" << ud << ", " << vd
                                        << ") not in " << form.toString() << " over [" << u0 << ", " << u1 << "] x ["
                                        << v0 << ", " << v1 << "], patch scale 2^" << scaleExp;
                                    tally.fail(out.str());
                                }
                            }
                    }
                }
            }
    INFO(tally.first.str());
    CHECK(tally.failures == 0);
    CHECK(tally.samples > 10000);
    // Horner in reduced affine folds every product's remainder into the error; the local power
    // basis keeps exact coefficients, so its error should almost never be the larger one.
    INFO(wider << " of " << compared << " bounds thicker than Horner's");
    CHECK(compared > 1000);
    CHECK(wider <= compared / 100);
}
