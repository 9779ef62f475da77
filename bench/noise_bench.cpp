// bench/noise_bench.cpp: vm/numbers/noise.h's Noise in every number type: evaluations per second at a
// point (double, Dual<double>) and over regions, and, for Interval and Affine, the two ways of
// bounding a region side by side: NoiseBoundMethod::Polynomial (the cell polynomial evaluated in
// T arithmetic: Interval's default, and Affine's before LocalForm) against Local (the cell
// polynomial in a LocalForm: Affine's default), as calls per second and the mean width of the
// bounds over the same regions. Region classes: coordinates 1/8, 1/64 and 1/512 of a cell wide
// inside one cell, and the same widths with coordinate 0 straddling a cell face (the regions a
// subdividing ray tracer spends its time on). The two methods are timed alternately, best of
// three, so that other load on the machine biases neither.
// Usage: affray_bench_noise [--seconds S]   (Release builds only; S per figure, default 0.05)
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>
#include <string>

#include "bench/evals_per_second.h"

#include "vm/numbers/noise.h"

using namespace affray::vm;

namespace {

using affray::bench::EvalsPerSecond;
// Evaluations between clock reads.
constexpr int kBatch = 64;
// Pre-built arguments: the rate is the noise call's alone.
constexpr int kArgs = 256;

volatile double g_sink;  // keeps results alive so the optimiser cannot drop the work

/// How the coordinates of a region sit on the lattice.
enum class Placement { Anywhere, InsideCell, StraddlingFace };

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
template <>
void UV(double, double* u, double* v) {
    *u = *v = 0.5;
}
template <>
void UV(double, Dual<double>* u, Dual<double>* v) {
    *u = Dual<double>(0.5, 1.0, 0.0);
    *v = Dual<double>(0.5, 0.0, 1.0);
}

/// Noise over p_i = o_i + a_i*u + b_i*v with u, v on [1/2 - r, 1/2 + r] and p_i `width` wide
/// (0: a point), placed as asked (StraddlingFace: coordinate 0 crosses an integer).
template <class T>
void MakeRegion(std::mt19937_64& rng, int dims, double width, Placement where, T* p) {
    std::uniform_real_distribution<double> unit(0, 1), s(-1, 1);
    std::uniform_int_distribution<int> cell(-50, 50);
    const double r = 1.0 / 64;
    T u, v;
    UV(r, &u, &v);
    for (int i = 0; i < dims; ++i) {
        double a = s(rng), b = s(rng), k = width / (2 * r * (std::fabs(a) + std::fabs(b)));
        // The centre of p_i (at u = v = 1/2).
        double centre = cell(rng) + unit(rng);
        if (where == Placement::InsideCell || (where == Placement::StraddlingFace && i > 0))
            centre = cell(rng) + 0.5 * width + unit(rng) * (1 - width);
        else if (where == Placement::StraddlingFace)
            centre = cell(rng) + 0.9 * width * (unit(rng) - 0.5);
        p[i] = (centre - 0.5 * (a * k + b * k)) + (a * k) * u + (b * k) * v;
    }
}

template <class T>
T Call(const T* p, int dims, uint32_t seed, NoiseBoundMethod method) {
    return noise_detail::GradientNoise<T>(p, nullptr, dims, seed, method);
}

struct Figures {
    double rate = 0, meanWidth = 0;
};

template <class T>
Figures Measure(int dims, double width, Placement where, NoiseBoundMethod method, double seconds) {
    std::mt19937_64 rng(5);
    static T args[kArgs][4];
    for (auto& p : args) MakeRegion(rng, dims, width, where, p);
    Figures f;
    for (int n = 0; n < kArgs; ++n)
        f.meanWidth += RangeOf(ValueOf(Call(args[n], dims, static_cast<uint32_t>(n % 3), method))).width() / kArgs;
    f.rate = EvalsPerSecond(seconds, kBatch, [&](long n) {
        g_sink = RangeOf(ValueOf(Call(args[n % kArgs], dims, static_cast<uint32_t>(n % 3), method))).hi();
    });
    return f;
}

/// Polynomial and Local on the same regions, timed alternately: the best of three each.
template <class T>
void Compare(int dims, double width, Placement where, double seconds, Figures* old, Figures* now) {
    for (int round = 0; round < 3; ++round) {
        Figures a = Measure<T>(dims, width, where, NoiseBoundMethod::Polynomial, seconds / 3);
        Figures b = Measure<T>(dims, width, where, NoiseBoundMethod::Local, seconds / 3);
        if (round == 0 || a.rate > old->rate) *old = a;
        if (round == 0 || b.rate > now->rate) *now = b;
    }
}

}  // namespace

int main(int argc, char** argv) {
    double seconds = 0.05;
    for (int i = 1; i < argc; ++i)
        if (!std::strcmp(argv[i], "--seconds") && i + 1 < argc) seconds = std::stod(argv[++i]);
    const auto kAuto = NoiseBoundMethod::Auto;

    std::printf("evaluations per second (thousands)\n");
    std::printf("%-34s %10s %10s %10s %10s\n", "", "1-D", "2-D", "3-D", "4-D");
    auto row = [&](const char* name, auto figure) {
        std::printf("%-34s", name);
        for (int dims = 1; dims <= 4; ++dims) std::printf(" %10.0f", figure(dims).rate / 1e3);
        std::printf("\n");
    };
    row("double", [&](int d) { return Measure<double>(d, 0, Placement::Anywhere, kAuto, seconds); });
    row("dual", [&](int d) { return Measure<Dual<double>>(d, 0, Placement::Anywhere, kAuto, seconds); });
    for (double width : {0.5, 4.0}) {
        char name[64];
        std::snprintf(name, sizeof name, "interval, width %g", width);
        row(name, [&](int d) { return Measure<Interval>(d, width, Placement::Anywhere, kAuto, seconds); });
        std::snprintf(name, sizeof name, "affine, width %g", width);
        row(name, [&](int d) { return Measure<Affine>(d, width, Placement::Anywhere, kAuto, seconds); });
        std::snprintf(name, sizeof name, "dual-affine, width %g", width);
        row(name, [&](int d) { return Measure<Dual<Affine>>(d, width, Placement::Anywhere, kAuto, seconds); });
    }

    std::printf(
        "\nPolynomial -> Local (Affine's default; Interval's default stays Polynomial):\n"
        "thousands of calls per second and mean bound width\n");
    std::printf("%-24s %4s %9s %9s %6s %11s %11s %7s\n", "region", "dims", "poly k/s", "local k/s", "speed",
                "poly width", "local width", "ratio");
    for (Placement where : {Placement::InsideCell, Placement::StraddlingFace}) {
        for (double width : {1.0 / 8, 1.0 / 64, 1.0 / 512}) {
            for (int type = 0; type < 2; ++type) {
                for (int dims = 1; dims <= 4; ++dims) {
                    Figures old, now;
                    if (type == 0)
                        Compare<Interval>(dims, width, where, seconds, &old, &now);
                    else
                        Compare<Affine>(dims, width, where, seconds, &old, &now);
                    char name[64];
                    std::snprintf(name, sizeof name, "%s %s 1/%.0f", type == 0 ? "interval" : "affine",
                                  where == Placement::InsideCell ? "inside" : "straddle", 1 / width);
                    std::printf("%-24s %4d %9.0f %9.0f %5.1fx %11.3g %11.3g %7.3f\n", name, dims, old.rate / 1e3,
                                now.rate / 1e3, now.rate / old.rate, old.meanWidth, now.meanWidth,
                                now.meanWidth / old.meanWidth);
                }
            }
        }
    }
    return 0;
}
