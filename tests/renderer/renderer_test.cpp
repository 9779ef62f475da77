// tests/renderer/renderer_test.cpp: one Renderer from one Options: its threads are started once
// and serve every render it makes (renderer/renderer.h), and it renders what its options say.
#include "renderer/renderer.h"

#include <catch2/catch.hpp>

#include <chrono>
#include <condition_variable>
#include <mutex>
#include <set>
#include <thread>

#include "rib/rib.h"
#include "tests/test_util.h"

namespace affray::renderer {
namespace {

constexpr const char* kScene = R"(Format 64 48 1
PixelSamples 1 1
Projection "perspective" "fov" [40]
Translate 0 0 4
WorldBegin
  Patch "bilinear" "P" [-1 -1 0  1 -1 0  -1 1 0  1 1 0]
WorldEnd
)";

/// Misses every ray: the test only looks at which threads ask for intersectors.
class NoHits : public SurfaceIntersector {
  public:
    bool Intersect(const Ray&, double, double, const Tolerance&, bool, Hit*, IntersectStats&,
                   const RayGroup*) override {
        return false;
    }
};

// The render in which this thread last asked for an intersector (0: never). A pool's threads keep
// it from one render to the next; threads started anew for each render would not.
thread_local int t_lastRender = 0;

TEST_CASE("Renderer: one pool of Options::threads threads serves every render", "[renderer]") {
    std::mutex mutex;
    int render = 0;
    std::set<std::thread::id> threads;  // asking in the current render
    int carried = 0;                    // threads that had asked in the render before
    Options options;
    options.threads = 3;
    options.tileSize = 8;
    std::condition_variable arrived;
    options.intersectorFactory = [&](const Primitive&, int) {
        std::unique_lock<std::mutex> lock(mutex);
        if (threads.insert(std::this_thread::get_id()).second && t_lastRender == render - 1 && render > 1) ++carried;
        t_lastRender = render;
        // Held until the three threads have come (or a while has passed): the first cannot take
        // every tile before the others wake.
        arrived.notify_all();
        arrived.wait_for(lock, std::chrono::seconds(5), [&] { return threads.size() >= 3; });
        return std::unique_ptr<SurfaceIntersector>(new NoHits);
    };
    const Renderer renderer(options);
    CHECK(renderer.threads() == 3);
    diag::Report report;
    std::optional<SceneDesc> desc = rib::ParseRib(kScene, "scene.rib", &report);
    REQUIRE(desc);
    PreparedScene prepared;
    REQUIRE(renderer.Prepare(*desc, &prepared, &report));
    for (render = 1; render <= 3; ++render) {
        threads.clear();
        image::ImageBuffer image;
        RenderStats stats;
        renderer.Render(prepared, &image, &stats);
        INFO("render " << render);
        // 48 tiles of 8 x 8 (TileSize keeps 8: four tiles a thread at least): every thread gets some.
        CHECK(threads.size() == 3);
        CHECK(stats.cameraRays >= 64 * 48);  // every pixel (and the tiles' filter margins again)
    }
    // Renders 2 and 3 ran on the threads of the render before (the caller's and the pool's two).
    CHECK(carried == 2 * 3);
}

TEST_CASE("Renderer::TileSize halves tiles until every thread has four", "[renderer]") {
    CameraDesc camera;
    camera.xres = 64;
    camera.yres = 64;
    CHECK(Renderer(Options{.threads = 1}).TileSize(camera) == 32);  // 4 tiles of 32
    CHECK(Renderer(Options{.threads = 2}).TileSize(camera) == 16);  // 16 tiles of 16
    CHECK(Renderer(Options{.threads = 16}).TileSize(camera) == 8);  // never below 8
}

}  // namespace
}  // namespace affray::renderer
