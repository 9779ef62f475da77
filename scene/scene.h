// scene/scene.h: the parsed scene description, as plain structs in world space.
// The RIB reader (rib/) fills these; the renderer consumes them, once RefineScene
// (scene/refine.h) has made the elements of the meshes that the reader keeps as read. Nothing
// here knows about RIB syntax: every transform has already been applied, so positions are world
// space and the camera carries one world->camera matrix. Add a field only with a default that
// matches RenderMan's default for it (RI Spec 3.2), and print it in the matching ToString below.
#pragma once

#include <array>
#include <cmath>
#include <glm/glm.hpp>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "scene/geometry/primvar.h"
#include "scene/geometry/surface.h"
#include "scene/motion.h"
#include "scene/number_text.h"

namespace affray::compiler {
struct CompiledShader;  // a light's program (compiler/compile.h)
}  // namespace affray::compiler

namespace affray::renderer {

struct UnrefinedMesh;  // scene/refine.h

/// One shader parameter as written in the RIB file: a name and raw values (numbers or strings).
struct ParamValue {
    std::string name;                  ///< The final word of the token: "uniform float Km" -> "Km".
    std::vector<double> numbers;       ///< The values if numeric (a bare number gives one value).
    std::vector<std::string> strings;  ///< The values if strings.
    std::string declaration;           ///< Inline declaration before the name ("uniform float"), or "".
};

/// A reference to a shader by name with its instance parameters: Displacement "wave" "Km" [0.2].
struct ShaderRef {
    std::string name;
    std::vector<ParamValue> params;  ///< In file order; a repeated name replaces the earlier value.
    int line = 0, column = 0;        ///< Where the request starts in the RIB file, for diagnostics.
    std::string file;                ///< The file of the request if not the scene's (ReadArchive), else "".
    /// Shader space: the current transform at the request (shader -> world, column vectors).
    glm::dmat4 shaderToWorld{1.0};
};

/// The built-in surface models of RI Spec 3.2 appendix A, with their defaults: "constant" (Cs),
/// "matte" (Ka = 1, Kd = 1), "metal" (Ka = 1, Ks = 1, roughness = 0.1: specular only, tinted by
/// Cs) and "plastic" (Ka = 1, Kd = 0.5, Ks = 0.5, roughness = 0.1, specularcolor = 1).
struct SurfaceDesc {
    enum class Model { Constant, Matte, Metal, Plastic } model = Model::Plastic;
    double Ka = 1, Kd = 0.5, Ks = 0.5, roughness = 0.1;
    glm::dvec3 specularColor{1.0};
    /// The Surface request's shader and parameters: its .sl (or a shader of the same name on the
    /// search path, for the names above) is compiled and run on the VM; the model above is what
    /// renders where no such shader is found, or it does not compile (warned).
    std::optional<ShaderRef> shader;
};

/// An atmosphere shader (Atmosphere): RI 3.2's standard volume shaders, run on what a camera ray
/// sees of a primitive. Fog: d = 1 - exp(-length(I) / distance); depth cue: d = (depth(P) -
/// mindistance) / (maxdistance - mindistance) clamped to [0, 1], depth the camera depth from the
/// near to the far clipping plane mapped to [0, 1]. Either mixes the surface's premultiplied colour
/// towards `background` and its opacity towards 1 by d: Ci = mix(Ci, background, d), Oi = mix(Oi,
/// 1, d).
struct AtmosphereDesc {
    enum class Kind { Fog, DepthCue } kind = Kind::Fog;
    double distance = 1;                      ///< fog
    double minDistance = 0, maxDistance = 1;  ///< depthcue
    glm::dvec3 background{0.0};
};

/// A light source in world space ("ambientlight", "distantlight", "pointlight", "spotlight").
struct LightDesc {
    enum class Kind { Ambient, Distant, Point, Spot } kind = Kind::Point;
    double intensity = 1;
    glm::dvec3 color{1.0};
    glm::dvec3 from{0.0}, to{0.0, 0.0, 1.0};  ///< World space; distant and spot lights shine from -> to.
    /// Spotlight only, RI defaults: half-angle of the cone and width of its soft edge (radians),
    /// and the exponent of the cosine fall-off across the beam.
    double coneAngle = 0.5235987755982988, coneDeltaAngle = 0.08726646259971647, beamDistribution = 2;
    std::string handle;  ///< The RIB light handle (number or string), as text.
    /// Its `__category` parameter: the comma-separated categories a surface shader's
    /// illuminance ("category", ...) selects lights by ("" if none).
    std::string category;
    int line = 0;
    /// A light declared under a moving transform (MotionBegin around transform requests): from and
    /// to are where the path's first matrix places them, carried at time t by At(t) times the
    /// first matrix's inverse (LightAt). Null for a light that stands still.
    std::shared_ptr<const MotionPath> motion;
    /// The LightSource request's shader and parameters (shader space: the transform at the
    /// request). Its .sl, found on the shader search path, is compiled (`program`, by
    /// Renderer::Prepare) and run on the VM; where none is found the fields above render it as
    /// the standard light of its name, or, for another name (`builtIn` false), it gives no light.
    std::optional<ShaderRef> shader;
    bool builtIn = true;
    std::shared_ptr<const compiler::CompiledShader> program;
    /// For a light that moves, as LightAt places it: the map from where it stands at the
    /// shutter's opening to where it stands now (its program runs in the first frame).
    glm::dmat4 moved{1.0};
    /// Whether the light traces shadow rays. RenderMan's standard lights cast no shadows (their
    /// shaders never call shadow()); the RIB reader turns this on for the shadow-map lights
    /// (shadowspot...), a light given a "shadowname", and BMRT's Attribute "light" "shadows" "on".
    bool castShadows = false;
};

/// The attributes a primitive takes from the graphics state at its request: shared by every
/// primitive the request makes (a mesh's pieces, a patch mesh's patches), so a mesh of a
/// million faces holds them once.
struct PrimitiveAttributes {
    /// How the primitive stops shadow rays (Attribute "visibility" "transmission", BMRT's
    /// Attribute "render" "casts_shadows"): wholly (Opaque, the default, BMRT's), by its opacity
    /// Os (Opacity: the light passing a hit is scaled by 1 - Os there), or not at all.
    enum class Transmission { Opaque, Opacity, Transparent } transmission = Transmission::Opaque;
    /// Attribute "visibility" "camera": false hides the primitive from camera rays (it still
    /// casts shadows as `transmission` says).
    bool cameraVisible = true;
    /// The geometric tolerance, in pixels, that the scene's level of detail asks of the primitive:
    /// 0.5 sqrt(ShadingRate) (RI default 1: 0.5, affray's default tolerance) or
    /// GeometricApproximation "flatness", the larger. The renderer takes it where it is coarser
    /// than its own tolerance, unless that was given on the command line.
    double sceneTolerance = 0.5;
    SurfaceDesc surface;
    std::optional<ShaderRef> displacement;
    /// Atmosphere: what lies between the camera and the primitive (unset: nothing).
    std::optional<AtmosphereDesc> atmosphere;
    int line = 0, column = 0;  ///< Where the request starts in the RIB file, for diagnostics.
    /// Object space: the current transform at the request (object -> world, column vectors).
    /// Under a moving transform (MotionBegin around transforms), its matrix at the path's first
    /// time, where the primitive's world-space geometry is placed.
    glm::dmat4 objectToWorld{1.0};
    /// The object -> world transform over time when it moves (null: it stands still): the
    /// primitive is a rigid copy of its geometry at the path's first time, carried to each time
    /// by path(time) * inverse(path(first time)).
    std::shared_ptr<const MotionPath> motion;
    /// Sides: false for "Sides 1" (seen from behind, the surface is invisible).
    bool twoSided = true;
    /// The lights that illuminate the primitive, as indices into SceneDesc::lights: the light list
    /// of the graphics state at the request (RI 3.2: a light is on from its LightSource, Illuminate
    /// turns it on or off, AttributeEnd restores the list). Unset: every light of the scene.
    std::optional<std::vector<int>> lights;
    /// The named spaces ScopedCoordinateSystem defined in the attribute blocks around the request
    /// (name -> world, column vectors), or null: its shaders see them, over the scene's
    /// coordinateSystems of the same names.
    std::shared_ptr<const std::map<std::string, glm::dmat4>> scopedSpaces;
};

/// One geometric primitive: its base surface (a bilinear, bicubic or rational patch with the part
/// of its mesh's (u,v) it covers, a placed quadric, a polygon mesh's piece or a subdivision
/// mesh's patch; scene/geometry/surface.h, world space) and its colours, with the attributes
/// of its request.
///
/// The base surface's flipNormal is whether RenderMan's normal is the negation of dPdu x dPdv
/// computed in world space. A primitive's natural normal is dPdu x dPdv in object space carried to
/// world as a normal (by the inverse transpose, which keeps a sphere's normals outward under any
/// placement); the world-space cross product of the placed tangents is that times sign(det
/// objectToWorld). RI 3.2 section 4.2 then turns the primitive inside out when the current
/// orientation differs from the handedness of the current coordinate system; a mirroring
/// transform flips both, so only Orientation ("inside"; "lh"/"rh" against the system's handedness
/// at the request) and ReverseOrientation make them differ. So flipNormal = (det objectToWorld <
/// 0) XOR insideOut. Default: a sphere's normals point out, whatever the camera and placement.
/// Its textureCoordinates are the TextureCoordinates in effect: the s, t of quadrics and patches
/// without their own "st".
///
/// A mesh is one PrimitiveDesc for all its pieces or patches: `elements` of them from its base's
/// onwards, sharing everything but their shape and colours (which the mesh's shared arrays hold),
/// so that a mesh of a million faces is one description, not a million. Element(i) is element i
/// as a primitive of its own. A mesh as the RIB reader leaves it has no elements yet, only its
/// UnrefinedMesh, until RefineScene (scene/refine.h) makes them.
struct PrimitiveDesc {
    using Transmission = PrimitiveAttributes::Transmission;
    BaseSurface base;
    /// The primitives this one stands for: a polygon mesh's pieces or a subdivision mesh's
    /// patches (none before RefineScene); 1 for any other shape.
    uint32_t elements = 1;
    /// The mesh as read, before RefineScene, which replaces it by `base` and `elements`; null
    /// after (and for every other shape). Not const: RefineScene takes its arrays when it holds
    /// the only reference.
    std::shared_ptr<UnrefinedMesh> unrefined;
    glm::dvec3 color{1.0};    ///< The RIB Color in effect, or the primitive's constant or uniform "Cs".
    glm::dvec3 opacity{1.0};  ///< The RIB Opacity in effect, or the primitive's constant or uniform "Os".
    /// A "Cs" or "Os" that varies over the primitive (varying, vertex, facevarying values), over
    /// its own (s,t) as the intersector's hits give them; null: `color` or `opacity` everywhere.
    /// A mesh's own Cs and Os (PieceMesh::colors, SubdivPatches::colors) take their place.
    std::shared_ptr<const ColorField> colorField, opacityField;
    /// Never null: the defaults unless the RIB reader gives the request's.
    std::shared_ptr<const PrimitiveAttributes> attributes = DefaultAttributes();

    const PrimitiveAttributes& attr() const { return *attributes; }

    /// Sets the colour (k = 0) or opacity (k = 1) from `field`: its value if it is constant,
    /// else the field.
    void SetColor(int k, ColorField field) {
        glm::dvec3 value;
        auto& target = k ? opacityField : colorField;
        if (field.ConstantP(&value)) {
            (k ? opacity : color) = value;
            target = nullptr;
        } else {
            target = std::make_shared<const ColorField>(std::move(field));
        }
    }
    /// Element i's Cs (k = 0) or Os (k = 1) as its mesh gives it, if the mesh has one.
    std::optional<ColorField> MeshColor(uint32_t i, int k) const {
        if (base.kind() == BaseSurface::Kind::MeshPiece) {
            const MeshPieceRef& ref = base.pieceRef();
            std::array<glm::dvec3, 4> corners;
            if (!ref.mesh->CornerColors(ref.index + i, k, &corners)) return std::nullopt;
            return ColorField::Bilinear(corners);
        }
        if (base.kind() == BaseSurface::Kind::SubdivPatch) {
            const SubdivPatchRef& ref = base.subdivRef();
            ColorField field;
            if (!ref.patches->PatchColor(ref.index + i, k, &field)) return std::nullopt;
            return field;
        }
        return std::nullopt;
    }
    /// Cs (k = 0) or Os (k = 1) of element i at the point (u, v) of its own parameters; Os from
    /// a field clamped to [0, 1] (a field may overshoot between its values).
    glm::dvec3 ColorAt(uint32_t i, int k, double u, double v) const {
        auto at = [&](const ColorField& f) { return k ? glm::clamp(f.At(u, v), 0.0, 1.0) : f.At(u, v); };
        if (std::optional<ColorField> f = MeshColor(i, k)) {
            glm::dvec3 value;
            return f->ConstantP(&value) ? value : at(*f);
        }
        const std::shared_ptr<const ColorField>& field = k ? opacityField : colorField;
        return field ? at(*field) : (k ? opacity : color);
    }
    /// Whether element i's Os is 1 everywhere.
    bool OpaqueP(uint32_t i) const {
        glm::dvec3 value;
        if (std::optional<ColorField> f = MeshColor(i, 1)) return f->ConstantP(&value) && value == glm::dvec3(1.0);
        return !opacityField && opacity == glm::dvec3(1.0);
    }
    /// Element i as a primitive of its own (its shape, its colours as fields).
    PrimitiveDesc Element(uint32_t i) const {
        PrimitiveDesc e = *this;
        e.base = base.Element(i);
        e.elements = 1;
        for (int k = 0; k < 2; ++k)
            if (std::optional<ColorField> f = MeshColor(i, k)) e.SetColor(k, std::move(*f));
        return e;
    }
    static const std::shared_ptr<const PrimitiveAttributes>& DefaultAttributes() {
        static const std::shared_ptr<const PrimitiveAttributes> defaults = std::make_shared<PrimitiveAttributes>();
        return defaults;
    }
};

/// The pixel reconstruction filter (PixelFilter): "box" or "gaussian", with its widths in pixels.
struct FilterDesc {
    enum class Kind { Box, Gaussian } kind = Kind::Gaussian;
    double xwidth = 2, ywidth = 2;  ///< RI default: gaussian 2 x 2
};

/// The camera options in effect at WorldBegin.
struct CameraDesc {
    int xres = 640, yres = 480;
    double pixelAspect = 1;
    bool perspective = true;        ///< The RIB reader sets false when no Projection is given (RI default).
    double fovDegrees = 90;         ///< Full angle across the shorter image axis (perspective only).
    glm::dmat4 worldToCamera{1.0};  ///< Column-vector convention: pCamera = worldToCamera * pWorld.
    /// FrameAspectRatio, if given (else xres * pixelAspect / yres).
    std::optional<double> frameAspectRatio;
    /// ScreenWindow left, right, bottom, top, if given (else derived from the frame aspect ratio).
    std::optional<glm::dvec4> screenWindow;
    /// CropWindow xmin, xmax, ymin, ymax in NDC (0..1, y down); the whole frame by default.
    glm::dvec4 cropWindow{0.0, 1.0, 0.0, 1.0};
    double nearClip = 1e-10, farClip = 1e30;  ///< Clipping, camera-space depths (RI defaults)
    int xsamples = 2, ysamples = 2;           ///< PixelSamples (RI default 2 x 2)
    /// Hider "hidden" "jitter": true places each sample at random in its stratum; false at the
    /// stratum's centre (with PixelSamples 1 1, the ray through the pixel centre).
    bool jitter = true;
    FilterDesc filter;
    double exposureGain = 1, exposureGamma = 1;  ///< Exposure: out = (gain * color)^(1/gamma)
    /// DepthOfField (RI 3.2 section 4.1.2): a thin lens of diameter focalLength / fstop (camera
    /// space units) focused on the plane z = focalDistance of camera space. An infinite fstop (the
    /// default, and DepthOfField without arguments) is a pinhole. Perspective cameras only.
    double fstop = std::numeric_limits<double>::infinity(), focalLength = 0, focalDistance = 0;
    /// Shutter (RI 3.2 section 4.1.2): the times the shutter opens and closes. Every camera
    /// sample takes a time between them (stratified per pixel); equal times (the default, 0 0)
    /// render the scene as it stands at that time, with no blur.
    double shutterOpen = 0, shutterClose = 0;
    /// The world -> camera transform over time when the camera moves (null: worldToCamera, which
    /// is then the path's matrix at its first time).
    std::shared_ptr<const MotionPath> motion;
    /// Imager "background": the colour composited under every pixel (colour += (1 - alpha) *
    /// background, alpha = 1), before the exposure, as RI 3.2's standard imager does. Unset: none.
    std::optional<glm::dvec3> background;
};

/// Everything a render needs from one frame of a RIB file: the world block with the options in
/// effect at its WorldBegin.
struct SceneDesc {
    std::string path;  ///< The RIB file, for messages.
    /// FrameBegin's number, if the world is inside a FrameBegin/FrameEnd block.
    std::optional<int> frame;
    int frameLine = 0;  ///< The line of the FrameBegin (or of the WorldBegin outside a frame).
    /// Why the frame renders no image ("" when it does): a shadow or depth map pass of a scanline
    /// renderer, whose maps affray does not need since it traces its shadows.
    std::string skipped;
    CameraDesc camera;
    std::string displayName = "out.exr";
    std::string displayType = "file";  ///< Display "name" "type" "mode", kept for tools.
    /// Display mode: channel groups separated by commas, from "rgb", "rgba", "rgbz", "rgbaz" (or
    /// their single letters r g b a z) and the AOVs "Z", "N", "P", "st", "cost", "err".
    std::string displayMode = "rgba";
    std::vector<LightDesc> lights;  ///< Empty if the scene defines none (the renderer adds a default).
    std::vector<PrimitiveDesc> primitives;
    /// Option "searchpath" "shader": directories in order, '&' already expanded to the previous
    /// value and '@' to the default. Empty: the renderer's default search path.
    std::vector<std::string> shaderSearchPath;
    /// Option "searchpath" "texture", likewise: where texture() looks for a relative file name,
    /// before the RIB file's directory, the shader's and the working directory.
    std::vector<std::string> textureSearchPath;
    /// MakeTexture requests, in file order: Renderer::Prepare makes each texture (a tiled, mip-mapped
    /// TIFF) before it compiles the shaders that may read it. Paths as written: relative ones are
    /// taken from the RIB file's directory.
    struct MakeTextureDesc {
        std::string picture, texture;
        std::string swrap = "periodic", twrap = "periodic";  ///< "black", "clamp" or "periodic"
        int line = 0, column = 0;                            ///< The request in the RIB file, for diagnostics.
        std::string file;  ///< The request's file if not the scene's (ReadArchive), else "".
    };
    std::vector<MakeTextureDesc> makeTextures;
    /// CoordinateSystem names, each the current transform at its request (object -> world).
    std::map<std::string, glm::dmat4> coordinateSystems;
};

// Printing. Every value type prints itself on one line (the scene on several), for logs and tests.

inline std::string ToString(const glm::dvec3& v) {
    std::string out = "[";
    for (int i = 0; i < 3; ++i) {
        if (i) out += ' ';
        AppendNumber(out, v[i]);
    }
    return out + ']';
}

inline std::string ToString(const glm::dmat4& m) {
    // Printed row by row in column-vector convention (row r = m[0][r] m[1][r] m[2][r] m[3][r]).
    std::string out = "[";
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) {
            if (r || c) out += ' ';
            AppendNumber(out, m[c][r]);
        }
    return out + ']';
}

/// The times and matrices of a moving transform: " motion t=T0 [...] t=T1 [...]".
inline std::string ToString(const MotionPath& path) {
    std::string out = " motion";
    for (size_t i = 0; i < path.times.size(); ++i) {
        out += " t=";
        AppendNumber(out, path.times[i]);
        out += ' ' + ToString(path.matrices[i]);
    }
    return out;
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
    static const char* const kNames[] = {"constant", "matte", "metal", "plastic"};
    std::ostringstream out;
    out << kNames[static_cast<int>(s.model)] << " Ka=" << s.Ka << " Kd=" << s.Kd << " Ks=" << s.Ks
        << " roughness=" << s.roughness << " specularcolor=" << ToString(s.specularColor);
    if (s.shader) out << " shader " << ToString(*s.shader);
    return out.str();
}

inline std::string ToString(const LightDesc& l) {
    static const char* const kNames[] = {"ambientlight", "distantlight", "pointlight", "spotlight"};
    std::ostringstream out;
    out << kNames[static_cast<int>(l.kind)] << " handle=" << l.handle << " intensity=" << l.intensity
        << " color=" << ToString(l.color) << " from=" << ToString(l.from) << " to=" << ToString(l.to);
    if (l.kind == LightDesc::Kind::Spot)
        out << " coneangle=" << l.coneAngle << " conedeltaangle=" << l.coneDeltaAngle
            << " beamdistribution=" << l.beamDistribution;
    if (l.castShadows) out << " shadows";
    if (!l.category.empty()) out << " category=\"" << l.category << "\"";
    if (l.shader) out << " shader " << ToString(*l.shader) << (l.builtIn ? "" : " (no built-in)");
    if (l.motion) out << ToString(*l.motion);
    return out.str();
}

/// `light` where it stands at `time`: from and to carried along its motion path.
inline LightDesc LightAt(const LightDesc& light, double time) {
    if (!light.motion) return light;
    LightDesc at = light;
    const glm::dmat4 move = light.motion->At(time) * glm::inverse(light.motion->matrices.front());
    at.from = glm::dvec3(move * glm::dvec4(light.from, 1.0));
    at.to = glm::dvec3(move * glm::dvec4(light.to, 1.0));
    at.moved = move;
    return at;
}

inline std::string ToString(const PrimitiveDesc& p) {
    const PrimitiveAttributes& a = p.attr();
    const BaseSurface& b = p.base;
    const std::string line = std::to_string(a.line);
    std::string text;
    switch (b.kind()) {
        case BaseSurface::Kind::BilinearPatch:
            text = "patch line " + line + ":";
            for (const glm::dvec3& c : b.patch().corners) text += " " + ToString(c);
            break;
        case BaseSurface::Kind::BicubicPatch: text = "patch line " + line + ": " + ToString(b.bicubic()); break;
        case BaseSurface::Kind::RationalPatch:
            text = "patch line " + line + ": " + ToString(b.rational());
            if (b.trim) text += " trimmed (" + std::to_string(b.trim->loops.size()) + " loops)";
            break;
        case BaseSurface::Kind::MeshPiece: text = "polygon line " + line + ": " + ToString(b.piece()); break;
        case BaseSurface::Kind::SubdivPatch: text = "subdivision line " + line + ": " + ToString(b.subdiv()); break;
        case BaseSurface::Kind::Quadric:
            text = std::string(Quadric::Name(b.quadric().quadric.kind)) + " line " + line + ": " +
                   ToString(b.quadric().quadric) + " objectToWorld=" + ToString(b.quadric().objectToWorld);
            break;
    }
    if (!b.range.unitP()) {
        std::ostringstream range;
        range << " uv=[" << b.range.u0 << ' ' << b.range.u1 << ' ' << b.range.v0 << ' ' << b.range.v1 << ']';
        text += range.str();
    }
    if (p.elements != 1) text += " elements=" + std::to_string(p.elements);
    if (!a.twoSided) text += " sides=1";
    if (a.lights) {
        text += " lights=[";
        for (size_t i = 0; i < a.lights->size(); ++i) text += (i ? " " : "") + std::to_string((*a.lights)[i]);
        text += "]";
    }
    if (b.flipNormal) text += " flipnormal";
    if (b.textureCoordinates) {
        std::ostringstream st;
        st << " st=[";
        for (size_t i = 0; i < 8; ++i) st << (i ? " " : "") << (*b.textureCoordinates)[i];
        text += st.str() + "]";
    }
    if (a.scopedSpaces)
        for (const auto& [name, m] : *a.scopedSpaces) text += " space " + name + "=" + ToString(m);
    if (a.motion) text += ToString(*a.motion);
    if (a.transmission == PrimitiveDesc::Transmission::Opacity) text += " transmission=Os";
    if (a.transmission == PrimitiveDesc::Transmission::Transparent) text += " transmission=transparent";
    if (!a.cameraVisible) text += " camera=0";
    if (a.sceneTolerance != 0.5) {
        std::ostringstream tolerance;
        tolerance << " tolerance=" << a.sceneTolerance;
        text += tolerance.str();
    }
    text += " color=" + ToString(p.color);
    if (p.colorField) text += " Cs=(" + ToString(*p.colorField) + ")";
    if (p.opacity != glm::dvec3(1.0)) text += " opacity=" + ToString(p.opacity);
    if (p.opacityField) text += " Os=(" + ToString(*p.opacityField) + ")";
    text += " " + ToString(a.surface);
    if (a.displacement) text += " displacement " + ToString(*a.displacement);
    if (a.atmosphere) {
        const AtmosphereDesc& at = *a.atmosphere;
        std::ostringstream atmosphere;
        if (at.kind == AtmosphereDesc::Kind::Fog)
            atmosphere << " atmosphere fog distance=" << at.distance;
        else
            atmosphere << " atmosphere depthcue distances=" << at.minDistance << ' ' << at.maxDistance;
        text += atmosphere.str() + " background=" + ToString(at.background);
    }
    return text;
}

/// Whether camera samples take times across an open shutter (Shutter with close > open).
inline bool ShutterOpenP(const CameraDesc& c) { return c.shutterClose > c.shutterOpen; }

/// Whether the camera has a lens (DepthOfField with a finite fstop and positive lengths, on a
/// perspective projection) whose blur can show: camera rays then start across it. A lens point
/// at distance d from the centre moves the image of a point at camera depth z by d |1/z - 1/f|
/// on the plane z = 1 (f the focal distance), most at the clipping planes; a lens that moves no
/// image by a hundredth of a pixel there (exporters write `DepthOfField 1000000 1 1` for a
/// pinhole, with near clipping far from the eye) is taken as the pinhole it draws, so that ray
/// groups still apply.
inline bool LensP(const CameraDesc& c) {
    if (!(c.perspective && std::isfinite(c.fstop) && c.fstop > 0 && c.focalLength > 0 && c.focalDistance > 0))
        return false;
    const double radius = 0.5 * c.focalLength / c.fstop, f = c.focalDistance;
    const double spread = radius * std::max(std::fabs(1 / c.nearClip - 1 / f), std::fabs(1 / c.farClip - 1 / f));
    // A pixel on the plane z = 1, the smaller of its sides (Camera's screen window, as derived there).
    const double aspect = c.frameAspectRatio.value_or(c.xres * c.pixelAspect / c.yres);
    const double tanHalf = std::tan(c.fovDegrees * (3.14159265358979323846 / 360));
    double width = aspect >= 1 ? 2 * aspect : 2, height = aspect >= 1 ? 2 : 2 / aspect;
    if (c.screenWindow) {
        width = std::fabs(c.screenWindow->y - c.screenWindow->x);
        height = std::fabs(c.screenWindow->w - c.screenWindow->z);
    }
    const double pixel = tanHalf * std::min(width / c.xres, height / c.yres);
    return !(spread < 0.01 * pixel);  // NaN (a clipping plane at 0): a lens
}

inline std::string ToString(const CameraDesc& c) {
    std::ostringstream out;
    out << c.xres << 'x' << c.yres << " pixelaspect=" << c.pixelAspect;
    if (c.perspective)
        out << " perspective fov=" << c.fovDegrees;
    else
        out << " orthographic";
    out << " worldToCamera=" << ToString(c.worldToCamera);
    if (c.frameAspectRatio) out << " frameaspectratio=" << *c.frameAspectRatio;
    if (c.screenWindow)
        out << " screenwindow=[" << c.screenWindow->x << ' ' << c.screenWindow->y << ' ' << c.screenWindow->z << ' '
            << c.screenWindow->w << ']';
    out << " cropwindow=[" << c.cropWindow.x << ' ' << c.cropWindow.y << ' ' << c.cropWindow.z << ' ' << c.cropWindow.w
        << "] clipping=" << c.nearClip << ' ' << c.farClip << " pixelsamples=" << c.xsamples << ' ' << c.ysamples
        << (c.jitter ? "" : " jitter=0")
        << " filter=" << (c.filter.kind == FilterDesc::Kind::Box ? "box " : "gaussian ") << c.filter.xwidth << ' '
        << c.filter.ywidth << " exposure=" << c.exposureGain << ' ' << c.exposureGamma;
    if (c.background) out << " imager=background " << ToString(*c.background);
    if (std::isfinite(c.fstop)) out << " depthoffield=" << c.fstop << ' ' << c.focalLength << ' ' << c.focalDistance;
    if (c.shutterOpen != 0 || c.shutterClose != 0) out << " shutter=" << c.shutterOpen << ' ' << c.shutterClose;
    if (c.motion) out << ToString(*c.motion);
    return out.str();
}

/// The scene after its camera but for its primitives: display, lights, coordinate systems, search
/// paths and texture requests, one per line.
inline std::string ToStringSettings(const SceneDesc& s) {
    std::string text = "  display \"" + s.displayName + "\" \"" + s.displayType + "\" \"" + s.displayMode + "\"\n";
    for (const LightDesc& l : s.lights) text += "  light " + ToString(l) + "\n";
    for (const auto& [name, m] : s.coordinateSystems) text += "  coordinatesystem " + name + " " + ToString(m) + "\n";
    for (const std::string& dir : s.shaderSearchPath) text += "  searchpath shader " + dir + "\n";
    for (const std::string& dir : s.textureSearchPath) text += "  searchpath texture " + dir + "\n";
    for (const SceneDesc::MakeTextureDesc& m : s.makeTextures)
        text += "  maketexture " + m.picture + " " + m.texture + " " + m.swrap + " " + m.twrap + "\n";
    return text;
}

/// The scene after its camera: ToStringSettings, then the primitives, one per line
/// (ToString(SceneDesc)'s lines after the camera's).
inline std::string ToStringAfterCamera(const SceneDesc& s) {
    std::string text = ToStringSettings(s);
    for (const PrimitiveDesc& p : s.primitives)
        for (uint32_t i = 0; i < p.elements; ++i) text += "  " + ToString(p.Element(i)) + "\n";
    return text;
}

/// The scene's primitives with each of a mesh's elements a primitive of its own
/// (PrimitiveDesc::Element), in order: for tests and tools that look at faces one by one.
inline std::vector<PrimitiveDesc> ElementPrimitives(const SceneDesc& s) {
    std::vector<PrimitiveDesc> out;
    for (const PrimitiveDesc& p : s.primitives)
        for (uint32_t i = 0; i < p.elements; ++i) out.push_back(p.Element(i));
    return out;
}

/// ToString(SceneDesc)'s first line, without its newline, naming the scene's file as `path`.
inline std::string SceneHeadLine(const SceneDesc& s, const std::string& path) {
    std::string text = "scene " + path;
    if (s.frame) text += " frame " + std::to_string(*s.frame);
    if (!s.skipped.empty()) text += " skipped (" + s.skipped + ")";
    return text;
}

inline std::string ToString(const SceneDesc& s) {
    return SceneHeadLine(s, s.path) + "\n  camera " + ToString(s.camera) + "\n" + ToStringAfterCamera(s);
}

}  // namespace affray::renderer
