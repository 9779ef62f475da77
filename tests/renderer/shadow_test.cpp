// tests/renderer/shadow_test.cpp: shadow rays (renderer/render.cpp, ShadeHit) neither shadow a
// surface by itself where nothing can block the light (acne) nor let light through an occluder
// (leaks). Small scenes rendered through the library with one ray per pixel (PixelSamples 1 1,
// box filter 1 x 1), so each pixel is exactly one shaded hit, and the N and P AOVs say where.
// Every expectation is derived by hand from the scene's geometry: which points the light cannot
// be blocked from, which points every ray toward the light must cross an occluder from, and the
// matte colour Cs * (Ka * ambient + Kd * cos) in each case (RI 3.2 appendix A, Ka = Kd = 1).
#include <catch2/catch.hpp>

#include <cmath>
#include <memory>
#include <sstream>

#include "renderer/film.h"
#include "renderer/renderer.h"
#include "rib/rib.h"
#include "scene/geometry/camera.h"
#include "tests/test_util.h"

using namespace affray;

namespace {

constexpr double kPi = 3.14159265358979323846;

/// Bumps on a sphere, continuous across the seam (whole periods in s) and constant at the poles
/// (sin(4 pi t) = 0 at t = 0 and 1), so the displaced sphere stays closed.
const char* const kBumps =
    "displacement bumps(float Km = 0.03) {\n"
    "    P += Km * sin(2 * PI * 3 * s) * sin(PI * 4 * t) * normalize(N);\n"
    "    N = calculatenormal(P);\n"
    "}\n";

/// Straight ripples across s on a patch.
const char* const kRipples =
    "displacement ripples(float Km = 0.01, frequency = 4) {\n"
    "    P += Km * sin(2 * PI * frequency * s) * normalize(N);\n"
    "    N = calculatenormal(P);\n"
    "}\n";

/// A rendered scene with its AOVs, one ray per pixel.
struct Rendered {
    renderer::PreparedScene scene;
    image::ImageBuffer image;
    std::unique_ptr<renderer::Camera> camera;

    const std::vector<float>& Channel(const std::string& name) const {
        for (const auto& [n, values] : image.extraChannels)
            if (n == name) return values;
        FAIL("no channel " << name);
        throw;  // unreachable
    }
    size_t Index(int x, int y) const { return static_cast<size_t>(y) * image.width + x; }
    float R(int x, int y) const { return image.rgba[Index(x, y) * 4]; }
    float A(int x, int y) const { return image.rgba[Index(x, y) * 4 + 3]; }
    glm::dvec3 Triple(const char* layer, int x, int y) const {
        const std::string l = layer;
        return {Channel(l + ".X")[Index(x, y)], Channel(l + ".Y")[Index(x, y)], Channel(l + ".Z")[Index(x, y)]};
    }
    glm::dvec3 N(int x, int y) const { return Triple("N", x, y); }
    glm::dvec3 P(int x, int y) const { return Triple("P", x, y); }
    glm::dvec3 Eye() const { return camera->Position(); }
    /// The world-space width of a pixel at P.
    double Footprint(const glm::dvec3& P) const { return camera->Footprint(glm::length(P - Eye())); }
};

/// Parses `rib` with its lights casting shadows (Attribute "light" "shadows" "on" after its
/// WorldBegin: RenderMan's standard lights cast none), sets one sample per pixel through a 1 x 1
/// box filter and the AOVs, prepares it with `dir` as the shader path and renders it.
std::unique_ptr<Rendered> Render(std::string rib, const test::TempDir& dir) {
    affray::diag::Report error;
    const size_t world = rib.find("WorldBegin\n");
    REQUIRE(world != std::string::npos);
    rib.insert(world + 11, "Attribute \"light\" \"shadows\" \"on\"\n");
    std::optional<renderer::SceneDesc> desc = rib::ParseRib(rib, "shadow.rib", &error);
    INFO(error);
    REQUIRE(desc);
    desc->camera.xsamples = desc->camera.ysamples = 1;
    desc->camera.filter.kind = renderer::FilterDesc::Kind::Box;
    desc->camera.filter.xwidth = desc->camera.filter.ywidth = 1;
    desc->displayMode = "rgba,Z,N,P";
    auto out = std::make_unique<Rendered>();
    REQUIRE(renderer::Renderer(renderer::Options{.shaderPaths = {dir.Path("")}}).Prepare(*desc, &out->scene, &error));
    out->camera = std::make_unique<renderer::Camera>(desc->camera);
    renderer::Options options;
    options.threads = 2;
    renderer::RenderStats stats;
    renderer::Renderer(options).Render(out->scene, &out->image, &stats);
    REQUIRE(out->image.width == desc->camera.xres);
    REQUIRE(out->image.height == desc->camera.yres);
    return out;
}

std::string Str(const glm::dvec3& v) { return renderer::ToString(v); }

/// A camera 5 in front of the origin looking at it (world y up on the screen), a unit sphere
/// filling the frame.
const char* const kFrontCamera =
    "Projection \"perspective\" \"fov\" [26]\n"
    "Translate 0 0 5\n";

/// A camera above and in front of the z = 0 plane looking down at the origin at 40 degrees
/// elevation, from world (0, 4.6, 3.9) for distance 6.
std::string ObliqueCamera(double distance, double fov = 40) {
    std::ostringstream out;
    out << "Projection \"perspective\" \"fov\" [" << fov << "]\nTranslate 0 0 " << distance << "\nRotate -130 1 0 0\n";
    return out.str();
}

/// The unit-square patch [-1, 1]^2 (z = 0), matte, seen obliquely at 48 x 36 and lit by one
/// distant light from direction L, with `displacement` (a RIB line, or "") applied to it.
std::string GrazingPatchScene(const glm::dvec3& L, const std::string& displacement) {
    std::ostringstream rib;
    rib.precision(17);
    rib << "Format 48 36 1\n"
        << ObliqueCamera(3.1) << "WorldBegin\n"
        << "LightSource \"distantlight\" 1 \"intensity\" [1] \"from\" [" << L.x << " " << L.y << " " << L.z
        << "] \"to\" [0 0 0]\n"
        << "Surface \"matte\"\n"
        << displacement << "Patch \"bilinear\" \"P\" [-1 -1 0  1 -1 0  -1 1 0  1 1 0]\nWorldEnd\n";
    return rib.str();
}

}  // namespace

TEST_CASE("shadow: a bumpy sphere lit by a distant light has no acne on its lit side", "[renderer][shadow]") {
    test::TempDir dir;
    dir.Write("bumps.sl", kBumps);
    // Poles along world y (away from the lit region's centre), light from the upper left front.
    // (A displaced sphere costs about 70 regions per ray: the image is kept small.)
    const glm::dvec3 from(-0.6, 0.6, -1.5);
    std::ostringstream rib;
    rib << "Format 24 24 1\n"
        << kFrontCamera << "WorldBegin\n"
        << "LightSource \"distantlight\" 1 \"intensity\" [1] \"from\" [" << from.x << " " << from.y << " " << from.z
        << "] \"to\" [0 0 0]\n"
        << "Surface \"matte\"\nDisplacement \"bumps\" \"Km\" [0.03]\n"
        << "AttributeBegin\nRotate 90 1 0 0\nSphere 1 -1 1 360\nAttributeEnd\nWorldEnd\n";
    auto r = Render(rib.str(), dir);
    const glm::dvec3 L = glm::normalize(from);
    // Why nothing can shadow the pixels checked: the height h = Km sin(6 pi s) sin(4 pi t) has
    // slope at most 3 Km / cos(latitude) along s and 4 Km along t, under 0.19 for Km = 0.03 and
    // cos(latitude) >= 0.5; where the undisplaced direction makes an angle under 60 degrees with
    // L, the light stands over 30 degrees (slope 0.58) above the base sphere's tangent plane,
    // which curves away below the ray: the ray rises faster than any bump it passes. (Along
    // the ray |P + tL|^2 >= (1-Km)^2 + (1-Km) t + t^2, so only t < 0.13 could reach r <= 1+Km.)
    int checked = 0, acne = 0;
    for (int y = 0; y < r->image.height; ++y)
        for (int x = 0; x < r->image.width; ++x) {
            if (r->A(x, y) != 1.0f) continue;
            const glm::dvec3 P = r->P(x, y), N = r->N(x, y);
            const glm::dvec3 V = glm::normalize(r->Eye() - P);
            const glm::dvec3 dir0 = glm::normalize(P);
            if (glm::dot(N, L) <= 0.3 || glm::dot(dir0, L) <= 0.5 || std::fabs(dir0.y) >= 0.8) continue;
            if (glm::dot(N, V) <= 0.05) continue;  // Nf = N: the shading normal faces the camera
            ++checked;
            const double expected = glm::dot(N, L);  // Cs = 1, Kd = 1, intensity 1, no ambient
            if (std::fabs(r->R(x, y) - expected) > 1e-4) {
                ++acne;
                UNSCOPED_INFO("pixel (" << x << "," << y << ") P=" << Str(P) << " N=" << Str(N) << " R=" << r->R(x, y)
                                        << " expected " << expected);
            }
        }
    INFO(checked << " pixels checked");
    CHECK(checked > 100);
    CHECK(acne == 0);
}

TEST_CASE("shadow: a flat patch lit at a grazing 10 degrees is lit everywhere", "[renderer][shadow]") {
    test::TempDir dir;
    const double elevation = 10 * kPi / 180;
    const glm::dvec3 L(std::cos(elevation), 0, std::sin(elevation));
    auto r = Render(GrazingPatchScene(L, ""), dir);
    // Nothing but the plane itself: every hit is lit, at Kd cos = sin(10 degrees).
    int hits = 0, dark = 0;
    for (int y = 0; y < r->image.height; ++y)
        for (int x = 0; x < r->image.width; ++x) {
            if (r->A(x, y) != 1.0f) continue;
            ++hits;
            if (std::fabs(r->R(x, y) - std::sin(elevation)) > 1e-5) {
                ++dark;
                UNSCOPED_INFO("pixel (" << x << "," << y << ") P=" << Str(r->P(x, y)) << " R=" << r->R(x, y));
            }
        }
    INFO(hits << " hits");
    CHECK(hits > 500);
    CHECK(dark == 0);
}

TEST_CASE("shadow: shallow ripples lit at a grazing 10 degrees show no speckles", "[renderer][shadow]") {
    test::TempDir dir;
    dir.Write("ripples.sl", kRipples);
    const double elevation = 10 * kPi / 180;
    const glm::dvec3 L(std::cos(elevation), 0, std::sin(elevation));
    auto r = Render(GrazingPatchScene(L, "Displacement \"ripples\" \"Km\" [0.01] \"frequency\" [4]\n"), dir);
    // The height 0.01 sin(8 pi s), s = (x + 1) / 2, rises at most 0.01 * 4 pi = 0.126 per unit
    // of x, less than the light's tan(10 degrees) = 0.176: a ray toward the light climbs away from
    // the surface everywhere, so nothing is shadowed, and the normal tilts at most 7.2 degrees,
    // so every point faces the light (cos >= sin(2.8 degrees)).
    int hits = 0, dark = 0;
    for (int y = 0; y < r->image.height; ++y)
        for (int x = 0; x < r->image.width; ++x) {
            if (r->A(x, y) != 1.0f) continue;
            ++hits;
            const glm::dvec3 N = r->N(x, y);
            const double expected = glm::dot(N, L);
            REQUIRE(expected > 0.04);
            if (std::fabs(r->R(x, y) - expected) > 1e-4) {
                ++dark;
                UNSCOPED_INFO("pixel (" << x << "," << y << ") P=" << Str(r->P(x, y)) << " N=" << Str(N)
                                        << " R=" << r->R(x, y) << " expected " << expected);
            }
        }
    INFO(hits << " hits");
    CHECK(hits > 500);
    CHECK(dark == 0);
}

TEST_CASE("shadow: a bumpy patch above the ground casts a full shadow and nothing more", "[renderer][shadow]") {
    test::TempDir dir;
    dir.Write("ripples.sl", kRipples);
    const glm::dvec3 from(0.3, 0.2, 1);
    const glm::dvec3 L = glm::normalize(from);
    const double km = 0.05, height = 1, ambient = 0.1;
    const glm::dvec2 lo(-0.6, -0.4), hi(0.6, 0.4);  // the occluder's rectangle
    std::ostringstream rib;
    rib << "Format 64 48 1\n"
        << ObliqueCamera(6) << "WorldBegin\n"
        << "LightSource \"ambientlight\" 1 \"intensity\" [" << ambient << "]\n"
        << "LightSource \"distantlight\" 2 \"intensity\" [1] \"from\" [" << from.x << " " << from.y << " " << from.z
        << "] \"to\" [0 0 0]\n"
        << "Surface \"matte\"\n"
        << "Patch \"bilinear\" \"P\" [-2.5 -2.5 0  2.5 -2.5 0  -2.5 2.5 0  2.5 2.5 0]\n"
        << "AttributeBegin\nDisplacement \"ripples\" \"Km\" [" << km << "] \"frequency\" [3]\n"
        << "Patch \"bilinear\" \"P\" [-0.6 -0.4 1  0.6 -0.4 1  -0.6 0.4 1  0.6 0.4 1]\nAttributeEnd\nWorldEnd\n";
    auto r = Render(rib.str(), dir);
    // The occluder moves only along z (its normal), staying within z in [1 - Km, 1 + Km] over its
    // rectangle. A ray from ground point P toward the light crosses that slab between
    // Q(1 - Km) and Q(1 + Km), Q(h) = P + (h / Lz) L: if both lie inside the rectangle (shrunk by
    // a margin), the ray must cross the surface (a continuous graph spanning the slab there), so
    // P sees only the ambient light. If the segment stays a margin outside it, P is fully lit.
    auto distanceOutside = [&](const glm::dvec3& P, double h) {
        const glm::dvec3 Q = P + ((h - P.z) / L.z) * L;
        return std::max({lo.x - Q.x, Q.x - hi.x, lo.y - Q.y, Q.y - hi.y});  // < 0: inside
    };
    int shadowed = 0, lit = 0, leaks = 0, falseShadows = 0;
    for (int y = 0; y < r->image.height; ++y)
        for (int x = 0; x < r->image.width; ++x) {
            if (r->A(x, y) != 1.0f) continue;
            const glm::dvec3 P = r->P(x, y);
            if (std::fabs(P.z) > 1e-5) continue;  // not the ground
            const double margin = r->Footprint(P);
            const double out0 = distanceOutside(P, height - km), out1 = distanceOutside(P, height + km);
            if (std::max(out0, out1) < -margin) {
                ++shadowed;
                if (std::fabs(r->R(x, y) - ambient) > 1e-6) {
                    ++leaks;
                    UNSCOPED_INFO("leak at pixel (" << x << "," << y << ") P=" << Str(P) << " R=" << r->R(x, y));
                }
            } else if (std::min(out0, out1) > 2 * margin) {
                ++lit;
                if (std::fabs(r->R(x, y) - (ambient + L.z)) > 1e-5) {
                    ++falseShadows;
                    UNSCOPED_INFO("unlit at pixel (" << x << "," << y << ") P=" << Str(P) << " R=" << r->R(x, y));
                }
            }
        }
    INFO(shadowed << " shadowed and " << lit << " lit ground pixels checked");
    CHECK(shadowed > 30);
    CHECK(lit > 300);
    CHECK(leaks == 0);
    CHECK(falseShadows == 0);
}

TEST_CASE("shadow: a cylinder of radius 0.01 still casts its shadow line", "[renderer][shadow]") {
    test::TempDir dir;
    const double radius = 0.01, ambient = 0.1;
    std::ostringstream rib;
    rib << "Format 64 48 1\n"
        << ObliqueCamera(3) << "WorldBegin\n"
        << "LightSource \"ambientlight\" 1 \"intensity\" [" << ambient << "]\n"
        << "LightSource \"distantlight\" 2 \"intensity\" [1] \"from\" [0 0 1] \"to\" [0 0 0]\n"
        << "Surface \"matte\"\n"
        << "Patch \"bilinear\" \"P\" [-2 -2 0  2 -2 0  -2 2 0  2 2 0]\n"
        // Object z becomes world x: the axis runs along x at height 0.5 over y = 0.
        << "AttributeBegin\nTranslate 0 0 0.5\nRotate 90 0 1 0\nCylinder " << radius
        << " -1.5 1.5 360\nAttributeEnd\nWorldEnd\n";
    auto r = Render(rib.str(), dir);
    // Light straight down: the shadow is exactly the strip |y| < radius, |x| < 1.5 of the ground.
    int inStrip = 0, leaks = 0, darkNear = 0, lit = 0, falseShadows = 0;
    for (int y = 0; y < r->image.height; ++y)
        for (int x = 0; x < r->image.width; ++x) {
            if (r->A(x, y) != 1.0f) continue;
            const glm::dvec3 P = r->P(x, y);
            if (std::fabs(P.z) > 1e-5 || std::fabs(P.x) > 1.4) continue;  // not the ground under the cylinder
            const bool dark = std::fabs(r->R(x, y) - ambient) < 1e-6;
            const double margin = r->Footprint(P);
            if (std::fabs(P.y) < radius * (1 - 1e-6)) {
                ++inStrip;
                if (!dark) {
                    ++leaks;
                    UNSCOPED_INFO("leak at pixel (" << x << "," << y << ") P=" << Str(P) << " R=" << r->R(x, y));
                }
            }
            if (dark && std::fabs(P.y) < radius + margin) ++darkNear;
            if (std::fabs(P.y) > radius + 2 * margin) {
                ++lit;
                if (std::fabs(r->R(x, y) - (ambient + 1)) > 1e-5) {
                    ++falseShadows;
                    UNSCOPED_INFO("unlit at pixel (" << x << "," << y << ") P=" << Str(P) << " R=" << r->R(x, y));
                }
            }
        }
    INFO(inStrip << " pixels inside the strip, " << darkNear << " dark pixels along the line, " << lit
                 << " lit pixels checked");
    CHECK(darkNear >= 5);
    CHECK(leaks == 0);
    CHECK(lit > 1000);
    CHECK(falseShadows == 0);
}

TEST_CASE("shadow: a point light inside a closed sphere lights nothing outside", "[renderer][shadow]") {
    test::TempDir dir;
    dir.Write("bumps.sl", kBumps);
    const double ambient = 0.1;
    auto scene = [&](const std::string& sphere) {
        std::ostringstream rib;
        rib << "Format 32 24 1\n"
            << ObliqueCamera(7) << "WorldBegin\n"
            << "LightSource \"ambientlight\" 1 \"intensity\" [" << ambient << "]\n"
            << "LightSource \"pointlight\" 2 \"intensity\" [2] \"from\" [0 0 0]\n"
            << "Surface \"matte\"\n"
            << "Patch \"bilinear\" \"P\" [-3 -3 -1.5  3 -3 -1.5  -3 3 -1.5  3 3 -1.5]\n"
            << "AttributeBegin\n"
            << sphere << "\nAttributeEnd\nWorldEnd\n";
        return rib.str();
    };
    // Everything visible is outside the sphere: the ground, reached by no ray from the light, and
    // the sphere's outside, which faces away from it. Only the ambient light remains.
    // A camera sample that grazes the silhouette within the tolerance is a hit whose surface point
    // may lie just past it, on the far side (the tolerance allows it); two-sided shading then
    // sees that point from inside, lit. Such samples are counted apart, and must stay a few.
    const glm::dvec3 eye(0, 7 * std::sin(130 * M_PI / 180), -7 * std::cos(130 * M_PI / 180));
    int grazing = 0;
    auto countLit = [&](const Rendered& r, int* hits) {
        int lit = 0;
        *hits = 0;
        for (int y = 0; y < r.image.height; ++y)
            for (int x = 0; x < r.image.width; ++x) {
                if (r.A(x, y) != 1.0f) continue;
                ++*hits;
                if (std::fabs(r.R(x, y) - ambient) > 1e-6) {
                    const glm::dvec3 P = r.P(x, y);
                    const bool onSphere = glm::length(P) < 1.2;
                    if (onSphere && glm::dot(P, eye - P) < 0) {
                        ++grazing;
                        continue;
                    }
                    ++lit;
                    UNSCOPED_INFO("lit pixel (" << x << "," << y << ") P=" << Str(P) << " R=" << r.R(x, y));
                }
            }
        return lit;
    };
    int hits = 0;
    SECTION("a plain sphere") {
        auto r = Render(scene("Sphere 1 -1 1 360"), dir);
        CHECK(countLit(*r, &hits) == 0);
        CHECK(hits > 250);
        CHECK(grazing <= 3);
    }
    SECTION("a bumpy sphere") {
        auto r = Render(scene("Displacement \"bumps\" \"Km\" [0.05]\nSphere 1 -1 1 360"), dir);
        CHECK(countLit(*r, &hits) == 0);
        CHECK(hits > 250);
        CHECK(grazing <= 3);
    }
    SECTION("control: a sphere with a 60 degree wedge cut out lets light onto the ground") {
        auto r = Render(scene("Sphere 1 -1 1 300"), dir);
        CHECK(countLit(*r, &hits) > 20);
    }
}
