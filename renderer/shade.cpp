// renderer/shade.cpp: ambient, diffuse and specular sums over the lights, with shadows, for the
// surface and light shaders of RI Spec 3.2 appendix A. A new light kind goes in Illuminate, a new
// surface model in the final switch of ShadeSurface (and in the terms it asks for).
#include "renderer/shade.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include "compiler/compile.h"

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
                        const std::vector<LightDesc>& lights, const ShadowTest& shadow, ShadingLights* shaders) {
    using Model = SurfaceDesc::Model;
    if (surface.model == Model::Constant) return Cs;  // no lights, so no shadow rays either
    // The terms the model uses; the others are neither summed nor worth a shadow ray.
    const bool wantsDiffuse = surface.model != Model::Metal;
    const bool wantsSpecular = surface.model != Model::Matte && surface.roughness > 0;

    glm::dvec3 ambient(0.0), diffuse(0.0), specular(0.0);
    int slot = -1;  // the light's slot in `shaders`, for lights that run a light shader
    for (const LightDesc& light : lights) {
        const LightRole role = RoleOf(light);
        if (role == LightRole::None) continue;
        if (role == LightRole::Lit) ++slot;
        if (light.program && !shaders) continue;
        if (role == LightRole::Ambient) {
            if (!light.program) ambient += light.intensity * light.color;
            continue;
        }
        std::optional<Incident> in;
        if (light.program) {
            auto query = [&](int first, bool shadowed) {
                return glm::dvec3(shaders->Light(slot, first, shadowed), shaders->Light(slot, first + 1, shadowed),
                                  shaders->Light(slot, first + 2, shadowed));
            };
            const glm::dvec3 toLight = query(0, false);
            const glm::dvec3 Cl = query(3, false);
            const double length = glm::length(toLight);
            if (!(length > 0) || Cl == glm::dvec3(0.0)) continue;
            const bool solar = light.program->emission == compiler::LoweredShader::Emission::Solar;
            in = Incident{Cl, toLight / length, solar ? INFINITY : length};
            const double cosine = glm::dot(sp.Nf, in->L);
            if (cosine <= 0) continue;
            // Its shadow, as the light shader's slot traces it (once per point).
            const glm::dvec3 shadowed = light.castShadows ? query(3, true) : Cl;
            if (wantsDiffuse) diffuse += shadowed * cosine;
            if (wantsSpecular) specular += shadowed * SpecularWeight(sp.Nf, in->L, sp.V, surface.roughness);
            continue;
        }
        in = Illuminate(light, sp.P);
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
    // Ambient lights that run a light shader: `shaders` sums every ambient light.
    if (shaders && std::any_of(lights.begin(), lights.end(),
                               [](const LightDesc& l) { return l.program && RoleOf(l) == LightRole::Ambient; }))
        ambient = glm::dvec3(shaders->Light(vm::kAmbientSlot, 3, false), shaders->Light(vm::kAmbientSlot, 4, false),
                             shaders->Light(vm::kAmbientSlot, 5, false));
    switch (surface.model) {
        case Model::Metal: return Cs * (surface.Ka * ambient + surface.Ks * specular);
        case Model::Plastic:
            return Cs * (surface.Ka * ambient + surface.Kd * diffuse) + surface.specularColor * surface.Ks * specular;
        default: return Cs * (surface.Ka * ambient + surface.Kd * diffuse);  // matte
    }
}

LightRole RoleOf(const LightDesc& light) {
    if (light.program)
        return light.program->emission == compiler::LoweredShader::Emission::Ambient ? LightRole::Ambient
                                                                                     : LightRole::Lit;
    if (!light.builtIn) return LightRole::None;
    return light.kind == LightDesc::Kind::Ambient ? LightRole::Ambient : LightRole::Lit;
}

std::string CategoryOf(const LightDesc& light) {
    if (light.program) {
        auto it = light.program->strings.find("__category");
        return it == light.program->strings.end() ? std::string() : it->second;
    }
    return light.category;
}

ShadingLights::ShadingLights() = default;
ShadingLights::~ShadingLights() = default;

void ShadingLights::Reset(const std::vector<LightDesc>& lights, const glm::dvec3& P, const ShadowTest* shadow,
                          const glm::dvec3& eye, const TraceFunction* trace) {
    m_trace = trace;
    m_hasTraced = false;
    m_slots.clear();
    m_ambientLights.clear();
    m_ambientComputed = false;
    m_P = P;
    m_eye = eye;
    m_shadow = shadow;
    for (const LightDesc& light : lights) {
        const LightRole role = RoleOf(light);
        if (role == LightRole::Ambient)
            m_ambientLights.push_back(&light);
        else if (role == LightRole::Lit && m_slots.size() < size_t(vm::kMaxLightSlots))
            m_slots.push_back({&light});
    }
}

void ShadingLights::RunLight(const LightDesc& light, glm::dvec3* Cl, glm::dvec3* L, bool* lit) {
    using vm::Global;
    const vm::Program& program = light.program->light;
    if (!m_interpreter)
        m_interpreter = std::make_unique<vm::Interpreter<double>>(program);
    else if (&m_interpreter->program() != &program)
        m_interpreter->SetProgram(program);
    vm::Interpreter<double>& interp = *m_interpreter;
    auto triple = [](const glm::dvec3& x) { return vm::Vec3<double>(x.x, x.y, x.z); };
    // The light's own surface is a point, the origin of its shader space. A light that moves
    // runs where it stood at the shutter's opening: the point lit is carried there, its L back.
    const bool moving = light.moved != glm::dmat4(1.0);
    const glm::dmat4 back = moving ? glm::inverse(light.moved) : glm::dmat4(1.0);
    const glm::dvec3 Ps = moving ? glm::dvec3(back * glm::dvec4(m_P, 1.0)) : m_P;
    const glm::dvec3 eye = moving ? glm::dvec3(back * glm::dvec4(m_eye, 1.0)) : m_eye;
    const glm::dvec3 origin(light.shader->shaderToWorld * glm::dvec4(0, 0, 0, 1));
    interp.SetGlobal(Global::Ps, triple(Ps));
    interp.SetGlobal(Global::E, triple(eye));
    interp.SetGlobal(Global::P, triple(origin));
    interp.SetGlobal(Global::I, triple(Ps - eye));
    for (Global g : {Global::N, Global::Ng, Global::dPdu, Global::dPdv}) interp.SetGlobal(g, triple(glm::dvec3(0.0)));
    for (Global g : {Global::s, Global::t, Global::u, Global::v, Global::du, Global::dv, Global::time, Global::dtime})
        interp.SetGlobal(g, 0.0);
    interp.Run();
    auto out = [&](const char* name) {
        const vm::Vec3<double> x = interp.OutputTriple(*program.findOutput(name));
        return glm::dvec3(x.x, x.y, x.z);
    };
    *Cl = out("Cl");
    *L = moving ? glm::dvec3(light.moved * glm::dvec4(out("L"), 0.0)) : out("L");
    *lit = interp.Register(program.findOutput("lit")->registers[0]) != 0;
}

void ShadingLights::Compute(Slot& slot) {
    const LightDesc& light = *slot.light;
    slot.computed = true;
    if (light.program) {
        glm::dvec3 Cl, fromLight;
        bool lit = false;
        RunLight(light, &Cl, &fromLight, &lit);
        slot.Cl = lit && std::isfinite(Cl.x + Cl.y + Cl.z) ? Cl : glm::dvec3(0.0);
        if (light.program->emission == compiler::LoweredShader::Emission::Solar) {
            const double length = glm::length(fromLight);
            slot.L = length > 0 && std::isfinite(length) ? -fromLight / length : glm::dvec3(0.0);
            slot.distance = INFINITY;
        } else {
            slot.L = -fromLight;
            slot.distance = glm::length(fromLight);
            // At the light, or past any distance: no light arrives (as Illuminate has it).
            if (!(slot.distance > 0 && std::isfinite(slot.distance))) slot.Cl = glm::dvec3(0.0);
        }
        return;
    }
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

double ShadingLights::Trace(const double direction[3], int channel) {
    if (channel < 0 || channel > 2 || !m_trace) return 0;
    const glm::dvec3 d(direction[0], direction[1], direction[2]);
    if (!m_hasTraced || d != m_traced) {
        m_traced = d;
        m_tracedColor = (*m_trace)(d);
        m_hasTraced = true;
    }
    return m_tracedColor[channel];
}

double ShadingLights::Light(int index, int component, bool shadowed) {
    if (component < 0 || component >= vm::kLightComponents) return 0;
    if (index == vm::kAmbientSlot) {
        if (component < 3) return 0.0;
        if (!m_ambientComputed) {
            m_ambientComputed = true;
            m_ambient = glm::dvec3(0.0);
            for (const LightDesc* light : m_ambientLights) {
                if (!light->program) {
                    m_ambient += light->intensity * light->color;
                    continue;
                }
                glm::dvec3 Cl, L;
                bool lit = false;
                RunLight(*light, &Cl, &L, &lit);
                if (std::isfinite(Cl.x + Cl.y + Cl.z)) m_ambient += Cl;
            }
        }
        return m_ambient[component - 3];
    }
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
