// tests/renderer/intersect_test.cpp: the guaranteed intersector against references.
// The certificate is checked exactly: the surface point at a hit's (u,v) must lie within the
// hit's certified error of the reported point. "No missed hit" is checked two ways: rays aimed
// at known surface points, and random rays against a dense brute-force march along the ray
// (wave.sl on a flat patch is a height field, so a sign change of ray height minus surface
// height is a crossing).
#include <catch2/catch.hpp>

#include <random>

#include "renderer/intersect.h"
#include "scene/geometry/nurbs.h"
#include "tests/test_util.h"

using namespace affray;
using renderer::BoundMode;
using renderer::Hit;
using renderer::IntersectStats;
using renderer::Ray;
using renderer::Tolerance;

namespace {

const renderer::BilinearPatch kSquare = renderer::BilinearPatch::UnitSquare();

/// Height of the displaced unit square over (x, y), and whether the shader moved only z there.
double Height(const vm::Program& program, double x, double y) { return test::PointOnSquare(program, x, y).z; }

/// First crossing of the ray with the height field, by marching `steps` steps over [0, tEnd]
/// and bisecting the sign change; returns -1 if none.
double MarchHeightField(const vm::Program& program, const Ray& ray, double tEnd, int steps) {
    auto g = [&](double t) {
        glm::dvec3 p = ray.origin + t * ray.dir;
        if (p.x < 0 || p.x > 1 || p.y < 0 || p.y > 1) return std::nan("");
        return p.z - Height(program, p.x, p.y);
    };
    double tPrev = 0, gPrev = g(0);
    for (int i = 1; i <= steps; ++i) {
        double t = tEnd * i / steps, gt = g(t);
        if (std::isfinite(gPrev) && std::isfinite(gt) && (gPrev > 0) != (gt > 0)) {
            double a = tPrev, b = t;
            for (int k = 0; k < 60; ++k) {
                double m = 0.5 * (a + b);
                ((g(m) > 0) == (gPrev > 0) ? a : b) = m;
            }
            return 0.5 * (a + b);
        }
        tPrev = t;
        gPrev = gt;
    }
    return -1;
}

/// The hit's certificate: the surface at the hit's (u,v) is within hit.error of the hit point.
void CheckCertificate(const vm::Program& program, const Ray& ray, const Hit& hit) {
    glm::dvec3 surface = test::PointOnSquare(program, hit.u, hit.v);
    glm::dvec3 reported = ray.origin + hit.t * ray.dir;
    INFO("hit t=" << hit.t << " (u,v)=(" << hit.u << "," << hit.v << ") error=" << hit.error);
    CHECK(glm::length(surface - reported) <= hit.error * (1 + 1e-9) + 1e-12);
}

glm::dvec3 RandomDirectionAbove(std::mt19937_64& rng, double minElevationDeg) {
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    double minSin = std::sin(minElevationDeg * M_PI / 180);
    double z = minSin + (1 - minSin) * unit(rng), phi = 2 * M_PI * unit(rng);
    double r = std::sqrt(1 - z * z);
    return {r * std::cos(phi), r * std::sin(phi), z};
}

void RunAgainstReferences(const vm::Program& program, BoundMode mode, int nRays, uint64_t seed,
                          double newtonReach = 0) {
    auto intersector = renderer::MakeSurfaceIntersector(kSquare, program, glm::dvec3(0, 0, 5), mode, 24);
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    IntersectStats stats;
    const Tolerance tol{2e-4, 0.0, newtonReach};

    // Rays aimed at a known surface point must hit no farther than it.
    for (int i = 0; i < nRays; ++i) {
        double u = unit(rng), v = unit(rng);
        glm::dvec3 target = test::PointOnSquare(program, u, v);
        glm::dvec3 up = RandomDirectionAbove(rng, 5.0);
        double distance = 0.5 + 3 * unit(rng);
        Ray ray{target + up * distance, -up};
        Hit hit;
        bool found = intersector->Intersect(ray, 0.0, INFINITY, tol, false, &hit, stats);
        INFO("aimed ray " << i << " at (" << u << "," << v << ")");
        REQUIRE(found);
        CHECK(hit.t <= distance + hit.error * (1 + 1e-9));
        CheckCertificate(program, ray, hit);
    }

    // Random rays, some missing: compare with the brute-force march.
    int hits = 0, misses = 0;
    for (int i = 0; i < nRays; ++i) {
        glm::dvec3 from(unit(rng) * 1.6 - 0.3, unit(rng) * 1.6 - 0.3, 0.3 + unit(rng));
        glm::dvec3 to(unit(rng) * 1.4 - 0.2, unit(rng) * 1.4 - 0.2, -0.2);
        Ray ray{from, glm::normalize(to - from)};
        double tEnd = glm::length(to - from);
        double tRef = MarchHeightField(program, ray, tEnd, 20000);
        Hit hit;
        bool found = intersector->Intersect(ray, 0.0, tEnd, tol, false, &hit, stats);
        INFO("random ray " << i << " tRef=" << tRef);
        if (tRef >= 0) {
            ++hits;
            REQUIRE(found);
            CHECK(hit.t <= tRef + hit.error * (1 + 1e-9));
        } else {
            ++misses;
        }
        if (found) CheckCertificate(program, ray, hit);
    }
    CHECK(hits > nRays / 10);
    CHECK(misses > nRays / 10);
    CHECK(stats.regionsBounded > 0);
    // With certified Newton, most hits are its own (to rounding), the rest leaves.
    if (newtonReach > 0) CHECK(stats.newtonHits > uint64_t(nRays));
}

}  // namespace

TEST_CASE("intersector: a flat patch is hit where the plane is", "[renderer][intersect]") {
    const vm::Program identity = vm::IdentityProgram();
    auto intersector = renderer::MakeSurfaceIntersector(kSquare, identity, glm::dvec3(0), BoundMode::Affine, 24);
    Ray ray{{0.3, 0.6, 2.0}, glm::normalize(glm::dvec3(0.1, -0.2, -1.0))};
    Hit hit;
    IntersectStats stats;
    REQUIRE(intersector->Intersect(ray, 0, INFINITY, {1e-6, 0}, false, &hit, stats));
    double tPlane = 2.0 / -ray.dir.z;
    CHECK(std::abs(hit.t - tPlane) <= hit.error);
    CHECK(hit.error <= 1e-6);
    // Affine bounds of a plane are exact: the ray needs few regions per level.
    CHECK(stats.regionsBounded < 300);
    // A ray beside the patch misses it.
    Ray beside{{1.5, 0.5, 2.0}, {0, 0, -1}};
    CHECK_FALSE(intersector->Intersect(beside, 0, INFINITY, {1e-6, 0}, false, &hit, stats));
    // tMax before the plane: no hit.
    CHECK_FALSE(intersector->Intersect(ray, 0, tPlane * 0.99, {1e-6, 0}, false, &hit, stats));
}

TEST_CASE("intersector: wave.sl against brute force, affine bounds", "[renderer][intersect]") {
    compiler::CompileResult r = compiler::CompileFile(test::SourceDir() + "/shaders/wave.sl");
    REQUIRE(r.ok());
    RunAgainstReferences(r.shader->bound, BoundMode::Affine, 150, 11);
}

TEST_CASE("intersector: wave.sl against brute force, interval bounds", "[renderer][intersect]") {
    compiler::CompileResult r = compiler::CompileFile(test::SourceDir() + "/shaders/wave.sl");
    REQUIRE(r.ok());
    RunAgainstReferences(r.shader->bound, BoundMode::Interval, 60, 12);
}

TEST_CASE("intersector: wave.sl against brute force, reduced affine bounds", "[renderer][intersect]") {
    // The default bounds: no hit missed with children culled by their parent's bound (ParentMisses).
    compiler::CompileResult r = compiler::CompileFile(test::SourceDir() + "/shaders/wave.sl");
    REQUIRE(r.ok());
    RunAgainstReferences(r.shader->bound, BoundMode::Reduced, 100, 14);
}

TEST_CASE("intersector: wave.sl against brute force, certified Newton near the tolerance", "[renderer][intersect]") {
    // Krawczyk's test tried on regions up to 4 tolerances across: a proof of one root never
    // drops a nearer region, a proof of none drops only its own.
    compiler::CompileResult r = compiler::CompileFile(test::SourceDir() + "/shaders/wave.sl");
    REQUIRE(r.ok());
    RunAgainstReferences(r.shader->bound, BoundMode::Reduced, 60, 16, 4);
    compiler::CompileResult stiff =
        compiler::CompileFile(test::SourceDir() + "/shaders/wave.sl", {{"frequency", {40}}, {"Km", {0.05}}});
    REQUIRE(stiff.ok());
    RunAgainstReferences(stiff.shader->bound, BoundMode::Reduced, 40, 17, 1);
}

TEST_CASE("intersector: stucco.sl (noise, thresholds) against brute force, reduced affine bounds",
          "[renderer][intersect]") {
    // Noise bounded cell by cell over each cell's part of a region (vm/numbers/noise.h), blobs
    // 4 per unit across the unit square and 0.1 high.
    compiler::CompileResult r =
        compiler::CompileFile(test::SourceDir() + "/shaders/stucco.sl", {{"frequency", {9}}, {"Km", {0.1}}});
    REQUIRE(r.ok());
    RunAgainstReferences(r.shader->bound, BoundMode::Reduced, 60, 15);
}

TEST_CASE("intersector: a stiff wave (frequency 40, amplitude 0.05) is not missed", "[renderer][intersect]") {
    compiler::CompileResult r =
        compiler::CompileFile(test::SourceDir() + "/shaders/wave.sl", {{"frequency", {40}}, {"Km", {0.05}}});
    REQUIRE(r.ok());
    RunAgainstReferences(r.shader->bound, BoundMode::Affine, 80, 13);
}

TEST_CASE("intersector: the depth limit is counted and still yields hits", "[renderer][intersect]") {
    compiler::CompileResult r = compiler::CompileFile(test::SourceDir() + "/shaders/wave.sl");
    REQUIRE(r.ok());
    auto intersector = renderer::MakeSurfaceIntersector(kSquare, r.shader->bound, glm::dvec3(0), BoundMode::Affine, 3);
    Ray ray{{0.5, 0.5, 2.0}, {0, 0, -1}};
    Hit hit;
    IntersectStats stats;
    REQUIRE(intersector->Intersect(ray, 0, INFINITY, {1e-9, 0}, false, &hit, stats));
    CHECK(hit.depthLimited);
    CHECK(stats.depthLimitHits >= 1);
    CheckCertificate(r.shader->bound, ray, hit);
}

TEST_CASE("intersector: unbounded regions are subdivided, never dropped, and counted at the limit",
          "[renderer][intersect]") {
    // P.z = 0.001 / (u - 0.5) is infinite at u = 0.5: every region touching it has an unbounded
    // z (x and y stay bounded: the shader moves P along z only).
    compiler::CompiledShader s = test::CompileOrThrow("displacement pole() { P += vector(0, 0, 0.001 / (u - 0.5)); }");
    auto intersector = renderer::MakeSurfaceIntersector(kSquare, s.bound, glm::dvec3(0), BoundMode::Affine, 10);
    // A ray down the pole: only the unbounded regions there can hold a hit.
    Ray ray{{0.5, 0.3, 5.0}, {0, 0, -1}};
    Hit hit;
    IntersectStats stats;
    REQUIRE(intersector->Intersect(ray, 0, INFINITY, {1e-3, 0}, false, &hit, stats));
    CHECK(hit.depthLimited);
    CHECK(std::isinf(hit.error));  // a possible hit carries no certificate
    CHECK(stats.depthLimitHits >= 1);
    // The nearest surface point of a depth-10 region beside the pole is at z = 0.001 * 2^11.
    CHECK(hit.t == Approx(5.0 - 0.001 * 2048).epsilon(1e-9));
    // Away from the pole the bounded x rules the pole's regions out: an ordinary certified hit.
    Ray away{{0.25, 0.3, 5.0}, {0, 0, -1}};
    REQUIRE(intersector->Intersect(away, 0, INFINITY, {1e-2, 0}, false, &hit, stats));
    CHECK_FALSE(hit.depthLimited);
    CHECK(hit.t == Approx(5.0 + 0.001 / 0.25).margin(1e-2));
    CheckCertificate(s.bound, away, hit);
}

TEST_CASE("intersector: certified-only walks report proved roots alone", "[renderer][intersect][newton]") {
    // Tolerance::certifiedOnly (a shadow ray's search near the surface it leaves): a hit is a
    // root Krawczyk's test proved, found to rounding; a shader that jumps everywhere (a step of
    // u) has no proved roots where it jumps, and leaves there are not hits.
    compiler::CompileResult r = compiler::CompileFile(test::SourceDir() + "/shaders/wave.sl");
    REQUIRE(r.ok());
    auto intersector =
        renderer::MakeSurfaceIntersector(kSquare, r.shader->bound, glm::dvec3(0, 0, 5), BoundMode::Reduced, 24);
    Tolerance tol{2e-4, 0.0, 1.0};
    tol.certifiedOnly = true;
    std::mt19937_64 rng(18);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    IntersectStats stats;
    int found = 0;
    for (int i = 0; i < 100; ++i) {
        const double u = 0.05 + 0.9 * unit(rng), v = 0.05 + 0.9 * unit(rng);
        const glm::dvec3 target = test::PointOnSquare(r.shader->bound, u, v);
        const glm::dvec3 up = RandomDirectionAbove(rng, 30.0);
        Ray ray{target + up * 2.0, -up};
        Hit hit;
        if (!intersector->Intersect(ray, 0.0, INFINITY, tol, false, &hit, stats)) continue;
        ++found;
        CHECK(hit.error < 1e-9);
        CHECK(hit.t <= 2.0 + 1e-9);
        CheckCertificate(r.shader->bound, ray, hit);
    }
    CHECK(found > 80);
    CHECK(stats.newtonHits >= uint64_t(found));

    compiler::CompiledShader steps =
        test::CompileOrThrow("displacement steps() { P += vector(0, 0, 0.05 * step(0.5, mod(u * 8, 1))); }");
    auto stepped = renderer::MakeSurfaceIntersector(kSquare, steps.bound, glm::dvec3(0, 0, 5), BoundMode::Reduced, 24);
    // Straight down onto a riser (u = 1/16 + k/8, where the step jumps): the leaves there are not
    // proved, so nothing is reported, while the default walk reports a leaf hit.
    Ray riser{{0.5 + 1.0 / 16, 0.3, 2.0}, {0, 0, -1}};
    Hit hit;
    CHECK_FALSE(stepped->Intersect(riser, 0.0, INFINITY, tol, false, &hit, stats));
    CHECK(stepped->Intersect(riser, 0.0, INFINITY, Tolerance{2e-4, 0.0}, false, &hit, stats));
}

TEST_CASE("intersector: a ray along the surface is hit where it first reaches it", "[renderer][intersect]") {
    // Rays in the plane of the flat unit square, along +x from x = -1: the parallelogram is
    // degenerate across them (not narrowed), and their first surface point is (0, y, 0), at
    // t = 1. A leaf hit's (u, v) stands for the region where the ray reaches it first (at a
    // silhouette the side facing the ray comes first), so the surface there is no farther along
    // the ray than the hit.
    const vm::Program identity = vm::IdentityProgram();
    auto intersector = renderer::MakeSurfaceIntersector(kSquare, identity, glm::dvec3(0), BoundMode::Affine, 24);
    for (const double y : {0.3, 0.55, 0.8}) {
        const Ray ray{{-1.0, y, 0.0}, {1.0, 0.0, 0.0}};
        Hit hit;
        IntersectStats stats;
        INFO("y " << y);
        REQUIRE(intersector->Intersect(ray, 0, INFINITY, {1e-3, 0}, false, &hit, stats));
        CHECK(hit.t >= 1 - 1e-12);
        CHECK(hit.t <= 1 + hit.error);
        const glm::dvec3 at = test::PointOnSquare(identity, hit.u, hit.v);
        CHECK(glm::dot(at - ray.origin, ray.dir) <= hit.t + 1e-12);
        CheckCertificate(identity, ray, hit);
    }
}

TEST_CASE("intersector: no hit is reported in a trimmed hole", "[renderer][intersect]") {
    // The flat unit square as a NuPatch with the square [0.4, 0.6]^2 trimmed away: rays through
    // the hole meet no surface (the patch is flat, so its root region is already a leaf there),
    // rays beside it meet the plane z = 0, at t = -oz / dz.
    const renderer::RationalPatch square = renderer::RationalPatch::Bilinear(
        {glm::dvec4(0, 0, 0, 1), glm::dvec4(1, 0, 0, 1), glm::dvec4(0, 1, 0, 1), glm::dvec4(1, 1, 0, 1)});
    auto hole = std::make_shared<renderer::TrimCurves>();
    hole->loops = {{{0.4, 0.4}, {0.6, 0.4}, {0.6, 0.6}, {0.4, 0.6}}};
    hole->keepInside = false;
    const renderer::BaseSurface surface(square, false, {}, hole);
    const vm::Program identity = vm::IdentityProgram();
    auto intersector = renderer::MakeSurfaceIntersector(surface, identity, glm::dvec3(0), BoundMode::Affine, 24);
    // Without and with certified Newton (it checks the trim of the point it proves).
    for (const double newtonReach : {0.0, 1.0}) {
        const Tolerance tol{1e-4, 0.0, newtonReach};
        IntersectStats stats;
        Hit hit;
        INFO("newtonReach " << newtonReach);
        CHECK_FALSE(intersector->Intersect({{0.5, 0.5, 2.0}, {0, 0, -1}}, 0, INFINITY, tol, false, &hit, stats));
        // Oblique, through the hole to (0.55, 0.45, 0).
        const glm::dvec3 from(0.45, 0.5, 1.0), to(0.55, 0.45, 0.0);
        CHECK_FALSE(intersector->Intersect({from, glm::normalize(to - from)}, 0, INFINITY, tol, false, &hit, stats));
        for (const glm::dvec2 xy : {glm::dvec2(0.2, 0.7), glm::dvec2(0.5, 0.35), glm::dvec2(0.65, 0.5)}) {
            INFO("beside the hole at (" << xy.x << ", " << xy.y << ")");
            REQUIRE(intersector->Intersect({{xy.x, xy.y, 2.0}, {0, 0, -1}}, 0, INFINITY, tol, false, &hit, stats));
            CHECK(std::fabs(hit.t - 2.0) <= hit.error + 1e-12);
        }
    }
}

TEST_CASE("intersector: a region at the depth limit along one parameter is split along the other",
          "[renderer][intersect]") {
    // A strip 256 long in u and 1 wide in v, rippled along v only (z = 0.05 sin(6 pi v)): its
    // regions stretch along u and are split along u (SplitAxis), so they reach the depth limit 8
    // in u while a quarter wide in v, where 3/4 of a ripple makes their bound far thicker than
    // the tolerance. Split along v from there, they become small: certified hits (no depth-limit
    // hit), at the ripple's height under the ray, z = 0.05 sin(6 pi y) by hand.
    const renderer::BilinearPatch strip{
        {glm::dvec3(0, 0, 0), glm::dvec3(256, 0, 0), glm::dvec3(0, 1, 0), glm::dvec3(256, 1, 0)}};
    const compiler::CompiledShader s =
        test::CompileOrThrow("displacement ripple() { P += vector(0, 0, 0.05 * sin(6 * PI * v)); }");
    auto intersector = renderer::MakeSurfaceIntersector(strip, s.bound, glm::dvec3(0), BoundMode::Affine, 8);
    const double tol = 5e-3;
    IntersectStats stats;
    for (const glm::dvec2 xy : {glm::dvec2(100.3, 0.4), glm::dvec2(17.9, 0.13), glm::dvec2(230.05, 0.77)}) {
        const Ray ray{{xy.x, xy.y, 2.0}, {0, 0, -1}};
        Hit hit;
        INFO("ray down at (" << xy.x << ", " << xy.y << ")");
        REQUIRE(intersector->Intersect(ray, 0, INFINITY, {tol, 0}, false, &hit, stats));
        CHECK_FALSE(hit.depthLimited);
        CHECK(hit.error <= tol);
        const double tRef = 2.0 - 0.05 * std::sin(6 * M_PI * xy.y);
        CHECK(std::fabs(hit.t - tRef) <= hit.error + 1e-12);
    }
    CHECK(stats.depthLimitHits == 0);
}

TEST_CASE("intersector: near-tangent crossings closer than the tolerance are told apart",
          "[renderer][intersect][newton]") {
    // z = 0.1 sin(2 pi u) and a ray along +x just under its crest (z = 0.1 at u = 1/4): it
    // crosses the surface twice, at u = 1/4 -+ acos(1 - h / 0.1) / (2 pi) for a depth h under
    // the crest (1.4e-3 and 4.5e-3 apart below). Krawczyk's test cannot prove a region holding
    // both crossings, so such a leaf is split down to an eighth of the tolerance (kUnprovedLeaf,
    // intersect.cpp) rather than taken at the tolerance: the hit is the first crossing, to an
    // eighth of the tolerance at worst.
    const compiler::CompiledShader s =
        test::CompileOrThrow("displacement crest() { P += vector(0, 0, 0.1 * sin(2 * PI * u)); }");
    auto intersector = renderer::MakeSurfaceIntersector(kSquare, s.bound, glm::dvec3(0), BoundMode::Reduced, 24);
    const double tol = 1e-2;
    IntersectStats stats;
    for (const double h : {1e-6, 1e-5}) {
        const Ray ray{{-1.0, 0.5, 0.1 - h}, {1, 0, 0}};
        Hit hit;
        INFO("depth under the crest " << h);
        REQUIRE(intersector->Intersect(ray, 0, INFINITY, {tol, 0, 1.0}, false, &hit, stats));
        const double tRef = 1.0 + 0.25 - std::acos(1 - h / 0.1) / (2 * M_PI);
        CHECK(std::fabs(hit.t - tRef) <= hit.error + 1e-12);
        CHECK(hit.error <= tol / 8);
        CheckCertificate(s.bound, ray, hit);
    }
    CHECK(stats.newtonUnknown > 0);
}

TEST_CASE("intersector: a surface point at tMin is hit, and no hit lies before tMin", "[renderer][intersect][newton]") {
    // Rays onto the flat unit square with tMin the t of their meeting point with the plane z = 0
    // (by hand: -oz / dz, rounded): the one root Newton proves has a t range of about rounding
    // around it, reaching below tMin. [tMin, tMax] is closed, so the point is a hit, and the
    // hit's t is not below tMin. With tMin a few ulps past the point, within that range, a hit
    // may still be reported (a leaf whose bound reaches tMin), but not before tMin.
    const vm::Program identity = vm::IdentityProgram();
    auto intersector = renderer::MakeSurfaceIntersector(kSquare, identity, glm::dvec3(0, 0, 5), BoundMode::Reduced, 24);
    std::mt19937_64 rng(19);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    IntersectStats stats;
    for (int i = 0; i < 100; ++i) {
        const glm::dvec3 target(0.05 + 0.9 * unit(rng), 0.05 + 0.9 * unit(rng), 0.0);
        const glm::dvec3 up = RandomDirectionAbove(rng, 20.0);
        const Ray ray{target + up * (0.5 + 2 * unit(rng)), -up};
        const double tPlane = -ray.origin.z / ray.dir.z;
        const Tolerance tol{1e-4, 0.0, 1.0};
        Hit hit;
        INFO("ray " << i << " tPlane " << tPlane);
        REQUIRE(intersector->Intersect(ray, tPlane, INFINITY, tol, false, &hit, stats));
        CHECK(hit.t >= tPlane);
        CHECK(hit.t <= tPlane + hit.error + 1e-12);
        for (int k = 1; k <= 16; ++k) {
            const double tMin = tPlane * (1 + k * 1e-16);
            if (intersector->Intersect(ray, tMin, INFINITY, tol, false, &hit, stats)) CHECK(hit.t >= tMin);
        }
    }
    CHECK(stats.newtonHits + stats.newtonUnknown > 0);
}

TEST_CASE("intersector: with proved hits only, a root before tMin blocks nothing", "[renderer][intersect][newton]") {
    // As a shadow ray's search near the surface it leaves (Tolerance::certifiedOnly): straight
    // down onto the plane z = 0 from z = 1, whose root is t = 1 exactly. With tMin a few ulps past
    // it the root lies before tMin, inside the rounding window Newton proves it in: only a window
    // wholly past tMin proves a hit, so there is none (a window that merely reaches tMin would
    // have the ray blocked by the surface it leaves); with tMin clearly before it, the hit (at
    // tMin = 1 exactly the window reaches before tMin too, so nothing is proved either way).
    const vm::Program identity = vm::IdentityProgram();
    auto intersector = renderer::MakeSurfaceIntersector(kSquare, identity, glm::dvec3(0, 0, 5), BoundMode::Reduced, 24);
    Tolerance proved{1e-4, 0.0, 1.0};
    proved.certifiedOnly = true;
    IntersectStats stats;
    Hit hit;
    int provable = 0;
    for (const glm::dvec2 at :
         {glm::dvec2(0.3, 0.4), glm::dvec2(0.71, 0.13), glm::dvec2(0.5, 0.5), glm::dvec2(0.37, 0.83)}) {
        const Ray ray{{at.x, at.y, 1.0}, {0, 0, -1}};
        INFO("at " << at.x << " " << at.y);
        // A root on the edge between two regions is proved in neither (Krawczyk's image must lie
        // inside the box): a proved-only search may miss it, which is why it only adds to the
        // ordinary one. Such points are left out.
        if (!intersector->Intersect(ray, 0.5, INFINITY, proved, false, &hit, stats)) continue;
        ++provable;
        CHECK(std::fabs(hit.t - 1.0) <= hit.error);
        CHECK(intersector->Intersect(ray, 1.0 - 1e-9, INFINITY, proved, false, &hit, stats));
        double tMin = 1.0;
        for (int k = 1; k <= 8; ++k) {
            tMin = std::nextafter(tMin, 2.0);
            INFO("tMin 1 + " << k << " ulps");
            CHECK_FALSE(intersector->Intersect(ray, tMin, INFINITY, proved, false, &hit, stats));
        }
    }
    CHECK(provable >= 2);
}

TEST_CASE("intersector: out of budget, the nearest pending region is the possible hit", "[renderer][intersect]") {
    // With a budget of 10 regions, rays at low elevation over wave.sl stop with regions pending
    // along them. The region holding the ray's first crossing of the surface (the brute-force
    // march) is among them, so the hit, the nearest one's near end, is not beyond that crossing.
    compiler::CompileResult r = compiler::CompileFile(test::SourceDir() + "/shaders/wave.sl");
    REQUIRE(r.ok());
    const vm::Program& program = r.shader->bound;
    auto intersector =
        renderer::MakeSurfaceIntersector(kSquare, program, glm::dvec3(0, 0, 5), BoundMode::Reduced, 24, 10);
    std::mt19937_64 rng(20);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    IntersectStats stats;
    int budgetHits = 0;
    for (int i = 0; i < 40; ++i) {
        // From above one side of the square to below the other, 10 to 25 degrees down.
        const double phi = 2 * M_PI * unit(rng), elevation = (10 + 15 * unit(rng)) * M_PI / 180;
        const glm::dvec3 across(std::cos(phi), std::sin(phi), 0.0);
        const glm::dvec3 from = glm::dvec3(0.5, 0.5, 0.1) - 0.45 * across;
        const glm::dvec3 dir(std::cos(elevation) * across.x, std::cos(elevation) * across.y, -std::sin(elevation));
        const Ray ray{from, dir};
        const double tEnd = 1.2;
        const double tRef = MarchHeightField(program, ray, tEnd, 20000);
        if (tRef < 0) continue;
        Hit hit;
        INFO("ray " << i << " tRef " << tRef);
        REQUIRE(intersector->Intersect(ray, 0.0, tEnd, Tolerance{2e-4, 0.0}, false, &hit, stats));
        if (!hit.depthLimited) continue;
        ++budgetHits;
        CHECK(hit.t <= tRef + 1e-12);
    }
    CHECK(budgetHits > 20);
    CHECK(stats.budgetExhausted >= uint64_t(budgetHits));
}

TEST_CASE("intersector: a ray along a curved surface's mean plane is not culled edge-on", "[renderer][intersect]") {
    // z = 0.4 (u - 1/2)^2 over the unit square, bounded as reduced affine forms: over the root
    // region z has no eps_u or eps_v part (the parabola is even about u = 1/2), only an error
    // term, so the parallelogram across a ray along +x is degenerate and the edge-on test
    // decides, on that error alone. A ray at height h meets the parabola first at
    // u = 1/2 - sqrt(h / 0.4), by hand.
    const compiler::CompiledShader s =
        test::CompileOrThrow("displacement bowl() { P += vector(0, 0, 0.4 * (u - 0.5) * (u - 0.5)); }");
    for (const BoundMode mode : {BoundMode::Reduced, BoundMode::Affine}) {
        auto intersector = renderer::MakeSurfaceIntersector(kSquare, s.bound, glm::dvec3(0), mode, 24);
        for (const glm::dvec2 yh : {glm::dvec2(0.25, 0.03), glm::dvec2(0.6, 0.07), glm::dvec2(0.4, 0.01)}) {
            const Ray ray{{-1.0, yh.x, yh.y}, {1, 0, 0}};
            Hit hit;
            IntersectStats stats;
            INFO("mode " << int(mode) << " y " << yh.x << " height " << yh.y);
            REQUIRE(intersector->Intersect(ray, 0, INFINITY, {1e-4, 0}, false, &hit, stats));
            const double tRef = 1.0 + 0.5 - std::sqrt(yh.y / 0.4);
            CHECK(std::fabs(hit.t - tRef) <= hit.error + 1e-12);
            CheckCertificate(s.bound, ray, hit);
        }
    }
}

TEST_CASE("intersector: a hit does not depend on tMax, only whether it is reported", "[renderer][intersect]") {
    // Issue 32: a render keeps the nearest of its primitives' hits, searching each only up to the
    // nearest hit so far. For the hit kept not to depend on the order the BVH offers them in, a
    // primitive's hit must be the same with any tMax at or beyond its t, and none nearer: the
    // same bits, with leaf and Newton hits, cheap and costly bounds (stucco's noise: the parent's
    // bound culls children, BoundTree::costlyBounds), alone or in a ray group (from its frontier).
    compiler::CompileResult wave = compiler::CompileFile(test::SourceDir() + "/shaders/wave.sl");
    compiler::CompileResult stucco =
        compiler::CompileFile(test::SourceDir() + "/shaders/stucco.sl", {{"frequency", {9}}, {"Km", {0.1}}});
    REQUIRE(wave.ok());
    REQUIRE(stucco.ok());
    // Rays from one point above the square, through the quadrilateral of a group's corners.
    const glm::dvec3 eye(0.45, 0.55, 1.5);
    const glm::dvec3 quad[4] = {{0.1, 0.1, 0}, {0.9, 0.1, 0}, {0.9, 0.9, 0}, {0.1, 0.9, 0}};
    Ray corners[4];
    for (int k = 0; k < 4; ++k) corners[k] = Ray{eye, glm::normalize(quad[k] - eye)};
    const renderer::RayGroup group = renderer::RayGroup::FromCorners(corners, 1);
    auto same = [](const Hit& a, const Hit& b) {
        return a.t == b.t && a.u == b.u && a.v == b.v && a.error == b.error && a.depthLimited == b.depthLimited;
    };
    for (const vm::Program* program : {&wave.shader->bound, &stucco.shader->bound})
        for (const double newtonReach : {0.0, 1.0})
            for (const bool grouped : {false, true}) {
                INFO("program of " << program->code.size() << " operations, Newton reach " << newtonReach
                                   << (grouped ? ", grouped" : ""));
                auto intersector = renderer::MakeSurfaceIntersector(kSquare, *program, eye, BoundMode::Reduced, 24);
                // A coarse tolerance: leaves whose ranges overlap, where the nearest hit so far
                // would cut them.
                const Tolerance tol{3e-3, 0.0, newtonReach};
                std::mt19937_64 rng(31);
                std::uniform_real_distribution<double> unit(0.0, 1.0);
                IntersectStats stats;
                const renderer::RayGroup* g = grouped ? &group : nullptr;
                int hits = 0;
                for (int i = 0; i < 60; ++i) {
                    const double a = unit(rng), b = unit(rng);
                    const glm::dvec3 target =
                        (1 - a) * ((1 - b) * quad[0] + b * quad[3]) + a * ((1 - b) * quad[1] + b * quad[2]);
                    const Ray ray{eye, glm::normalize(target - eye)};
                    Hit hit;
                    if (!intersector->Intersect(ray, 0.0, INFINITY, tol, false, &hit, stats, g)) continue;
                    ++hits;
                    INFO("ray " << i << ": t " << hit.t << ", error " << hit.error);
                    for (const double tMax : {hit.t, std::nextafter(hit.t, INFINITY), hit.t + 0.3 * hit.error,
                                              hit.t + hit.error, hit.t + 3 * hit.error, 2 * hit.t}) {
                        Hit again;
                        INFO("tMax " << tMax);
                        REQUIRE(intersector->Intersect(ray, 0.0, tMax, tol, false, &again, stats, g));
                        CHECK(same(again, hit));
                    }
                    for (const double tMax : {std::nextafter(hit.t, 0.0), hit.t - 0.3 * hit.error}) {
                        if (!(tMax < hit.t)) continue;
                        Hit nearer;
                        INFO("tMax " << tMax);
                        CHECK_FALSE(intersector->Intersect(ray, 0.0, tMax, tol, false, &nearer, stats, g));
                    }
                }
                CHECK(hits > 40);
                if (newtonReach > 0) CHECK(stats.newtonHits > 0);
            }
}
