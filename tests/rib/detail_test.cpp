// Levels of detail (rib/detail.cpp): Detail, DetailRange and RelativeDetail choose which
// primitives a scene keeps by the raster area of a bound.
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "rib/rib.h"
#include "tests/rib/rib_test_util.h"

namespace affray {
namespace {

// A 200 x 100 image, fov 90 across the shorter axis: the screen window is [-2, 2] x [-1, 1], one
// screen unit is 50 pixels, and the cube [-1, 1]^3 at distance `distance` (its near face at
// distance - 1) covers (100 / (distance - 1))^2 pixels.
std::string Scene(double distance, const std::string& options, const std::string& levels) {
    return "Format 200 100 1\nProjection \"perspective\" \"fov\" [90]\n" + options + "Translate 0 0 " +
           std::to_string(distance) + "\nWorldBegin\nAttributeBegin\n" + levels + "AttributeEnd\nWorldEnd\n";
}

// Two levels switching at a detail of 150 (the middle of the transition 100 .. 200): a coarse one
// (red) below, a fine one (green) above and at any larger size.
const std::string kBound = "Detail [-1 1 -1 1 -1 1]\n";
const std::string kLevels =
    "DetailRange [0 0 100 200]\nColor [1 0 0]\nSphere 1 -1 1 360\n"
    "DetailRange [100 200 1e38 1e38]\nColor [0 1 0]\nSphere 1 -1 1 360\n"
    "Disk 0 1 360\n";

// The colours of the primitives the scene keeps, "r" or "g" each.
std::string Kept(const std::string& rib, diag::Report* report = nullptr) {
    diag::Report local;
    diag::Report& r = report ? *report : local;
    std::optional<renderer::SceneDesc> scene = rib::ParseRib(rib, "t.rib", &r);
    INFO(r);
    REQUIRE(scene);
    std::string kept;
    for (const renderer::PrimitiveDesc& p : scene->primitives) kept += p.color.x == 1 ? "r" : "g";
    return kept;
}

TEST_CASE("detail: DetailRange keeps the level drawn at the bound's raster area", "[rib][detail]") {
    CHECK(Kept(Scene(11, "", kBound + kLevels)) == "r");    // 100 pixels
    CHECK(Kept(Scene(9.5, "", kBound + kLevels)) == "r");   // 138.4 pixels, below the middle
    CHECK(Kept(Scene(9, "", kBound + kLevels)) == "gg");    // 156.25 pixels, above it
    CHECK(Kept(Scene(6, "", kBound + kLevels)) == "gg");    // 400 pixels
    CHECK(Kept(Scene(1.5, "", kBound + kLevels)) == "gg");  // 40,000 pixels
    // A bound reaching behind the eye is as large as can be: the level up to infinity.
    CHECK(Kept(Scene(0.5, "", kBound + kLevels)) == "gg");
    // Far away neither level is drawn once the coarse one's range ends.
    CHECK(Kept(Scene(6, "", kBound + "DetailRange [0 0 10 20]\nColor [1 0 0]\nSphere 1 -1 1 360\n")) == "");
    // Primitives before any DetailRange, and after the block that held one, are always drawn.
    CHECK(Kept(Scene(11, "",
                     "Color [0 1 0]\nSphere 1 -1 1 360\nAttributeBegin\n" + kBound + kLevels +
                         "AttributeEnd\nColor [1 0 0]\nSphere 1 -1 1 360\n")) == "grr");
}

TEST_CASE("detail: a delayed archive of a level not drawn is not opened", "[rib][detail]") {
    // 100 pixels at 11 units: the coarse level is drawn, the fine one's archive (which does not
    // exist) is never opened; at 6 units (400 pixels) it is, and its absence is an error.
    const std::string levels = kBound + "DetailRange [0 0 100 200]\nColor [1 0 0]\nSphere 1 -1 1 360\n" +
                               "DetailRange [100 200 1e38 1e38]\n"
                               "Procedural \"DelayedReadArchive\" [\"no_such_fine.rib\"] [-1 1 -1 1 -1 1]\n";
    CHECK(Kept(Scene(11, "", levels)) == "r");
    CHECK(test::FirstError(Scene(6, "", levels)).find("no_such_fine.rib") != std::string::npos);
}

TEST_CASE("detail: RelativeDetail scales the detail, and the bound follows the transform", "[rib][detail]") {
    CHECK(Kept(Scene(6, "RelativeDetail 0.25\n", kBound + kLevels)) == "r");  // 400 x 0.25 = 100
    CHECK(Kept(Scene(11, "RelativeDetail 4\n", kBound + kLevels)) == "gg");   // 100 x 4 = 400
    // The bound is in the object space of the Detail request: scaled by 2 it is the cube at 6
    // seen from 11 units (its near face at 9): (100 / 4.5)^2 = 494 pixels.
    CHECK(Kept(Scene(11, "", "Scale 2 2 2\n" + kBound + kLevels)) == "gg");
}

TEST_CASE("detail: a range without a bound draws the finest level, with a warning", "[rib][detail]") {
    diag::Report report;
    CHECK(Kept(Scene(11, "", kLevels), &report) == "gg");
    bool warned = false, noted = false;
    for (const diag::Diagnostic& d : report.all()) {
        warned |= d.message.find("'DetailRange' without a 'Detail' bound") != std::string::npos;
        noted |= d.message.find("transitions are not dissolved") != std::string::npos;
    }
    CHECK(warned);
    CHECK(noted);
}

TEST_CASE("detail: malformed bounds and ranges are errors at their request", "[rib][detail]") {
    CHECK(test::FirstError(Scene(6, "", "DetailRange [3 2 1 0]\n")) ==
          "t.rib:6: error: 'DetailRange' expects 0 <= minvisible <= lowertransition <= uppertransition <= "
          "maxvisible, got 3 2 1 0");
    CHECK(test::FirstError(Scene(6, "", "Detail [1 -1 0 1 0 1]\n")) ==
          "t.rib:6: error: 'Detail' expects a finite bound with each minimum at most its maximum, got 1 > -1");
    CHECK(test::FirstError(Scene(6, "RelativeDetail 0\n", "")) ==
          "t.rib:3: error: 'RelativeDetail' must be positive, got 0");
    CHECK(test::FirstError("DetailRange [0 0 1 1]\n") ==
          "t.rib:1: error: 'DetailRange' must come between 'WorldBegin' and 'WorldEnd'");
}

}  // namespace
}  // namespace affray
