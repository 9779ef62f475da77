// tests/vm/numbers/aavalid.h: the operands of Stolfi's aavalid method, shared by the containment tests of
// every affine type (tests/vm/numbers/affine_test.cpp, tests/vm/numbers/reduced_affine_test.cpp): a random region
// u = uc + ur*eps_u, v = vc + vr*eps_v with a point (eps_u, eps_v) in it, all exact doubles, and
// random recipes that build operands from u and v with the same code on any number type, and
// random straight-line programs over every built-in.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include "tests/test_random.h"
#include "vm/numbers/number.h"

namespace affray::test::aavalid {

using vm::sign;
using vm::sqr;

inline bool ExactSum(double c, double r, double e, double* out) {
    double p = r * e, s = c + p;
    *out = s;
    return std::fma(r, e, -p) == 0 && vm::TwoSumError(c, p, s) == 0;
}

/// One region and one point in it, exactly representable.
struct Region {
    double uc, ur, vc, vr, eu, ev, u, v;
};

struct RegionConfig {
    int expLo = -20, expHi = 20;  // magnitude (log2) of u and v
    double touchZero = 0.15;      // chance that u's range touches 0
    double uWidth = 0;            // if > 0: ur is about uWidth/2 (sin/cos periods)
    double uCenter = 0;           // if > 0: |uc| up to this
};

inline Region RandomRegion(Rng& rng, const RegionConfig& cfg) {
    for (;;) {
        Region r;
        int eu = rng.integer(cfg.expLo, cfg.expHi), ev = rng.integer(cfg.expLo, cfg.expHi);
        r.ur = std::fabs(rng.dyadic(eu - rng.integer(0, 8), 16));
        r.uc = rng.dyadic(eu, 20);
        r.vr = std::fabs(rng.dyadic(ev - rng.integer(0, 8), 16));
        r.vc = rng.dyadic(ev, 20);
        if (cfg.uWidth > 0) {
            // A grid fine enough for the width, coarse enough to keep uc + ur exact.
            double q = std::ldexp(1.0, std::ilogb(std::fmax(cfg.uCenter, 1.0)) - 44);
            double w = cfg.uWidth * rng.uniform(0.97, 1.03);
            r.ur = std::round(w / 2 / q) * q;
            r.uc = std::round(rng.uniform(-cfg.uCenter, cfg.uCenter) / q) * q;
        }
        if (rng.chance(cfg.touchZero)) r.uc = rng.chance(0.5) ? r.ur : -r.ur;
        double t;
        if (r.ur == 0 || !ExactSum(r.uc, r.ur, 1, &t) || !ExactSum(r.uc, r.ur, -1, &t) ||
            !ExactSum(r.vc, r.vr, 1, &t) || !ExactSum(r.vc, r.vr, -1, &t))
            continue;
        // A random point if it is exact, else a corner or the center (exact by the above).
        for (int k = 0; k < 20; ++k) {
            r.eu = rng.eps();
            r.ev = rng.eps();
            if (ExactSum(r.uc, r.ur, r.eu, &r.u) && ExactSum(r.vc, r.vr, r.ev, &r.v)) return r;
        }
        r.eu = rng.integer(-1, 1);
        r.ev = rng.integer(-1, 1);
        ExactSum(r.uc, r.ur, r.eu, &r.u);
        ExactSum(r.vc, r.vr, r.ev, &r.v);
        return r;
    }
}

/// A recipe for an operand: the same operations run on any number type.
struct Recipe {
    int kind = 0;
    double c[4] = {0, 0, 0, 0};
    double shift = 0;
    double scale = 1;
};

struct RecipeConfig {
    int kindHi = 6;                      // kinds 0..kindHi
    int coefExpLo = -4, coefExpHi = 4;   // coefficient magnitudes (log2)
    std::vector<double> shifts = {0.0};  // added at the end (e.g. 700 for exp)
    double scale = 1;                    // multiplies the result (applied before the shift)
};

inline Recipe RandomRecipe(Rng& rng, const RecipeConfig& cfg) {
    Recipe r;
    r.kind = rng.integer(0, cfg.kindHi);
    for (double& c : r.c) c = rng.chance(0.1) ? 1.0 : rng.dyadic(rng.integer(cfg.coefExpLo, cfg.coefExpHi), 24);
    r.shift = cfg.shifts[rng.integer(0, static_cast<int>(cfg.shifts.size()) - 1)];
    r.scale = cfg.scale;
    return r;
}

template <class T>
T Build(const Recipe& r, const T& u, const T& v) {
    using std::cos, std::sin;
    T x = u;
    switch (r.kind) {
        case 0: x = u; break;
        case 1: x = v; break;
        case 2: x = r.c[0] + r.c[1] * u + r.c[2] * v; break;
        case 3: x = r.c[0] * u * v + r.c[1] * u - r.c[2]; break;
        case 4: x = r.c[0] + r.c[1] * sqr(u - r.c[2]) + r.c[3] * v; break;
        case 5: x = r.c[0] * u + r.c[1] * sin(r.c[2] * u + v); break;
        default: {
            // Many nonlinear terms: more fresh symbols than Affine::kCapacity.
            x = r.c[0] * v;
            for (int k = 1; k <= 14; ++k) x = x + (r.c[1] / k) * cos(k * u + r.c[2] * v);
        }
    }
    if (r.scale != 1) x = x * r.scale;
    if (r.shift != 0) x = x + r.shift;
    return x;
}

/// A random straight-line program over registers 0 = u, 1 = v: every built-in, any operands.
struct Step {
    int op, a, b;
    double k;
};

template <class T>
T RunStep(const Step& s, const T& a, const T& b) {
    using std::abs, std::cos, std::exp, std::log, std::pow, std::sin, std::sqrt;
    // clang-format off
    switch (s.op) {
        case 0: return a + b;       case 1: return a - b;      case 2: return a * b;
        case 3: return a / b;       case 4: return sqr(a);     case 5: return sqrt(a);
        case 6: return exp(a);      case 7: return log(a);     case 8: return sin(a);
        case 9: return cos(a);      case 10: return abs(a);    case 11: return sign(a);
        case 12: return pow(a, b);  case 13: return pow(a, T(s.k));
        case 14: return a * s.k + b;  case 15: return s.k / a;  default: return s.k - a;
    }
    // clang-format on
}

/// 16 random steps, each reading one of the last 4 registers and any other.
inline std::vector<Step> RandomSteps(Rng& rng) {
    std::vector<Step> program;
    for (int i = 0; i < 16; ++i) {
        int n = 2 + i;
        Step s{rng.integer(0, 16), rng.integer(std::max(0, n - 4), n - 1), rng.integer(0, n - 1),
               rng.dyadic(rng.integer(-3, 2), 8)};
        if (s.op == 13) s.k = rng.integer(-4, 5) + (rng.chance(0.3) ? 0.5 : 0.0);
        program.push_back(s);
    }
    return program;
}

template <class T>
std::vector<T> RunProgram(const std::vector<Step>& program, const T& u, const T& v) {
    std::vector<T> r = {u, v};
    for (const Step& s : program) r.push_back(RunStep(s, r[s.a], r[s.b]));
    return r;
}

}  // namespace affray::test::aavalid
