// tests/renderer/render_coverage.h: whole-renderer crack tests shared by the mesh and subdivision
// suites: render a RIB scene without and with an outward displacement and count the camera rays
// that the undisplaced surface stops but the displaced one does not (a crack), or stops farther.
#pragma once

#include <catch2/catch.hpp>

#include <optional>
#include <string>
#include <vector>

#include "renderer/film.h"
#include "renderer/renderer.h"
#include "rib/rib.h"
#include "tests/test_util.h"

namespace affray::test {

/// Renders `rib` (one sample per pixel at its centre, box filter, 2 threads) with shaders from
/// `dir`; no ray may reach the depth limit. The render's statistics go to *stats if given. With a
/// `tolerancePixels`, hits are certified to it whatever the scene's own tolerance says.
inline image::ImageBuffer RenderRib(const TempDir& dir, const std::string& rib, renderer::RenderStats* stats = nullptr,
                                    std::optional<double> tolerancePixels = std::nullopt) {
    affray::diag::Report error;
    std::optional<renderer::SceneDesc> desc = rib::ParseRib(rib, dir.Path("scene.rib"), &error);
    INFO(error);
    REQUIRE(desc);
    desc->camera.xsamples = desc->camera.ysamples = 1;
    desc->camera.jitter = false;
    desc->camera.filter = renderer::FilterDesc{renderer::FilterDesc::Kind::Box, 1, 1};
    renderer::PreparedScene prepared;
    const bool ok =
        renderer::Renderer(renderer::Options{.shaderPaths = {dir.Path(".")}}).Prepare(*desc, &prepared, &error);
    INFO(error);
    REQUIRE(ok);
    renderer::Options options;
    options.threads = 2;
    if (tolerancePixels) {
        options.tolerancePixels = *tolerancePixels;
        options.sceneTolerance = false;
    }
    image::ImageBuffer image;
    renderer::RenderStats own;
    if (!stats) stats = &own;
    renderer::Renderer(options).Render(prepared, &image, stats);
    CHECK(stats->camera.depthLimitHits == 0);
    return image;
}

inline const std::vector<float>& DepthOf(const image::ImageBuffer& image) {
    for (const auto& [n, values] : image.extraChannels)
        if (n == "Z") return values;
    FAIL("no Z channel");
    static std::vector<float> none;
    return none;
}

/// What the displaced image does with the pixels the base image covers.
struct Coverage {
    int covered = 0, misses = 0, farther = 0;
};

inline Coverage CompareCoverage(const image::ImageBuffer& base, const image::ImageBuffer& displaced) {
    const std::vector<float>&zBase = DepthOf(base), &zDisplaced = DepthOf(displaced);
    Coverage c;
    for (size_t i = 0; i < zBase.size(); ++i) {
        if (base.rgba[4 * i + 3] == 0) continue;
        ++c.covered;
        if (displaced.rgba[4 * i + 3] == 0)
            ++c.misses;
        else if (zDisplaced[i] > zBase[i])
            ++c.farther;
    }
    return c;
}

}  // namespace affray::test
