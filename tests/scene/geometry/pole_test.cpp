// tests/scene/geometry/pole_test.cpp: patches with an edge collapsed to a point
// (scene/geometry/pole.h): the classic teapot's lid and bottom, a rational dome, a spindle
// collapsed at both ends, an edge of s. Off the pole the normal direction is a positive multiple
// of dPdu x dPdv; on it, it is defined and is the limit of the normals next to it; its bounds
// over regions that touch the pole are finite and contain the double values; and a displaced
// patch with a pole renders without depth-limit hits.
#include <catch2/catch.hpp>

#include <sstream>

#include "renderer/renderer.h"
#include "rib/rib.h"
#include "scene/geometry/pole.h"
#include "scene/geometry/surface.h"
#include "tests/test_random.h"
#include "tests/test_util.h"

using namespace affray;
using renderer::BicubicPatch;
using renderer::CubicBasis;
using renderer::RationalPatch;

namespace {

// The classic teapot's lid knob (patch 21 of the Newell data) and one of its bottom patches
// (29), as a RIB exporter writes them: 16 points, u fastest. Each has an edge whose four points
// coincide.
const double kLid[48] = {
    0, 0, 3.15, 0, 0, 3.15, 0, 0, 3.15, 0, 0, 3.15, 0.8, 0, 3.15, 0.8, -0.45,  3.15, 0.45,  -0.8, 3.15, 0, -0.8, 3.15,
    0, 0, 2.85, 0, 0, 2.85, 0, 0, 2.85, 0, 0, 2.85, 0.2, 0, 2.7,  0.2, -0.112, 2.7,  0.112, -0.2, 2.7,  0, -0.2, 2.7};
const double kBottom[48] = {0,     0, 0,     0,     0,     0,     0,     0,     0,     0, 0,     0,
                            1.425, 0, 0,     1.425, 0.798, 0,     0.798, 1.425, 0,     0, 1.425, 0,
                            1.5,   0, 0.075, 1.5,   0.84,  0.075, 0.84,  1.5,   0.075, 0, 1.5,   0.075,
                            1.5,   0, 0.15,  1.5,   0.84,  0.15,  0.84,  1.5,   0.15,  0, 1.5,   0.15};

std::array<glm::dvec3, 16> Points(const double* xyz, bool transpose) {
    std::array<glm::dvec3, 16> p;
    for (int k = 0; k < 16; ++k) {
        const int from = transpose ? 4 * (k % 4) + k / 4 : k;
        p[k] = glm::dvec3(xyz[3 * from], xyz[3 * from + 1], xyz[3 * from + 2]);
    }
    return p;
}

glm::dvec3 Glm(const vm::Vec3<double>& v) { return {v.x, v.y, v.z}; }

/// A surface under test: its frame with the pole's normal direction, in any number type.
struct PoleSurface {
    std::string name;
    std::function<renderer::SurfaceFrame<double>(double, double)> atPoint;
    std::function<renderer::SurfaceFrame<vm::ReducedAffine>(const vm::ReducedAffine&, const vm::ReducedAffine&)> ra;
    std::function<renderer::SurfaceFrame<vm::Interval>(const vm::Interval&, const vm::Interval&)> iv;
    int axis;  // the parameter whose ends may collapse
    std::vector<int> ends;
};

/// The patch's frame with its pole's normal direction.
template <class T, class Patch>
renderer::SurfaceFrame<T> Frame(const Patch& patch, const T& s, const T& t) {
    renderer::SurfaceFrame<T> f;
    if constexpr (std::is_same_v<Patch, BicubicPatch>)
        f = renderer::BicubicFrame(patch, s, t);
    else
        f = renderer::RationalFrame(patch, s, t);
    renderer::PoleNormalDirection(patch, s, t, &f);
    return f;
}

template <class Patch>
PoleSurface Surface(const std::string& name, const Patch& patch, std::vector<int> ends) {
    REQUIRE(patch.poles);
    return {name,
            [patch](double s, double t) { return Frame(patch, s, t); },
            [patch](const vm::ReducedAffine& s, const vm::ReducedAffine& t) { return Frame(patch, s, t); },
            [patch](const vm::Interval& s, const vm::Interval& t) { return Frame(patch, s, t); },
            patch.poles->axis,
            std::move(ends)};
}

std::vector<PoleSurface> Surfaces() {
    const CubicBasis bezier = CubicBasis::Bezier();
    const glm::dmat4 place = glm::dmat4(1.0);
    std::vector<PoleSurface> out;
    // The lid collapses along its v = 0 edge as written; transposed, along u = 0.
    out.push_back(Surface("lid", BicubicPatch::FromControlPoints(Points(kLid, false), bezier, bezier, place), {0}));
    out.push_back(
        Surface("lid transposed", BicubicPatch::FromControlPoints(Points(kLid, true), bezier, bezier, place), {0}));
    out.push_back(
        Surface("bottom", BicubicPatch::FromControlPoints(Points(kBottom, false), bezier, bezier, place), {0}));
    // A spindle: a quarter of a surface of revolution closed at both ends (edges v = 0, v = 1).
    std::array<glm::dvec3, 16> spindle;
    const double k = 0.5523, ring[4][2] = {{1, 0}, {1, k}, {k, 1}, {0, 1}}, radius[4] = {0, 0.8, 0.8, 0};
    for (int v = 0; v < 4; ++v)
        for (int u = 0; u < 4; ++u)
            spindle[4 * v + u] = glm::dvec3(radius[v] * ring[u][0], radius[v] * ring[u][1], 1.0 - v / 1.5);
    out.push_back(Surface("spindle", BicubicPatch::FromControlPoints(spindle, bezier, bezier, place), {0, 1}));
    // A rational dome collapsed at v = 1, with weights that vary.
    std::array<glm::dvec4, 16> dome;
    const double height[4] = {0, 0.6, 1.0, 1.1}, r[4] = {1, 1.05, 0.6, 0};
    for (int v = 0; v < 4; ++v)
        for (int u = 0; u < 4; ++u) {
            const double w = (u == 1 || u == 2 ? 0.8 : 1.0) * (v == 2 ? 1.3 : 1.0);
            const glm::dvec3 p(r[v] * ring[u][0], r[v] * ring[u][1], height[v]);
            dome[4 * v + u] = glm::dvec4(p * w, w);
        }
    out.push_back(Surface("rational dome", RationalPatch::Bicubic(dome, bezier, bezier, place), {1}));
    return out;
}

}  // namespace

TEST_CASE("pole: patches without a collapsed edge have no poles", "[renderer][bicubic][pole]") {
    test::Rng rng(3);
    std::array<glm::dvec3, 16> g;
    for (glm::dvec3& p : g) p = glm::dvec3(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
    const CubicBasis bezier = CubicBasis::Bezier();
    CHECK_FALSE(BicubicPatch::FromControlPoints(g, bezier, bezier, glm::dmat4(1.0)).poles);
    // Nearly collapsed (1e-3 apart) is not collapsed: the normal is dPdu x dPdv, which is defined.
    std::array<glm::dvec3, 16> near = Points(kLid, false);
    near[1].x += 1e-3;
    CHECK_FALSE(BicubicPatch::FromControlPoints(near, bezier, bezier, glm::dmat4(1.0)).poles);
}

TEST_CASE("pole: the normal direction is dPdu x dPdv off the pole and its limit on it", "[renderer][bicubic][pole]") {
    test::Rng rng(17);
    for (const PoleSurface& surface : Surfaces()) {
        INFO(surface.name);
        for (int k = 0; k < 200; ++k) {
            const double s = rng.uniform(0, 1), t = rng.uniform(0, 1);
            const renderer::SurfaceFrame<double> f = surface.atPoint(s, t);
            const glm::dvec3 n = Glm(f.normalDirection), c = glm::cross(Glm(f.dPdu), Glm(f.dPdv));
            INFO("at (" << s << ", " << t << ")");
            REQUIRE(glm::length(n) > 0);
            if (glm::length(c) < 1e-9 * glm::length(n)) continue;
            CHECK(glm::dot(n, c) > 0);
            CHECK(glm::length(glm::cross(glm::normalize(n), glm::normalize(c))) < 1e-7);
        }
        // On a collapsed edge the tangents' cross product vanishes; the direction is the limit of
        // the normals beside it.
        for (int end : surface.ends)
            for (int k = 0; k <= 10; ++k) {
                const double a = k / 10.0, e = end, inside = end == 0 ? 1e-5 : 1 - 1e-5;
                const double s = surface.axis == 1 ? a : e, t = surface.axis == 1 ? e : a;
                const renderer::SurfaceFrame<double> f = surface.atPoint(s, t);
                const glm::dvec3 n = glm::normalize(Glm(f.normalDirection));
                INFO("on the edge at " << a);
                CHECK(glm::length(glm::cross(Glm(f.dPdu), Glm(f.dPdv))) < 1e-9);
                const renderer::SurfaceFrame<double> g =
                    surface.atPoint(surface.axis == 1 ? a : inside, surface.axis == 1 ? inside : a);
                const glm::dvec3 beside = glm::normalize(glm::cross(Glm(g.dPdu), Glm(g.dPdv)));
                CHECK(glm::dot(n, beside) > 1 - 1e-4);
            }
    }
}

TEST_CASE("pole: unit normals over regions at the pole are bounded and contain the point values",
          "[renderer][bicubic][pole]") {
    test::Rng rng(29);
    for (const PoleSurface& surface : Surfaces()) {
        INFO(surface.name);
        for (int k = 0; k < 60; ++k) {
            // A region of width 2^-j touching a collapsed edge.
            const double width = std::ldexp(1.0, -static_cast<int>(rng.uniform(1, 9)));
            const int end = surface.ends[k % surface.ends.size()];
            const double a0 = rng.uniform(0, 1 - width), b0 = end == 0 ? 0.0 : 1 - width;
            const double s0 = surface.axis == 1 ? a0 : b0, t0 = surface.axis == 1 ? b0 : a0;
            const double s1 = s0 + width, t1 = t0 + width;
            INFO("region [" << s0 << ", " << s1 << "] x [" << t0 << ", " << t1 << "]");
            const auto sr = renderer::SurfaceParameter<vm::ReducedAffine>(s0, s1, 0);
            const auto tr = renderer::SurfaceParameter<vm::ReducedAffine>(t0, t1, 1);
            const vm::Vec3<vm::ReducedAffine> nr = vm::Normalize(surface.ra(sr, tr).normalDirection);
            const vm::Vec3<vm::Interval> ni =
                vm::Normalize(surface.iv(vm::Interval(s0, s1), vm::Interval(t0, t1)).normalDirection);
            // Small regions give bounded, tight normals: the intersector can stop there (over wide
            // ones the normal's length may not be bounded away from 0, and they are split).
            if (width <= 1.0 / 32)
                for (int i = 0; i < 3; ++i) {
                    REQUIRE_FALSE(nr[i].range().isUnbounded());
                    REQUIRE_FALSE(ni[i].isUnbounded());
                }
            if (width <= 1.0 / 128)
                for (int i = 0; i < 3; ++i) CHECK(nr[i].range().width() < 0.5);
            // What the pole normal fixes: normalize(dPdu x dPdv) over the same region, whose length
            // reaches 0 on the edge, is not bounded away from the whole unit sphere.
            const renderer::SurfaceFrame<vm::ReducedAffine> frame = surface.ra(sr, tr);
            const vm::Vec3<vm::ReducedAffine> naive = vm::Normalize(vm::Cross(frame.dPdu, frame.dPdv));
            bool wide = false;
            for (int i = 0; i < 3; ++i) wide = wide || !(naive[i].range().width() < 1);
            CHECK(wide);
            for (int m = 0; m < 20; ++m) {
                const double s = m == 0 ? s0 : rng.uniform(s0, s1), t = m == 0 ? t0 : rng.uniform(t0, t1);
                const glm::dvec3 n = Glm(vm::Normalize(surface.atPoint(s, t).normalDirection));
                for (int i = 0; i < 3; ++i) {
                    CHECK(nr[i].range().contains(n[i]));
                    CHECK(ni[i].contains(n[i]));
                }
            }
        }
    }
}

TEST_CASE("pole: a displaced teapot lid renders with every hit certified", "[renderer][render][pole]") {
    std::ostringstream rib;
    rib << "Format 40 30 1\nPixelSamples 1 1\nProjection \"perspective\" \"fov\" [40]\n"
           "Translate 0 0 5\nRotate -170 1 0 0\nWorldBegin\n"
           "LightSource \"distantlight\" 1 \"from\" [0 0 5] \"to\" [0 0 0]\n"
           "Displacement \"dented\" \"Km\" [0.05]\n";
    for (bool transposed : {false, true}) {
        rib << "Patch \"bicubic\" \"P\" [";
        const std::array<glm::dvec3, 16> p = Points(kLid, transposed);
        for (const glm::dvec3& x : p) rib << ' ' << (transposed ? -x.x : x.x) << ' ' << x.y << ' ' << x.z;
        rib << "]\n";
    }
    rib << "WorldEnd\n";
    diag::Report error;
    std::optional<renderer::SceneDesc> desc = rib::ParseRib(rib.str(), "lid.rib", &error);
    INFO(error);
    REQUIRE(desc);
    renderer::PreparedScene prepared;
    REQUIRE(renderer::Renderer(renderer::Options{.shaderPaths = {test::SourceDir() + "/shaders"}})
                .Prepare(*desc, &prepared, &error));
    renderer::Options options;
    options.threads = 2;
    image::ImageBuffer image;
    renderer::RenderStats stats;
    renderer::Renderer(options).Render(prepared, &image, &stats);
    CHECK(stats.camera.depthLimitHits == 0);
    CHECK(stats.camera.budgetExhausted == 0);
    CHECK(stats.camera.maxRegionsPerRay < 5000);
    for (float x : image.rgba) CHECK(std::isfinite(x));
}
