// tests/renderer/bvh_test.cpp: the top-level hierarchy (renderer/bvh.h): the slab test is
// conservative, every crossed box is visited, nearer boxes first, and a lowered tMax prunes.
#include "renderer/bvh.h"

#include <catch2/catch.hpp>

#include <algorithm>

#include "tests/test_random.h"

using namespace affray::renderer;

namespace {

Box MakeBox(const glm::dvec3& lo, const glm::dvec3& hi) {
    Box b;
    b.lo = lo;
    b.hi = hi;
    return b;
}

/// The primitives `bvh` offers `ray` (from t = 0, no hit lowering tMax), in increasing order.
std::vector<int> Visited(const Bvh& bvh, const Ray& ray) {
    std::vector<int> visited;
    double tMax = INFINITY;
    bvh.Traverse(ray, 0, &tMax, [&](int i, double) {
        visited.push_back(i);
        return true;
    });
    std::sort(visited.begin(), visited.end());
    return visited;
}

}  // namespace

TEST_CASE("bvh: a ray visits exactly the boxes it crosses, nearest entry first", "[renderer][bvh]") {
    affray::test::Rng rng(5);
    std::vector<Box> boxes;
    for (int i = 0; i < 40; ++i) {
        glm::dvec3 c(rng.uniform(-10, 10), rng.uniform(-10, 10), rng.uniform(-10, 10));
        glm::dvec3 h(rng.uniform(0.1, 2), rng.uniform(0.1, 2), rng.uniform(0.1, 2));
        boxes.push_back(MakeBox(c - h, c + h));
    }
    boxes.push_back(Box());  // empty: never visited
    boxes.push_back(MakeBox(glm::dvec3(-INFINITY, 3, -INFINITY), glm::dvec3(INFINITY, 3.5, INFINITY)));
    const Bvh bvh(boxes);
    for (int r = 0; r < 500; ++r) {
        Ray ray{{rng.uniform(-15, 15), rng.uniform(-15, 15), rng.uniform(-15, 15)},
                glm::normalize(glm::dvec3(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1)))};
        if (r % 50 == 0) ray.dir = glm::dvec3(0, 0, 1);  // axis-aligned: zero components
        std::vector<int> expected;
        for (int i = 0; i < static_cast<int>(boxes.size()); ++i) {
            double t0 = 0, t1 = INFINITY;
            if (boxes[i].Clip(ray, &t0, &t1)) expected.push_back(i);
        }
        CHECK(Visited(bvh, ray) == expected);
    }
}

TEST_CASE("bvh: the slab test contains every point of the box on the ray", "[renderer][bvh]") {
    affray::test::Rng rng(6);
    for (int i = 0; i < 2000; ++i) {
        const glm::dvec3 lo(rng.uniform(-1e6, 1e6), rng.uniform(-1e6, 1e6), rng.uniform(-1e6, 1e6));
        const Box box = MakeBox(lo, lo + glm::dvec3(rng.uniform(0, 3), rng.uniform(0, 3), rng.uniform(0, 3)));
        // A ray aimed at a point of the box: it must be crossed at a t that includes that point.
        const glm::dvec3 target(rng.uniform(box.lo.x, box.hi.x), rng.uniform(box.lo.y, box.hi.y),
                                rng.uniform(box.lo.z, box.hi.z));
        const glm::dvec3 origin(rng.uniform(-2e6, 2e6), rng.uniform(-2e6, 2e6), rng.uniform(-2e6, 2e6));
        const double distance = glm::length(target - origin);
        const Ray ray{origin, (target - origin) / distance};
        double t0 = 0, t1 = INFINITY;
        REQUIRE(box.Clip(ray, &t0, &t1));
        CHECK(t0 <= distance);
        CHECK(t1 >= distance * (1 - 1e-12));
    }
}

TEST_CASE("bvh: nearer boxes are visited first and a lowered tMax skips farther ones", "[renderer][bvh]") {
    std::vector<Box> boxes;
    boxes.reserve(8);
    for (int i = 0; i < 8; ++i) boxes.push_back(MakeBox(glm::dvec3(-1, -1, 10.0 * i), glm::dvec3(1, 1, 10.0 * i + 1)));
    const Bvh bvh(boxes);
    const Ray ray{{0, 0, -5}, {0, 0, 1}};
    std::vector<int> order;
    double tMax = INFINITY;
    bvh.Traverse(ray, 0, &tMax, [&](int i, double tEntry) {
        order.push_back(i);
        CHECK(tEntry <= 10.0 * i + 5 + 1e-9);
        if (i == 2) tMax = 26;  // a hit inside box 2 (entered at t = 25)
        return true;
    });
    CHECK(order == std::vector<int>{0, 1, 2});
    // Any-hit: returning false stops at once.
    order.clear();
    tMax = INFINITY;
    bvh.Traverse(ray, 0, &tMax, [&](int i, double) {
        order.push_back(i);
        return false;
    });
    CHECK(order == std::vector<int>{0});
}

TEST_CASE("bvh: boxes past float's range keep their primitives (the leaves' float boxes round outwards)",
          "[renderer][bvh]") {
    // Sides beyond float's largest, on either side, and a box of width 1e-30 near 1e7 (narrower
    // than a float's step there): a ray through each still visits it.
    std::vector<Box> boxes = {MakeBox(glm::dvec3(-1e300, -1, -1), glm::dvec3(1e300, 1, 1)),
                              MakeBox(glm::dvec3(1e200, -1, -1), glm::dvec3(1e201, 1, 1)),
                              MakeBox(glm::dvec3(-1e201, -1, -1), glm::dvec3(-1e200, 1, 1)),
                              MakeBox(glm::dvec3(1e7, 5, -1), glm::dvec3(1e7 + 1e-30, 6, 1))};
    const Bvh bvh(boxes);
    CHECK(Visited(bvh, {{0, 0, -5}, {0, 0, 1}}) == std::vector<int>{0});
    CHECK(Visited(bvh, {{1.5e200, 0, -5}, {0, 0, 1}}) == std::vector<int>{0, 1});
    CHECK(Visited(bvh, {{-1.5e200, 0, -5}, {0, 0, 1}}) == std::vector<int>{0, 2});
    CHECK(Visited(bvh, {{1e7, 5.5, -5}, {0, 0, 1}}) == std::vector<int>{3});
}
