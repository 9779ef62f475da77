// bench/noise_bench.cpp: evaluations per second of vm/noise.h's Noise in every number type, at a
// point (double, Dual<double>) and over regions one cell wide, a few cells wide and past the cell
// cap (Interval, Affine, Dual<Affine>), for 1 to 4 dimensions.
// Usage: affray_bench_noise [--seconds S]   (Release builds only)
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>

#include "bench/evals_per_second.h"

#include "vm/noise.h"

using namespace affray::vm;

namespace {

using affray::bench::EvalsPerSecond;
// Evaluations between clock reads.
constexpr int kBatch = 64;

volatile double g_sink;  // keeps results alive so the optimiser cannot drop the work

/// Noise over p_i = o_i + a_i*u + b_i*v with u, v on [c - r, c + r] and p_i about `width` wide.
template <class T>
void MakeRegion(std::mt19937_64& rng, int dims, double width, T* p);

template <>
void MakeRegion(std::mt19937_64& rng, int dims, double width, double* p) {
    std::uniform_real_distribution<double> o(-50, 50);
    (void)width;
    for (int i = 0; i < dims; ++i) p[i] = o(rng);
}
template <>
void MakeRegion(std::mt19937_64& rng, int dims, double width, Dual<double>* p) {
    std::uniform_real_distribution<double> o(-50, 50), s(-1, 1);
    (void)width;
    for (int i = 0; i < dims; ++i) p[i] = Dual<double>(o(rng), s(rng), s(rng));
}
template <class U>
void UV(double r, U* u, U* v);
template <>
void UV(double r, Interval* u, Interval* v) {
    *u = Interval(0.5 - r, 0.5 + r);
    *v = *u;
}
template <>
void UV(double r, Affine* u, Affine* v) {
    Affine::BeginEvaluation();
    *u = Affine::FromSymbol(0.5, r, Affine::kSymbolU);
    *v = Affine::FromSymbol(0.5, r, Affine::kSymbolV);
}
template <>
void UV(double r, Dual<Affine>* u, Dual<Affine>* v) {
    Affine a, b;
    UV(r, &a, &b);
    *u = Dual<Affine>(a, Affine(1.0), Affine(0.0));
    *v = Dual<Affine>(b, Affine(0.0), Affine(1.0));
}
template <class T>
void MakeRegion(std::mt19937_64& rng, int dims, double width, T* p) {
    std::uniform_real_distribution<double> o(-50, 50), s(-1, 1);
    const double r = 1.0 / 64;
    T u, v;
    UV(r, &u, &v);
    for (int i = 0; i < dims; ++i) {
        double a = s(rng), b = s(rng), k = width / (2 * r * (std::fabs(a) + std::fabs(b)));
        p[i] = o(rng) + (a * k) * u + (b * k) * v;
    }
}

template <class T>
double Rate(int dims, double width, double seconds) {
    std::mt19937_64 rng(5);
    // Pre-built arguments: the rate is the noise call's alone.
    constexpr int kArgs = 256;
    static T args[kArgs][4];
    for (auto& p : args) MakeRegion(rng, dims, width, p);
    return EvalsPerSecond(seconds, kBatch, [&](long n) {
        g_sink = RangeOf(ValueOf(Noise(args[n % kArgs], dims, static_cast<uint32_t>(n % 3)))).hi();
    });
}

}  // namespace

int main(int argc, char** argv) {
    double seconds = 0.3;
    for (int i = 1; i < argc; ++i)
        if (!std::strcmp(argv[i], "--seconds") && i + 1 < argc) seconds = std::atof(argv[++i]);
    std::printf("evaluations per second (thousands)\n");
    std::printf("%-28s %10s %10s %10s %10s\n", "", "1-D", "2-D", "3-D", "4-D");
    auto row = [&](const char* name, auto rate) {
        std::printf("%-28s", name);
        for (int dims = 1; dims <= 4; ++dims) std::printf(" %10.0f", rate(dims) / 1e3);
        std::printf("\n");
    };
    row("double", [&](int d) { return Rate<double>(d, 0, seconds); });
    row("dual", [&](int d) { return Rate<Dual<double>>(d, 0, seconds); });
    for (double width : {1e-3, 0.5, 4.0}) {
        char name[64];
        std::snprintf(name, sizeof name, "interval, width %g", width);
        row(name, [&](int d) { return Rate<Interval>(d, width, seconds); });
        std::snprintf(name, sizeof name, "affine, width %g", width);
        row(name, [&](int d) { return Rate<Affine>(d, width, seconds); });
        std::snprintf(name, sizeof name, "dual-affine, width %g", width);
        row(name, [&](int d) { return Rate<Dual<Affine>>(d, width, seconds); });
    }
    return 0;
}
