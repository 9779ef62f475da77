// tests/renderer/shade_test.cpp: the surface models and lights (renderer/shade.*) against values
// worked out by hand from RI Spec 3.2 appendix A, plastic and matte against the implementation
// they had before metal, constant and spotlight were added, and shadow rays only where needed.
#include "renderer/shade.h"

#include <catch2/catch.hpp>
#include <cmath>

#include "compiler/compile.h"

using namespace affray::renderer;

namespace {

constexpr double kPi = 3.14159265358979323846;

/// A point at the origin facing +z, seen from straight above.
ShadingPoint Facing() { return {glm::dvec3(0.0), glm::dvec3(0, 0, 1), glm::dvec3(0, 0, 1)}; }

/// A point light that casts shadows (as the lights of these tests do, but the last case's).
LightDesc Point(const glm::dvec3& from, double intensity) {
    LightDesc l;
    l.kind = LightDesc::Kind::Point;
    l.from = from;
    l.intensity = intensity;
    l.castShadows = true;
    return l;
}

LightDesc Ambient(double intensity) {
    LightDesc l;
    l.kind = LightDesc::Kind::Ambient;
    l.intensity = intensity;
    return l;
}

/// A spotlight 2 above the origin shining straight down: coneangle 30 deg, delta 5 deg.
LightDesc Spot(double intensity = 4) {
    LightDesc l;
    l.kind = LightDesc::Kind::Spot;
    l.castShadows = true;
    l.from = {0, 0, 2};
    l.to = {0, 0, 0};
    l.intensity = intensity;
    l.coneAngle = 30 * kPi / 180;
    l.coneDeltaAngle = 5 * kPi / 180;
    l.beamDistribution = 2;
    return l;
}

SurfaceDesc Model(SurfaceDesc::Model model, double Ka, double Kd, double Ks, double roughness = 0.1) {
    SurfaceDesc s;
    s.model = model;
    s.Ka = Ka;
    s.Kd = Kd;
    s.Ks = Ks;
    s.roughness = roughness;
    return s;
}

/// A shadow test that blocks nothing (or everything, or lets `through` through) and counts its
/// calls.
struct CountingOcclusion {
    int calls = 0;
    bool blocked = false;
    glm::dvec3 through{1.0};
    ShadowTest Test() {
        return [this](const glm::dvec3&, double) {
            ++calls;
            return blocked ? glm::dvec3(0.0) : through;
        };
    }
};

/// The matte and plastic of shade.cpp as they were before metal, constant and spotlight: the
/// reference that the refactored code must reproduce bit for bit.
glm::dvec3 ShadeBefore(const SurfaceDesc& surface, const glm::dvec3& Cs, const ShadingPoint& sp,
                       const std::vector<LightDesc>& lights, const ShadowTest& occluded) {
    glm::dvec3 ambient(0.0), diffuse(0.0), specular(0.0);
    for (const LightDesc& light : lights) {
        glm::dvec3 Cl = light.intensity * light.color;
        if (light.kind == LightDesc::Kind::Ambient) {
            ambient += Cl;
            continue;
        }
        glm::dvec3 L;
        double distance;
        if (light.kind == LightDesc::Kind::Distant) {
            L = glm::normalize(light.from - light.to);
            distance = INFINITY;
        } else {
            glm::dvec3 toLight = light.from - sp.P;
            distance = glm::length(toLight);
            if (!(distance > 0)) continue;
            L = toLight / distance;
            Cl /= distance * distance;
        }
        double cosine = glm::dot(sp.Nf, L);
        if (cosine <= 0) continue;
        if (occluded(L, distance) != glm::dvec3(1.0)) continue;  // blocked (these tests block all or nothing)
        diffuse += Cl * cosine;
        if (surface.model == SurfaceDesc::Model::Plastic && surface.roughness > 0) {
            glm::dvec3 H = glm::normalize(L + sp.V);
            specular += Cl * std::pow(std::max(0.0, glm::dot(sp.Nf, H)), 1.0 / surface.roughness);
        }
    }
    glm::dvec3 color = Cs * (surface.Ka * ambient + surface.Kd * diffuse);
    if (surface.model == SurfaceDesc::Model::Plastic) color += surface.specularColor * surface.Ks * specular;
    return color;
}

void RequireNear(const glm::dvec3& got, const glm::dvec3& want) {
    INFO("got [" << got.x << " " << got.y << " " << got.z << "], want [" << want.x << " " << want.y << " " << want.z
                 << "]");
    for (int c = 0; c < 3; ++c) REQUIRE(got[c] == Approx(want[c]).margin(1e-14));
}

}  // namespace

TEST_CASE("Plastic by hand: ambient, diffuse and an off-axis highlight", "[shade]") {
    const glm::dvec3 Cs(1, 0.5, 0.25);
    const SurfaceDesc plastic = Model(SurfaceDesc::Model::Plastic, 1, 0.5, 0.5);
    CountingOcclusion occ;
    // Overhead, intensity 4 at distance 2: Cl = 1, N.L = 1, N.H = 1.
    glm::dvec3 c = ShadeSurface(plastic, Cs, Facing(), {Point({0, 0, 2}, 4), Ambient(0.1)}, occ.Test());
    RequireNear(c, Cs * (0.1 + 0.5) + glm::dvec3(0.5));
    // At 45 degrees, distance sqrt(8): Cl = 1/8, N.L = cos 45, H halfway: N.H = cos 22.5.
    c = ShadeSurface(plastic, Cs, Facing(), {Point({2, 0, 2}, 1)}, occ.Test());
    const double Cl = 1.0 / 8, spec = std::pow(std::cos(kPi / 8), 10);
    RequireNear(c, Cs * 0.5 * Cl * std::cos(kPi / 4) + glm::dvec3(0.5 * Cl * spec));
    CHECK(occ.calls == 2);
}

TEST_CASE("Plastic and matte are unchanged bit for bit", "[shade]") {
    const std::vector<LightDesc> lights = [] {
        std::vector<LightDesc> l = {Point({0.3, -0.2, 2}, 3), Point({-4, 1, 0.5}, 20), Ambient(0.07),
                                    Point({0, 0, -3}, 5)};  // the last is behind the surface
        LightDesc distant;
        distant.kind = LightDesc::Kind::Distant;
        distant.from = {1, 2, 3};
        distant.to = {0, 0, 0};
        distant.color = {1, 0.9, 0.8};
        distant.castShadows = true;
        l.push_back(distant);
        return l;
    }();
    ShadingPoint sp{
        {0.1, 0.2, 0.05}, glm::normalize(glm::dvec3(0.1, -0.2, 1)), glm::normalize(glm::dvec3(-0.3, 0.4, 1))};
    const glm::dvec3 Cs(0.8, 0.6, 0.3);
    for (auto model : {SurfaceDesc::Model::Matte, SurfaceDesc::Model::Plastic})
        for (double roughness : {0.05, 0.1, 0.3, 0.0})
            for (bool blocked : {false, true}) {
                SurfaceDesc s = Model(model, 0.9, 0.6, 0.4, roughness);
                s.specularColor = {1, 0.5, 0.5};
                CountingOcclusion occ;
                occ.blocked = blocked;
                const glm::dvec3 got = ShadeSurface(s, Cs, sp, lights, occ.Test());
                const glm::dvec3 want = ShadeBefore(s, Cs, sp, lights, occ.Test());
                INFO("model " << int(model) << " roughness " << roughness << " blocked " << blocked);
                CHECK(got == want);
            }
}

TEST_CASE("Constant is Cs and casts no shadow rays", "[shade]") {
    CountingOcclusion occ;
    const glm::dvec3 Cs(0.2, 0.4, 0.6);
    SurfaceDesc constant;
    constant.model = SurfaceDesc::Model::Constant;
    CHECK(ShadeSurface(constant, Cs, Facing(), {Point({0, 0, 2}, 4), Ambient(1), Spot()}, occ.Test()) == Cs);
    CHECK(ShadeSurface(constant, Cs, Facing(), {}, occ.Test()) == Cs);
    CHECK(occ.calls == 0);
}

TEST_CASE("Metal is Cs times ambient and specular, without diffuse", "[shade]") {
    const glm::dvec3 Cs(1, 0.5, 0.25);
    SurfaceDesc metal = Model(SurfaceDesc::Model::Metal, 1, 0.5, 1, 0.1);
    metal.specularColor = {0, 0, 0};  // metal tints its highlight with Cs, not specularcolor
    CountingOcclusion occ;
    // Off axis as in the plastic case: Cl = 1/8, N.H = cos 22.5.
    glm::dvec3 c = ShadeSurface(metal, Cs, Facing(), {Point({2, 0, 2}, 1), Ambient(0.2)}, occ.Test());
    RequireNear(c, Cs * (0.2 + std::pow(std::cos(kPi / 8), 10) / 8));
    CHECK(occ.calls == 1);
    // Ka and Ks scale their terms.
    metal.Ka = 0.5;
    metal.Ks = 2;
    c = ShadeSurface(metal, Cs, Facing(), {Point({0, 0, 2}, 4), Ambient(0.2)}, occ.Test());
    RequireNear(c, Cs * (0.5 * 0.2 + 2 * 1.0));
    // No highlight without roughness: nothing a light could add, so no shadow ray.
    metal.roughness = 0;
    occ.calls = 0;
    c = ShadeSurface(metal, Cs, Facing(), {Point({0, 0, 2}, 4), Ambient(0.2)}, occ.Test());
    RequireNear(c, Cs * 0.1);
    CHECK(occ.calls == 0);
}

TEST_CASE("Spotlight on the axis, inside, at the edge and outside its cone", "[shade]") {
    const SurfaceDesc matte = Model(SurfaceDesc::Model::Matte, 0, 1, 0);
    const glm::dvec3 white(1.0);
    auto at = [&](double degreesOffAxis, CountingOcclusion* occ) {
        // The point on the plane z = 0 that the spot sees at this angle from its axis.
        ShadingPoint sp = Facing();
        sp.P = {2 * std::tan(degreesOffAxis * kPi / 180), 0, 0};
        return ShadeSurface(matte, white, sp, {Spot()}, occ->Test());
    };
    CountingOcclusion occ;
    // On the axis: intensity 4 at distance 2, smoothstep 1, cos^2 = 1, N.L = 1.
    RequireNear(at(0, &occ), glm::dvec3(1.0));
    // 10 degrees off: inside the inner cone (25 deg); Cl = 4 c^2/4 (1/d^2 with d = 2/c) * c^2
    // (beamdistribution 2) and N.L = c: c^5.
    const double c10 = std::cos(10 * kPi / 180);
    RequireNear(at(10, &occ), glm::dvec3(std::pow(c10, 5)));
    CHECK(occ.calls == 2);
    // Outside the cone: dark, and no shadow ray.
    occ.calls = 0;
    RequireNear(at(40, &occ), glm::dvec3(0.0));
    RequireNear(at(30.5, &occ), glm::dvec3(0.0));
    CHECK(occ.calls == 0);
    // In the soft edge, a quarter of the way from cos 30 to cos 25: smoothstep = t^2 (3 - 2t) = 0.15625.
    const double cosOut = std::cos(30 * kPi / 180), cosIn = std::cos(25 * kPi / 180);
    const double c = cosOut + 0.25 * (cosIn - cosOut);
    RequireNear(at(std::acos(c) * 180 / kPi, &occ), glm::dvec3(0.15625 * std::pow(c, 5)));
    // Halfway: 0.5.
    const double h = 0.5 * (cosOut + cosIn);
    RequireNear(at(std::acos(h) * 180 / kPi, &occ), glm::dvec3(0.5 * std::pow(h, 5)));
}

TEST_CASE("Spotlight beam distribution and colour", "[shade]") {
    LightDesc spot = Spot(8);
    spot.beamDistribution = 5;
    spot.color = {1, 0.5, 0};
    ShadingPoint sp = Facing();
    const double angle = 20 * kPi / 180, c = std::cos(angle);
    sp.P = {0, 2 * std::tan(angle), 0};
    CountingOcclusion occ;
    glm::dvec3 got = ShadeSurface(Model(SurfaceDesc::Model::Matte, 0, 1, 0), glm::dvec3(1.0), sp, {spot}, occ.Test());
    // 8 / d^2 = 2 c^2, beam c^5, N.L = c.
    RequireNear(got, glm::dvec3(1, 0.5, 0) * (2 * std::pow(c, 8)));
}

TEST_CASE("Shadow rays only for lights that would add light", "[shade]") {
    const SurfaceDesc plastic = Model(SurfaceDesc::Model::Plastic, 1, 0.5, 0.5);
    CountingOcclusion occ;
    // Behind the surface, and ambient: no shadow rays.
    ShadeSurface(plastic, glm::dvec3(1.0), Facing(), {Point({0, 0, -2}, 4), Ambient(1)}, occ.Test());
    CHECK(occ.calls == 0);
    // A blocked light adds nothing; the ambient still shows.
    occ.blocked = true;
    glm::dvec3 c = ShadeSurface(plastic, glm::dvec3(1.0), Facing(), {Point({0, 0, 2}, 4), Ambient(0.25)}, occ.Test());
    CHECK(occ.calls == 1);
    RequireNear(c, glm::dvec3(0.25));
    // A blocked spotlight likewise.
    occ.calls = 0;
    c = ShadeSurface(plastic, glm::dvec3(1.0), Facing(), {Spot()}, occ.Test());
    CHECK(occ.calls == 1);
    RequireNear(c, glm::dvec3(0.0));
}

TEST_CASE("Lights that cast no shadows trace no shadow rays, a partial shadow scales the light", "[shade]") {
    const SurfaceDesc plastic = Model(SurfaceDesc::Model::Plastic, 1, 0.5, 0.5);
    const glm::dvec3 Cs(1, 0.5, 0.25);
    LightDesc standard = Point({0, 0, 2}, 4);
    standard.castShadows = false;  // RenderMan's pointlight: no shadow() call
    CountingOcclusion occ;
    occ.blocked = true;
    glm::dvec3 c = ShadeSurface(plastic, Cs, Facing(), {standard, Ambient(0.1)}, occ.Test());
    CHECK(occ.calls == 0);
    // Overhead, Cl = 1, N.L = N.H = 1: as if nothing were in the way.
    RequireNear(c, Cs * (0.1 + 0.5) + glm::dvec3(0.5));
    // The same light casting shadows behind a half-transparent occluder (1 - Os = 0.5, 0.25, 0):
    // its diffuse and specular terms scaled per component, the ambient untouched.
    occ.blocked = false;
    occ.through = {0.5, 0.25, 0};
    c = ShadeSurface(plastic, Cs, Facing(), {Point({0, 0, 2}, 4), Ambient(0.1)}, occ.Test());
    CHECK(occ.calls == 1);
    RequireNear(c, Cs * 0.1 + (Cs * 0.5 + glm::dvec3(0.5)) * occ.through);
}

TEST_CASE("ShadingLights: each light's L and Cl as the built-in models take them, its shadow traced once",
          "[shade][surface]") {
    // Slots: the point light (0), the spotlight (1), a distant light (2); the ambient lights sum.
    LightDesc distant;
    distant.kind = LightDesc::Kind::Distant;
    distant.from = {0, 0, 5};
    distant.to = {1, 0, 5};
    distant.intensity = 0.5;
    distant.color = {1, 0.5, 0.25};
    const std::vector<LightDesc> lights = {Ambient(0.1), Point({0, 3, 4}, 25), Spot(), Ambient(0.2), distant};
    CountingOcclusion occlusion;
    occlusion.through = {0.5, 0.25, 1};
    const ShadowTest shadow = occlusion.Test();
    ShadingLights q;
    q.Reset(lights, glm::dvec3(0.0), &shadow);
    auto L = [&](int slot) {
        return glm::dvec3(q.Light(slot, 0, false), q.Light(slot, 1, false), q.Light(slot, 2, false));
    };
    auto Cl = [&](int slot, bool shadowed) {
        return glm::dvec3(q.Light(slot, 3, shadowed), q.Light(slot, 4, shadowed), q.Light(slot, 5, shadowed));
    };
    CHECK(Cl(affray::vm::kAmbientSlot, true) == glm::dvec3(0.1 + 0.2));
    CHECK(L(affray::vm::kAmbientSlot) == glm::dvec3(0.0));
    // The point light: from P to the light, its colour falling off with the squared distance (5).
    CHECK(L(0) == glm::dvec3(0, 3, 4));
    CHECK(Cl(0, false) == glm::dvec3(1.0));
    CHECK(occlusion.calls == 0);
    // With its shadow: one shadow ray, however often the colour is asked.
    CHECK(Cl(0, true) == glm::dvec3(0.5, 0.25, 1));
    CHECK(Cl(0, true) == glm::dvec3(0.5, 0.25, 1));
    CHECK(occlusion.calls == 1);
    // The spotlight straight above: its whole beam (4 / 2^2), L up to it.
    CHECK(L(1) == glm::dvec3(0, 0, 2));
    CHECK(Cl(1, false).x == Approx(1.0));
    // The distant light: the unit direction towards it, no fall-off.
    CHECK(L(2) == glm::dvec3(-1, 0, 0));
    CHECK(Cl(2, false) == 0.5 * distant.color);
    // A light that casts no shadows traces none.
    CHECK(Cl(2, true) == 0.5 * distant.color);
    CHECK(occlusion.calls == 1);
    // Outside the spot's cone the colour is 0 and no shadow ray is traced for it.
    q.Reset(lights, glm::dvec3(3, 0, 0), &shadow);
    CHECK(Cl(1, true) == glm::dvec3(0.0));
    CHECK(occlusion.calls == 1);
    // Slots past the set, and unknown components, are dark.
    CHECK(q.Light(3, 3, true) == 0.0);
    CHECK(q.Light(0, 6, true) == 0.0);
}

TEST_CASE("ShadingLights: the standard lights as light shaders give the built-in lights' L and Cl", "[shade][light]") {
    // The .sl versions in shaders/, compiled for each light's parameters, against the built-in
    // models of the same LightDesc, at points around them.
    auto withShader = [](LightDesc light, const std::string& name,
                         const std::vector<affray::compiler::ParamOverride>& params) {
        affray::compiler::CompileResult r =
            affray::compiler::CompileFile(std::string(AFFRAY_SOURCE_DIR) + "/shaders/" + name + ".sl", params);
        INFO(r.diagnostics.format());
        REQUIRE(r.ok());
        light.shader = affray::renderer::ShaderRef{name, {}, 0, 0, {}, glm::dmat4(1.0)};
        light.program = r.shader;
        return light;
    };
    auto v = [](const glm::dvec3& x) { return std::vector<double>{x.x, x.y, x.z}; };
    const LightDesc point = Point({1, 2, 3}, 5);
    const LightDesc spot = Spot(6);
    LightDesc distant;
    distant.kind = LightDesc::Kind::Distant;
    distant.from = {1, 1, 1};
    distant.to = {0, 0, -1};
    distant.color = {1, 0.5, 0.25};
    const std::vector<LightDesc> builtIn = {Ambient(0.25), point, spot, distant};
    const std::vector<LightDesc> shaders = {
        withShader(Ambient(0.25), "ambientlight", {{"intensity", {0.25}}}),
        withShader(point, "pointlight", {{"from", v(point.from)}, {"intensity", {5}}}),
        withShader(spot, "spotlight",
                   {{"from", v(spot.from)},
                    {"to", v(spot.to)},
                    {"intensity", {6}},
                    {"coneangle", {spot.coneAngle}},
                    {"conedeltaangle", {spot.coneDeltaAngle}},
                    {"beamdistribution", {spot.beamDistribution}}}),
        withShader(distant, "distantlight",
                   {{"from", v(distant.from)}, {"to", v(distant.to)}, {"lightcolor", v(distant.color)}})};
    const ShadowTest shadow = [](const glm::dvec3&, double) { return glm::dvec3(1.0); };
    ShadingLights a, b;
    int compared = 0;
    for (const glm::dvec3& P :
         {glm::dvec3(0.0), glm::dvec3(0.2, -0.1, 0.3), glm::dvec3(3, 0, 0), glm::dvec3(-1, 4, -2)}) {
        a.Reset(builtIn, P, &shadow);
        b.Reset(shaders, P, &shadow);
        for (int slot : {0, 1, 2, affray::vm::kAmbientSlot})
            for (int component = 0; component < 6; ++component) {
                INFO("P " << P.x << " " << P.y << " " << P.z << ", slot " << slot << ", component " << component);
                CHECK(b.Light(slot, component, true) == Approx(a.Light(slot, component, true)).margin(1e-12));
                ++compared;
            }
    }
    CHECK(compared == 4 * 4 * 6);
}
