// tests/scene/geometry/quadric_test.cpp: the quadrics' (u,v) parameterisations (scene/geometry/quadric.h):
// hand-computed points, bounds that contain every point of a region in Interval and Affine, and
// tangents from duals that agree with finite differences.
#include <catch2/catch.hpp>

#include <numbers>

#include <glm/gtc/matrix_transform.hpp>

#include "scene/geometry/quadric.h"
#include "scene/geometry/surface.h"
#include "tests/test_random.h"
#include "tests/test_util.h"

using namespace affray;
using Catch::Matchers::WithinAbs;
using renderer::Quadric;

namespace {

constexpr double kEps = 1e-12;

Quadric Make(Quadric::Kind kind) {
    Quadric q;
    q.kind = kind;
    return q;
}

/// Every kind, with arguments that exercise partial sweeps and ranges.
std::vector<Quadric> Examples() {
    std::vector<Quadric> out;
    Quadric q = Make(Quadric::Kind::Sphere);
    q.radius = 2, q.zmin = -3, q.zmax = 3;  // clamped to the poles
    out.push_back(q);
    q.zmin = -0.5, q.zmax = 1.5, q.thetamax = 270;
    out.push_back(q);
    q = Make(Quadric::Kind::Cylinder);
    q.radius = 0.5, q.zmin = -1, q.zmax = 2, q.thetamax = -180;
    out.push_back(q);
    q = Make(Quadric::Kind::Cone);
    q.radius = 1.5, q.height = 2;
    out.push_back(q);
    q = Make(Quadric::Kind::Disk);
    q.radius = 3, q.height = 0.25, q.thetamax = 90;
    out.push_back(q);
    q = Make(Quadric::Kind::Torus);
    q.majorRadius = 2, q.minorRadius = 0.5, q.phimin = -90, q.phimax = 270;
    out.push_back(q);
    q = Make(Quadric::Kind::Hyperboloid);
    q.point1[0] = 1, q.point1[1] = 0, q.point1[2] = -1;
    q.point2[0] = 0, q.point2[1] = 1, q.point2[2] = 1;
    out.push_back(q);
    q = Make(Quadric::Kind::Paraboloid);
    q.radius = 1, q.zmin = 0.5, q.zmax = 4;
    out.push_back(q);
    return out;
}

glm::dvec3 At(const Quadric& q, double u, double v) {
    vm::Vec3<double> p = renderer::QuadricPoint<double>(q, u, v);
    return {p.x, p.y, p.z};
}

void CheckPoint(const glm::dvec3& got, const glm::dvec3& want) {
    INFO("got (" << got.x << ", " << got.y << ", " << got.z << "), want (" << want.x << ", " << want.y << ", " << want.z
                 << ")");
    CHECK_THAT(got.x, WithinAbs(want.x, kEps));
    CHECK_THAT(got.y, WithinAbs(want.y, kEps));
    CHECK_THAT(got.z, WithinAbs(want.z, kEps));
}

}  // namespace

TEST_CASE("quadrics: points of RenderMan's parameterisations", "[renderer][quadric]") {
    Quadric sphere = Make(Quadric::Kind::Sphere);
    sphere.radius = 2, sphere.zmin = -2, sphere.zmax = 2;
    CheckPoint(At(sphere, 0.25, 0.5), {0, 2, 0});  // theta 90, on the equator
    CheckPoint(At(sphere, 0.5, 1), {0, 0, 2});     // the north pole
    CheckPoint(At(sphere, 0, 0), {0, 0, -2});
    sphere.zmin = 0, sphere.zmax = 1;  // phi from 0 to 30 degrees
    CheckPoint(At(sphere, 0, 1), {std::sqrt(3.0), 0, 1});

    Quadric cylinder = Make(Quadric::Kind::Cylinder);
    cylinder.radius = 0.5, cylinder.zmin = -1, cylinder.zmax = 3, cylinder.thetamax = 180;
    CheckPoint(At(cylinder, 1, 0.25), {-0.5, 0, 0});

    Quadric cone = Make(Quadric::Kind::Cone);
    cone.radius = 2, cone.height = 4;
    CheckPoint(At(cone, 0.25, 0.5), {0, 1, 2});
    CheckPoint(At(cone, 0.7, 1), {0, 0, 4});  // the apex

    Quadric disk = Make(Quadric::Kind::Disk);
    disk.radius = 2, disk.height = 0.5;
    CheckPoint(At(disk, 0.5, 0.25), {-1.5, 0, 0.5});

    Quadric torus = Make(Quadric::Kind::Torus);
    torus.majorRadius = 3, torus.minorRadius = 1;
    CheckPoint(At(torus, 0, 0.25), {3, 0, 1});    // phi 90: the top of the tube
    CheckPoint(At(torus, 0.25, 0.5), {0, 2, 0});  // phi 180: the inner equator

    Quadric hyperboloid = Make(Quadric::Kind::Hyperboloid);
    hyperboloid.point1[0] = 1, hyperboloid.point1[1] = 0, hyperboloid.point1[2] = -1;
    hyperboloid.point2[0] = 0, hyperboloid.point2[1] = 1, hyperboloid.point2[2] = 1;
    CheckPoint(At(hyperboloid, 0, 0.5), {0.5, 0.5, 0});
    CheckPoint(At(hyperboloid, 0.25, 0), {0, 1, -1});

    Quadric paraboloid = Make(Quadric::Kind::Paraboloid);
    paraboloid.radius = 1, paraboloid.zmin = 0, paraboloid.zmax = 4;
    CheckPoint(At(paraboloid, 0, 0.25), {0.5, 0, 1});
    CheckPoint(At(paraboloid, 0.5, 1), {-1, 0, 4});
}

TEST_CASE("quadrics: Interval and Affine bounds contain every point of a region", "[renderer][quadric]") {
    test::Rng rng(11);
    const int regions = test::Samples(400);
    for (const Quadric& q : Examples()) {
        INFO(Quadric::Name(q.kind));
        for (int r = 0; r < regions; ++r) {
            const double width = std::pow(10.0, -rng.uniform(0, 9));
            const double u0 = rng.uniform(0, 1 - width), v0 = rng.uniform(0, 1 - width);
            const double u1 = u0 + width, v1 = v0 + width;
            vm::Affine::BeginEvaluation();
            const vm::Vec3<vm::Affine> a =
                renderer::QuadricPoint<vm::Affine>(q, renderer::SurfaceParameter<vm::Affine>(u0, u1, 0),
                                                   renderer::SurfaceParameter<vm::Affine>(v0, v1, 1));
            const vm::Vec3<vm::Interval> iv =
                renderer::QuadricPoint<vm::Interval>(q, vm::Interval(u0, u1), vm::Interval(v0, v1));
            const renderer::SurfaceFrame<vm::Interval> frame =
                renderer::QuadricFrame<vm::Interval>(q, vm::Interval(u0, u1), vm::Interval(v0, v1));
            for (int k = 0; k < 8; ++k) {
                // The corners, and points inside.
                const double u = k < 4 ? (k & 1 ? u1 : u0) : rng.uniform(u0, u1);
                const double v = k < 4 ? (k & 2 ? v1 : v0) : rng.uniform(v0, v1);
                const vm::Vec3<double> p = renderer::QuadricPoint<double>(q, u, v);
                for (int c = 0; c < 3; ++c) {
                    INFO("region [" << u0 << ", " << u1 << "] x [" << v0 << ", " << v1 << "], point (" << u << ", " << v
                                    << "), component " << c << " = " << p[c]);
                    CHECK(iv[c].contains(p[c]));
                    CHECK(RangeOf(a[c]).contains(p[c]));
                    const renderer::SurfaceFrame<double> f = renderer::QuadricFrame<double>(q, u, v);
                    CHECK((std::isnan(f.dPdv[c]) || frame.dPdv[c].contains(f.dPdv[c])));
                    CHECK(frame.dPdu[c].contains(f.dPdu[c]));
                }
            }
        }
    }
}

TEST_CASE("quadrics: tangents by hand, by duals and by finite differences agree", "[renderer][quadric]") {
    test::Rng rng(12);
    for (const Quadric& q : Examples()) {
        INFO(Quadric::Name(q.kind));
        for (int i = 0; i < 50; ++i) {
            const double u = rng.uniform(0.05, 0.95), v = rng.uniform(0.05, 0.95), h = 1e-6;
            using D = vm::Dual<double>;
            const vm::Vec3<D> p = renderer::QuadricPoint<D>(q, D(u, 1.0, 0.0), D(v, 0.0, 1.0));
            for (int c = 0; c < 3; ++c) {
                const double du =
                    (renderer::QuadricPoint<double>(q, u + h, v)[c] - renderer::QuadricPoint<double>(q, u - h, v)[c]) /
                    (2 * h);
                const double dv =
                    (renderer::QuadricPoint<double>(q, u, v + h)[c] - renderer::QuadricPoint<double>(q, u, v - h)[c]) /
                    (2 * h);
                CHECK_THAT(p[c].du, WithinAbs(du, 1e-6 * std::max(1.0, std::abs(du))));
                CHECK_THAT(p[c].dv, WithinAbs(dv, 1e-6 * std::max(1.0, std::abs(dv))));
                // The hand-written tangents are the duals' (up to rounding).
                const renderer::SurfaceFrame<double> f = renderer::QuadricFrame<double>(q, u, v);
                CHECK_THAT(f.dPdu[c], WithinAbs(p[c].du, 1e-12 * std::max(1.0, std::abs(du))));
                CHECK_THAT(f.dPdv[c], WithinAbs(p[c].dv, 1e-12 * std::max(1.0, std::abs(dv))));
                CHECK(f.P[c] == p[c].v);
            }
        }
    }
}

TEST_CASE("quadrics: arguments that describe no surface are named", "[renderer][quadric]") {
    for (const Quadric& q : Examples()) CHECK(q.Problem().empty());
    Quadric q = Make(Quadric::Kind::Sphere);
    q.radius = 0;
    CHECK(q.Problem() == "the radius must be positive");
    q.radius = 1, q.zmin = 2, q.zmax = 3;
    CHECK(q.Problem() == "zmin..zmax does not cut the sphere");
    q.zmin = -1, q.thetamax = 0;
    CHECK(q.Problem() == "thetamax is 0: the surface is empty");
    q.thetamax = std::numeric_limits<double>::infinity();
    CHECK(q.Problem() == "its arguments must be finite");
    q = Make(Quadric::Kind::Paraboloid);
    q.zmin = -1;
    CHECK(q.Problem() == "it needs 0 <= zmin < zmax");
    q = Make(Quadric::Kind::Torus);
    q.minorRadius = -1;
    CHECK(q.Problem() == "the minor radius must be positive");
}

TEST_CASE("quadrics: a displacement shader's bounds over a placed quadric contain its points", "[renderer][quadric]") {
    // P moves along N by a wave of s and t: reads P, N, s, t through SetQuadricGlobals.
    const std::string source = "displacement d(float Km = 0.1) { P += Km * sin(10 * s) * cos(7 * t) * normalize(N); }";
    const compiler::CompiledShader shader = test::CompileOrThrow(source);
    const compiler::CompiledShader flat = test::CompileOrThrow(source, {{"Km", {0.0}}});
    const vm::ProgramOutput& out = *shader.bound.findOutput("P");
    renderer::PlacedQuadric placed;
    placed.objectToWorld = glm::translate(glm::dmat4(1.0), glm::dvec3(1, -2, 3)) *
                           glm::rotate(glm::dmat4(1.0), 0.4, glm::dvec3(1, 1, 0)) *
                           glm::scale(glm::dmat4(1.0), glm::dvec3(2, 1, 0.5));
    vm::Interpreter<double> point(shader.bound);
    vm::Interpreter<vm::Affine> affine(shader.bound);
    vm::Interpreter<vm::Interval> interval(shader.bound);
    test::Rng rng(13);
    for (const Quadric& q : Examples()) {
        placed.quadric = q;
        INFO(Quadric::Name(q.kind));
        // Undisplaced, at a point: the world point is M times the object point.
        vm::Interpreter<double> base(flat.bound);
        renderer::SetQuadricGlobals(base, placed, 0.3, 0.3, 0.6, 0.6, glm::dvec3(0.0));
        base.Run();
        const vm::Vec3<double> local = renderer::QuadricPoint<double>(q, 0.3, 0.6);
        const glm::dvec4 world = placed.objectToWorld * glm::dvec4(local.x, local.y, local.z, 1.0);
        const vm::Vec3<double> P = base.OutputTriple(*flat.bound.findOutput("P"));
        CheckPoint({P.x, P.y, P.z}, glm::dvec3(world));
        for (int r = 0; r < 100; ++r) {
            const double width = std::pow(10.0, -rng.uniform(0, 6));
            const double u0 = rng.uniform(0, 1 - width), v0 = rng.uniform(0.01, 0.99 - width);
            renderer::SetQuadricGlobals(affine, placed, u0, u0 + width, v0, v0 + width, glm::dvec3(0.0));
            affine.Run();
            const vm::Vec3<vm::Affine> a = affine.OutputTriple(out);
            renderer::SetQuadricGlobals(interval, placed, u0, u0 + width, v0, v0 + width, glm::dvec3(0.0));
            interval.Run();
            const vm::Vec3<vm::Interval> iv = interval.OutputTriple(out);
            for (int k = 0; k < 4; ++k) {
                const double u = rng.uniform(u0, u0 + width), v = rng.uniform(v0, v0 + width);
                renderer::SetQuadricGlobals(point, placed, u, u, v, v, glm::dvec3(0.0));
                point.Run();
                const vm::Vec3<double> p = point.OutputTriple(out);
                for (int c = 0; c < 3; ++c) {
                    INFO("region at (" << u0 << ", " << v0 << ") width " << width << ", component " << c);
                    CHECK(RangeOf(a[c]).contains(p[c]));
                    CHECK(iv[c].contains(p[c]));
                }
            }
        }
    }
}

TEST_CASE("quadrics: the normal direction is along dPdu x dPdv and stays defined at poles and apexes",
          "[renderer][quadric]") {
    test::Rng rng(13);
    for (const Quadric& q : Examples()) {
        INFO(Quadric::Name(q.kind));
        for (int i = 0; i < 100; ++i) {
            const double u = rng.uniform(0, 1), v = rng.uniform(0.01, 0.99);
            const renderer::SurfaceFrame<double> f = renderer::QuadricFrame<double>(q, u, v);
            const vm::Vec3<double> cross = vm::Cross(f.dPdu, f.dPdv);
            const glm::dvec3 c(cross.x, cross.y, cross.z);
            if (!f.hasNormalDirection) {
                CHECK(q.kind == Quadric::Kind::Hyperboloid);
                continue;
            }
            const glm::dvec3 n(f.normalDirection.x, f.normalDirection.y, f.normalDirection.z);
            // Parallel and with the same orientation: the unit vectors agree.
            const glm::dvec3 a = glm::normalize(c), b = glm::normalize(n);
            CHECK_THAT(glm::dot(a, b), WithinAbs(1.0, 1e-9));
        }
    }
    // At the sphere's poles and the cone's apex the tangents' cross product vanishes; the normal
    // direction is the pole's axis and the cone's (h, 0, r) turned.
    Quadric sphere = Make(Quadric::Kind::Sphere);
    for (double v : {0.0, 1.0}) {
        const renderer::SurfaceFrame<double> f = renderer::QuadricFrame<double>(sphere, 0.3, v);
        const glm::dvec3 n = glm::normalize(glm::dvec3(f.normalDirection.x, f.normalDirection.y, f.normalDirection.z));
        CheckPoint(n, {0, 0, v == 0 ? -1 : 1});
    }
    Quadric cone = Make(Quadric::Kind::Cone);
    cone.radius = 1, cone.height = 2;
    const renderer::SurfaceFrame<double> apex = renderer::QuadricFrame<double>(cone, 0, 1.0);
    CheckPoint({apex.normalDirection.x, apex.normalDirection.y, apex.normalDirection.z}, {2, 0, 1});
    // Over a region that contains the north pole, the bounded unit normal of a shader is finite.
    const compiler::CompiledShader shader = test::CompileOrThrow("displacement d() { P += 0.1 * normalize(N); }");
    vm::Interpreter<vm::Affine> interp(shader.bound);
    const vm::Vec3<vm::Affine> p =
        renderer::EvaluateOnSurface(interp, renderer::BaseSurface(renderer::PlacedQuadric{sphere, glm::dmat4(1.0)}), 0,
                                    1, 0.99, 1, glm::dvec3(0, 0, 5), *shader.bound.findOutput("P"));
    for (int c = 0; c < 3; ++c) CHECK(!RangeOf(p[c]).isUnbounded());
    CHECK(RangeOf(p.z).contains(1.1));
}

TEST_CASE("quadrics: normals follow the placed tangents' cross product, and flipNormal turns them",
          "[renderer][quadric]") {
    const compiler::CompiledShader shader = test::CompileOrThrow("displacement d() { P += 0.5 * normalize(N); }");
    vm::Interpreter<double> interp(shader.bound);
    const vm::ProgramOutput& out = *shader.bound.findOutput("P");
    Quadric sphere = Make(Quadric::Kind::Sphere);
    const glm::dmat4 mirror = glm::scale(glm::dmat4(1.0), glm::dvec3(-1, 1, 1));
    for (bool flip : {false, true})
        for (bool mirrored : {false, true}) {
            renderer::BaseSurface base(renderer::PlacedQuadric{sphere, mirrored ? mirror : glm::dmat4(1.0)}, flip);
            const vm::Vec3<double> p =
                renderer::EvaluateOnSurface(interp, base, 0.1, 0.1, 0.4, 0.4, glm::dvec3(0), out);
            const double radius = glm::length(glm::dvec3(p.x, p.y, p.z));
            // Outward, the point moves from radius 1 to 1.5; inward to 0.5. A mirror turns the
            // world tangents' cross product in (the RIB reader's orientation rule then sets
            // flipNormal, scene.h), and the normal follows it.
            CHECK_THAT(radius, WithinAbs(flip != mirrored ? 0.5 : 1.5, 1e-12));
        }
}
