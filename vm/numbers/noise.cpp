// vm/numbers/noise.cpp: the lattice hash and the gradient sets of vm/numbers/noise.h (the templates live there).
// The hash is integer arithmetic on uint64_t only (wrap-around is defined), so every platform
// draws the same gradients and cell values.
#include "vm/numbers/noise.h"

#include <cmath>

namespace affray::vm {

namespace {

// cos and sin of 22.5 degrees, rounded to nearest.
constexpr double kC = 0.92387953251128674;
constexpr double kS = 0.38268343236508978;

// d = 1: magnitudes 9/16 .. 16/16 with both signs (a spread of slopes, not just +-1).
constexpr double kGradients1[16] = {9 / 16.0,   10 / 16.0,  11 / 16.0,  12 / 16.0,  13 / 16.0,  14 / 16.0,
                                    15 / 16.0,  1.0,        -9 / 16.0,  -10 / 16.0, -11 / 16.0, -12 / 16.0,
                                    -13 / 16.0, -14 / 16.0, -15 / 16.0, -1.0};
// d = 2: the unit vectors at 22.5 + 45k degrees.
constexpr double kGradients2[8 * 2] = {kC, kS, kS, kC, -kS, kC, -kC, kS, -kC, -kS, -kS, -kC, kS, -kC, kC, -kS};
// d = 3: the 12 edge vectors (+-1, +-1, 0), (+-1, 0, +-1), (0, +-1, +-1).
constexpr double kGradients3[12 * 3] = {1, 1, 0, -1, 1,  0, 1, -1, 0,  -1, -1, 0,   //
                                        1, 0, 1, -1, 0,  1, 1, 0,  -1, -1, 0,  -1,  //
                                        0, 1, 1, 0,  -1, 1, 0, 1,  -1, 0,  -1, -1};
// d = 4: the 24 vectors with two components +-1 and two 0.
constexpr double kGradients4[24 * 4] = {1, 1, 0, 0, -1, 1,  0,  0, 1, -1, 0,  0,  -1, -1, 0,  0,   //
                                        1, 0, 1, 0, -1, 0,  1,  0, 1, 0,  -1, 0,  -1, 0,  -1, 0,   //
                                        1, 0, 0, 1, -1, 0,  0,  1, 1, 0,  0,  -1, -1, 0,  0,  -1,  //
                                        0, 1, 1, 0, 0,  -1, 1,  0, 0, 1,  -1, 0,  0,  -1, -1, 0,   //
                                        0, 1, 0, 1, 0,  -1, 0,  1, 0, 1,  0,  -1, 0,  -1, 0,  -1,  //
                                        0, 0, 1, 1, 0,  0,  -1, 1, 0, 0,  1,  -1, 0,  0,  -1, -1};

const NoiseGradientSet kSets[5] = {
    {0, 0, nullptr, 0},        {1, 16, kGradients1, 1.0}, {2, 8, kGradients2, kC},
    {3, 12, kGradients3, 1.0}, {4, 24, kGradients4, 1.0},
};
// 0.5 / B_d; B_d is proven in tests/vm/numbers/noise_test.cpp (see vm/numbers/noise.h).
const double kScales[5] = {0, 1.0, 0.5 / 0.665, 0.5 / 1.05, 0.5 / 1.125};

/// SplitMix64's finaliser (Stafford's "mix13"): a bijection of uint64_t with full avalanche.
uint64_t Mix64(uint64_t x) {
    x ^= x >> 30;
    x *= 0xbf58476d1ce4e5b9ULL;
    x ^= x >> 27;
    x *= 0x94d049bb133111ebULL;
    x ^= x >> 31;
    return x;
}

}  // namespace

const NoiseGradientSet& NoiseGradients(int dims) { return kSets[dims >= 1 && dims <= 4 ? dims : 0]; }

double NoiseScale(int dims) { return kScales[dims >= 1 && dims <= 4 ? dims : 0]; }

namespace noise_detail {

constexpr double kIndexLimit = 0x1p62;

int64_t CellIndex(double k) {
    if (!(k > -kIndexLimit)) return -static_cast<int64_t>(kIndexLimit);
    if (!(k < kIndexLimit)) return static_cast<int64_t>(kIndexLimit);
    return static_cast<int64_t>(k);
}

int64_t PeriodOf(double period) {
    double p = std::round(period);
    if (!(p >= 1)) return 1;
    if (!(p < kIndexLimit)) return static_cast<int64_t>(kIndexLimit);
    return static_cast<int64_t>(p);
}

uint64_t HashLattice(const int64_t* c, int dims, uint32_t seed, HashKind kind) {
    // Start from (kind, dims, seed), then absorb one coordinate per round; each round is a
    // bijection of the state, so distinct inputs collide only by 64-bit chance.
    uint64_t h =
        Mix64(0x243f6a8885a308d3ULL ^ (static_cast<uint64_t>(kind) << 56) ^ (static_cast<uint64_t>(dims) << 48) ^ seed);
    for (int i = 0; i < dims; ++i) h = Mix64(h ^ static_cast<uint64_t>(c[i]));
    return h;
}

void LatticeGradient(const int64_t* c, int dims, uint32_t seed, double* g) {
    const NoiseGradientSet& set = kSets[dims];
    uint64_t h = HashLattice(c, dims, seed, HashKind::Gradient);
    // The top 32 bits scaled to [0, count): bias below 2^-27.
    uint64_t index = ((h >> 32) * static_cast<uint64_t>(set.count)) >> 32;
    for (int i = 0; i < dims; ++i) g[i] = set.components[index * dims + i];
}

double CellValue(const int64_t* c, int dims, uint32_t seed) {
    return static_cast<double>(HashLattice(c, dims, seed, HashKind::Cell) >> 11) * 0x1p-53;
}

}  // namespace noise_detail

}  // namespace affray::vm
