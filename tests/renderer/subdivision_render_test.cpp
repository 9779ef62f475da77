// tests/renderer/subdivision_render_test.cpp: displaced subdivision meshes through the whole
// renderer (rib/subdivision.cpp, scene/geometry/subdivision.*, renderer/render.cpp): a closed
// one-sided Catmull-Clark mesh with extraordinary vertices, a triangle and a pentagon, displaced
// outward, hides every camera ray that the undisplaced surface stops, no farther than it, so no
// ray passes through a crack.
#include <catch2/catch.hpp>

#include <cmath>
#include <sstream>

#include "tests/renderer/render_coverage.h"

using namespace affray;

namespace {

/// A pentagonal prism capped by a pyramid (a pentagon, five quads, five triangles around a
/// valence-5 apex), with a crease around the prism's top.
std::string TowerRib() {
    std::ostringstream out;
    out.precision(17);
    out << "SubdivisionMesh \"catmull-clark\" [5 4 4 4 4 4 3 3 3 3 3] [4 3 2 1 0";
    for (int i = 0; i < 5; ++i) out << ' ' << i << ' ' << (i + 1) % 5 << ' ' << 5 + (i + 1) % 5 << ' ' << 5 + i;
    for (int i = 0; i < 5; ++i) out << ' ' << 5 + i << ' ' << 5 + (i + 1) % 5 << " 10";
    out << "] [\"crease\"] [6 1] [5 6 7 8 9 5] [3] \"P\" [";
    for (int level = 0; level < 2; ++level)
        for (int i = 0; i < 5; ++i)
            out << ' ' << std::cos(2 * M_PI * i / 5) << ' ' << std::sin(2 * M_PI * i / 5) << ' ' << level * 1.5 - 0.75;
    out << " 0.2 0.1 1.8]\n";
    return out.str();
}

}  // namespace

TEST_CASE("subdivision render: a closed displaced subdivision mesh stops every ray its base stops",
          "[renderer][subdivision][cracks]") {
    test::TempDir dir;
    dir.Write("outward.sl",
              "displacement outward(float Km = 0.1) { P += (Km + 0.08 * noise(P * 3)) * normalize(N);"
              " N = calculatenormal(P); }");
    const std::string head = R"(Format 40 40 1
Projection "perspective" "fov" [40]
Display "t.exr" "file" "rgba,Z"
Translate 0 0 4.2
Rotate 33 1 1 0
WorldBegin
Sides 1
)";
    const std::string mesh = TowerRib();
    const image::ImageBuffer base = test::RenderRib(dir, head + mesh + "WorldEnd\n");
    const image::ImageBuffer displaced =
        test::RenderRib(dir, head + "Displacement \"outward\"\n" + mesh + "WorldEnd\n");
    const test::Coverage c = test::CompareCoverage(base, displaced);
    CHECK(c.covered > 300);
    CHECK(c.misses == 0);
    CHECK(c.farther == 0);
}
