// tests/scene/geometry/subdivision_test.cpp: Catmull-Clark subdivision meshes as base surfaces
// (scene/geometry/subdivision.*): regular faces are their B-spline patches; limit positions
// are exact and the approximated patches stay within kAccDeviation of deep refinement; shared
// edges have the same points and normal directions from both sides; bounds of the patches and of
// displaced patches contain their points in every number type; rays aimed at every shared edge
// of a displaced closed mesh hit it (and miss without the normal field); the tags.
#include <catch2/catch.hpp>

#include <cmath>

#include "renderer/intersect.h"
#include "scene/geometry/subdivision.h"
#include "scene/geometry/surface.h"
#include "tests/renderer/edge_rays.h"
#include "tests/test_random.h"
#include "tests/test_util.h"
#include "tests/vm/shader_containment.h"

using namespace affray;
using renderer::SubdivisionMesh;
using renderer::SubdivisionResult;
using renderer::SubdivPatch;

namespace {

SubdivisionMesh Mesh(std::vector<glm::dvec3> points, const std::vector<std::vector<int>>& faces) {
    SubdivisionMesh m;
    m.points = std::move(points);
    for (const auto& f : faces) {
        m.faceSizes.push_back(static_cast<int>(f.size()));
        m.faceVerts.insert(m.faceVerts.end(), f.begin(), f.end());
    }
    return m;
}

/// The cube [-1, 1]^3, counter-clockwise from outside: eight valence-3 vertices.
SubdivisionMesh Cube() {
    std::vector<glm::dvec3> p;
    p.reserve(8);
    for (int i = 0; i < 8; ++i) p.emplace_back(i & 1 ? 1 : -1, i & 2 ? 1 : -1, i & 4 ? 1 : -1);
    return Mesh(p, {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}});
}

/// A pentagonal prism capped by a pyramid: a pentagon, five quads, five triangles around a
/// valence-5 apex.
SubdivisionMesh Tower() {
    std::vector<glm::dvec3> p;
    for (int level = 0; level < 2; ++level)
        for (int i = 0; i < 5; ++i)
            p.emplace_back(std::cos(2 * M_PI * i / 5), std::sin(2 * M_PI * i / 5), level * 1.5 - 0.75);
    p.emplace_back(0.2, 0.1, 1.8);
    std::vector<std::vector<int>> faces = {{4, 3, 2, 1, 0}};
    for (int i = 0; i < 5; ++i) {
        const int j = (i + 1) % 5;
        faces.push_back({i, j, 5 + j, 5 + i});
        faces.push_back({5 + i, 5 + j, 10});
    }
    return Mesh(p, faces);
}

/// An n x m grid of quads on a torus (periodic both ways): every vertex has valence 4.
SubdivisionMesh Torus(int n, int m, std::vector<glm::dvec3>* grid = nullptr) {
    std::vector<glm::dvec3> p;
    for (int j = 0; j < m; ++j)
        for (int i = 0; i < n; ++i) {
            const double a = 2 * M_PI * i / n, b = 2 * M_PI * j / m, r = 2 + 0.7 * std::cos(b) + 0.1 * std::sin(3 * a);
            p.emplace_back(r * std::cos(a), r * std::sin(a), 0.7 * std::sin(b));
        }
    std::vector<std::vector<int>> faces;
    for (int j = 0; j < m; ++j)
        for (int i = 0; i < n; ++i)
            faces.push_back({j * n + i, j * n + (i + 1) % n, ((j + 1) % m) * n + (i + 1) % n, ((j + 1) % m) * n + i});
    if (grid) *grid = p;
    return Mesh(p, faces);
}

/// An open n x n grid of quads in the plane z = 0 over [0, n]^2.
SubdivisionMesh Grid(int n) {
    std::vector<glm::dvec3> p;
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i) p.emplace_back(i, j, 0.1 * std::sin(i + 2.0 * j));
    std::vector<std::vector<int>> faces;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i)
            faces.push_back({j * (n + 1) + i, j * (n + 1) + i + 1, (j + 1) * (n + 1) + i + 1, (j + 1) * (n + 1) + i});
    return Mesh(p, faces);
}

SubdivisionResult Build(const SubdivisionMesh& mesh, int levels = -1) {
    SubdivisionResult r;
    const std::string problem = renderer::BuildSubdivisionPatches(mesh, &r, levels);
    INFO(problem);
    REQUIRE(problem.empty());
    return r;
}

glm::dvec3 Glm(const vm::Vec3<double>& v) { return {v.x, v.y, v.z}; }

/// The unit normal the renderer uses at (u, v) (before any orientation flip).
glm::dvec3 NormalAt(const SubdivPatch& p, double u, double v) {
    const renderer::SurfaceFrame<double> f = renderer::SubdivPatchFrame<double>(p, u, v);
    return glm::normalize(f.hasNormalDirection ? Glm(f.normalDirection) : glm::cross(Glm(f.dPdu), Glm(f.dPdv)));
}

/// The (u, v) of point t along edge k (0: v = 0, 1: u = 1, 2: v = 1, 3: u = 0), from corner k to k + 1.
glm::dvec2 EdgeParam(int k, double t) {
    switch (k) {
        case 0: return {t, 0};
        case 1: return {1, t};
        case 2: return {1 - t, 1};
        default: return {0, 1 - t};
    }
}

double Diagonal(const SubdivisionMesh& m) {
    glm::dvec3 lo(1e30), hi(-1e30);
    for (const glm::dvec3& p : m.points) lo = glm::min(lo, p), hi = glm::max(hi, p);
    return glm::length(hi - lo);
}

/// The distance from x to the patches (a grid search, then Gauss-Newton on the nearest patches).
double DistanceToPatches(const std::vector<SubdivPatch>& patches, const glm::dvec3& x) {
    std::vector<std::pair<double, std::pair<size_t, glm::dvec2>>> best;
    for (size_t i = 0; i < patches.size(); ++i) {
        double d = 1e30;
        glm::dvec2 at(0);
        for (int a = 0; a <= 8; ++a)
            for (int b = 0; b <= 8; ++b) {
                const double dd = glm::length(patches[i].geometry.At(a / 8.0, b / 8.0) - x);
                if (dd < d) d = dd, at = {a / 8.0, b / 8.0};
            }
        best.push_back({d, {i, at}});
    }
    std::sort(best.begin(), best.end(), [](const auto& p, const auto& q) { return p.first < q.first; });
    double result = best[0].first;
    for (size_t k = 0; k < std::min<size_t>(4, best.size()); ++k) {
        const SubdivPatch& p = patches[best[k].second.first];
        glm::dvec2 uv = best[k].second.second;
        for (int it = 0; it < 30; ++it) {
            const renderer::SurfaceFrame<double> f = renderer::BicubicFrame<double>(p.geometry, uv.x, uv.y);
            const glm::dvec3 r = Glm(f.P) - x, du = Glm(f.dPdu), dv = Glm(f.dPdv);
            const double a = glm::dot(du, du), b = glm::dot(du, dv), c = glm::dot(dv, dv);
            const double g0 = glm::dot(du, r), g1 = glm::dot(dv, r), det = a * c - b * b;
            if (!(det > 0)) break;
            uv -= glm::dvec2((c * g0 - b * g1) / det, (a * g1 - b * g0) / det);
            uv = glm::clamp(uv, 0.0, 1.0);
        }
        result = std::min(result, glm::length(p.geometry.At(uv.x, uv.y) - x));
    }
    return result;
}

/// The uniform cubic B-spline weights at t.
std::array<double, 4> BSplineWeights(double t) {
    const double s = 1 - t;
    return {s * s * s / 6, (3 * t * t * t - 6 * t * t + 4) / 6, (-3 * t * t * t + 3 * t * t + 3 * t + 1) / 6,
            t * t * t / 6};
}

}  // namespace

TEST_CASE("subdivision: a regular mesh's patches are its B-spline patches", "[renderer][subdivision]") {
    std::vector<glm::dvec3> grid;
    const int n = 7, m = 5;
    const SubdivisionResult r = Build(Torus(n, m, &grid));
    CHECK(r.levels == 0);
    REQUIRE(r.patches.size() == size_t(n) * size_t(m));
    CHECK(r.regularPatches == n * m);
    test::Rng rng(3);
    for (int j = 0; j < m; ++j)
        for (int i = 0; i < n; ++i) {
            const SubdivPatch& p = r.patches[size_t(j) * size_t(n) + size_t(i)];
            for (int s = 0; s < 4; ++s) {
                const double u = rng.uniform(0, 1), v = rng.uniform(0, 1);
                const auto wu = BSplineWeights(u), wv = BSplineWeights(v);
                glm::dvec3 want(0.0);
                for (int a = 0; a < 4; ++a)
                    for (int b = 0; b < 4; ++b)
                        want +=
                            wu[a] * wv[b] * grid[size_t((j - 1 + b + m) % m) * size_t(n) + size_t((i - 1 + a + n) % n)];
                CHECK(glm::length(p.geometry.At(u, v) - want) < 1e-12);
            }
        }
    // The same mesh refined once is still regular, and its patches are the same surface.
    const SubdivisionResult refined = Build(Torus(n, m), 1);
    CHECK(refined.regularPatches == int(refined.patches.size()));
    CHECK(DistanceToPatches(r.patches, refined.patches[7].geometry.At(0.3, 0.6)) < 1e-9);
}

TEST_CASE("subdivision: limit positions are exact and the patches stay near the limit surface",
          "[renderer][subdivision]") {
    for (auto [name, mesh] : {std::pair{"cube", Cube()}, {"tower", Tower()}}) {
        INFO(name);
        const SubdivisionResult r = Build(mesh);
        CHECK(r.levels == renderer::kSubdivisionLevels);
        CHECK(r.regularPatches > 0);
        CHECK(r.regularPatches < int(r.patches.size()));
        // A vertex keeps its index through refinement and its limit position is where deep
        // refinement takes it.
        const SubdivisionResult deep = Build(mesh, 6);
        for (size_t v = 0; v < r.refinedPoints.size(); ++v)
            CHECK(glm::length(r.refinedPoints[v] - deep.refinedPoints[v]) < 1e-12);
        // Every patch corner is a limit position.
        for (const SubdivPatch& p : r.patches)
            for (int c = 0; c < 4; ++c) {
                const glm::dvec3 corner = p.geometry.At(c & 1, c >> 1);
                double nearest = 1e30;
                for (const glm::dvec3& x : r.refinedPoints) nearest = std::min(nearest, glm::length(x - corner));
                CHECK(nearest < 1e-12);
            }
        // The patches against the limit surface: limit points of a deeper mesh.
        const SubdivisionResult five = Build(mesh, 4);
        double worst = 0;
        for (const glm::dvec3& x : five.refinedPoints) worst = std::max(worst, DistanceToPatches(r.patches, x));
        const double relative = worst / Diagonal(mesh);
        WARN(name << ": largest distance to the limit surface " << worst << " (" << relative << " of the diagonal)");
        CHECK(relative <= renderer::kAccDeviation);
        CHECK(relative > 0);  // the approximation is not exact, so this measures something
    }
}

TEST_CASE("subdivision: a dense control mesh takes fewer steps and its patches stay near the limit surface",
          "[renderer][subdivision]") {
    // Past kSubdivisionPatchBudget patches the default steps are cut: a cube refined five times
    // (6,144 quads, valence-3 corners) takes one step, not two (98,304 patches).
    const SubdivisionMesh dense = renderer::RefineSubdivisionMesh(Cube(), 5);
    REQUIRE(dense.faceSizes.size() == 6144);
    const SubdivisionResult r = Build(dense);
    CHECK(r.levels == 1);
    CHECK(r.patches.size() == 4 * 6144);
    // Its patches without any step (what a mesh of more than 65,536 quads gets), against the
    // limit surface (the limit positions of the mesh refined twice), near an extraordinary corner
    // where the patches are approximated: within a small part of a face's size.
    const SubdivisionMesh mesh = renderer::RefineSubdivisionMesh(Cube(), 3);  // 384 faces
    const SubdivisionResult none = Build(mesh, 0);
    CHECK(none.levels == 0);
    REQUIRE(none.patches.size() == 384);
    CHECK(none.regularPatches < 384);
    const SubdivisionResult deep = Build(mesh, 2);
    const double face = Diagonal(mesh) / (std::sqrt(3.0) * 8);  // a face's side: the cube's over 8
    const glm::dvec3 corner = deep.refinedPoints[0];            // a limit corner of valence 3
    double worst = 0;
    int near = 0;
    for (const glm::dvec3& x : deep.refinedPoints) {
        if (glm::length(x - corner) > 2 * face) continue;
        ++near;
        worst = std::max(worst, DistanceToPatches(none.patches, x));
    }
    CHECK(near > 10);
    WARN("no step, 384 faces: largest distance to the limit surface near a corner " << worst / face
                                                                                    << " of a face's side");
    CHECK(worst / face < 0.002);  // measured 3.1e-4
    CHECK(worst > 0);
}

TEST_CASE("subdivision: neighbours share points and normal directions along every edge", "[renderer][subdivision]") {
    for (auto [name, mesh] : {std::pair{"cube", Cube()}, {"tower", Tower()}}) {
        INFO(name);
        const SubdivisionResult r = Build(mesh);
        const double scale = Diagonal(mesh);
        int edges = 0;
        double worstP = 0, worstN = 0;
        for (size_t a = 0; a < r.patches.size(); ++a)
            for (int ka = 0; ka < 4; ++ka) {
                const SubdivPatch& pa = r.patches[a];
                const glm::dvec2 a0 = EdgeParam(ka, 0), a1 = EdgeParam(ka, 1);
                const glm::dvec3 from = pa.geometry.At(a0.x, a0.y), to = pa.geometry.At(a1.x, a1.y);
                // The neighbour runs the edge the other way.
                for (size_t b = 0; b < r.patches.size(); ++b)
                    for (int kb = 0; kb < 4; ++kb) {
                        if (b == a) continue;
                        const SubdivPatch& pb = r.patches[b];
                        const glm::dvec2 b0 = EdgeParam(kb, 0), b1 = EdgeParam(kb, 1);
                        if (glm::length(pb.geometry.At(b0.x, b0.y) - to) > 1e-9 * scale ||
                            glm::length(pb.geometry.At(b1.x, b1.y) - from) > 1e-9 * scale)
                            continue;
                        ++edges;
                        for (double t : {0.0, 0.1, 0.37, 0.5, 0.81, 1.0}) {
                            const glm::dvec2 ua = EdgeParam(ka, t), ub = EdgeParam(kb, 1 - t);
                            worstP =
                                std::max(worstP, glm::length(pa.geometry.At(ua.x, ua.y) - pb.geometry.At(ub.x, ub.y)));
                            worstN = std::max(worstN, glm::length(NormalAt(pa, ua.x, ua.y) - NormalAt(pb, ub.x, ub.y)));
                        }
                    }
            }
        CHECK(edges == 2 * 2 * int(r.patches.size()));  // each of the 2 |F| edges, from both sides
        CHECK(worstP < 1e-12 * scale);
        CHECK(worstN < 1e-12);
    }
}

TEST_CASE("subdivision: bounds of the patches contain their points in every number type",
          "[renderer][subdivision][containment]") {
    test::Rng rng(17);
    const SubdivisionResult r = Build(Tower());
    int checked = 0, irregular = 0;
    for (size_t i = 0; i < r.patches.size(); i += 7) {
        const SubdivPatch& p = r.patches[i];
        irregular += !p.regular;
        for (int k = 0; k < 8; ++k) {
            const double w = std::pow(10.0, -rng.uniform(0, 6));
            const double u0 = rng.uniform(0, 1 - w), v0 = rng.uniform(0, 1 - w), u1 = u0 + w, v1 = v0 + w;
            const auto fi = renderer::SubdivPatchFrame<vm::Interval>(p, vm::Interval(u0, u1), vm::Interval(v0, v1));
            vm::Affine::BeginEvaluation();
            const auto fa = renderer::SubdivPatchFrame<vm::Affine>(p, renderer::SurfaceParameter<vm::Affine>(u0, u1, 0),
                                                                   renderer::SurfaceParameter<vm::Affine>(v0, v1, 1));
            const auto fr = renderer::SubdivPatchFrame<vm::ReducedAffine>(
                p, renderer::SurfaceParameter<vm::ReducedAffine>(u0, u1, 0),
                renderer::SurfaceParameter<vm::ReducedAffine>(v0, v1, 1));
            using DI = vm::Dual<vm::Interval>;
            const auto fd = renderer::SubdivPatchFrame<DI>(p, renderer::SurfaceParameter<DI>(u0, u1, 0),
                                                           renderer::SurfaceParameter<DI>(v0, v1, 1));
            for (int s = 0; s < 6; ++s) {
                const double u = s < 4 ? (s & 1 ? u1 : u0) : rng.uniform(u0, u1);
                const double v = s < 4 ? (s >> 1 ? v1 : v0) : rng.uniform(v0, v1);
                const auto f = renderer::SubdivPatchFrame<double>(p, u, v);
                using D = vm::Dual<double>;
                const auto fdd = renderer::SubdivPatchFrame<D>(p, D(u, 1.0, 0.0), D(v, 0.0, 1.0));
                for (int c = 0; c < 3; ++c) {
                    for (auto [x, bi, ba, br, bd] :
                         {std::tuple{f.P[c], fi.P[c], fa.P[c], fr.P[c], fd.P[c]},
                          {f.dPdu[c], fi.dPdu[c], fa.dPdu[c], fr.dPdu[c], fd.dPdu[c]},
                          {f.normalDirection[c], fi.normalDirection[c], fa.normalDirection[c], fr.normalDirection[c],
                           fd.normalDirection[c]}}) {
                        CHECK(bi.contains(x));
                        CHECK(RangeOf(ba).contains(x));
                        CHECK(RangeOf(br).contains(x));
                        CHECK(bd.v.contains(x));
                        ++checked;
                    }
                    // Dual derivatives are the frame's own tangents.
                    CHECK(fdd.P[c].v == f.P[c]);
                    CHECK(std::fabs(fdd.P[c].du - f.dPdu[c]) <= 1e-9 * (1 + std::fabs(f.dPdu[c])));
                }
            }
        }
    }
    CHECK(irregular > 0);
    CHECK(checked > 1000);
    // A displacement along N that reads s, t: containment through the whole shader.
    const compiler::CompiledShader shader =
        test::CompileOrThrow("displacement d(float Km = 0.1) { P += (Km + 0.05 * noise(P * 3 + s)) * normalize(N); }");
    for (size_t i = 0; i < r.patches.size(); i += 13) {
        const renderer::BaseSurface surface(r.patches[i]);
        test::CheckContainmentOn<vm::Affine, vm::Interval, vm::ReducedAffine>("patch " + std::to_string(i),
                                                                              shader.bound, surface, 12, 8, 90 + i);
    }
}

namespace {

/// Rays from outside aimed at points along every edge of every patch of `patches` displaced
/// outward by `program` (along N): the displaced closed surface lies between the ray's origin
/// and the point, so the ray must hit it no farther. Returns the number of rays that do not.
int EdgeRayMisses(const std::vector<SubdivPatch>& patches, const vm::Program& program, int* rays) {
    std::vector<std::unique_ptr<renderer::SurfaceIntersector>> intersectors;
    intersectors.reserve(patches.size());
    for (const SubdivPatch& p : patches)
        intersectors.push_back(renderer::MakeSurfaceIntersector(renderer::BaseSurface(p), program, glm::dvec3(0.0),
                                                                renderer::BoundMode::Affine, 30));
    test::EdgeRays probe(std::move(intersectors));
    for (const SubdivPatch& p : patches)
        for (int k = 0; k < 4; ++k)
            for (double t : {0.0, 0.125, 0.5, 0.7, 0.999}) {
                const glm::dvec2 uv = EdgeParam(k, t), uvNext = EdgeParam(k, t + 0.001);
                const glm::dvec3 target = p.geometry.At(uv.x, uv.y);
                probe.At(target, NormalAt(p, uv.x, uv.y), glm::normalize(p.geometry.At(uvNext.x, uvNext.y) - target),
                         [&] { return ToString(p); });
            }
    *rays += probe.rays;
    return probe.misses;
}

}  // namespace

TEST_CASE("subdivision: a displaced closed mesh has no cracks at its edges", "[renderer][subdivision][cracks]") {
    const compiler::CompiledShader shader =
        test::CompileOrThrow("displacement d(float Km = 0.15) { P += (Km + 0.1 * noise(P * 2)) * normalize(N); }");
    for (auto [name, mesh] : {std::pair{"cube", Cube()}, {"tower", Tower()}}) {
        INFO(name);
        const SubdivisionResult r = Build(mesh, 1);
        int rays = 0;
        CHECK(EdgeRayMisses(r.patches, shader.bound, &rays) == 0);
        CHECK(rays > 400);
        // With their geometric normals instead of the shared field, the approximated patches part
        // along the edges at extraordinary vertices: the same rays go through, so the test above
        // can fail.
        std::vector<SubdivPatch> geometric = r.patches;
        for (SubdivPatch& p : geometric) p.regular = true;
        rays = 0;
        CHECK(EdgeRayMisses(geometric, shader.bound, &rays) > 0);
    }
}

TEST_CASE("subdivision: holes, boundaries, creases and corners", "[renderer][subdivision]") {
    SECTION("a hole removes its face's patches") {
        SubdivisionMesh cube = Cube();
        const size_t all = Build(cube).patches.size();
        cube.holes = {2};
        CHECK(Build(cube).patches.size() == all - all / 6);
    }
    SECTION("an open grid reaches its boundary only with interpolateboundary") {
        SubdivisionMesh grid = Grid(4);
        const SubdivisionResult none = Build(grid);
        // Without the tag, control faces with a boundary vertex only shape the surface: the
        // inner 2 x 2 faces are left, 16 patches each.
        CHECK(none.patches.size() == size_t{4} * 16);
        grid.boundary = renderer::SubdivBoundary::EdgesAndCorners;
        const SubdivisionResult r = Build(grid);
        CHECK(r.patches.size() == size_t{16} * 16);
        // The boundary curve is the cubic B-spline of the boundary vertices (the corners
        // interpolated): its points at the boundary vertices are (a + 4 v + b) / 6.
        const std::vector<glm::dvec3>& p = grid.points;
        const glm::dvec3 want = (p[1] + 4.0 * p[2] + p[3]) / 6.0;
        double nearest = 1e30, corner = 1e30;
        for (const SubdivPatch& patch : r.patches)
            for (int c = 0; c < 4; ++c) {
                nearest = std::min(nearest, glm::length(patch.geometry.At(c & 1, c >> 1) - want));
                corner = std::min(corner, glm::length(patch.geometry.At(c & 1, c >> 1) - p[0]));
            }
        CHECK(nearest < 1e-12);
        CHECK(corner < 1e-12);
        // Halfway between boundary vertices 1 and 2: the B-spline's midpoint (a + 23 b + 23 c + d) / 48.
        const glm::dvec3 mid = (p[0] + 23.0 * p[1] + 23.0 * p[2] + p[3]) / 48.0;
        CHECK(DistanceToPatches(r.patches, mid) < 1e-12);
    }
    SECTION("a sharp crease follows the B-spline of its vertices; a corner is interpolated") {
        SubdivisionMesh torus = Torus(8, 6);
        torus.creases.push_back({{8, 9, 10, 11, 12, 13, 14, 15, 8}, 10});
        torus.corners.push_back({40, 10});
        const SubdivisionResult r = Build(torus);
        const std::vector<glm::dvec3>& p = torus.points;
        for (int i = 0; i < 8; ++i) {
            const glm::dvec3 a = p[8 + (i + 7) % 8], b = p[8 + i], c = p[8 + (i + 1) % 8], d = p[8 + (i + 2) % 8];
            CHECK(DistanceToPatches(r.patches, (a + 4.0 * b + c) / 6.0) < 1e-12);
            CHECK(DistanceToPatches(r.patches, (a + 23.0 * b + 23.0 * c + d) / 48.0) < 1e-12);
        }
        CHECK(DistanceToPatches(r.patches, p[40]) < 1e-12);
        // Without the tags, the surface passes nowhere near the crease's control points.
        CHECK(DistanceToPatches(Build(Torus(8, 6)).patches, p[40]) > 1e-3);
    }
    SECTION("bad topology is reported") {
        SubdivisionMesh m = Cube();
        std::swap(m.faceVerts[0], m.faceVerts[1]);  // one face turned over
        SubdivisionResult r;
        CHECK_FALSE(renderer::BuildSubdivisionPatches(m, &r).empty());
    }
}
