// tests/scene/motion_test.cpp: moving transforms (scene/motion.h): the matrix between and beyond
// the times, and the path of a transform that does not move.
#include <catch2/catch.hpp>

#include <glm/gtc/matrix_transform.hpp>

#include "scene/motion.h"

using namespace affray::renderer;

namespace {

glm::dvec3 Place(const glm::dmat4& m, const glm::dvec3& p) { return glm::dvec3(m * glm::dvec4(p, 1.0)); }

}  // namespace

TEST_CASE("a moving transform interpolates its matrices between its times and holds them beyond", "[scene][motion]") {
    const glm::dmat4 a = glm::translate(glm::dmat4(1.0), {0, 0, 0});
    const glm::dmat4 b = glm::translate(glm::dmat4(1.0), {4, 0, 0});
    const glm::dmat4 c = glm::translate(glm::dmat4(1.0), {4, 8, 0});
    const std::shared_ptr<const MotionPath> path = MotionPath::Make({1, 2, 4}, {a, b, c});
    REQUIRE(path);
    // A point moves on straight lines between its places at the times, at a constant rate on each.
    CHECK(Place(path->At(1), {1, 1, 1}) == glm::dvec3(1, 1, 1));
    CHECK(Place(path->At(1.25), {1, 1, 1}) == glm::dvec3(2, 1, 1));
    CHECK(Place(path->At(2), {1, 1, 1}) == glm::dvec3(5, 1, 1));
    CHECK(Place(path->At(3), {1, 1, 1}) == glm::dvec3(5, 5, 1));
    CHECK(Place(path->At(4), {1, 1, 1}) == glm::dvec3(5, 9, 1));
    // Before the first time and after the last: the end matrices (and NaN: the first).
    CHECK(path->At(-10) == a);
    CHECK(path->At(10) == c);
    CHECK(path->At(std::nan("")) == a);
    CHECK(MatrixAt(path.get(), b, 1.25) == path->At(1.25));
    CHECK(MatrixAt(nullptr, b, 1.25) == b);

    // The matrices are interpolated, not the motion they stand for: half way between two
    // rotations a point lies on the chord, not on the arc.
    const glm::dmat4 r = glm::rotate(glm::dmat4(1.0), glm::radians(90.0), glm::dvec3(0, 0, 1));
    const glm::dvec3 half = Place(MotionPath::Make({0, 1}, {glm::dmat4(1.0), r})->At(0.5), {1, 0, 0});
    CHECK(half.x == Approx(0.5));
    CHECK(half.y == Approx(0.5));
}

TEST_CASE("a transform that does not move has no path", "[scene][motion]") {
    const glm::dmat4 m = glm::scale(glm::dmat4(1.0), {2, 2, 2});
    CHECK_FALSE(MotionPath::Make({0, 1}, {m, m}));
    CHECK_FALSE(MotionPath::Make({0}, {m}));                      // one time: still
    CHECK_FALSE(MotionPath::Make({0, 1}, {m}));                   // mismatched: nothing to move by
    CHECK(MotionPath::Make({0, 1, 2}, {m, m, glm::dmat4(1.0)}));  // moves at the end only
}
