// renderer/shade.cpp: ambient, diffuse and specular sums over the lights, with shadows, for the
// surface and light shaders of RI Spec 3.2 appendix A. A new light kind goes in Illuminate, a new
// surface model in the final switch of ShadeSurface (and in the terms it asks for).
#include "renderer/shade.h"

#include <algorithm>
#include <cmath>
#include <optional>

namespace affray::renderer {

namespace {

/// Light arriving at a point from a non-ambient light: its colour there and where it comes from.
struct Incident {
    glm::dvec3 Cl;    // the light's colour at the point (attenuation applied)
    glm::dvec3 L;     // unit vector from the point towards the light
    double distance;  // to the light; infinite for distant lights
};

/// The shading language's smoothstep: 0 below lo, 1 from hi on, a cubic Hermite in between.
double SmoothStep(double lo, double hi, double x) {
    if (x < lo) return 0;
    if (x >= hi) return 1;
    const double t = (x - lo) / (hi - lo);
    return t * t * (3 - 2 * t);
}

/// How much of a spotlight's beam reaches direction `cosAngle` off its axis (appendix A
/// "spotlight"): smoothstep(cos(coneangle), cos(coneangle - conedeltaangle), cosangle) *
/// cosangle^beamdistribution. Zero outside the cone (illuminate's cone excludes those points).
double SpotFalloff(const LightDesc& light, double cosAngle) {
    const double cosOutside = std::cos(light.coneAngle);
    const double cosInside = std::cos(light.coneAngle - light.coneDeltaAngle);
    if (!(cosAngle > cosOutside)) return 0;
    return SmoothStep(cosOutside, cosInside, cosAngle) * std::pow(cosAngle, light.beamDistribution);
}

/// The light `light` sends to P, or nothing if it cannot reach P (at P, or outside a spot cone).
std::optional<Incident> Illuminate(const LightDesc& light, const glm::dvec3& P) {
    glm::dvec3 Cl = light.intensity * light.color;
    if (light.kind == LightDesc::Kind::Distant) return Incident{Cl, glm::normalize(light.from - light.to), INFINITY};
    const glm::dvec3 toLight = light.from - P;
    const double distance = glm::length(toLight);
    if (!(distance > 0)) return std::nullopt;
    const glm::dvec3 L = toLight / distance;
    Cl /= distance * distance;  // point and spot lights fall off with the squared distance
    if (light.kind == LightDesc::Kind::Spot) {
        const glm::dvec3 axis = glm::normalize(light.to - light.from);
        const double falloff = SpotFalloff(light, glm::dot(-L, axis));
        if (!(falloff > 0)) return std::nullopt;
        Cl *= falloff;
    }
    return Incident{Cl, L, distance};
}

/// RenderMan's specular() weight for one light: (N.H)^(1/roughness), H halfway between L and V.
double SpecularWeight(const glm::dvec3& Nf, const glm::dvec3& L, const glm::dvec3& V, double roughness) {
    const glm::dvec3 H = glm::normalize(L + V);
    return std::pow(std::max(0.0, glm::dot(Nf, H)), 1.0 / roughness);
}

}  // namespace

glm::dvec3 ShadeSurface(const SurfaceDesc& surface, const glm::dvec3& Cs, const ShadingPoint& sp,
                        const std::vector<LightDesc>& lights, const ShadowTest& shadow) {
    using Model = SurfaceDesc::Model;
    if (surface.model == Model::Constant) return Cs;  // no lights, so no shadow rays either
    // The terms the model uses; the others are neither summed nor worth a shadow ray.
    const bool wantsDiffuse = surface.model != Model::Metal;
    const bool wantsSpecular = surface.model != Model::Matte && surface.roughness > 0;

    glm::dvec3 ambient(0.0), diffuse(0.0), specular(0.0);
    for (const LightDesc& light : lights) {
        if (light.kind == LightDesc::Kind::Ambient) {
            ambient += light.intensity * light.color;
            continue;
        }
        const std::optional<Incident> in = Illuminate(light, sp.P);
        if (!in) continue;
        const double cosine = glm::dot(sp.Nf, in->L);
        if (cosine <= 0) continue;  // the light is behind the surface: no need for a shadow ray
        glm::dvec3 d = wantsDiffuse ? in->Cl * cosine : glm::dvec3(0.0);
        glm::dvec3 s = wantsSpecular ? in->Cl * SpecularWeight(sp.Nf, in->L, sp.V, surface.roughness) : glm::dvec3(0.0);
        if (d == glm::dvec3(0.0) && s == glm::dvec3(0.0)) continue;  // adds nothing: skip the shadow ray
        if (light.castShadows) {
            const glm::dvec3 through = shadow(in->L, in->distance);
            if (through == glm::dvec3(0.0)) continue;
            d *= through;  // (exact where nothing is in the way: through is 1)
            s *= through;
        }
        diffuse += d;
        specular += s;
    }
    switch (surface.model) {
        case Model::Metal: return Cs * (surface.Ka * ambient + surface.Ks * specular);
        case Model::Plastic:
            return Cs * (surface.Ka * ambient + surface.Kd * diffuse) + surface.specularColor * surface.Ks * specular;
        default: return Cs * (surface.Ka * ambient + surface.Kd * diffuse);  // matte
    }
}

void ShadingLights::Reset(const std::vector<LightDesc>& lights, const glm::dvec3& P, const ShadowTest* shadow) {
    m_slots.clear();
    m_ambient = glm::dvec3(0.0);
    m_P = P;
    m_shadow = shadow;
    for (const LightDesc& light : lights) {
        if (light.kind == LightDesc::Kind::Ambient)
            m_ambient += light.intensity * light.color;
        else if (m_slots.size() < size_t(vm::kMaxLightSlots))
            m_slots.push_back({&light});
    }
}

void ShadingLights::Compute(Slot& slot) const {
    const LightDesc& light = *slot.light;
    slot.computed = true;
    if (light.kind == LightDesc::Kind::Distant) {
        slot.L = glm::normalize(light.from - light.to);
        slot.distance = INFINITY;
    } else {
        slot.L = light.from - m_P;
        slot.distance = glm::length(slot.L);
    }
    const std::optional<Incident> in = Illuminate(light, m_P);
    slot.Cl = in ? in->Cl : glm::dvec3(0.0);
}

double ShadingLights::Light(int index, int component, bool shadowed) {
    if (component < 0 || component >= vm::kLightComponents) return 0;
    if (index == vm::kAmbientSlot) return component < 3 ? 0.0 : m_ambient[component - 3];
    if (index < 0 || static_cast<size_t>(index) >= m_slots.size()) return 0;  // (a light set smaller than compiled for)
    Slot& slot = m_slots[static_cast<size_t>(index)];
    if (!slot.computed) Compute(slot);
    if (component < 3) return slot.L[component];
    if (!shadowed || !slot.light->castShadows || !m_shadow || slot.Cl == glm::dvec3(0.0)) return slot.Cl[component - 3];
    if (!slot.shadowTraced) {
        slot.shadowTraced = true;
        const glm::dvec3 toLight = std::isfinite(slot.distance) ? slot.L / slot.distance : slot.L;
        slot.shadowedCl = slot.Cl * (*m_shadow)(toLight, slot.distance);
    }
    return slot.shadowedCl[component - 3];
}

}  // namespace affray::renderer
