// tests/scene/geometry/mesh_test.cpp: polygon meshes as base surfaces (scene/geometry/mesh.*):
// the pieces' parameterisations in every number type, bounds that contain a displaced piece's
// points, the triangulation of concave faces, faces with holes and collinear corners, and the
// absence of cracks in closed displaced meshes with vertex normals (and their presence without).
#include <catch2/catch.hpp>

#include <cmath>
#include <map>

#include "renderer/bound_tree.h"
#include "renderer/intersect.h"
#include "scene/geometry/mesh.h"
#include "scene/geometry/surface.h"
#include "tests/renderer/edge_rays.h"
#include "tests/test_random.h"
#include "tests/test_util.h"

using namespace affray;
using renderer::MeshPiece;
using renderer::MeshVariable;
using renderer::PolygonMesh;
using renderer::StorageClass;

namespace {

/// A mesh of faces with one loop each (indices into `points`).
PolygonMesh Faces(std::vector<glm::dvec3> points, const std::vector<std::vector<int>>& faces) {
    PolygonMesh mesh;
    mesh.points = std::move(points);
    for (const auto& f : faces) {
        mesh.loops.push_back(1);
        mesh.loopSizes.push_back(static_cast<int>(f.size()));
        mesh.corners.insert(mesh.corners.end(), f.begin(), f.end());
    }
    return mesh;
}

std::vector<MeshPiece> Split(const PolygonMesh& mesh) {
    std::vector<MeshPiece> pieces;
    const std::string problem = renderer::SplitMesh(mesh, &pieces);
    INFO(problem);
    REQUIRE(problem.empty());
    return pieces;
}

/// Vertex normals: the normalised sum of the (area-weighted) normals of the faces around each point.
void AverageNormals(PolygonMesh* mesh) {
    std::vector<glm::dvec3> sum(mesh->points.size(), glm::dvec3(0.0));
    size_t c = 0;
    for (int size : mesh->loopSizes) {
        glm::dvec3 n(0.0);
        for (int k = 0; k < size; ++k) {
            const glm::dvec3 &a = mesh->points[mesh->corners[c + k]],
                             &b = mesh->points[mesh->corners[c + (k + 1) % size]];
            n += glm::cross(a, b);
        }
        for (int k = 0; k < size; ++k) sum[mesh->corners[c + k]] += glm::normalize(n);
        c += size;
    }
    MeshVariable normals{StorageClass::Vertex, 3, {}};
    for (const glm::dvec3& n : sum) {
        const glm::dvec3 u = glm::normalize(n);
        normals.values.insert(normals.values.end(), {u.x, u.y, u.z});
    }
    mesh->normals = normals;
}

/// A cube [-1, 1]^3, faces counter-clockwise seen from outside.
PolygonMesh Cube() {
    std::vector<glm::dvec3> p;
    p.reserve(8);
    for (int i = 0; i < 8; ++i) p.emplace_back(i & 1 ? 1 : -1, i & 2 ? 1 : -1, i & 4 ? 1 : -1);
    return Faces(p, {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}});
}

/// An octahedron with each face cut into four, its points pushed onto the unit sphere.
PolygonMesh SphereMesh() {
    std::vector<glm::dvec3> p = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    const int tri[8][3] = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
    std::map<std::pair<int, int>, int> mid;
    auto midpoint = [&](int a, int b) {
        auto key = std::minmax(a, b);
        if (auto it = mid.find(key); it != mid.end()) return it->second;
        p.push_back(glm::normalize(p[a] + p[b]));
        return mid[key] = static_cast<int>(p.size()) - 1;
    };
    std::vector<std::vector<int>> faces;
    for (const auto& t : tri) {
        const int ab = midpoint(t[0], t[1]), bc = midpoint(t[1], t[2]), ca = midpoint(t[2], t[0]);
        faces.push_back({t[0], ab, ca});
        faces.push_back({ab, t[1], bc});
        faces.push_back({ca, bc, t[2]});
        faces.push_back({ab, bc, ca});
    }
    return Faces(p, faces);
}

/// A prism over an L-shaped (concave) cap, with collinear points on the L's long sides.
PolygonMesh LPrism() {
    const glm::dvec2 l[] = {{0, 0}, {1, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}, {0, 1}};
    const int n = 8;
    std::vector<glm::dvec3> p;
    for (int z = 0; z < 2; ++z)
        for (const glm::dvec2& q : l) p.emplace_back(q.x - 0.8, q.y - 0.8, z ? 0.6 : -0.6);
    std::vector<std::vector<int>> faces;
    std::vector<int> top, bottom;
    for (int i = 0; i < n; ++i) top.push_back(n + i), bottom.push_back(n - 1 - i);
    faces.push_back(top);
    faces.push_back(bottom);
    for (int i = 0; i < n; ++i) faces.push_back({i, (i + 1) % n, n + (i + 1) % n, n + i});
    return Faces(p, faces);
}

double Area(const MeshPiece& piece) {
    const glm::dvec3 a = glm::cross(piece.P[1] - piece.P[0], piece.P[2] - piece.P[0]);
    if (piece.triangle) return 0.5 * glm::length(a);
    return 0.5 * (glm::length(a) + glm::length(glm::cross(piece.P[2] - piece.P[3], piece.P[1] - piece.P[3])));
}

double TotalArea(const std::vector<MeshPiece>& pieces) {
    double sum = 0;
    for (const MeshPiece& p : pieces) sum += Area(p);
    return sum;
}

}  // namespace

TEST_CASE("mesh: a triangle is a bilinear piece with one edge collapsed, a convex quad a bilinear piece",
          "[renderer][mesh]") {
    const glm::dvec3 a(0, 0, 0), b(2, 0, 0), c(0, 1, 1), d(2, 1, 0.5);
    std::vector<MeshPiece> pieces = Split(Faces({a, b, d, c}, {{0, 1, 3}, {0, 1, 2, 3}}));
    REQUIRE(pieces.size() == 2);
    REQUIRE(pieces[0].triangle);
    REQUIRE_FALSE(pieces[1].triangle);
    for (double u : {0.0, 0.3, 1.0})
        for (double v : {0.0, 0.6, 1.0}) {
            // Barycentric weights (1-u)(1-v), u(1-v), v.
            const vm::Vec3<double> t = renderer::MeshPieceFrame<double>(pieces[0], u, v).P;
            test::RequireVec({t.x, t.y, t.z}, (1 - u) * (1 - v) * a + u * (1 - v) * b + v * c);
            const vm::Vec3<double> q = renderer::MeshPieceFrame<double>(pieces[1], u, v).P;
            test::RequireVec({q.x, q.y, q.z}, (1 - u) * (1 - v) * a + u * (1 - v) * b + (1 - u) * v * c + u * v * d);
        }
    // The geometric normal follows the corners' order, as dPdu x dPdv does.
    CHECK(glm::dot(pieces[0].faceNormal, glm::cross(b - a, c - a)) > 0);
    CHECK(glm::length(pieces[0].faceNormal) == Approx(1.0));
}

TEMPLATE_TEST_CASE("mesh: every number type evaluates a piece at a point as double does", "[renderer][mesh]",
                   vm::Interval, vm::Affine, vm::ReducedAffine, vm::Dual<double>, vm::Dual<vm::Affine>) {
    PolygonMesh mesh = Faces({{0, 0, 0}, {2, 0, 0}, {2.5, 1, 0.5}, {0, 1, 1}}, {{0, 1, 2}, {0, 1, 2, 3}});
    mesh.normals = MeshVariable{StorageClass::Vertex, 3, {0, 0, 1, 0.2, 0, 1, 0, 0.3, 1, -0.1, 0.1, 1}};
    mesh.st = MeshVariable{StorageClass::FaceVarying, 2, {0, 0, 1, 0, 1, 1, 0, 0, 0.5, 0, 0.5, 0.5, 0, 0.5}};
    for (const MeshPiece& piece : Split(mesh)) {
        for (double u : {0.0, 0.25, 0.9, 1.0})
            for (double v : {0.0, 0.5, 1.0}) {
                if constexpr (std::is_same_v<TestType, vm::Affine> || std::is_same_v<TestType, vm::Dual<vm::Affine>>)
                    vm::Affine::BeginEvaluation();
                const TestType tu = renderer::SurfaceParameter<TestType>(u, u, 0);
                const TestType tv = renderer::SurfaceParameter<TestType>(v, v, 1);
                const auto f = renderer::MeshPieceFrame(piece, tu, tv);
                const auto g = renderer::MeshPieceFrame(piece, u, v);
                TestType s, t;
                double sd, td;
                renderer::MeshPieceST(piece, tu, tv, &s, &t);
                renderer::MeshPieceST(piece, u, v, &sd, &td);
                auto same = [](const TestType& x, double want) {
                    const vm::Interval r = RangeOf(x);
                    INFO(r.toString() << " vs " << want);
                    CHECK(r.contains(want));
                    CHECK(r.hi() - r.lo() <= 1e-12);
                };
                for (int i = 0; i < 3; ++i) {
                    same(f.P[i], g.P[i]);
                    same(f.dPdu[i], g.dPdu[i]);
                    same(f.dPdv[i], g.dPdv[i]);
                    same(f.normalDirection[i], g.normalDirection[i]);
                    if constexpr (std::is_same_v<TestType, vm::Dual<double>>) {
                        // The duals' exact derivatives are the frame's tangents.
                        CHECK(f.P[i].du == Approx(g.dPdu[i]).margin(1e-12));
                        CHECK(f.P[i].dv == Approx(g.dPdv[i]).margin(1e-12));
                    }
                }
                same(s, sd);
                same(t, td);
            }
    }
}

TEST_CASE("mesh: a displacement shader's bounds over a triangle and a quad contain its points", "[renderer][mesh]") {
    // Reads P, N (interpolated vertex normals), s, t (facevarying st) and Ng.
    const std::string source =
        "displacement d(float Km = 0.1) { P += (Km * sin(10 * s) * cos(7 * t) + 0.05 * noise(P * 3)) * normalize(N)"
        " + 0.01 * Ng; }";
    const compiler::CompiledShader shader = test::CompileOrThrow(source);
    const vm::ProgramOutput& out = *shader.bound.findOutput("P");
    PolygonMesh mesh = Faces({{0, 0, 0}, {2, 0, 0}, {2.5, 1, 0.5}, {0, 1, 1}}, {{0, 1, 3}, {0, 1, 2, 3}});
    mesh.normals = MeshVariable{StorageClass::Vertex, 3, {0, 0, 1, 0.5, 0, 1, 0, 0.5, 1, -0.4, 0.3, 1}};
    mesh.st = MeshVariable{StorageClass::FaceVarying, 2, {0, 0, 1, 0, 1, 1, 0, 0, 0.5, 0, 0.5, 0.5, 0, 0.5}};
    const std::vector<MeshPiece> pieces = Split(mesh);
    REQUIRE(pieces.size() == 2);
    vm::Interpreter<double> point(shader.bound);
    vm::Interpreter<vm::Affine> affine(shader.bound);
    vm::Interpreter<vm::Interval> interval(shader.bound);
    test::Rng rng(29);
    for (const MeshPiece& piece : pieces) {
        INFO(ToString(piece));
        for (int r = 0; r < 150; ++r) {
            const double width = r == 0 ? 1.0 : std::pow(10.0, -rng.uniform(0, 6));
            const double u0 = rng.uniform(0, 1 - width), v0 = rng.uniform(0, 1 - width);
            renderer::SetMeshPieceGlobals(affine, piece, u0, u0 + width, v0, v0 + width, glm::dvec3(0.0), r % 2);
            affine.Run();
            const vm::Vec3<vm::Affine> a = affine.OutputTriple(out);
            renderer::SetMeshPieceGlobals(interval, piece, u0, u0 + width, v0, v0 + width, glm::dvec3(0.0), r % 2);
            interval.Run();
            const vm::Vec3<vm::Interval> iv = interval.OutputTriple(out);
            for (int k = 0; k < 6; ++k) {
                // Corners first, then random points.
                const double u = k < 4 ? u0 + (k & 1) * width : rng.uniform(u0, u0 + width);
                const double v = k < 4 ? v0 + (k >> 1) * width : rng.uniform(v0, v0 + width);
                renderer::SetMeshPieceGlobals(point, piece, u, u, v, v, glm::dvec3(0.0), r % 2);
                point.Run();
                const vm::Vec3<double> p = point.OutputTriple(out);
                for (int c = 0; c < 3; ++c) {
                    INFO("region at (" << u0 << ", " << v0 << ") width " << width << ", component " << c);
                    CHECK(RangeOf(a[c]).contains(p[c]));
                    CHECK(iv[c].contains(p[c]));
                }
            }
        }
    }
}

TEST_CASE("mesh: concave faces, collinear corners and holes are triangulated", "[renderer][mesh]") {
    SECTION("an L with collinear corners keeps every corner and its area") {
        const PolygonMesh prism = LPrism();
        std::vector<MeshPiece> pieces;
        REQUIRE(renderer::SplitMesh(prism, &pieces).empty());
        std::vector<MeshPiece> cap;
        for (const MeshPiece& p : pieces)
            if (p.face == 0) cap.push_back(p);
        CHECK(cap.size() == 6);  // 8 corners: n - 2 triangles, none of zero area
        CHECK(TotalArea(cap) == Approx(3.0));
        for (const MeshPiece& p : cap) {
            CHECK(p.triangle);
            CHECK(Area(p) > 1e-9);
            CHECK(glm::dot(glm::cross(p.P[1] - p.P[0], p.P[2] - p.P[0]), p.faceNormal) > 0);
        }
        // Every corner of the L is a corner of some triangle (no T-junction on the sides).
        for (int i = 8; i < 16; ++i) {
            bool used = false;
            for (const MeshPiece& p : cap)
                for (int k = 0; k < 3; ++k) used = used || p.P[k] == prism.points[i];
            CHECK(used);
        }
    }
    SECTION("a square with a square hole") {
        PolygonMesh mesh;
        mesh.points = {{0, 0, 0}, {4, 0, 0}, {4, 4, 0}, {0, 4, 0}, {1, 1, 0}, {1, 3, 0}, {3, 3, 0}, {3, 1, 0}};
        mesh.loops = {2};
        mesh.loopSizes = {4, 4};
        mesh.corners = {0, 1, 2, 3, 4, 5, 6, 7};
        const std::vector<MeshPiece> pieces = Split(mesh);
        CHECK(TotalArea(pieces) == Approx(12.0));
        CHECK(pieces.size() == 8);
        // No triangle covers the hole's centre.
        for (const MeshPiece& p : pieces) {
            const glm::dvec3 c(2, 2, 0);
            const double w0 = glm::cross(p.P[1] - p.P[0], c - p.P[0]).z, w1 = glm::cross(p.P[2] - p.P[1], c - p.P[1]).z,
                         w2 = glm::cross(p.P[0] - p.P[2], c - p.P[2]).z;
            CHECK_FALSE((w0 > 0 && w1 > 0 && w2 > 0));
        }
    }
    SECTION("a concave quad is two triangles, not a folded patch") {
        const std::vector<MeshPiece> pieces =
            Split(Faces({{0, 0, 0}, {2, 0, 0}, {0.5, 0.5, 0}, {0, 2, 0}}, {{0, 1, 2, 3}}));
        CHECK(pieces.size() == 2);
        CHECK(TotalArea(pieces) == Approx(1.0));
    }
    SECTION("a degenerate face is an error") {
        std::vector<MeshPiece> pieces;
        CHECK(renderer::SplitMesh(Faces({{0, 0, 0}, {1, 1, 1}, {2, 2, 2}}, {{0, 1, 2}}), &pieces) ==
              "face 0 is degenerate: its outline has no area (its corners are collinear or coincide)");
        // A bow tie: its two lobes cancel, so its outline has no area either.
        CHECK_FALSE(
            renderer::SplitMesh(Faces({{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {2, 2, 0}}, {{0, 1, 2, 3}}), &pieces).empty());
    }
}

namespace {

/// Rays from outside aimed at points of every edge of every piece (vertices included) of `mesh`
/// displaced outward: the displaced surface, if closed, lies between the ray's origin and the
/// point, so the ray must hit it no farther. Returns the number of rays that do not.
int EdgeRayMisses(const PolygonMesh& mesh, const vm::Program& program, int* rays) {
    const std::vector<MeshPiece> pieces = Split(mesh);
    std::vector<std::unique_ptr<renderer::SurfaceIntersector>> intersectors;
    intersectors.reserve(pieces.size());
    for (const MeshPiece& p : pieces)
        intersectors.push_back(renderer::MakeSurfaceIntersector(renderer::BaseSurface(p), program, glm::dvec3(0.0),
                                                                renderer::BoundMode::Affine, 30));
    test::EdgeRays probe(std::move(intersectors));
    for (const MeshPiece& piece : pieces) {
        const int order[] = {0, 1, 3, 2};
        const int n = piece.triangle ? 3 : 4;
        for (int e = 0; e < n; ++e) {
            const int i = piece.triangle ? e : order[e], j = piece.triangle ? (e + 1) % 3 : order[(e + 1) % 4];
            for (double lambda : {0.0, 0.125, 0.5, 0.7, 0.999}) {
                const glm::dvec3 target = (1 - lambda) * piece.P[i] + lambda * piece.P[j];
                const glm::dvec3 normal = piece.hasNormals
                                              ? glm::normalize((1 - lambda) * piece.N[i] + lambda * piece.N[j])
                                              : piece.faceNormal;
                probe.At(target, normal, glm::normalize(piece.P[j] - piece.P[i]), [&] { return ToString(piece); });
            }
        }
    }
    *rays += probe.rays;
    return probe.misses;
}

}  // namespace

TEST_CASE("mesh: a displaced closed mesh with vertex normals has no cracks at edges and vertices",
          "[renderer][mesh][cracks]") {
    const compiler::CompiledShader shader =
        test::CompileOrThrow("displacement d(float Km = 0.15) { P += (Km + 0.1 * noise(P * 2)) * normalize(N); }");
    for (auto [name, mesh] : {std::pair{"cube", Cube()}, {"sphere", SphereMesh()}, {"L prism", LPrism()}}) {
        INFO(name);
        AverageNormals(&mesh);
        int rays = 0;
        CHECK(EdgeRayMisses(mesh, shader.bound, &rays) == 0);
        CHECK(rays > 300);
    }
    // Without vertex normals the faces part at the creases (as in RenderMan): the same rays
    // through the cube's cracks miss, so the test above can fail.
    int rays = 0;
    CHECK(EdgeRayMisses(Cube(), shader.bound, &rays) > 0);
}
