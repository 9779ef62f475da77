// tests/renderer/bvh_test.cpp: the top-level hierarchy (renderer/bvh.h): the slab test is
// conservative, every crossed box is visited (with the surface-area heuristic, the median split
// and degenerate inputs alike), nearer boxes first, and a lowered tMax prunes; the tree is the
// same for any number of threads, no deeper than Traverse's stack allows, its memory exact, and
// its SAH cost below the median split's where the primitives cluster.
#include "renderer/bvh.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <memory>

#include "renderer/thread_pool.h"
#include "tests/test_random.h"
#include "tests/test_util.h"

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

/// The boxes `ray` crosses (from t = 0), by brute force, in increasing order.
std::vector<int> Crossed(const std::vector<Box>& boxes, const Ray& ray) {
    std::vector<int> crossed;
    for (int i = 0; i < static_cast<int>(boxes.size()); ++i) {
        double t0 = 0, t1 = INFINITY;
        if (boxes[size_t(i)].Clip(ray, &t0, &t1)) crossed.push_back(i);
    }
    return crossed;
}

/// Random rays for `boxes`: from anywhere in [-span, span]^3 in any direction, some along an axis
/// (zero direction components), and half of them aimed at a point of a (finite) box.
std::vector<Ray> RaysFor(const std::vector<Box>& boxes, double span, affray::test::Rng& rng, int n) {
    std::vector<Ray> rays;
    for (int r = 0; r < n; ++r) {
        const glm::dvec3 origin(rng.uniform(-span, span), rng.uniform(-span, span), rng.uniform(-span, span));
        glm::dvec3 dir(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
        if (r % 2 == 0 && !boxes.empty()) {
            const Box& b = rng.pick(boxes);
            glm::dvec3 target;
            for (int i = 0; i < 3; ++i)
                target[i] = std::isfinite(b.lo[i]) && std::isfinite(b.hi[i]) && b.lo[i] <= b.hi[i]
                                ? rng.uniform(b.lo[i], b.hi[i])
                                : 0.0;
            if (target != origin) dir = target - origin;
        }
        if (r % 25 == 0) dir = glm::dvec3(0, 0, r % 50 == 0 ? 1 : -1);  // along an axis
        rays.push_back({origin, glm::normalize(dir)});
    }
    return rays;
}

/// `boxes` widened by float's rounding: the hierarchy keeps its primitives' boxes in floats, rounded
/// outwards, so a ray grazing a box may visit it.
std::vector<Box> Widened(std::vector<Box> boxes) {
    for (Box& b : boxes) {
        b.lo -= 1e-6 * glm::abs(b.lo) + 1e-30;
        b.hi += 1e-6 * glm::abs(b.hi) + 1e-30;
    }
    return boxes;
}

/// Checks that every ray visits the boxes it crosses (and no box it misses by more than float's
/// rounding), that the tree is within Traverse's depth, and that its memory is exactly its nodes
/// and its primitives.
void CheckVisitsCrossed(const Bvh& bvh, const std::vector<Box>& boxes, const std::vector<Ray>& rays) {
    CHECK(bvh.depth() <= Bvh::kMaxDepth);
    const size_t items =
        static_cast<size_t>(std::count_if(boxes.begin(), boxes.end(), [](const Box& b) { return !b.empty(); }));
    CHECK(bvh.bytes() == size_t(bvh.nodeCount()) * 32 + items * 28);
    const std::vector<Box> widened = Widened(boxes);
    int failures = 0;
    for (const Ray& ray : rays) {
        const std::vector<int> visited = Visited(bvh, ray), crossed = Crossed(boxes, ray),
                               nearly = Crossed(widened, ray);
        const bool ok = std::includes(visited.begin(), visited.end(), crossed.begin(), crossed.end()) &&
                        std::includes(nearly.begin(), nearly.end(), visited.begin(), visited.end());
        if (!ok && ++failures <= 3) {
            INFO("ray from (" << ray.origin.x << ", " << ray.origin.y << ", " << ray.origin.z << ") along ("
                              << ray.dir.x << ", " << ray.dir.y << ", " << ray.dir.z << ")");
            CHECK(visited == crossed);
        }
    }
    CHECK(failures == 0);
}

/// n boxes in a few tight clusters far apart, of sizes from tiny to long and thin.
std::vector<Box> ClusteredBoxes(int n, affray::test::Rng& rng) {
    std::vector<glm::dvec3> centres;
    for (int c = 0; c < 6; ++c)
        centres.emplace_back(rng.uniform(-100, 100), rng.uniform(-100, 100), rng.uniform(-100, 100));
    std::vector<Box> boxes;
    boxes.reserve(size_t(n));
    for (int i = 0; i < n; ++i) {
        const glm::dvec3 c = rng.pick(centres) + glm::dvec3(rng.uniform(-3, 3), rng.uniform(-3, 3), rng.uniform(-3, 3));
        glm::dvec3 h(rng.uniform(0.01, 0.3), rng.uniform(0.01, 0.3), rng.uniform(0.01, 0.3));
        if (i % 40 == 0) h[i % 3] = 20;  // a long thin one
        boxes.push_back(MakeBox(c - h, c + h));
    }
    return boxes;
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
    const Bvh bvh(boxes, nullptr, GENERATE(Bvh::Split::kSah, Bvh::Split::kMedian));
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

TEST_CASE("bvh: the SAH tree visits every crossed box, on random and degenerate inputs", "[renderer][bvh]") {
    affray::test::Rng rng(7);
    ThreadPool pool(2);
    std::vector<std::pair<std::string, std::vector<Box>>> inputs;
    inputs.emplace_back("clustered", ClusteredBoxes(3000, rng));
    std::vector<Box> random;
    for (int i = 0; i < 3000; ++i) {
        const glm::dvec3 c(rng.uniform(-50, 50), rng.uniform(-50, 50), rng.uniform(-50, 50));
        const glm::dvec3 h(rng.uniform(0, 4), rng.uniform(0, 4), rng.uniform(0, 4));
        random.push_back(MakeBox(c - h, c + h));
    }
    inputs.emplace_back("random", random);
    inputs.emplace_back("all equal", std::vector<Box>(500, MakeBox(glm::dvec3(-1, -2, -3), glm::dvec3(1, 2, 3))));
    std::vector<Box> points;  // zero-size boxes, many at the same point
    for (int i = 0; i < 500; ++i) {
        const glm::dvec3 p = i % 3 ? glm::dvec3(rng.integer(-3, 3), rng.integer(-3, 3), 0) : glm::dvec3(0);
        points.push_back(MakeBox(p, p));
    }
    inputs.emplace_back("points", points);
    std::vector<Box> plane;  // every centre on the plane z = 1, boxes of any size
    for (int i = 0; i < 1000; ++i) {
        const glm::dvec3 c(rng.uniform(-20, 20), rng.uniform(-20, 20), 1);
        const glm::dvec3 h(rng.uniform(0, 2), rng.uniform(0, 2), rng.uniform(0, 2));
        plane.push_back(MakeBox(c - h, c + h));
    }
    inputs.emplace_back("centres on a plane", plane);
    std::vector<Box> mixed = random;  // empty and infinite boxes among finite ones
    mixed.resize(600);
    for (int i = 0; i < 600; i += 7) mixed[size_t(i)] = Box();
    for (int i = 3; i < 600; i += 50) {
        mixed[size_t(i)].lo[i % 3] = -INFINITY;
        if (i % 100 == 3) mixed[size_t(i)].hi[(i + 1) % 3] = INFINITY;
    }
    mixed.push_back(MakeBox(glm::dvec3(-INFINITY), glm::dvec3(INFINITY)));  // crossed by every ray
    inputs.emplace_back("empty and infinite", mixed);
    std::vector<Box> infinite(40, MakeBox(glm::dvec3(-INFINITY, -1, -INFINITY), glm::dvec3(INFINITY, 1, INFINITY)));
    for (int i = 0; i < 40; ++i) infinite[size_t(i)].lo.y = infinite[size_t(i)].hi.y = i - 20.0;
    inputs.emplace_back("all infinite", infinite);
    inputs.emplace_back("all empty", std::vector<Box>(10));
    for (int n = 0; n <= 3; ++n)
        inputs.emplace_back(std::to_string(n) + " boxes", std::vector<Box>(random.begin(), random.begin() + n));
    // Points spaced geometrically over float's range, halving from 2^127 to 2^-119: SAH peels a few
    // off the far end at each split, 76 deep without the depth limit, deeper than Traverse's
    // stack allows.
    std::vector<Box> geometric;
    for (int i = 0; i <= 246; ++i) {
        const double x = std::ldexp(1.0, 127 - i);
        geometric.push_back(MakeBox(glm::dvec3(x, x, 0), glm::dvec3(x, x, 0)));
    }
    inputs.emplace_back("geometric", geometric);

    for (const auto& [name, boxes] : inputs) {
        INFO(name);
        const std::vector<Ray> rays = RaysFor(boxes, 60, rng, 400);
        const Bvh serial(boxes), parallel(boxes, &pool);
        CHECK(serial == parallel);
        CheckVisitsCrossed(parallel, boxes, rays);
    }
    // The geometric input's tree did need the limit.
    CHECK(Bvh(geometric).depth() == Bvh::kMaxDepth);
    CHECK(Bvh(std::vector<Box>()).nodeCount() == 0);
    CHECK(Bvh(std::vector<Box>(random.begin(), random.begin() + 2)).nodeCount() == 1);
}

TEST_CASE("bvh: the tree is the same, node for node, for any number of threads", "[renderer][bvh]") {
    affray::test::Rng rng(8);
    // Big enough that the top levels bin on the pool's threads and there are many subtrees (half
    // as many under the sanitizers: still above kParallelBinItems, 32,768).
    const std::vector<Box> boxes = ClusteredBoxes(affray::test::kSanitized ? 50000 : 100000, rng);
    for (const Bvh::Split split : {Bvh::Split::kSah, Bvh::Split::kMedian}) {
        const Bvh serial(boxes, nullptr, split);
        for (int threads : {1, 2, 4}) {
            INFO("threads " << threads);
            ThreadPool pool(threads);
            CHECK(Bvh(boxes, &pool, split) == serial);
        }
    }
    // The same rays visit the same primitives in the same order (the traversal sees one tree).
    ThreadPool pool(4);
    const Bvh a(boxes), b(boxes, &pool);
    for (const Ray& ray : RaysFor(boxes, 120, rng, 200)) {
        std::vector<int> orderA, orderB;
        double tMax = INFINITY;
        a.Traverse(ray, 0, &tMax, [&](int i, double) {
            orderA.push_back(i);
            return true;
        });
        b.Traverse(ray, 0, &tMax, [&](int i, double) {
            orderB.push_back(i);
            return true;
        });
        CHECK(orderA == orderB);
    }
}

TEST_CASE("bvh: on clustered boxes the SAH tree costs less than the median split's", "[renderer][bvh]") {
    affray::test::Rng rng(9);
    const std::vector<Box> boxes = ClusteredBoxes(20000, rng);
    const double sah = Bvh(boxes).SahCost(), median = Bvh(boxes, nullptr, Bvh::Split::kMedian).SahCost();
    INFO("SAH cost " << sah << ", median split's " << median);
    CHECK(sah < 0.9 * median);
    // A ray crossing nothing but the root's box tests at least that box.
    CHECK(Bvh(std::vector<Box>{MakeBox(glm::dvec3(0), glm::dvec3(1))}).SahCost() == 2);
}
