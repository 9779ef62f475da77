// renderer/rib_attributes.cpp: RIB requests for shading attributes, lights and geometry (Color,
// Surface, Displacement, LightSource, Patch). Rules shared with rib.cpp are in rib_parser.h.
// Positions are transformed to world space here, with the CTM current at the request.
#include <array>
#include <cmath>

#include "renderer/rib_parser.h"

namespace affray::renderer {

bool RibParser::DoColor(const RibRequest& r) {
    double v[3];
    if (!Numbers(r, 3, "r g b", v)) return false;
    m_state.color = glm::dvec3(v[0], v[1], v[2]);
    return true;
}

bool RibParser::DoSurface(const RibRequest& r) {
    std::string name;
    std::vector<RibParam> params;
    if (!LeadingString(r, "a surface shader name", &name) || !ParamList(r, 1, &params))
        return false;
    SurfaceDesc surface;  // plastic defaults
    if (name == "matte") {
        surface.model = SurfaceDesc::Model::Matte;
        surface.Kd = 1;  // RI 3.2 matte: Ka = 1, Kd = 1
        surface.Ks = 0;
    } else if (name != "plastic") {
        Warn(r.line, "surface shader " + Quote(name) + " is not supported yet; using \"plastic\"");
        m_state.surface = surface;
        return true;
    }
    const std::string context = "'Surface \"" + name + "\"'";
    bool matte = surface.model == SurfaceDesc::Model::Matte;
    for (const RibParam& p : params) {
        const std::string& n = p.value.name;
        bool ok = true;
        if (n == "Ka")
            ok = ParamNumbers(p, context, 1, &surface.Ka);
        else if (n == "Kd")
            ok = ParamNumbers(p, context, 1, &surface.Kd);
        else if (n == "Ks" && !matte)
            ok = ParamNumbers(p, context, 1, &surface.Ks);
        else if (n == "roughness" && !matte)
            ok = ParamNumbers(p, context, 1, &surface.roughness);
        else if (n == "specularcolor" && !matte)
            ok = ParamVector(p, context, &surface.specularColor);
        else
            Warn(p.line, context + " has no parameter " + Quote(n) + "; ignored");
        if (!ok) return false;
    }
    if (!(surface.roughness > 0))  // plastic's highlight exponent is 1 / roughness
        return Fail(r.line, context + " roughness must be positive, got " +
                                FormatNumber(surface.roughness));
    m_state.surface = surface;
    return true;
}

bool RibParser::DoDisplacement(const RibRequest& r) {
    ShaderRef shader;
    std::vector<RibParam> params;
    if (!LeadingString(r, "a displacement shader name", &shader.name) || !ParamList(r, 1, &params))
        return false;
    if (shader.name.empty()) {  // Displacement "" removes the shader
        m_state.displacement.reset();
        return true;
    }
    shader.line = r.line;
    shader.shaderToWorld = m_state.ctm;
    for (RibParam& p : params) shader.params.push_back(std::move(p.value));
    m_state.displacement = std::move(shader);
    return true;
}

bool RibParser::DoLightSource(const RibRequest& r) {
    std::string name;
    if (!LeadingString(r, "a light shader name", &name)) return false;
    if (r.args.size() < 2 || r.args[1].isArray)
        return Fail(
            r.line,
            "'LightSource' expects a light handle (a number or a string) after the shader name");
    std::vector<RibParam> params;
    if (!ParamList(r, 2, &params)) return false;
    if (m_worldEnded) return Fail(r.line, "'LightSource' after 'WorldEnd'");

    LightDesc light;
    light.line = r.line;
    const RibArg& handle = r.args[1];
    light.handle = handle.StringsP() ? handle.strings[0] : FormatNumber(handle.numbers[0]);
    if (name == "ambientlight")
        light.kind = LightDesc::Kind::Ambient;
    else if (name == "distantlight")
        light.kind = LightDesc::Kind::Distant;
    else if (name == "pointlight")
        light.kind = LightDesc::Kind::Point;
    else {
        Warn(r.line, "light source " + Quote(name) + " is not supported yet; ignored");
        return true;
    }
    const std::string context = "'LightSource \"" + name + "\"'";
    for (const RibParam& p : params) {
        const std::string& n = p.value.name;
        bool ok = true;
        if (n == "intensity")
            ok = ParamNumbers(p, context, 1, &light.intensity);
        else if (n == "lightcolor")
            ok = ParamVector(p, context, &light.color);
        else if (n == "from" && light.kind != LightDesc::Kind::Ambient)
            ok = ParamVector(p, context, &light.from);
        else if (n == "to" && light.kind == LightDesc::Kind::Distant)
            ok = ParamVector(p, context, &light.to);
        else
            Warn(p.line, context + " has no parameter " + Quote(n) + "; ignored");
        if (!ok) return false;
    }
    // from/to are points in the current space; before WorldBegin that is camera space, which is
    // mapped to world space once the camera transform is known.
    light.from = TransformPoint(m_state.ctm, light.from);
    light.to = TransformPoint(m_state.ctm, light.to);
    if (light.kind == LightDesc::Kind::Distant && light.from == light.to)
        return Fail(r.line, context + " 'from' and 'to' must differ");
    if (m_worldSeen)
        m_scene.lights.push_back(light);
    else
        m_cameraLights.push_back(light);
    return true;
}

// ---- geometry ----

bool RibParser::DoPatch(const RibRequest& r) {
    std::string type;
    if (!LeadingString(r, "a patch type", &type)) return false;
    if (type == "bicubic") return Fail(r.line, "'Patch \"bicubic\"' is not supported yet");
    if (type != "bilinear")
        return Fail(r.args[0].line, "unknown patch type " + Quote(type) +
                                        " (expected \"bilinear\" or \"bicubic\")");
    std::vector<RibParam> params;
    if (!ParamList(r, 1, &params) || !InsideWorld(r)) return false;

    const std::string context = "'Patch \"bilinear\"'";
    std::array<glm::dvec3, 4> corners{};
    bool havePosition = false;
    for (const RibParam& p : params) {
        const std::string& n = p.value.name;
        if (n == "P") {
            double v[12];
            if (!ParamNumbers(p, context, 12, v)) return false;
            for (int i = 0; i < 4; ++i)
                corners[i] = glm::dvec3(v[3 * i], v[3 * i + 1], v[3 * i + 2]);
        } else if (n == "Pw") {  // homogeneous points
            double v[16];
            if (!ParamNumbers(p, context, 16, v)) return false;
            for (int i = 0; i < 4; ++i) {
                if (v[4 * i + 3] == 0)
                    return Fail(p.line, context + " parameter 'Pw' has a zero w");
                corners[i] = glm::dvec3(v[4 * i], v[4 * i + 1], v[4 * i + 2]) / v[4 * i + 3];
            }
        } else if (n == "Pz") {  // heights over the unit square (x = u, y = v)
            double z[4];
            if (!ParamNumbers(p, context, 4, z)) return false;
            for (int i = 0; i < 4; ++i) corners[i] = glm::dvec3(i & 1, i >> 1, z[i]);
        } else {
            Warn(p.line, context + " parameter " + Quote(n) + " is not supported yet; ignored");
            continue;
        }
        havePosition = true;
    }
    if (!havePosition) return Fail(r.line, context + " needs a \"P\" parameter");

    PrimitiveDesc patch;
    for (int i = 0; i < 4; ++i) {
        patch.corners[i] = TransformPoint(m_state.ctm, corners[i]);
        if (!FiniteP(patch.corners[i]))
            return Fail(r.line,
                        context + " corner " + std::to_string(i) + " overflows in world space");
    }
    patch.color = m_state.color;
    patch.surface = m_state.surface;
    patch.displacement = m_state.displacement;
    patch.line = r.line;
    patch.objectToWorld = m_state.ctm;
    m_scene.primitives.push_back(std::move(patch));
    return true;
}

}  // namespace affray::renderer
