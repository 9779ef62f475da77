// tests/renderer/level_of_detail_test.cpp: the scene's level of detail (ShadingRate,
// GeometricApproximation "flatness"; rib/settings.cpp, PrimitiveAttributes::sceneTolerance): read as
// attributes, honoured where coarser than the render's tolerance (cheaper, every hit still
// certified to the tolerance asked for), and not at all when the tolerance is the user's.
#include <catch2/catch.hpp>

#include <string>

#include "renderer/renderer.h"
#include "rib/rib.h"
#include "tests/test_util.h"

using namespace affray;

namespace {

const char* const kHead =
    "Format 48 36 1\nPixelSamples 1 1\nProjection \"perspective\" \"fov\" [40]\nTranslate 0 0 3\nWorldBegin\n";

renderer::SceneDesc Parse(const std::string& rib) {
    diag::Report error;
    std::optional<renderer::SceneDesc> desc = rib::ParseRib(rib, "lod.rib", &error);
    INFO(error);
    REQUIRE(desc);
    return *desc;
}

/// Renders `rib` with shaders/ and returns its statistics; `given`: the tolerance is the user's.
renderer::RenderStats Render(const std::string& rib, bool given) {
    renderer::SceneDesc desc = Parse(rib);
    diag::Report error;
    renderer::PreparedScene prepared;
    REQUIRE(renderer::Renderer(renderer::Options{.shaderPaths = {test::SourceDir() + "/shaders"}})
                .Prepare(desc, &prepared, &error));
    renderer::Options options;
    options.threads = 2;
    options.sceneTolerance = !given;
    image::ImageBuffer image;
    renderer::RenderStats stats;
    renderer::Renderer(options).Render(prepared, &image, &stats);
    CHECK(stats.camera.depthLimitHits == 0);
    return stats;
}

}  // namespace

TEST_CASE("level of detail: ShadingRate and flatness are attributes giving each primitive its tolerance",
          "[renderer][rib][lod]") {
    const renderer::SceneDesc desc = Parse(std::string(kHead) +
                                           "Sphere 1 -1 1 360\n"
                                           "AttributeBegin\nShadingRate 4\nSphere 1 -1 1 360\n"
                                           "GeometricApproximation \"flatness\" [3]\nSphere 1 -1 1 360\n"
                                           "ShadingRate 0.25\nGeometricApproximation \"flatness\" 0.1\n"
                                           "Sphere 1 -1 1 360\nAttributeEnd\n"
                                           "GeometricApproximation \"motionfactor\" 1\nSphere 1 -1 1 360\n"
                                           "WorldEnd\n");
    REQUIRE(desc.primitives.size() == 5);
    CHECK(desc.primitives[0].attr().sceneTolerance == 0.5);  // RI defaults: ShadingRate 1
    CHECK(desc.primitives[1].attr().sceneTolerance == 1.0);  // 0.5 sqrt(4)
    CHECK(desc.primitives[2].attr().sceneTolerance == 3.0);  // the larger of the two
    CHECK(desc.primitives[3].attr().sceneTolerance == 0.25);
    CHECK(desc.primitives[4].attr().sceneTolerance == 0.5);  // AttributeEnd restored; motionfactor ignored
    diag::Report error;
    CHECK_FALSE(
        rib::ParseRib(std::string(kHead) + "GeometricApproximation \"flatness\" -1\nWorldEnd\n", "x.rib", &error));
    CHECK(test::LastMessage(error).find("must not be negative") != std::string::npos);
}

TEST_CASE("level of detail: a coarser ShadingRate is cheaper and certified to what it asks",
          "[renderer][render][lod]") {
    const std::string body = "Displacement \"dented\" \"Km\" [0.08] \"frequency\" [6]\nSphere 1 -1 1 360\nWorldEnd\n";
    const renderer::RenderStats fine = Render(std::string(kHead) + body, false);
    const renderer::RenderStats coarse = Render(std::string(kHead) + "ShadingRate 64\n" + body, false);
    const renderer::RenderStats given = Render(std::string(kHead) + "ShadingRate 64\n" + body, true);
    // At 0.5 sqrt(64) = 4 pixels the hierarchy stops levels earlier: fewer regions and bounds.
    CHECK(coarse.camera.regionsBounded < fine.camera.regionsBounded);
    CHECK(coarse.camera.regionsEvaluated < fine.camera.regionsEvaluated);
    // Every hit stays certified, to the coarser tolerance: errors grow with it, 8 times (4 pixels
    // over 0.5), not more.
    INFO("fine " << fine.camera.maxHitError << ", coarse " << coarse.camera.maxHitError);
    CHECK(coarse.camera.maxHitError > fine.camera.maxHitError);
    CHECK(coarse.camera.maxHitError < 10 * fine.camera.maxHitError);
    // A tolerance the user gave wins over the scene's.
    CHECK(given.camera.regionsBounded == fine.camera.regionsBounded);
    CHECK(given.camera.maxHitError == fine.camera.maxHitError);
}
