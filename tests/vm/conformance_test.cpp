// tests/vm/conformance_test.cpp: the opcode conformance suite (issue 14, item 4). It iterates the
// opcode list itself (vm/opcodes.h), so an opcode added later without a sample here does not
// compile: SampleFor's switch names every opcode (-Wswitch under -Werror), and a static_assert
// checks that every opcode but Ext, Light and Trace has a sample whose operand count is its
// format's (Light and Trace are no arithmetic: the renderer answers them, tests/renderer/).
// A sample builds a one-instruction program from the opcode's format (registers, constants, Ext
// words), names the scalar reference (written here from the meaning strings and vm/numbers/number.h, not
// taken from the VM; the noise functions have no independent definition, so they compare with
// vm::Noise, vm::PNoise and vm::CellNoise) and the domain its operands are drawn from. Then, over
// every number type the VM is instantiated with (AFFRAY_CONFORMANCE_TYPES, TEMPLATE_TEST_CASEs):
//  - double: the interpreter's result is the reference's, bit for bit;
//  - Dual<double>: its value is double's bit for bit, and its derivatives agree with central
//    finite differences of the reference wherever those are consistent and no kink is near;
//  - a bound type: over random regions (each operand c + a*eps_u + b*eps_v +- e, e an independent
//    error, evaluated exactly at dyadic points), the bound's range and its form at the point
//    (checked in binary128, so that a bound narrowed by an ulp shows) contain the scalar result,
//    rounding included; at edge values (+-0, +-inf, NaN, subnormals, huge) too, where a NaN or
//    infinite result is contained only by Unbounded; truth values are 1, 0 or [0, 1]; moderate
//    point operands give a (nearly) point bound;
//  - Dual<bound>: the same for the value and both derivatives, against Dual<double> at the point.
// And a verifier fuzz over every opcode value 0..255: what Verify accepts must be safe to run
// (checked here independently, then run under double and Interval, with ASan in CI), and
// well-formed programs must be accepted.
// Everything uses fixed seeds (one per opcode, so adding an opcode changes no other's samples).
// What the suite found in the number types, and was fixed, is kept in regression tests at the end
// of the file (tag [conformance-regression]); no check exempts anything.
#include <catch2/catch.hpp>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <sstream>
#include <string>
#include <type_traits>
#include <vector>

#include "tests/test_random.h"
#include "texture/texture.h"
#include "vm/interpreter.h"
#include "vm/numbers/noise.h"
#include "vm/verify.h"

// Every number type the VM is instantiated with (vm/interpreter_*.cpp): a new instantiation is one
// more name here.
#define AFFRAY_CONFORMANCE_TYPES                                                                   \
    double, vm::Interval, vm::Affine, vm::ReducedAffine, vm::Dual<double>, vm::Dual<vm::Interval>, \
        vm::Dual<vm::Affine>, vm::Dual<vm::ReducedAffine>

namespace {

using namespace affray;
using vm::Op;

// The Number API's free functions (hidden friends of the bound types, found by ADL) and double's.
using vm::IsUnbounded;
using vm::RangeOf;
using vm::ToString;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

// ---------------------------------------------------------------------------------------------
// The samples.

/// Where an operand's values come from: a centre in [lo, hi] (sometimes an integer or a
/// half-integer, an end, 0, or of log-uniform magnitude) and a radius up to maxRadius.
struct Domain {
    double lo = -8, hi = 8;
    double pInt = 0.15;    // chance of an integer centre (and half as often a half-integer)
    double pPoint = 0.2;   // chance of a point (radius 0)
    double maxRadius = 0;  // 0: (hi - lo) / 2
};

enum class Kind : uint8_t { None, Plain, DerivU, DerivV };

/// The scalar reference on the operand values in format order (and the noise channel).
using RefFn = double (*)(const double* x, uint8_t channel);
/// Whether a spot where the reference is not differentiable, or where finite differences see
/// something else than the dual's choice (a tie of min, a select on exactly 0), lies within
/// `reach` of the operand values: no finite differences there.
using KinkFn = bool (*)(const double* x, double reach);

struct Sample {
    Kind kind = Kind::None;
    int arity = 0;  // operands: the format's 'r' and 'k' letters
    RefFn ref = nullptr;
    Domain dom[8] = {};
    KinkFn kink = nullptr;
    /// Where a bound of point operands need not be (nearly) the point (the reach is unused).
    KinkFn loose = nullptr;
    bool truth = false;      // a truth value: 1 or 0, and every bound within [0, 1]
    bool unitRange = false;  // values in [0, 1]: bounds of finite inputs too (noise)
    int channels = 1;        // noise channels (flags) to draw from
    /// The least scale of a finite-difference step: 0 (steps relative to the operands, which may
    /// be near a singularity), 2^-12 for noise (no singularity; eight operands, one often tiny).
    double stepFloor = 0;

    constexpr Sample withKink(KinkFn k) const {
        Sample s = *this;
        s.kink = k;
        return s;
    }
    constexpr Sample withLoose(KinkFn k) const {
        Sample s = *this;
        s.loose = k;
        return s;
    }
    constexpr Sample asTruth() const {
        Sample s = *this;
        s.truth = true;
        return s;
    }
};

constexpr Sample Make(RefFn f, int arity, Domain d0, Domain d1 = {}, Domain d2 = {}) {
    Sample s;
    s.kind = Kind::Plain;
    s.arity = arity;
    s.ref = f;
    s.dom[0] = d0;
    s.dom[1] = d1;
    s.dom[2] = d2;
    return s;
}

constexpr Sample Deriv(Kind k) {
    Sample s;
    s.kind = k;
    s.arity = 1;
    // Without derivatives a double's Du and Dv are "unknown": NaN (vm/numbers/number.h).
    s.ref = [](const double*, uint8_t) { return kNaN; };
    s.dom[0] = Domain{.lo = -10, .hi = 10};
    return s;
}

/// Noise-family samples: coordinates within a few cells (regions up to maxRadius cells wide, so
/// both the cell-by-cell bound and the cell-independent fallback run), integer periods mostly.
constexpr Sample NoiseSample(RefFn f, int dims, int periods, double maxRadius) {
    Sample s;
    s.kind = Kind::Plain;
    s.arity = dims + periods;
    s.ref = f;
    for (int i = 0; i < dims; ++i)
        s.dom[i] = Domain{.lo = -20, .hi = 20, .pInt = 0.15, .pPoint = 0.15, .maxRadius = maxRadius};
    for (int i = dims; i < dims + periods; ++i)
        s.dom[i] = Domain{.lo = -1, .hi = 9, .pInt = 0.7, .pPoint = 0.8, .maxRadius = 3};
    s.unitRange = true;
    s.channels = 4;
    s.stepFloor = 0x1p-12;
    return s;
}

/// The texture slots every texture sample reads (the flags byte picks one): a 16x16 map of two
/// channels with random texels, a 1x1 map, and a 4x16 one (its slopes along s and t differ, so a
/// bound that takes one for the other shows), under every wrap mode and filter, with blur, a
/// channel the map lacks and a missing map (both the fill value).
const std::shared_ptr<const vm::TextureSlots>& TestTextures() {
    static const std::shared_ptr<const vm::TextureSlots> slots = [] {
        test::Rng rng(0x7E47);
        auto draw = [&](size_t count) {
            std::vector<float> texels(count);
            for (float& x : texels) x = static_cast<float>(rng.chance(0.1) ? rng.uniform(-40, 40) : rng.uniform(0, 1));
            return texels;
        };
        auto map = texture::TextureMap::FromPixels(16, 16, 2, draw(size_t{16} * 16 * 2));
        auto tiny = texture::TextureMap::FromPixels(1, 1, 1, {0.75f}, texture::Wrap::Clamp, texture::Wrap::Clamp);
        auto tall = texture::TextureMap::FromPixels(4, 16, 1, draw(size_t{4} * 16));
        using W = texture::Wrap;
        using F = texture::Filter;
        auto slot = [&](std::shared_ptr<const texture::TextureMap> m, int channel, W s, W t, F f, double blur,
                        double fill) {
            vm::TextureSlot x;
            x.path = m ? m->name() : "missing.exr";
            x.map = std::move(m);
            x.options = {
                .channel = channel, .swrap = s, .twrap = t, .filter = f, .sblur = blur, .tblur = blur, .fill = fill};
            x.fillIfMissing = !x.map;
            return x;
        };
        auto out = std::make_shared<vm::TextureSlots>();
        out->push_back(slot(map, 0, W::Periodic, W::Periodic, F::Box, 0, 0));
        out->push_back(slot(map, 1, W::Clamp, W::Black, F::Box, 0, 0.5));
        out->push_back(slot(map, 0, W::Black, W::Periodic, F::CatmullRom, 0, 0));
        out->push_back(slot(map, 1, W::Periodic, W::Clamp, F::Gaussian, 0.25, 0));
        out->push_back(slot(map, 0, W::Black, W::Black, F::Triangle, 0.25, 0));
        out->push_back(slot(map, 0, W::Clamp, W::Clamp, F::Box, 0.25, 0));
        out->push_back(slot(map, 2, W::Periodic, W::Periodic, F::Box, 0, 0.25));
        out->push_back(slot(nullptr, 0, W::Periodic, W::Periodic, F::Box, 0, -3));
        out->push_back(slot(tiny, 0, W::Clamp, W::Clamp, F::CatmullRom, 0, 0));
        out->push_back(slot(tall, 0, W::Periodic, W::Clamp, F::Box, 0, 0));
        return out;
    }();
    return slots;
}
constexpr int kTextureSlots = 10;

// The scalar references, on the operand values in format order: vm/numbers/number.h's semantics of
// double (std's functions, fmin/fmax with the first operand on a tie of -0 and +0, sign in {-1,
// 0, 1} keeping a signed zero, comparisons 1 or 0 and false with NaN but !=, truth as "not 0",
// NaN included; sqrt 0 below 0, pow of a negative base to a non-integer that of +0, division by
// either zero that by +0), written from the opcodes' meanings rather than taken from the VM. The noise
// functions have no second definition: vm's.
namespace ref {
double First(const double* x, uint8_t) { return x[0]; }
double Neg(const double* x, uint8_t) { return -x[0]; }
double Add(const double* x, uint8_t) { return x[0] + x[1]; }
double Sub(const double* x, uint8_t) { return x[0] - x[1]; }
double Mul(const double* x, uint8_t) { return x[0] * x[1]; }
double Div(const double* x, uint8_t) { return x[1] == 0 ? x[0] / 0.0 : x[0] / x[1]; }
double Sqr(const double* x, uint8_t) { return x[0] * x[0]; }
double Sqrt(const double* x, uint8_t) { return x[0] < 0 ? 0.0 : std::sqrt(x[0]); }
double Exp(const double* x, uint8_t) { return std::exp(x[0]); }
double Log(const double* x, uint8_t) { return std::log(x[0]); }
double Sin(const double* x, uint8_t) { return std::sin(x[0]); }
double Cos(const double* x, uint8_t) { return std::cos(x[0]); }
double Tan(const double* x, uint8_t) { return std::tan(x[0]); }
double Abs(const double* x, uint8_t) { return std::fabs(x[0]); }
double Sign(const double* x, uint8_t) { return x[0] > 0 ? 1.0 : x[0] < 0 ? -1.0 : x[0]; }
double Pow(const double* x, uint8_t) {
    const bool fraction = std::isfinite(x[1]) && std::trunc(x[1]) != x[1];
    return std::pow(x[0] < 0 && (fraction || std::isnan(x[1])) ? 0.0 : x[0], x[1]);
}
double Floor(const double* x, uint8_t) { return std::floor(x[0]); }
double Ceil(const double* x, uint8_t) { return std::ceil(x[0]); }
double Round(const double* x, uint8_t) { return std::round(x[0]); }  // halves away from 0
double Asin(const double* x, uint8_t) { return std::asin(x[0]); }
double Acos(const double* x, uint8_t) { return std::acos(x[0]); }
double Atan(const double* x, uint8_t) { return std::atan(x[0]); }
double Not(const double* x, uint8_t) { return x[0] != 0 ? 0.0 : 1.0; }
double Atan2(const double* x, uint8_t) { return std::atan2(x[0], x[1]); }  // (y, x)
double Min(const double* x, uint8_t) {
    if (std::isnan(x[0]) || std::isnan(x[1])) return std::fmin(x[0], x[1]);
    return x[1] < x[0] ? x[1] : x[0];
}
double Max(const double* x, uint8_t) {
    if (std::isnan(x[0]) || std::isnan(x[1])) return std::fmax(x[0], x[1]);
    return x[0] < x[1] ? x[1] : x[0];
}
double Lt(const double* x, uint8_t) { return x[0] < x[1] ? 1.0 : 0.0; }
double Le(const double* x, uint8_t) { return x[0] <= x[1] ? 1.0 : 0.0; }
double Eq(const double* x, uint8_t) { return x[0] == x[1] ? 1.0 : 0.0; }
double Ne(const double* x, uint8_t) { return x[0] != x[1] ? 1.0 : 0.0; }
double And(const double* x, uint8_t) { return x[0] != 0 && x[1] != 0 ? 1.0 : 0.0; }
double Or(const double* x, uint8_t) { return x[0] != 0 || x[1] != 0 ? 1.0 : 0.0; }
double Select(const double* x, uint8_t) { return x[0] != 0 ? x[1] : x[2]; }
template <int kDims>
double Noise(const double* x, uint8_t channel) {
    return vm::Noise<double>(x, kDims, channel);
}
template <int kDims>
double PNoise(const double* x, uint8_t channel) {  // coordinates, then periods
    return vm::PNoise<double>(x, x + kDims, kDims, channel);
}
template <int kDims>
double CellNoise(const double* x, uint8_t channel) {
    return vm::CellNoise<double>(x, kDims, channel);
}
// The texture lookups have no second definition either: texture::Sample's (tested against
// brute-force lookups in tests/texture/).
double Texture2(const double* x, uint8_t slot) {
    const vm::TextureSlot& t = (*TestTextures())[slot];
    return texture::Sample(t.map.get(), t.options, 0, x[0], x[1]);
}
double Texture8(const double* x, uint8_t slot) {
    const vm::TextureSlot& t = (*TestTextures())[slot];
    const double s[4] = {x[0], x[2], x[4], x[6]}, tt[4] = {x[1], x[3], x[5], x[7]};
    return texture::SampleQuad(t.map.get(), t.options, 0, s, tt);
}
}  // namespace ref

// The kinks (see KinkFn).
namespace kink {
bool NearInteger(double x, double reach) { return std::fabs(x - std::round(x)) <= reach; }
bool NearHalf(double x, double reach) { return std::fabs(x - std::floor(x) - 0.5) <= reach; }
bool AtZero(const double* x, double reach) { return std::fabs(x[0]) <= reach; }
bool EitherAtZero(const double* x, double reach) { return std::fabs(x[0]) <= reach || std::fabs(x[1]) <= reach; }
bool Tie(const double* x, double reach) { return std::fabs(x[0] - x[1]) <= 2 * reach; }
bool AtInteger(const double* x, double reach) { return NearInteger(x[0], reach); }
// pow: 0 as a base, and a negative base near an integer exponent, where it jumps between
// x^n and pow(0, y) as the exponent moves.
bool PowJump(const double* x, double reach) { return AtZero(x, reach) || (x[0] < 0 && NearInteger(x[1], reach)); }
bool AtHalf(const double* x, double reach) { return NearHalf(x[0], reach); }
// tan's poles (k + 1/2) pi, where |cos| is about the distance to the pole.
bool AtPole(const double* x, double reach) { return std::fabs(std::cos(x[0])) <= 2 * reach; }
// atan2(y, x): the branch cut y = 0, x < 0, and the origin.
bool Atan2Cut(const double* x, double reach) { return std::fabs(x[0]) <= reach && x[1] <= reach; }
// A point bound cannot tell -0 from +0, which atan2 distinguishes on its cut (Sample::loose).
bool Atan2SignedZero(const double* x, double) { return x[0] == 0 && x[1] <= 0; }
// pnoise is piecewise constant in its periods (rounded): kinks where one is a half-integer.
template <int kDims>
bool PeriodHalf(const double* x, double reach) {
    for (int i = kDims; i < 2 * kDims; ++i)
        if (NearHalf(x[i], reach)) return true;
    return false;
}
// cellnoise is piecewise constant: kinks where a coordinate is an integer.
template <int kDims>
bool CellFace(const double* x, double reach) {
    for (int i = 0; i < kDims; ++i)
        if (NearInteger(x[i], reach)) return true;
    return false;
}
// A lookup in the test maps (16 or 4 texels a side) is piecewise smooth between texel centres and
// edges (and the blurred ones' taps, a quarter of the map wide in four steps, land on them too):
// kinks where s or t is a multiple of 1/32.
bool TexelGrid(const double* x, double reach) {
    for (int i = 0; i < 2; ++i)
        if (NearInteger(32 * x[i], 32 * reach)) return true;
    return false;
}
// The four-corner lookup averages lookups at taps that move with the corners (convex
// combinations, so no farther than `reach`): a kink where one of them is on the grid above.
bool QuadTexelGrid(const double* x, double reach) {
    for (int j = 0; j < texture::kQuadTaps; ++j)
        for (int i = 0; i < texture::kQuadTaps; ++i) {
            const double u = (i + 0.5) / texture::kQuadTaps, v = (j + 0.5) / texture::kQuadTaps;
            double tap[2];
            for (int k = 0; k < 2; ++k)
                tap[k] = (1 - v) * ((1 - u) * x[k] + u * x[2 + k]) + v * ((1 - u) * x[4 + k] + u * x[6 + k]);
            if (TexelGrid(tap, reach)) return true;
        }
    return false;
}
}  // namespace kink

/// Texture samples: coordinates within a few map widths (wrap modes matter), regions up to half
/// the map wide; the flags byte draws a slot of TestTextures().
constexpr Sample TextureSample(RefFn f, int arity) {
    Sample s;
    s.kind = Kind::Plain;
    s.arity = arity;
    s.ref = f;
    for (int i = 0; i < arity; ++i) s.dom[i] = Domain{.lo = -1.25, .hi = 2.25, .pInt = 0.1, .maxRadius = 0.5};
    s.channels = kTextureSlots;
    // Steps of 2^-18 or more: a lookup rounds at the magnitude of its texels (up to 40 here), not
    // of its value, so smaller steps drown the differences in rounding; no singularity to avoid.
    s.stepFloor = 1;
    return s;
}

/// The sample of every opcode; Ext (the pseudo-op) has none. No default: -Wswitch names a
/// missing opcode, and the static_assert below catches it without warnings too.
constexpr Sample SampleFor(Op op) {
    using D = Domain;
    constexpr D wide{.lo = -1e6, .hi = 1e6};
    constexpr D arith{.lo = -1e3, .hi = 1e3};
    constexpr D divisor{.lo = -10, .hi = 10, .pInt = 0.3};
    constexpr D small{.lo = -10, .hi = 10, .pInt = 0.3};
    constexpr D steps{.lo = -20, .hi = 20, .pInt = 0.3};
    constexpr D ties{.lo = -4, .hi = 4, .pInt = 0.5, .pPoint = 0.4};
    constexpr D truths{.lo = -1, .hi = 2, .pInt = 0.6, .pPoint = 0.4};
    constexpr D base{.lo = -4, .hi = 4, .pInt = 0.2};
    constexpr D exponent{.lo = -5, .hi = 5, .pInt = 0.5, .pPoint = 0.5};
    constexpr D unit{.lo = -1.1, .hi = 1.1, .pInt = 0.2};
    constexpr D positive{.lo = -1, .hi = 1e4};                        // mostly > 0, sometimes straddling 0
    constexpr D exponential{.lo = -760, .hi = 720, .maxRadius = 20};  // underflow and overflow
    constexpr D angle{.lo = -1e9, .hi = 1e9, .maxRadius = 10};        // past 1e8 too
    switch (op) {
        case Op::LoadK:
        case Op::Move: return Make(ref::First, 1, wide);
        case Op::Neg: return Make(ref::Neg, 1, wide);
        case Op::AddRR:
        case Op::AddRK: return Make(ref::Add, 2, arith, arith);
        case Op::SubRR:
        case Op::SubRK:
        case Op::SubKR: return Make(ref::Sub, 2, arith, arith);
        case Op::MulRR:
        case Op::MulRK: return Make(ref::Mul, 2, arith, arith);
        case Op::DivRR:
        case Op::DivRK:
        case Op::DivKR: return Make(ref::Div, 2, arith, divisor);
        case Op::Sqr: return Make(ref::Sqr, 1, arith);
        case Op::Sqrt: return Make(ref::Sqrt, 1, positive);
        case Op::Exp: return Make(ref::Exp, 1, exponential);
        case Op::Log: return Make(ref::Log, 1, positive);
        case Op::Sin: return Make(ref::Sin, 1, angle);
        case Op::Cos: return Make(ref::Cos, 1, angle);
        case Op::Abs: return Make(ref::Abs, 1, small).withKink(kink::AtZero);
        case Op::Sign: return Make(ref::Sign, 1, small).withKink(kink::AtZero);
        case Op::PowRR:
        case Op::PowRK: return Make(ref::Pow, 2, base, exponent).withKink(kink::PowJump);
        case Op::DerivU: return Deriv(Kind::DerivU);
        case Op::DerivV: return Deriv(Kind::DerivV);
        case Op::Floor: return Make(ref::Floor, 1, steps).withKink(kink::AtInteger);
        case Op::Ceil: return Make(ref::Ceil, 1, steps).withKink(kink::AtInteger);
        case Op::Round: return Make(ref::Round, 1, steps).withKink(kink::AtHalf);
        case Op::Asin: return Make(ref::Asin, 1, unit);
        case Op::Acos: return Make(ref::Acos, 1, unit);
        case Op::Atan: return Make(ref::Atan, 1, D{.lo = -1e4, .hi = 1e4});
        case Op::Not: return Make(ref::Not, 1, truths).asTruth().withKink(kink::AtZero);
        case Op::Atan2RR:
            return Make(ref::Atan2, 2, base, base).withKink(kink::Atan2Cut).withLoose(kink::Atan2SignedZero);
        case Op::MinRR:
        case Op::MinRK: return Make(ref::Min, 2, small, small).withKink(kink::Tie);
        case Op::MaxRR:
        case Op::MaxRK: return Make(ref::Max, 2, small, small).withKink(kink::Tie);
        case Op::LtRR:
        case Op::LtRK:
        case Op::LtKR: return Make(ref::Lt, 2, ties, ties).asTruth().withKink(kink::Tie);
        case Op::LeRR:
        case Op::LeRK:
        case Op::LeKR: return Make(ref::Le, 2, ties, ties).asTruth().withKink(kink::Tie);
        case Op::EqRR:
        case Op::EqRK: return Make(ref::Eq, 2, ties, ties).asTruth().withKink(kink::Tie);
        case Op::NeRR:
        case Op::NeRK: return Make(ref::Ne, 2, ties, ties).asTruth().withKink(kink::Tie);
        case Op::AndRR: return Make(ref::And, 2, truths, truths).asTruth().withKink(kink::EitherAtZero);
        case Op::OrRR: return Make(ref::Or, 2, truths, truths).asTruth().withKink(kink::EitherAtZero);
        case Op::Select: return Make(ref::Select, 3, truths, small, small).withKink(kink::AtZero);
        case Op::Ext:
        case Op::Light:
        case Op::Trace: return Sample();
        // (Radii up to 10, 5, 4 and 4 cells: some regions touch more than kNoiseCellCap cells and
        // take the cell-independent bound.)
        case Op::Noise1: return NoiseSample(ref::Noise<1>, 1, 0, 10);
        case Op::Noise2: return NoiseSample(ref::Noise<2>, 2, 0, 5);
        case Op::Noise3: return NoiseSample(ref::Noise<3>, 3, 0, 4);
        case Op::Noise4: return NoiseSample(ref::Noise<4>, 4, 0, 4);
        case Op::PNoise1: return NoiseSample(ref::PNoise<1>, 1, 1, 10).withKink(kink::PeriodHalf<1>);
        case Op::PNoise2: return NoiseSample(ref::PNoise<2>, 2, 2, 5).withKink(kink::PeriodHalf<2>);
        case Op::PNoise3: return NoiseSample(ref::PNoise<3>, 3, 3, 4).withKink(kink::PeriodHalf<3>);
        case Op::PNoise4: return NoiseSample(ref::PNoise<4>, 4, 4, 4).withKink(kink::PeriodHalf<4>);
        case Op::CellNoise1: return NoiseSample(ref::CellNoise<1>, 1, 0, 3).withKink(kink::CellFace<1>);
        case Op::CellNoise2: return NoiseSample(ref::CellNoise<2>, 2, 0, 3).withKink(kink::CellFace<2>);
        case Op::CellNoise3: return NoiseSample(ref::CellNoise<3>, 3, 0, 3).withKink(kink::CellFace<3>);
        case Op::CellNoise4: return NoiseSample(ref::CellNoise<4>, 4, 0, 3).withKink(kink::CellFace<4>);
        case Op::Tan: return Make(ref::Tan, 1, D{.lo = -1e4, .hi = 1e4, .maxRadius = 2}).withKink(kink::AtPole);
        case Op::Texture2: return TextureSample(ref::Texture2, 2).withKink(kink::TexelGrid);
        case Op::Texture8: return TextureSample(ref::Texture8, 8).withKink(kink::QuadTexelGrid);
    }
    return Sample();
}

/// Operands an instruction of this format reads: its 'r' and 'k' letters.
constexpr int OperandCount(const char* format) {
    int n = 0;
    for (int i = 0; format[i]; ++i) n += format[i] == 'r' || format[i] == 'k';
    return n;
}

constexpr bool EveryOpcodeHasASample() {
    for (int i = 0; i < vm::kOpCount; ++i) {
        const Op op = static_cast<Op>(i);
        if (op == Op::Ext || op == Op::Light || op == Op::Trace) continue;
        const Sample s = SampleFor(op);
        // (Not s.ref == nullptr: GCC with sanitizers cannot fold the address of a template
        // instance, ref::Noise<1>, in a constant expression. Every maker sets ref.)
        if (s.kind == Kind::None || s.arity != OperandCount(vm::kOpInfo[i].format) || vm::kOpInfo[i].format[0] != 'w')
            return false;
    }
    return true;
}
static_assert(
    EveryOpcodeHasASample(),
    "every opcode but Ext, Light and Trace needs a sample in SampleFor, with as many operands as its format reads");

// ---------------------------------------------------------------------------------------------
// Operands: forms over the region's symbols, exact at the points drawn.

/// c + a*eps_u + b*eps_v +- e: e >= 0 is an independent error (a fresh symbol of its own in
/// Affine, ReducedAffine's error term, part of the range in Interval), whose value at a point is
/// drawn like a symbol's.
struct Form {
    double c = 0, a = 0, b = 0, e = 0;
    bool point() const { return a == 0 && b == 0 && e == 0; }
};

double Quantize(double x, double q) { return std::round(x / q) * q; }

/// A form of domain d, with an error term with chance pError. Centre and coefficients are
/// multiples of 2^(E - 40), E the exponent of the largest, so the value at any eps multiple of
/// 2^-10 is exact (53 bits).
Form DrawForm(test::Rng& rng, const Domain& d, double pError) {
    const double lo = d.lo, hi = d.hi;
    const double ilo = std::ceil(lo), ihi = std::floor(hi);
    const double pick = rng.uniform(0, 1);
    double c;
    if (pick < d.pInt) {
        c = static_cast<double>(rng.integer<int64_t>(static_cast<int64_t>(ilo), static_cast<int64_t>(ihi)));
    } else if (pick < 1.5 * d.pInt) {
        c = static_cast<double>(rng.integer<int64_t>(static_cast<int64_t>(ilo), static_cast<int64_t>(ihi) - 1)) + 0.5;
    } else if (pick < 1.5 * d.pInt + 0.05) {
        c = rng.chance(0.5) ? lo : hi;
    } else if (pick < 1.5 * d.pInt + 0.08 && lo <= 0 && hi >= 0) {
        c = 0;
    } else if (pick < 0.6) {
        // Log-uniform magnitude, for the small values a uniform draw never gives.
        const double top = std::log10(std::max(std::fabs(lo), std::fabs(hi)));
        const double mag = std::pow(10.0, rng.uniform(-8, top));
        bool negative = rng.chance(0.5);
        if (negative && -mag < lo) negative = false;
        if (!negative && mag > hi) negative = true;
        c = std::clamp(negative ? -mag : mag, lo, hi);
    } else {
        c = rng.uniform(lo, hi);
    }
    double r = 0;
    if (!rng.chance(d.pPoint))
        r = (d.maxRadius > 0 ? d.maxRadius : (hi - lo) / 2) * std::pow(10.0, -rng.uniform(0, 11));
    double a = r, b = 0;
    const double split = rng.uniform(0, 1);
    if (split < 0.2) {
        a = 0, b = r;  // along eps_v only
    } else if (split < 0.6) {
        const double t = rng.uniform(0, 1);
        a = r * t, b = r * (1 - t);
    }
    if (rng.chance(0.5)) a = -a;
    if (rng.chance(0.5)) b = -b;
    // An error term, often on a point (a region of a value computed before, with its rounding).
    double e = 0;
    if (rng.chance(pError)) e = (r > 0 ? r : std::max(std::fabs(c), 1.0)) * std::pow(10.0, -rng.uniform(0, 6));
    const double s = std::max({std::fabs(c), std::fabs(a), std::fabs(b), e});
    if (s == 0) return {};
    const double q = std::ldexp(1.0, std::max(std::ilogb(s) - 40, -1060));
    return {Quantize(c, q), Quantize(a, q), Quantize(b, q), Quantize(e, q)};
}

/// A value to fix a symbol at: -1, 0, 1 or a multiple of 2^-10 in [-1, 1].
double DrawEps(test::Rng& rng) {
    const int k = rng.integer(0, 4);
    return k < 3 ? k - 1.0 : std::ldexp(rng.integer(-1024, 1024), -10);
}

/// The form's value at (eu, ev) with its error term at ee, if it is an exact double.
bool Eval(const Form& f, double eu, double ev, double ee, double* out) {
    if (f.point()) {
        *out = f.c;
        return true;
    }
    const double p = f.a * eu, q = f.b * ev, w = f.e * ee;
    // (A product below 2^-1000 may have lost bits that fma's residual, itself rounded, hides.)
    auto exact = [](double c, double e, double r) {
        return std::fma(c, e, -r) == 0 && (c == 0 || e == 0 || std::fabs(r) >= 0x1p-1000);
    };
    if (!exact(f.a, eu, p) || !exact(f.b, ev, q) || !exact(f.e, ee, w)) return false;
    const double pq = p + q;
    if (vm::TwoSumError(p, q, pq) != 0) return false;
    const double s = pq + w;
    if (vm::TwoSumError(pq, w, s) != 0) return false;
    const double x = f.c + s;
    if (!std::isfinite(x) || vm::TwoSumError(f.c, s, x) != 0) return false;
    *out = x;
    return true;
}

std::string Describe(const Form& f) {
    std::ostringstream o;
    o.precision(17);
    o << f.c;
    if (f.a != 0) o << (f.a < 0 ? " - " : " + ") << std::fabs(f.a) << "*eu";
    if (f.b != 0) o << (f.b < 0 ? " - " : " + ") << std::fabs(f.b) << "*ev";
    if (f.e != 0) o << " +- " << f.e;
    return o.str();
}

std::string Num(double x) {
    std::ostringstream o;
    o.precision(17);
    o << x;
    return o.str();
}

// ---------------------------------------------------------------------------------------------
// One case: a program of one instruction (after an optional prelude) and its operands.

/// An input register: its value and, for the dual types, its derivatives (forms too).
struct Input {
    Form v, du, dv;
};

struct Operand {
    bool constant;
    int index;  // into Case::inputs or Case::constants
};

// Registers: inputs in 0..8 (globals P, N and Ng), the result in 9, the prelude's input (global u)
// in 10 and its scratch in 11.
constexpr int kMaxInputs = 9;
constexpr uint16_t kResult = 9, kStraddle = 10, kScratch = 11;

struct Case {
    Op op = Op::LoadK;
    uint8_t channel = 0;
    std::vector<Input> inputs;
    std::vector<double> constants;
    std::vector<Operand> operands;  // in format order
    // Exhaust the interpreter's splits first (kMaxSplits floors of a value straddling an integer),
    // so that floor, ceil and round run their unsplit bounded versions on a straddling range too.
    bool prelude = false;
    vm::Program program;
};

void BuildProgram(Case& c) {
    vm::Program& p = c.program;
    p = vm::Program();
    p.registerCount = 12;
    p.globalRegisters[static_cast<int>(vm::Global::P)] = 0;
    p.globalRegisters[static_cast<int>(vm::Global::N)] = 3;
    p.globalRegisters[static_cast<int>(vm::Global::Ng)] = 6;
    p.globalRegisters[static_cast<int>(vm::Global::u)] = kStraddle;
    if (c.prelude)
        for (int i = 0; i < vm::Interpreter<double>::kMaxSplits; ++i)
            p.code.push_back(vm::Instr{Op::Floor, 0, kScratch, kStraddle, 0});
    const char* format = vm::Info(c.op).format;
    std::vector<vm::Instr> words(vm::WordCount(format), vm::Instr{Op::Ext, 0, 0, 0, 0});
    words[0].op = c.op;
    words[0].flags = c.channel;
    for (int i = 0, k = 0; format[i]; ++i) {
        uint16_t value = 0;
        if (format[i] == 'w') value = kResult;
        if (format[i] == 'r' || format[i] == 'k') value = static_cast<uint16_t>(c.operands[k++].index);
        vm::Instr& w = words[i / 3];
        (i % 3 == 0 ? w.a : i % 3 == 1 ? w.b : w.c) = value;
    }
    p.code.insert(p.code.end(), words.begin(), words.end());
    p.constants = c.constants;
    if (vm::OperationOf(c.op) == vm::Operation::Texture) p.textures = TestTextures();
    vm::ProgramOutput out;
    out.name = "x";
    out.size = 1;
    out.registers = {kResult, vm::kNoRegister, vm::kNoRegister};
    p.outputs.push_back(out);
}

/// Operand forms from the sample's domains; a register operand sometimes reads the register of
/// an earlier one (x - x, x * x, min(x, x): correlations the affine types must see).
Case DrawCase(Op op, const Sample& s, test::Rng& rng) {
    Case c;
    c.op = op;
    c.channel = static_cast<uint8_t>(rng.integer(0, s.channels - 1));
    const char* format = vm::Info(op).format;
    for (int i = 1, k = 0; format[i]; ++i) {
        if (format[i] == 'k') {
            c.operands.push_back({true, static_cast<int>(c.constants.size())});
            c.constants.push_back(DrawForm(rng, s.dom[k++], 0).c);
        } else if (format[i] == 'r') {
            std::vector<int> earlier;
            for (const Operand& o : c.operands)
                if (!o.constant) earlier.push_back(o.index);
            if (!earlier.empty() && rng.chance(0.12)) {
                c.operands.push_back({false, rng.pick(earlier)});
            } else {
                Input in;
                in.v = DrawForm(rng, s.dom[k], 0.25);
                // Derivatives: often exactly 0 (ChainScale's case), else small forms or constants.
                const Domain seed{.lo = -3, .hi = 3, .pInt = 0.3, .pPoint = 0.7, .maxRadius = 1};
                in.du = rng.chance(0.2) ? Form{} : DrawForm(rng, seed, 0.1);
                in.dv = rng.chance(0.2) ? Form{} : DrawForm(rng, seed, 0.1);
                c.operands.push_back({false, static_cast<int>(c.inputs.size())});
                c.inputs.push_back(in);
            }
            ++k;
        }
    }
    return c;
}

/// A point of a region: its symbols' values, and a seed for its error terms' (0: all 0).
struct Point {
    double eu = 0, ev = 0;
    uint64_t errors = 0;
};

/// The operands' values and derivative seeds at a point, and the inputs' (false if inexact).
struct PointValues {
    double x[8] = {}, su[8] = {}, sv[8] = {};
    double in[kMaxInputs] = {}, inDu[kMaxInputs] = {}, inDv[kMaxInputs] = {};
};

bool ValuesAt(const Case& c, const Point& pt, PointValues* p) {
    // The error terms' values, as DrawEps draws them, from SplitMix64 (seeding a Mersenne twister
    // per point would cost more than the checks).
    uint64_t state = pt.errors;
    auto error = [&] {
        if (!pt.errors) return 0.0;
        uint64_t z = (state += 0x9e3779b97f4a7c15ULL);
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
        z ^= z >> 31;
        const int k = static_cast<int>(z % 5);
        return k < 3 ? k - 1.0 : std::ldexp(static_cast<double>(static_cast<int>((z >> 8) % 2049) - 1024), -10);
    };
    for (size_t i = 0; i < c.inputs.size(); ++i) {
        const double ev = error(), edu = error(), edv = error();
        if (!Eval(c.inputs[i].v, pt.eu, pt.ev, ev, &p->in[i]) ||
            !Eval(c.inputs[i].du, pt.eu, pt.ev, edu, &p->inDu[i]) ||
            !Eval(c.inputs[i].dv, pt.eu, pt.ev, edv, &p->inDv[i]))
            return false;
    }
    for (size_t k = 0; k < c.operands.size(); ++k) {
        const Operand& o = c.operands[k];
        p->x[k] = o.constant ? c.constants[o.index] : p->in[o.index];
        p->su[k] = o.constant ? 0.0 : p->inDu[o.index];
        p->sv[k] = o.constant ? 0.0 : p->inDv[o.index];
    }
    return true;
}

std::string Describe(const Case& c) {
    std::ostringstream o;
    o << vm::Info(c.op).name;
    if (c.channel) o << " (channel " << int(c.channel) << ")";
    if (c.prelude) o << " (after " << vm::Interpreter<double>::kMaxSplits << " splits)";
    o << " of";
    for (const Operand& op : c.operands) {
        if (op.constant) {
            o << " K" << op.index << "=" << Num(c.constants[op.index]);
        } else {
            const Input& in = c.inputs[op.index];
            o << " R" << op.index << "=[" << Describe(in.v) << "; du " << Describe(in.du) << "; dv " << Describe(in.dv)
              << "]";
        }
        o << ",";
    }
    return o.str();
}

// ---------------------------------------------------------------------------------------------
// Number types.

template <class T>
struct TypeInfo {
    static constexpr bool kDual = false;
    using Base = T;
};
template <class B>
struct TypeInfo<vm::Dual<B>> {
    static constexpr bool kDual = true;
    using Base = B;
};
/// double and Dual<double> hold one value: they are run at points, the others over regions.
template <class T>
constexpr bool kPointType = std::is_same_v<typename TypeInfo<T>::Base, double>;

template <class B>
B ToBound(const Form& f);
template <>
vm::Interval ToBound<vm::Interval>(const Form& f) {
    if (f.point()) return vm::Interval(f.c);
    const double r = vm::AddUp(vm::AddUp(std::fabs(f.a), std::fabs(f.b)), f.e);
    return vm::Interval(vm::SubDown(f.c, r), vm::AddUp(f.c, r));
}
template <>
vm::Affine ToBound<vm::Affine>(const Form& f) {
    if (f.point()) return vm::Affine(f.c);
    vm::Affine x = vm::Affine::FromSymbol(f.c, f.a, vm::Affine::kSymbolU);
    if (f.b != 0) x = x + vm::Affine::FromSymbol(0.0, f.b, vm::Affine::kSymbolV);
    if (f.e != 0) x = x + vm::Affine::FromSymbol(0.0, f.e, vm::Affine::NewSymbol());
    return x;
}
template <>
vm::ReducedAffine ToBound<vm::ReducedAffine>(const Form& f) {
    if (f.point()) return vm::ReducedAffine(f.c);
    vm::ReducedAffine x = vm::ReducedAffine::FromSymbol(f.c, f.a, vm::ReducedAffine::kSymbolU);
    if (f.b != 0) x = x + vm::ReducedAffine::FromSymbol(0.0, f.b, vm::ReducedAffine::kSymbolV);
    if (f.e != 0) x = x + vm::ReducedAffine::FromInterval(vm::Interval(-f.e, f.e));
    return x;
}

/// The bound at (eu, ev): the type's own evaluation there (the affine forms' symbols fixed),
/// which must hold the scalar value as well as the range.
vm::Interval At(const vm::Interval& x, double, double) { return x; }
vm::Interval At(const vm::Affine& x, double eu, double ev) { return x.evaluateAt(eu, ev); }
vm::Interval At(const vm::ReducedAffine& x, double eu, double ev) { return x.evaluateAt(eu, ev); }

// Whether the form holds x at (eu, ev): |centre + sum coef*eps - x| <= error + sum |free coef|
// in real numbers (the contract of vm/numbers/affine.h and vm/numbers/reduced_affine.h), evaluated in binary128:
// products of doubles are exact there, and a relative margin of 2^-100 covers the sums. Not with
// the type's evaluateAt, whose outward rounding (an ulp per term) would hide a bound narrowed by
// an ulp.
using Quad = __float128;
Quad QAbs(Quad x) { return x < 0 ? -x : x; }
bool FormHolds(Quad value, Quad radius, Quad magnitude) { return QAbs(value) <= radius + magnitude * Quad(0x1p-100); }
bool HoldsAt(const vm::Interval& b, double, double, double x) { return b.contains(x); }
bool HoldsAt(const vm::Affine& b, double eu, double ev, double x) {
    if (b.isUnbounded()) return true;
    Quad value = Quad(b.center()) - Quad(x), radius = b.error();
    Quad magnitude = QAbs(b.center()) + QAbs(x) + Quad(b.error());
    for (int i = 0; i < b.termCount(); ++i) {
        const vm::Affine::SymbolId id = b.termSymbol(i);
        const double coef = b.termCoef(i);
        magnitude += QAbs(coef);
        if (id == vm::Affine::kSymbolU)
            value += Quad(coef) * Quad(eu);
        else if (id == vm::Affine::kSymbolV)
            value += Quad(coef) * Quad(ev);
        else
            radius += QAbs(coef);
    }
    return FormHolds(value, radius, magnitude);
}
bool HoldsAt(const vm::ReducedAffine& b, double eu, double ev, double x) {
    if (b.isUnbounded()) return true;
    const Quad value =
        Quad(b.center()) + Quad(b.coefficientU()) * Quad(eu) + Quad(b.coefficientV()) * Quad(ev) - Quad(x);
    const Quad magnitude =
        QAbs(b.center()) + QAbs(b.coefficientU()) + QAbs(b.coefficientV()) + QAbs(x) + Quad(b.error());
    return FormHolds(value, b.error(), magnitude);
}

/// The bound's range and its form at (eu, ev) both hold the scalar value x.
template <class B>
bool Contains(const B& bound, double eu, double ev, double x) {
    return RangeOf(bound).contains(x) && HoldsAt(bound, eu, ev, x);
}

template <class T>
T BoundInput(const Input& in) {
    if constexpr (TypeInfo<T>::kDual) {
        using B = typename TypeInfo<T>::Base;
        return T(ToBound<B>(in.v), ToBound<B>(in.du), ToBound<B>(in.dv));
    } else {
        return ToBound<T>(in.v);
    }
}

template <class T>
T PointInput(double v, double du, double dv) {
    if constexpr (TypeInfo<T>::kDual)
        return T(v, du, dv);
    else
        return T(v);
}

template <class T>
void SetInputs(vm::Interpreter<T>& interp, const T* in, int n, const T& straddle) {
    T r[kMaxInputs];
    for (int i = 0; i < kMaxInputs; ++i) r[i] = i < n ? in[i] : T(0.0);
    interp.SetGlobal(vm::Global::P, vm::Vec3<T>(r[0], r[1], r[2]));
    interp.SetGlobal(vm::Global::N, vm::Vec3<T>(r[3], r[4], r[5]));
    interp.SetGlobal(vm::Global::Ng, vm::Vec3<T>(r[6], r[7], r[8]));
    interp.SetGlobal(vm::Global::u, straddle);
}

/// Runs a point type at one point of the case.
template <class T>
T RunAt(vm::Interpreter<T>& interp, const Case& c, const PointValues& p) {
    T in[kMaxInputs];
    for (size_t i = 0; i < c.inputs.size(); ++i) in[i] = PointInput<T>(p.in[i], p.inDu[i], p.inDv[i]);
    SetInputs(interp, in, static_cast<int>(c.inputs.size()), T(1.0));
    interp.Run();
    return interp.Register(kResult);
}

bool Same(double a, double b) {
    return std::bit_cast<uint64_t>(a) == std::bit_cast<uint64_t>(b) || (std::isnan(a) && std::isnan(b));
}

// ---------------------------------------------------------------------------------------------
// Checks.

struct Report {
    /// At edge values a dual's derivative may be NaN ("unknown": inf * 0, an overflow inside the
    /// chain rule) where the true one is a number; elsewhere it must be the number.
    bool allowUnknown = false;
    int cases = 0, points = 0, inexact = 0, failures = 0;
    int fdChecked = 0, fdSkipped = 0;
    std::ostringstream first;
    void fail(const std::string& s) {
        if (failures++ < 6) first << s << "\n";
    }
};

/// `x` to 8 significant bits: seeds that small make every step t*seed of a power of two t exact.
double Round8(double x) {
    if (x == 0 || !std::isfinite(x)) return x;
    const int e = std::ilogb(x);
    return std::ldexp(std::round(std::ldexp(x, 7 - e)), e - 7);
}

/// Compares the dual's derivative along the seeds with central differences of the reference:
/// Richardson extrapolations from steps h, h/2 and h/4 (h a power of two, 2^-18 of the smallest
/// moving operand's magnitude clamped to [stepFloor, 1], or max(2^-12, stepFloor) if it is 0; a point where a perturbed operand is not
/// exact is skipped) must agree with each other (else the function is not smooth enough there:
/// skipped) and with the dual.
void CheckDerivative(const Sample& s, const Case& c, const PointValues& p, const double* seed, double dual,
                     const char* which, Report& rep) {
    const int n = s.arity;
    double h = kInf, smax = 0;
    for (int k = 0; k < n; ++k) {
        if (!std::isfinite(seed[k]) || !std::isfinite(p.x[k])) {
            ++rep.fdSkipped;
            return;
        }
        if (seed[k] == 0) continue;
        smax = std::max(smax, std::fabs(seed[k]));
        const double scale =
            p.x[k] == 0 ? std::max(0x1p-12, s.stepFloor) : std::clamp(std::fabs(p.x[k]), s.stepFloor, 1.0);
        h = std::min(h, scale / std::fabs(seed[k]));
    }
    const double f0 = s.ref(p.x, c.channel);
    if (!std::isfinite(f0)) {
        ++rep.fdSkipped;
        return;
    }
    if (smax == 0) {
        // No operand moves: the derivative is exactly 0 (or unknown, NaN, at a singular point such
        // as atan2's origin, where the chain rule's factor is 0/0).
        ++rep.fdChecked;
        if (dual != 0 && !((rep.allowUnknown || (s.kink && s.kink(p.x, 0))) && std::isnan(dual)))
            rep.fail(Describe(c) + " " + which + " = " + Num(dual) + " with zero seeds");
        return;
    }
    if (!(h >= 0x1p-900)) {
        // Steps that small underflow: finite differences see nothing.
        ++rep.fdSkipped;
        return;
    }
    h = std::ldexp(1.0, std::ilogb(h) - 18);
    if (s.kink && s.kink(p.x, 2 * h * smax)) {
        ++rep.fdSkipped;
        return;
    }
    double fmax = std::fabs(f0);
    bool exact = true;
    auto g = [&](double t) {
        double y[8];
        for (int k = 0; k < n; ++k) {
            y[k] = p.x[k] + t * seed[k];
            // (Exact, and not lost to underflow.)
            exact &= y[k] - p.x[k] == t * seed[k] && (seed[k] == 0 || std::fabs(t * seed[k]) >= 0x1p-1000);
        }
        const double v = s.ref(y, c.channel);
        fmax = std::max(fmax, std::fabs(v));
        return v;
    };
    const double d1 = (g(h) - g(-h)) / (2 * h), d2 = (g(h / 2) - g(-h / 2)) / h, d4 = (g(h / 4) - g(-h / 4)) / (h / 2);
    const double r1 = (4 * d2 - d1) / 3, r2 = (4 * d4 - d2) / 3;
    // Rounding noise of the differences (the reference is within a few ulps, or subnormal steps).
    const double noise = 64 * (0x1p-52 * fmax + 0x1p-1074) / h;
    if (!exact || !std::isfinite(r1) || !std::isfinite(r2) ||
        std::fabs(r1 - r2) > 1e-6 * std::max(std::fabs(r1), std::fabs(r2)) + noise) {
        ++rep.fdSkipped;
        return;
    }
    if (rep.allowUnknown && std::isnan(dual)) {
        ++rep.fdSkipped;
        return;
    }
    ++rep.fdChecked;
    // (An infinite dual fails: the tolerance, relative to the larger of the two, would be infinite
    // too. Finite differences that agree mean a finite derivative.)
    const double tol = 1e-6 * std::max(std::fabs(r2), std::fabs(dual)) + noise;
    if (!(std::isfinite(dual) && std::fabs(dual - r2) <= tol)) {
        std::string at;
        for (int k = 0; k < n; ++k) at += (k ? ", " : "") + Num(p.x[k]);
        rep.fail(Describe(c) + " at (" + at + "): dual " + which + " = " + Num(dual) + ", finite differences " +
                 Num(r2));
    }
}

/// The point's values with every derivative seed rounded to 8 bits, and those below 2^-20 of the
/// largest of their direction made 0 (their steps would be lost in rounding; see CheckDerivative).
PointValues RoundSeeds(const Case& c, PointValues p) {
    double maxU = 0, maxV = 0;
    for (size_t i = 0; i < c.inputs.size(); ++i) {
        maxU = std::max(maxU, std::fabs(p.inDu[i]));
        maxV = std::max(maxV, std::fabs(p.inDv[i]));
    }
    for (size_t i = 0; i < c.inputs.size(); ++i) {
        p.inDu[i] = std::fabs(p.inDu[i]) < 0x1p-20 * maxU ? 0.0 : Round8(p.inDu[i]);
        p.inDv[i] = std::fabs(p.inDv[i]) < 0x1p-20 * maxV ? 0.0 : Round8(p.inDv[i]);
    }
    for (size_t k = 0; k < c.operands.size(); ++k) {
        const Operand& o = c.operands[k];
        p.su[k] = o.constant ? 0.0 : p.inDu[o.index];
        p.sv[k] = o.constant ? 0.0 : p.inDv[o.index];
    }
    return p;
}

/// The checks at one point of a case, for a point type: T = double against the reference bit for
/// bit, T = Dual<double> against double and finite differences.
template <class T>
void CheckPoint(const Sample& s, const Case& c, const PointValues& p, vm::Interpreter<double>& scalar,
                [[maybe_unused]] vm::Interpreter<T>& interp, Report& rep) {
    const double r = RunAt(scalar, c, p);
    if constexpr (std::is_same_v<T, double>) {
        const double want = s.ref(p.x, c.channel);
        if (!Same(r, want))
            rep.fail(Describe(c) + " at " + Num(p.x[0]) + (s.arity > 1 ? ", " + Num(p.x[1]) : "") + ": VM " + Num(r) +
                     ", reference " + Num(want));
        if (s.truth && r != 0 && r != 1) rep.fail(Describe(c) + ": truth value " + Num(r));
    } else {
        const PointValues q = RoundSeeds(c, p);
        const T d = RunAt(interp, c, q);
        if (s.kind == Kind::Plain) {
            if (!Same(d.v, r)) rep.fail(Describe(c) + ": Dual<double> value " + Num(d.v) + ", double " + Num(r));
            CheckDerivative(s, c, q, q.su, d.du, "du", rep);
            CheckDerivative(s, c, q, q.sv, d.dv, "dv", rep);
        } else {
            // Du and Dv give the operand's derivative as a value; their own derivatives are 0.
            const double want = s.kind == Kind::DerivU ? q.su[0] : q.sv[0];
            if (!Same(d.v, want) || d.du != 0 || d.dv != 0)
                rep.fail(Describe(c) + ": " + ToString(d) + ", want (" + Num(want) + "; 0; 0)");
        }
    }
}

/// The checks of a bound (value or derivative part) against the scalar at (eu, ev).
template <class B>
void CheckContains(const Case& c, const B& bound, const PointValues& p, double eu, double ev, double scalar,
                   const char* part, Report& rep) {
    if (!Contains(bound, eu, ev, scalar))
        rep.fail(Describe(c) + " at (eu, ev) = (" + Num(eu) + ", " + Num(ev) + "), operands" +
                 [&] {
                     std::string x;
                     for (size_t k = 0; k < c.operands.size(); ++k) x += " " + Num(p.x[k]);
                     return x;
                 }() +
                 ": " + part + " " + Num(scalar) + " not in " + ToString(bound) + " (range " +
                 RangeOf(bound).toString() + ", there " + At(bound, eu, ev).toString() + ")");
}

/// Calls check(point, values) at each point where the case's values are exact, counting the
/// points checked and skipped.
template <class F>
void ForEachPoint(const Case& c, const std::vector<Point>& points, Report& rep, F check) {
    for (const Point& pt : points) {
        PointValues p;
        if (!ValuesAt(c, pt, &p)) {
            ++rep.inexact;
            continue;
        }
        ++rep.points;
        check(pt, p);
    }
}

/// Runs one case under T and checks it at the points (for a point type, each point is a run).
template <class T>
void CheckCase(const Sample& s, const Case& c, const std::vector<Point>& points, Report& rep) {
    ++rep.cases;
    vm::Interpreter<double> scalar(c.program);
    if constexpr (kPointType<T>) {
        vm::Interpreter<T> interp(c.program);
        ForEachPoint(c, points, rep,
                     [&](const Point&, const PointValues& p) { CheckPoint<T>(s, c, p, scalar, interp, rep); });
    } else {
        using B = typename TypeInfo<T>::Base;
        vm::Affine::BeginEvaluation();
        T in[kMaxInputs];
        bool finiteInputs = true;  // every operand's range bounded
        bool pointInputs = true, moderate = true;
        for (size_t i = 0; i < c.inputs.size(); ++i) {
            in[i] = BoundInput<T>(c.inputs[i]);
            const Form& f = c.inputs[i].v;
            const vm::Interval r = RangeOf(vm::ValueOf(in[i]));
            finiteInputs &= !r.isUnbounded();
            pointInputs &= f.point();
            moderate &= std::fabs(f.c) + std::fabs(f.a) + std::fabs(f.b) + f.e <= 1e6;
        }
        for (double k : c.constants) {
            finiteInputs &= std::isfinite(k);
            moderate &= std::fabs(k) <= 1e6;
        }
        vm::Interpreter<T> interp(c.program);
        SetInputs(interp, in, static_cast<int>(c.inputs.size()), BoundInput<T>(Input{{1, 0, 0.5}, {}, {}}));
        interp.Run();
        const T result = interp.Register(kResult);
        const vm::Interval range = RangeOf(vm::ValueOf(result));
        // Truth values are 1, 0 or within [0, 1] (Unbounded operands included); noise is within
        // [0, 1] for finite input (vm/numbers/noise.h), ranges reaching +-1e308 included.
        if ((s.truth || (s.unitRange && finiteInputs)) && !(range.lo() >= 0 && range.hi() <= 1))
            rep.fail(Describe(c) + ": " + ToString(result) + " leaves [0, 1]");
        // ...and precisely the point 1, the point 0 or [0, 1] (undecided).
        if (s.truth && !(range.isPoint() || (range.lo() == 0 && range.hi() == 1)))
            rep.fail(Describe(c) + ": the truth value " + ToString(result) + " is neither 1, 0 nor [0, 1]");
        if (s.kind != Kind::Plain && !TypeInfo<T>::kDual && !IsUnbounded(result))
            rep.fail(Describe(c) + ": Du/Dv without derivatives gave " + ToString(result) + ", not Unbounded");
        std::optional<vm::Interpreter<vm::Dual<double>>> dualInterp;
        if constexpr (TypeInfo<T>::kDual) dualInterp.emplace(c.program);
        ForEachPoint(c, points, rep, [&](const Point& pt, const PointValues& p) {
            if constexpr (TypeInfo<T>::kDual) {
                const vm::Dual<double> d = RunAt(*dualInterp, c, p);
                CheckContains<B>(c, result.v, p, pt.eu, pt.ev, d.v, "value", rep);
                CheckContains<B>(c, result.du, p, pt.eu, pt.ev, d.du, "du", rep);
                CheckContains<B>(c, result.dv, p, pt.eu, pt.ev, d.dv, "dv", rep);
                // Tightness: a bound of moderate point operands is (nearly) the point.
                if (pointInputs && moderate && s.kind == Kind::Plain && std::isfinite(d.v) &&
                    !(s.loose && s.loose(p.x, 0)) && !(range.width() <= 1e-9 * std::max(1.0, std::fabs(d.v))))
                    rep.fail(Describe(c) + ": point operands, value " + Num(d.v) + ", bound " + range.toString());
            } else {
                const double r = RunAt(scalar, c, p);
                CheckContains<B>(c, result, p, pt.eu, pt.ev, r, "value", rep);
                if (pointInputs && moderate && s.kind == Kind::Plain && std::isfinite(r) &&
                    !(s.loose && s.loose(p.x, 0)) && !(range.width() <= 1e-9 * std::max(1.0, std::fabs(r))))
                    rep.fail(Describe(c) + ": point operands, value " + Num(r) + ", bound " + range.toString());
            }
            // A decided truth value is exact.
            if (s.truth && pointInputs && moderate && !range.isPoint())
                rep.fail(Describe(c) + ": point operands, undecided " + range.toString());
        });
    }
}

constexpr int kRangesPerOp = 500;
constexpr int kPointsPerRange = 16;

template <class T>
void RandomRanges(Op op, Report& rep) {
    const Sample s = SampleFor(op);
    test::Rng rng(0xC0F0 + static_cast<uint64_t>(op));  // the same cases for every type
    const bool rounding = op == Op::Floor || op == Op::Ceil || op == Op::Round;
    for (int r = 0; r < kRangesPerOp; ++r) {
        Case c = DrawCase(op, s, rng);
        c.prelude = rounding && r % 2 == 1;
        BuildProgram(c);
        // The corners and the centre, then random points; every point draws its error terms' values.
        std::vector<Point> points = {
            {-1, -1, rng.gen()}, {1, -1, rng.gen()}, {-1, 1, rng.gen()}, {1, 1, rng.gen()}, {0, 0, rng.gen()}};
        while (points.size() < static_cast<size_t>(kPointsPerRange))
            points.push_back({DrawEps(rng), DrawEps(rng), rng.gen()});
        CheckCase<T>(s, c, points, rep);
    }
}

// Edge values: signed zeros, infinities, NaN, subnormals, huge, and a few ordinary values to
// pair them with.
const std::vector<double> kEdges = {0.0,     -0.0,     kInf,      -kInf, kNaN,   5e-324,
                                    -5e-324, 2.2e-308, -2.2e-308, 1e300, -1e308, std::numeric_limits<double>::max(),
                                    1.0,     -1.0,     0.5,       -2.5,  3.0,    0.7};
const std::vector<double> kEdgeSeeds = {0.0, 1.0, -0.5, 1e300, 5e-324, kInf, kNaN};
const std::vector<double> kEdgeRadii = {5e-324, 1e-300, 1.0, 1e300, 1e308};

template <class T>
void EdgeValues(Op op, Report& rep) {
    const Sample s = SampleFor(op);
    rep.allowUnknown = true;
    test::Rng rng(0xED6E + static_cast<uint64_t>(op));
    const char* format = vm::Info(op).format;
    // Every pair for one or two operands, random combinations for more.
    const int n = s.arity;
    const int count = n == 1   ? static_cast<int>(kEdges.size())
                      : n == 2 ? static_cast<int>(kEdges.size() * kEdges.size())
                               : 400;
    for (int i = 0; i < count; ++i) {
        Case c;
        c.op = op;
        c.channel = static_cast<uint8_t>(rng.integer(0, s.channels - 1));
        for (int l = 1, k = 0; format[l]; ++l) {
            if (format[l] != 'r' && format[l] != 'k') continue;
            const size_t m = kEdges.size(), at = static_cast<size_t>(i);
            const size_t e = n == 1 ? at : n == 2 ? (k == 0 ? at % m : at / m) : rng.integer<size_t>(0, m - 1);
            const double x = kEdges[e];
            if (format[l] == 'k') {
                c.operands.push_back({true, static_cast<int>(c.constants.size())});
                c.constants.push_back(x);
            } else {
                Input in;
                in.v.c = x;
                in.du.c = rng.pick(kEdgeSeeds);
                in.dv.c = rng.chance(0.5) ? 0.0 : rng.pick(kEdgeSeeds);
                c.operands.push_back({false, static_cast<int>(c.inputs.size())});
                c.inputs.push_back(in);
            }
            ++k;
        }
        BuildProgram(c);
        CheckCase<T>(s, c, {{0, 0}}, rep);
    }
    // Huge and tiny ranges around edge values: the bounds must stay sound (or Unbounded) where
    // sums overflow.
    for (int i = 0; i < 200; ++i) {
        Case c;
        c.op = op;
        c.channel = static_cast<uint8_t>(rng.integer(0, s.channels - 1));
        for (int l = 1; format[l]; ++l) {
            if (format[l] != 'r' && format[l] != 'k') continue;
            const double x = rng.pick(kEdges);
            if (format[l] == 'k') {
                c.operands.push_back({true, static_cast<int>(c.constants.size())});
                c.constants.push_back(x);
                continue;
            }
            Input in;
            in.v.c = x;
            if (std::isfinite(x)) in.v.a = rng.pick(kEdgeRadii);
            in.du.c = rng.chance(0.5) ? 1.0 : 0.0;
            c.operands.push_back({false, static_cast<int>(c.inputs.size())});
            c.inputs.push_back(in);
        }
        BuildProgram(c);
        CheckCase<T>(s, c, {{0, 0}, {-1, 0}, {1, 0}, {0.5, 0}}, rep);
    }
}

std::string Summary(Op op, const Report& rep) {
    std::ostringstream o;
    o << vm::Info(op).name << ": " << rep.failures << " failures in " << rep.cases << " cases, " << rep.points
      << " points (" << rep.inexact << " inexact skipped), finite differences " << rep.fdChecked << " checked, "
      << rep.fdSkipped << " skipped\n"
      << rep.first.str();
    return o.str();
}

}  // namespace

TEST_CASE("conformance: every opcode but Ext, Light and Trace has a sample", "[conformance]") {
    // (The static_assert above already guarantees it; this lists the samples for the record.)
    int sampled = 0;
    for (int i = 0; i < vm::kOpCount; ++i) {
        const Op op = static_cast<Op>(i);
        const Sample s = SampleFor(op);
        INFO(vm::kOpInfo[i].name << " " << vm::kOpInfo[i].format);
        if (op == Op::Ext || op == Op::Light || op == Op::Trace) {
            CHECK(s.kind == Kind::None);
            continue;
        }
        CHECK(s.kind != Kind::None);
        CHECK(s.arity == OperandCount(vm::kOpInfo[i].format));
        ++sampled;
    }
    CHECK(sampled == vm::kOpCount - 3);
}

namespace {

/// Runs check(op, rep) under T for every opcode but Ext, Light and Trace, and requires no failures;
/// harness(op, rep) checks more of the report (of the harness itself).
template <class T, class Check, class Harness>
void EveryOpcode(Check check, Harness harness) {
    for (int i = 0; i < vm::kOpCount; ++i) {
        const Op op = static_cast<Op>(i);
        if (op == Op::Ext || op == Op::Light || op == Op::Trace) continue;
        Report rep;
        check(op, rep);
        INFO(vm::NumberTraits<T>::kName << " " << Summary(op, rep));
        CHECK(rep.failures == 0);
        harness(op, rep);
    }
}

}  // namespace

TEMPLATE_TEST_CASE("conformance: every opcode over random regions", "[conformance]", AFFRAY_CONFORMANCE_TYPES) {
    EveryOpcode<TestType>(RandomRanges<TestType>, [](Op op, const Report& rep) {
        // The harness itself: points are exact, and finite differences are not all skipped.
        CHECK(rep.inexact * 50 <= rep.points);
        if constexpr (std::is_same_v<TestType, vm::Dual<double>>)
            if (SampleFor(op).kind == Kind::Plain) CHECK(rep.fdChecked >= rep.fdSkipped / 4);
    });
}

TEMPLATE_TEST_CASE("conformance: every opcode on edge values", "[conformance]", AFFRAY_CONFORMANCE_TYPES) {
    EveryOpcode<TestType>(EdgeValues<TestType>, [](Op, const Report&) {});
}

// ---------------------------------------------------------------------------------------------
// The verifier fuzz: every opcode value 0..255.

namespace {

/// What the interpreter relies on, from Verify's contract (vm/verify.h) and the interpreter's
/// loop, checked without Verify: true if `p` is safe to run.
bool SafeToRun(const vm::Program& p, std::string* why) {
    auto no = [why](const std::string& reason) {
        *why = reason;
        return false;
    };
    const int n = p.registerCount;
    if (n < 0 || n > vm::kMaxRegisters) return no("register count");
    if (!p.lines.empty() && p.lines.size() != p.code.size()) return no("line table");
    std::vector<bool> written(n, false);
    for (int g = 0; g < vm::kGlobalCount; ++g) {
        const uint16_t base = p.globalRegisters[g];
        if (base == vm::kNoRegister) continue;
        const int size = vm::GlobalSize(static_cast<vm::Global>(g));
        if (base + size > n) return no("global register");
        for (int i = 0; i < size; ++i) written[base + i] = true;
    }
    for (const vm::ProgramParam& param : p.params) {
        if (param.size < 1 || param.defaults.size() != static_cast<size_t>(param.size)) return no("parameter");
        if (param.firstRegister == vm::kNoRegister) continue;
        if (param.firstRegister + param.size > n) return no("parameter register");
        for (int i = 0; i < param.size; ++i) written[param.firstRegister + i] = true;
    }
    for (size_t pc = 0; pc < p.code.size(); ++pc) {
        const vm::Instr& in = p.code[pc];
        const int op = static_cast<int>(in.op);
        if (op >= vm::kOpCount) return no("opcode " + std::to_string(op));
        if (in.op == Op::Ext) return no("Ext word at " + std::to_string(pc));
        const char* format = vm::kOpInfo[op].format;
        const size_t words = vm::WordCount(format);
        if (pc + words > p.code.size()) return no("missing Ext words");
        for (size_t w = 1; w < words; ++w)
            if (p.code[pc + w].op != Op::Ext) return no("not an Ext word");
        if (vm::OperationOf(in.op) == vm::Operation::Texture && (!p.textures || in.flags >= p.textures->size()))
            return no("texture slot " + std::to_string(in.flags));
        int write = -1;
        for (int i = 0; format[i]; ++i) {
            const vm::Instr& word = p.code[pc + i / 3];
            const uint16_t x = i % 3 == 0 ? word.a : i % 3 == 1 ? word.b : word.c;
            if (format[i] == 'r' && (x >= n || !written[x])) return no("register read " + std::to_string(x));
            if (format[i] == 'k' && x >= p.constants.size()) return no("constant " + std::to_string(x));
            if (format[i] == 'w') {
                if (x >= n) return no("register written " + std::to_string(x));
                write = x;
            }
        }
        if (write >= 0) written[write] = true;
        pc += words - 1;
    }
    for (const vm::ProgramOutput& out : p.outputs) {
        if (out.size != 1 && out.size != 3) return no("output size");
        for (int i = 0; i < out.size; ++i)
            if (out.registers[i] >= n || !written[out.registers[i]]) return no("output register");
    }
    return true;
}

template <class T>
void RunFuzzed(const vm::Program& p, test::Rng& rng) {
    vm::Interpreter<T> interp(p);
    for (int g = 0; g < vm::kGlobalCount; ++g) {
        auto value = [&] { return rng.chance(0.3) ? T(rng.pick(kEdges)) : T(rng.uniform(-10, 10)); };
        const vm::Global global = static_cast<vm::Global>(g);
        if (vm::GlobalSize(global) == 3)
            interp.SetGlobal(global, vm::Vec3<T>(value(), value(), value()));
        else
            interp.SetGlobal(global, value());
    }
    interp.Run();
    for (const vm::ProgramOutput& out : p.outputs)
        for (int i = 0; i < out.size; ++i) (void)RangeOf(interp.Register(out.registers[i]));
}

}  // namespace

TEST_CASE("conformance: the verifier over every opcode value, and what it accepts runs", "[conformance][verify]") {
    test::Rng rng(0xF022);
    const int iterations = 20000;
    std::vector<int> acceptedOps(vm::kOpCount, 0);
    int accepted = 0, rejectedInvalidOp = 0, failures = 0;
    std::ostringstream first;
    auto fail = [&](const std::string& s) {
        if (failures++ < 6) first << s << "\n";
    };
    for (int iter = 0; iter < iterations; ++iter) {
        vm::Program p;
        p.registerCount = rng.chance(0.97) ? rng.integer(3, 12) : rng.integer(0, 2);
        const int n = p.registerCount;
        bool valid = true;  // every choice kept the program well-formed: Verify must accept it
        bool invalidOp = false;
        std::vector<bool> written(n, false);
        auto markGlobal = [&](vm::Global g) {
            const int size = vm::GlobalSize(g);
            const int base = n >= size && rng.chance(0.95) ? rng.integer(0, n - size) : rng.integer(0, 12);
            p.globalRegisters[static_cast<int>(g)] = static_cast<uint16_t>(base);
            if (base + size > n) valid = false;
            for (int i = 0; i < size && base + i < n; ++i) written[base + i] = true;
        };
        if (rng.chance(0.85)) markGlobal(vm::Global::P);
        if (rng.chance(0.5)) markGlobal(vm::Global::u);
        if (rng.chance(0.1)) {
            vm::ProgramParam param;
            param.name = "k";
            param.type = "float";
            param.size = rng.integer(1, 3);
            param.defaults.assign(rng.chance(0.9) ? param.size : param.size + 1, 0.25);
            param.firstRegister = rng.chance(0.3) ? vm::kNoRegister : static_cast<uint16_t>(rng.integer(0, 12));
            if (param.defaults.size() != static_cast<size_t>(param.size)) valid = false;
            if (param.firstRegister != vm::kNoRegister) {
                if (param.firstRegister + param.size > n) valid = false;
                for (int i = 0; i < param.size && param.firstRegister + i < n; ++i)
                    written[param.firstRegister + i] = true;
            }
            p.params.push_back(param);
        }
        if (rng.chance(0.8)) p.textures = TestTextures();
        const int nk = rng.integer(0, 4);  // (no constants: every K operand is out of range)
        for (int i = 0; i < nk; ++i) p.constants.push_back(rng.chance(0.5) ? rng.pick(kEdges) : rng.uniform(-5, 5));
        auto readable = [&]() -> uint16_t {
            std::vector<uint16_t> w;
            for (int r = 0; r < n; ++r)
                if (written[r]) w.push_back(static_cast<uint16_t>(r));
            const uint16_t x =
                !w.empty() && rng.chance(0.97) ? rng.pick(w) : static_cast<uint16_t>(rng.integer(0, n + 2));
            if (x >= n || !written[x]) valid = false;
            return x;
        };
        const int instructions = rng.integer(1, 8);
        for (int i = 0; i < instructions; ++i) {
            const double kind = rng.uniform(0, 1);
            const int opv = kind < 0.93   ? rng.integer(0, vm::kOpCount - 1)
                            : kind < 0.98 ? rng.integer(vm::kOpCount, 255)
                                          : static_cast<int>(Op::Ext);
            vm::Instr head{static_cast<Op>(opv), static_cast<uint8_t>(rng.integer(0, 255)), 0, 0, 0};
            if (opv < vm::kOpCount && vm::OperationOf(head.op) == vm::Operation::Texture) {
                // Mostly a slot of the table, if there is one; else out of range.
                if (rng.chance(0.9)) head.flags = static_cast<uint8_t>(rng.integer(0, kTextureSlots - 1));
                if (!p.textures || head.flags >= p.textures->size()) valid = false;
            }
            if (opv >= vm::kOpCount || head.op == Op::Ext || rng.chance(0.02)) {
                // A garbage word.
                invalidOp |= opv >= vm::kOpCount;
                valid = false;
                head.a = static_cast<uint16_t>(rng.chance(0.5) ? rng.integer(0, 20) : rng.integer(0, 65535));
                head.b = static_cast<uint16_t>(rng.chance(0.5) ? rng.integer(0, 20) : rng.integer(0, 65535));
                head.c = static_cast<uint16_t>(rng.chance(0.5) ? rng.integer(0, 20) : rng.integer(0, 65535));
                p.code.push_back(head);
                continue;
            }
            const char* format = vm::kOpInfo[opv].format;
            std::vector<vm::Instr> words(vm::WordCount(format), vm::Instr{Op::Ext, 0, 0, 0, 0});
            words[0] = head;
            int write = -1;
            for (int l = 0; format[l]; ++l) {
                uint16_t x = 0;
                switch (format[l]) {
                    case 'r': x = readable(); break;
                    case 'k':
                        x = static_cast<uint16_t>(nk > 0 && rng.chance(0.97) ? rng.integer(0, nk - 1)
                                                                             : rng.integer(0, 5));
                        if (x >= nk) valid = false;
                        break;
                    case 'w':
                        x = static_cast<uint16_t>(n > 0 && rng.chance(0.97) ? rng.integer(0, n - 1)
                                                                            : rng.integer(0, n + 2));
                        if (x >= n) valid = false;
                        write = x;
                        break;
                    default:  // unused: ignored by everyone
                        x = static_cast<uint16_t>(rng.chance(0.9) ? 0 : rng.integer(0, 65535));
                        break;
                }
                vm::Instr& w = words[l / 3];
                (l % 3 == 0 ? w.a : l % 3 == 1 ? w.b : w.c) = x;
            }
            if (write >= 0 && write < n) written[write] = true;
            if (words.size() > 1 && rng.chance(0.05)) {
                // An Ext word missing or replaced by another instruction.
                valid = false;
                if (rng.chance(0.5))
                    words.pop_back();
                else
                    words.back().op = static_cast<Op>(rng.integer(0, static_cast<int>(Op::Ext) - 1));
            }
            p.code.insert(p.code.end(), words.begin(), words.end());
        }
        const int outputs = rng.integer(0, 2);
        for (int i = 0; i < outputs; ++i) {
            vm::ProgramOutput out;
            out.name = "o" + std::to_string(i);
            out.size = rng.chance(0.03) ? 2 : rng.chance(0.5) ? 1 : 3;
            if (out.size == 2) valid = false;
            for (int c = 0; c < std::min(out.size, 3); ++c) out.registers[c] = readable();
            p.outputs.push_back(out);
        }
        if (rng.chance(0.15)) {
            const size_t size = rng.chance(0.7) ? p.code.size() : p.code.size() + 1;
            if (size != p.code.size()) valid = false;
            p.lines.assign(size, 7);
        }

        // A light query is allowed only in a surface program (Verify's `lights`).
        const bool lights = rng.chance(0.5);
        for (size_t pc = 0; pc < p.code.size(); ++pc)
            if ((p.code[pc].op == Op::Light || p.code[pc].op == Op::Trace) && !lights) valid = false;
        std::string error;
        const bool ok = vm::Verify(p, &error, lights);
        if (!ok) {
            if (error.empty()) fail("rejected without a message, iteration " + std::to_string(iter));
            if (valid) fail("a well-formed program rejected: " + error + ", iteration " + std::to_string(iter));
            rejectedInvalidOp += invalidOp;
            continue;
        }
        std::string why;
        if (!SafeToRun(p, &why)) {
            fail("accepted but unsafe (" + why + "), iteration " + std::to_string(iter));
            continue;
        }
        ++accepted;
        for (size_t pc = 0; pc < p.code.size(); pc += vm::Words(p.code[pc].op))
            ++acceptedOps[static_cast<int>(p.code[pc].op)];
        RunFuzzed<double>(p, rng);
        RunFuzzed<vm::Interval>(p, rng);
    }
    INFO(first.str());
    CHECK(failures == 0);
    CHECK(accepted >= iterations / 10);
    CHECK(rejectedInvalidOp > 0);
    for (int op = 0; op < vm::kOpCount; ++op) {
        INFO(vm::kOpInfo[op].name);
        if (static_cast<Op>(op) != Op::Ext) CHECK(acceptedOps[op] > 0);
    }
}

// ---------------------------------------------------------------------------------------------
// Regressions: what this suite found in the number types, each fixed, checked on its own here as
// well as by the suite's samples.

TEST_CASE("regression: noise of an unbounded operand under Dual<bound> has unknown derivatives",
          "[conformance][conformance-regression]") {
    // x's bound is Unbounded (it holds x = 0.3, among others) and dx/du = 1. At x = 0.3 noise has
    // a nonzero derivative, so the bound's derivatives must hold it: they were exactly 0 (T(NaN)).
    const vm::Dual<double> point(0.3, 1.0, 0.0);
    const vm::Dual<double> at = vm::Noise(&point, 1, 0);
    REQUIRE(at.du != 0);
    const vm::Dual<vm::Interval> xi(vm::Interval::Unbounded(), vm::Interval(1.0), vm::Interval(0.0));
    const vm::Dual<vm::Affine> xa(vm::Affine::Unbounded(), vm::Affine(1.0), vm::Affine(0.0));
    const vm::Dual<vm::ReducedAffine> xr(vm::ReducedAffine::Unbounded(), vm::ReducedAffine(1.0),
                                         vm::ReducedAffine(0.0));
    CHECK(RangeOf(vm::Noise(&xi, 1, 0).du).contains(at.du));
    CHECK(RangeOf(vm::Noise(&xa, 1, 0).du).contains(at.du));
    CHECK(RangeOf(vm::Noise(&xr, 1, 0).du).contains(at.du));
    CHECK(IsUnbounded(vm::Noise(&xi, 1, 0).dv));
    // pnoise likewise, for an unbounded period.
    const vm::Dual<double> period(4.0, 0.0, 0.0);
    const vm::Dual<double> pat = vm::PNoise(&point, &period, 1, 0);
    REQUIRE(pat.du != 0);
    const vm::Dual<vm::Interval> pi(vm::Interval(0.3), vm::Interval(1.0), vm::Interval(0.0));
    const vm::Dual<vm::Interval> unboundedPeriod(vm::Interval::Unbounded(), vm::Interval(0.0), vm::Interval(0.0));
    CHECK(RangeOf(vm::PNoise(&pi, &unboundedPeriod, 1, 0).du).contains(pat.du));
    // A double's noise of a non-finite coordinate is NaN, its derivatives unknown (NaN) too.
    const vm::Dual<double> inf(kInf, 1.0, 0.0);
    const vm::Dual<double> atInf = vm::Noise(&inf, 1, 0);
    CHECK(std::isnan(atInf.v));
    CHECK(std::isnan(atInf.du));
}

TEST_CASE("regression: Dual<double> atan2 keeps its derivative where x^2 + y^2 overflows or underflows",
          "[conformance][conformance-regression]") {
    // d atan2(y, x)/du at y = 0.5 (dy/du = 1), x = 1e300 is x / (x^2 + y^2) = 1e-300; the chain rule
    // divided by x^2 + y^2 = inf and gave 0.
    const vm::Dual<double> y(0.5, 1.0, 0.0), x(1e300, 0.0, 0.0);
    const vm::Dual<double> r = atan2(y, x);
    CHECK(r.du == Approx(1e-300).epsilon(1e-12));
    CHECK(r.dv == 0);
    // dx/du: -y / (x^2 + y^2), with y the larger (1e300) and x = 2.
    const vm::Dual<double> r2 = atan2(vm::Dual<double>(1e300, 0.0, 0.0), vm::Dual<double>(2.0, 1.0, 0.0));
    CHECK(r2.du == Approx(-1e-300).epsilon(1e-12));
    // Both tiny: x^2 + y^2 underflows to 0; the derivative along y is x / (x^2 + y^2) = 0.5e200.
    const vm::Dual<double> r3 = atan2(vm::Dual<double>(1e-200, 1.0, 0.0), vm::Dual<double>(1e-200, 0.0, 0.0));
    CHECK(r3.du == Approx(0.5e200).epsilon(1e-12));
    // Bounds of those derivatives hold the doubles': x over a region around 1e300.
    const vm::Dual<vm::Interval> yi(vm::Interval(0.5), vm::Interval(1.0), vm::Interval(0.0));
    const vm::Dual<vm::Interval> xi(vm::Interval(0.5e300, 2e300), vm::Interval(0.0), vm::Interval(0.0));
    const vm::Interval du = RangeOf(atan2(yi, xi).du);
    CHECK_FALSE(du.isUnbounded());
    for (double xv : {0.5e300, 1e300, 2e300}) CHECK(du.contains(atan2(y, vm::Dual<double>(xv, 0.0, 0.0)).du));
    // A region where some points scale and others do not joins both formulas.
    const vm::Dual<vm::Interval> xw(vm::Interval(1e150, 1e160), vm::Interval(0.0), vm::Interval(0.0));
    const vm::Interval dw = RangeOf(atan2(yi, xw).du);
    for (double xv : {1e150, 1e153, 1e154, 1e155, 1e160})
        CHECK(dw.contains(atan2(y, vm::Dual<double>(xv, 0.0, 0.0)).du));
}

TEST_CASE("regression: min and max of -0 and +0 agree in double, Dual<double> and the folder",
          "[conformance][conformance-regression]") {
    // fmin/fmax(-0, +0) may be either zero in C, and GCC may swap the operands of fmin and fmax:
    // the scalar VM and its Dual<double> (which the renderer shades with) gave different zeros.
    // vm/numbers/number.h fixes the rule: the first operand.
    for (Op op : {Op::MaxRR, Op::MinRR}) {
        for (double first : {-0.0, 0.0}) {
            Case c;
            c.op = op;
            c.inputs = {Input{Form{first}, {}, {}}, Input{Form{-first}, {}, {}}};
            c.operands = {{false, 0}, {false, 1}};
            BuildProgram(c);
            PointValues p;
            REQUIRE(ValuesAt(c, Point{}, &p));
            vm::Interpreter<double> scalar(c.program);
            vm::Interpreter<vm::Dual<double>> dual(c.program);
            const double s = RunAt(scalar, c, p), d = RunAt(dual, c, p).v;
            const double operands[2] = {first, -first};
            const double folded = vm::RunScalarOpcode(op, operands, 0);
            INFO(vm::Info(op).name << "(" << first << ", " << -first << "): double " << s << ", Dual<double> " << d
                                   << ", folded " << folded);
            CHECK(std::signbit(s) == std::signbit(first));
            CHECK(std::signbit(d) == std::signbit(first));
            CHECK(std::signbit(folded) == std::signbit(first));
            // The constant forms: min(R, K) with K the second operand.
            c.constants = {-first};
            c.op = op == Op::MaxRR ? Op::MaxRK : Op::MinRK;
            c.operands = {{false, 0}, {true, 0}};
            BuildProgram(c);
            vm::Interpreter<double> scalarK(c.program);
            vm::Interpreter<vm::Dual<double>> dualK(c.program);
            CHECK(std::signbit(RunAt(scalarK, c, p)) == std::signbit(first));
            CHECK(std::signbit(RunAt(dualK, c, p).v) == std::signbit(first));
        }
    }
}

TEST_CASE("regression: noise over a region reaching +-1e308 lies between 0 and 1",
          "[conformance][conformance-regression]") {
    // p - floor(p) overflowed in the cell-independent bound, which gave Unbounded.
    const vm::Interval huge(-1e308, 1e308);
    for (int dims = 1; dims <= 4; ++dims) {
        vm::Interval pi[4] = {huge, huge, huge, huge};
        const vm::Interval ni = vm::Noise(pi, dims, 0);
        INFO(dims << " " << ni.toString());
        CHECK(ni.lo() >= 0);
        CHECK(ni.hi() <= 1);
        vm::Affine pa[4];
        vm::Dual<vm::Interval> pd[4];
        for (int i = 0; i < 4; ++i) {
            pa[i] = vm::Affine::FromInterval(huge);
            pd[i] = vm::Dual<vm::Interval>(huge, vm::Interval(1.0), vm::Interval(0.0));
        }
        const vm::Interval na = vm::Noise(pa, dims, 0).range();
        CHECK(na.lo() >= 0);
        CHECK(na.hi() <= 1);
        const vm::Dual<vm::Interval> nd = vm::Noise(pd, dims, 0);
        CHECK(nd.v.lo() >= 0);
        CHECK(nd.v.hi() <= 1);
        // The derivative at a point of the region (0.3 in every coordinate) lies in the bound's.
        const vm::Dual<double> pt[4] = {{0.3, 1.0, 0.0}, {0.3, 1.0, 0.0}, {0.3, 1.0, 0.0}, {0.3, 1.0, 0.0}};
        CHECK(RangeOf(nd.du).contains(vm::Noise(pt, dims, 0).du));
    }
    const vm::Interval period[1] = {vm::Interval(4.0)};
    const vm::Interval p1[1] = {huge};
    const vm::Interval np = vm::PNoise(p1, period, 1, 0);
    CHECK(np.lo() >= 0);
    CHECK(np.hi() <= 1);
}
