// rib/resource.cpp: named attribute states (prman's Resource, ResourceBegin and ResourceEnd, which
// RenderMan for Maya and other exporters of prman 13 and later write). `Resource "name"
// "attributes" "string operation" ["save"]` keeps a copy of the current graphics state under the
// name, outside the attribute stack; `"restore"` puts back the part of it that `"string subset"`
// names (a comma-separated list; "all", the default, is the whole state). ResourceBegin and
// ResourceEnd scope the names: those saved between them are forgotten at ResourceEnd. Resources
// of other types (textures, archives) are ignored with a warning.
//
// The subsets, as prman and Pixie document them, over affray's state (parser.h, State):
//   shading                Color, Opacity, Surface, Displacement, the lights that are on, whether
//                          new lights trace shadows, ShadingRate, TextureCoordinates, user and
//                          other attributes, scoped coordinate systems
//   geometrymodification   Sides, orientation, GeometricApproximation "flatness", Detail
//   geometrydefinition     Basis, TrimCurve and its sense
//   hiding, visibility     Attribute "visibility" (camera rays, shadow rays)
//   transform              the current transform
#include <sstream>
#include <vector>

#include "rib/parser.h"

namespace affray::rib {

bool RibParser::DoResource(const RibRequest& r) {
    std::string name;
    if (!LeadingString(r, "a resource name", &name)) return false;
    if (r.args.size() < 2 || r.args[1].isArray || !r.args[1].StringsP())
        return Fail(r.at, "'Resource' expects a name, a resource type and parameters");
    const std::string type = r.args[1].strings[0];
    std::vector<RibParam> params;
    if (!ParamList(r, 2, &params)) return false;
    if (type != "attributes") {
        Warn(r.at, "'Resource' of type " + Quote(type) + " is not supported; ignored");
        return true;
    }
    std::string operation, subset = "all";
    RibPos subsetAt = r.at;
    for (const RibParam& p : params) {
        const bool single = p.value.strings.size() == 1 && p.value.numbers.empty();
        if ((p.value.name == "operation" || p.value.name == "subset") && !single)
            return Fail(p.at, "'Resource' parameter " + Quote(p.value.name) + " expects one string");
        if (p.value.name == "operation") {
            operation = p.value.strings[0];
        } else if (p.value.name == "subset") {
            subset = p.value.strings[0];
            subsetAt = p.at;
        } else {
            Warn(p.at, "'Resource' parameter " + Quote(p.value.name) + " is not supported; ignored");
        }
    }
    if (operation == "save") {
        m_resources[name] = m_state;
        return true;
    }
    if (operation != "restore")
        return Fail(r.at, "'Resource \"" + name +
                              "\" \"attributes\"' needs \"string operation\" \"save\" or "
                              "\"restore\"" +
                              (operation.empty() ? std::string() : ", got " + Quote(operation)));
    const auto saved = m_resources.find(name);
    if (saved == m_resources.end())
        return Fail(r.args[0].at, "'Resource' restores " + Quote(name) + ", which no 'Resource' has saved" +
                                      (m_resourceScopes.empty() ? "" : " (in this 'ResourceBegin' block)"));
    const State& from = saved->second;
    State to = m_state;
    std::istringstream parts(subset);
    for (std::string part; std::getline(parts, part, ',');) {
        if (part == "all") {
            to = from;
        } else if (part == "shading") {
            to.color = from.color;
            to.opacity = from.opacity;
            to.surface = from.surface;
            to.displacement = from.displacement;
            to.lights = from.lights;
            to.lightShadows = from.lightShadows;
            to.shadingRate = from.shadingRate;
            to.textureCoordinates = from.textureCoordinates;
            to.attributes = from.attributes;
            to.scopedSpaces = from.scopedSpaces;
        } else if (part == "geometrymodification") {
            to.twoSided = from.twoSided;
            to.insideOut = from.insideOut;
            to.flatness = from.flatness;
            to.detailBound = from.detailBound;
            to.detailHidden = from.detailHidden;
        } else if (part == "geometrydefinition") {
            to.uBasis = from.uBasis;
            to.vBasis = from.vBasis;
            to.trim = from.trim;
            to.trimKeepInside = from.trimKeepInside;
        } else if (part == "hiding" || part == "visibility") {
            to.transmission = from.transmission;
            to.cameraVisible = from.cameraVisible;
        } else if (part == "transform") {
            to.ctm = from.ctm;
            to.perspectiveFov = from.perspectiveFov;
            to.perspectiveAt = from.perspectiveAt;
        } else {
            return Fail(subsetAt, "'Resource' subset " + Quote(part) +
                                      " is unknown (expected shading, geometrymodification, geometrydefinition, "
                                      "hiding, visibility, transform or all, separated by commas)");
        }
    }
    // A state saved before an earlier frame's FrameEnd may name lights that frame had.
    const size_t nLights = m_scene.lights.size() + m_cameraLights.size();
    std::erase_if(to.lights, [&](int light) { return static_cast<size_t>(light) >= nLights; });
    m_state = to;
    return true;
}

bool RibParser::DoResourceBegin(const RibRequest& r) {
    if (!NoArgs(r)) return false;
    m_resourceScopes.push_back({r.at, m_resources});
    return true;
}

bool RibParser::DoResourceEnd(const RibRequest& r) {
    if (!NoArgs(r)) return false;
    if (m_resourceScopes.empty()) return Fail(r.at, "'ResourceEnd' without matching 'ResourceBegin'");
    m_resources = std::move(m_resourceScopes.back().second);
    m_resourceScopes.pop_back();
    return true;
}

}  // namespace affray::rib
