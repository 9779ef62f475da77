// tests/test_random.h: the random sampling and failure tally the property tests share. Every test seeds its own
// generator, so a failure reproduces; AFFRAY_SAMPLES raises the sample counts (e.g. 1e6 for a
// long run) without changing what CTest runs.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace affray::test {

/// `base`, or AFFRAY_SAMPLES if that is larger.
inline int Samples(int base) {
    const char* s = std::getenv("AFFRAY_SAMPLES");
    return s ? std::max(base, static_cast<int>(std::strtol(s, nullptr, 10))) : base;
}

struct Rng {
    std::mt19937_64 gen;
    explicit Rng(uint64_t seed) : gen(seed) {}
    double uniform(double lo, double hi) { return std::uniform_real_distribution<>(lo, hi)(gen); }
    /// Uniform in [lo, hi], of the arguments' integer type.
    template <class I>
    I integer(I lo, I hi) {
        return std::uniform_int_distribution<I>(lo, hi)(gen);
    }
    bool chance(double p) { return uniform(0, 1) < p; }
    template <class T>
    const T& pick(const std::vector<T>& v) {
        return v[integer<size_t>(0, v.size() - 1)];
    }
    /// A double with `bits` significant bits, of magnitude about 2^exponent, random sign.
    double dyadic(int exponent, int bits = 20) {
        double m = static_cast<double>(integer<int64_t>(int64_t{1} << (bits - 1), (int64_t{1} << bits) - 1));
        return std::ldexp(chance(0.5) ? m : -m, exponent - bits + 1);
    }
    /// -1, 0 or 1, or a uniform multiple of 2^-12 in [-1, 1]: a value to fix a noise symbol at.
    double eps() {
        int k = integer(0, 4);
        return k < 3 ? k - 1.0 : std::ldexp(integer(-4096, 4096), -12);
    }
};

/// Counts of a property test's samples, and the first few failures' descriptions (the rest
/// are only counted, so a broken bound does not print a million lines).
struct Tally {
    int samples = 0, failures = 0;
    int bounded = 0, finite = 0, loose = 0;  // what a test chooses to count besides
    std::ostringstream first;
    void fail(const std::string& s) {
        if (failures++ < 4) first << s << "\n";
    }
};

}  // namespace affray::test
