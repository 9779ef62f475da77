// tests/vm/numbers/noise_test.cpp: vm/numbers/noise.h. The double functions against their RenderMan semantics
// (range, mean, spread, continuity, derivatives, cellnoise cells, pnoise periods, golden values);
// the proof of the scale (an interval branch and bound); and the bounded evaluations: Interval,
// Affine, ReducedAffine and the Duals of each contain the double (and Dual<double>) result at every
// point of random regions from one cell to many, never exceed [0, 1], and are tight inside one
// cell. AFFRAY_SAMPLES=N raises the number of random regions.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdlib>
#include <random>
#include <sstream>
#include <vector>

#include "tests/test_random.h"
#include "vm/numbers/noise.h"

using namespace affray::vm;
using affray::test::Rng;
using affray::test::Samples;

namespace {

// ---------------------------------------------------------------------------------------------
// The double functions.

TEST_CASE("noise values lie between 0 and 1 with mean 0.5 and the measured spread", "[vm][noise]") {
    // Standard deviations measured over 1e6 points (vm/numbers/noise.h's gradient sets and scales):
    // d = 1: 0.192-0.199, d = 2: 0.162, d = 3: 0.1286, d = 4: 0.1062. The bounds sit ~10 % below:
    // the sample deviation of 1e5 points of a field correlated over about one cell varies by ~1 %
    // (d = 1 most, each of its cells being shaped by only two gradients), so they never fail by
    // chance, and a scale or gradient set losing contrast (e.g. the analytic B_d: -14 % for d = 3)
    // fails them.
    const double minStdDev[5] = {0, 0.175, 0.147, 0.116, 0.096};
    for (int dims = 1; dims <= 4; ++dims) {
        for (uint32_t seed = 0; seed < 3; ++seed) {
            Rng rng(100 * dims + seed);
            const int n = 100000;
            double sum = 0, sum2 = 0, lo = 1, hi = 0;
            for (int k = 0; k < n; ++k) {
                double p[4];
                for (int i = 0; i < dims; ++i) p[i] = rng.uniform(-1e4, 1e4);
                double x = Noise(p, dims, seed);
                sum += x;
                sum2 += x * x;
                lo = std::min(lo, x);
                hi = std::max(hi, x);
            }
            double mean = sum / n, sd = std::sqrt(sum2 / n - mean * mean);
            INFO("dims " << dims << " seed " << seed << ": range [" << lo << ", " << hi << "] mean " << mean << " sd "
                         << sd);
            CHECK(lo >= 0);
            CHECK(hi <= 1);
            CHECK(std::fabs(mean - 0.5) < 0.05);
            CHECK(std::fabs(mean - 0.5) < 0.01);  // measured: < 0.002
            CHECK(sd > minStdDev[dims]);
        }
    }
}

TEST_CASE("noise is 0.5 on lattice points and continuous across cell faces", "[vm][noise]") {
    Rng rng(7);
    for (int dims = 1; dims <= 4; ++dims) {
        for (int k = 0; k < 2000; ++k) {
            double p[4], q[4];
            for (int i = 0; i < dims; ++i) p[i] = rng.integer(-1000, 1000);
            CHECK(Noise(p, dims, k % 3) == 0.5);
            // Small steps from points on, near and away from cell faces: the change is at most a
            // Lipschitz constant times the step (|gradient| measured below 1.6 with Dual<double>).
            for (int i = 0; i < dims; ++i) {
                int kind = rng.integer(0, 2);
                p[i] += kind == 0 ? 0.0 : kind == 1 ? rng.uniform(-1e-6, 1e-6) : rng.uniform(0, 1);
            }
            double h = std::ldexp(1.0, -rng.integer(10, 40));
            for (int i = 0; i < dims; ++i) q[i] = p[i] + rng.uniform(-h, h);
            double a = Noise(p, dims, k % 3), b = Noise(q, dims, k % 3);
            INFO("dims " << dims << " step " << h << ": " << a << " vs " << b);
            CHECK(std::fabs(a - b) <= 4 * dims * h + 1e-15);
        }
    }
}

TEST_CASE("noise Dual<double> derivatives match central differences", "[vm][noise]") {
    Rng rng(11);
    double maxGradient = 0;
    for (int dims = 1; dims <= 4; ++dims) {
        for (int k = 0; k < 3000; ++k) {
            uint32_t seed = k % 3;
            double x[4], a[4], b[4];
            Dual<double> p[4];
            for (int i = 0; i < dims; ++i) {
                // Integers and exact cell faces too: C1 means the derivative is the same from both
                // sides, so central differences across a face still agree.
                int kind = rng.integer(0, 3);
                x[i] = kind == 0 ? rng.integer(-50, 50) : rng.uniform(-50, 50);
                a[i] = rng.uniform(-1, 1);
                b[i] = rng.uniform(-1, 1);
                p[i] = Dual<double>(x[i], a[i], b[i]);
            }
            Dual<double> r = Noise(p, dims, seed);
            CHECK(r.v == Noise(x, dims, seed));
            const double h = 1e-5;
            auto at = [&](const double* dir, double s) {
                double q[4];
                for (int i = 0; i < dims; ++i) q[i] = x[i] + s * dir[i];
                return Noise(q, dims, seed);
            };
            double du = (at(a, h) - at(a, -h)) / (2 * h), dv = (at(b, h) - at(b, -h)) / (2 * h);
            INFO("dims " << dims << " seed " << seed << ": du " << r.du << " vs " << du << ", dv " << r.dv << " vs "
                         << dv);
            // Truncation h^2/6 |f'''| (|f'''| < 100) plus rounding 1e-16/h: far below 1e-6.
            CHECK(std::fabs(r.du - du) < 1e-6);
            CHECK(std::fabs(r.dv - dv) < 1e-6);
            // The gradient along coordinate axes, for the Lipschitz bound of the test above.
            for (int i = 0; i < dims; ++i) {
                Dual<double> q[4];
                for (int j = 0; j < dims; ++j) q[j] = Dual<double>(x[j], i == j ? 1.0 : 0.0, 0.0);
                maxGradient = std::max(maxGradient, std::fabs(Noise(q, dims, seed).du));
            }
        }
    }
    CHECK(maxGradient < 1.6);  // measured 1.55 (d = 2); the continuity test relies on < 4
}

TEST_CASE("cellnoise is constant on cells, differs between them and lies between 0 and 1", "[vm][noise]") {
    Rng rng(13);
    for (int dims = 1; dims <= 4; ++dims) {
        int same = 0, pairs = 0;
        double sum = 0;
        const int n = 5000;
        for (int k = 0; k < n; ++k) {
            uint32_t seed = k % 3;
            double cell[4], p[4], q[4];
            for (int i = 0; i < dims; ++i) {
                cell[i] = rng.integer(-100000, 100000);
                p[i] = cell[i] + (rng.chance(0.2) ? 0.0 : rng.uniform(0, 1));
                q[i] = cell[i] + rng.uniform(0, 0.9999);
            }
            double c = CellNoise(p, dims, seed);
            sum += c;
            CHECK(c >= 0);
            CHECK(c < 1);
            CHECK(CellNoise(q, dims, seed) == c);
            Dual<double> d[4];
            for (int i = 0; i < dims; ++i) d[i] = Dual<double>(p[i], 1.0, -2.0);
            Dual<double> cd = CellNoise(d, dims, seed);
            CHECK(cd.v == c);
            CHECK(cd.du == 0);
            CHECK(cd.dv == 0);
            // Neighbours across each face, and other seeds.
            for (int i = 0; i < dims; ++i) {
                q[i] = p[i] + (rng.chance(0.5) ? 1 : -1);
                same += CellNoise(q, dims, seed) == c;
                ++pairs;
                q[i] = p[i];
            }
            same += CellNoise(p, dims, seed + 1) == c;
            ++pairs;
        }
        INFO("dims " << dims << ": " << same << " equal neighbours of " << pairs);
        CHECK(same <= pairs / 1000);  // 53-bit values: equal only by a 2^-53 chance
        CHECK(std::fabs(sum / n - 0.5) < 0.02);
    }
}

TEST_CASE("pnoise repeats with the rounded period and equals noise inside one period", "[vm][noise]") {
    Rng rng(17);
    for (int dims = 1; dims <= 4; ++dims) {
        for (int k = 0; k < 2000; ++k) {
            uint32_t seed = k % 3;
            double p[4], period[4], rounded[4];
            for (int i = 0; i < dims; ++i) {
                // Dyadic points, so that p + period is exact and the local coordinates agree bit
                // for bit.
                p[i] = std::ldexp(rng.integer(-(1 << 26), 1 << 26), -18);
                rounded[i] = rng.integer(1, 12);
                period[i] = rounded[i] + rng.uniform(-0.49, 0.49);
            }
            double x = PNoise(p, period, dims, seed);
            CHECK(x >= 0);
            CHECK(x <= 1);
            for (int i = 0; i < dims; ++i) {
                double q[4];
                std::copy(p, p + dims, q);
                q[i] += rounded[i] * rng.integer(-3, 3);
                CHECK(PNoise(q, period, dims, seed) == x);
                // A non-positive or small period is 1.
                double small[4];
                std::copy(period, period + dims, small);
                small[i] = rng.uniform(-5, 1.49);
                std::copy(p, p + dims, q);
                q[i] += rng.integer(-3, 3);
                CHECK(PNoise(q, small, dims, seed) == PNoise(p, small, dims, seed));
            }
            // Inside the first period (no corner wraps) pnoise is noise.
            double r[4];
            bool inside = true;
            for (int i = 0; i < dims; ++i) {
                r[i] = std::fmod(std::fabs(p[i]), rounded[i]);
                inside = inside && std::floor(r[i]) + 1 < rounded[i];
            }
            if (inside) CHECK(PNoise(r, period, dims, seed) == Noise(r, dims, seed));
        }
    }
}

TEST_CASE("noise is deterministic: golden values", "[vm][noise]") {
    const double p[4] = {0.3, -1.7, 2.25, 10.5};
    // Computed once by this implementation (x86-64, glibc); they depend only on IEEE arithmetic
    // and the integer hash, so every platform must reproduce them bit for bit.
    struct Golden {
        int dims;
        uint32_t seed;
        double noise, cell;
    };
    const Golden golden[] = {
        {1, 0, 0.80530849999999998, 0.24525582159337656}, {1, 2, 0.15759499999999999, 0.38285963728049566},
        {2, 0, 0.40826709537922634, 0.85472535024240559}, {2, 1, 0.30995510968422246, 0.98265758727797059},
        {3, 0, 0.68182156792075888, 0.77658714197504874}, {3, 1, 0.68532820796428573, 0.58977641520064694},
        {3, 2, 0.59763677663950898, 0.86439763607975961}, {4, 0, 0.57978204214097229, 0.5107686282369418},
        {4, 2, 0.5258665332630208, 0.26673817282877366},
    };
    for (const Golden& g : golden) {
        INFO("dims " << g.dims << " seed " << g.seed);
        double n = Noise(p, g.dims, g.seed), c = CellNoise(p, g.dims, g.seed);
        CHECK(n == g.noise);
        CHECK(c == g.cell);
        CHECK(Noise(p, g.dims, g.seed) == n);
    }
    // Channels differ.
    CHECK(Noise(p, 3, 0) != Noise(p, 3, 1));
    CHECK(Noise(p, 3, 1) != Noise(p, 3, 2));
}

TEST_CASE("noise of non-finite input is NaN, Unbounded in bounded types", "[vm][noise]") {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    double p[3] = {0.5, nan, 1.0};
    CHECK(std::isnan(Noise(p, 3, 0)));
    CHECK(std::isnan(CellNoise(p, 3, 0)));
    p[1] = kInfinity;
    CHECK(std::isnan(Noise(p, 3, 0)));
    Affine a[2] = {Affine(0.5), Affine::Unbounded()};
    CHECK(Noise(a, 2, 0).isUnbounded());
    CHECK(CellNoise(a, 2, 0).isUnbounded());
    double q[1] = {0.5}, infinitePeriod[1] = {kInfinity};
    CHECK(std::isnan(PNoise(q, infinitePeriod, 1, 0)));
    Interval i[2] = {Interval(0.5), Interval(0.25, 0.75)};
    Interval nanPeriod[2] = {Interval(3.0), Interval(nan)};
    CHECK(PNoise(i, nanPeriod, 2, 0).isUnbounded());
    // A bounded period range that is not one point: the cell-independent bound, within [0, 1].
    Interval widePeriod[2] = {Interval(3.0), Interval(2.0, 5.0)};
    Interval r = PNoise(i, widePeriod, 2, 0);
    CHECK(r.lo() >= 0);
    CHECK(r.hi() <= 1);
}

// ---------------------------------------------------------------------------------------------
// The scale: a computer-assisted proof of sup F <= 0.5 / NoiseScale(d) (see vm/numbers/noise.h).

/// True if `set` is closed under sign changes of single components and under swapping two
/// components, exactly (so F is symmetric under t_i -> 1 - t_i and under permutations).
bool HasSymmetries(const NoiseGradientSet& set) {
    auto contains = [&](const double* g) {
        for (int k = 0; k < set.count; ++k)
            if (std::equal(g, g + set.dims, set.components + static_cast<ptrdiff_t>(k) * set.dims)) return true;
        return false;
    };
    for (int k = 0; k < set.count; ++k) {
        const double* g = set.components + static_cast<ptrdiff_t>(k) * set.dims;
        for (int i = 0; i < set.dims; ++i) {
            double h[4];
            std::copy(g, g + set.dims, h);
            h[i] = -h[i];
            if (!contains(h)) return false;
            for (int j = i + 1; j < set.dims; ++j) {
                std::copy(g, g + set.dims, h);
                std::swap(h[i], h[j]);
                if (!contains(h)) return false;
            }
        }
    }
    return true;
}

/// The fade 6t^5 - 15t^4 + 10t^3 at the point t, as an enclosing interval.
Interval FadeAt(double t) {
    Interval x(t);
    return x * x * x * (x * (x * 6.0 - 15.0) + 10.0);
}

struct ScaleProof {
    const NoiseGradientSet& set;
    double bound;
    long boxes = 0;

    /// An upper bound of F(t) = sum_o W_o(t) phi(t - o) over the box [lo, hi] (in [0, 1/2]^d),
    /// rounded upward: W_o is increasing in t_i for o_i = 1 (the fade is increasing) and
    /// decreasing for o_i = 0; phi(t - o) = max_g g.(t - o) is at most the max over g of each
    /// term's maximum over the box.
    double upperF(const double* lo, const double* hi) {
        ++boxes;
        const int d = set.dims;
        double w[4][2];   // upper bounds of 1 - s(t_i) and s(t_i)
        double dt[4][2];  // upper bounds of (t_i - o_i) * sign: [i][o] -> {max, -min}
        double dtLo[4][2];
        for (int i = 0; i < d; ++i) {
            w[i][0] = (1.0 - FadeAt(lo[i])).hi();
            w[i][1] = FadeAt(hi[i]).hi();
            for (int o = 0; o < 2; ++o) {
                dt[i][o] = SubUp(hi[i], o);
                dtLo[i][o] = SubDown(lo[i], o);
            }
        }
        double total = 0;
        for (int o = 0; o < (1 << d); ++o) {
            double weight = 1;
            for (int i = 0; i < d; ++i) weight = MulUp(weight, w[i][(o >> i) & 1]);
            double phi = 0;
            for (int k = 0; k < set.count; ++k) {
                const double* g = set.components + static_cast<ptrdiff_t>(k) * d;
                double dot = 0;
                for (int i = 0; i < d; ++i) {
                    int b = (o >> i) & 1;
                    dot = AddUp(dot, MulUp(g[i], g[i] >= 0 ? dt[i][b] : dtLo[i][b]));
                }
                phi = std::max(phi, dot);
            }
            total = AddUp(total, MulUp(weight, phi));
        }
        return total;
    }

    /// True if F <= bound on the box intersected with t_0 <= t_1 <= ... (by bisection).
    bool prove(double* lo, double* hi, int depth) {
        for (int i = 0; i + 1 < set.dims; ++i)
            if (lo[i] > hi[i + 1]) return true;  // no sorted point in the box
        if (upperF(lo, hi) <= bound) return true;
        if (depth > 60) return false;
        int k = 0;
        for (int i = 1; i < set.dims; ++i)
            if (hi[i] - lo[i] > hi[k] - lo[k]) k = i;
        double mid = 0.5 * (lo[k] + hi[k]), saved = hi[k];
        hi[k] = mid;
        bool ok = prove(lo, hi, depth + 1);
        hi[k] = saved;
        if (!ok) return false;
        saved = lo[k];
        lo[k] = mid;
        ok = prove(lo, hi, depth + 1);
        lo[k] = saved;
        return ok;
    }
};

TEST_CASE("noise scale: computer-assisted proof that unclamped noise lies between 0 and 1", "[vm][noise]") {
    // d = 1 is proven analytically in vm/numbers/noise.h (its sup 1/2 is attained, so no margin is left
    // for bisection); check its premise: every gradient has |g| <= 1 and the scale is 1.
    const NoiseGradientSet& one = NoiseGradients(1);
    for (int k = 0; k < one.count; ++k) CHECK(std::fabs(one.components[k]) <= 1);
    CHECK(NoiseScale(1) == 1.0);
    for (int dims = 2; dims <= 4; ++dims) {
        const NoiseGradientSet& set = NoiseGradients(dims);
        REQUIRE(set.dims == dims);
        REQUIRE(HasSymmetries(set));
        // The fallback's component range covers the set.
        for (int k = 0; k < set.count * dims; ++k) CHECK(std::fabs(set.components[k]) <= set.componentBound);
        ScaleProof proof{set, DivDown(0.5, NoiseScale(dims))};
        double lo[4] = {0, 0, 0, 0}, hi[4] = {0.5, 0.5, 0.5, 0.5};
        INFO("dims " << dims << ": proving F <= " << proof.bound);
        CHECK(proof.prove(lo, hi, 0));
        INFO(proof.boxes << " boxes");
    }
}

// ---------------------------------------------------------------------------------------------
// Bounded evaluations.

/// p_i = offset + a*u + b*v + c*u*v: the same recipe on every number type.
struct Coordinate {
    double offset, a, b, c;
    template <class T>
    T operator()(const T& u, const T& v) const {
        return offset + a * u + b * v + c * (u * v);
    }
};

/// A region (u = uc + r*eps_u, v = vc + r*eps_v, exact at the sampled eps) and the coordinates
/// of the noise argument, each of width about `width` over it.
struct NoiseRegion {
    double uc, vc, r;
    Coordinate coord[4];
    double period[4];
};

/// Where a region's coordinates sit: offsets in [-30, 30]; around +-1e6 (where an ulp is 1e-10);
/// coordinate 0 centred on a cell face (the others anywhere); or around 0 (negative coordinates,
/// where the double p - floor(p) rounds).
enum class Placement { Anywhere, Far, StraddlingFace, NearZero };

NoiseRegion RandomRegion(Rng& rng, int dims, double width, Placement where = Placement::Anywhere) {
    NoiseRegion g;
    g.uc = std::ldexp(rng.integer(0, 1 << 20), -20);
    g.vc = std::ldexp(rng.integer(0, 1 << 20), -20);
    g.r = std::ldexp(1.0, -rng.integer(3, 12));
    for (int i = 0; i < dims; ++i) {
        Coordinate& c = g.coord[i];
        c.offset = rng.chance(0.2) ? rng.integer(-20, 20) : rng.uniform(-30, 30);
        double s = width / (2 * g.r);  // |a| + |b| + |c| (|u|, |v| <= ~1) about s
        double wa = rng.uniform(0, 1), wb = rng.uniform(0, 1), wc = rng.chance(0.5) ? 0 : rng.uniform(0, 0.5);
        double sum = wa + wb + wc;
        c.a = (rng.chance(0.5) ? s : -s) * wa / sum;
        c.b = (rng.chance(0.5) ? s : -s) * wb / sum;
        c.c = (rng.chance(0.5) ? s : -s) * wc / sum;
        g.period[i] = rng.integer(1, 6);
        // The coordinate at the region's centre, moved where asked.
        if (where == Placement::Anywhere) continue;
        const double atCentre = c.a * g.uc + c.b * g.vc + c.c * (g.uc * g.vc);
        const double jitter = rng.uniform(-0.3, 0.3) * width;
        if (where == Placement::Far)
            c.offset = rng.integer(-1000000, 1000000) + rng.uniform(0, 1) - atCentre;
        else if (where == Placement::StraddlingFace && i == 0)
            c.offset = rng.integer(-20, 20) + jitter - atCentre;
        else if (where == Placement::NearZero)
            c.offset = rng.uniform(-1, 1) * std::fmin(1.0, width) + jitter - atCentre;
    }
    return g;
}

/// Range containment for each type (with the point's eps for affine forms).
bool Contains(const Interval& bound, double x, double, double) { return bound.contains(x); }
bool Contains(const Affine& bound, double x, double eu, double ev) {
    return bound.evaluateAt(eu, ev).contains(x) && bound.range().contains(x);
}
bool Contains(const ReducedAffine& bound, double x, double eu, double ev) {
    return bound.evaluateAt(eu, ev).contains(x) && bound.range().contains(x);
}
template <class T>
bool Contains(const Dual<T>& bound, const Dual<double>& x, double eu, double ev) {
    return Contains(bound.v, x.v, eu, ev) && Contains(bound.du, x.du, eu, ev) && Contains(bound.dv, x.dv, eu, ev);
}
template <class T>
bool Contains(const T& bound, const Dual<double>& x, double eu, double ev) {
    return Contains(bound, x.v, eu, ev);
}

/// u and v of a region in each type.
void MakeUV(const NoiseRegion& g, Interval* u, Interval* v) {
    *u = Interval(g.uc - g.r, g.uc + g.r);
    *v = Interval(g.vc - g.r, g.vc + g.r);
}
void MakeUV(const NoiseRegion& g, Affine* u, Affine* v) {
    *u = Affine::FromSymbol(g.uc, g.r, Affine::kSymbolU);
    *v = Affine::FromSymbol(g.vc, g.r, Affine::kSymbolV);
}
void MakeUV(const NoiseRegion& g, ReducedAffine* u, ReducedAffine* v) {
    *u = ReducedAffine::FromSymbol(g.uc, g.r, ReducedAffine::kSymbolU);
    *v = ReducedAffine::FromSymbol(g.vc, g.r, ReducedAffine::kSymbolV);
}
template <class T>
void MakeUV(const NoiseRegion& g, Dual<T>* u, Dual<T>* v) {
    T uu, vv;
    MakeUV(g, &uu, &vv);
    *u = Dual<T>(uu, T(1.0), T(0.0));
    *v = Dual<T>(vv, T(0.0), T(1.0));
}

enum class Function { Noise, PNoise, PNoiseVaryingPeriod, CellNoise };

template <class T>
T Evaluate(Function f, const T* p, const T* period, int dims, uint32_t seed,
           NoiseBoundMethod method = NoiseBoundMethod::Auto) {
    switch (f) {
        case Function::Noise: return noise_detail::GradientNoise(p, static_cast<const T*>(nullptr), dims, seed, method);
        case Function::CellNoise: return CellNoise(p, dims, seed);
        default: return noise_detail::GradientNoise(p, period, dims, seed, method);
    }
}

struct ContainmentReport {
    int regions = 0, points = 0, failures = 0;
    int oneCell = 0, fewCells = 0, manyCells = 0;
    std::ostringstream first;
};

/// Evaluates f over a region in T and at random points in Dual<double>: every point's value (and,
/// for dual T, derivatives) must lie in the bound, and the bound's range in [0, 1].
template <class T>
void CheckRegion(ContainmentReport& rep, Rng& rng, Function f, int dims, uint32_t seed, double width,
                 NoiseBoundMethod method = NoiseBoundMethod::Auto, Placement where = Placement::Anywhere) {
    NoiseRegion g = RandomRegion(rng, dims, width, where);
    Affine::BeginEvaluation();
    T u, v;
    MakeUV(g, &u, &v);
    T p[4], period[4];
    double cells = 1;
    for (int i = 0; i < dims; ++i) {
        p[i] = g.coord[i](u, v);
        Interval r = RangeOf(ValueOf(p[i]));
        cells *= std::floor(r.hi()) - std::floor(r.lo()) + 1;
        // A varying period: a range of width up to 1 around the integer period.
        period[i] = f == Function::PNoiseVaryingPeriod ? g.period[i] + 0.25 * (u - g.uc) / g.r : T(g.period[i]);
    }
    rep.regions++;
    (cells == 1 ? rep.oneCell : cells <= kNoiseCellCap ? rep.fewCells : rep.manyCells)++;
    T bound = Evaluate(f, p, period, dims, seed, method);
    Interval range = RangeOf(ValueOf(bound));
    if (!(range.lo() >= 0 && range.hi() <= 1) && rep.failures++ < 4)
        rep.first << "range " << range.toString() << " leaves [0, 1]\n";
    for (int k = 0; k < 20; ++k) {
        double eu = rng.eps(), ev = rng.eps();
        Dual<double> ud(g.uc + g.r * eu, 1.0, 0.0), vd(g.vc + g.r * ev, 0.0, 1.0);
        Dual<double> pd[4], periodd[4];
        for (int i = 0; i < dims; ++i) {
            pd[i] = g.coord[i](ud, vd);
            periodd[i] =
                f == Function::PNoiseVaryingPeriod ? g.period[i] + 0.25 * (ud - g.uc) / g.r : Dual<double>(g.period[i]);
        }
        Dual<double> x = Evaluate(f, pd, periodd, dims, seed);
        rep.points++;
        if (!Contains(bound, x, eu, ev) && rep.failures++ < 4)
            rep.first << "dims " << dims << " seed " << seed << " width " << width << " cells " << cells << " at ("
                      << eu << ", " << ev << "): " << ToString(x) << " not in " << ToString(bound) << "\n";
    }
}

template <class T>
void CheckContainment(const char* name, int regionsPerWidth) {
    // One cell, a few cells, and (from ~1.5 for d = 4 to 16 for d = 1) past kNoiseCellCap.
    const double widths[] = {1e-9, 1e-6, 1e-3, 0.05, 0.3, 0.9, 1.5, 3, 10, 40};
    for (Function f : {Function::Noise, Function::PNoise, Function::PNoiseVaryingPeriod, Function::CellNoise}) {
        for (int dims = 1; dims <= 4; ++dims) {
            ContainmentReport rep;
            Rng rng(1000 * dims + static_cast<int>(f));
            for (double width : widths)
                for (int k = 0; k < regionsPerWidth; ++k) CheckRegion<T>(rep, rng, f, dims, k % 3, width);
            INFO(name << " function " << static_cast<int>(f) << " dims " << dims << ": " << rep.regions << " regions ("
                      << rep.oneCell << " in one cell, " << rep.fewCells << " in 2.." << kNoiseCellCap << ", "
                      << rep.manyCells << " in more), " << rep.points << " points\n"
                      << rep.first.str());
            CHECK(rep.failures == 0);
            CHECK(rep.oneCell > 0);
            CHECK(rep.fewCells > 0);
            CHECK(rep.manyCells > 0);
        }
    }
}

TEST_CASE("noise bounds contain the double value: Interval", "[vm][noise]") {
    CheckContainment<Interval>("interval", Samples(40));
}
TEST_CASE("noise bounds contain the double value: Affine", "[vm][noise]") {
    CheckContainment<Affine>("affine", Samples(40));
}
TEST_CASE("noise bounds contain the Dual<double> value and derivatives: Dual<Affine>", "[vm][noise]") {
    CheckContainment<Dual<Affine>>("dual-affine", Samples(25));
}
TEST_CASE("noise bounds contain the Dual<double> value and derivatives: Dual<Interval>", "[vm][noise]") {
    CheckContainment<Dual<Interval>>("dual-interval", Samples(25));
}
TEST_CASE("noise bounds contain the double value: ReducedAffine", "[vm][noise][reduced]") {
    CheckContainment<ReducedAffine>("reduced", Samples(40));
}
TEST_CASE("noise bounds contain the Dual<double> value and derivatives: Dual<ReducedAffine>", "[vm][noise][reduced]") {
    CheckContainment<Dual<ReducedAffine>>("dual-reduced", Samples(25));
}

TEST_CASE("noise bounds contain the double value far from the origin, near 0 and across faces", "[vm][noise]") {
    // Every way of bounding: LocalForm (Affine's and ReducedAffine's default, Interval on
    // request) and the cell polynomial in T arithmetic (Interval's and the Duals' default, Affine
    // and ReducedAffine on request), over widths from 1e-9 to several cells.
    const double widths[] = {1e-9, 1e-6, 1e-3, 1.0 / 512, 1.0 / 64, 1.0 / 8, 0.5, 1.5, 4};
    const int regions = Samples(2);
    ContainmentReport rep;
    int check = 0;
    auto run = [&](auto tag, NoiseBoundMethod method, int dims, Function f, Placement where) {
        using T = decltype(tag);
        Rng rng(7000 + 100 * dims + 10 * static_cast<int>(f) + static_cast<int>(where) + 1000 * check++);
        for (double width : widths)
            for (int k = 0; k < regions; ++k) CheckRegion<T>(rep, rng, f, dims, k % 3, width, method, where);
    };
    for (Placement where : {Placement::Far, Placement::StraddlingFace, Placement::NearZero}) {
        for (Function f : {Function::Noise, Function::PNoise, Function::CellNoise}) {
            for (int dims = 1; dims <= 4; ++dims) {
                run(Affine(), NoiseBoundMethod::Auto, dims, f, where);
                run(Affine(), NoiseBoundMethod::Polynomial, dims, f, where);
                run(Interval(), NoiseBoundMethod::Auto, dims, f, where);
                run(Interval(), NoiseBoundMethod::Local, dims, f, where);
                run(Dual<Affine>(), NoiseBoundMethod::Auto, dims, f, where);
                run(ReducedAffine(), NoiseBoundMethod::Auto, dims, f, where);
                run(ReducedAffine(), NoiseBoundMethod::Polynomial, dims, f, where);
            }
        }
    }
    INFO(rep.regions << " regions (" << rep.oneCell << " in one cell, " << rep.fewCells << " in 2.." << kNoiseCellCap
                     << ", " << rep.manyCells << " in more), " << rep.points << " points\n"
                     << rep.first.str());
    CHECK(rep.failures == 0);
}

TEST_CASE("noise LocalForm operations contain the double results (aavalid)", "[vm][noise]") {
    // Stolfi's method (/work/shared/AFFINE-NOTES.md): random operand forms (shared symbols, exact
    // constants, x*x, magnitudes from 2^-40 to 4), every symbol fixed at -1, 0, 1 or a random
    // value, double operand values inside the forms there, the double operation on them; the
    // result form at the same symbols (its fresh symbol free) must contain the double result.
    // Sums are taken in long double (64-bit significands), far finer than the slack checked.
    using noise_detail::LocalForm;
    Rng rng(31);
    affray::test::Tally tally;
    int skipped = 0;
    for (int n = 0; n < Samples(3000); ++n) {
        const int dims = rng.integer(1, 4);
        LocalForm::Begin(dims);
        auto randomForm = [&]() {
            LocalForm x(rng.uniform(-2, 2) * std::ldexp(1.0, rng.integer(-30, 4)));
            if (rng.chance(0.1)) return x;  // an exact constant
            x.n = rng.integer(1, dims + 3);
            const double scale = std::ldexp(1.0, rng.integer(-40, 2));
            for (int k = 0; k < x.n; ++k) x.c[k] = rng.chance(0.2) ? 0.0 : rng.uniform(-1, 1) * scale;
            // Some error, so that a rounded value can lie inside.
            x.e = (std::fabs(x.c0) + scale) * (rng.chance(0.5) ? 0x1p-45 : rng.uniform(0, 1) * 1e-3);
            return x;
        };
        const LocalForm x = randomForm();
        const bool square = rng.chance(0.2);
        const LocalForm y = square ? x : randomForm();
        // A product's fresh symbol goes after every slot in use.
        const int used = std::max({x.n, y.n, dims});
        LocalForm::NextFresh() = used;
        const double k = rng.chance(0.3) ? rng.integer(-15, 15) : rng.uniform(-16, 16);
        const int op = rng.integer(0, 6);
        const LocalForm r = op == 0   ? x + y
                            : op == 1 ? x - y
                            : op == 2 ? x * y
                            : op == 3 ? x * k
                            : op == 4 ? x + k
                            : op == 5 ? -x
                                      : k * x;
        for (int trial = 0; trial < 8; ++trial) {
            long double sigma[LocalForm::kSlots];
            for (long double& s : sigma) s = rng.eps();
            auto centre = [&](const LocalForm& f) {
                long double v = f.c0;
                for (int j = 0; j < f.n; ++j) v += static_cast<long double>(f.c[j]) * sigma[j];
                return v;
            };
            // A double inside f at sigma (or NaN if rounding pushed it out).
            auto value = [&](const LocalForm& f) {
                const long double m = centre(f);
                const double v = static_cast<double>(m + static_cast<long double>(rng.eps()) * f.e);
                return std::fabs(v - m) <= f.e ? v : std::numeric_limits<double>::quiet_NaN();
            };
            const double a = value(x), b = square ? a : value(y);
            if (std::isnan(a) || std::isnan(b)) {
                ++skipped;
                continue;
            }
            const double scalar = op == 0   ? a + b
                                  : op == 1 ? a - b
                                  : op == 2 ? a * b
                                  : op == 3 ? a * k
                                  : op == 4 ? a + k
                                  : op == 5 ? -a
                                            : k * a;
            long double mid = r.c0, rad = r.e;
            for (int j = 0; j < r.n; ++j) {
                if (j < used)
                    mid += static_cast<long double>(r.c[j]) * sigma[j];
                else
                    rad += std::fabs(r.c[j]);  // the fresh symbol, free
            }
            tally.samples++;
            if (!(std::fabs(static_cast<long double>(scalar) - mid) <= rad))
                tally.fail("op " + std::to_string(op) + ": " + ToString(scalar) + " outside " +
                           ToString(static_cast<double>(mid)) + " +- " + ToString(static_cast<double>(rad)));
        }
    }
    INFO(tally.samples << " samples, " << skipped << " skipped\n" << tally.first.str());
    CHECK(tally.failures == 0);
    CHECK(skipped < tally.samples / 2);
}

TEST_CASE("noise bounds are tight inside one cell", "[vm][noise]") {
    // Regions whose coordinates each span about 1e-3 inside one lattice cell. The noise changes
    // there by at most sum_i |dn/dp_i| * 1e-3, and sum_i |dn/dp_i| was measured (3e5 points per
    // dims, Dual<double>) at most 1.35, 2.02, 2.26, 2.19 for d = 1..4: an exact bound is at most
    // ~2.3e-3 wide, and affine arithmetic adds only second-order terms (~1e-6) and rounding.
    // Measured worst widths over 3000 regions per dims: 1.69e-3, 1.97e-3, 1.64e-3, 1.58e-3 for
    // d = 1..4 (intervals: 0.029, 0.097, 0.24, 0.60; affine is 3.5 to 34 times narrower on
    // average). The threshold 4e-3 is 1.7 times the exact bound and 12 times below the 0.05
    // that would already make noise shaders slow to render.
    // Affine's LocalForm bounds (its default) must not be wider on average than the cell
    // polynomial in Affine arithmetic (measured mean ratio 0.995-0.999), and Interval's
    // LocalForm bounds are close to affine ones (measured mean ratio to the interval polynomial
    // 0.13 (d = 1) down to 0.02 (d = 4)).
    Rng rng(23);
    const auto kPolynomial = NoiseBoundMethod::Polynomial, kLocal = NoiseBoundMethod::Local;
    for (int dims = 1; dims <= 4; ++dims) {
        double worstAffine = 0, worstInterval = 0, sumRatio = 0, sumLocalRatio = 0;
        double sumIntervalLocalRatio = 0;
        int n = 0;
        while (n < 1000) {
            NoiseRegion g = RandomRegion(rng, dims, 1e-3);
            Affine::BeginEvaluation();
            Affine u, v, p[4];
            Interval ui, vi, pi[4];
            MakeUV(g, &u, &v);
            MakeUV(g, &ui, &vi);
            bool oneCell = true;
            for (int i = 0; i < dims; ++i) {
                p[i] = g.coord[i](u, v);
                pi[i] = g.coord[i](ui, vi);
                oneCell = oneCell && std::floor(p[i].range().lo()) == std::floor(p[i].range().hi());
            }
            if (!oneCell) continue;
            ++n;
            const uint32_t seed = n % 3;
            double wa = Noise(p, dims, seed).range().width();
            double wi = Noise(pi, dims, seed).width();
            double wap = noise_detail::GradientNoise<Affine>(p, nullptr, dims, seed, kPolynomial).range().width();
            double wil = noise_detail::GradientNoise<Interval>(pi, nullptr, dims, seed, kLocal).width();
            worstAffine = std::max(worstAffine, wa);
            worstInterval = std::max(worstInterval, wil);
            sumRatio += wa / wi;
            sumLocalRatio += wa / wap;
            sumIntervalLocalRatio += wil / wi;
        }
        INFO("dims " << dims << ": worst affine width " << worstAffine << ", interval (local) " << worstInterval
                     << ", mean affine/interval " << sumRatio / n << ", affine local/polynomial " << sumLocalRatio / n
                     << ", interval local/polynomial " << sumIntervalLocalRatio / n);
        CHECK(worstAffine < 4e-3);
        CHECK(worstInterval < 4e-3);
        CHECK(sumRatio / n < 0.5);  // measured 0.28 (d = 1) down to 0.03 (d = 4)
        CHECK(sumLocalRatio / n <= 1.0);
        CHECK(sumIntervalLocalRatio / n < 0.4);
    }
}

TEST_CASE("noise fade axes contain the double fade and are no wider than the fade in LocalForm arithmetic",
          "[vm][noise]") {
    // MakeLocalAxis's closed-form fade (its Taylor polynomial at the part's centre, rounding bounded
    // a priori) against Fade<double> at the ends and random doubles of parts of a cell from the
    // whole cell down to 2^-40 of it, near 0, 1/2 and 1; its width (|fadeLinear| + fadeOwn +
    // fadeError) against the fade computed in LocalForm arithmetic (five products, each remainder
    // on a fresh symbol), which it replaces.
    using noise_detail::LocalForm;
    Rng rng(29);
    int failures = 0, wider = 0, samples = 0;
    std::ostringstream first;
    const int parts = Samples(3000);
    for (int n = 0; n < parts; ++n) {
        const double width = n % 10 == 0 ? 1.0 : std::ldexp(rng.uniform(0.5, 1), -rng.integer(0, 40));
        const int where = n % 4;
        const double lo = where == 0   ? 0.0
                          : where == 1 ? 1.0 - width
                          : where == 2 ? std::max(0.0, 0.5 - width * rng.uniform(0, 1))
                                       : rng.uniform(0, 1 - width);
        const double hi = std::min(1.0, lo + width);
        const double k = std::floor(rng.uniform(-1e6, 1e6));
        const noise_detail::LocalAxis axis = noise_detail::MakeLocalAxis(Interval(k + lo, k + hi), k);
        // The same part in LocalForm arithmetic, as MakeLocalAxis computed it before.
        LocalForm::Begin(1);
        const LocalForm fade = noise_detail::Fade(LocalForm::Coordinate(axis.centre, axis.reach, 0));
        double own = 0;
        for (int s = 1; s < fade.n; ++s) own += std::fabs(fade.c[s]);
        const double oldWidth = std::fabs(fade.n > 0 ? fade.c[0] : 0.0) + own + fade.e;
        const double newWidth = std::fabs(axis.fadeLinear) + axis.fadeOwn + axis.fadeError;
        // Beyond rounding: the closed form bounds it a priori (about 1e-13 for a fade near 1), where
        // LocalForm tracks each operation's (about 1e-14); a part of a cell 2^-40 wide is that thin.
        if (newWidth > oldWidth * (1 + 1e-6) + 1e-12) ++wider;
        for (int s = 0; s < 8; ++s) {
            // t_d = p - k for p in the part, as the double reference computes it.
            const double p = s == 0 ? k + lo : s == 1 ? k + hi : rng.uniform(k + lo, k + hi);
            const double t = p - k;
            if (t < axis.centre - axis.reach || t > axis.centre + axis.reach) continue;
            ++samples;
            const double value = noise_detail::Fade(t);
            const double sigma = axis.reach > 0 ? std::clamp((t - axis.centre) / axis.reach, -1.0, 1.0) : 0.0;
            const double mid = axis.fade0 + axis.fadeLinear * sigma;
            const double slack =
                axis.fadeOwn + axis.fadeError + 4 * kEpsilon * (std::fabs(mid) + std::fabs(axis.fadeLinear));
            if (std::fabs(value - mid) > slack && failures++ < 4)
                first << "Fade(" << t << ") = " << value << " not in " << mid << " +- " << slack << " over [" << lo
                      << ", " << hi << "]\n";
        }
    }
    INFO(first.str());
    CHECK(failures == 0);
    CHECK(samples > 10000);
    INFO(wider << " of " << parts << " closed-form fades wider than LocalForm's");
    CHECK(wider == 0);
}

TEST_CASE("reduced affine noise over more cells than are bounded one by one is at worst its range",
          "[vm][noise][reduced]") {
    // Past kNoiseCellCap cells the cell polynomial runs on the gradients' ranges: its form had an
    // error of about 30,000 around the range [0, 1], and every product downstream (a displaced
    // point's form) carried it. The value is now at worst [0, 1] as 0.5 +- 0.5, and it still
    // holds every sampled double.
    Rng rng(37);
    for (int n = 0; n < 50; ++n) {
        ReducedAffine p[3];
        double c[3], a[3], b[3];
        for (int i = 0; i < 3; ++i) {
            c[i] = rng.uniform(-50, 50);
            a[i] = rng.uniform(2, 4) * (rng.uniform(0, 1) < 0.5 ? -1 : 1);
            b[i] = rng.uniform(-3, 3);
            p[i] = ReducedAffine::FromForm(c[i], a[i], b[i], 0.01);
        }
        const ReducedAffine value = Noise(p, 3, 0);
        INFO(value.toString());
        CHECK(value.error() + std::fabs(value.coefficientU()) + std::fabs(value.coefficientV()) <= 0.5 + 1e-12);
        for (int k = 0; k < 20; ++k) {
            const double eu = rng.uniform(-1, 1), ev = rng.uniform(-1, 1);
            double q[3];
            for (int i = 0; i < 3; ++i) q[i] = c[i] + a[i] * eu + b[i] * ev;
            const double scalar = Noise(q, 3, 0);
            CHECK(value.evaluateAt(eu, ev).contains(scalar));
        }
    }
}

TEST_CASE("reduced affine noise bounds stay close to the noise's own deviation from their plane",
          "[vm][noise][reduced]") {
    // A surface's region is a parallelogram in noise space, not the box of its coordinate ranges:
    // QuadraticCellOnRegion bounds each cell on the region's own symbols, keeping second order to
    // the end, so its error is compared with how far the noise really strays from the bound's
    // plane over the parallelogram (sampled on a 41 x 41 grid), for regions 0.3 to 0.01 of a cell
    // wide in 3-d noise, inside a cell and straddling faces (joined over up to 8 cells). Measured
    // mean ratios: inside 2.0, 1.5, 1.2 and 1.02; straddling 2.3, 2.2, 2.1 and 1.1. (With the
    // lerps as products of QuadForms, not Lerp: 3.1, 2.0, 1.4 and 1.04 inside; with each cell
    // over the whole region, not its own part: 5.1, 5.0, 4.6 and 1.09 straddling, and 5.8, 5.5,
    // 4.9 and 1.1 with products too; on LocalForms in eps_u and eps_v with a symbol per product:
    // 5.6, 4.8, 4.0 and 3.6 inside, 5.3, 5.1, 4.7 and 1.5 straddling; on the box of the
    // coordinates, 6.7 at 0.1 and 5.9 at 0.01.)
    struct Case {
        double width;
        bool straddling;
        double limit;
    };
    const Case cases[] = {{0.3, false, 2.3}, {0.2, false, 1.7}, {0.1, false, 1.35}, {0.01, false, 1.1},
                          {0.3, true, 2.6},  {0.2, true, 2.5},  {0.1, true, 2.35},  {0.01, true, 1.2}};
    Rng rng(31);
    for (const Case& test : cases) {
        double sumError = 0, sumTrue = 0;
        for (int n = 0; n < 200; ++n) {
            double c[3], a[3], b[3];
            for (int i = 0; i < 3; ++i) {
                c[i] = std::floor(rng.uniform(0, 100)) +
                       (test.straddling ? rng.uniform(-0.05, 0.05) : 0.5 + rng.uniform(-0.3, 0.3));
                a[i] = 0.5 * test.width * rng.uniform(-1, 1);
                b[i] = 0.5 * test.width * rng.uniform(-1, 1);
            }
            const ReducedAffine eu = ReducedAffine::FromSymbol(0, 1, ReducedAffine::kSymbolU);
            const ReducedAffine ev = ReducedAffine::FromSymbol(0, 1, ReducedAffine::kSymbolV);
            ReducedAffine p[3];
            for (int i = 0; i < 3; ++i) p[i] = eu * a[i] + ev * b[i] + c[i];
            const ReducedAffine bound = Noise(p, 3, 0);
            REQUIRE_FALSE(bound.isUnbounded());
            double lo = INFINITY, hi = -INFINITY;
            for (int i = 0; i <= 40; ++i)
                for (int j = 0; j <= 40; ++j) {
                    const double x = -1 + i / 20.0, y = -1 + j / 20.0;
                    double q[3];
                    for (int k = 0; k < 3; ++k) q[k] = c[k] + a[k] * x + b[k] * y;
                    const double off =
                        Noise(q, 3, 0) - (bound.center() + bound.coefficientU() * x + bound.coefficientV() * y);
                    lo = std::min(lo, off);
                    hi = std::max(hi, off);
                }
            sumError += bound.error();
            sumTrue += 0.5 * (hi - lo);
        }
        INFO("width " << test.width << (test.straddling ? " straddling" : " inside") << ": mean error "
                      << sumError / 200 << ", mean deviation " << sumTrue / 200 << ", ratio " << sumError / sumTrue);
        CHECK(sumError < test.limit * sumTrue);
    }
}

TEST_CASE("noise: the in-place LocalForm cell polynomial makes the template's forms exactly", "[vm][noise]") {
    // FadedCellPolynomialInPlace must be FadedCellPolynomial<LocalForm> without its copies: the
    // same centre, coefficients, slot count and error, bit for bit, for every gradient set and
    // for gradients other than 0 and +-1, on random coordinate and fade forms.
    using noise_detail::LocalForm;
    Rng rng(37);
    int mismatches = 0;
    for (int n = 0; n < Samples(400); ++n) {
        const int dims = 1 + n % 4;
        LocalForm t[4], fade[4];
        double g[16][4];
        for (int o = 0; o < (1 << dims); ++o)
            for (int i = 0; i < dims; ++i) {
                const int kind = rng.integer(0, 3);
                g[o][i] = kind == 0 ? 0.0 : kind == 1 ? 1.0 : kind == 2 ? -1.0 : rng.uniform(-2, 2);
            }
        auto make = [&] {
            LocalForm::Begin(2 * dims);
            for (int i = 0; i < dims; ++i) {
                t[i] = LocalForm::Coordinate(rng.uniform(0, 1), rng.uniform(0, 0.5), i);
                LocalForm& f = fade[i];
                f.c0 = rng.uniform(0, 1);
                f.e = rng.chance(0.5) ? 0.0 : rng.uniform(0, 1e-12);
                f.n = dims + i + 1;
                for (int k = 0; k < f.n; ++k) f.c[k] = 0;
                f.c[i] = rng.uniform(-2, 2);
                f.c[dims + i] = rng.uniform(0, 0.1);
            }
        };
        const uint64_t state = rng.gen();
        rng.gen.seed(state);
        make();
        const LocalForm a = noise_detail::FadedCellPolynomial(t, fade, dims, [&](int o, int i) { return g[o][i]; });
        rng.gen.seed(state);
        make();
        const LocalForm b = noise_detail::FadedCellPolynomialInPlace(t, fade, dims, g);
        bool same = a.c0 == b.c0 && a.e == b.e && a.n == b.n;
        for (int k = 0; same && k < a.n; ++k) same = a.c[k] == b.c[k];
        if (!same) ++mismatches;
    }
    CHECK(mismatches == 0);
}

}  // namespace

TEST_CASE("noise: a straddling region's cell parts hold every point of the region in the cell",
          "[vm][noise][reduced]") {
    // CellPartOf: for planes through boxes of 2 to 8 cells (with coordinate errors), every
    // sampled point whose double coordinates (any value each form allows there) fall in a cell
    // lies in that cell's box, and the cells no point can reach are reported, not bounded.
    Rng rng(53);
    int points = 0, outside = 0, unreachable = 0, reachable = 0, missedReachable = 0;
    std::ostringstream first;
    for (int n = 0; n < Samples(400); ++n) {
        const int dims = rng.integer(1, 4);
        ReducedAffine p[4];
        double c[4], a[4], b[4], e[4];
        for (int i = 0; i < dims; ++i) {
            c[i] = std::floor(rng.uniform(-50, 50)) + rng.uniform(-0.2, 0.2);
            const double width = rng.chance(0.2) ? 1e-6 : rng.uniform(0.01, 0.4);
            a[i] = rng.chance(0.15) ? 0.0 : width * rng.uniform(-1, 1);
            b[i] = rng.chance(0.15) ? 0.0 : width * rng.uniform(-1, 1);
            e[i] = rng.chance(0.5) ? 0.0 : rng.uniform(0, 0.01);
            p[i] = ReducedAffine::FromForm(c[i], a[i], b[i], e[i]);
        }
        noise_detail::CellBox box;
        REQUIRE(box.Of(p, dims));
        if (!(box.cells <= kNoiseCellCap)) continue;
        box.ForEach(dims, [&](const double* k, const int*) {
            noise_detail::CellPart part;
            const bool found = noise_detail::CellPartOf(p, k, dims, &part);
            (found ? reachable : unreachable)++;
            for (int s = 0; s < 200; ++s) {
                const double eu = rng.eps(), ev = rng.eps();
                bool in = true;
                for (int i = 0; i < dims; ++i) {
                    const double x = c[i] + a[i] * eu + b[i] * ev + e[i] * rng.eps();
                    in = in && std::floor(x) == k[i];
                }
                if (!in) continue;
                ++points;
                if (!found) {
                    if (missedReachable++ == 0) first << "a point in a cell reported unreachable\n";
                    continue;
                }
                if (!(std::fabs(eu - part.mu) <= part.su && std::fabs(ev - part.mv) <= part.sv) && outside++ == 0)
                    first << "(" << eu << ", " << ev << ") outside the box " << part.mu << " +- " << part.su << ", "
                          << part.mv << " +- " << part.sv << "\n";
            }
        });
    }
    INFO(points << " points, " << reachable << " cells reachable, " << unreachable << " not\n" << first.str());
    CHECK(points > 1000);
    CHECK(outside == 0);
    CHECK(missedReachable == 0);
    CHECK(unreachable > 0);
}
