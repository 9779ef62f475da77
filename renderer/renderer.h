// renderer/renderer.h: the Renderer, built from one Options: it prepares scenes as read (their
// shaders compiled and specialised, their primitives boxed, the BVH built: renderer/prepare.cpp)
// and renders prepared scenes into images (renderer/render.cpp), both on the one thread pool it
// owns. The command line builds one per run and prepares and renders each frame with it.
#pragma once

#include <atomic>
#include <mutex>
#include <set>
#include <string>

#include "diag/diagnostic.h"
#include "image/exr_writer.h"
#include "renderer/film.h"
#include "renderer/options.h"
#include "renderer/render.h"
#include "renderer/thread_pool.h"

namespace affray::renderer {

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

/// What one render is given besides the Renderer's options: the hooks of one frame.
struct RenderControl {
    /// Set, by a signal handler say, to stop the render: the workers check it between samples and
    /// give up their unfinished tiles; RenderStats::stopped is then true and the image incomplete.
    const std::atomic<bool>* stop = nullptr;
    /// Where finished tiles are kept and restored from (null: nowhere).
    TileStore* tileStore = nullptr;
    /// Told how the render advances (the command line draws its progress bar with it); null: no one.
    RenderProgress* progress = nullptr;
    /// Cut the image into tiles of exactly this side (a resumed render must cut it as the
    /// interrupted one did); 0: Renderer::TileSize's.
    int tileSize = 0;
};

class Renderer {
  public:
    /// Starts the pool's threads (options.threads, 0: one per core).
    explicit Renderer(Options options);

    const Options& options() const { return m_options; }
    /// The threads preparing and rendering use (Options::threads resolved).
    int threads() const { return m_pool.size(); }
    ThreadPool& pool() const { return m_pool; }

    /// Prepares `desc` as read for rendering into *out: refines the meshes the reader kept as read
    /// (RefineScene, scene/refine.h, meshes at once on the pool: an error there at the mesh's
    /// request), checks the image against the limits, runs
    /// its MakeTexture requests, compiles every displacement instance (each with its own
    /// parameter values; an instance like an earlier one reuses its compilation) and specialises
    /// it for its surface, and boxes every primitive for the BVH. Shaders are found as NAME.sl or
    /// NAME.afb in the scene's Option "searchpath" "shader", then in Options::shaderPaths. The
    /// shaders' diagnostics go to *report (may be null); on error returns false with an error
    /// there at the request at fault.
    bool Prepare(SceneDesc desc, PreparedScene* out, diag::Report* report) const;

    /// Renders the prepared scene into `image`: full resolution, RGBA plus the AOVs the Display
    /// mode asks for, pixels outside the CropWindow zero (renderer/film.h), row 0 at the top.
    void Render(const PreparedScene& scene, image::ImageBuffer* image, RenderStats* stats,
                const RenderControl& control = {}) const;

    /// The side of the tiles Render cuts `camera`'s image (its crop) into without a
    /// RenderControl::tileSize: Options::tileSize, halved for small images down to 8 pixels so
    /// that every thread gets four tiles at least. The image's pixels do not depend on it.
    int TileSize(const CameraDesc& camera) const;

  private:
    Options m_options;
    mutable ThreadPool m_pool;  // used by const calls: running a job changes no result
    /// What Prepare has warned about surface shaders, once per sentence over every frame the
    /// renderer prepares (a scene's frames name the same shaders).
    mutable std::mutex m_warnedMutex;
    mutable std::set<std::string> m_warned;
};

}  // namespace affray::renderer
