// tests/scene/geometry/texture_coordinates_test.cpp: TextureCoordinates (BaseSurface::
// textureCoordinates) give the s, t a shader reads on quadrics and patches, bilinear in u, v from
// the corners, with derivatives along u, v; meshes keep their own; the affine and interval bounds
// of a shader reading them contain every point.
#include <catch2/catch.hpp>

#include "scene/geometry/surface.h"
#include "tests/test_random.h"
#include "tests/test_util.h"

using namespace affray;
using renderer::BaseSurface;

namespace {

// P moves by (s, t, s*t): the displaced point shows the s and t the shader saw.
const char* const kShowST = "displacement d() { P += vector(s, t, s * t); }";

// s, t by hand: bilinear from the corners (0,0), (1,0), (0,1), (1,1).
glm::dvec2 Expected(const std::array<double, 8>& c, double u, double v) {
    auto at = [&](int i) {
        return (1 - u) * (1 - v) * c[i] + u * (1 - v) * c[2 + i] + (1 - u) * v * c[4 + i] + u * v * c[6 + i];
    };
    return {at(0), at(1)};
}

}  // namespace

TEST_CASE("texture coordinates: s and t are bilinear in u, v on patches and quadrics", "[renderer][st]") {
    const compiler::CompiledShader shader = test::CompileOrThrow(kShowST);
    const auto coords = std::make_shared<const std::array<double, 8>>(std::array<double, 8>{2, 1, -1, 0, 3, 5, 0.5, 4});
    BaseSurface square(renderer::BilinearPatch::UnitSquare());
    BaseSurface base = square;
    square.textureCoordinates = coords;
    renderer::PlacedQuadric sphere;
    sphere.quadric.kind = renderer::Quadric::Kind::Sphere;
    sphere.quadric.radius = 1;
    sphere.quadric.zmin = -1;
    sphere.quadric.zmax = 1;
    sphere.quadric.thetamax = 360;
    BaseSurface ball(sphere), plainBall(sphere);
    ball.textureCoordinates = coords;
    for (double u : {0.0, 0.25, 1.0})
        for (double v : {0.0, 0.6, 1.0}) {
            INFO("u " << u << " v " << v);
            const glm::dvec2 st = Expected(*coords, u, v);
            const glm::dvec3 moved =
                test::PointOnSurface(shader.bound, square, u, v) - test::PointOnSurface(shader.bound, base, u, v);
            CHECK(moved.x == Approx(st.x - u).margin(1e-12));
            CHECK(moved.y == Approx(st.y - v).margin(1e-12));
            CHECK(moved.z == Approx(st.x * st.y - u * v).margin(1e-12));
            const glm::dvec3 onBall =
                test::PointOnSurface(shader.bound, ball, u, v) - test::PointOnSurface(shader.bound, plainBall, u, v);
            CHECK(onBall.x == Approx(st.x - u).margin(1e-12));
            CHECK(onBall.y == Approx(st.y - v).margin(1e-12));
        }
    // Derivatives along u and v (Dual): ds/du at (0.25, 0.6) from the bilinear form.
    const compiler::CompiledShader slope = test::CompileOrThrow("displacement d() { P += vector(Du(s), Dv(t), 0); }");
    const glm::dvec3 d =
        test::PointOnSurface(slope.bound, square, 0.25, 0.6) - test::PointOnSurface(slope.bound, base, 0.25, 0.6);
    const std::array<double, 8>& c = *coords;
    CHECK(d.x == Approx((c[2] - c[0]) * (1 - 0.6) + (c[6] - c[4]) * 0.6 - 1).margin(1e-9));
    CHECK(d.y == Approx((c[5] - c[1]) * (1 - 0.25) + (c[7] - c[3]) * 0.25 - 1).margin(1e-9));
}

TEST_CASE("texture coordinates: the bounds of a shader reading s, t contain every point", "[renderer][st]") {
    const compiler::CompiledShader shader =
        test::CompileOrThrow("displacement d() { P += normalize(N) * 0.2 * sin(9 * s) * cos(5 * t * s); }");
    BaseSurface surface(renderer::BilinearPatch{
        {glm::dvec3(0, 0, 0), glm::dvec3(2, 0, 0.5), glm::dvec3(0, 1, 0), glm::dvec3(2, 1.5, 1)}});
    surface.textureCoordinates =
        std::make_shared<const std::array<double, 8>>(std::array<double, 8>{1, 0, -2, 1, 0, 3, 4, -1});
    test::Rng rng(21);
    for (int r = 0; r < 200; ++r) {
        const double width = std::pow(10.0, -rng.uniform(0, 5));
        const double u0 = rng.uniform(0, 1 - width), v0 = rng.uniform(0, 1 - width);
        const auto a = test::EvalOnSurface<vm::Affine>(shader.bound, surface, u0, u0 + width, v0, v0 + width);
        const auto ra = test::EvalOnSurface<vm::ReducedAffine>(shader.bound, surface, u0, u0 + width, v0, v0 + width);
        const auto iv = test::EvalOnSurface<vm::Interval>(shader.bound, surface, u0, u0 + width, v0, v0 + width);
        for (int k = 0; k < 4; ++k) {
            const double u = rng.uniform(u0, u0 + width), v = rng.uniform(v0, v0 + width);
            const glm::dvec3 p = test::PointOnSurface(shader.bound, surface, u, v);
            for (int c = 0; c < 3; ++c) {
                INFO("region (" << u0 << ", " << v0 << ") width " << width << " component " << c);
                CHECK(RangeOf(a[c]).contains(p[c]));
                CHECK(RangeOf(ra[c]).contains(p[c]));
                CHECK(iv[c].contains(p[c]));
            }
        }
    }
}
