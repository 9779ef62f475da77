// tests/renderer/render_text.h: a RIB text rendered as the renderer renders it (its own samples,
// filter and options, shaders from shaders/, 2 threads), and the RMSE of two images' RGB: for the
// brute-force tests of camera effects (depth of field, motion blur) and of surface shaders, which
// compare whole images.
#pragma once

#include <catch2/catch.hpp>

#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "renderer/renderer.h"
#include "rib/rib.h"
#include "tests/test_util.h"

namespace affray::test {

/// The image of the RIB text `rib`, which must read and prepare, with shaders from `shaderPaths`
/// (shaders/ unless given).
inline image::ImageBuffer RenderText(const std::string& rib, std::optional<std::vector<std::string>> shaderPaths = {}) {
    diag::Report error;
    std::optional<renderer::SceneDesc> desc = rib::ParseRib(rib, "t.rib", &error);
    INFO(error);
    REQUIRE(desc);
    renderer::PreparedScene prepared;
    const bool ok = renderer::Renderer(
                        renderer::Options{.shaderPaths = shaderPaths.value_or(std::vector{SourceDir() + "/shaders"})})
                        .Prepare(*desc, &prepared, &error);
    INFO(error);
    REQUIRE(ok);
    renderer::Options options;
    options.threads = 2;
    image::ImageBuffer image;
    renderer::RenderStats stats;
    renderer::Renderer(options).Render(prepared, &image, &stats);
    return image;
}

/// The root mean square difference of the RGB channels of two images of one size.
inline double RgbRmse(const image::ImageBuffer& a, const image::ImageBuffer& b) {
    double sum = 0;
    for (size_t i = 0; i < a.rgba.size(); ++i) {
        if (i % 4 == 3) continue;
        const double d = double(a.rgba[i]) - double(b.rgba[i]);
        sum += d * d;
    }
    return std::sqrt(sum / double(a.rgba.size() / 4 * 3));
}

}  // namespace affray::test
