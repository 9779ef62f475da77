// renderer/scene.h: the parsed scene description, as plain structs in world space.
// The RIB reader (renderer/rib.*) fills these; the renderer consumes them. Nothing here knows about
// RIB syntax: every transform has already been applied, so positions are world space and the camera
// carries one world->camera matrix. Add a field only with a default that matches RenderMan's
// default for it (RI Spec 3.2), and print it in the matching ToString below.
#pragma once

#include <array>
#include <glm/glm.hpp>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

namespace affray::renderer {

/// One shader parameter as written in the RIB file: a name and raw values (numbers or strings).
struct ParamValue {
    std::string name;                  ///< The final word of the token: "uniform float Km" -> "Km".
    std::vector<double> numbers;       ///< The values if numeric (a bare number gives one value).
    std::vector<std::string> strings;  ///< The values if strings.
    std::string declaration;  ///< Inline declaration before the name ("uniform float"), or "".
};

/// A reference to a shader by name with its instance parameters: Displacement "wave" "Km" [0.2].
struct ShaderRef {
    std::string name;
    std::vector<ParamValue> params;  ///< In file order; a repeated name replaces the earlier value.
    int line = 0;                    ///< RIB line of the request, for diagnostics.
    /// Shader space: the current transform at the request (shader -> world, column vectors).
    glm::dmat4 shaderToWorld{1.0};
};

/// The built-in surface models. Defaults are those of RenderMan's "plastic"; "matte" sets Kd = 1.
struct SurfaceDesc {
    enum class Model { Matte, Plastic } model = Model::Plastic;
    double Ka = 1, Kd = 0.5, Ks = 0.5, roughness = 0.1;
    glm::dvec3 specularColor{1.0};
};

/// A light source in world space ("ambientlight", "distantlight", "pointlight").
struct LightDesc {
    enum class Kind { Ambient, Distant, Point } kind = Kind::Point;
    double intensity = 1;
    glm::dvec3 color{1.0};
    glm::dvec3 from{0.0}, to{0.0, 0.0, 1.0};  ///< World space; a distant light shines from -> to.
    std::string handle;                       ///< The RIB light handle (number or string), as text.
    int line = 0;
};

/// A bilinear patch in world space with its shading attributes.
struct PatchDesc {
    std::array<glm::dvec3, 4> corners{};  ///< World space, RenderMan order u0v0, u1v0, u0v1, u1v1.
    glm::dvec3 color{1.0};                ///< The RIB Color (Cs) in effect.
    SurfaceDesc surface;
    std::optional<ShaderRef> displacement;
    int line = 0;
    /// Object space: the current transform at the patch (object -> world, column vectors).
    glm::dmat4 objectToWorld{1.0};
};

/// The camera options in effect at WorldBegin.
struct CameraDesc {
    int xres = 640, yres = 480;
    double pixelAspect = 1;
    bool perspective =
        true;  ///< The RIB reader sets false when no Projection is given (RI default).
    double fovDegrees = 90;  ///< Full angle across the shorter image axis (perspective only).
    glm::dmat4 worldToCamera{1.0};  ///< Column-vector convention: pCamera = worldToCamera * pWorld.
};

/// Everything a render needs from one RIB file.
struct SceneDesc {
    std::string path;  ///< The RIB file, for messages.
    CameraDesc camera;
    std::string displayName = "out.exr";
    std::string displayType = "file";  ///< Display "name" "type" "mode", kept for tools.
    std::string displayMode = "rgba";
    std::vector<LightDesc>
        lights;  ///< Empty if the scene defines none (the renderer adds a default).
    std::vector<PatchDesc> patches;
};

// Printing. Every value type prints itself on one line (the scene on several), for logs and tests.

inline std::string ToString(const glm::dvec3& v) {
    std::ostringstream out;
    out << '[' << v.x << ' ' << v.y << ' ' << v.z << ']';
    return out.str();
}

inline std::string ToString(const glm::dmat4& m) {
    // Printed row by row in column-vector convention (row r = m[0][r] m[1][r] m[2][r] m[3][r]).
    std::ostringstream out;
    out << '[';
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) out << (r || c ? " " : "") << m[c][r];
    out << ']';
    return out.str();
}

inline std::string ToString(const ParamValue& p) {
    std::ostringstream out;
    out << '"' << (p.declaration.empty() ? "" : p.declaration + " ") << p.name << "\" [";
    for (size_t i = 0; i < p.numbers.size(); ++i) out << (i ? " " : "") << p.numbers[i];
    for (size_t i = 0; i < p.strings.size(); ++i) out << (i ? " \"" : "\"") << p.strings[i] << '"';
    out << ']';
    return out.str();
}

inline std::string ToString(const ShaderRef& s) {
    std::string text = "\"" + s.name + "\"";
    for (const ParamValue& p : s.params) text += " " + ToString(p);
    return text;
}

inline std::string ToString(const SurfaceDesc& s) {
    std::ostringstream out;
    out << (s.model == SurfaceDesc::Model::Matte ? "matte" : "plastic") << " Ka=" << s.Ka
        << " Kd=" << s.Kd << " Ks=" << s.Ks << " roughness=" << s.roughness
        << " specularcolor=" << ToString(s.specularColor);
    return out.str();
}

inline std::string ToString(const LightDesc& l) {
    static const char* const kNames[] = {"ambientlight", "distantlight", "pointlight"};
    std::ostringstream out;
    out << kNames[static_cast<int>(l.kind)] << " handle=" << l.handle
        << " intensity=" << l.intensity << " color=" << ToString(l.color)
        << " from=" << ToString(l.from) << " to=" << ToString(l.to);
    return out.str();
}

inline std::string ToString(const PatchDesc& p) {
    std::string text = "patch line " + std::to_string(p.line) + ":";
    for (const glm::dvec3& c : p.corners) text += " " + ToString(c);
    text += " color=" + ToString(p.color) + " " + ToString(p.surface);
    if (p.displacement) text += " displacement " + ToString(*p.displacement);
    return text;
}

inline std::string ToString(const CameraDesc& c) {
    std::ostringstream out;
    out << c.xres << 'x' << c.yres << " pixelaspect=" << c.pixelAspect;
    if (c.perspective)
        out << " perspective fov=" << c.fovDegrees;
    else
        out << " orthographic";
    out << " worldToCamera=" << ToString(c.worldToCamera);
    return out.str();
}

inline std::string ToString(const SceneDesc& s) {
    std::string text = "scene " + s.path + "\n  camera " + ToString(s.camera) + "\n  display \"" +
                       s.displayName + "\" \"" + s.displayType + "\" \"" + s.displayMode + "\"\n";
    for (const LightDesc& l : s.lights) text += "  light " + ToString(l) + "\n";
    for (const PatchDesc& p : s.patches) text += "  " + ToString(p) + "\n";
    return text;
}

}  // namespace affray::renderer
