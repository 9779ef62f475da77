// tests/scene/refine_test.cpp: the preparation of the meshes that the RIB reader leaves as read
// (scene/refine.*): reading keeps a mesh unrefined and RefineScene makes its elements; what only
// the refinement finds is an error there, at the mesh's request as the reader gave it; the result
// does not depend on the threads; a copy of the scene keeps its mesh as read.
#include <catch2/catch.hpp>

#include <functional>
#include <string>
#include <thread>
#include <variant>
#include <vector>

#include "rib/rib.h"
#include "scene/refine.h"
#include "tests/rib/rib_test_util.h"

using namespace affray;
using renderer::BaseSurface;
using renderer::PolygonMesh;
using renderer::PrimitiveDesc;
using renderer::RefineScene;
using renderer::SceneDesc;
using renderer::SubdivisionMesh;

namespace {

/// The scene of `world` as the reader leaves it (no mesh refined); it must read without errors.
SceneDesc Read(const std::string& world) {
    diag::Report report;
    std::optional<SceneDesc> scene = rib::ParseRib(test::InWorld(world), "t.rib", &report);
    INFO(report);
    REQUIRE(scene);
    REQUIRE(!report.hasErrors());
    return *scene;
}

/// A grid of nx x ny quads in the plane z = 0 as a mesh request's arguments: the faces' sizes,
/// their corners, `tags` (a subdivision mesh's) and "P".
std::string Grid(int nx, int ny, const std::string& tags = "") {
    std::string sizes, corners, points;
    for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i) {
            const int a = j * (nx + 1) + i, b = a + 1, c = b + nx + 1, d = a + nx + 1;
            sizes += "4 ";
            corners +=
                std::to_string(a) + " " + std::to_string(b) + " " + std::to_string(c) + " " + std::to_string(d) + " ";
        }
    for (int j = 0; j <= ny; ++j)
        for (int i = 0; i <= nx; ++i) points += std::to_string(i) + " " + std::to_string(j) + " 0 ";
    return "[" + sizes + "] [" + corners + "] " + tags + " \"P\" [" + points + "]";
}

/// `n` colours as a parameter's values, all different.
std::string Colors(int n) {
    std::string values;
    for (int i = 0; i < n; ++i) values += std::to_string(double(i) / n) + " 0.5 1 ";
    return "[" + values + "]";
}

/// A ParallelFor that runs body(i) for i from n - 1 down to 0, each on a thread of its own: the
/// meshes at once, started in the order opposite the scene's.
void Backwards(size_t n, const std::function<void(size_t)>& body) {
    std::vector<std::thread> threads;
    for (size_t i = n; i-- > 0;) threads.emplace_back(body, i);
    for (std::thread& t : threads) t.join();
}

/// The report's diagnostics and their notes with their places, one per line ("t.rib:3: error:
/// ... (column 5) | the source line").
std::string Located(const diag::Report& report) {
    std::string text;
    auto line = [&](const diag::Diagnostic& d) {
        text += test::ShortDiagnostic(d) + " (column " + std::to_string(d.where.column) + ") | " + d.where.text + "\n";
    };
    for (const diag::Diagnostic& d : report.all()) {
        line(d);
        for (const diag::Diagnostic& note : d.notes) line(note);
    }
    return text;
}

}  // namespace

TEST_CASE("refine: reading keeps a mesh as read, RefineScene makes its elements", "[scene][refine]") {
    SECTION("a polygon mesh of 1000 faces") {
        SceneDesc scene = Read("Sphere 1 -1 1 360\nPointsPolygons " + Grid(40, 25) + "\n");
        REQUIRE(scene.primitives.size() == 2);
        const PrimitiveDesc& read = scene.primitives[1];
        CHECK(read.elements == 0);
        REQUIRE(read.unrefined);
        REQUIRE(std::holds_alternative<PolygonMesh>(read.unrefined->mesh));
        CHECK(std::get<PolygonMesh>(read.unrefined->mesh).loops.size() == 1000);
        CHECK(read.base.kind() != BaseSurface::Kind::MeshPiece);
        CHECK(!scene.primitives[0].unrefined);

        REQUIRE(RefineScene(&scene, nullptr));
        REQUIRE(scene.primitives.size() == 2);
        const PrimitiveDesc& refined = scene.primitives[1];
        CHECK(!refined.unrefined);
        CHECK(refined.elements == 1000);
        REQUIRE(refined.base.kind() == BaseSurface::Kind::MeshPiece);
        CHECK(refined.base.pieceRef().mesh->pieces.size() == 1000);
        CHECK(refined.attr().line == 3);
    }
    SECTION("a subdivision mesh of 1000 faces") {
        SceneDesc scene = Read("SubdivisionMesh \"catmull-clark\" " + Grid(40, 25) + "\n");
        REQUIRE(scene.primitives.size() == 1);
        CHECK(scene.primitives[0].elements == 0);
        REQUIRE(scene.primitives[0].unrefined);
        REQUIRE(std::holds_alternative<SubdivisionMesh>(scene.primitives[0].unrefined->mesh));
        CHECK(std::get<SubdivisionMesh>(scene.primitives[0].unrefined->mesh).faceSizes.size() == 1000);

        REQUIRE(RefineScene(&scene, nullptr));
        REQUIRE(scene.primitives.size() == 1);
        const PrimitiveDesc& refined = scene.primitives[0];
        CHECK(!refined.unrefined);
        REQUIRE(refined.base.kind() == BaseSurface::Kind::SubdivPatch);
        // Without interpolateboundary the faces on the boundary are not rendered: 38 x 23 faces
        // of 16 patches each (two steps).
        CHECK(refined.elements == 38 * 23 * 16);
        CHECK(refined.base.subdivRef().patches->patches.size() == refined.elements);
    }
    SECTION("a mesh whose every face is a hole is dropped") {
        SceneDesc scene = Read("SubdivisionMesh \"catmull-clark\" " + Grid(1, 1) + "\nSphere 1 -1 1 360\n");
        REQUIRE(scene.primitives.size() == 2);
        REQUIRE(RefineScene(&scene, nullptr));
        REQUIRE(scene.primitives.size() == 1);
        CHECK(scene.primitives[0].base.kind() == BaseSurface::Kind::Quadric);
    }
}

TEST_CASE("refine: what only refinement finds is an error at the mesh's request", "[scene][refine]") {
    SECTION("a degenerate face") {
        SceneDesc scene = Read("Sphere 1 -1 1 360\n  PointsPolygons [3] [0 1 2] \"P\" [0 0 0  1 1 1  2 2 2]\n");
        diag::Report report;
        CHECK(!RefineScene(&scene, &report));
        CHECK(Located(report) ==
              "t.rib:3: error: 'PointsPolygons' face 0 is degenerate: its outline has no area (its corners are "
              "collinear or coincide) (column 3) |   PointsPolygons [3] [0 1 2] \"P\" [0 0 0  1 1 1  2 2 2]\n");
    }
    SECTION("a topology that cannot be refined, in an object: the note at the instance") {
        SceneDesc scene = Read(
            "ObjectBegin 1\n"
            "  SubdivisionMesh \"catmull-clark\" [4 4] [0 1 2 3  0 1 2 3] \"P\" [0 0 0  1 0 0  1 1 0  0 1 0]\n"
            "ObjectEnd\n"
            "Translate 0 0 1\n"
            " ObjectInstance 1\n");
        diag::Report report;
        CHECK(!RefineScene(&scene, &report));
        CHECK(Located(report) ==
              "t.rib:3: error: 'SubdivisionMesh' edge 0-1 is used twice in the same direction (a non-manifold edge, "
              "or faces of opposite orientation) (column 3) |   SubdivisionMesh \"catmull-clark\" [4 4] [0 1 2 3  0 1 "
              "2 3] \"P\" [0 0 0  1 0 0  1 1 0  0 1 0]\n"
              "t.rib:6: note: in the instance of object '1' here (column 2) |  ObjectInstance 1\n");
    }
    SECTION("patches that overflow") {
        SceneDesc scene = Read(
            "SubdivisionMesh \"catmull-clark\" [4 4 4 4] [0 1 4 3  1 2 5 4  3 4 7 6  4 5 8 7] "
            "[\"interpolateboundary\"] [0 0] [] [] "
            "\"P\" [0 0 0  1 0 0  2 0 0  0 1 0  1 1 1.7e308  2 1 0  0 2 0  1 2 0  2 2 0]\n");
        diag::Report report;
        CHECK(!RefineScene(&scene, &report));
        CHECK(test::ShortDiagnostic(report.all().at(0)) ==
              "t.rib:2: error: 'SubdivisionMesh' has a patch that overflows in world space");
    }
    SECTION("the first of two bad meshes in the scene's order, whatever the threads") {
        const std::string bad = "PointsPolygons [3] [0 1 2] \"P\" [0 0 0  1 1 1  2 2 2]\n";
        for (const renderer::ParallelFor& parallelFor : {renderer::ParallelFor(), renderer::ParallelFor(Backwards)}) {
            SceneDesc scene = Read("PointsPolygons " + Grid(3, 3) + "\n" + bad + bad);
            diag::Report report;
            CHECK(!RefineScene(&scene, &report, parallelFor));
            REQUIRE(report.all().size() == 1);
            CHECK(report.all()[0].where.line == 3);
        }
    }
}

TEST_CASE("refine: the scene refined does not depend on the threads", "[scene][refine]") {
    // Meshes of every kind with colours of every class that a mesh keeps, between other shapes.
    const std::string world = "PointsPolygons " + Grid(6, 5) + " \"facevarying color Cs\" " + Colors(120) +
                              "\nSphere 1 -1 1 360\n"
                              "GeneralPolygon [4 3] \"P\" [0 0 0  4 0 0  4 4 0  0 4 0  1 1 0  2 1 0  1 2 0] \"Os\" "
                              "[0.5 0.5 0.5]\n"
                              "SubdivisionMesh \"catmull-clark\" " +
                              Grid(4, 4, "[\"interpolateboundary\"] [0 0] [] []") + " \"vertex color Cs\" " +
                              Colors(25) + " \"uniform color Os\" " + Colors(16) +
                              "\nSubdivisionMesh \"catmull-clark\" " + Grid(3, 2) + "\n";
    SceneDesc serial = Read(world);
    SceneDesc threaded = serial;  // shares its meshes as read with `serial`
    SceneDesc later = serial;
    REQUIRE(RefineScene(&serial, nullptr));
    // The copies kept their meshes whole: the scene refined first did not take their arrays.
    REQUIRE(later.primitives[0].unrefined);
    CHECK(std::get<PolygonMesh>(later.primitives[0].unrefined->mesh).points.size() == 42);
    REQUIRE(RefineScene(&threaded, nullptr, Backwards));
    REQUIRE(RefineScene(&later, nullptr));
    const std::string text = ToString(serial);
    CHECK(text.find("Cs=(") != std::string::npos);
    // 30 quads, the sphere, the square with a hole in 7 triangles, 16 faces in 16 patches each, and
    // the last mesh dropped (every face on its boundary).
    CHECK(ElementPrimitives(serial).size() == 30 + 1 + 7 + 256);
    CHECK(ToString(threaded) == text);
    CHECK(ToString(later) == text);
}
