// tests/renderer/stiff_sphere_test.cpp: the stiff suite's sphere-poles case (docs/stiff.md).
// At a sphere's poles the (u,v) parameterisation folds a whole edge of the domain to one point:
// dPdu vanishes, dPdu x dPdv with it, and a normal computed from it is 0/0. The quadric's normal
// direction (scene/geometry/quadric.h) must keep every region's bound finite there, so rays aimed at
// the poles are hit with certified errors, with no region left unbounded to the depth limit.
//
// The reference: tests/scenes/stiff/lumpy.sl moves P along the sphere's radial normal by noise of P,
// so the displaced sphere is star-shaped, rho(d) = |P'(u(d), v(d))| along each direction d from
// the centre, with rho continuous. g(x) = |x| - rho(x / |x|) changes sign where a ray crosses the
// surface, and a ray aimed at a surface point P'(u,v) meets the surface no farther than P'.
#include <catch2/catch.hpp>

#include <numbers>
#include <random>

#include "renderer/intersect.h"
#include "renderer/renderer.h"
#include "rib/rib.h"
#include "scene/geometry/camera.h"
#include "tests/test_util.h"

using namespace affray;
using renderer::Hit;
using renderer::IntersectStats;
using renderer::Ray;
using renderer::Tolerance;

namespace {

struct SphereCase {
    renderer::PreparedScene prepared;
    std::unique_ptr<renderer::Camera> camera;
    const renderer::Primitive& primitive() const { return prepared.primitives.at(0); }
};

SphereCase LoadSphere() {
    SphereCase c;
    affray::diag::Report error;
    const std::string dir = test::SourceDir() + "/tests/scenes/stiff";
    std::optional<renderer::SceneDesc> desc = rib::ReadRib(dir + "/sphere-poles.rib", &error);
    INFO(error);
    REQUIRE(desc);
    REQUIRE(renderer::Renderer(renderer::Options{.shaderPaths = {dir}}).Prepare(*desc, &c.prepared, &error));
    REQUIRE(c.prepared.primitives.size() == 1);
    REQUIRE(c.primitive().base().kind() == renderer::BaseSurface::Kind::Quadric);
    c.camera = std::make_unique<renderer::Camera>(desc->camera);
    return c;
}

/// The displaced surface P'(u,v) with the scalar program (duals if it takes derivatives).
class DisplacedSphere {
  public:
    explicit DisplacedSphere(const renderer::Primitive& prim)
        : m_prim(prim), m_interp(prim.bound()), m_output(*prim.bound().findOutput("P")) {}

    glm::dvec3 At(double u, double v) {
        auto p = renderer::EvaluateOnSurface(m_interp, m_prim.base(), u, u, v, v, glm::dvec3(0), m_output);
        return {p.x.v, p.y.v, p.z.v};
    }

    /// |x| - rho(x / |x|): negative inside the displaced sphere.
    double Inside(const glm::dvec3& x) {
        const double r = glm::length(x);
        const double u = std::fmod(std::atan2(x.y, x.x) / (2 * std::numbers::pi) + 1.0, 1.0);
        const double v = (std::asin(std::clamp(x.z / r, -1.0, 1.0)) + std::numbers::pi / 2) / std::numbers::pi;
        return r - glm::length(At(u, v));
    }

  private:
    const renderer::Primitive& m_prim;
    vm::Interpreter<vm::Dual<double>> m_interp;
    const vm::ProgramOutput& m_output;
};

struct Tally {
    int rays = 0, missed = 0, tooFar = 0, badCertificates = 0, references = 0;
    IntersectStats stats;
};

/// Traces `ray` and checks the hit against a reference distance `tRef` that the surface is met at
/// or before (infinite: no reference), and the hit's certificate against the surface.
void Check(renderer::SurfaceIntersector& intersector, DisplacedSphere& surface, const Ray& ray, double tRef,
           const Tolerance& tol, Tally* tally) {
    Hit hit;
    const bool found = intersector.Intersect(ray, 0, INFINITY, tol, false, &hit, tally->stats);
    ++tally->rays;
    if (std::isfinite(tRef)) {
        ++tally->references;
        if (!found) {
            ++tally->missed;
            UNSCOPED_INFO("missed: " << renderer::ToString(ray) << " reference t=" << tRef);
            return;
        }
        if (hit.t > tRef + hit.error * (1 + 1e-9) + 1e-9) {
            ++tally->tooFar;
            UNSCOPED_INFO("too far: " << renderer::ToString(ray) << " t=" << hit.t << " error=" << hit.error
                                      << " reference t=" << tRef);
        }
    }
    if (found && std::isfinite(hit.error)) {
        const double gap = glm::length(surface.At(hit.u, hit.v) - (ray.origin + hit.t * ray.dir));
        if (gap > hit.error * (1 + 1e-9) + 1e-12) {
            ++tally->badCertificates;
            UNSCOPED_INFO("certificate: " << renderer::ToString(ray) << " gap=" << gap << " error=" << hit.error);
        }
    }
}

/// The first t in (0, tFar] where g changes sign from outside to inside, bisected; INFINITY if none.
double MarchReference(DisplacedSphere& surface, const Ray& ray, double tFar, int steps) {
    double tPrev = 0;
    if (!(surface.Inside(ray.origin) > 0)) return INFINITY;
    for (int i = 1; i <= steps; ++i) {
        const double t = tFar * i / steps, g = surface.Inside(ray.origin + t * ray.dir);
        if (g <= 0) {
            double lo = tPrev, hi = t;
            for (int k = 0; k < 60; ++k) {
                const double mid = 0.5 * (lo + hi);
                (surface.Inside(ray.origin + mid * ray.dir) > 0 ? lo : hi) = mid;
            }
            return hi;
        }
        tPrev = t;
    }
    return INFINITY;
}

}  // namespace

TEST_CASE("stiff: a displaced sphere seen at its poles", "[renderer][stiff]") {
    SphereCase scene = LoadSphere();
    const renderer::Primitive& prim = scene.primitive();
    DisplacedSphere surface(prim);
    const glm::dvec3 eye = scene.camera->Position();
    auto intersector =
        renderer::MakeSurfaceIntersector(prim.base(), prim.bound(), eye, renderer::BoundMode::Affine, 24);
    const Tolerance cameraTol{0, 0.5 * scene.camera->PixelAngle()};
    Tally tally;

    // Camera rays on a grid, against the march.
    const renderer::CameraDesc& desc = scene.prepared.desc.camera;
    for (int j = 0; j < 12; ++j)
        for (int i = 0; i < 12; ++i) {
            const Ray ray = scene.camera->GenerateRay((i + 0.5) * desc.xres / 12, (j + 0.5) * desc.yres / 12);
            Check(*intersector, surface, ray, MarchReference(surface, ray, 8.0, 3000), cameraTol, &tally);
        }
    // Rays aimed at points ever nearer the north pole from the camera, and at the south pole from
    // below, each meeting the surface no farther than its target.
    std::mt19937_64 rng(48);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    for (int k = 1; k <= 12; ++k)
        for (int pole = 0; pole < 2; ++pole) {
            const double u = unit(rng), gap = std::pow(10.0, -k);
            const double v = pole ? 1 - gap : gap;
            const glm::dvec3 target = surface.At(u, v);
            const glm::dvec3 origin = pole ? eye : glm::dvec3(0.3, -0.2, -4.0);
            const double distance = glm::length(target - origin);
            Check(*intersector, surface, Ray{origin, (target - origin) / distance}, distance, cameraTol, &tally);
        }
    // And exactly at the poles.
    for (double v : {0.0, 1.0}) {
        const glm::dvec3 target = surface.At(0.25, v);
        const glm::dvec3 origin = v == 1 ? eye : glm::dvec3(0.3, -0.2, -4.0);
        const double distance = glm::length(target - origin);
        Check(*intersector, surface, Ray{origin, (target - origin) / distance}, distance, cameraTol, &tally);
    }

    INFO("rays " << tally.rays << ", references " << tally.references << ", regions per ray max "
                 << tally.stats.maxRegionsPerRay << ", depth-limit hits " << tally.stats.depthLimitHits
                 << ", max certified error " << tally.stats.maxHitError);
    CHECK(tally.missed == 0);
    CHECK(tally.tooFar == 0);
    CHECK(tally.badCertificates == 0);
    CHECK(tally.references >= 60);
    CHECK(tally.stats.depthLimitHits == 0);
    CHECK(tally.stats.maxRegionsPerRay <= 5000);
}
