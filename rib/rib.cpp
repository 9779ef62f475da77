// rib/rib.cpp: the RIB request dispatcher; builds a SceneDesc from requests.
// Owns the meaning of each request (RI Spec 3.2), the options (here) and the graphics state: the
// current transform (CTM), color, surface, displacement, sides and orientation, saved and
// restored by the Begin/End blocks. To add a request: write a handler (attributes and lights in
// attributes.cpp, geometry in geometry.cpp, archives and objects in archive.cpp), list it in
// Dispatch(), and take it out of the lists of unsupported.cpp. Handlers return false after
// Fail(); the first error ends the parse. Run() reads the innermost open file (see archive.cpp).
// Frames and world blocks, and the requests that only serve shadow passes, are in frames.cpp.
// Longer than most files: the options are many small handlers that share the placement rules.
//
// Transform convention: RenderMan premultiplies row vectors, so "concatenate T" is, in GLM's
// column-vector terms, CTM = CTM * T (the last transform given applies to the object first). A RIB
// matrix is 16 numbers row-major for row vectors; loaded column-major into a glm::dmat4 it is
// already the transposed, column-vector matrix. The CTM at WorldBegin is world->camera.
#include "rib/rib.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <glm/gtc/matrix_transform.hpp>
#include <set>
#include <system_error>
#include <unordered_map>

#include "diag/limits.h"
#include "rib/file.h"
#include "rib/parser.h"
#include "scene/display.h"

namespace affray::rib {
namespace {

// RI 3.2 requests that make texture, environment and shadow maps from images (DoMake).
constexpr std::string_view kMakeRequests[] = {"MakeBump", "MakeCubeFaceEnvironment", "MakeLatLongEnvironment",
                                              "MakeShadow", "MakeTexture"};

// The requests that open and close the blocks of m_blocks.
constexpr std::string_view kBlockRequests[] = {"FrameBegin",     "FrameEnd",     "WorldBegin",     "WorldEnd",
                                               "AttributeBegin", "AttributeEnd", "TransformBegin", "TransformEnd",
                                               "SolidBegin",     "SolidEnd"};

constexpr int kMaxResolution = 65536;

bool ContainsP(const std::string_view* begin, const std::string_view* end, std::string_view name) {
    return std::find(begin, end, name) != end;
}

}  // namespace

namespace {

// Marks the request and its arguments as read from file `file` (RibPos::file).
void StampFile(RibRequest* r, int file) {
    r->at.file = file;
    for (RibArg& arg : r->args) arg.at.file = file;
}

}  // namespace

std::optional<std::vector<SceneDesc>> RibParser::Run() {
    RibRequest request;
    std::string message;
    RibPos at;
    bool ok = true;
    for (;;) {
        OpenReader& current = m_readers.back();
        RibRequestReader::Status status = RibRequestReader::Status::End;
        if (!current.inlineRequests)
            status = current.reader.Next(&request, &message, &at);
        else if (current.next < current.inlineRequests->size())
            request = (*current.inlineRequests)[current.next++], status = RibRequestReader::Status::Ok;
        if (status == RibRequestReader::Status::End) {
            if (m_readers.size() == 1) break;
            const OpenReader done = std::move(m_readers.back());
            m_readers.pop_back();  // the end of an archive: back to the file that read it
            if (!EndArchive(done)) {
                ok = false;
                break;
            }
            continue;
        }
        if (status == RibRequestReader::Status::Error) {
            at.file = current.file;
            ok = Fail(at, message);
            break;
        }
        if (!current.inlineRequests) StampFile(&request, current.file);
        // An inline archive's requests are kept as written, conditionals included, until
        // ReadArchive reads them.
        if (m_archiveDef) {
            if (!RecordArchive(request)) {
                ok = false;
                break;
            }
            continue;
        }
        bool consumed = false;
        if (!Conditional(request, &consumed)) {
            ok = false;
            break;
        }
        if (consumed) continue;
        // ArchiveBegin defines at once, in an object definition too (as Declare does).
        const bool archive = request.name == "ArchiveBegin" || request.name == "ArchiveEnd";
        if (!(archive ? DoArchiveBegin(request) : m_defining ? Record(request) : Dispatch(request))) {
            ok = false;
            break;
        }
    }
    if (ok && m_archiveDef) ok = Fail(m_archiveDef->at, "'ArchiveBegin' has no matching 'ArchiveEnd'");
    if (ok && m_defining) ok = Fail(m_defining->second.at, "'ObjectBegin' has no matching 'ObjectEnd'");
    if (ok && m_motion) ok = Fail(m_motion->at, "'MotionBegin' has no matching 'MotionEnd'");
    if (ok && !m_conditionals.empty()) ok = Fail(m_conditionals.back().at, "'IfBegin' has no matching 'IfEnd'");
    if (ok && !m_resourceScopes.empty())
        ok = Fail(m_resourceScopes.back().first, "'ResourceBegin' has no matching 'ResourceEnd'");
    if (ok && !m_blocks.empty()) {
        const OpenBlock& open = m_blocks.back();
        ok =
            Fail(open.at, Quote(BlockName(open.kind, false)) + " has no matching " + Quote(BlockName(open.kind, true)));
    }
    if (ok && m_frames.empty())
        ok = Fail(m_readers.front().reader.LastPos(), "no 'WorldBegin': the file describes no scene");
    if (!ok) {
        if (m_report) {
            m_report->error(Where(m_errorAt), m_errorMessage);
            if (m_errorNote) m_report->note(Where(m_errorNote->first), m_errorNote->second);
        }
        return std::nullopt;
    }
    return std::move(m_frames);
}

namespace {

/// The requests that change the CTM and nothing else that moves: a motion block of them moves
/// the CTM (RibParser::Dispatch).
constexpr std::string_view kCtmRequests[] = {
    "ConcatTransform", "CoordSysTransform", "Identity", "Perspective", "Rotate", "Scale", "Skew",
    "Transform",       "Translate"};

}  // namespace

bool RibParser::Dispatch(const RibRequest& r) {
    ++m_requestSerial;  // the primitives of one request share their attributes (SetPrimitiveAttributes)
    // Inside a solid that affray skips, only the requests that open and close blocks run, so
    // that the blocks still nest as written and the solid ends at its own SolidEnd.
    if (m_skipping > 0 && !ContainsP(std::begin(kBlockRequests), std::end(kBlockRequests), r.name)) return true;
    // MotionBegin [t0 t1 ...] holds one request of a kind per time. A block of transforms moves
    // the CTM: each sample runs on the CTM at its time, and the primitives that follow move
    // with it (MotionPath). Of any other block (deformation, a moving light or shader) the
    // first sample (the shutter-open one, as exporters write them) runs and the others are
    // checked for kind and skipped.
    if (r.name == "MotionBegin") {
        if (m_motion)
            return Fail(r.at, "'MotionBegin' inside the motion block started on " + LineName(m_motion->at, r.at));
        const bool array = r.args.size() == 1 && r.args[0].isArray;
        const std::vector<double> times = array ? r.args[0].numbers : std::vector<double>{};
        if (!array || !r.args[0].NumericP() || times.empty())
            return Fail(r.at, "'MotionBegin' expects an array of the times of its samples");
        for (size_t i = 0; i < times.size(); ++i)
            if (!std::isfinite(times[i]) || (i > 0 && !(times[i] > times[i - 1])))
                return Fail(r.args[0].at, "'MotionBegin' times must be finite and increasing");
        m_motion = Motion{r.at, times, "", 0, {}, {}, {}};
        return true;
    }
    if (r.name == "MotionEnd") {
        if (!NoArgs(r)) return false;
        if (!m_motion) return Fail(r.at, "'MotionEnd' without matching 'MotionBegin'");
        const Motion motion = std::move(*m_motion);
        m_motion.reset();
        if (motion.count != motion.times.size())
            return Fail(r.at, "the motion block started on " + LineName(motion.at, r.at) + " has " +
                                  std::to_string(motion.count) + " request" + (motion.count == 1 ? "" : "s") + " for " +
                                  std::to_string(motion.times.size()) + " times");
        if (!motion.ctms.empty()) {
            m_state.ctm = motion.ctms.front();
            m_state.motion = renderer::MotionPath::Make(motion.times, motion.ctms);
        }
        return true;
    }
    if (m_motion) {
        Motion& motion = *m_motion;
        if (motion.count == 0) motion.request = r.name;
        if (r.name != motion.request)
            return Fail(r.at, "a motion block holds one kind of request, one per time: " + Quote(r.name) + " after " +
                                  Quote(motion.request));
        if (motion.count == motion.times.size())
            return Fail(r.at, "the motion block started on " + LineName(motion.at, r.at) +
                                  " has more requests than its " + std::to_string(motion.times.size()) + " times");
        const size_t sample = motion.count++;
        if (ContainsP(std::begin(kCtmRequests), std::end(kCtmRequests), r.name)) {
            if (sample == 0) {
                motion.ctmBefore = m_state.ctm;
                motion.pathBefore = m_state.motion;
            }
            // A CTM that moved already is taken at this sample's time (its own times in between
            // are not kept: the block's times are the path's).
            m_state.ctm = renderer::MatrixAt(motion.pathBefore.get(), motion.ctmBefore, motion.times[sample]);
            m_state.motion = nullptr;
            if (!DispatchRequest(r)) return false;
            motion.ctms.push_back(m_state.ctm);
            return true;
        }
        if (sample > 0) return true;
        Warn(motion.at, "motion blur of " + Quote(r.name) +
                            " is not rendered: its motion block takes its first sample (time " +
                            FormatNumber(motion.times[0]) + ")");
    } else if (m_state.motion && ContainsP(std::begin(kCtmRequests), std::end(kCtmRequests), r.name)) {
        return OnEveryTime(r);
    }
    return DispatchRequest(r);
}

bool RibParser::OnEveryTime(const RibRequest& r) {
    const std::shared_ptr<const renderer::MotionPath> path = m_state.motion;
    std::vector<glm::dmat4> ctms;
    for (const glm::dmat4& m : path->matrices) {
        m_state.ctm = m;
        m_state.motion = nullptr;
        if (!DispatchRequest(r)) return false;
        ctms.push_back(m_state.ctm);
    }
    m_state.ctm = ctms.front();
    m_state.motion = renderer::MotionPath::Make(path->times, ctms);
    return true;
}

void RibParser::WarnIfMoving(const RibRequest& r, const std::string& what) {
    if (!m_state.motion) return;
    Warn(r.at, Quote(r.name) + " under a moving transform is placed where the transform is at its first time (" +
                   FormatNumber(m_state.motion->times.front()) + "): " + what + " do not move");
}

bool RibParser::DispatchRequest(const RibRequest& r) {
    static const std::unordered_map<std::string_view, Handler> kHandlers = {
        {"Format", &RibParser::DoFormat},
        {"Projection", &RibParser::DoProjection},
        {"Perspective", &RibParser::DoPerspective},
        {"Display", &RibParser::DoDisplay},
        {"DisplayChannel", &RibParser::DoDisplayChannel},
        {"FrameAspectRatio", &RibParser::DoFrameAspectRatio},
        {"ScreenWindow", &RibParser::DoScreenWindow},
        {"CropWindow", &RibParser::DoCropWindow},
        {"Clipping", &RibParser::DoClipping},
        {"DepthOfField", &RibParser::DoDepthOfField},
        {"Shutter", &RibParser::DoShutter},
        {"PixelSamples", &RibParser::DoPixelSamples},
        {"PixelFilter", &RibParser::DoPixelFilter},
        {"Exposure", &RibParser::DoExposure},
        {"Imager", &RibParser::DoImager},
        {"Option", &RibParser::DoOption},
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
        {"Opacity", &RibParser::DoOpacity},
        {"Attribute", &RibParser::DoAttribute},
        {"Sides", &RibParser::DoSides},
        {"ReverseOrientation", &RibParser::DoReverseOrientation},
        {"Orientation", &RibParser::DoOrientation},
        {"CoordinateSystem", &RibParser::DoCoordinateSystem},
        {"ScopedCoordinateSystem", &RibParser::DoCoordinateSystem},
        {"Surface", &RibParser::DoSurface},
        {"Displacement", &RibParser::DoDisplacement},
        {"Atmosphere", &RibParser::DoAtmosphere},
        {"Points", &RibParser::DoPoints},
        {"Curves", &RibParser::DoCurves},
        {"LightSource", &RibParser::DoLightSource},
        {"Basis", &RibParser::DoBasis},
        {"Patch", &RibParser::DoPatch},
        {"PatchMesh", &RibParser::DoPatchMesh},
        {"NuPatch", &RibParser::DoNuPatch},
        {"TrimCurve", &RibParser::DoTrimCurve},
        {"Sphere", &RibParser::DoSphere},
        {"Cylinder", &RibParser::DoCylinder},
        {"Cone", &RibParser::DoCone},
        {"Disk", &RibParser::DoDisk},
        {"Torus", &RibParser::DoTorus},
        {"Hyperboloid", &RibParser::DoHyperboloid},
        {"Paraboloid", &RibParser::DoParaboloid},
        {"Polygon", &RibParser::DoPolygon},
        {"GeneralPolygon", &RibParser::DoGeneralPolygon},
        {"PointsPolygons", &RibParser::DoPointsPolygons},
        {"PointsGeneralPolygons", &RibParser::DoPointsGeneralPolygons},
        {"SubdivisionMesh", &RibParser::DoSubdivisionMesh},
        {"HierarchicalSubdivisionMesh", &RibParser::DoSubdivisionMesh},
        {"version", &RibParser::DoVersion},
        {"Hider", &RibParser::DoHider},
        {"Declare", &RibParser::DoDeclare},
        {"ShadingRate", &RibParser::DoShadingRate},
        {"GeometricApproximation", &RibParser::DoGeometricApproximation},
        {"ShadingInterpolation", &RibParser::DoShadingInterpolation},
        {"TextureCoordinates", &RibParser::DoTextureCoordinates},
        {"Detail", &RibParser::DoDetail},
        {"DetailRange", &RibParser::DoDetailRange},
        {"RelativeDetail", &RibParser::DoRelativeDetail},
        {"ArchiveRecord", &RibParser::DoArchiveRecord},
        {"Illuminate", &RibParser::DoIlluminate},
        {"Skew", &RibParser::DoSkew},
        {"SolidBegin", &RibParser::DoSolidBegin},
        {"SolidEnd", &RibParser::DoSolidEnd},
        {"ReadArchive", &RibParser::DoReadArchive},
        {"Procedural", &RibParser::DoProcedural},
        {"Procedural2", &RibParser::DoProcedural},
        {"ObjectBegin", &RibParser::DoObjectBegin},
        {"ObjectEnd", &RibParser::DoObjectEnd},
        {"ObjectInstance", &RibParser::DoObjectInstance},
        {"CoordSysTransform", &RibParser::DoCoordSysTransform},
        {"Resource", &RibParser::DoResource},
        {"ResourceBegin", &RibParser::DoResourceBegin},
        {"ResourceEnd", &RibParser::DoResourceEnd},
    };
    if (auto it = kHandlers.find(r.name); it != kHandlers.end()) {
        if (!(this->*(it->second))(r)) return false;
        // A level of detail not drawn at its size on screen: its primitives are dropped (read
        // and checked all the same, except in a delayed archive, which is not opened).
        if (m_state.detailHidden) m_scene.primitives.resize(m_primitivesStamped);
        m_primitivesStamped = m_scene.primitives.size();
        return true;
    }
    if (ContainsP(std::begin(kMakeRequests), std::end(kMakeRequests), r.name)) return DoMake(r);
    return DoUnhandled(r);
}

void RibParser::Warn(RibPos at, const std::string& message) {
    if (!m_warned.insert(message).second) return;
    if (m_report) m_report->warning(Where(at), message);
}

void RibParser::Note(RibPos at, const std::string& message) {
    if (!m_warned.insert(message).second) return;
    if (m_report) m_report->notice(Where(at), message);
}

diag::Location RibParser::Where(RibPos at) const {
    const Source& source = m_sources[static_cast<size_t>(at.file)];
    return {source.path, at.line, at.column, std::string(diag::LineOf(source.text, at.line))};
}

std::string RibParser::LineName(RibPos at, RibPos from) const {
    std::string text = "line " + std::to_string(at.line);
    if (at.file != from.file) text += " of " + m_sources[static_cast<size_t>(at.file)].path;
    return text;
}

const char* RibParser::BlockName(Block kind, bool end) {
    switch (kind) {
        case Block::Frame: return end ? "FrameEnd" : "FrameBegin";
        case Block::World: return end ? "WorldEnd" : "WorldBegin";
        case Block::Attribute: return end ? "AttributeEnd" : "AttributeBegin";
        case Block::Transform: return end ? "TransformEnd" : "TransformBegin";
        case Block::Solid: return end ? "SolidEnd" : "SolidBegin";
    }
    return "?";
}

bool RibParser::SetCtm(const RibRequest& r, const glm::dmat4& ctm) {
    if (!FiniteP(ctm)) return Fail(r.at, Quote(r.name) + " makes the current transform overflow");
    m_state.ctm = ctm;
    return true;
}

bool RibParser::FiniteP(const glm::dmat4& m) {
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
            if (!std::isfinite(m[c][r])) return false;
    return true;
}

bool RibParser::FiniteP(const glm::dvec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

bool RibParser::BeforeWorld(const RibRequest& r) {
    if (!m_worldSeen) return true;
    return Fail(r.at, Quote(r.name) + " is an option and must come before 'WorldBegin'");
}

glm::dmat4 RibParser::ObjectToCamera() const {
    // After WorldEnd the CTM is the camera transform again, relative to camera space as before.
    bool inWorld = m_worldSeen && !m_worldEnded;
    return inWorld ? m_scene.camera.worldToCamera * m_state.ctm : m_state.ctm;
}

bool RibParser::InsideWorld(const RibRequest& r) {
    for (const OpenBlock& b : m_blocks)
        if (b.kind == Block::World) return true;
    return Fail(r.at, Quote(r.name) + " must come between 'WorldBegin' and 'WorldEnd'");
}

bool RibParser::Begin(const RibRequest& r, Block kind) {
    m_blocks.push_back({kind, r.at, m_state});
    return true;
}

bool RibParser::End(const RibRequest& r, Block kind) {
    bool anyOpen = std::any_of(m_blocks.begin(), m_blocks.end(), [&](const OpenBlock& b) { return b.kind == kind; });
    if (!anyOpen) return Fail(r.at, Quote(r.name) + " without matching " + Quote(BlockName(kind, false)));
    const OpenBlock& open = m_blocks.back();
    if (open.kind != kind)
        return Fail(r.at, Quote(r.name) + " does not match " + Quote(BlockName(open.kind, false)) + " on " +
                              LineName(open.at, r.at));
    // TransformEnd restores only the transform, SolidEnd nothing; every other block restores all
    // attributes.
    if (kind == Block::Transform) {
        m_state.ctm = open.saved.ctm;
        m_state.motion = open.saved.motion;
        m_state.perspectiveFov = open.saved.perspectiveFov;
        m_state.perspectiveAt = open.saved.perspectiveAt;
    } else if (kind != Block::Solid)
        m_state = open.saved;
    if (open.skips) --m_skipping;
    if (kind == Block::World) m_worldEnded = true;
    m_blocks.pop_back();
    return true;
}

// ---- options ----

bool RibParser::DoFormat(const RibRequest& r) {
    double v[3];
    if (!BeforeWorld(r) || !Numbers(r, 3, "xresolution yresolution pixelaspectratio", v)) return false;
    const char* names[2] = {"xresolution", "yresolution"};
    for (int i = 0; i < 2; ++i)
        if (!(v[i] >= 1 && v[i] <= kMaxResolution && v[i] == std::floor(v[i])))
            return Fail(r.at, std::string("'Format' ") + names[i] + " must be an integer from 1 to " +
                                  std::to_string(kMaxResolution) + ", got " + FormatNumber(v[i]));
    // RI 3.2: a pixel aspect ratio that is not positive (exporters write -1 or 0) asks for the
    // display's default, which for affray's image files is square pixels. (The lexer reads no NaN
    // or infinity, so the value is finite.)
    double aspect = v[2];
    if (!(aspect > 0)) {
        Note(r.at, "'Format' pixelaspectratio " + FormatNumber(aspect) +
                       " asks for the display's default (RI 3.2): using 1, square pixels");
        aspect = 1;
    }
    m_scene.camera.xres = static_cast<int>(v[0]);
    m_scene.camera.yres = static_cast<int>(v[1]);
    m_scene.camera.pixelAspect = aspect;
    return true;
}

bool RibParser::DoProjection(const RibRequest& r) {
    std::string name;
    std::vector<RibParam> params;
    if (!BeforeWorld(r) || !LeadingString(r, "a projection name", &name) || !ParamList(r, 1, &params)) return false;
    CameraDesc& camera = m_scene.camera;
    if (name == "perspective") {
        camera.perspective = true;
        camera.fovDegrees = 90;
        for (const RibParam& p : params) {
            if (p.value.name != "fov") {
                Warn(p.at, "'Projection' parameter " + Quote(p.value.name) + " is not supported; ignored");
                continue;
            }
            if (!ParamNumbers(p, "'Projection'", 1, &camera.fovDegrees)) return false;
            if (!(camera.fovDegrees > 0 && camera.fovDegrees < 180))
                return Fail(
                    p.at, "'Projection' fov must be between 0 and 180 degrees, got " + FormatNumber(camera.fovDegrees));
        }
    } else if (name == "orthographic") {
        camera.perspective = false;
        for (const RibParam& p : params)
            Warn(p.at, "'Projection' parameter " + Quote(p.value.name) + " is not supported; ignored");
    } else {
        return Fail(r.at, "projection " + Quote(name) + " is not supported yet");
    }
    // RI 3.2: transforms before Projection form the screen transform; Projection then resets the
    // CTM to identity and what follows is the camera transform.
    if (m_state.ctm != glm::dmat4(1.0) || m_state.perspectiveFov > 0)
        Warn(r.at, "transforms before 'Projection' (screen transforms) are not supported; ignored");
    m_state.ctm = glm::dmat4(1.0);
    m_state.perspectiveFov = 0;
    return true;
}

// Perspective fov (RI 3.2 section 4.3) concatenates a perspective transform onto the CTM. Before
// WorldBegin, with nothing concatenated yet, the camera transform is that perspective followed by
// what comes after it; seen through the orthographic projection (the default, or given), that is
// the perspective projection of the same fov, so WorldBegin makes it one. Everywhere else the
// transform it makes is projective, which affray's affine transforms cannot hold.
bool RibParser::DoPerspective(const RibRequest& r) {
    double fov;
    if (!Numbers(r, 1, "fov", &fov)) return false;
    const std::string request = "'Perspective " + FormatNumber(fov) + "'";
    if (m_worldSeen && !m_worldEnded)
        return Fail(r.at, request +
                              " inside the world block makes the object transform projective (affray's transforms "
                              "are affine); not supported");
    if (m_worldSeen) return Fail(r.at, request + " after 'WorldEnd': a camera transform comes before 'WorldBegin'");
    if (!(fov > 0 && fov < 180))
        return Fail(r.at, "'Perspective' fov must be between 0 and 180 degrees, got " + FormatNumber(fov));
    if (m_state.perspectiveFov > 0)
        return Fail(r.at, request + " after the 'Perspective' on " + LineName(m_state.perspectiveAt, r.at) +
                              " composes two perspective transforms, a projective camera transform (affray's "
                              "transforms are affine); not supported");
    if (m_scene.camera.perspective)
        return Fail(r.at, request +
                              " after 'Projection \"perspective\"' composes two perspective transforms, a projective "
                              "camera transform (affray's transforms are affine); not supported");
    if (m_state.ctm != glm::dmat4(1.0))
        return Fail(r.at, request +
                              " after other transforms makes the camera transform projective (affray's transforms "
                              "are affine); not supported: give 'Projection \"perspective\" \"fov\" [" +
                              FormatNumber(fov) + "]' before the camera's transforms instead");
    Note(r.at, request +
                   " before any other camera transform is the camera's projection: taken as 'Projection "
                   "\"perspective\" \"fov\" [" +
                   FormatNumber(fov) + "]'");
    m_state.perspectiveFov = fov;
    m_state.perspectiveAt = r.at;
    return true;
}

bool RibParser::NoPendingPerspective(const RibRequest& r) {
    if (m_state.perspectiveFov == 0) return true;
    return Fail(r.at, Quote(r.name) + " after 'Perspective' on " + LineName(m_state.perspectiveAt, r.at) +
                          " is placed in the projective space it makes (affray's transforms are affine); not "
                          "supported: give it after 'WorldBegin', or 'Projection \"perspective\"' instead of "
                          "'Perspective'");
}

bool RibParser::DoDisplay(const RibRequest& r) {
    if (!BeforeWorld(r)) return false;
    for (size_t i = 0; i < 3; ++i)
        if (i >= r.args.size() || r.args[i].isArray || !r.args[i].StringsP())
            return Fail(r.at, "'Display' expects 3 strings (name type mode)");
    std::vector<RibParam> params;  // display parameters are checked but none is used
    if (!ParamList(r, 3, &params)) return false;
    const std::string& name = r.args[0].strings[0];
    if (!name.empty() && name[0] == '+') {
        Warn(r.at, "additional display " + Quote(name) + " is not supported yet; ignored");
        return true;
    }
    if (name.empty()) return Fail(r.args[0].at, "'Display' name must not be empty");
    // The mode is checked here so that a typo fails before a long render, not after it; a shadow
    // map's or a "null" display's mode (another renderer's) is not, since that frame is skipped. A channel the scene
    // declares (DisplayChannel, Declare, or inline as "color Ci") is one of prman's output
    // variables: affray's own under its name, else left out with a warning (a typo is declared
    // nowhere, so it still fails).
    const std::string& type = r.args[1].strings[0];
    const std::string& given = r.args[2].strings[0];
    const bool noImage = ShadowMapTypeP(type) || type == "null";  // a skipped frame (SkipReason)
    std::string mode = noImage ? given : "";
    for (size_t begin = 0; !noImage;) {
        const size_t end = std::min(given.find(',', begin), given.size());
        // A typed channel, "color Ci", by spaces only (a line break in a mode is no separator).
        const DeclaredName channel = SplitDeclaredName(given.substr(begin, end - begin), " ");
        const std::string& group = channel.name;
        const bool declared = !channel.declaration.empty() || m_displayChannels.count(group) || m_declared.count(group);
        if (renderer::DisplayGroupP(group)) {
            mode += (mode.empty() ? "" : ",") + group;
        } else if (declared) {
            Warn(r.args[2].at, "'Display' channel " + Quote(group) +
                                   " is an output variable affray does not compute: left out of the image");
        } else {
            return Fail(r.args[2].at, "'Display' mode " + Quote(given) + " has an unknown channel group " +
                                          Quote(group) +
                                          " (expected rgb, rgba, rgbz, rgbaz, r, g, b, a, z, Ci, Oi, Z, N, P, st, cost "
                                          "or err, or a channel declared by DisplayChannel, separated by commas)");
        }
        if (end == given.size()) break;
        begin = end + 1;
    }
    if (mode.empty()) return Fail(r.args[2].at, "'Display' mode " + Quote(given) + " has no channel affray computes");
    m_scene.displayName = name;
    m_scene.displayType = type;
    m_scene.displayMode = mode;
    if (type != "file" && type != "openexr" && type != "exr" && !noImage)
        Warn(r.at, "display type " + Quote(type) + " is not supported; writing an OpenEXR file");
    return true;
}

// DisplayChannel "[type] name" (prman): declares an output variable that a Display mode may name.
// Its parameters (the channel's filter, quantization, ...) are ignored with a warning each.
bool RibParser::DoDisplayChannel(const RibRequest& r) {
    std::string channel;
    std::vector<RibParam> params;
    if (!BeforeWorld(r) || !LeadingString(r, "a channel (\"color Ci\")", &channel) || !ParamList(r, 1, &params))
        return false;
    const std::string name = SplitDeclaredName(channel, " ").name;
    if (name.empty()) return Fail(r.args[0].at, "'DisplayChannel' needs a channel name");
    m_displayChannels.insert(name);
    for (const RibParam& p : params)
        Warn(p.at, "'DisplayChannel' parameter " + Quote(p.value.name) + " is not supported; ignored");
    return true;
}

bool RibParser::DoFrameAspectRatio(const RibRequest& r) {
    double a;
    if (!BeforeWorld(r) || !Numbers(r, 1, "frameratio", &a)) return false;
    if (!(a > 0)) return Fail(r.at, "'FrameAspectRatio' must be positive, got " + FormatNumber(a));
    m_scene.camera.frameAspectRatio = a;
    return true;
}

bool RibParser::DoScreenWindow(const RibRequest& r) {
    double v[4];
    if (!BeforeWorld(r) || !Numbers(r, 4, "left right bottom top", v)) return false;
    // A reversed window mirrors the image, which RI allows; an empty one maps nothing.
    if (v[0] == v[1] || v[2] == v[3])
        return Fail(r.at, "'ScreenWindow' must have a nonzero width and height, got " + FormatNumber(v[0]) + " " +
                              FormatNumber(v[1]) + " " + FormatNumber(v[2]) + " " + FormatNumber(v[3]));
    m_scene.camera.screenWindow = glm::dvec4(v[0], v[1], v[2], v[3]);
    return true;
}

bool RibParser::DoCropWindow(const RibRequest& r) {
    double v[4];
    if (!BeforeWorld(r) || !Numbers(r, 4, "xmin xmax ymin ymax", v)) return false;
    const char* axes[2] = {"x", "y"};
    for (size_t i = 0; i < 2; ++i) {
        double lo = v[2 * i], hi = v[2 * i + 1];
        if (!(lo >= 0 && lo < hi && hi <= 1))
            return Fail(r.at, std::string("'CropWindow' needs 0 <= ") + axes[i] + "min < " + axes[i] +
                                  "max <= 1, got " + FormatNumber(lo) + " " + FormatNumber(hi));
    }
    m_scene.camera.cropWindow = glm::dvec4(v[0], v[1], v[2], v[3]);
    return true;
}

bool RibParser::DoClipping(const RibRequest& r) {
    double v[2];
    if (!BeforeWorld(r) || !Numbers(r, 2, "near far", v)) return false;
    // RI 3.2 asks near >= RI_EPSILON (1e-10); exporters write 0 for "as near as possible", which
    // prman takes as that.
    constexpr double kRiEpsilon = 1e-10;
    if (v[0] >= 0 && v[0] < kRiEpsilon && kRiEpsilon < v[1]) {
        Warn(r.at, "'Clipping' near " + FormatNumber(v[0]) + " is below RI_EPSILON; taken as 1e-10");
        v[0] = kRiEpsilon;
    }
    if (!(v[0] > 0 && v[0] < v[1]))
        return Fail(r.at, "'Clipping' needs 0 <= near < far, got " + FormatNumber(v[0]) + " " + FormatNumber(v[1]));
    m_scene.camera.nearClip = v[0];
    m_scene.camera.farClip = v[1];
    return true;
}

bool RibParser::DoDepthOfField(const RibRequest& r) {
    if (!BeforeWorld(r)) return false;
    CameraDesc& camera = m_scene.camera;
    // Without arguments, or with an infinite fstop (RI_INFINITY, 1e38), a pinhole camera.
    const bool none = r.args.empty() || (r.args.size() == 1 && r.args[0].isArray && r.args[0].numbers.empty() &&
                                         r.args[0].strings.empty());
    double v[3] = {std::numeric_limits<double>::infinity(), 0, 0};
    if (!none && !Numbers(r, 3, "fstop focallength focaldistance", v)) return false;
    if (v[0] >= 1e30) {
        camera.fstop = std::numeric_limits<double>::infinity();
        camera.focalLength = camera.focalDistance = 0;
        return true;
    }
    if (!(v[0] > 0 && v[1] > 0 && v[2] > 0) || !std::isfinite(v[1]) || !std::isfinite(v[2])) {
        // Exporters write "DepthOfField 0 ..." for a camera without one; prman renders it sharp.
        Warn(r.at, "'DepthOfField' " + FormatNumber(v[0]) + " " + FormatNumber(v[1]) + " " + FormatNumber(v[2]) +
                       ": a lens needs fstop, focallength and focaldistance above 0; rendering without depth of field");
        camera.fstop = std::numeric_limits<double>::infinity();
        camera.focalLength = camera.focalDistance = 0;
        return true;
    }
    camera.fstop = v[0];
    camera.focalLength = v[1];
    camera.focalDistance = v[2];
    return true;
}

// Shutter min max (RI 3.2 section 4.1.2): camera samples take times from min to max; motion
// blocks place the scene at those times.
bool RibParser::DoShutter(const RibRequest& r) {
    double v[2];
    if (!BeforeWorld(r) || !Numbers(r, 2, "min max", v)) return false;
    if (!std::isfinite(v[0]) || !std::isfinite(v[1]) || v[1] < v[0])
        return Fail(r.at, "'Shutter' needs finite times with max not before min, got " + FormatNumber(v[0]) + " " +
                              FormatNumber(v[1]));
    m_scene.camera.shutterOpen = v[0];
    m_scene.camera.shutterClose = v[1];
    return true;
}

bool RibParser::DoPixelSamples(const RibRequest& r) {
    double v[2];
    if (!BeforeWorld(r) || !Numbers(r, 2, "xsamples ysamples", v)) return false;
    const char* names[2] = {"xsamples", "ysamples"};
    for (int i = 0; i < 2; ++i)
        if (!(v[i] >= 1 && v[i] <= static_cast<double>(diag::LimitValue(diag::Limit::PixelSamples)) &&
              v[i] == std::floor(v[i])))
            return Fail(r.at, std::string("'PixelSamples' ") + names[i] + " must be an integer from 1 to " +
                                  std::to_string(diag::LimitValue(diag::Limit::PixelSamples)) + ", got " +
                                  FormatNumber(v[i]) +
                                  (v[i] > static_cast<double>(diag::LimitValue(diag::Limit::PixelSamples))
                                       ? " " + diag::LimitNote(diag::Limit::PixelSamples)
                                       : std::string()));
    m_scene.camera.xsamples = static_cast<int>(v[0]);
    m_scene.camera.ysamples = static_cast<int>(v[1]);
    return true;
}

bool RibParser::DoPixelFilter(const RibRequest& r) {
    std::string name;
    if (!BeforeWorld(r) || !LeadingString(r, "a filter name", &name)) return false;
    if (r.args.size() != 3 || r.args[1].isArray || !r.args[1].NumericP() || r.args[2].isArray || !r.args[2].NumericP())
        return Fail(r.at, "'PixelFilter' expects a filter name and 2 numbers (xwidth ywidth)");
    double xwidth = r.args[1].numbers[0], ywidth = r.args[2].numbers[0];
    if (!(xwidth > 0 && ywidth > 0))
        return Fail(r.at,
                    "'PixelFilter' widths must be positive, got " + FormatNumber(xwidth) + " " + FormatNumber(ywidth));
    FilterDesc& filter = m_scene.camera.filter;
    if (name == "box") {
        filter.kind = FilterDesc::Kind::Box;
    } else {
        // The other RI filters (triangle, catmull-rom, sinc) are all smooth low-pass filters too.
        if (name != "gaussian") Warn(r.at, "pixel filter " + Quote(name) + " is not supported; using \"gaussian\"");
        filter.kind = FilterDesc::Kind::Gaussian;
    }
    filter.xwidth = xwidth;
    filter.ywidth = ywidth;
    return true;
}

bool RibParser::DoExposure(const RibRequest& r) {
    double v[2];
    if (!BeforeWorld(r) || !Numbers(r, 2, "gain gamma", v)) return false;
    if (!(v[0] > 0 && v[1] > 0))
        return Fail(r.at,
                    "'Exposure' gain and gamma must be positive, got " + FormatNumber(v[0]) + " " + FormatNumber(v[1]));
    m_scene.camera.exposureGain = v[0];
    m_scene.camera.exposureGamma = v[1];
    return true;
}

// Imager "background" ["background" color] (RI 3.2's standard imager; BMRT's and Houdini's
// exports name the colour "bgcolor"): the colour composited under every pixel, white by default.
// "" or "null" removes the imager; any other imager shader is warned about and ignored.
bool RibParser::DoImager(const RibRequest& r) {
    std::string name;
    std::vector<RibParam> params;
    if (!BeforeWorld(r) || !LeadingString(r, "an imager shader name", &name) || !ParamList(r, 1, &params)) return false;
    if (name.empty() || name == "null") {
        m_scene.camera.background.reset();
        return true;
    }
    if (name != "background") {
        Warn(r.args[0].at, "imager shader " + Quote(name) + " is not supported (only \"background\"); ignored");
        return true;
    }
    glm::dvec3 color(1.0);
    for (const RibParam& p : params) {
        if (p.value.name != "background" && p.value.name != "bgcolor") {
            Warn(p.at, "'Imager \"background\"' parameter " + Quote(p.value.name) + " is not supported; ignored");
            continue;
        }
        double v[3];
        if (!ParamNumbers(p, "'Imager \"background\"'", 3, v)) return false;
        color = glm::dvec3(v[0], v[1], v[2]);
    }
    m_scene.camera.background = color;
    return true;
}

// ---- transforms ----

bool RibParser::DoTransform(const RibRequest& r) {
    glm::dmat4 m;
    if (!Matrix(r, &m)) return false;
    m_state.perspectiveFov = 0;  // replaced with the rest of the CTM
    return SetCtm(r, m);
}

bool RibParser::DoConcatTransform(const RibRequest& r) {
    glm::dmat4 m;
    return Matrix(r, &m) && SetCtm(r, m_state.ctm * m);
}

bool RibParser::DoTranslate(const RibRequest& r) {
    double v[3];
    return Numbers(r, 3, "dx dy dz", v) && SetCtm(r, glm::translate(m_state.ctm, glm::dvec3(v[0], v[1], v[2])));
}

bool RibParser::DoRotate(const RibRequest& r) {
    double v[4];
    if (!Numbers(r, 4, "angle dx dy dz", v)) return false;
    glm::dvec3 axis(v[1], v[2], v[3]);
    double length = glm::length(axis);
    if (!(length > 0) || !std::isfinite(length)) return Fail(r.at, "'Rotate' axis must not be zero");
    return SetCtm(r, glm::rotate(m_state.ctm, glm::radians(v[0]), axis / length));
}

bool RibParser::DoScale(const RibRequest& r) {
    double v[3];
    return Numbers(r, 3, "sx sy sz", v) && SetCtm(r, glm::scale(m_state.ctm, glm::dvec3(v[0], v[1], v[2])));
}

// Skew angle dx1 dy1 dz1 dx2 dy2 dz2 (RI 3.2 section 4.3): a shear along lines parallel to d2 that
// turns the direction d1 by `angle` degrees towards d2. With e the unit vector along d2 and n the
// unit part of d1 perpendicular to it, a point moves along e by k times its component along n,
// P' = P + k (n . P) e. d1, at angle phi from d2, goes to angle phi - angle, so k = cot(phi -
// angle) - cot(phi), which needs 0 < phi - angle < 180 degrees (the spec's limits on angle).
bool RibParser::DoSkew(const RibRequest& r) {
    double v[7];
    if (!Numbers(r, 7, "angle dx1 dy1 dz1 dx2 dy2 dz2", v)) return false;
    const glm::dvec3 d1(v[1], v[2], v[3]), d2(v[4], v[5], v[6]);
    const double length2 = glm::length(d2);
    const glm::dvec3 e = d2 / length2;
    const glm::dvec3 across = d1 - glm::dot(d1, e) * e;
    const double lengthAcross = glm::length(across);
    // An axis of zero, or two parallel axes (within rounding of their lengths), define no shear.
    if (!(length2 > 0 && std::isfinite(length2) && lengthAcross > 1e-12 * glm::length(d1) &&
          std::isfinite(lengthAcross)))
        return Fail(r.at, "'Skew' axes must be nonzero and not parallel");
    const glm::dvec3 n = across / lengthAcross;
    const double phi = std::atan2(lengthAcross, glm::dot(d1, e));  // in (0, pi)
    const double rest = phi - glm::radians(v[0]);
    if (!(rest > 0 && rest < glm::pi<double>()))
        return Fail(r.at, "'Skew' angle must be less than the angle between the axes (" +
                              FormatNumber(glm::degrees(phi)) + " degrees) and more than that angle minus 180, got " +
                              FormatNumber(v[0]));
    const double k = 1 / std::tan(rest) - 1 / std::tan(phi);
    glm::dmat4 shear(1.0);  // I + k e n^T, column-major: shear[column][row]
    for (int column = 0; column < 3; ++column)
        for (int row = 0; row < 3; ++row) shear[column][row] += k * e[row] * n[column];
    return SetCtm(r, m_state.ctm * shear);
}

std::optional<std::vector<SceneDesc>> ParseRibFrames(std::string_view text, const std::string& pathForMessages,
                                                     diag::Report* report) {
    std::string decompressed;
    if (GzipP(text)) {
        decompressed = text;
        if (const std::string reason = Gunzip(&decompressed); !reason.empty()) {
            if (report) report->error({pathForMessages}, "cannot read file: " + reason);
            return std::nullopt;
        }
        text = decompressed;
    }
    RibParser parser(text, pathForMessages, report);
    return parser.Run();
}

std::optional<std::vector<SceneDesc>> ReadRibFrames(const std::string& path, diag::Report* report) {
    auto fail = [&](const std::string& reason) -> std::optional<std::vector<SceneDesc>> {
        if (report) report->error({path}, "cannot read file: " + reason);
        return std::nullopt;
    };
    std::string text;
    if (const std::string reason = ReadRibFile(path, &text); !reason.empty()) return fail(reason);
    RibParser parser(text, path, report);
    return parser.Run();
}

namespace {

std::optional<SceneDesc> FirstImage(std::optional<std::vector<SceneDesc>> frames, const std::string& path,
                                    diag::Report* report) {
    if (!frames) return std::nullopt;
    for (SceneDesc& frame : *frames)
        if (frame.skipped.empty()) return std::move(frame);
    if (report) report->error({path}, "no frame of the file renders an image");
    return std::nullopt;
}

}  // namespace

std::optional<SceneDesc> ParseRib(std::string_view text, const std::string& pathForMessages, diag::Report* report) {
    return FirstImage(ParseRibFrames(text, pathForMessages, report), pathForMessages, report);
}

std::optional<SceneDesc> ReadRib(const std::string& path, diag::Report* report) {
    return FirstImage(ReadRibFrames(path, report), path, report);
}

}  // namespace affray::rib
