// renderer/render.h: what preparing a scene makes (renderer/prepare.cpp) and rendering it
// reads and reports (renderer/render.cpp): primitives with their specialised programs, the
// prepared scene, the render's statistics. The Renderer that makes and renders them is
// renderer/renderer.h.
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
    bool stopped = false;   // RenderControl::stop was set in time: some tiles are missing from the image
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
    /// The surface shader compiled for the primitive's light set (its `surface` program), or
    /// null: the built-in model of SurfaceDesc shades it.
    std::shared_ptr<const compiler::CompiledShader> surface;
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
    /// Renderer::Prepare: a vector moved with the scene keeps its elements in place).
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

/// The shader globals that do not vary over `base` seen from `eye` under a shutter open from
/// `shutterOpen` to `shutterClose`, for specialising its programs: E, du, dv, time (the opening)
/// and dtime (the shutter's length), and for a flat patch N, Ng, dPdu and dPdv.
std::vector<compiler::ConstantGlobal> ConstantGlobals(const BaseSurface& base, const glm::dvec3& eye,
                                                      double shutterOpen, double shutterClose);

/// The box of `prim`'s displaced surface over its whole domain seen from `eye`, as its BVH box is
/// made: the union of its interval bounds over a grid of `cells` x `cells` cells of its (u,v);
/// infinite if a bound overflows somewhere.
Box DisplacedBox(const Primitive& prim, const glm::dvec3& eye, int cells);

/// The memory `scene` holds, by structure (not the allocator's overhead): the primitives, their
/// descriptions, the shapes, meshes, attributes and colour fields they share (each once), the
/// BVH, and what a render adds per primitive (a bound hierarchy's slot, and per thread an
/// intersector's slot) with `threads` threads. Programs and shaders
/// are left out (a few per scene).
uint64_t SceneBytes(const PreparedScene& scene, int threads);

}  // namespace affray::renderer
