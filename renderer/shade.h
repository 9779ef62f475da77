// renderer/shade.h: RenderMan's built-in surface models and light sources, at one hit point.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "scene/scene.h"
#include "vm/interpreter.h"
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
/// Lights that run a light shader (LightDesc::program) are asked of `shaders` (reset for this
/// point and these lights), and left out without it; a light shader affray did not find gives
/// no light.
class ShadingLights;
glm::dvec3 ShadeSurface(const SurfaceDesc& surface, const glm::dvec3& Cs, const ShadingPoint& sp,
                        const std::vector<LightDesc>& lights, const ShadowTest& shadow,
                        ShadingLights* shaders = nullptr);

/// How a light takes part in shading: not at all (a light shader affray did not find, with no
/// standard light of its name), as an ambient light (ambient() sums it: an "ambientlight", or a
/// light shader with neither illuminate nor solar), or as a light that light loops visit.
enum class LightRole { None, Ambient, Lit };
LightRole RoleOf(const LightDesc& light);
/// The light's categories (its `__category`): its shader's value if a shader renders it, else
/// the RIB's.
std::string CategoryOf(const LightDesc& light);

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
    ShadingLights();
    ~ShadingLights() override;
    ShadingLights(const ShadingLights&) = delete;
    ShadingLights& operator=(const ShadingLights&) = delete;
    /// A light that runs a light shader (LightDesc::program) is that program at P seen from
    /// `eye` (the global Ps, E): its Cl, and L reversed (the program's runs from the light).
    /// `trace` answers trace() (the colour seen along a direction), or null: black.
    using TraceFunction = std::function<glm::dvec3(const glm::dvec3& direction)>;
    void Reset(const std::vector<LightDesc>& lights, const glm::dvec3& P, const ShadowTest* shadow,
               const glm::dvec3& eye = glm::dvec3(0.0), const TraceFunction* trace = nullptr);
    double Light(int slot, int component, bool shadowed) override;
    /// The colour `trace` gives along `direction`, traced once for its three channels.
    double Trace(const double direction[3], int channel) override;

  private:
    struct Slot {
        const LightDesc* light = nullptr;
        bool computed = false, shadowTraced = false;
        glm::dvec3 L{0.0}, Cl{0.0}, shadowedCl{0.0};
        double distance = 0;
    };
    void Compute(Slot& slot);
    /// Runs `light`'s program at the point: its Cl, its L (from the light) and whether it lit.
    void RunLight(const LightDesc& light, glm::dvec3* Cl, glm::dvec3* L, bool* lit);
    std::vector<Slot> m_slots;
    std::vector<const LightDesc*> m_ambientLights;
    glm::dvec3 m_ambient{0.0};
    bool m_ambientComputed = false;
    glm::dvec3 m_P{0.0}, m_eye{0.0};
    const ShadowTest* m_shadow = nullptr;
    const TraceFunction* m_trace = nullptr;
    glm::dvec3 m_traced{0.0}, m_tracedColor{0.0};  // the last direction traced, and what it saw
    bool m_hasTraced = false;
    std::unique_ptr<vm::Interpreter<double>> m_interpreter;  // the light programs', made once
};

}  // namespace affray::renderer
