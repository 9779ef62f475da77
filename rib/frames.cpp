// rib/frames.cpp: frames and world blocks (FrameBegin, FrameEnd, WorldBegin, WorldEnd) and what
// only serves a scanline renderer's shadow passes (their frames, the Make* requests) and prman's
// other passes that make no image (photon maps, "null" displays). Each world
// block is one frame, a SceneDesc pushed at WorldEnd; FrameBegin saves the options (and the
// camera-space lights and coordinate systems) that FrameEnd restores, so options before the first
// frame are every frame's defaults (RI 3.2 section 4.1). Rules shared with rib.cpp are in
// rib/parser.h.
#include <algorithm>
#include <cmath>
#include <iterator>

#include "rib/parser.h"

namespace affray::rib {

namespace {

// Display types whose file is a shadow or depth map for a scanline renderer.
constexpr std::string_view kShadowDisplayTypes[] = {"zfile", "shadow", "deepshadow"};

}  // namespace

bool RibParser::ShadowMapTypeP(std::string_view type) {
    return std::find(std::begin(kShadowDisplayTypes), std::end(kShadowDisplayTypes), type) !=
           std::end(kShadowDisplayTypes);
}

bool RibParser::DoFrameBegin(const RibRequest& r) {
    if (r.args.size() != 1 || r.args[0].isArray || !r.args[0].NumericP())
        return Fail(r.at, "'FrameBegin' expects one frame number");
    const double number = r.args[0].numbers[0];
    if (!(number == std::floor(number) && std::fabs(number) <= 1e9))
        return Fail(r.args[0].at, "'FrameBegin' frame number must be an integer, got " + FormatNumber(number));
    if (!m_blocks.empty())
        return Fail(r.at, "'FrameBegin' inside " + Quote(BlockName(m_blocks.back().kind, false)) + " on line " +
                              std::to_string(m_blocks.back().at.line));
    if (m_worldSeen) return Fail(r.at, "'FrameBegin' after a 'WorldBegin' outside any frame");
    // The options in effect now are every frame's defaults: FrameEnd restores them.
    m_frameDefaults = FrameDefaults{m_scene,        m_archiveSearchPath, m_cameraLights,   m_cameraCoordinateSystems,
                                    m_lightHandles, m_options,           m_relativeDetail, m_resources,
                                    m_hider};
    m_scene.frame = static_cast<int>(number);
    m_scene.frameLine = r.at.line;
    return Begin(r, Block::Frame);
}

bool RibParser::DoFrameEnd(const RibRequest& r) {
    if (!NoArgs(r) || !End(r, Block::Frame)) return false;
    FrameDefaults& defaults = *m_frameDefaults;
    m_scene = std::move(defaults.scene);
    m_archiveSearchPath = std::move(defaults.archiveSearchPath);
    m_cameraLights = std::move(defaults.cameraLights);
    m_cameraCoordinateSystems = std::move(defaults.cameraCoordinateSystems);
    m_lightHandles = std::move(defaults.lightHandles);
    m_options = std::move(defaults.options);
    m_relativeDetail = defaults.relativeDetail;
    m_resources = std::move(defaults.resources);  // their lights are the frame's
    m_hider = std::move(defaults.hider);
    m_frameDefaults.reset();
    m_primitivesStamped = 0;
    m_worldSeen = m_worldEnded = false;
    return true;
}

std::string RibParser::SkipReason() const {
    const std::string& type = m_scene.displayType;
    const bool shadow = type == "shadow" || type == "deepshadow";
    // Depth alone to a file that is not OpenEXR (prman's "file" is a TIFF) is a depth map pass;
    // to OpenEXR it is affray's depth image.
    const bool depthOnly = m_scene.displayMode == "z" && type != "openexr" && type != "exr";
    const std::string display =
        "Display " + Quote(m_scene.displayName) + " " + Quote(type) + " " + Quote(m_scene.displayMode);
    // prman's photon map pass and its "null" display (a pass run for what its shaders write:
    // baked point clouds, brick maps) make no image either.
    if (m_hider == "photon") return "a photon map (Hider \"photon\") for a global illumination pass";
    if (type == "null") return "no image (" + display + "): a pass run for what its shaders write (baked maps)";
    if (!shadow && type != "zfile" && !depthOnly) return "";
    return std::string(shadow ? "a shadow map" : "a depth map") + " for a scanline renderer (" + display + ")";
}

bool RibParser::DoWorldBegin(const RibRequest& r) {
    if (!NoArgs(r)) return false;
    if (m_worldSeen)
        return Fail(r.at, m_frameDefaults ? "a second 'WorldBegin' in frame " + std::to_string(*m_scene.frame) +
                                                "; give each world its own 'FrameBegin'/'FrameEnd'"
                                          : "a second 'WorldBegin' outside frames; give each world its own "
                                            "'FrameBegin'/'FrameEnd'");
    // Exporters (Houdini) may wrap the camera transform and the world in TransformBegin or
    // AttributeBegin: the world starts from the transform current here all the same, and the block
    // restores what it saved after WorldEnd. (No other block can be open here: FrameBegin is
    // refused inside a block, and solids inside a world.)
    if (!m_blocks.empty() && m_blocks.back().kind != Block::Frame) {
        const std::string block = Quote(BlockName(m_blocks.back().kind, false));
        Note(r.at, "'WorldBegin' inside " + block +
                       ": the world starts from the transform current here (the camera transform), and " +
                       Quote(BlockName(m_blocks.back().kind, true)) + " after 'WorldEnd' ends the block");
    }
    // The CTM now is world -> camera; it must be invertible for rays to be generated.
    glm::dmat4 worldToCamera = m_state.ctm;
    double det = glm::determinant(worldToCamera);
    glm::dmat4 cameraToWorld = glm::inverse(worldToCamera);
    if (!(std::fabs(det) > 0) || !std::isfinite(det) || !FiniteP(cameraToWorld))
        return Fail(r.at, "the camera transform (the transform at 'WorldBegin') is singular");
    m_scene.camera.worldToCamera = worldToCamera;
    // A camera transform that moves (a motion block before WorldBegin): each of its matrices
    // must be invertible too. Lights and coordinate systems given before WorldBegin are placed
    // at its first time.
    m_scene.camera.motion = m_state.motion;
    if (m_state.motion)
        for (size_t i = 0; i < m_state.motion->matrices.size(); ++i) {
            const glm::dmat4& m = m_state.motion->matrices[i];
            const double d = glm::determinant(m);
            if (!(std::fabs(d) > 0) || !std::isfinite(d) || !FiniteP(glm::inverse(m)))
                return Fail(r.at, "the camera transform at time " + FormatNumber(m_state.motion->times[i]) +
                                      " (the moving transform at 'WorldBegin') is singular");
        }
    if (m_state.perspectiveFov > 0) {  // DoPerspective
        m_scene.camera.perspective = true;
        m_scene.camera.fovDegrees = m_state.perspectiveFov;
        m_state.perspectiveFov = 0;
    }
    if (!m_scene.camera.perspective && std::isfinite(m_scene.camera.fstop)) {
        Warn(r.at, "'DepthOfField' applies to perspective projections only; ignored: the orthographic camera is sharp");
        m_scene.camera.fstop = std::numeric_limits<double>::infinity();
    }
    // Lights given before WorldBegin come first, so their indices (LightSource) hold.
    for (LightDesc light : m_cameraLights) {
        light.from = TransformPoint(cameraToWorld, light.from);
        light.to = TransformPoint(cameraToWorld, light.to);
        if (light.shader) light.shader->shaderToWorld = cameraToWorld * light.shader->shaderToWorld;
        m_scene.lights.push_back(light);
    }
    m_cameraLights.clear();
    for (const auto& [name, objectToCamera] : m_cameraCoordinateSystems)
        m_scene.coordinateSystems[name] = cameraToWorld * objectToCamera;
    m_cameraCoordinateSystems.clear();
    if (!m_frameDefaults) m_scene.frameLine = r.at.line;
    m_scene.skipped = SkipReason();
    if (!m_scene.skipped.empty()) {
        const std::string what =
            m_frameDefaults ? "frame " + std::to_string(*m_scene.frame) : std::string("the world block");
        const RibPos at = m_frameDefaults ? m_blocks.front().at : r.at;  // FrameBegin opens no block inside another
        const char* why = m_hider == "photon"             ? "affray computes no global illumination"
                          : m_scene.displayType == "null" ? "affray's shaders write no files"
                                                          : "affray traces shadows";
        Note(at, what + " renders " + m_scene.skipped + "; " + why + ": skipped");
    }
    m_worldSeen = true;
    Begin(r, Block::World);
    m_state.ctm = glm::dmat4(1.0);
    m_state.motion = nullptr;
    return true;
}

// The world block ends: the frame is complete (a skipped one without its primitives).
bool RibParser::DoWorldEnd(const RibRequest& r) {
    if (!NoArgs(r) || !End(r, Block::World)) return false;
    // The primitives move into the frame (no geometry may follow WorldEnd, and FrameEnd restores
    // the scene of FrameBegin): a mesh of thousands of faces is not copied.
    std::vector<PrimitiveDesc> primitives = std::move(m_scene.primitives);
    m_scene.primitives.clear();
    SceneDesc frame = m_scene;
    if (frame.skipped.empty()) frame.primitives = std::move(primitives);
    // A texture is made when its request is read, as in RenderMan: every frame after it has it.
    frame.makeTextures = m_madeTextures;
    m_frames.push_back(std::move(frame));
    return true;
}

// MakeShadow, MakeTexture, MakeBump, MakeLatLongEnvironment, MakeCubeFaceEnvironment: they turn
// images into maps. MakeTexture "picture" "texture" "swrap" "twrap" "filter" swidth twidth
// [params] is recorded for every frame from there on (RenderMan makes the file when it reads the
// request), and Renderer::Prepare makes the texture (the filter and widths shape a scanline renderer's
// resampling and are not used; a failure is a warning). affray traces shadows and its shaders read
// no environment or bump maps, so the others are skipped with a note (their file names are not
// checked).
bool RibParser::DoMake(const RibRequest& r) {
    std::string picture;
    if (!LeadingString(r, "an image file name", &picture)) return false;
    if (r.name == "MakeShadow") {
        Note(r.at, "'MakeShadow' makes a shadow map for a scanline renderer; affray traces shadows: skipped");
        return true;
    }
    if (r.name != "MakeTexture") {
        Note(r.at, Quote(r.name) + " makes a map that affray's shaders cannot read yet: skipped");
        return true;
    }
    // The texture name and the wrap modes, strings; the filter's name and widths.
    const char* what[] = {"a texture file name", "an s wrap mode", "a t wrap mode", "a filter name"};
    std::string strings[4];
    for (size_t i = 1; i <= 4; ++i) {
        if (r.args.size() <= i || r.args[i].isArray || r.args[i].strings.size() != 1)
            return Fail(i < r.args.size() ? r.args[i].at : r.at,
                        "'MakeTexture' argument " + std::to_string(i + 1) + " must be " + what[i - 1]);
        strings[i - 1] = r.args[i].strings[0];
    }
    for (size_t i = 5; i <= 6; ++i)
        if (r.args.size() <= i || r.args[i].isArray || r.args[i].numbers.size() != 1)
            return Fail(i < r.args.size() ? r.args[i].at : r.at,
                        "'MakeTexture' argument " + std::to_string(i + 1) + " must be a filter width");
    std::vector<RibParam> params;
    if (!ParamList(r, 7, &params)) return false;
    SceneDesc::MakeTextureDesc make;
    make.picture = picture;
    make.texture = strings[0];
    for (int i = 0; i < 2; ++i) {
        const std::string& w = strings[1 + i];
        if (w != "periodic" && w != "clamp" && w != "black")
            return Fail(r.args[2 + i].at, "'MakeTexture' wrap mode " + Quote(w) + " is not periodic, clamp or black");
        (i == 0 ? make.swrap : make.twrap) = w;
    }
    for (const RibParam& p : params) Warn(p.at, "'MakeTexture' parameter " + Quote(p.value.name) + " ignored");
    make.line = r.at.line;
    make.column = r.at.column;
    make.file = FileOf(r.at);
    m_madeTextures.push_back(make);
    return true;
}

}  // namespace affray::rib
