// bench/evals_per_second.h: the one timing loop of the benchmarks: how many times per second
// `evaluate(n)` runs (n counts the calls), measured for at least `seconds` of wall time.
// The clock is read once per batch of `batch` calls, so that reading it costs nothing measurable
// beside cheap evaluations.
#pragma once

#include <chrono>

namespace affray::bench {

template <class F>
double EvalsPerSecond(double seconds, int batch, F&& evaluate) {
    using Clock = std::chrono::steady_clock;
    long n = 0;
    const auto start = Clock::now();
    double elapsed = 0;
    do {
        for (int i = 0; i < batch; ++i) evaluate(n++);
        elapsed = std::chrono::duration<double>(Clock::now() - start).count();
    } while (elapsed < seconds);
    return n / elapsed;
}

}  // namespace affray::bench
