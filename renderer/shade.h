// renderer/shade.h: RenderMan's built-in surface models and light sources, at one hit point.
#pragma once

#include <functional>
#include <vector>

#include <glm/glm.hpp>

#include "scene/scene.h"
#include "vm/lights.h"

namespace affray::renderer {

/// A point to shade, in world space.
struct ShadingPoint {
    glm::dvec3 P;   // the displaced surface point
    glm::dvec3 Nf;  // unit shading normal, facing the viewer
    glm::dvec3 V;   // unit vector from P towards the viewer
};

/// The part of a light's colour that gets through the segment from the shading point towards
/// the light, per component: 1 where nothing is in the way, 0 behind an opaque occluder, between
/// behind partly transparent ones. `toLight` is a unit vector and `distance` the distance to the
/// light (infinite for distant lights).
using ShadowTest = std::function<glm::dvec3(const glm::dvec3& toLight, double distance)>;

/// The colour of `sp` under `lights` for the surface model `surface` with colour Cs, following the
/// RenderMan shaders of RI Spec 3.2 appendix A:
///   constant  Cs (no lights, so `shadow` is never called)
///   matte     Cs * (Ka*ambient() + Kd*diffuse(Nf))
///   metal     Cs * (Ka*ambient() + Ks*specular(Nf, V, roughness))
///   plastic   Cs * (Ka*ambient() + Kd*diffuse(Nf)) + specularcolor * Ks*specular(Nf, V, roughness)
/// specular() sums Cl * max(0, Nf.H)^(1/roughness) over the lights in front (none if roughness <= 0).
/// Lights: ambientlight (intensity*lightcolor, unshadowed), distantlight (from -> to), pointlight
/// (intensity*lightcolor / distance^2) and spotlight (the pointlight's colour times
/// smoothstep(cos(coneangle), cos(coneangle - conedeltaangle), cosangle) * cosangle^beamdistribution,
/// cosangle the cosine between from -> P and from -> to; nothing outside the cone).
/// Shadows: a light that casts them (LightDesc::castShadows; RenderMan's standard lights do not)
/// is scaled by what `shadow` lets through. `shadow` is asked only about such lights that would
/// add something: in front of the surface and with a nonzero contribution to a term the model
/// uses. The result is the colour Ci before RenderMan's final Ci *= Os (the caller composites).
glm::dvec3 ShadeSurface(const SurfaceDesc& surface, const glm::dvec3& Cs, const ShadingPoint& sp,
                        const std::vector<LightDesc>& lights, const ShadowTest& shadow);

/// What a surface shader's light loops ask at one shading point (vm/lights.h), from the same
/// lights as ShadeSurface: slot k is the k-th light of the set that is not ambient, the ambient
/// slot the sum of the ambient lights. L is the vector from P to the light (a distant light's
/// unit direction towards it); Cl the light's colour arriving at P, as ShadeSurface takes it (0
/// outside a spotlight's cone or at the light), times what `shadow` lets through when the
/// shader wants the light's shadow, the light casts shadows and its colour is not 0. Each light
/// is computed once per point, its shadow ray traced at most once, when first wanted. Reset for
/// each point; kept per thread (no allocation once it has seen the largest light set).
class ShadingLights final : public vm::LightQueries {
  public:
    void Reset(const std::vector<LightDesc>& lights, const glm::dvec3& P, const ShadowTest* shadow);
    double Light(int slot, int component, bool shadowed) override;

  private:
    struct Slot {
        const LightDesc* light = nullptr;
        bool computed = false, shadowTraced = false;
        glm::dvec3 L{0.0}, Cl{0.0}, shadowedCl{0.0};
        double distance = 0;
    };
    void Compute(Slot& slot) const;
    std::vector<Slot> m_slots;
    glm::dvec3 m_ambient{0.0};
    glm::dvec3 m_P{0.0};
    const ShadowTest* m_shadow = nullptr;
};

}  // namespace affray::renderer
