// rib/frames.cpp: frames and world blocks (FrameBegin, FrameEnd, WorldBegin, WorldEnd) and what
// only serves a scanline renderer's shadow passes (their frames, the Make* requests). Each world
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
    m_frameDefaults =
        FrameDefaults{m_scene, m_archiveSearchPath, m_cameraLights, m_cameraCoordinateSystems, m_lightHandles};
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
    if (!shadow && type != "zfile" && !depthOnly) return "";
    return std::string(shadow ? "a shadow map" : "a depth map") + " for a scanline renderer (Display " +
           Quote(m_scene.displayName) + " " + Quote(type) + " " + Quote(m_scene.displayMode) + ")";
}

bool RibParser::DoWorldBegin(const RibRequest& r) {
    if (!NoArgs(r)) return false;
    if (m_worldSeen)
        return Fail(r.at, m_frameDefaults ? "a second 'WorldBegin' in frame " + std::to_string(*m_scene.frame) +
                                                "; give each world its own 'FrameBegin'/'FrameEnd'"
                                          : "a second 'WorldBegin' outside frames; give each world its own "
                                            "'FrameBegin'/'FrameEnd'");
    if (!m_blocks.empty() && m_blocks.back().kind != Block::Frame)
        return Fail(r.at, "'WorldBegin' inside " + Quote(BlockName(m_blocks.back().kind, false)) + " on line " +
                              std::to_string(m_blocks.back().at.line));
    // The CTM now is world -> camera; it must be invertible for rays to be generated.
    glm::dmat4 worldToCamera = m_state.ctm;
    double det = glm::determinant(worldToCamera);
    glm::dmat4 cameraToWorld = glm::inverse(worldToCamera);
    if (!(std::fabs(det) > 0) || !std::isfinite(det) || !FiniteP(cameraToWorld))
        return Fail(r.at, "the camera transform (the transform at 'WorldBegin') is singular");
    m_scene.camera.worldToCamera = worldToCamera;
    // Lights given before WorldBegin come first, so their indices (LightSource) hold.
    for (LightDesc light : m_cameraLights) {
        light.from = TransformPoint(cameraToWorld, light.from);
        light.to = TransformPoint(cameraToWorld, light.to);
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
        const RibPos at = m_frameDefaults ? m_blocks.back().at : r.at;
        Note(at, what + " renders " + m_scene.skipped + "; affray traces shadows: skipped");
    }
    m_worldSeen = true;
    Begin(r, Block::World);
    m_state.ctm = glm::dmat4(1.0);
    return true;
}

// The world block ends: the frame is complete (a skipped one without its primitives).
bool RibParser::DoWorldEnd(const RibRequest& r) {
    if (!NoArgs(r) || !End(r, Block::World)) return false;
    SceneDesc frame = m_scene;
    if (!frame.skipped.empty()) frame.primitives.clear();
    m_frames.push_back(std::move(frame));
    return true;
}

// MakeShadow, MakeTexture, MakeBump, MakeLatLongEnvironment, MakeCubeFaceEnvironment: they turn
// images into maps that shaders of a scanline renderer read. affray traces shadows and its
// shaders read no textures, so each is skipped with a note (its file names are not checked).
bool RibParser::DoMake(const RibRequest& r) {
    std::string picture;
    if (!LeadingString(r, "an image file name", &picture)) return false;
    if (r.name == "MakeShadow")
        Note(r.at, "'MakeShadow' makes a shadow map for a scanline renderer; affray traces shadows: skipped");
    else
        Note(r.at, Quote(r.name) + " makes a texture map, which affray's shaders cannot read yet: skipped");
    return true;
}

}  // namespace affray::rib
