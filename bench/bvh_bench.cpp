// bench/bvh_bench.cpp: the top-level BVH (renderer/bvh.h) over a million boxes, built by the median
// split and by the surface-area heuristic, on 1 and 2 threads: the build's seconds (the median of
// several builds), the tree's nodes, memory, depth and SAH cost, and the seconds and primitives
// offered per ray of a closest-hit search through it. Prints one Markdown table.
//
//     affray_bench_bvh [--boxes N] [--repeats R] [--rays N]
//
// Two inputs: "hill", the boxes of a sqrt(N) x sqrt(N) grid of faces of a height field (as
// bench/mesh renders: a face's box is its corners' and a displacement bound about them), and
// "clustered", N boxes in 30 clusters of varied spread, with one box in 50 long and thin. The rays
// start outside the scene's box and aim at points inside it; a primitive is "hit" in the middle of
// its box along the ray, which lowers tMax as the renderer's nearest hit does. Run nothing else
// while timing.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "renderer/bvh.h"
#include "renderer/thread_pool.h"

using namespace affray::renderer;

namespace {

using Clock = std::chrono::steady_clock;

double SecondsSince(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

Box MakeBox(const glm::dvec3& lo, const glm::dvec3& hi) {
    Box b;
    b.lo = lo;
    b.hi = hi;
    return b;
}

/// The boxes of an n x n grid of faces over [0, 10]^2 of a hilly height field.
std::vector<Box> HillBoxes(int n) {
    auto height = [](double x, double y) {
        return 1.5 * std::sin(0.7 * x) * std::cos(0.5 * y) + 0.3 * std::sin(3.1 * x + 1.3 * y);
    };
    std::vector<Box> boxes;
    boxes.reserve(size_t(n) * size_t(n));
    const double step = 10.0 / n, bound = 0.02;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            Box b;
            for (int c = 0; c < 4; ++c) {
                const double x = (i + c % 2) * step, y = (j + c / 2) * step;
                b.Extend(glm::dvec3(x, y, height(x, y)));
            }
            b.lo -= bound;
            b.hi += bound;
            boxes.push_back(b);
        }
    return boxes;
}

/// n boxes in 30 clusters of varied spread, one in 50 long and thin.
std::vector<Box> ClusteredBoxes(int n, std::mt19937_64& rng) {
    std::uniform_real_distribution<> u(0, 1);
    std::vector<glm::dvec3> centres;
    std::vector<double> spreads;
    for (int c = 0; c < 30; ++c) {
        centres.emplace_back(200 * u(rng) - 100, 200 * u(rng) - 100, 200 * u(rng) - 100);
        spreads.push_back(0.5 + 10 * u(rng) * u(rng));
    }
    std::normal_distribution<> g(0, 1);
    std::vector<Box> boxes;
    boxes.reserve(size_t(n));
    for (int i = 0; i < n; ++i) {
        const size_t c = size_t(rng() % centres.size());
        const glm::dvec3 p = centres[c] + spreads[c] * glm::dvec3(g(rng), g(rng), g(rng));
        glm::dvec3 h = 0.02 * spreads[c] * glm::dvec3(u(rng), u(rng), u(rng));
        if (i % 50 == 0) h[size_t(i % 3)] = 5 * spreads[c];
        boxes.push_back(MakeBox(p - h, p + h));
    }
    return boxes;
}

/// Rays from outside `scene` (a sphere around it) aimed at points inside it.
std::vector<Ray> RaysInto(const Box& scene, int n, std::mt19937_64& rng) {
    std::uniform_real_distribution<> u(0, 1);
    const glm::dvec3 centre = 0.5 * (scene.lo + scene.hi);
    const double radius = glm::length(scene.hi - scene.lo);
    std::vector<Ray> rays;
    for (int r = 0; r < n; ++r) {
        const glm::dvec3 target = scene.lo + (scene.hi - scene.lo) * glm::dvec3(u(rng), u(rng), u(rng));
        const glm::dvec3 origin =
            centre + radius * glm::normalize(glm::dvec3(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5 + 0.3));
        rays.push_back({origin, glm::normalize(target - origin)});
    }
    return rays;
}

struct Row {
    std::string input, split;
    int threads;
    double buildSeconds;
    int nodes, depth;
    size_t bytes;
    double sahCost, raySeconds, offeredPerRay;
};

}  // namespace

int main(int argc, char** argv) {
    int nBoxes = 1000000, repeats = 5, nRays = 200000;
    for (int i = 1; i + 1 < argc; i += 2) {
        if (!std::strcmp(argv[i], "--boxes"))
            nBoxes = std::atoi(argv[i + 1]);
        else if (!std::strcmp(argv[i], "--repeats"))
            repeats = std::max(1, std::atoi(argv[i + 1]));
        else if (!std::strcmp(argv[i], "--rays"))
            nRays = std::atoi(argv[i + 1]);
        else {
            std::fprintf(stderr, "usage: affray_bench_bvh [--boxes N] [--repeats R] [--rays N]\n");
            return 2;
        }
    }
    std::mt19937_64 rng(1);
    const int side = static_cast<int>(std::lround(std::sqrt(double(nBoxes))));
    const std::vector<std::pair<std::string, std::vector<Box>>> inputs = {
        {"hill " + std::to_string(side) + "x" + std::to_string(side), HillBoxes(side)},
        {"clustered " + std::to_string(nBoxes), ClusteredBoxes(nBoxes, rng)}};
    std::vector<Row> rows;
    for (const auto& [name, boxes] : inputs) {
        Box scene;
        for (const Box& b : boxes) scene.Extend(b);
        const std::vector<Ray> rays = RaysInto(scene, nRays, rng);
        for (const Bvh::Split split : {Bvh::Split::kMedian, Bvh::Split::kSah}) {
            for (int threads : {1, 2}) {
                ThreadPool pool(threads);
                std::vector<double> seconds;
                std::unique_ptr<Bvh> bvh;
                for (int r = 0; r < repeats; ++r) {
                    bvh.reset();
                    const Clock::time_point start = Clock::now();
                    bvh = std::make_unique<Bvh>(boxes, threads > 1 ? &pool : nullptr, split);
                    seconds.push_back(SecondsSince(start));
                }
                std::nth_element(seconds.begin(), seconds.begin() + repeats / 2, seconds.end());
                // The closest-hit search: each primitive offered is hit halfway through its box.
                size_t offered = 0;
                const Clock::time_point start = Clock::now();
                for (const Ray& ray : rays) {
                    double best = INFINITY;
                    bvh->Traverse(ray, 0, &best, [&](int i, double) {
                        ++offered;
                        double t0 = 0, t1 = best;
                        if (boxes[size_t(i)].Clip(ray, &t0, &t1)) best = std::min(best, 0.5 * (t0 + t1));
                        return true;
                    });
                }
                const double raySeconds = SecondsSince(start);
                rows.push_back({name, split == Bvh::Split::kSah ? "SAH" : "median", threads,
                                seconds[size_t(repeats / 2)], bvh->nodeCount(), bvh->depth(), bvh->bytes(),
                                bvh->SahCost(), raySeconds, double(offered) / double(rays.size())});
            }
        }
    }
    std::printf(
        "| input | split | threads | build | nodes | memory | depth | SAH cost | %d rays | primitives offered per ray "
        "|\n",
        nRays);
    std::printf("|---|---|---|---|---|---|---|---|---|---|\n");
    for (const Row& r : rows)
        std::printf("| %s | %s | %d | %.3f s | %d | %.1f MB | %d | %.1f | %.3f s | %.2f |\n", r.input.c_str(),
                    r.split.c_str(), r.threads, r.buildSeconds, r.nodes, double(r.bytes) / 1e6, r.depth, r.sahCost,
                    r.raySeconds, r.offeredPerRay);
    return 0;
}
