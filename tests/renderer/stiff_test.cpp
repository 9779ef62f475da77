// tests/renderer/stiff_test.cpp: the stiff and extreme cases of issue 4 (docs/stiff.md), one
// TEST_CASE per case, each on its scene in tests/scenes/stiff/ and through the library API.
//
// Every case checks "no missed hit" one-sidedly, so that the reference itself can never invent a
// miss. All the stiff shaders move P along the normal of a flat patch only (checked), so the
// displaced surface is a height field over the patch plane; with w the height of a point above
// the plane and h(u,v) the shader's height at the point's foot, g = w - h is continuous along a
// ray wherever h is. Two references give rays that certainly meet the surface:
//   - a sign change of g between two finite samples of a ray (bisected) brackets a crossing
//     t in [ta, tb] (intermediate value theorem): the intersector must hit at t <= tb + error;
//   - a ray aimed from the camera (or from a chosen direction) at a surface point P'(u,v)
//     meets the surface at distance |P' - origin| at the latest: it must hit no farther.
// A hit with a finite certified error is checked exactly: the surface point at its (u,v) lies
// within the error of the reported point. Each case also states a range [hLo, hHi] that its
// shader's height provably stays in; a ray that misses that slab over the patch (by more than
// its error, if certified) cannot meet the surface and must not hit at all.
#include <catch2/catch.hpp>

#include <fstream>
#include <glm/gtc/matrix_transform.hpp>
#include <random>
#include <sstream>

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

/// A scene of tests/scenes/stiff/ ready to intersect, with the options its `##stiff-args:` line gives
/// (the same line bench/stiff_table.sh passes to `affray render`).
struct StiffScene {
    renderer::PreparedScene prepared;
    renderer::Options options;
    std::unique_ptr<renderer::Camera> camera;

    const renderer::Primitive& primitive() const { return prepared.primitives.at(0); }
    Tolerance CameraTolerance() const {
        return {options.tolerancePixels * camera->PixelWidth(), options.tolerancePixels * camera->PixelAngle()};
    }
};

std::string StiffDir() { return test::SourceDir() + "/tests/scenes/stiff"; }

renderer::Options OptionsFromArgs(const std::string& ribPath) {
    renderer::Options options;
    std::ifstream in(ribPath);
    std::string line;
    while (std::getline(in, line)) {
        if (line.rfind("##stiff-args:", 0) != 0) continue;
        std::istringstream args(line.substr(13));
        std::string option;
        while (args >> option) {
            if (option == "--tolerance")
                args >> options.tolerancePixels;
            else if (option == "--max-depth")
                args >> options.maxDepth;
            else if (option == "--bounds") {
                std::string mode;
                args >> mode;
                options.bounds = mode == "interval" ? renderer::BoundMode::Interval : renderer::BoundMode::Affine;
            } else
                FAIL("unknown ##stiff-args option " << option);
        }
    }
    return options;
}

StiffScene PrepareDesc(const renderer::SceneDesc& desc, const renderer::Options& options) {
    StiffScene s;
    affray::diag::Report error;
    bool ok = renderer::Renderer(renderer::Options{.shaderPaths = {StiffDir(), test::SourceDir() + "/shaders"}})
                  .Prepare(desc, &s.prepared, &error);
    INFO(error);
    REQUIRE(ok);
    REQUIRE(s.prepared.primitives.size() == 1);
    s.options = options;
    s.camera = std::make_unique<renderer::Camera>(desc.camera);
    return s;
}

renderer::SceneDesc ReadStiffDesc(const std::string& name) {
    affray::diag::Report error;
    std::optional<renderer::SceneDesc> desc = rib::ReadRib(StiffDir() + "/" + name + ".rib", &error);
    INFO(error);
    REQUIRE(desc);
    return *desc;
}

StiffScene LoadStiff(const std::string& name) {
    return PrepareDesc(ReadStiffDesc(name), OptionsFromArgs(StiffDir() + "/" + name + ".rib"));
}

/// The displaced surface of one flat patch as a height field over its plane, evaluated with the
/// scalar program (dual numbers if the program takes derivatives).
class HeightField {
  public:
    HeightField(const renderer::Primitive& prim, const glm::dvec3& eye)
        : m_patch(prim.base().patch()), m_program(prim.bound()), m_eye(eye), m_output(*prim.bound().findOutput("P")) {
        REQUIRE(m_patch.flat());
        m_normal = m_patch.flatNormal();
        m_toPlane = glm::inverse(glm::dmat3(m_patch.a(), m_patch.b(), m_normal));
        if (m_program.usesDerivatives())
            m_dual = std::make_unique<vm::Interpreter<vm::Dual<double>>>(m_program);
        else
            m_scalar = std::make_unique<vm::Interpreter<double>>(m_program);
        double scale = 0;
        for (const glm::dvec3& c : m_patch.corners) scale = std::max(scale, glm::length(c));
        m_slack = 1e-12 * (1 + scale);
    }

    glm::dvec3 Surface(double u, double v) {
        if (m_dual) {
            auto p = renderer::EvaluateOnPatch(*m_dual, m_patch, u, u, v, v, m_eye, m_output);
            return {p.x.v, p.y.v, p.z.v};
        }
        auto p = renderer::EvaluateOnPatch(*m_scalar, m_patch, u, u, v, v, m_eye, m_output);
        return {p.x, p.y, p.z};
    }
    glm::dvec3 Base(double u, double v) const { return m_patch.corners[0] + m_patch.a() * u + m_patch.b() * v; }
    /// (u, v, w) of a point: its foot on the patch plane and its height along the unit normal.
    glm::dvec3 Locate(const glm::dvec3& q) const { return m_toPlane * (q - m_patch.corners[0]); }
    /// Height of the displaced surface above the plane at (u, v).
    double Height(double u, double v) { return glm::dot(Surface(u, v) - Base(u, v), m_normal); }
    /// w - h at q: NaN off the patch or where the shader is not finite.
    double G(const glm::dvec3& q) {
        glm::dvec3 uvw = Locate(q);
        if (!(uvw.x >= 0 && uvw.x <= 1 && uvw.y >= 0 && uvw.y <= 1)) return NAN;
        return uvw.z - Height(uvw.x, uvw.y);
    }
    /// Absolute slack for rounding in world coordinates of this patch's magnitude.
    double Slack() const { return m_slack; }
    const glm::dvec3& Normal() const { return m_normal; }

    /// Requires that the shader moves points along the normal only (else g is meaningless).
    void RequireNormalDisplacement(int n) {
        for (int i = 0; i <= n; ++i)
            for (int j = 0; j <= n; ++j) {
                double u = (i + 0.37) / (n + 1), v = (j + 0.61) / (n + 1);
                glm::dvec3 d = Surface(u, v) - Base(u, v);
                if (!std::isfinite(glm::dot(d, d))) continue;
                glm::dvec3 tangential = d - glm::dot(d, m_normal) * m_normal;
                INFO("(u,v)=(" << u << "," << v << ")");
                REQUIRE(glm::length(tangential) <= 1e-9 * (1 + glm::length(d)) + m_slack);
            }
    }

    /// The part [t0, t1] (t >= 0) of the ray whose foot is inside the patch widened by `margin`
    /// (in u and v); false if there is none. The foot moves linearly with t.
    bool FootInside(const Ray& ray, double margin, double* t0, double* t1) const {
        glm::dvec3 o = Locate(ray.origin), d = m_toPlane * ray.dir;
        double lo = 0, hi = INFINITY;
        for (int axis = 0; axis < 2; ++axis) {
            double a = -margin - o[axis], b = 1 + margin - o[axis];
            if (d[axis] == 0) {
                if (a > 0 || b < 0) return false;
                continue;
            }
            double ta = a / d[axis], tb = b / d[axis];
            if (ta > tb) std::swap(ta, tb);
            lo = std::max(lo, ta);
            hi = std::min(hi, tb);
        }
        *t0 = lo;
        *t1 = hi;
        return lo <= hi;
    }

  private:
    renderer::BilinearPatch m_patch;
    const vm::Program& m_program;
    glm::dvec3 m_eye;
    const vm::ProgramOutput& m_output;
    glm::dvec3 m_normal;
    glm::dmat3 m_toPlane;
    std::unique_ptr<vm::Interpreter<double>> m_scalar;
    std::unique_ptr<vm::Interpreter<vm::Dual<double>>> m_dual;
    double m_slack;
};

/// A bracket [ta, tb] of the first crossing of the ray with the height field that `steps` samples
/// of [t0, t1] reveal (a sign change between finite samples, then bisected), or tb < 0 if none.
struct Crossing {
    double ta = -1, tb = -1;
};

Crossing MarchForCrossing(HeightField& field, const Ray& ray, double t0, double t1, int steps) {
    auto g = [&](double t) { return field.G(ray.origin + t * ray.dir); };
    double tPrev = t0, gPrev = g(t0);
    for (int i = 1; i <= steps; ++i) {
        double t = t0 + (t1 - t0) * i / steps, gt = g(t);
        if (std::isfinite(gPrev) && std::isfinite(gt) && (gPrev > 0) != (gt > 0)) {
            // Keep a sign change between finite samples while halving.
            double a = tPrev, b = t;
            for (int k = 0; k < 60; ++k) {
                double m = 0.5 * (a + b), gm = g(m);
                if (!std::isfinite(gm) || m <= a || m >= b) break;
                ((gm > 0) == (gPrev > 0) ? a : b) = m;
            }
            return {a, b};
        }
        tPrev = t;
        gPrev = gt;
    }
    return {};
}

/// What one case's rays showed; the test asserts on it and prints it on failure.
struct CaseReport {
    IntersectStats stats;
    int rays = 0, bruteForceHits = 0, aimedRays = 0, missed = 0, tooFar = 0, badCertificates = 0;
    int falseHits = 0, uncertifiedHits = 0;

    std::string ToString() const {
        std::ostringstream out;
        out << "rays=" << rays << " brute-force hits=" << bruteForceHits << " aimed=" << aimedRays
            << " missed=" << missed << " too far=" << tooFar << " bad certificates=" << badCertificates
            << " false hits=" << falseHits << " uncertified hits=" << uncertifiedHits
            << " regions/ray mean=" << (stats.rays ? double(stats.regionsBounded) / stats.rays : 0)
            << " max=" << stats.maxRegionsPerRay << " depth-limit hits=" << stats.depthLimitHits
            << " max error=" << stats.maxHitError;
        return out.str();
    }
};

class CaseRunner {
  public:
    /// `hLo`, `hHi`: a range the shader's height provably stays in (hLo may be -infinity).
    CaseRunner(const StiffScene& scene, double hLo, double hHi)
        : m_scene(scene),
          m_hLo(hLo),
          m_hHi(hHi),
          m_field(scene.primitive(), scene.camera->Position()),
          m_intersector(renderer::MakeSurfaceIntersector(scene.primitive().base(), scene.primitive().bound(),
                                                         scene.camera->Position(), scene.options.bounds,
                                                         scene.options.maxDepth)) {
        m_field.RequireNormalDisplacement(12);
    }

    HeightField& field() { return m_field; }
    const CaseReport& report() const { return m_report; }

    /// Intersects the ray; counts a certified hit whose certificate fails, and any hit on a ray
    /// that provably misses the surface (by more than the hit's error).
    bool Trace(const Ray& ray, const Tolerance& tol, Hit* hit) {
        ++m_report.rays;
        bool found = m_intersector->Intersect(ray, 0.0, INFINITY, tol, false, hit, m_report.stats);
        if (!found) return false;
        if (!std::isfinite(hit->error)) {
            ++m_report.uncertifiedHits;
        } else {
            glm::dvec3 surface = m_field.Surface(hit->u, hit->v);
            glm::dvec3 reported = ray.origin + hit->t * ray.dir;
            if (!(glm::length(surface - reported) <= hit->error * (1 + 1e-9) + m_field.Slack())) {
                ++m_report.badCertificates;
                UNSCOPED_INFO("bad certificate: " << renderer::ToString(ray) << " t=" << hit->t << " (u,v)=(" << hit->u
                                                  << "," << hit->v << ") error=" << hit->error);
            }
        }
        double margin = 1e-3 + (std::isfinite(hit->error) ? hit->error : 0.0);
        if (ProvablyMisses(ray, margin)) {
            ++m_report.falseHits;
            UNSCOPED_INFO("false hit: " << renderer::ToString(ray) << " t=" << hit->t << " (u,v)=(" << hit->u << ","
                                        << hit->v << ") error=" << hit->error);
        }
        return true;
    }

    /// True if the ray stays `margin` away from the slab of heights [hLo, hHi] over the patch
    /// (widened by `margin`), where the whole surface lies.
    bool ProvablyMisses(const Ray& ray, double margin) const {
        double t0, t1;
        const renderer::BilinearPatch& patch = m_scene.primitive().base().patch();
        double uvMargin = margin / std::min(glm::length(patch.a()), glm::length(patch.b()));
        if (!m_field.FootInside(ray, uvMargin, &t0, &t1)) return true;
        // The height above the plane is linear along the ray.
        double w0 = m_field.Locate(ray.origin + t0 * ray.dir).z, slope = glm::dot(ray.dir, m_field.Normal());
        double w1 = std::isfinite(t1) ? m_field.Locate(ray.origin + t1 * ray.dir).z
                                      : (slope > 0   ? INFINITY
                                         : slope < 0 ? -INFINITY
                                                     : w0);
        return std::min(w0, w1) > m_hHi + margin || std::max(w0, w1) < m_hLo - margin;
    }

    /// A ray checked against the height-field march with `steps` samples of the part of the ray
    /// over the patch.
    void BruteForceRay(const Ray& ray, const Tolerance& tol, int steps) {
        double t0, t1;
        if (!m_field.FootInside(ray, 0.0, &t0, &t1) || !std::isfinite(t1)) {
            Hit hit;
            Trace(ray, tol, &hit);
            return;
        }
        BruteForceSegment(ray, tol, t0, t1, steps);
    }

    /// The same over the part [t0, t1] of the ray only (where a thin feature lies).
    void BruteForceSegment(const Ray& ray, const Tolerance& tol, double t0, double t1, int steps) {
        Hit hit;
        bool found = Trace(ray, tol, &hit);
        Crossing c = MarchForCrossing(m_field, ray, t0, t1, steps);
        if (c.tb < 0) return;
        ++m_report.bruteForceHits;
        CheckNoFarther(ray, found, hit, c.tb,
                       "brute force bracket [" + std::to_string(c.ta) + "," + std::to_string(c.tb) + "]");
    }

    /// A ray from `origin` through the surface point at (u, v): it must hit no farther.
    void AimedRay(const glm::dvec3& origin, double u, double v, const Tolerance& tol) {
        glm::dvec3 target = m_field.Surface(u, v);
        if (!std::isfinite(glm::dot(target, target))) return;
        double distance = glm::length(target - origin);
        Ray ray{origin, (target - origin) / distance};
        Hit hit;
        bool found = Trace(ray, tol, &hit);
        ++m_report.aimedRays;
        CheckNoFarther(ray, found, hit, distance,
                       "aimed at (u,v)=(" + std::to_string(u) + "," + std::to_string(v) + ")");
    }

    /// Camera rays through an n x n grid of raster positions, against the march.
    void CameraRays(int n, int steps) {
        const renderer::CameraDesc& desc = m_scene.prepared.desc.camera;
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i)
                BruteForceRay(m_scene.camera->GenerateRay((i + 0.5) * desc.xres / n, (j + 0.5) * desc.yres / n),
                              m_scene.CameraTolerance(), steps);
    }

    /// Camera rays aimed at surface points (u, v) drawn by `pick`.
    template <class Pick>
    void AimedCameraRays(int n, Pick pick) {
        for (int i = 0; i < n; ++i) {
            auto [u, v] = pick(i);
            AimedRay(m_scene.camera->Position(), u, v, m_scene.CameraTolerance());
        }
    }

  private:
    void CheckNoFarther(const Ray& ray, bool found, const Hit& hit, double tRef, const std::string& what) {
        if (!found) {
            ++m_report.missed;
            UNSCOPED_INFO("missed hit: " << renderer::ToString(ray) << ", " << what);
        } else if (hit.t > tRef + hit.error * (1 + 1e-9) + m_field.Slack()) {
            ++m_report.tooFar;
            UNSCOPED_INFO("hit too far: " << renderer::ToString(ray) << " t=" << hit.t << " error=" << hit.error << ", "
                                          << what << " at t=" << tRef);
        }
    }

    const StiffScene& m_scene;
    double m_hLo, m_hHi;
    HeightField m_field;
    std::unique_ptr<renderer::SurfaceIntersector> m_intersector;
    CaseReport m_report;
};

/// The assertions every case shares: no missed hit, no hit too far, every certificate holds,
/// the references found enough hits to mean something, and the work per ray stayed in budget.
void RequireSound(const CaseReport& r, int minReferenceHits, uint64_t maxRegionsPerRay, bool checkFalseHits = true) {
    INFO(r.ToString());
    CHECK(r.missed == 0);
    CHECK(r.tooFar == 0);
    CHECK(r.badCertificates == 0);
    if (checkFalseHits) CHECK(r.falseHits == 0);
    CHECK(r.bruteForceHits + r.aimedRays >= minReferenceHits);
    CHECK(r.stats.maxRegionsPerRay <= maxRegionsPerRay);
}

glm::dvec3 DirectionAtElevation(double elevationDeg, double azimuth, const glm::dvec3& normal) {
    glm::dvec3 helper = std::abs(normal.x) < 0.6 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
    glm::dvec3 t1 = glm::normalize(glm::cross(normal, helper));
    glm::dvec3 t2 = glm::cross(normal, t1);
    double e = elevationDeg * M_PI / 180;
    return std::cos(e) * (std::cos(azimuth) * t1 + std::sin(azimuth) * t2) + std::sin(e) * normal;
}

}  // namespace

TEST_CASE("stiff: frequency 1000 on a unit patch", "[renderer][stiff]") {
    StiffScene scene = LoadStiff("freq1000");
    CaseRunner run(scene, -0.06, 0.06);
    // A wavelength of 1e-3 in (s, t): 8000 samples over the ray's foot (about one unit long)
    // are 5 or more per wavelength.
    run.CameraRays(8, 8000);
    std::mt19937_64 rng(41);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    run.AimedCameraRays(48, [&](int) { return std::pair(unit(rng), unit(rng)); });
    RequireSound(run.report(), 40, 20000);
}

TEST_CASE("stiff: amplitude 1000 on a unit patch", "[renderer][stiff]") {
    StiffScene scene = LoadStiff("amp1000");
    CaseRunner run(scene, -1000, 1000);
    run.CameraRays(8, 4000);
    std::mt19937_64 rng(42);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    run.AimedCameraRays(32, [&](int) { return std::pair(unit(rng), unit(rng)); });
    // Rays straight down and up the walls, with the camera's tolerance at 4000 units. (Oblique
    // rays are the case below.)
    const Tolerance tol{scene.CameraTolerance().At(4000), 0};
    for (int i = 0; i < 16; ++i) {
        double u = unit(rng), v = unit(rng);
        glm::dvec3 dir = (i % 2 ? 1.0 : -1.0) * run.field().Normal();
        run.AimedRay(run.field().Surface(u, v) + 3000.0 * dir, u, v, tol);
    }
    RequireSound(run.report(), 40, 2000);
}

TEST_CASE("stiff: amplitude 1000, an oblique ray needs few regions", "[renderer][stiff]") {
    // A ray at 60 degrees of elevation: across the ray, the bound of a region of these walls is a
    // long thin parallelogram (its height, 25000 times its width, seen sideways) that neither
    // fixed plane through the ray separates from it until the regions are tiny: 24689 regions at
    // depth 9 and ~1e6 at the default depth. The intersector also tests the normals of the eps_u
    // and eps_v generators in the plane across the ray (where a 2D zonotope's separating lines
    // lie), which this checks.
    StiffScene scene = LoadStiff("amp1000");
    HeightField field(scene.primitive(), glm::dvec3(0));
    const glm::dvec3 target = field.Surface(0.3, 0.6);
    const double e = M_PI / 3;
    const glm::dvec3 dir(std::cos(e) * 0.6, std::cos(e) * 0.8, std::sin(e));
    auto intersector = renderer::MakeSurfaceIntersector(scene.primitive().base(), scene.primitive().bound(),
                                                        glm::dvec3(0), renderer::BoundMode::Affine, 9);
    Ray ray{target + 3000.0 * dir, -dir};
    Hit hit;
    IntersectStats stats;
    REQUIRE(intersector->Intersect(ray, 0, INFINITY, {0.02, 0}, false, &hit, stats));
    CHECK(hit.t <= 3000 + hit.error);
    INFO("regions bounded: " << stats.regionsBounded);
    CHECK(stats.regionsBounded < 5000);
}

TEST_CASE("stiff: needles with sigma 1e-4", "[renderer][stiff]") {
    StiffScene scene = LoadStiff("needles");
    CaseRunner run(scene, 0, 0.3);
    run.CameraRays(8, 4000);
    // Camera rays through the flanks of the needles, within 3 sigma of their axes: a sampled
    // renderer at this resolution would almost never see them.
    std::mt19937_64 rng(43);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    const double sigma = 1e-4;
    run.AimedCameraRays(64, [&](int i) {
        double cu = (i % 4 + 0.5) / 4, cv = (i / 4 % 4 + 0.5) / 4;
        double r = 3 * sigma * unit(rng), phi = 2 * M_PI * unit(rng);
        return std::pair(cu + r * std::cos(phi), cv + r * std::sin(phi));
    });
    RequireSound(run.report(), 60, 5000);
}

namespace {

/// The singular point of tests/scenes/stiff/singular.sl, and points near it from 1e-12 to 1e-2 away.
constexpr double kSingularS = 0.4375, kSingularT = 0.5625;

std::pair<double, double> NearSingularPoint(std::mt19937_64& rng) {
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    double r = std::pow(10.0, -12 + 10 * unit(rng)), phi = 2 * M_PI * unit(rng);
    return {kSingularS + r * std::cos(phi), kSingularT + r * std::sin(phi)};
}

/// The height range of each kind of singular.sl (Km = 0.05; r <= 0.8 on the unit patch).
std::pair<double, double> SingularHeights(const std::string& name) {
    if (name == "singular-sqrt") return {0, 0.05 * (std::sqrt(0.5625) + std::sqrt(0.8))};  // sqrt|s-c| + sqrt(r)
    if (name == "singular-log") return {-INFINITY, 0.05 * std::log(0.8)};                  // log(r)
    return {-0.05, 0.05};                                                                  // |sin(x)/x| <= 1
}

void RunSingular(const std::string& name, uint64_t seed, bool checkFalseHits) {
    StiffScene scene = LoadStiff(name);
    auto [hLo, hHi] = SingularHeights(name);
    CaseRunner run(scene, hLo, hHi);
    run.CameraRays(8, 4000);
    std::mt19937_64 rng(seed);
    run.AimedCameraRays(32, [&](int) { return NearSingularPoint(rng); });
    RequireSound(run.report(), 30, 5000, checkFalseHits);
}

}  // namespace

TEST_CASE("stiff: sqrt whose argument reaches 0 inside a region", "[renderer][stiff]") {
    RunSingular("singular-sqrt", 44, true);
}

// log(r) and sin(x)/x are unbounded over every region that touches their singular point, down to
// the depth limit. These two cases check for missed hits only; false hits are the case below.
TEST_CASE("stiff: log whose argument reaches 0 inside a region", "[renderer][stiff]") {
    RunSingular("singular-log", 45, false);
}

TEST_CASE("stiff: division by a range containing 0", "[renderer][stiff]") { RunSingular("singular-div", 46, false); }

TEST_CASE("stiff: unbounded regions at a singular point give no hit to rays that miss the surface",
          "[renderer][stiff]") {
    // The depth-limited unbounded region at the singular point is reported as a possible hit at
    // the ray's closest approach to the surface point at its centre. It must only be reached by
    // rays that cross the box of the region's bounded coordinates (x and y here: only z runs off
    // to infinity); before that test, camera rays passing over the patch above every height the
    // shader reaches still hit.
    for (const char* name : {"singular-log", "singular-div"}) {
        StiffScene scene = LoadStiff(name);
        auto [hLo, hHi] = SingularHeights(name);
        CaseRunner run(scene, hLo, hHi);
        int missing = 0;
        const renderer::CameraDesc& desc = scene.prepared.desc.camera;
        for (int j = 0; j < 12; ++j)
            for (int i = 0; i < 12; ++i) {
                Ray ray = scene.camera->GenerateRay((i + 0.5) * desc.xres / 12, (j + 0.5) * desc.yres / 12);
                if (!run.ProvablyMisses(ray, 1e-3)) continue;
                ++missing;
                Hit hit;
                run.Trace(ray, scene.CameraTolerance(), &hit);
            }
        INFO(name << ": " << run.report().ToString());
        CHECK(missing >= 20);
        CHECK(run.report().falseHits == 0);
    }
}

TEST_CASE("stiff: a singular line costs regions linear in the depth limit", "[renderer][stiff]") {
    // log|s - 0.4375| is unbounded over every region touching the line s = 0.4375: their z is
    // unbounded, so neither ray plane can exclude them. Unless the ray is tested against the box
    // of their bounded x and y, all survive and the work per ray doubles with every level, which
    // at the default depth of 24 is a hang.
    compiler::CompiledShader s =
        test::CompileOrThrow("displacement line() { P += 0.05 * log(abs(s - 0.4375)) * normalize(N); }");
    const renderer::BilinearPatch square = renderer::BilinearPatch::UnitSquare();
    std::vector<std::string> errors;
    const vm::Program bound = *compiler::Specialise(s.bound, {}, &errors, {{vm::Global::N, {0, 0, 1}}});
    Ray ray{{0.2, 0.3, 2.0}, glm::normalize(glm::dvec3(0.3, 0.2, -1.0))};
    uint64_t regions[2];
    for (int i = 0; i < 2; ++i) {
        auto intersector =
            renderer::MakeSurfaceIntersector(square, bound, glm::dvec3(0), renderer::BoundMode::Affine, 8 + 2 * i);
        Hit hit;
        IntersectStats stats;
        intersector->Intersect(ray, 0, INFINITY, {1e-3, 0}, false, &hit, stats);
        regions[i] = stats.regionsBounded;
    }
    INFO("regions per ray at depth 8: " << regions[0] << ", at depth 10: " << regions[1]);
    CHECK(regions[1] < 2 * regions[0]);
}

TEST_CASE("stiff: the patch placed 1e6 units from the origin", "[renderer][stiff]") {
    StiffScene scene = LoadStiff("far-offset");
    CaseRunner run(scene, -0.06, 0.06);
    run.CameraRays(8, 4000);
    std::mt19937_64 rng(47);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    run.AimedCameraRays(32, [&](int) { return std::pair(unit(rng), unit(rng)); });
    RequireSound(run.report(), 40, 2000);

    // The same scene moved back to the origin: the same rays hit at the same distances, within
    // the two certified errors.
    renderer::SceneDesc near = ReadStiffDesc("far-offset");
    const glm::dvec3 offset = near.primitives.at(0).base.patch().corners[0];
    REQUIRE(glm::length(offset) >= 1e6);
    renderer::BilinearPatch shifted = near.primitives[0].base.patch();
    for (glm::dvec3& c : shifted.corners) c -= offset;
    const renderer::BaseSurface& old = near.primitives[0].base;
    renderer::BaseSurface base(shifted, old.flipNormal, old.range);
    base.textureCoordinates = old.textureCoordinates;
    near.primitives[0].base = base;
    near.camera.worldToCamera = near.camera.worldToCamera * glm::translate(glm::dmat4(1.0), offset);
    StiffScene moved = PrepareDesc(near, scene.options);
    CaseRunner runNear(moved, -0.06, 0.06);
    auto farIntersector = renderer::MakeSurfaceIntersector(scene.primitive().base(), scene.primitive().bound(),
                                                           scene.camera->Position(), renderer::BoundMode::Affine, 24);
    int compared = 0;
    for (int j = 0; j < 8; ++j)
        for (int i = 0; i < 8; ++i) {
            double x = (i + 0.5) * 4, y = (j + 0.5) * 4;
            Ray farRay = scene.camera->GenerateRay(x, y), nearRay = moved.camera->GenerateRay(x, y);
            Hit farHit, nearHit;
            IntersectStats stats;
            bool farFound =
                farIntersector->Intersect(farRay, 0, INFINITY, scene.CameraTolerance(), false, &farHit, stats);
            bool nearFound = runNear.Trace(nearRay, moved.CameraTolerance(), &nearHit);
            INFO("raster (" << x << "," << y << ")");
            // The ray directions agree to rounding, so only a ray grazing the patch's edge may differ.
            if (farFound != nearFound) continue;
            if (!farFound) continue;
            ++compared;
            CHECK(std::abs(farHit.t - nearHit.t) <= farHit.error + nearHit.error + 1e-6);
        }
    CHECK(compared >= 10);
}

TEST_CASE("stiff: the patch seen from 1e6 units away", "[renderer][stiff]") {
    StiffScene scene = LoadStiff("far-distance");
    CaseRunner run(scene, -0.06, 0.06);
    run.CameraRays(8, 4000);
    std::mt19937_64 rng(48);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    run.AimedCameraRays(32, [&](int) { return std::pair(unit(rng), unit(rng)); });
    RequireSound(run.report(), 40, 2000);
}

TEST_CASE("stiff: grazing rays within 0.1 degree of the surface", "[renderer][stiff]") {
    StiffScene scene = LoadStiff("grazing");
    CaseRunner run(scene, -0.002, 0.002);
    // The scene's camera rays all meet the plane at under 0.1 degree.
    run.CameraRays(8, 4000);
    // Rays from every azimuth at 0.001 to 0.1 degree above the plane, aimed at surface points.
    std::mt19937_64 rng(49);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    const Tolerance tol{1e-3, 0};
    for (int i = 0; i < 48; ++i) {
        double u = unit(rng), v = unit(rng);
        double elevation = std::pow(10.0, -3 + 2 * unit(rng));
        glm::dvec3 dir = DirectionAtElevation(elevation, 2 * M_PI * unit(rng), run.field().Normal());
        run.AimedRay(run.field().Surface(u, v) + (1 + 20 * unit(rng)) * dir, u, v, tol);
    }
    RequireSound(run.report(), 50, 5000);
}

TEST_CASE("stiff: tolerance 1e-4 pixel", "[renderer][stiff]") {
    StiffScene scene = LoadStiff("tolerance");
    REQUIRE(scene.options.tolerancePixels == 1e-4);
    CaseRunner run(scene, -0.06, 0.06);
    run.CameraRays(8, 4000);
    std::mt19937_64 rng(50);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    run.AimedCameraRays(32, [&](int) { return std::pair(unit(rng), unit(rng)); });
    RequireSound(run.report(), 40, 5000);
    // The certified error follows the tolerance: under 1e-4 pixel footprints at 5 units.
    CHECK(run.report().stats.maxHitError <= scene.CameraTolerance().At(5.0));
}

TEST_CASE("stiff: a bad number in a RIB parameter list names the parameter", "[renderer][stiff][rib]") {
    auto errorOf = [](const std::string& text) {
        affray::diag::Report error;
        CHECK_FALSE(rib::ParseRib(text, "t.rib", &error));
        return test::LastMessage(error);
    };
    CHECK(errorOf("WorldBegin\nDisplacement \"wave\" \"Km\" [1e400]\n") ==
          "t.rib:2:27: error: number '1e400' is out of range (in the value of parameter \"Km\" of Displacement)");
    CHECK(errorOf("WorldBegin\nDisplacement \"wave\" \"float Km\" -inf\n") ==
          "t.rib:2:32: error: invalid number '-inf': NaN and infinity are not allowed (in the value of parameter "
          "\"float Km\" of Displacement)");
    CHECK(errorOf("LightSource \"pointlight\" 1 \"from\" [0 nan 0]\n") ==
          "t.rib:1:38: error: invalid number 'nan': NaN and infinity are not allowed (in the value of parameter "
          "\"from\" of LightSource)");
    // Without a parameter name before it, the message is the lexer's alone.
    CHECK(errorOf("Translate 0 0 1e999\n") == "t.rib:1:15: error: number '1e999' is out of range");
}

TEST_CASE("stiff: a ray stops at its region budget when every bound overflows", "[renderer][stiff]") {
    // Heights near 1e140 over a unit patch: every bound is finite but enormous, so no region is
    // small enough to be a hit until the depth limit. The parallelogram test follows the ray down
    // to it through a few regions per level; a small region budget ends the search earlier, with
    // an uncertified possible hit.
    compiler::CompiledShader s =
        test::CompileOrThrow("displacement huge() { P += 1e140 * sin(40 * s) * normalize(N); }");
    const renderer::BilinearPatch square = renderer::BilinearPatch::UnitSquare();
    std::vector<std::string> errors;
    const vm::Program bound = *compiler::Specialise(s.bound, {}, &errors, {{vm::Global::N, {0, 0, 1}}});
    Ray ray{{0.2, 0.3, 2.0}, glm::normalize(glm::dvec3(0.3, 0.2, -1.0))};
    {
        auto intersector =
            renderer::MakeSurfaceIntersector(square, bound, glm::dvec3(0), renderer::BoundMode::Affine, 24, 5000);
        Hit hit;
        IntersectStats stats;
        const bool found = intersector->Intersect(ray, 0, INFINITY, {1e-3, 0}, false, &hit, stats);
        INFO("regions bounded: " << stats.regionsBounded);
        CHECK(stats.regionsBounded <= 5000 + 4);
        CHECK(stats.budgetExhausted + stats.depthLimitHits >= 1);
        if (found) CHECK(hit.depthLimited);
    }
    auto intersector =
        renderer::MakeSurfaceIntersector(square, bound, glm::dvec3(0), renderer::BoundMode::Affine, 24, 40);
    Hit hit;
    IntersectStats stats;
    const bool found = intersector->Intersect(ray, 0, INFINITY, {1e-3, 0}, false, &hit, stats);
    INFO("regions bounded: " << stats.regionsBounded);
    CHECK(stats.budgetExhausted == 1);
    CHECK(stats.regionsBounded <= 40 + 4);
    if (found) CHECK(hit.depthLimited);
}

TEST_CASE("stiff: a wall 1e-4 thick covers every pixel of its projected rectangle", "[renderer][stiff]") {
    // tests/scenes/stiff/wall.rib at a quarter of its size: the wall stands on x = 0 (s = 0.5), 1e-4
    // thick, |y| <= 0.5, 0 <= z <= 1. Every pixel-centre ray that crosses the plane x = 0 inside
    // that rectangle (a pixel's footprint away from its edges) passes through the wall, so must hit.
    std::ifstream file(test::SourceDir() + "/tests/scenes/stiff/wall.rib");
    std::stringstream text;
    text << file.rdbuf();
    std::string rib = text.str();
    const std::string format = "Format 320 384 1";
    REQUIRE(rib.find(format) != std::string::npos);
    rib.replace(rib.find(format), format.size(), "Format 80 96 1");
    affray::diag::Report error;
    std::optional<renderer::SceneDesc> desc =
        rib::ParseRib(rib, test::SourceDir() + "/tests/scenes/stiff/wall.rib", &error);
    INFO(error);
    REQUIRE(desc);
    desc->camera.filter = renderer::FilterDesc{renderer::FilterDesc::Kind::Box, 1, 1};
    renderer::PreparedScene prepared;
    const bool ok = renderer::Renderer(renderer::Options{.shaderPaths = {test::SourceDir() + "/tests/scenes/stiff"}})
                        .Prepare(*desc, &prepared, &error);
    INFO(error);
    REQUIRE(ok);
    renderer::Options options;
    options.threads = 2;
    image::ImageBuffer image;
    renderer::RenderStats stats;
    renderer::Renderer(options).Render(prepared, &image, &stats);
    const renderer::Camera camera(desc->camera);
    const double margin = 2 * camera.PixelWidth();
    int inside = 0, missed = 0;
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
            // One jittered sample per pixel: test the rays through the pixel's corners too.
            bool through = true;
            for (double dx : {0.0, 1.0})
                for (double dy : {0.0, 1.0}) {
                    const Ray ray = camera.GenerateRay(x + dx, y + dy);
                    if (ray.dir.x == 0) through = false;
                    const double t = -ray.origin.x / ray.dir.x;
                    const glm::dvec3 p = ray.origin + t * ray.dir;
                    through = through && std::fabs(p.y) < 0.5 - margin && p.z > margin && p.z < 1 - margin;
                }
            if (!through) continue;
            ++inside;
            if (image.rgba[(size_t(y) * image.width + x) * 4 + 3] != 1.0f) ++missed;
        }
    INFO(inside << " pixels inside the wall's rectangle");
    CHECK(inside > 500);
    CHECK(missed == 0);
    CHECK(stats.camera.depthLimitHits == 0);
}

TEST_CASE("stiff: a ridge one texel wide in a 4096-texel map is hit in every pixel, from every angle",
          "[renderer][stiff][texture]") {
    // tests/scenes/stiff/ridge.rib: texel column 2048 of ridge.exr is 1, the others 0; with the
    // bilinear lookup the height is a tent 0.2 high over s in [2047.5, 2049.5] / 4096, about a
    // quarter of a pixel wide here.
    StiffScene scene = LoadStiff("ridge");
    CaseRunner run(scene, 0, 0.2);
    const double sLo = 2047.5 / 4096, sHi = 2049.5 / 4096;
    // Every pixel's centre ray, marched finely over the part of it whose foot is on the tent.
    const renderer::CameraDesc& desc = scene.prepared.desc.camera;
    int onRidge = 0;
    for (int y = 0; y < desc.yres; ++y)
        for (int x = 0; x < desc.xres; ++x) {
            const Ray ray = scene.camera->GenerateRay(x + 0.5, y + 0.5);
            const glm::dvec3 o = run.field().Locate(ray.origin), d = run.field().Locate(ray.origin + ray.dir) - o;
            if (d.x == 0) continue;
            double t0 = (sLo - o.x) / d.x, t1 = (sHi - o.x) / d.x;
            if (t0 > t1) std::swap(t0, t1);
            double f0, f1;
            if (!run.field().FootInside(ray, 0.0, &f0, &f1)) continue;
            t0 = std::max({t0, f0, 0.0});
            t1 = std::min(t1, f1);
            if (!(t0 < t1)) continue;
            const int before = run.report().bruteForceHits;
            run.BruteForceSegment(ray, scene.CameraTolerance(), t0, t1, 400);
            onRidge += run.report().bruteForceHits - before;
        }
    INFO(onRidge << " pixels see the ridge");
    CHECK(onRidge >= 100);
    // Rays aimed at points of the tent's flanks and crest from every side, 1 to 89 degrees above
    // the patch, each from 3 units away.
    std::mt19937_64 rng(47);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    const Tolerance tol{scene.CameraTolerance().At(3), 0};
    for (int i = 0; i < 240; ++i) {
        const double u = sLo + (sHi - sLo) * unit(rng), v = 0.02 + 0.96 * unit(rng);
        const glm::dvec3 dir = DirectionAtElevation(1 + 88 * unit(rng), 2 * M_PI * unit(rng), run.field().Normal());
        run.AimedRay(run.field().Surface(u, v) + 3.0 * dir, u, v, tol);
    }
    RequireSound(run.report(), 300, 20000);
}
