// renderer/render.h: from a scene description to an image: shader compilation per instance,
// camera rays through the guaranteed intersector, shading with shadows, threads over rows.
#pragma once

#include <atomic>
#include <deque>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "compiler/compile.h"
#include "image/exr_writer.h"
#include "renderer/bvh.h"
#include "renderer/film.h"
#include "renderer/intersect.h"
#include "scene/scene.h"

namespace affray::renderer {

struct Primitive;

/// Makes the intersector one thread uses for one primitive (`index` in PreparedScene::primitives).
using IntersectorFactory = std::function<std::unique_ptr<SurfaceIntersector>(const Primitive& primitive, int index)>;

/// Told how a render advances: Begin(tiles) before the first tile, TileDone() from the worker
/// threads as each tile is finished (so it must be thread-safe), Finish() after the last.
class RenderProgress {
  public:
    virtual ~RenderProgress() = default;
    virtual void Begin(int tiles) = 0;
    virtual void TileDone() = 0;
    virtual void Finish() = 0;
};

/// Keeps a render's finished tiles outside it and gives back those an earlier, interrupted render
/// of the same image finished (the command line's checkpoint file, renderer/checkpoint.h).
class TileStore {
  public:
    virtual ~TileStore() = default;
    /// Before any tile is rendered, on the calling thread: copies the tile's pixels, every
    /// channel, into `image` (from Film::MakeImage) and returns true if the store has them; the
    /// tile is then not rendered. False: the tile is rendered.
    virtual bool Restore(const PixelRange& tile, image::ImageBuffer* image) = 0;
    /// The tile's pixels in `image` are final. Called from the worker threads as each tile is
    /// finished (so it must be thread-safe); other threads meanwhile write other tiles' pixels.
    virtual void Finished(const PixelRange& tile, const image::ImageBuffer& image) = 0;
};

/// The side of a block of pixels whose camera rays are traced as a group (`--ray-groups`).
inline constexpr int kDefaultRayGroupPixels = 8;

struct RenderOptions {
    int threads = 0;               // 0: one per core
    double tolerancePixels = 0.5;  // a region is a hit once its bound is smaller than this many pixels
    /// Whether a primitive whose scene asks for a coarser tolerance (PrimitiveAttributes::sceneTolerance:
    /// ShadingRate, GeometricApproximation) is certified to that; false when tolerancePixels was
    /// given by the user (--tolerance).
    bool sceneTolerance = true;
    BoundMode bounds = BoundMode::Reduced;
    /// Certified Newton hits (renderer/newton.h) at the leaves of the walk: a hit to rounding
    /// where Krawczyk's test proves the leaf meets the ray once, the leaf's own bound elsewhere.
    bool newton = false;
    int maxDepth = 24;
    size_t cacheBytes = kDefaultCacheBytes;        // the bound hierarchies' memory budget (renderer/bound_tree.h)
    uint64_t regionBudget = kDefaultRegionBudget;  // per ray (renderer/intersect.h)
    int tileSize = 32;                             // pixels per side (less for small images)
    /// Cut the image into tiles of exactly tileSize (a resumed render must cut it as the
    /// interrupted one did), not smaller ones for small images (RenderTileSize).
    bool fixedTileSize = false;
    /// Take the tiles last first: the image must not depend on the order (a test option).
    bool reverseTileOrder = false;
    /// Set, by a signal handler say, to stop the render: the workers check it between samples and
    /// give up their unfinished tiles; RenderStats::stopped is then true and the image incomplete.
    const std::atomic<bool>* stop = nullptr;
    /// Where finished tiles are kept and restored from (null: nowhere).
    TileStore* tileStore = nullptr;
    /// Camera rays are traced in groups of this many pixels per side, which share the walk of the
    /// bound hierarchies' top levels (RayGroup); blocks of the whole image, so the image does not
    /// depend on the tiles. 0: every ray alone.
    int rayGroupPixels = kDefaultRayGroupPixels;
    /// Told how the render advances (the command line draws its progress bar with it); null: no one.
    class RenderProgress* progress = nullptr;
    /// Replaces the guaranteed intersector, for every primitive and thread: the benches' in-process
    /// tessellation baseline (bench/) renders the same samples, shading and shadows through it.
    /// Empty: affray's own.
    IntersectorFactory intersectorFactory;
};

struct RenderStats {
    double wallSeconds = 0;
    uint64_t cameraRays = 0;  // camera samples traced (a tile's filter margin is traced again)
    IntersectStats camera;    // camera rays only; its `rays` counts ray-primitive tests
    IntersectStats shadow;    // shadow rays
    BoundTreeStats cache;     // the bound hierarchies, summed over the primitives
    size_t cacheBudgetBytes = 0;
    uint64_t cachePeakBytes = 0;  // the most the hierarchies held together
    /// The process's resident memory when the render began (the scene read and prepared, no
    /// film yet) and its peak over the process's life (what the budgets bound: the tracing adds
    /// at most --cache-mb + --texture-mb + the film + per-thread state to the first).
    uint64_t residentAtStartBytes = 0, peakResidentBytes = 0;
    /// The scene's own data as the render holds it (SceneBytes), and its primitives: what a
    /// primitive costs before any bound is computed is their ratio.
    uint64_t sceneBytes = 0, primitives = 0;
    /// Set by the caller (the command line): the seconds reading the RIB file and preparing the
    /// scene took (0 if not given).
    double readSeconds = 0, prepareSeconds = 0;
    int width = 0, height = 0;
    bool stopped = false;   // RenderOptions::stop was set in time: some tiles are missing from the image
    int tilesRestored = 0;  // tiles the TileStore gave back instead of being rendered

    /// The one-line JSON of `affray render --stats`.
    std::string ToJson() const;
};

/// The programs a primitive runs: its shader instance and the instance's programs specialised
/// further for the globals constant on its surface (E, du, dv, and N, Ng, dPdu, dPdv of a flat
/// patch). One per distinct (instance, constants), shared by the primitives that have them (every
/// face of a mesh, say).
struct PrimitivePrograms {
    std::shared_ptr<const compiler::CompiledShader> shader;  // null: no displacement
    vm::Program bound;
    vm::Program shade;
};

/// A primitive ready to render: its description (base surface, colours and attributes, in
/// PreparedScene::desc; for a mesh's piece or patch, the mesh's and its element's index), its
/// programs and lights. A handful of words: a mesh of a million faces is a million of these,
/// sharing everything else.
struct Primitive {
    const PrimitiveDesc* desc = nullptr;
    const PrimitivePrograms* programs = nullptr;
    int32_t lightSet = 0;  // the lights that illuminate it: PreparedScene::lightSets[lightSet]
    uint32_t element = 0;  // which of desc's elements (PrimitiveDesc::elements) it is

    /// Its base surface (a mesh's piece or patch made from the mesh's: a handle and an index).
    BaseSurface base() const { return desc->base.Element(element); }
    const PrimitiveAttributes& attributes() const { return *desc->attributes; }
    const std::shared_ptr<const compiler::CompiledShader>& shader() const { return programs->shader; }
    const vm::Program& bound() const { return programs->bound; }
    const vm::Program& shade() const { return programs->shade; }
    const SurfaceDesc& surface() const { return attributes().surface; }
    PrimitiveDesc::Transmission transmission() const { return attributes().transmission; }
    bool cameraVisible() const { return attributes().cameraVisible; }
    bool twoSided() const { return attributes().twoSided; }
    double sceneTolerance() const { return attributes().sceneTolerance; }  // pixels
    int line() const { return attributes().line; }                         // the RIB request

    /// Cs and Os at the point (u, v) of the primitive's own parameters (a hit's), as
    /// PrimitiveDesc::ColorAt gives them.
    glm::dvec3 ColorAt(double u, double v) const { return desc->ColorAt(element, 0, u, v); }
    glm::dvec3 OpacityAt(double u, double v) const { return desc->ColorAt(element, 1, u, v); }
    /// Whether Os is 1 everywhere.
    bool OpaqueP() const { return desc->OpaqueP(element); }
};

struct PreparedScene {
    /// The scene as read; its primitives are those `primitives` point to (never changed after
    /// PrepareScene: a vector moved with the scene keeps its elements in place).
    SceneDesc desc;
    std::vector<Primitive> primitives;
    /// The distinct programs of the primitives (a deque: they stay in place as it grows).
    std::deque<PrimitivePrograms> programs;
    std::unique_ptr<Bvh> bvh;       // over the primitives' boxes
    std::vector<LightDesc> lights;  // the scene's, or a default key light if it has none
    /// The distinct sets of lights that illuminate primitives (Illuminate): each a subset of
    /// `lights` in its order; [0] is all of them.
    std::vector<std::vector<LightDesc>> lightSets;
    /// Shader instances compiled, and those that reused a compilation (same file bytes, same
    /// parameter values: compiler/shader_cache.h).
    int shadersCompiled = 0, shadersReused = 0;
    /// The digest of the scene's inputs that a render's identity and its frame's share
    /// (renderer/render_identity.cpp), computed by the first that needs it.
    mutable std::string identityDigest;
};

/// The shader globals that do not vary over `base` seen from `eye`, for specialising its programs:
/// E, du, dv, and for a flat patch N, Ng, dPdu and dPdv.
std::vector<compiler::ConstantGlobal> ConstantGlobals(const BaseSurface& base, const glm::dvec3& eye);

/// The box of `prim`'s displaced surface over its whole domain seen from `eye`, as its BVH box is
/// made: the union of its interval bounds over a grid of `cells` x `cells` cells of its (u,v);
/// infinite if a bound overflows somewhere.
Box DisplacedBox(const Primitive& prim, const glm::dvec3& eye, int cells);

/// Refines the meshes of `desc` that the reader left as read (RefineScene, scene/refine.h: an error
/// there at the mesh's request), then compiles every displacement instance of `desc` (each with
/// its own parameter values) and specialises it for its surface (an instance like an earlier one
/// reuses its compilation).
/// Shaders are found as NAME.sl or NAME.afb in the scene's Option "searchpath" "shader" (relative
/// directories taken from the RIB file's directory), then in `shaderPaths`;
/// `preprocess` gives the -I and -D of the C preprocessor. The shaders' diagnostics go to *report
/// (may be null); on error returns false with an error there at the Displacement request.
/// `threads` refine the meshes and bound the primitives' boxes (0: one per core), as
/// RenderOptions::threads renders.
bool PrepareScene(SceneDesc desc, const std::vector<std::string>& shaderPaths,
                  const lang::PreprocessOptions& preprocess, PreparedScene* out, diag::Report* report, int threads = 0);

/// The memory `scene` holds, by structure (not the allocator's overhead): the primitives, their
/// descriptions, the shapes, meshes, attributes and colour fields they share (each once), the
/// BVH, and what a render adds per primitive (a bound hierarchy's slot, and per thread an
/// intersector's slot) with `threads` threads. Programs and shaders
/// are left out (a few per scene).
uint64_t SceneBytes(const PreparedScene& scene, int threads);

/// The side of the tiles RenderImage cuts `camera`'s image (its crop) into with `options`:
/// options.tileSize, halved for small images down to 8 pixels so that every thread gets four
/// tiles at least; exactly options.tileSize if options.fixedTileSize. The image's pixels do not
/// depend on it.
int RenderTileSize(const CameraDesc& camera, const RenderOptions& options);

/// Renders the prepared scene into `image`: full resolution, RGBA plus the AOVs the Display mode
/// asks for, pixels outside the CropWindow zero (renderer/film.h), row 0 at the top.
void RenderImage(const PreparedScene& scene, const RenderOptions& options, image::ImageBuffer* image,
                 RenderStats* stats);

}  // namespace affray::renderer
