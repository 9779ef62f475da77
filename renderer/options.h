// renderer/options.h: everything a run of the renderer is told (the command line's flags): where
// shaders are found, how many threads, the budgets and the tolerance. One Options builds one
// Renderer (renderer/renderer.h), which prepares and renders every frame of the run with it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "lang/preprocess.h"
#include "renderer/bound_tree.h"
#include "renderer/bvh.h"
#include "renderer/intersect.h"

namespace affray::renderer {

struct Primitive;

/// Makes the intersector one thread uses for one primitive (`index` in PreparedScene::primitives).
using IntersectorFactory = std::function<std::unique_ptr<SurfaceIntersector>(const Primitive& primitive, int index)>;

/// The side of a block of pixels whose camera rays are traced as a group (`--ray-groups`).
inline constexpr int kDefaultRayGroupPixels = 8;

struct Options {
    /// The threads preparing and rendering use, the caller's included (the Renderer's pool);
    /// 0: one per core.
    int threads = 0;

    // Preparing a scene.
    /// Where shaders are looked for after the scene's Option "searchpath" "shader" (relative
    /// directories taken from the RIB file's directory): NAME.sl or NAME.afb.
    std::vector<std::string> shaderPaths = {};
    /// The C preprocessor's -I and -D for every shader compiled.
    lang::PreprocessOptions preprocess = {};

    // Rendering.
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
    int tileSize = 32;                             // pixels per side (less for small images: Renderer::TileSize)
    /// Take the tiles last first: the image must not depend on the order (a test option).
    bool reverseTileOrder = false;
    /// How the top-level BVH splits its nodes: the image must not depend on the tree's shape (a
    /// test option, issue 32).
    Bvh::Split bvhSplit = Bvh::Split::kSah;
    /// Camera rays are traced in groups of this many pixels per side, which share the walk of the
    /// bound hierarchies' top levels (RayGroup); blocks of the whole image, so the image does not
    /// depend on the tiles. 0: every ray alone.
    int rayGroupPixels = kDefaultRayGroupPixels;
    /// Replaces the guaranteed intersector, for every primitive and thread: the benches' in-process
    /// tessellation baseline (bench/) renders the same samples, shading and shadows through it.
    /// Empty: affray's own.
    IntersectorFactory intersectorFactory = {};
};

}  // namespace affray::renderer
