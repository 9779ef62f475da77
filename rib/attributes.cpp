// rib/attributes.cpp: RIB requests for attributes and lights (Color, TextureCoordinates, Opacity, Surface,
// Displacement, Attribute, Sides, ReverseOrientation, Orientation, Basis, LightSource,
// Illuminate), with the attributes that decide shadows: which lights cast them (the shadow-map
// lights, map names, Attribute "light") and which primitives stop them (Attribute "visibility",
// BMRT's "render"). Rules shared with rib.cpp are in rib/parser.h. Light positions are
// transformed with the CTM current at the request. A new light shader goes in kLightShaders (and
// LightParams if it has new parameters).
#include <algorithm>
#include <cmath>
#include <optional>

#include "rib/parser.h"

namespace affray::rib {

namespace {

// The light shaders affray knows: RI 3.2's standard ones, and the shadow-map versions of them
// that scanline-era scenes use (shadowspot, shadowpoint, shadowdistant), which affray renders
// as the standard light, with traced shadows where they name a map.
struct LightShader {
    std::string_view name;
    LightDesc::Kind kind;
    bool shadowMapped;  // reads shadow maps: its map parameters are accepted and ignored
};
constexpr LightShader kLightShaders[] = {
    {"ambientlight", LightDesc::Kind::Ambient, false}, {"distantlight", LightDesc::Kind::Distant, false},
    {"pointlight", LightDesc::Kind::Point, false},     {"spotlight", LightDesc::Kind::Spot, false},
    {"shadowdistant", LightDesc::Kind::Distant, true}, {"shadowpoint", LightDesc::Kind::Point, true},
    {"shadowspot", LightDesc::Kind::Spot, true},
};

// The parameters through which light shaders read shadow maps (shadowname; shadowpoint's six
// cube faces) and filter them (samples, width, blur, bias...). affray traces its shadows instead.
constexpr std::string_view kShadowMapParams[] = {
    "shadowname", "sfpx",   "sfnx",   "sfpy", "sfny", "sfpz",       "sfnz",       "samples",
    "width",      "swidth", "twidth", "blur", "bias", "shadowbias", "shadowblur", "shadowsamples"};

}  // namespace

bool RibParser::DoColor(const RibRequest& r) {
    double v[3];
    if (!Numbers(r, 3, "r g b", v)) return false;
    m_state.color = glm::dvec3(v[0], v[1], v[2]);
    return true;
}

// TextureCoordinates s1 t1 s2 t2 s3 t3 s4 t4: the s, t of the quadrics and patches that follow
// at their (u,v) corners (0,0), (1,0), (0,1), (1,1), bilinear between (RI 3.2 section 4.3);
// primitives with an "st" of their own keep it.
bool RibParser::DoTextureCoordinates(const RibRequest& r) {
    std::array<double, 8> v;
    if (!Numbers(r, 8, "s1 t1 s2 t2 s3 t3 s4 t4", v.data())) return false;
    static constexpr std::array<double, 8> kDefault = {0, 0, 1, 0, 0, 1, 1, 1};
    m_state.textureCoordinates = v == kDefault ? nullptr : std::make_shared<const std::array<double, 8>>(v);
    return true;
}

// Opacity r g b: the Os of the primitives that follow, each component from 0 (clear) to 1.
bool RibParser::DoOpacity(const RibRequest& r) {
    double v[3];
    if (!Numbers(r, 3, "r g b", v)) return false;
    glm::dvec3 opacity(v[0], v[1], v[2]);
    if (glm::clamp(opacity, 0.0, 1.0) != opacity) {
        Warn(r.at, "'Opacity' components must be from 0 to 1; clamped");
        opacity = glm::clamp(opacity, 0.0, 1.0);
    }
    m_state.opacity = opacity;
    return true;
}

bool RibParser::DoAttribute(const RibRequest& r) {
    std::string name;
    std::vector<RibParam> params;
    if (!LeadingString(r, "an attribute name", &name) || !ParamList(r, 1, &params)) return false;
    // Every value is kept for conditional RIB ($category:name), which is what "user" is for; the
    // map is shared by the blocks that saved it, so it is copied to change.
    if (!params.empty()) {
        auto attributes = m_state.attributes ? std::make_shared<std::map<std::string, ParamValue>>(*m_state.attributes)
                                             : std::make_shared<std::map<std::string, ParamValue>>();
        for (const RibParam& p : params) (*attributes)[name + ":" + p.value.name] = p.value;
        m_state.attributes = std::move(attributes);
    }
    // The intersector bounds displaced surfaces exactly, so no user bound is needed.
    if (name == "trimcurve") {
        // Attribute "trimcurve" "sense" "inside"|"outside": which side of the trim loops NuPatches keep.
        for (const RibParam& p : params) {
            if (p.value.name != "sense" || p.value.strings.size() != 1 ||
                (p.value.strings[0] != "inside" && p.value.strings[0] != "outside"))
                return Fail(p.at, "'Attribute \"trimcurve\"' takes \"sense\" \"inside\" or \"outside\"");
            m_state.trimKeepInside = p.value.strings[0] == "inside";
        }
        return true;
    }
    if (name == "user") return true;
    if (name == "Ri") return RiAttributes(params);
    if (name == "light") return LightAttribute(params);
    if (name == "visibility" || name == "render") return VisibilityAttribute(name, params);
    if (name == "displacementbound")
        Warn(r.at,
             "'Attribute \"displacementbound\"' is not needed: affray bounds displacement "
             "exactly; ignored");
    else
        Warn(r.at, "'Attribute \"" + name + "\"' does not apply to affray; ignored");
    return true;
}

// Attribute "light" "shadows" "on"|"off" (BMRT, and Houdini's exports): whether the lights
// declared from now on, until the end of the attribute block, trace shadows.
bool RibParser::LightAttribute(const std::vector<RibParam>& params) {
    for (const RibParam& p : params) {
        const ParamValue& v = p.value;
        if (v.name != "shadows") {
            Warn(p.at, "'Attribute \"light\"' parameter " + Quote(v.name) + " does not apply to affray; ignored");
        } else if (v.strings.size() == 1 && (v.strings[0] == "on" || v.strings[0] == "off")) {
            m_state.lightShadows = v.strings[0] == "on";
        } else {
            Warn(p.at, "'Attribute \"light\" \"shadows\"' takes \"on\" or \"off\", got " +
                           (v.strings.empty() ? "numbers" : "\"" + v.strings[0] + "\"") + "; ignored");
        }
    }
    return true;
}

// Which rays see the primitives that follow: Attribute "visibility" "transmission" (prman 11:
// "opaque", "Os", "shader" or "transparent"; later prman: 1 or 0, the opacity then from the
// shader, Os here) and "camera" 0|1; BMRT's Attribute "render" "casts_shadows" ("none",
// "opaque", "Os", "shade") and "visibility" (bits: 1 camera rays, 4 shadow rays).
bool RibParser::VisibilityAttribute(const std::string& name, const std::vector<RibParam>& params) {
    using Transmission = PrimitiveDesc::Transmission;
    const std::string context = "'Attribute \"" + name + "\"'";
    const bool prman = name == "visibility";
    for (const RibParam& p : params) {
        const ParamValue& v = p.value;
        const std::string* word = v.strings.size() == 1 ? &v.strings[0] : nullptr;
        const double* number = v.numbers.size() == 1 ? &v.numbers[0] : nullptr;
        const std::string what = "'Attribute \"" + name + "\" \"" + v.name + "\"'";
        auto bad = [&](const std::string& expected) {
            Warn(p.at, what + " takes " + expected + ", got " +
                           (word     ? "\"" + *word + "\""
                            : number ? FormatNumber(*number)
                                     : "a list") +
                           "; ignored");
        };
        if (prman && v.name == "transmission") {
            if (word && *word == "opaque")
                m_state.transmission = Transmission::Opaque;
            else if (word && (*word == "Os" || *word == "shader"))
                m_state.transmission = Transmission::Opacity;
            else if (word && *word == "transparent")
                m_state.transmission = Transmission::Transparent;
            else if (number && (*number == 0 || *number == 1))
                m_state.transmission = *number == 1 ? Transmission::Opacity : Transmission::Transparent;
            else
                bad("\"opaque\", \"Os\", \"shader\", \"transparent\", 1 or 0");
        } else if (prman && v.name == "camera") {
            if (number && (*number == 0 || *number == 1))
                m_state.cameraVisible = *number == 1;
            else
                bad("1 or 0");
        } else if (!prman && v.name == "casts_shadows") {
            if (word && *word == "none")
                m_state.transmission = Transmission::Transparent;
            else if (word && *word == "opaque")
                m_state.transmission = Transmission::Opaque;
            else if (word && (*word == "Os" || *word == "shade"))
                m_state.transmission = Transmission::Opacity;
            else
                bad("\"none\", \"opaque\", \"Os\" or \"shade\"");
        } else if (!prman && v.name == "visibility") {
            if (number && *number >= 0 && *number <= 7 && *number == std::floor(*number)) {
                const int bits = static_cast<int>(*number);
                m_state.cameraVisible = (bits & 1) != 0;
                if (!(bits & 4))
                    m_state.transmission = Transmission::Transparent;
                else if (m_state.transmission == Transmission::Transparent)
                    m_state.transmission = Transmission::Opaque;
            } else {
                bad("a sum of 1 (camera), 2 (reflection) and 4 (shadow rays)");
            }
        } else {
            Warn(p.at, context + " parameter " + Quote(v.name) + " does not apply to affray; ignored");
        }
    }
    return true;
}

// Basis ubasis ustep vbasis vstep: each basis a predefined name or 16 numbers (row-major, as
// RiBasis takes them), each step a positive integer (the control points between a patch mesh's
// patches). Attribute state: AttributeEnd restores the bases of its AttributeBegin.
bool RibParser::DoBasis(const RibRequest& r) {
    if (r.args.size() != 4)
        return Fail(r.at,
                    "'Basis' expects 4 arguments (ubasis ustep vbasis vstep), got " + std::to_string(r.args.size()));
    CubicBasis bases[2];
    for (size_t axis = 0; axis < 2; ++axis) {
        const RibArg& basis = r.args[2 * axis];
        const RibArg& step = r.args[2 * axis + 1];
        const std::string which = axis == 0 ? "u" : "v";
        if (!basis.isArray && basis.StringsP()) {
            std::optional<CubicBasis> named = CubicBasis::Named(basis.strings[0]);
            if (!named)
                return Fail(basis.at, "'Basis': unknown " + which + " basis " + Quote(basis.strings[0]) +
                                          " (expected " + CubicBasis::NameList() + ", or 16 numbers)");
            bases[axis] = *named;
        } else if (basis.isArray && basis.NumericP() && basis.numbers.size() == 16) {
            for (int i = 0; i < 16; ++i) {
                if (!std::isfinite(basis.numbers[i]))
                    return Fail(basis.at, "'Basis': the " + which + " basis matrix must be finite");
                bases[axis].m[i] = basis.numbers[i];
            }
        } else {
            return Fail(basis.at, "'Basis': the " + which + " basis must be a name (" + CubicBasis::NameList() +
                                      ") or an array of 16 numbers, got " + basis.Describe());
        }
        if (step.isArray || !step.NumericP() || step.numbers.size() != 1 || !(step.numbers[0] >= 1) ||
            step.numbers[0] != std::floor(step.numbers[0]) || step.numbers[0] > 1e6)
            return Fail(step.at, "'Basis': the " + which + " step must be a positive integer, got " + step.Describe());
        bases[axis].step = static_cast<int>(step.numbers[0]);
    }
    m_state.uBasis = bases[0];
    m_state.vBasis = bases[1];
    return true;
}

bool RibParser::DoSides(const RibRequest& r) {
    double sides;
    if (!Numbers(r, 1, "sides", &sides)) return false;
    if (sides != 1 && sides != 2) return Fail(r.at, "'Sides' must be 1 or 2, got " + FormatNumber(sides));
    m_state.twoSided = sides == 2;
    return true;
}

bool RibParser::DoReverseOrientation(const RibRequest& r) {
    if (!NoArgs(r)) return false;
    m_state.insideOut = !m_state.insideOut;
    return true;
}

bool RibParser::DoOrientation(const RibRequest& r) {
    std::string name;
    if (!LeadingString(r, "an orientation", &name)) return false;
    if (r.args.size() > 1) return Fail(r.at, "'Orientation' expects one string");
    // "outside" and "inside" are relative to the handedness of the current coordinate system;
    // "lh" and "rh" are absolute, so they are inside out where the system has the other one.
    if (name == "lh")
        m_state.insideOut = RightHandedP();
    else if (name == "rh")
        m_state.insideOut = !RightHandedP();
    else if (name == "outside")
        m_state.insideOut = false;
    else if (name == "inside")
        m_state.insideOut = true;
    else
        return Fail(r.args[0].at,
                    "unknown orientation " + Quote(name) + " (expected \"outside\", \"inside\", \"lh\" or \"rh\")");
    return true;
}

// The built-in surfaces of RI 3.2 appendix A, and the shader the request names, which a scene
// renders with when it is found (renderer/prepare.cpp); an unknown name not found falls back to
// plastic.
bool RibParser::DoSurface(const RibRequest& r) {
    std::string name;
    std::vector<RibParam> params;
    if (!LeadingString(r, "a surface shader name", &name)) return false;
    // The parameters of a shader affray may not find are checked by its compiler, if found.
    const bool known = name == "matte" || name == "metal" || name == "constant" || name == "plastic";
    if (!ParamList(r, 1, &params, known)) return false;
    SurfaceDesc surface;  // plastic defaults
    // The shader itself, looked for on the search path when the scene is prepared.
    ShaderRef shader;
    shader.name = name;
    shader.file = FileOf(r.at);
    shader.line = r.at.line;
    shader.column = r.at.column;
    shader.shaderToWorld = m_state.ctm;
    for (const RibParam& p : params) shader.params.push_back(p.value);
    if (!name.empty()) surface.shader = std::move(shader);
    using Model = SurfaceDesc::Model;
    if (name == "matte") {
        surface.model = Model::Matte;
        surface.Kd = 1;  // RI 3.2 matte: Ka = 1, Kd = 1
        surface.Ks = 0;
    } else if (name == "metal") {
        surface.model = Model::Metal;
        surface.Kd = 0;  // RI 3.2 metal: Ka = 1, Ks = 1, roughness = 0.1, no diffuse term
        surface.Ks = 1;
    } else if (name == "constant") {
        surface.model = Model::Constant;  // Cs alone: no lighting terms
        surface.Kd = 0;
        surface.Ks = 0;
    } else if (name != "plastic") {
        m_state.surface = surface;  // plastic unless the shader is found (renderer/prepare.cpp)
        return true;
    }
    const std::string context = "'Surface \"" + name + "\"'";
    const Model model = surface.model;
    const bool lit = model != Model::Constant;
    const bool diffuse = model == Model::Matte || model == Model::Plastic;
    const bool specular = model == Model::Metal || model == Model::Plastic;
    for (const RibParam& p : params) {
        const std::string& n = p.value.name;
        bool ok = true;
        if (n == "Ka" && lit)
            ok = ParamNumbers(p, context, 1, &surface.Ka);
        else if (n == "Kd" && diffuse)
            ok = ParamNumbers(p, context, 1, &surface.Kd);
        else if (n == "Ks" && specular)
            ok = ParamNumbers(p, context, 1, &surface.Ks);
        else if (n == "roughness" && specular)
            ok = ParamNumbers(p, context, 1, &surface.roughness);
        else if (n == "specularcolor" && model == Model::Plastic)
            ok = ParamVector(p, context, &surface.specularColor);
        else
            Warn(p.at, context + " has no parameter " + Quote(n) + "; ignored");
        if (!ok) return false;
    }
    if (!(surface.roughness > 0))  // the highlight exponent is 1 / roughness
        return Fail(r.at, context + " roughness must be positive, got " + FormatNumber(surface.roughness));
    m_state.surface = surface;
    return true;
}

bool RibParser::DoDisplacement(const RibRequest& r) {
    ShaderRef shader;
    std::vector<RibParam> params;
    if (!LeadingString(r, "a displacement shader name", &shader.name) || !ParamList(r, 1, &params)) return false;
    if (shader.name.empty()) {  // Displacement "" removes the shader
        m_state.displacement.reset();
        return true;
    }
    shader.file = FileOf(r.at);
    shader.line = r.at.line;
    shader.column = r.at.column;
    shader.shaderToWorld = m_state.ctm;
    for (RibParam& p : params) shader.params.push_back(std::move(p.value));
    m_state.displacement = std::move(shader);
    return true;
}

// Atmosphere: RI 3.2's standard volume shaders "fog" (distance, background) and "depthcue"
// (mindistance, maxdistance, background), an attribute of the primitives that follow; "" or
// "null" removes it. Another atmosphere shader is warned about and ignored (the primitives keep
// the one in effect).
bool RibParser::DoAtmosphere(const RibRequest& r) {
    std::string name;
    std::vector<RibParam> params;
    if (!LeadingString(r, "an atmosphere shader name", &name)) return false;
    const bool known = name == "fog" || name == "depthcue";
    if (!ParamList(r, 1, &params, known)) return false;
    if (name.empty() || name == "null") {
        m_state.atmosphere.reset();
        return true;
    }
    if (!known) {
        Warn(r.at, "atmosphere shader " + Quote(name) + " is not supported (only \"fog\" and \"depthcue\"); ignored");
        return true;
    }
    using Kind = renderer::AtmosphereDesc::Kind;
    renderer::AtmosphereDesc atmosphere;
    atmosphere.kind = name == "fog" ? Kind::Fog : Kind::DepthCue;
    const std::string context = "'Atmosphere \"" + name + "\"'";
    for (const RibParam& p : params) {
        const std::string& n = p.value.name;
        bool ok = true;
        if (n == "background")
            ok = ParamVector(p, context, &atmosphere.background);
        else if (n == "distance" && atmosphere.kind == Kind::Fog)
            ok = ParamNumbers(p, context, 1, &atmosphere.distance);
        else if (n == "mindistance" && atmosphere.kind == Kind::DepthCue)
            ok = ParamNumbers(p, context, 1, &atmosphere.minDistance);
        else if (n == "maxdistance" && atmosphere.kind == Kind::DepthCue)
            ok = ParamNumbers(p, context, 1, &atmosphere.maxDistance);
        else
            Warn(p.at, context + " has no parameter " + Quote(n) + "; ignored");
        if (!ok) return false;
    }
    if (atmosphere.kind == Kind::Fog && !(atmosphere.distance > 0))
        return Fail(r.at, context + " distance must be positive, got " + FormatNumber(atmosphere.distance));
    if (atmosphere.kind == Kind::DepthCue && !(atmosphere.minDistance < atmosphere.maxDistance))
        return Fail(r.at, context + " needs mindistance < maxdistance, got " + FormatNumber(atmosphere.minDistance) +
                              " " + FormatNumber(atmosphere.maxDistance));
    m_state.atmosphere = atmosphere;
    return true;
}

bool RibParser::DoLightSource(const RibRequest& r) {
    std::string name;
    if (!LeadingString(r, "a light shader name", &name)) return false;
    if (r.args.size() < 2 || r.args[1].isArray)
        return Fail(r.at, "'LightSource' expects a light handle (a number or a string) after the shader name");
    const LightShader* shader = nullptr;
    for (const LightShader& known : kLightShaders)
        if (known.name == name) shader = &known;
    std::vector<RibParam> params;  // those of a light affray does not have are unchecked
    if (!ParamList(r, 2, &params, shader != nullptr)) return false;
    if (m_worldEnded) return Fail(r.at, "'LightSource' after 'WorldEnd'");
    // A light in the world moves with a moving transform (LightDesc::motion); one given before
    // WorldBegin, in camera space, is placed once the camera is known, at its first time.
    if (!m_worldSeen) WarnIfMoving(r, "lights given before 'WorldBegin'");

    LightDesc light;
    light.line = r.at.line;
    const RibArg& handle = r.args[1];
    light.handle = handle.StringsP() ? handle.strings[0] : FormatNumber(handle.numbers[0]);
    // The shader itself, looked for on the search path when the scene is prepared: it renders
    // the light where found (renderer/prepare.cpp).
    ShaderRef ref;
    ref.name = name;
    ref.file = FileOf(r.at);
    ref.line = r.at.line;
    ref.column = r.at.column;
    ref.shaderToWorld = m_state.ctm;  // before WorldBegin camera space, mapped at WorldBegin
    for (const RibParam& p : params) ref.params.push_back(p.value);
    light.shader = std::move(ref);
    if (!shader) {
        // Another light shader: only its .sl can render it. Its shadows: as a standard light's
        // (a shadow map name given, or the attribute).
        light.builtIn = false;
        for (const RibParam& p : params)
            if ((p.value.name == "shadowname" || p.value.name == "shadowmap") && p.value.strings.size() == 1 &&
                !p.value.strings[0].empty())
                light.castShadows = true;
        light.castShadows = light.castShadows || m_state.lightShadows;
        if (m_worldSeen) light.motion = m_state.motion;
        return AddLight(light);
    }
    light.kind = shader->kind;
    const std::string standard = shader->kind == LightDesc::Kind::Distant ? "distantlight"
                                 : shader->kind == LightDesc::Kind::Point ? "pointlight"
                                                                          : "spotlight";
    const std::string context = "'LightSource \"" + name + "\"'";
    // Shadows: a light's given a map name that is not empty (a shadow-map light's default names
    // are empty, "" in RenderMan's shaders: it then reads no map and shadow() gives 0), or the
    // attribute's.
    light.castShadows = false;
    if (!LightParams(context, params, shader->shadowMapped, &light)) return false;
    if (shader->shadowMapped)
        Note(r.at, "light source " + Quote(name) + " renders as " + Quote(standard) +
                       (light.castShadows ? " with traced shadows" : " without shadows (it names no shadow map)") +
                       "; its shadow map parameters (shadowname, samples, width, blur, bias, ...) are ignored");
    light.castShadows = light.castShadows || m_state.lightShadows;
    if (light.kind == LightDesc::Kind::Spot && !CheckSpotlight(r, context, light)) return false;
    // from/to are points in the current space; before WorldBegin that is camera space, which is
    // mapped to world space once the camera transform is known.
    if (!m_worldSeen && !NoPendingPerspective(r)) return false;
    light.from = TransformPoint(m_state.ctm, light.from);
    light.to = TransformPoint(m_state.ctm, light.to);
    if (m_worldSeen) light.motion = m_state.motion;
    bool aimed = light.kind == LightDesc::Kind::Distant || light.kind == LightDesc::Kind::Spot;
    if (aimed && light.from == light.to) return Fail(r.at, context + " 'from' and 'to' must differ");
    return AddLight(light);
}

bool RibParser::AddLight(const LightDesc& light) {
    // Its index: lights given before WorldBegin come first in the frame's list (DoWorldBegin).
    const int index = static_cast<int>(m_scene.lights.size() + m_cameraLights.size());
    if (m_worldSeen)
        m_scene.lights.push_back(light);
    else
        m_cameraLights.push_back(light);
    m_lightHandles[light.handle] = index;
    m_state.lights.push_back(index);  // on from its declaration, in the current attribute block
    return true;
}

// Illuminate handle on|off: turns the light on or off in the current attributes, so for the
// primitives that follow until the enclosing AttributeEnd restores the list (RI 3.2).
bool RibParser::DoIlluminate(const RibRequest& r) {
    if (r.args.size() != 2 || r.args[0].isArray || r.args[1].isArray || !r.args[1].NumericP())
        return Fail(r.at, "'Illuminate' expects a light handle and 0 or 1");
    const RibArg& handle = r.args[0];
    const std::string name = handle.StringsP() ? handle.strings[0] : FormatNumber(handle.numbers[0]);
    const double on = r.args[1].numbers[0];
    if (on != 0 && on != 1) return Fail(r.args[1].at, "'Illuminate' expects 0 or 1, got " + FormatNumber(on));
    auto it = m_lightHandles.find(name);
    if (it == m_lightHandles.end()) {
        Warn(r.args[0].at, "'Illuminate': no light source has the handle " + Quote(name) + "; ignored");
        return true;
    }
    if (it->second < 0) return true;  // a light shader affray skipped
    std::vector<int>& lights = m_state.lights;
    auto at = std::lower_bound(lights.begin(), lights.end(), it->second);
    const bool isOn = at != lights.end() && *at == it->second;
    if (on == 1 && !isOn) lights.insert(at, it->second);
    if (on == 0 && isOn) lights.erase(at);
    return true;
}

// The parameters of the RI 3.2 light shaders; each light takes only its own.
// A shadow-map light shader, or a standard one given "shadowname" (some renderers' standard lights
// read one), takes its map parameters, which are ignored with one note. The map names decide
// light->castShadows: any name ("raytrace", which asks for traced shadows, or a file) turns them
// on; names that are all empty (RenderMan's default: no map) turn them off.
bool RibParser::LightParams(const std::string& context, const std::vector<RibParam>& params, bool shadowMapped,
                            LightDesc* light) {
    using Kind = LightDesc::Kind;
    const bool spot = light->kind == Kind::Spot;
    std::optional<bool> named;  // a map name given: is one of them not empty?
    for (const RibParam& p : params) {
        const std::string& n = p.value.name;
        const bool mapParam =
            std::find(std::begin(kShadowMapParams), std::end(kShadowMapParams), n) != std::end(kShadowMapParams);
        // shadowname, or shadowpoint's six faces sfpx ... sfnz.
        const bool mapName = n == "shadowname" || (shadowMapped && mapParam && n.size() == 4 && n.rfind("sf", 0) == 0);
        const std::string file = p.value.strings.size() == 1 ? p.value.strings[0] : "";
        if (mapName && p.value.strings.size() == 1) named = named.value_or(false) || !file.empty();
        bool ok = true;
        if (mapParam && shadowMapped)
            continue;  // noted once at the request
        else if (n == "shadowname") {
            if (!file.empty() && file != "raytrace")
                Note(p.at, context +
                               " parameter 'shadowname' names a shadow map; affray traces the light's "
                               "shadows instead");
        } else if (n == "intensity")
            ok = ParamNumbers(p, context, 1, &light->intensity);
        else if (n == "lightcolor")
            ok = ParamVector(p, context, &light->color);
        else if (n == "from" && light->kind != Kind::Ambient)
            ok = ParamVector(p, context, &light->from);
        else if (n == "to" && (light->kind == Kind::Distant || spot))
            ok = ParamVector(p, context, &light->to);
        else if (n == "coneangle" && spot)
            ok = ParamNumbers(p, context, 1, &light->coneAngle);
        else if (n == "conedeltaangle" && spot)
            ok = ParamNumbers(p, context, 1, &light->coneDeltaAngle);
        else if (n == "beamdistribution" && spot)
            ok = ParamNumbers(p, context, 1, &light->beamDistribution);
        else if (n == "__category" && p.value.strings.size() == 1)
            light->category = p.value.strings[0];
        else if (n == "__category")
            return Fail(p.at, context + " parameter '__category' takes one string");
        else
            Warn(p.at, context + " has no parameter " + Quote(n) + "; ignored");
        if (!ok) return false;
    }
    if (named) light->castShadows = *named;
    return true;
}

// The spotlight's cone (radians): a half-angle of up to a half turn, a soft edge inside it.
bool RibParser::CheckSpotlight(const RibRequest& r, const std::string& context, const LightDesc& light) {
    const double pi = 3.14159265358979323846;
    if (!(light.coneAngle > 0 && light.coneAngle <= pi))
        return Fail(r.at, context + " coneangle must be in (0, pi] radians, got " + FormatNumber(light.coneAngle));
    if (!(light.coneDeltaAngle >= 0 && light.coneDeltaAngle <= light.coneAngle))
        return Fail(r.at,
                    context + " conedeltaangle must be from 0 to coneangle, got " + FormatNumber(light.coneDeltaAngle));
    if (!(light.beamDistribution >= 0))
        return Fail(r.at,
                    context + " beamdistribution must not be negative, got " + FormatNumber(light.beamDistribution));
    return true;
}

}  // namespace affray::rib
