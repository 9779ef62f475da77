// tests/renderer/mesh_render_test.cpp: displaced polygon meshes through the whole renderer
// (rib/polygons.cpp, scene/geometry/mesh.*, renderer/render.cpp): a closed one-sided mesh with
// vertex normals displaced outward hides every camera ray that the undisplaced mesh stops, no
// farther than it, so no ray passes through a crack.
#include <catch2/catch.hpp>

#include <map>
#include <sstream>

#include "tests/renderer/render_coverage.h"

using namespace affray;
using namespace affray::renderer;

namespace {

/// An octahedron with every face cut into four `levels` times, on the unit sphere, as
/// PointsPolygons with vertex normals (the points themselves).
std::string SphereMeshRib(int levels) {
    std::vector<glm::dvec3> p = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    std::vector<std::array<int, 3>> faces = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4},
                                             {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
    for (int level = 0; level < levels; ++level) {
        std::map<std::pair<int, int>, int> mid;
        auto midpoint = [&](int a, int b) {
            auto key = std::minmax(a, b);
            if (auto it = mid.find(key); it != mid.end()) return it->second;
            p.push_back(glm::normalize(p[a] + p[b]));
            return mid[key] = static_cast<int>(p.size()) - 1;
        };
        std::vector<std::array<int, 3>> next;
        for (const auto& t : faces) {
            const int ab = midpoint(t[0], t[1]), bc = midpoint(t[1], t[2]), ca = midpoint(t[2], t[0]);
            next.push_back({t[0], ab, ca});
            next.push_back({ab, t[1], bc});
            next.push_back({ca, bc, t[2]});
            next.push_back({ab, bc, ca});
        }
        faces = next;
    }
    std::ostringstream out;
    out.precision(17);
    out << "PointsPolygons [";
    for (size_t i = 0; i < faces.size(); ++i) out << " 3";
    out << "] [";
    for (const auto& t : faces) out << ' ' << t[0] << ' ' << t[1] << ' ' << t[2];
    out << "]\n \"P\" [";
    for (const glm::dvec3& q : p) out << ' ' << q.x << ' ' << q.y << ' ' << q.z;
    out << "]\n \"N\" [";
    for (const glm::dvec3& q : p) out << ' ' << q.x << ' ' << q.y << ' ' << q.z;
    out << "]\n";
    return out.str();
}

}  // namespace

TEST_CASE("mesh render: a closed displaced mesh with vertex normals stops every ray its base stops",
          "[renderer][mesh][cracks]") {
    test::TempDir dir;
    dir.Write("outward.sl",
              "displacement outward(float Km = 0.12) { P += (Km + 0.1 * noise(P * 3)) * normalize(N);"
              " N = calculatenormal(P); }");
    const std::string head = R"(Format 40 40 1
Projection "perspective" "fov" [40]
Display "t.exr" "file" "rgba,Z"
Translate 0 0 4.5
Rotate 33 1 1 0
WorldBegin
Sides 1
)";
    const std::string mesh = SphereMeshRib(1);
    const image::ImageBuffer base = test::RenderRib(dir, head + mesh + "WorldEnd\n");
    const image::ImageBuffer displaced =
        test::RenderRib(dir, head + "Displacement \"outward\"\n" + mesh + "WorldEnd\n");
    const test::Coverage c = test::CompareCoverage(base, displaced);
    CHECK(c.covered > 300);
    CHECK(c.misses == 0);
    CHECK(c.farther == 0);
}
