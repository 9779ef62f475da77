// renderer/rib.cpp: the RIB request dispatcher; builds a SceneDesc from requests.
// Owns the meaning of each request (RI Spec 3.2) and the graphics state: the current transform
// (CTM), color, surface and displacement, saved and restored by the Begin/End blocks. To add a
// request: write a handler, list it in Dispatch(), and take it out of kIgnored / kUnsupported.
// Handlers return false after Fail(); the first error ends the parse.
//
// Transform convention: RenderMan premultiplies row vectors, so "concatenate T" is, in GLM's
// column-vector terms, CTM = CTM * T (the last transform given applies to the object first). A RIB
// matrix is 16 numbers row-major for row vectors; loaded column-major into a glm::dmat4 it is
// already the transposed, column-vector matrix. The CTM at WorldBegin is world->camera.
#include "renderer/rib.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <glm/gtc/matrix_transform.hpp>
#include <iterator>
#include <set>
#include <system_error>
#include <unordered_map>

#include "renderer/rib_parser.h"

namespace affray::renderer {
namespace {

// clang-format off
// RI 3.2 requests whose absence changes only appearance, sampling or bookkeeping: skipped with one
// warning per name.
constexpr std::string_view kIgnored[] = {
    "ArchiveRecord", "AreaLightSource", "Atmosphere", "Attribute", "Basis", "Begin", "Bound",
    "Clipping", "ClippingPlane", "ColorSamples", "CoordinateSystem", "CropWindow", "Declare",
    "DepthOfField", "Detail", "DetailRange", "End", "ErrorHandler", "Exposure", "Exterior",
    "FrameAspectRatio", "GeometricApproximation", "Hider", "Illuminate", "Imager", "Interior",
    "MakeBump", "MakeCubeFaceEnvironment", "MakeLatLongEnvironment", "MakeShadow", "MakeTexture",
    "Matte", "Opacity", "Option", "Orientation", "PixelFilter", "PixelSamples", "PixelVariance",
    "Quantize", "RelativeDetail", "ReverseOrientation", "ScreenWindow", "ShadingInterpolation",
    "ShadingRate", "Shutter", "Sides", "TextureCoordinates", "TransformPoints", "TrimCurve",
};

// RI 3.2 requests that create or move geometry: ignoring them would render the wrong scene, so
// they are errors until implemented.
constexpr std::string_view kUnsupported[] = {
    "Blobby", "Cone", "CoordSysTransform", "Curves", "Cylinder", "Deformation", "Disk",
    "GeneralPolygon", "Geometry", "Hyperboloid", "MotionBegin", "MotionEnd", "NuPatch",
    "ObjectBegin", "ObjectEnd", "ObjectInstance", "Paraboloid", "PatchMesh", "Perspective",
    "Points", "PointsGeneralPolygons", "PointsPolygons", "Polygon", "Procedural", "ReadArchive",
    "Skew", "SolidBegin", "SolidEnd", "Sphere", "SubdivisionMesh", "Torus",
};
// clang-format on

constexpr int kMaxResolution = 65536;

bool ContainsP(const std::string_view* begin, const std::string_view* end, std::string_view name) {
    return std::find(begin, end, name) != end;
}

}  // namespace

std::optional<SceneDesc> RibParser::Run(std::string* error) {
    RibRequest request;
    std::string message;
    int line = 0;
    bool ok = true;
    for (;;) {
        RibRequestReader::Status status = m_reader.Next(&request, &message, &line);
        if (status == RibRequestReader::Status::End) break;
        if (status == RibRequestReader::Status::Error) {
            ok = Fail(line, message);
            break;
        }
        if (!Dispatch(request)) {
            ok = false;
            break;
        }
    }
    if (ok && !m_blocks.empty()) {
        const OpenBlock& open = m_blocks.back();
        ok = Fail(open.line, Quote(BlockName(open.kind, false)) + " has no matching " +
                                 Quote(BlockName(open.kind, true)));
    }
    if (ok && !m_worldSeen)
        ok = Fail(m_reader.LastLine(), "no 'WorldBegin': the file describes no scene");
    if (!ok) {
        if (error)
            *error = m_path + ":" + std::to_string(m_errorLine) + ": error: " + m_errorMessage;
        return std::nullopt;
    }
    return std::move(m_scene);
}

bool RibParser::Dispatch(const RibRequest& r) {
    static const std::unordered_map<std::string_view, Handler> kHandlers = {
        {"Format", &RibParser::DoFormat},
        {"Projection", &RibParser::DoProjection},
        {"Display", &RibParser::DoDisplay},
        {"FrameBegin", &RibParser::DoFrameBegin},
        {"FrameEnd", &RibParser::DoFrameEnd},
        {"WorldBegin", &RibParser::DoWorldBegin},
        {"WorldEnd", &RibParser::DoWorldEnd},
        {"AttributeBegin", &RibParser::DoAttributeBegin},
        {"AttributeEnd", &RibParser::DoAttributeEnd},
        {"TransformBegin", &RibParser::DoTransformBegin},
        {"TransformEnd", &RibParser::DoTransformEnd},
        {"Identity", &RibParser::DoIdentity},
        {"Transform", &RibParser::DoTransform},
        {"ConcatTransform", &RibParser::DoConcatTransform},
        {"Translate", &RibParser::DoTranslate},
        {"Rotate", &RibParser::DoRotate},
        {"Scale", &RibParser::DoScale},
        {"Color", &RibParser::DoColor},
        {"Surface", &RibParser::DoSurface},
        {"Displacement", &RibParser::DoDisplacement},
        {"LightSource", &RibParser::DoLightSource},
        {"Patch", &RibParser::DoPatch},
        {"version", &RibParser::DoVersion},
    };
    if (auto it = kHandlers.find(r.name); it != kHandlers.end()) return (this->*(it->second))(r);
    if (ContainsP(std::begin(kIgnored), std::end(kIgnored), r.name)) {
        Warn(r.line, "request " + Quote(r.name) + " is not supported yet; ignored");
        return true;
    }
    if (ContainsP(std::begin(kUnsupported), std::end(kUnsupported), r.name))
        return Fail(r.line, Quote(r.name) + " is not supported yet");
    return Fail(r.line, "unknown RIB request " + Quote(r.name));
}

void RibParser::Warn(int line, const std::string& message) {
    if (!m_warned.insert(message).second) return;
    if (m_warnings)
        m_warnings->push_back(m_path + ":" + std::to_string(line) + ": warning: " + message);
}

const char* RibParser::BlockName(Block kind, bool end) {
    switch (kind) {
        case Block::Frame:
            return end ? "FrameEnd" : "FrameBegin";
        case Block::World:
            return end ? "WorldEnd" : "WorldBegin";
        case Block::Attribute:
            return end ? "AttributeEnd" : "AttributeBegin";
        case Block::Transform:
            return end ? "TransformEnd" : "TransformBegin";
    }
    return "?";
}

bool RibParser::SetCtm(const RibRequest& r, const glm::dmat4& ctm) {
    if (!FiniteP(ctm)) return Fail(r.line, Quote(r.name) + " makes the current transform overflow");
    m_state.ctm = ctm;
    return true;
}

bool RibParser::FiniteP(const glm::dmat4& m) {
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
            if (!std::isfinite(m[c][r])) return false;
    return true;
}

bool RibParser::FiniteP(const glm::dvec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

bool RibParser::BeforeWorld(const RibRequest& r) {
    if (!m_worldSeen) return true;
    return Fail(r.line, Quote(r.name) + " is an option and must come before 'WorldBegin'");
}

bool RibParser::InsideWorld(const RibRequest& r) {
    for (const OpenBlock& b : m_blocks)
        if (b.kind == Block::World) return true;
    return Fail(r.line, Quote(r.name) + " must come between 'WorldBegin' and 'WorldEnd'");
}

bool RibParser::Begin(const RibRequest& r, Block kind) {
    m_blocks.push_back({kind, r.line, m_state});
    return true;
}

bool RibParser::End(const RibRequest& r, Block kind) {
    bool anyOpen = std::any_of(m_blocks.begin(), m_blocks.end(),
                               [&](const OpenBlock& b) { return b.kind == kind; });
    if (!anyOpen)
        return Fail(r.line, Quote(r.name) + " without matching " + Quote(BlockName(kind, false)));
    const OpenBlock& open = m_blocks.back();
    if (open.kind != kind)
        return Fail(r.line, Quote(r.name) + " does not match " +
                                Quote(BlockName(open.kind, false)) + " on line " +
                                std::to_string(open.line));
    // TransformEnd restores only the transform; every other block restores all attributes.
    if (kind == Block::Transform)
        m_state.ctm = open.saved.ctm;
    else
        m_state = open.saved;
    if (kind == Block::World) m_worldEnded = true;
    m_blocks.pop_back();
    return true;
}

// ---- options ----

bool RibParser::DoFormat(const RibRequest& r) {
    double v[3];
    if (!BeforeWorld(r) || !Numbers(r, 3, "xresolution yresolution pixelaspectratio", v))
        return false;
    const char* names[2] = {"xresolution", "yresolution"};
    for (int i = 0; i < 2; ++i)
        if (!(v[i] >= 1 && v[i] <= kMaxResolution && v[i] == std::floor(v[i])))
            return Fail(r.line, std::string("'Format' ") + names[i] +
                                    " must be an integer from 1 to " +
                                    std::to_string(kMaxResolution) + ", got " + FormatNumber(v[i]));
    if (!(v[2] > 0))
        return Fail(r.line,
                    "'Format' pixelaspectratio must be positive, got " + FormatNumber(v[2]));
    m_scene.camera.xres = static_cast<int>(v[0]);
    m_scene.camera.yres = static_cast<int>(v[1]);
    m_scene.camera.pixelAspect = v[2];
    return true;
}

bool RibParser::DoProjection(const RibRequest& r) {
    std::string name;
    std::vector<RibParam> params;
    if (!BeforeWorld(r) || !LeadingString(r, "a projection name", &name) ||
        !ParamList(r, 1, &params))
        return false;
    CameraDesc& camera = m_scene.camera;
    if (name == "perspective") {
        camera.perspective = true;
        camera.fovDegrees = 90;
        for (const RibParam& p : params) {
            if (p.value.name != "fov") {
                Warn(p.line, "'Projection' parameter " + Quote(p.value.name) +
                                 " is not supported; ignored");
                continue;
            }
            if (!ParamNumbers(p, "'Projection'", 1, &camera.fovDegrees)) return false;
            if (!(camera.fovDegrees > 0 && camera.fovDegrees < 180))
                return Fail(p.line, "'Projection' fov must be between 0 and 180 degrees, got " +
                                        FormatNumber(camera.fovDegrees));
        }
    } else if (name == "orthographic") {
        camera.perspective = false;
        for (const RibParam& p : params)
            Warn(p.line,
                 "'Projection' parameter " + Quote(p.value.name) + " is not supported; ignored");
    } else {
        return Fail(r.line, "projection " + Quote(name) + " is not supported yet");
    }
    // RI 3.2: transforms before Projection form the screen transform; Projection then resets the
    // CTM to identity and what follows is the camera transform.
    if (m_state.ctm != glm::dmat4(1.0))
        Warn(r.line,
             "transforms before 'Projection' (screen transforms) are not supported; ignored");
    m_state.ctm = glm::dmat4(1.0);
    return true;
}

bool RibParser::DoDisplay(const RibRequest& r) {
    if (!BeforeWorld(r)) return false;
    for (size_t i = 0; i < 3; ++i)
        if (i >= r.args.size() || r.args[i].isArray || !r.args[i].StringsP())
            return Fail(r.line, "'Display' expects 3 strings (name type mode)");
    std::vector<RibParam> params;  // display parameters are checked but none is used
    if (!ParamList(r, 3, &params)) return false;
    const std::string& name = r.args[0].strings[0];
    if (!name.empty() && name[0] == '+') {
        Warn(r.line, "additional display " + Quote(name) + " is not supported yet; ignored");
        return true;
    }
    if (name.empty()) return Fail(r.args[0].line, "'Display' name must not be empty");
    m_scene.displayName = name;
    m_scene.displayType = r.args[1].strings[0];
    m_scene.displayMode = r.args[2].strings[0];
    const std::string& type = m_scene.displayType;
    if (type != "file" && type != "openexr" && type != "exr")
        Warn(r.line, "display type " + Quote(type) + " is not supported; writing an OpenEXR file");
    return true;
}

// ---- blocks ----

bool RibParser::DoFrameBegin(const RibRequest& r) {
    if (r.args.size() > 1 || (r.args.size() == 1 && (r.args[0].isArray || !r.args[0].NumericP())))
        return Fail(r.line, "'FrameBegin' expects one frame number");
    if (!m_blocks.empty())
        return Fail(r.line, "'FrameBegin' inside " + Quote(BlockName(m_blocks.back().kind, false)) +
                                " on line " + std::to_string(m_blocks.back().line));
    if (m_worldSeen) return Fail(r.line, "a second frame is not supported yet");
    return Begin(r, Block::Frame);
}

bool RibParser::DoWorldBegin(const RibRequest& r) {
    if (!NoArgs(r)) return false;
    if (m_worldSeen)
        return Fail(r.line, "a second 'WorldBegin' (several frames) is not supported yet");
    if (!m_blocks.empty() && m_blocks.back().kind != Block::Frame)
        return Fail(r.line, "'WorldBegin' inside " + Quote(BlockName(m_blocks.back().kind, false)) +
                                " on line " + std::to_string(m_blocks.back().line));
    // The CTM now is world -> camera; it must be invertible for rays to be generated.
    glm::dmat4 worldToCamera = m_state.ctm;
    double det = glm::determinant(worldToCamera);
    glm::dmat4 cameraToWorld = glm::inverse(worldToCamera);
    if (!(std::fabs(det) > 0) || !std::isfinite(det) || !FiniteP(cameraToWorld))
        return Fail(r.line, "the camera transform (the transform at 'WorldBegin') is singular");
    m_scene.camera.worldToCamera = worldToCamera;
    for (LightDesc light : m_cameraLights) {
        light.from = TransformPoint(cameraToWorld, light.from);
        light.to = TransformPoint(cameraToWorld, light.to);
        m_scene.lights.push_back(light);
    }
    m_cameraLights.clear();
    m_worldSeen = true;
    Begin(r, Block::World);
    m_state.ctm = glm::dmat4(1.0);
    return true;
}

// ---- transforms ----

bool RibParser::DoTransform(const RibRequest& r) {
    glm::dmat4 m;
    return Matrix(r, &m) && SetCtm(r, m);
}

bool RibParser::DoConcatTransform(const RibRequest& r) {
    glm::dmat4 m;
    return Matrix(r, &m) && SetCtm(r, m_state.ctm * m);
}

bool RibParser::DoTranslate(const RibRequest& r) {
    double v[3];
    return Numbers(r, 3, "dx dy dz", v) &&
           SetCtm(r, glm::translate(m_state.ctm, glm::dvec3(v[0], v[1], v[2])));
}

bool RibParser::DoRotate(const RibRequest& r) {
    double v[4];
    if (!Numbers(r, 4, "angle dx dy dz", v)) return false;
    glm::dvec3 axis(v[1], v[2], v[3]);
    double length = glm::length(axis);
    if (!(length > 0) || !std::isfinite(length))
        return Fail(r.line, "'Rotate' axis must not be zero");
    return SetCtm(r, glm::rotate(m_state.ctm, glm::radians(v[0]), axis / length));
}

bool RibParser::DoScale(const RibRequest& r) {
    double v[3];
    return Numbers(r, 3, "sx sy sz", v) &&
           SetCtm(r, glm::scale(m_state.ctm, glm::dvec3(v[0], v[1], v[2])));
}

std::optional<SceneDesc> ParseRib(std::string_view text, const std::string& pathForMessages,
                                  std::string* error, std::vector<std::string>* warnings) {
    if (text.size() >= 2 && static_cast<unsigned char>(text[0]) == 0x1f &&
        static_cast<unsigned char>(text[1]) == 0x8b) {
        if (error) *error = pathForMessages + ":1: error: gzip-compressed RIB is not supported yet";
        return std::nullopt;
    }
    RibParser parser(text, pathForMessages, warnings);
    return parser.Run(error);
}

std::optional<SceneDesc> ReadRib(const std::string& path, std::string* error,
                                 std::vector<std::string>* warnings) {
    auto fail = [&](const std::string& reason) {
        if (error) *error = path + ": error: cannot read file: " + reason;
        return std::nullopt;
    };
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec)) return fail("it is a directory");
    errno = 0;
    std::ifstream in(path, std::ios::binary);
    if (!in) return fail(errno ? std::generic_category().message(errno) : "cannot open");
    std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    if (in.bad()) return fail("read error");
    return ParseRib(text, path, error, warnings);
}

}  // namespace affray::renderer
