// tests/renderer/thread_pool_test.cpp: the Renderer's thread pool runs every call once, on as
// many threads as asked, nests without deadlock and passes exceptions back.
#include "renderer/thread_pool.h"

#include <atomic>
#include <mutex>
#include <set>
#include <stdexcept>

#include <catch2/catch.hpp>

namespace affray::renderer {
namespace {

TEST_CASE("ThreadPool::Run calls the job once per worker, each on its own thread", "[thread_pool]") {
    ThreadPool pool(4);
    REQUIRE(pool.size() == 4);
    for (int workers : {1, 2, 3, 4, 9}) {
        std::mutex m;
        std::multiset<int> seen;
        std::set<std::thread::id> threads;
        pool.Run(workers, [&](int w) {
            std::lock_guard<std::mutex> lock(m);
            seen.insert(w);
            threads.insert(std::this_thread::get_id());
        });
        const int expected = std::min(workers, 4);
        CHECK(int(seen.size()) == expected);
        CHECK(int(threads.size()) == expected);
        for (int w = 0; w < expected; ++w) CHECK(seen.count(w) == 1);
    }
}

TEST_CASE("ThreadPool::ForEach visits every index once, over many jobs", "[thread_pool]") {
    ThreadPool pool(3);
    for (size_t n : {size_t(0), size_t(1), size_t(7), size_t(1000)}) {
        for (size_t grain : {size_t(1), size_t(5), size_t(64)}) {
            std::vector<std::atomic<int>> visits(n);
            std::atomic<int> badWorker{0};
            pool.ForEach(
                n,
                [&](size_t i, int w) {
                    visits[i]++;
                    if (w < 0 || w >= pool.size()) badWorker++;
                },
                grain);
            for (size_t i = 0; i < n; ++i) CHECK(visits[i].load() == 1);
            CHECK(badWorker.load() == 0);
        }
    }
}

TEST_CASE("ThreadPool: a Run inside a job runs serially, and exceptions reach the caller", "[thread_pool]") {
    ThreadPool pool(2);
    std::atomic<int> inner{0};
    pool.Run(2, [&](int) { pool.Run(2, [&](int) { inner++; }); });
    CHECK(inner.load() == 4);
    CHECK_THROWS_AS(pool.Run(2,
                             [&](int w) {
                                 if (w == 1) throw std::runtime_error("worker 1");
                             }),
                    std::runtime_error);
    // The pool still works after an exception.
    std::atomic<int> calls{0};
    pool.Run(2, [&](int) { calls++; });
    CHECK(calls.load() == 2);
    // A pool of one thread (the caller's) and the default (one per core).
    ThreadPool one(1);
    CHECK(one.size() == 1);
    CHECK(ThreadPool(0).size() == ThreadsFor(0));
}

}  // namespace
}  // namespace affray::renderer
