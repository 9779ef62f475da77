// rib/parser.h: the RIB reader's state machine, shared by its source files.
// Private to the reader: use rib/rib.h. rib.cpp holds dispatch, the block structure, options
// and transforms; frames.cpp frames, world blocks and shadow passes; attributes.cpp the shading
// attributes (with Sides and orientation) and lights; geometry.cpp the primitives and coordinate
// systems; nurbs.cpp NuPatch and TrimCurve; primvars.cpp the colour primitive variables;
// archive.cpp ReadArchive and retained objects; unsupported.cpp the requests read without being
// rendered. The graphics state (CTM, color, opacity, surface, displacement, sides, orientation,
// basis, the lights that are on, whether new lights cast shadows, which rays see the primitives)
// is saved by every Begin and restored by its End; the options by FrameBegin and FrameEnd
// (FrameDefaults).
#pragma once

#include <array>
#include <glm/glm.hpp>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "diag/diagnostic.h"
#include "rib/args.h"
#include "rib/lexer.h"
#include "scene/refine.h"
#include "scene/scene.h"

namespace affray::rib {

/// Builds a SceneDesc from the requests of one RIB text. Use once: construct, then Run().
class RibParser : private RibArgChecks {
  public:
    RibParser(std::string_view text, const std::string& path, diag::Report* report) : m_report(report) {
        m_sources.push_back({path, nullptr, text});
        m_readers.push_back({RibRequestReader(text), 0});
        m_scene.path = path;
        m_scene.camera.perspective = false;  // RI default without a Projection request
    }

    /// Parses everything into one scene per world block (see rib.h); on failure reports the first
    /// error and returns nothing. Warnings and notes are reported as they are found, each distinct
    /// one once.
    std::optional<std::vector<SceneDesc>> Run();

  private:
    struct State {
        glm::dmat4 ctm{1.0};
        /// The CTM over time, when a motion block of transforms made it move (null: `ctm`
        /// stands still); `ctm` is then its matrix at its first time.
        std::shared_ptr<const renderer::MotionPath> motion;
        /// Perspective given before WorldBegin with nothing concatenated before it: the CTM is
        /// this perspective (its fov in degrees; 0: none) followed by `ctm`, which WorldBegin
        /// makes the camera's projection (see DoPerspective).
        double perspectiveFov = 0;
        RibPos perspectiveAt{};
        glm::dvec3 color{1.0};
        glm::dvec3 opacity{1.0};  // Opacity
        /// Attribute "light" "shadows" (BMRT): whether the lights declared now trace shadows.
        bool lightShadows = false;
        /// Attribute "visibility" "transmission" and "camera" (and BMRT's "render" forms).
        PrimitiveDesc::Transmission transmission = PrimitiveDesc::Transmission::Opaque;
        bool cameraVisible = true;
        /// ShadingRate and GeometricApproximation "flatness" (0: none given), for
        /// PrimitiveAttributes::sceneTolerance.
        double shadingRate = 1, flatness = 0;
        SurfaceDesc surface;
        std::optional<ShaderRef> displacement;
        std::optional<renderer::AtmosphereDesc> atmosphere;
        bool twoSided = true;  // Sides 2 (RI default)
        /// The current orientation differs from the handedness of the current coordinate system
        /// (RI 3.2 section 4.2: a transform that flips one flips the other, so only Orientation
        /// and ReverseOrientation change this).
        bool insideOut = false;
        /// Basis: the bicubic patches' u and v bases with their steps (RI default bezier 3).
        CubicBasis uBasis = CubicBasis::Bezier(), vBasis = CubicBasis::Bezier();
        /// The lights that are on (Illuminate), as sorted indices into the frame's lights: every
        /// light is on from its LightSource.
        std::vector<int> lights;
        /// TrimCurve: the trim loops of the NuPatches that follow (null: none), and
        /// Attribute "trimcurve" "sense": whether the inside of the loops is kept ("inside").
        std::shared_ptr<const renderer::TrimCurves> trim;
        bool trimKeepInside = true;
        /// Detail: the corners of the current detail bound in camera space (null: none given).
        std::shared_ptr<const std::array<glm::dvec3, 8>> detailBound;
        /// DetailRange: the primitives that follow are a level of detail not drawn at the
        /// bound's size on screen.
        bool detailHidden = false;
        /// TextureCoordinates (null: none given, s, t are u, v).
        std::shared_ptr<const std::array<double, 8>> textureCoordinates;
        /// ScopedCoordinateSystem: the named spaces of this block and those around it (null:
        /// none), given to every primitive (PrimitiveAttributes::scopedSpaces).
        std::shared_ptr<const std::map<std::string, glm::dmat4>> scopedSpaces;
        /// Attribute values by "category:name" (null: none), for conditional RIB's $category:name.
        std::shared_ptr<const std::map<std::string, ParamValue>> attributes;
    };
    /// What FrameEnd restores: the options and camera-space lights and coordinate systems in
    /// effect at FrameBegin (the graphics state is restored by the block itself).
    struct FrameDefaults {
        SceneDesc scene;
        std::vector<std::string> archiveSearchPath;
        std::vector<LightDesc> cameraLights;
        std::map<std::string, glm::dmat4> cameraCoordinateSystems;
        std::map<std::string, int> lightHandles;
        std::map<std::string, ParamValue> options;
        double relativeDetail;
        std::map<std::string, State> resources;
        std::string hider;
    };
    /// Solid: SolidBegin ... SolidEnd, which saves and restores nothing (RI 3.2 section 5.8).
    enum class Block { Frame, World, Attribute, Transform, Solid };
    struct OpenBlock {
        Block kind;
        RibPos at;
        State saved;
        /// A solid affray cannot render (intersection, difference): its requests are skipped.
        bool skips = false;
    };
    using Handler = bool (RibParser::*)(const RibRequest&);
    /// A file the reader has read: the scene (0) or an archive. RibPos::file indexes these.
    struct Source {
        std::string path;
        std::unique_ptr<std::string> owned;  // an archive's text (the scene's is the caller's)
        std::string_view text;
    };
    /// A file being read; the innermost ReadArchive is the last.
    struct OpenReader {
        RibRequestReader reader;
        int file;
        /// Read for a Procedural (at `at`): its requests run in an attribute block of their own,
        /// the block m_blocks[blocks - 1] (or, in an object definition, a recorded one).
        bool procedural = false;
        RibPos at{};
        size_t blocks = 0;
        /// An inline archive read by ReadArchive: its requests (`reader` is unused), the next to run.
        std::shared_ptr<const std::vector<RibRequest>> inlineRequests{};
        size_t next = 0;
        std::string inlineName{};
    };
    /// An ArchiveBegin ... ArchiveEnd being recorded.
    struct ArchiveDef {
        std::string name;
        RibPos at;
        std::vector<RibRequest> requests;
        int depth = 0;  // nested ArchiveBegin open in it
    };
    /// An ObjectBegin ... ObjectEnd definition: its requests, replayed by ObjectInstance.
    struct ObjectDef {
        RibPos at;
        std::vector<RibRequest> requests;
    };

    /// Runs `r`, taking motion blocks into account: each sample of a block of transforms runs
    /// on the CTM at its time; of any other block only the first sample runs. A transform
    /// request outside a block runs on every time of a moving CTM.
    bool Dispatch(const RibRequest& r);
    /// Runs the transform request `r` on each matrix of the moving CTM.
    bool OnEveryTime(const RibRequest& r);
    /// Warns that `r` (a light given before WorldBegin, a coordinate system) is placed at the first
    /// time of the CTM, if the CTM moves: "`what` do not move".
    void WarnIfMoving(const RibRequest& r, const std::string& what);
    /// Adds `light` to the frame's lights (after those given before WorldBegin) and turns it on
    /// in the current attributes; true.
    bool AddLight(const LightDesc& light);
    /// Runs `r` by its handler.
    bool DispatchRequest(const RibRequest& r);
    /// An open MotionBegin: where, its times, the kind of request it holds, how many so far.
    struct Motion {
        RibPos at;
        std::vector<double> times;
        std::string request;
        size_t count = 0;
        /// A block of transforms: the CTM (and its path) before it, and the CTM each sample made.
        glm::dmat4 ctmBefore{1.0};
        std::shared_ptr<const renderer::MotionPath> pathBefore;
        std::vector<glm::dmat4> ctms;
    };
    std::optional<Motion> m_motion;
    /// An open IfBegin: where; whether the branch being read is taken; whether one was already
    /// (or none can be, inside a branch not taken); whether its Else came.
    struct OpenConditional {
        RibPos at;
        bool active, taken, elseSeen;
    };
    std::vector<OpenConditional> m_conditionals;
    /// Conditional RIB (rib/conditional.cpp), before objects record `r`: runs IfBegin, ElseIf,
    /// Else and IfEnd, and sets *consumed for them and for the requests of a branch not taken.
    bool Conditional(const RibRequest& r, bool* consumed);
    /// Checks that IfBegin or ElseIf `r` has one expression, and if `evaluate`, its truth.
    bool Condition(const RibRequest& r, bool evaluate, bool* out);
    /// The value of the attribute, else the option, "category:name"; null if neither is given.
    const ParamValue* FindSetting(const std::string& name) const;
    /// While an object is being defined: records `r` in it, or runs it if it acts at once
    /// (ObjectEnd, ReadArchive, Declare). Requests an object cannot hold are errors.
    bool Record(const RibRequest& r);
    /// The path of file `file` of m_sources, for ShaderRef::file ("" for the scene itself).
    std::string FileOf(const RibPos& at) const { return at.file == 0 ? std::string() : m_sources[at.file].path; }
    void Warn(RibPos at, const std::string& message);
    /// A note of its own (a request affray skips on purpose), each distinct one once.
    void Note(RibPos at, const std::string& message);
    /// `at` as a diagnostic location, with its source line.
    diag::Location Where(RibPos at) const;
    /// "line 3" for `at`, with " of FILE" if it is in another file than `from`.
    std::string LineName(RibPos at, RibPos from) const;
    static const char* BlockName(Block kind, bool end);
    static bool FiniteP(const glm::dmat4& m);
    static bool FiniteP(const glm::dvec3& v);
    static glm::dvec3 TransformPoint(const glm::dmat4& m, const glm::dvec3& p) {
        return glm::dvec3(m * glm::dvec4(p, 1.0));
    }

    bool SetCtm(const RibRequest& r, const glm::dmat4& ctm);
    bool BeforeWorld(const RibRequest& r);
    bool InsideWorld(const RibRequest& r);
    bool Begin(const RibRequest& r, Block kind);
    bool End(const RibRequest& r, Block kind);
    /// The current object -> camera transform: before WorldBegin the CTM already maps to camera
    /// space; inside the world it maps to world space and the camera transform follows.
    glm::dmat4 ObjectToCamera() const;
    /// Whether the current coordinate system is right-handed (camera space is left-handed).
    bool RightHandedP() const { return glm::determinant(ObjectToCamera()) < 0; }
    /// BaseSurface::flipNormal for a primitive made now (see PrimitiveDesc's comment in scene.h).
    bool FlipNormalP() const;
    /// Fills the attributes every primitive takes from the graphics state (color, shading, sides,
    /// orientation, lights, line): those of p->attributes made once per request and shared by
    /// its primitives. Call it once p->base has its shape.
    void SetPrimitiveAttributes(const RibRequest& r, PrimitiveDesc* p) const;
    /// A quadric request: positional numbers (bare or one array), then ignored parameters.
    bool DoQuadric(const RibRequest& r, Quadric::Kind kind);
    bool DoPoints(const RibRequest& r);
    bool DoCurves(const RibRequest& r);

    // Handlers, one per implemented request: options, blocks and transforms in rib.cpp; attributes
    // and lights in rib_attributes.cpp; geometry and coordinate systems in rib_geometry.cpp.
    bool DoFormat(const RibRequest& r);
    bool DoProjection(const RibRequest& r);
    /// Perspective fov: before WorldBegin, on the identity, the camera's perspective projection;
    /// anywhere else refused (a projective transform).
    bool DoPerspective(const RibRequest& r);
    /// Fails if a Perspective is pending in the CTM (State::perspectiveFov): `r` would place
    /// something in the projective space it makes.
    bool NoPendingPerspective(const RibRequest& r);
    bool DoDisplay(const RibRequest& r);
    bool DoDisplayChannel(const RibRequest& r);
    bool DoFrameAspectRatio(const RibRequest& r);
    bool DoScreenWindow(const RibRequest& r);
    bool DoCropWindow(const RibRequest& r);
    bool DoClipping(const RibRequest& r);
    bool DoDepthOfField(const RibRequest& r);
    bool DoShutter(const RibRequest& r);
    bool DoPixelSamples(const RibRequest& r);
    bool DoPixelFilter(const RibRequest& r);
    bool DoExposure(const RibRequest& r);
    bool DoImager(const RibRequest& r);
    bool DoOption(const RibRequest& r);
    /// Option "Ri" and Attribute "Ri" (RenderMan 21 and later): each parameter run as the
    /// standard request it stands for (rib/settings.cpp).
    bool RiOptions(const std::vector<RibParam>& params);
    bool RiAttributes(const std::vector<RibParam>& params);
    /// Runs request `name` with `args`, located at `at` (a parameter of Option or Attribute "Ri").
    bool Forward(const std::string& name, RibPos at, std::vector<RibArg> args);
    /// Option "searchpath" "shader" or "archive": a ':'-separated list into *out.
    bool SetSearchPath(const RibParam& p, std::vector<std::string>* out);
    bool DoHider(const RibRequest& r);
    bool DoDeclare(const RibRequest& r);
    bool DoShadingRate(const RibRequest& r);
    bool DoGeometricApproximation(const RibRequest& r);
    bool DoShadingInterpolation(const RibRequest& r);
    /// TextureCoordinates s1 t1 s2 t2 s3 t3 s4 t4 (an attribute).
    bool DoTextureCoordinates(const RibRequest& r);
    /// Detail, DetailRange and RelativeDetail: levels of detail chosen by a bound's raster area.
    bool DoDetail(const RibRequest& r);
    bool DoDetailRange(const RibRequest& r);
    bool DoRelativeDetail(const RibRequest& r);
    bool DoArchiveRecord(const RibRequest& r);
    /// ReadArchive "name": an inline archive of that name (ArchiveBegin), else a file.
    bool DoReadArchive(const RibRequest& r);
    /// ArchiveBegin "name" [params]: starts recording an inline archive; ArchiveEnd outside one
    /// is an error.
    bool DoArchiveBegin(const RibRequest& r);
    /// Records `r` in the inline archive being defined, or ends it at its ArchiveEnd.
    bool RecordArchive(const RibRequest& r);
    /// Procedural "DelayedReadArchive" and Procedural2 "DelayedReadArchive2": the archive read
    /// at once, in an attribute block of its own (the bound is not needed: affray bounds what
    /// the archive holds). Procedurals that run programs are refused.
    bool DoProcedural(const RibRequest& r);
    /// Opens archive `name` (written at `nameAt` in `r`) for reading next; `procedural` scopes it
    /// in an attribute block, closed by EndArchive.
    bool OpenArchive(const RibRequest& r, RibPos nameAt, const std::string& name, bool procedural);
    /// At the end of an archive's text: closes a Procedural's attribute block.
    bool EndArchive(const OpenReader& reader);
    /// The file ReadArchive `name` names, as given in file `from`: an absolute path, else
    /// relative to that file's directory, else to each Option "searchpath" "archive" directory.
    /// Empty if none exists; *searched lists where it looked.
    std::string FindArchive(const std::string& name, int from, std::string* searched) const;
    bool DoObjectBegin(const RibRequest& r);
    bool DoObjectEnd(const RibRequest& r);
    bool DoObjectInstance(const RibRequest& r);
    /// An object handle argument (a number or a string) as a key; false if there is none.
    bool ObjectHandle(const RibRequest& r, std::string* out);
    bool DoFrameBegin(const RibRequest& r);
    bool DoFrameEnd(const RibRequest& r);
    bool DoWorldBegin(const RibRequest& r);
    bool DoWorldEnd(const RibRequest& r);
    /// Why the current frame renders no image (a shadow, depth or photon map pass, a "null"
    /// display), or "".
    std::string SkipReason() const;
    /// Whether a Display of type `type` writes a shadow or depth map (another renderer's).
    static bool ShadowMapTypeP(std::string_view type);
    /// MakeShadow, MakeTexture and the other Make* requests: their arguments checked, skipped with a note.
    bool DoMake(const RibRequest& r);
    bool DoAttributeBegin(const RibRequest& r) { return NoArgs(r) && Begin(r, Block::Attribute); }
    bool DoAttributeEnd(const RibRequest& r) { return NoArgs(r) && End(r, Block::Attribute); }
    bool DoTransformBegin(const RibRequest& r) { return NoArgs(r) && Begin(r, Block::Transform); }
    bool DoTransformEnd(const RibRequest& r) { return NoArgs(r) && End(r, Block::Transform); }
    bool DoIdentity(const RibRequest& r) {
        m_state.perspectiveFov = 0;  // replaces a Perspective too
        return NoArgs(r) && SetCtm(r, glm::dmat4(1.0));
    }
    bool DoTransform(const RibRequest& r);
    bool DoSkew(const RibRequest& r);
    bool DoConcatTransform(const RibRequest& r);
    bool DoTranslate(const RibRequest& r);
    bool DoRotate(const RibRequest& r);
    bool DoScale(const RibRequest& r);
    bool DoColor(const RibRequest& r);
    bool DoOpacity(const RibRequest& r);
    bool DoAttribute(const RibRequest& r);
    bool DoSides(const RibRequest& r);
    bool DoReverseOrientation(const RibRequest& r);
    bool DoOrientation(const RibRequest& r);
    bool DoSurface(const RibRequest& r);
    bool DoDisplacement(const RibRequest& r);
    bool DoAtmosphere(const RibRequest& r);
    bool DoLightSource(const RibRequest& r);
    bool DoIlluminate(const RibRequest& r);
    /// The parameters of a light shader; `shadowMapped` accepts (and ignores) those of the
    /// shadow-map light shaders too.
    bool LightParams(const std::string& context, const std::vector<RibParam>& params, bool shadowMapped,
                     LightDesc* light);
    bool CheckSpotlight(const RibRequest& r, const std::string& context, const LightDesc& light);
    bool DoCoordinateSystem(const RibRequest& r);
    bool DoCoordSysTransform(const RibRequest& r);
    bool DoBasis(const RibRequest& r);
    bool DoPatch(const RibRequest& r);
    bool DoPatchMesh(const RibRequest& r);
    /// The homogeneous control points of a patch or patch mesh of `count` points from "P" (w = 1)
    /// or "Pw" (w > 0; *rational if some w != 1), and "Pz" if `heights` is given (the point i of
    /// a bilinear patch at (i & 1, i >> 1)). Other parameters are warned about.
    bool PatchPoints(const RibRequest& r, const std::vector<RibParam>& params, const std::string& context, size_t count,
                     bool heights, std::vector<glm::dvec4>* out, bool* rational);
    /// Adds a bilinear (4 points) or bicubic (16, the current bases) patch of homogeneous control
    /// points in object space covering `range` of its mesh: rational if `rational`.
    bool AddPatch(const RibRequest& r, const std::string& context, bool bicubic, bool rational,
                  const std::vector<glm::dvec4>& points, const renderer::ParameterRange& range);
    /// Adds a rational patch (world space) covering `range` of its surface, cut by `trim`.
    bool AddRational(const RibRequest& r, const std::string& context, const renderer::RationalPatch& patch,
                     const renderer::ParameterRange& range, std::shared_ptr<const renderer::TrimCurves> trim);
    /// NuPatch and TrimCurve (rib/nurbs.cpp).
    bool DoNuPatch(const RibRequest& r);
    bool DoTrimCurve(const RibRequest& r);
    /// Adds a bilinear patch (corners in object space) covering `range` of its mesh.
    bool AddBilinear(const RibRequest& r, const std::string& context, const std::array<glm::dvec3, 4>& corners,
                     const renderer::ParameterRange& range);
    /// Adds a bicubic patch (16 control points in object space, the current bases) covering
    /// `range` of its mesh.
    bool AddBicubic(const RibRequest& r, const std::string& context, const std::array<glm::dvec3, 16>& points,
                    const renderer::ParameterRange& range);
    bool DoSphere(const RibRequest& r) { return DoQuadric(r, Quadric::Kind::Sphere); }
    bool DoCylinder(const RibRequest& r) { return DoQuadric(r, Quadric::Kind::Cylinder); }
    bool DoCone(const RibRequest& r) { return DoQuadric(r, Quadric::Kind::Cone); }
    bool DoDisk(const RibRequest& r) { return DoQuadric(r, Quadric::Kind::Disk); }
    bool DoTorus(const RibRequest& r) { return DoQuadric(r, Quadric::Kind::Torus); }
    bool DoHyperboloid(const RibRequest& r) { return DoQuadric(r, Quadric::Kind::Hyperboloid); }
    bool DoParaboloid(const RibRequest& r) { return DoQuadric(r, Quadric::Kind::Paraboloid); }
    // The polygon requests (rib/polygons.cpp): each reads its counts and indices, then MeshRequest
    // checks them and the parameter list and adds the mesh (AddMesh).
    bool DoPolygon(const RibRequest& r);
    bool DoGeneralPolygon(const RibRequest& r);
    bool DoPointsPolygons(const RibRequest& r);
    bool DoPointsGeneralPolygons(const RibRequest& r);
    /// Integers in argument `index` of `r` (an array or one bare number), each at least `least`;
    /// `what` names them for messages ("nverts").
    bool IntArray(const RibRequest& r, size_t index, const char* what, int least, std::vector<int>* out);
    /// A polygon mesh request with its faces' loop counts, loop sizes and corner indices (`points`
    /// < 0: the corners are the points in order, as Polygon gives them) and its parameter list
    /// from argument `first`.
    bool MeshRequest(const RibRequest& r, std::vector<int> loops, std::vector<int> loopSizes, std::vector<int> corners,
                     size_t first, bool indexed);
    /// Adds the polygon or subdivision mesh of request `r` as read, with its "Cs" (colors[0]) and
    /// "Os" (colors[1]): one primitive whose elements RefineScene makes (scene/refine.h), with
    /// what it needs to report a problem at `r` as Fail would.
    void AddMesh(const RibRequest& r, std::variant<renderer::PolygonMesh, renderer::SubdivisionMesh> mesh,
                 std::optional<renderer::ColorValues> (&colors)[2]);
    /// Values a primitive holds per storage class (RI Spec 3.2 table 4.1): a polygon or
    /// subdivision mesh's faces, points and face corners (varying values are per point); a
    /// patch's or quadric's patches, varying values (at the patches' corners) and control points.
    struct PrimvarCounts {
        size_t faces, points, corners, varying;
        size_t Of(renderer::StorageClass s) const;
    };
    /// A colour primitive variable ("Cs" or "Os") as given: its storage class, one colour per value.
    using ColorValues = renderer::ColorValues;
    /// Reads `p` ("Cs" or "Os") into *out after checking its declaration (a color), its count
    /// against `counts` and its values (an opacity clamped to 0..1). `facevarying` false: the
    /// primitive has no such class (NuPatch). False after a Fail.
    bool ColorPrimvar(const RibParam& p, const std::string& context, const PrimvarCounts& counts, bool facevarying,
                      ColorValues* out);
    /// Sets prim's colour (colors[0]) and opacity (colors[1]) from those of `colors` that are
    /// constant (a mesh keeps the others in its arrays).
    static void SetConstantColors(const std::optional<ColorValues> (&colors)[2], PrimitiveDesc* prim);
    /// Reads a patch's (or patch mesh's) "Cs" and "Os" into colors[0] and colors[1].
    bool PatchColors(const std::vector<RibParam>& params, const std::string& context, const PrimvarCounts& counts,
                     std::optional<ColorValues> (&colors)[2]);
    /// Sets the colour and opacity of `prim`, a patch (or quadric) just made, from `colors`: its
    /// uniform value is number `face`, its varying values at its corners (patch order) numbers
    /// `corners`, its vertex values those of its control points `vertices` (4 or 16, `bicubic`),
    /// whose weights are those of `points` (homogeneous, indexed as the values) if `rational`.
    void PatchColorFields(PrimitiveDesc* prim, const std::optional<ColorValues> (&colors)[2], size_t face,
                          const std::array<size_t, 4>& corners, const std::vector<size_t>& vertices,
                          const std::vector<glm::dvec4>& points, bool bicubic, bool rational);
    /// The Attribute requests affray follows (rib/attributes.cpp): "light", "visibility", "render".
    bool LightAttribute(const std::vector<RibParam>& params);
    bool VisibilityAttribute(const std::string& name, const std::vector<RibParam>& params);
    /// A declaration without a storage class is uniform (RI Spec 3.2, section 3), but exporters
    /// write "float[2] st" with a value per vertex: when p's count does not fit uniform, *d takes
    /// the first class whose count does (the standard variable's own, then varying, vertex,
    /// facevarying where `facevarying`, constant), with a note; otherwise *d is left as it is
    /// (the caller reports the count).
    void ResolveStorage(const RibParam& p, const std::string& context, const PrimvarCounts& counts, bool facevarying,
                        RibDeclaration* d);
    /// A primitive variable of a mesh (polygons, subdivision) against its declaration, inline or
    /// standard, and its value count against `counts`. False after a Fail; *declared false, with a
    /// warning, for a parameter that has no declaration (the caller skips it). `context` names the
    /// request in messages.
    bool MeshPrimvar(const RibParam& p, const std::string& context, const PrimvarCounts& counts, RibDeclaration* d,
                     bool* declared);
    /// The points of a polygon or subdivision mesh: its "P" (`width` 3 numbers a point) or, if it
    /// has none, its first "Pw" (4), holding `count` points.
    struct MeshPoints {
        const RibParam* param = nullptr;
        size_t width = 0, count = 0;
    };
    /// Finds the points of mesh request `r` in its parameter list and checks that they are
    /// numbers, a whole number of points and at least one (rib/polygons.cpp). False after a Fail.
    bool FindMeshPoints(const RibRequest& r, const std::vector<RibParam>& params, const std::string& context,
                        MeshPoints* out);
    /// SubdivisionMesh (rib/subdivision.cpp): its counts, tags and parameters checked, its patches added.
    bool DoSubdivisionMesh(const RibRequest& r);
    bool DoVersion(const RibRequest&) { return true; }  // "version 3.03": nothing to check
    // Requests affray reads without rendering what they ask (rib/unsupported.cpp).
    /// SolidBegin "primitive"|"union"|"intersection"|"difference" and SolidEnd.
    bool DoSolidBegin(const RibRequest& r);
    bool DoSolidEnd(const RibRequest& r);
    /// A request without a handler: another renderer's option or attribute (a warning), a
    /// primitive affray cannot render (skipped with a warning), one whose absence would render
    /// another scene (an error), or no request at all (an error).
    bool DoUnhandled(const RibRequest& r);
    /// Resource "name" "attributes" (save or restore a graphics state), ResourceBegin, ResourceEnd
    /// (rib/resource.cpp).
    bool DoResource(const RibRequest& r);
    bool DoResourceBegin(const RibRequest& r);
    bool DoResourceEnd(const RibRequest& r);

    std::vector<Source> m_sources;
    std::vector<OpenReader> m_readers;
    diag::Report* m_report;
    std::vector<std::string> m_archiveSearchPath;            // Option "searchpath" "archive"
    std::vector<SceneDesc::MakeTextureDesc> m_madeTextures;  // MakeTexture requests so far
    std::map<std::string, ObjectDef> m_objects;              // by handle ("1" or the string)
    std::optional<ArchiveDef> m_archiveDef;                  // between ArchiveBegin and ArchiveEnd
    std::map<std::string, std::shared_ptr<const std::vector<RibRequest>>> m_inlineArchives;  // by name
    std::optional<std::pair<std::string, ObjectDef>> m_defining;   // between ObjectBegin and ObjectEnd
    int m_definingDepth = 0;                                       // Attribute/Transform blocks open in it
    int m_instanceDepth = 0;                                       // ObjectInstance replays under way
    std::optional<std::pair<RibPos, std::string>> m_errorNote;     // a note on the error, if any
    std::optional<std::pair<RibPos, std::string>> m_instanceNote;  // that note for the replay under way
    std::set<std::string> m_warned;                                // each distinct warning once

    SceneDesc m_scene;
    State m_state;
    std::vector<OpenBlock> m_blocks;
    int m_skipping = 0;                            // open blocks whose requests are skipped (OpenBlock::skips)
    std::vector<SceneDesc> m_frames;               // one per world block ended
    std::optional<FrameDefaults> m_frameDefaults;  // inside FrameBegin ... FrameEnd
    std::map<std::string, int> m_lightHandles;     // light handle -> index into the frame's lights; -1: ignored
    size_t m_primitivesStamped = 0;                // primitives of requests finished (see Dispatch)
    uint64_t m_requestSerial = 0;                  // requests dispatched
    // The attributes of the primitives of request m_attributesSerial (SetPrimitiveAttributes).
    mutable std::shared_ptr<const renderer::PrimitiveAttributes> m_attributes;
    mutable uint64_t m_attributesSerial = 0;
    bool m_worldSeen = false;  // in the current frame (or the file, outside frames)
    bool m_worldEnded = false;
    std::vector<LightDesc> m_cameraLights;  // lights given before WorldBegin, in camera space
    // CoordinateSystem given before WorldBegin: object -> camera, mapped to world at WorldBegin.
    std::map<std::string, glm::dmat4> m_cameraCoordinateSystems;
    std::map<std::string, ParamValue> m_options;  // Option values by "category:name" (conditional RIB)
    double m_relativeDetail = 1;                  // RelativeDetail (an option)
    std::map<std::string, State> m_resources;     // Resource "attributes" saved, by name
    std::set<std::string> m_displayChannels;      // DisplayChannel names, which Display may use
    std::string m_hider = "hidden";               // Hider (an option)
    /// Open ResourceBegin blocks: where, and the resources saved before them (ResourceEnd restores).
    std::vector<std::pair<RibPos, std::map<std::string, State>>> m_resourceScopes;
};

}  // namespace affray::rib
