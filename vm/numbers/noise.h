// vm/numbers/noise.h: the RenderMan noise functions (noise, pnoise, cellnoise), written once as templates
// over the number type, so that the double value a shader computes at a point and the bound an
// Interval, Affine or Dual<...> evaluation computes over a (u,v) region come from the same code.
// Owns Noise, PNoise and CellNoise, their lattice hash and gradient sets (vm/numbers/noise.cpp), the
// scale that keeps gradient noise inside [0, 1], and LocalForm, the small affine arithmetic that
// bounds one cell (see "Bounds"). This header is longer than 600 lines because the templates
// and the proofs that keep them sound belong together.
//
// Semantics (double is the reference, as everywhere in the VM):
//  - Noise(p, dims, seed): gradient ("Perlin") noise of dims = 1..4 coordinates. Lattice point c
//    (an integer vector) gets a gradient g(c) drawn by an integer hash of (c, dims, seed) from a
//    fixed set (NoiseGradients). In the cell k = floor(p), with local coordinates t = p - k in
//    [0,1]^dims, fades s_i = 6t^5 - 15t^4 + 10t^3 and corner weights W_o = prod_i (o_i ? s_i :
//    1 - s_i) for o in {0,1}^dims, the raw value is
//        raw(t) = sum_o W_o * g(k + o).(t - o)        (computed as nested lerps, dimension 0 first)
//    and the result is 0.5 + raw * NoiseScale(dims), clamped to [0, 1] (a no-op in exact
//    arithmetic, see "The scale" below; it only guards rounding). C1: the fade has zero first and
//    second derivatives at 0 and 1, so raw is C2 across cell faces. Values are 0.5 at lattice
//    points; the mean is 0.5 (the gradient sets are symmetric, so raw is symmetric about 0).
//    `seed` selects independent channels (the compiler uses 0, 1, 2 for x, y, z of a triple).
//    Non-finite input gives NaN (Unbounded for bounded types), with unknown derivatives.
//  - PNoise(p, period, dims, seed): the same noise on a lattice that wraps with the integer period
//    P_i = max(1, round(period_i)) per dimension: gradients are hashed from (c_i mod P_i). Hence
//    PNoise(p + P e_i) = PNoise(p), and PNoise = Noise wherever 0 <= floor(p_i) and
//    floor(p_i) + 1 < P_i for every i (both hash the same corners there). Periods are uniform
//    values; a non-finite period gives NaN (Unbounded for a bounded period that may be one).
//  - CellNoise(p, dims, seed): constant on each cell floor(p): a hash of (floor(p), dims, seed)
//    mapped to [0, 1) (53 bits). Derivatives 0.
//
// Bounds (Interval, Affine and Dual<...> of them; the same template code, CellPolynomial, on
// every type):
//  1. The range of each coordinate gives the cells it touches, floor(lo)..floor(hi). If at most
//     kNoiseCellCap cells are touched in total, each touched cell is bounded on its own and the
//     results are Joined. Every point lies in one of these cells (floor is monotone), and each
//     cell's bound contains the double value at every point of the region in that cell.
//     kNoiseCellCap = 16 = 2^4: every region narrower than one cell in each coordinate (so
//     touching at most 2 cells per coordinate) is bounded cell by cell in every dimension up to 4,
//     which covers the regions a subdividing ray tracer spends its time on; a region a full cell
//     wide or more sees noise through most of its range anyway, so the fallback loses little.
//     A cell is bounded one of two ways (NoiseBoundMethod):
//     a. Local (Affine's and ReducedAffine's default): CellPolynomial (then * scale + 0.5) evaluated on LocalForms, a
//        small affine arithmetic whose first symbols are the cell's local coordinates over the
//        part B of the region inside the cell (t_i = c_i + reach_i sigma_i, c the centre of B)
//        and whose further symbols are fresh, one per product. It keeps Affine's contract and
//        error formulas (tested by Stolfi's aavalid method in tests/vm/numbers/noise_test.cpp), so the
//        form contains the double value at every double t in B. The result z0 + sum_i z_i
//        sigma_i +- rest is then mapped back to T by sigma_i = (t_i - c_i)/reach_i, with
//        t_i = p_i - k_i, as sum_i a_i p_i + [constant +- rest] (a_i = z_i/reach_i; the
//        rounding of a_i, of p_i - k_i and of the constant are added to rest; the Interval and
//        Affine operations that form it enclose their exact results as well as the double ones):
//        2 dims T operations instead of the ~50 (d = 3) to ~100 (d = 4) of method b. In Affine,
//        [constant +- rest] is one fresh symbol, so a shader reusing the value keeps its
//        correlation. This is a bound-only path (double and the Duals never take it), but the
//        double value and the bound still come from the same CellPolynomial.
//        Why it is cheaper: LocalForm is dense (at most dims + 31 slots, the products of one cell
//        polynomial), inline, with no sorting, enclosure or capacity folding; Affine spends most
//        of its time on those (range() alone was 29 % of a profile). Why it is as tight: the
//        local coordinates are exactly the t_i, so the first-order part is exact as in Affine;
//        the remainders are Affine's, but none is folded for lack of capacity, and B excludes
//        the parts of a straddling region outside the cell (no overhang, no clamp).
//        Measured (bench/noise_bench.cpp, regions 1/8, 1/64, 1/512 of a cell inside one cell or
//        with one coordinate straddling a face, d = 1..4): Affine 2.1-4.0 times the calls per
//        second, with mean widths 0.66-1.0 times the polynomial's (never wider: 0.87-0.94 at
//        1/8, 0.97-0.99 at 1/64 and 1/512 inside a cell, 0.66-0.71 straddling at 1/8). A 96x72
//        render of shaders/dented.sl: 2.2 times less CPU time, regions per ray 22.37 -> 22.03.
//        Interval can take it too (NoiseBoundMethod::Local): 5 to 100 times narrower bounds, but
//        up to 2.5 times the cost of the interval polynomial per call, and the same dented render
//        with --bounds interval then takes 60 % more time for 2.4 times fewer regions per ray,
//        so Interval keeps b by default. ReducedAffine takes it by default: in its polynomial
//        every product's remainder lands in the one error term and the correlations between
//        them are lost, whereas here only [constant +- rest] does (bench/bounds_bench.cpp, 100
//        regions, mean z widths of Local over Polynomial at 1/8, 1/64, 1/512: dented 0.91, 0.62,
//        0.88; stucco 1.0, 0.70, 0.96; ridged 0.97, 0.84, 0.93; strata 0.87, 0.91, 0.99; cost
//        per evaluation between 0.65 and 1.3 times Polynomial's).
//        Each coordinate's fade over its part of the cell enters as its Taylor polynomial at the
//        part's centre in closed form (MakeLocalAxis), not as the fade computed in LocalForm
//        (five products, each remainder on a symbol): its nonlinear part is 0.12 to 0.16 times
//        as wide (mean over parts 0.5 to 0.001 of a cell wide), and it is cheaper (bench/real's
//        subdivision scene, a crop of 7,956 camera rays: 42.6 bounds evaluated per ray instead
//        of 73.5, 2.9 thread-seconds of bounds instead of 5.0).
//        ReducedAffine takes a third way (QuadraticCellOnRegion): its coordinates are affine in
//        the region's own eps_u and eps_v (a surface's region is a parallelogram in noise space,
//        not the box of its coordinate ranges), so the cell polynomial is evaluated on those
//        symbols, in QuadForm arithmetic (vm/numbers/quad_form.h), which keeps the second-order
//        terms in eps_u, eps_v exactly through the fades and the lerps and reduces only third and
//        fourth order (u^3 = 0.75 u +- 0.25, ...); each fade is its Taylor polynomial over the
//        coordinate's part of the cell (MakeQuadAxis), its terms beyond second order on a symbol
//        of the coordinate's own. Each lerp is QuadForm's Lerp, whose remainder is the convex
//        combination of its ends' (a product would count the first end's twice, compounding over
//        the lerps). A region straddling faces is bounded cell by cell over each cell's own part
//        of it (CellPartOf: the bounding box, in eps_u and eps_v, of the parallelogram clipped to
//        the cell; a cell the region cannot reach, often half of the box of cells, is skipped), and
//        the pieces are joined over their own boxes (JoinPieces), not over the whole region,
//        where a cell's polynomial continued past its faces strays. The error left is the
//        quadratic part's range over the region plus small change: over regions 0.3, 0.2, 0.1
//        and 0.01 of a cell wide it is 2.0, 1.5, 1.2 and 1.02 times the noise's true deviation
//        from the bound's plane inside a cell, and 2.3, 2.2, 2.1 and 1.1 across faces
//        (tests/vm/numbers/noise_test.cpp). Products for lerps gave 3.1, 2.0, 1.4 and 1.04 inside;
//        joining the cells' bounds over the whole region, 5.8, 5.5, 4.9 and 1.1 across faces. The
//        LocalForm on eps_u and eps_v that the QuadForms replace (one symbol per product) gave
//        5.6, 4.8, 4.0 and 3.6 inside and 5.3, 5.1, 4.7 and 1.5 across faces, at about twice the
//        cost per cell. Each
//        coordinate's error (the region's own, and the rounding of t = p - k) is a symbol of the
//        coordinate's too, shared by t and its fade: left in the QuadForm's error, every product
//        would multiply it (the teapot of bench/real tested 207 regions per camera ray so, 124
//        with the symbol, 128 with the LocalForms).
//        The mean-value form raw(c) + grad raw(B).(t - c), with the gradient over B enclosed by
//        interval forward differentiation, was tried first and dropped: as slow (the interval
//        gradient costs as much as the affine polynomial) and 1.2-8 times wider at 1/64 (the
//        interval gradient's dependency overestimate enters the second-order term).
//     b. Polynomial (every other type, and Affine or ReducedAffine on request): CellPolynomial in T arithmetic with
//        t_i = clamp(p_i - k_i, 0, 1) (so, values at that cell's points only): the T evaluation
//        of the same operations contains the double result, rounding included.
//        A t_i whose range overhangs [0, 1] by at most kNoiseOverhang = 1/16 is left unclamped (the
//        polynomial over a superset of the cell still contains its values): past a face, a cell's
//        polynomial agrees with its neighbour's to third order (C2), so the Joined forms of a
//        region straddling a face stay nearly equal, whereas Min/Max make them differ. Measured on
//        regions straddling faces, about 0.025 wide: affine bounds 15-25 % narrower for d = 2..4
//        (6 % wider for d = 1); past overhangs of ~0.1 clamping wins.
//  2. Otherwise (or for a period whose range is not one point) a cell-independent evaluation: the
//     same formula with t_i = clamp(p_i - floor(p_i), 0, 1) and every gradient component replaced
//     by Join(T(-G), T(G)), G the largest |component| of the set (a separate Join per corner and
//     component, since corners have independent gradients): it contains every cell's value. A
//     double never takes this path (it touches one cell, and its finite period is one point),
//     which is why Join(T(-G), T(G)) may be meaningless for double.
//  3. The result is clamped to [0, 1] with Min/Max, so a bound is never wider than [0, 1]
//     (except Unbounded for non-finite input; a bound that overflows on finite input, p -
//     floor(p) over a range reaching +-1e308, is [0, 1] itself, derivatives unknown). Clamps (of
//     t and of the result) are applied only when the value's range leaves [0, 1] (plus the
//     overhang for t); a double never needs the t clamp, so Dual<double> derivatives are the
//     polynomial's exact chain rule.
//
// The scale. For any gradients from a set S closed under negation, and phi(y) = max_{g in S} g.y
// (>= 0), the partition of unity (W_o >= 0, sum_o W_o = 1) gives
//     |raw(t)| <= sum_o W_o |g_o.(t - o)| <= F(t) := sum_o W_o(t) phi(t - o).
// NoiseScale(d) = 0.5 / B_d with B_d >= sup over [0,1]^d of F, so 0.5 + raw*scale is in [0, 1]:
//  - d = 1, S = {+-9/16, ..., +-16/16}: phi(y) = |y|, F(t) = h(t) := (1 - s)t + s(1 - t) and
//    h(t) - 1/2 = (t - 1/2)(1 - 2s(t)) <= 0 since the fade s is increasing with s(1/2) = 1/2.
//    So B_1 = 1/2, attained at t = 1/2 (by gradients +-1): scale 1.
//  - d >= 2: a general analytic bound is phi(y) <= |g|max |y|_2 and, by Jensen,
//    sum_o W_o |t - o|_2 <= sqrt(sum_i h2(t_i)) with h2(t) = (1-s)t^2 + s(1-t)^2 <= 1/4 (h2(t) - 1/4
//    = (t - 1/2)(t + 1/2 - 2s), and on [0, 1/2] the convex s lies below the line t/2 + 1/4,
//    which it meets at t = 1/2; h2(1 - t) = h2(t)), so
//    B_d = |g|max sqrt(d)/2. It is attained only by sets holding the diagonals; ours do not, and
//    a computer-assisted proof gives a tighter B_d (more contrast): an interval branch and bound
//    over [0, 1/2]^d (F is symmetric under t_i -> 1 - t_i and, S being closed under coordinate
//    permutations, under permutations) with outward rounding shows F <= 0.5/NoiseScale(d)
//    everywhere. It is the test "noise scale: computer-assisted proof" (tests/vm/numbers/noise_test.cpp),
//    which also checks the symmetries of the sets. The sets and the proven bounds (and the
//    largest F found by local search, i.e. how tight each B_d is):
//      d = 2: 8 unit vectors at odd multiples of 22.5 deg:   B_2 = 0.665  (sup F ~ 0.66082)
//      d = 3: the 12 edge vectors (+-1, +-1, 0) permuted:    B_3 = 1.05   (sup F ~ 1.03636)
//      d = 4: the 24 vectors (+-1, +-1, 0, 0) permuted:      B_4 = 1.125  (sup F ~ 1.07346)
//    The analytic bound for these sets (0.707, 1.225, 1.414) is 6, 17 and 26 % larger: that much
//    less contrast. (Sets holding the diagonals reach it, with the same spread of raw.)
//
// Sources: Perlin, "An image synthesizer" (SIGGRAPH 1985) and "Improving noise" (SIGGRAPH 2002)
// for gradient noise, the quintic fade and edge-vector gradients; the RenderMan Interface
// Specification 3.2 for noise/pnoise/cellnoise; Heidrich & Seidel, "Ray-tracing procedural
// displacement shaders" (GI 1998) for bounding noise cell by cell in affine arithmetic.
#pragma once

#include <algorithm>
#include <bit>
#include <cstdint>
#include <limits>
#include <type_traits>

#include "vm/numbers/number.h"
#include "vm/numbers/quad_form.h"

namespace affray::vm {

/// At most this many lattice cells are bounded one by one (see the head comment).
inline constexpr int kNoiseCellCap = 16;
/// A cell's local coordinate is not clamped when its range overhangs [0, 1] by at most this.
inline constexpr double kNoiseOverhang = 1.0 / 16;

/// How GradientNoise bounds a region (the bench compares them; Noise and PNoise use Auto).
enum class NoiseBoundMethod {
    Auto,        ///< Local for Affine and ReducedAffine, Polynomial for every other type
    Polynomial,  ///< each touched cell's polynomial evaluated in T arithmetic
    Local,       ///< each touched cell's polynomial in a LocalForm (Interval, Affine, ReducedAffine)
};

/// A gradient set: `count` vectors of `dims` components, row by row.
struct NoiseGradientSet {
    int dims;
    int count;
    const double* components;
    /// The largest |component| (the fallback's per-component range).
    double componentBound;
};
/// The gradient set of dims = 1..4 coordinates.
const NoiseGradientSet& NoiseGradients(int dims);
/// 0.5 / B_dims (see the head comment): raw * NoiseScale(dims) lies in [-0.5, 0.5].
double NoiseScale(int dims);

namespace noise_detail {

/// Which function a hash is for: noise (and pnoise) gradients or cellnoise values.
enum class HashKind : uint64_t { Gradient = 1, Cell = 2 };

/// The integer lattice coordinate of a cell floor value k (an integral finite double): k itself,
/// saturated to +-2^62 (far beyond 2^53, where every double is an integer anyway).
int64_t CellIndex(double k);
/// max(1, round(period)) saturated to 2^62, for a finite period.
int64_t PeriodOf(double period);
/// A 64-bit hash of the lattice point c[0..dims) for (kind, dims, seed).
uint64_t HashLattice(const int64_t* c, int dims, uint32_t seed, HashKind kind);
/// The gradient of lattice point c: `dims` components into g.
void LatticeGradient(const int64_t* c, int dims, uint32_t seed, double* g);
/// The cellnoise value of cell c, in [0, 1).
double CellValue(const int64_t* c, int dims, uint32_t seed);

/// x unchanged where its range lies in [-slack, 1 + slack] or is unbounded (NaN stays NaN),
/// else Max(Min(x, 1), 0).
template <class T>
T ClampUnit(const T& x, double slack = 0) {
    Interval r = RangeOf(ValueOf(x));
    if ((r.lo() >= -slack && r.hi() <= 1 + slack) || r.isUnbounded()) return x;
    return Max(Min(x, T(1.0)), T(0.0));
}

/// acc + g*x (acc = g*x for the first term). Components 0, 1 and -1 (most of the edge-vector
/// sets') skip the product: the same double results, fewer bounded operations. Fallback
/// gradients (T ranges) always multiply.
template <class T>
void AddTerm(T& acc, bool& any, double g, const T& x) {
    if (g == 0) return;
    if (g == 1 || g == -1) {
        acc = any ? (g == 1 ? acc + x : acc - x) : (g == 1 ? x : -x);
    } else {
        acc = any ? acc + g * x : g * x;
    }
    any = true;
}
template <class T, class G>
void AddTerm(T& acc, bool& any, const G& g, const T& x) {
    acc = any ? acc + g * x : g * x;
    any = true;
}

/// The fade s(t) = 6t^5 - 15t^4 + 10t^3, as every type computes it.
template <class T>
T Fade(const T& x) {
    return x * x * x * (x * (x * 6.0 - 15.0) + 10.0);
}

/// The cell polynomial's lerp v0 + s (v1 - v0) in T's arithmetic (QuadraticCellOnRegion lerps
/// its QuadForms by Lerp, whose remainder is a convex combination of the ends').
template <class T>
T CellLerp(const T& v0, const T& v1, const T& s) {
    return v0 + s * (v1 - v0);
}

/// raw(t) of one cell given the fades of its local coordinates, fade[i] = Fade(t[i]) (see
/// CellPolynomial).
template <class T, class GradientOf>
T FadedCellPolynomial(const T* t, const T* fade, int dims, GradientOf&& gradient) {
    T offset[4][2];  // t_i - o_i
    for (int i = 0; i < dims; ++i) {
        offset[i][0] = t[i];
        offset[i][1] = t[i] - 1.0;
    }
    T v[16];
    const int corners = 1 << dims;
    for (int o = 0; o < corners; ++o) {
        T acc(0.0);
        bool any = false;
        for (int i = 0; i < dims; ++i) AddTerm(acc, any, gradient(o, i), offset[i][(o >> i) & 1]);
        v[o] = acc;
    }
    // Lerp away dimension 0, then 1, ...: v[o] + s_i (v[o + 2^i] - v[o]) over the remaining o.
    for (int i = 0, n = corners; i < dims; ++i) {
        n >>= 1;
        for (int j = 0; j < n; ++j) v[j] = CellLerp(v[2 * j], v[2 * j + 1], fade[i]);
    }
    return v[0];
}

/// raw(t) of one cell: gradient(o, i) gives component i of corner o's gradient (a double or a
/// T); corners are numbered by bits, bit i set for o_i = 1.
template <class T, class GradientOf>
T CellPolynomial(const T* t, int dims, GradientOf&& gradient) {
    T fade[4];
    for (int i = 0; i < dims; ++i) fade[i] = Fade(t[i]);
    return FadedCellPolynomial(t, fade, dims, gradient);
}

/// Whether T can bound cells by LocalForm (the bounded types without derivatives: a Dual's
/// derivatives would need forms of their own; double is the reference and never bounds), and
/// whether it does by default (NoiseBoundMethod::Auto): Affine and ReducedAffine, see the head
/// comment.
template <class T>
inline constexpr bool kLocalNoise = false;
template <>
inline constexpr bool kLocalNoise<Interval> = true;
template <>
inline constexpr bool kLocalNoise<Affine> = true;
template <>
inline constexpr bool kLocalNoise<ReducedAffine> = true;
template <class T>
inline constexpr bool kLocalNoiseByDefault = false;
template <>
inline constexpr bool kLocalNoiseByDefault<Affine> = true;
template <>
inline constexpr bool kLocalNoiseByDefault<ReducedAffine> = true;

/// An affine form over one cell's part of a region (see the head comment, "Bounds"):
///     x = c0 + sum_k c[k]*sigma_k +- e,    every sigma_k in [-1, 1], e >= 0,
/// where sigma_0..sigma_{dims-1} stand for the local coordinates (t_i = centre_i +
/// reach_i*sigma_i) and the later slots for fresh symbols, one per product (a product's whole
/// remainder, rounding included, goes on its own symbol, as in vm/numbers/affine.cpp). Dense storage of
/// the first n slots (zeros where a symbol is absent): no sorting, no enclosure, no capacity
/// folding (a cell polynomial makes at most 31 products, all of which fit), all inline, which is
/// what makes it several times cheaper than Affine.
/// Contract (Affine's): for every sigma, the double result of the same operation on any operand
/// values the operand forms allow at sigma lies in the result form at sigma, rounding included.
/// The error formulas are vm/numbers/affine.cpp's (vm/numbers/rounding.h's LinearError, Scale, MulForms), with
/// the term slack of kSlots terms.
struct LocalForm {
    static constexpr int kSlots = 4 + 32;
    /// Roundings per term of a sum of kSlots terms, doubled (vm/numbers/affine.cpp's kTermSlack).
    static constexpr double kTermSlack = 2.0 * kSlots + 4.0;

    double c0 = 0;
    double e = 0;
    int n = 0;  // c[0..n) are set
    double c[kSlots];

    LocalForm() = default;
    LocalForm(double x) : c0(x) {}  // NOLINT: implicit, as CellPolynomial's T(0.0) and mixed ops
    /// Copies copy the slots in use only.
    LocalForm(const LocalForm& x) { copyFrom(x); }
    LocalForm& operator=(const LocalForm& x) {
        if (this != &x) copyFrom(x);
        return *this;
    }
    void copyFrom(const LocalForm& x) {
        c0 = x.c0;
        e = x.e;
        n = x.n;
        for (int k = 0; k < n; ++k) c[k] = x.c[k];
    }

    /// Restarts the fresh symbols after the `dims` coordinates' slots.
    static void Begin(int dims) { NextFresh() = dims; }
    /// centre + reach*sigma_i exactly (reach >= 0), i < the dims given to Begin.
    static LocalForm Coordinate(double centre, double reach, int i) {
        LocalForm r(centre);
        r.n = i + 1;
        for (int k = 0; k < i; ++k) r.c[k] = 0;
        r.c[i] = reach;
        return r;
    }
    /// The next fresh symbol's slot (kSlots when none is left). Every form's n is at most it.
    static int& NextFresh() {
        static thread_local int next = 0;
        return next;
    }

    bool isConstant() const { return n == 0 && e == 0; }
    /// sum |c[k]|, rounded to nearest (the callers' kSumSlack covers it).
    double termSum() const {
        double s = 0;
        for (int k = 0; k < n; ++k) s += std::fabs(c[k]);
        return s;
    }

    friend LocalForm operator-(const LocalForm& x) {
        LocalForm r;
        r.c0 = -x.c0;
        r.e = x.e;
        r.n = x.n;
        for (int k = 0; k < x.n; ++k) r.c[k] = -x.c[k];
        return r;
    }
    /// x = x + y (x - y with kSubtract) written into x, without a copy; x and y distinct.
    template <bool kSubtract>
    static void AddInPlace(LocalForm& x, const LocalForm& y) {
        const bool constant = x.isConstant() && y.isConstant();
        x.c0 = kSubtract ? x.c0 - y.c0 : x.c0 + y.c0;
        if (constant) return;  // the double operation itself (x.n = 0, x.e = 0 already)
        const int common = std::min(x.n, y.n);
        double absSum = std::fabs(x.c0);
        for (int k = 0; k < common; ++k) {
            x.c[k] = kSubtract ? x.c[k] - y.c[k] : x.c[k] + y.c[k];
            absSum += std::fabs(x.c[k]);
        }
        for (int k = common; k < x.n; ++k) absSum += std::fabs(x.c[k]);
        for (int k = common; k < y.n; ++k) {
            x.c[k] = kSubtract ? -y.c[k] : y.c[k];
            absSum += std::fabs(x.c[k]);
        }
        x.n = std::max(x.n, y.n);
        x.e = LinearError(x.e + y.e, absSum);
    }
    template <bool kSubtract>
    static LocalForm Add(const LocalForm& x, const LocalForm& y) {
        LocalForm r = x;
        AddInPlace<kSubtract>(r, y);
        return r;
    }
    friend LocalForm operator+(const LocalForm& x, const LocalForm& y) { return Add<false>(x, y); }
    friend LocalForm operator-(const LocalForm& x, const LocalForm& y) { return Add<true>(x, y); }
    friend LocalForm operator+(const LocalForm& x, double k) {
        LocalForm r = x;
        r.c0 = x.c0 + k;
        if (x.isConstant()) return r;
        r.e = LinearError(x.e, std::fabs(r.c0) + x.termSum());
        return r;
    }
    friend LocalForm operator-(const LocalForm& x, double k) { return x + (-k); }
    /// vm/numbers/affine.cpp's Scale.
    friend LocalForm operator*(const LocalForm& x, double k) {
        if (k == 0) return LocalForm(0.0);
        if (k == 1) return x;
        if (k == -1) return -x;
        LocalForm r(x.c0 * k);
        if (x.isConstant()) return r;
        r.n = x.n;
        double absSum = std::fabs(r.c0);
        for (int i = 0; i < x.n; ++i) {
            r.c[i] = x.c[i] * k;
            absSum += std::fabs(r.c[i]);
        }
        r.e = LinearError(std::fabs(k) * x.e * (1 + kEpsilon), absSum) + kUnderflowSlack;
        return r;
    }
    friend LocalForm operator*(double k, const LocalForm& x) { return x * k; }
    /// vm/numbers/affine.cpp's MulForms: center x0*y0 + (1/2) sum xk*yk, coefficients x0*yk + y0*xk, and
    /// the remainder (rx + ex)(ry + ey) - (1/2) sum |xk*yk| + |x0| ey + |y0| ex plus rounding on a
    /// fresh symbol (in e when none is left).
    friend LocalForm operator*(const LocalForm& x, const LocalForm& y) {
        if (x.isConstant()) return y * x.c0;
        if (y.isConstant()) return x * y.c0;
        const double x0 = x.c0, y0 = y.c0;
        LocalForm r;
        const int common = std::min(x.n, y.n);
        double rx = 0, ry = 0, diag = 0, absDiag = 0, absSum = 0;
        for (int k = 0; k < common; ++k) {
            const double xk = x.c[k], yk = y.c[k];
            const double p = xk * yk;
            diag += p;
            absDiag += std::fabs(p);
            rx += std::fabs(xk);
            ry += std::fabs(yk);
            r.c[k] = x0 * yk + y0 * xk;
            absSum += std::fabs(r.c[k]);
        }
        for (int k = common; k < x.n; ++k) {
            rx += std::fabs(x.c[k]);
            r.c[k] = y0 * x.c[k];
            absSum += std::fabs(r.c[k]);
        }
        for (int k = common; k < y.n; ++k) {
            ry += std::fabs(y.c[k]);
            r.c[k] = x0 * y.c[k];
            absSum += std::fabs(r.c[k]);
        }
        r.n = std::max(x.n, y.n);
        r.c0 = x0 * y0 + 0.5 * diag;
        absSum += std::fabs(r.c0);
        const double delta = ProductRemainder({x0, y0, rx, ry, x.e, y.e, diag, absDiag, absSum}, kTermSlack);
        int& fresh = NextFresh();
        if (fresh < kSlots) {
            for (int k = r.n; k < fresh; ++k) r.c[k] = 0;
            r.c[fresh] = delta;
            r.n = ++fresh;
        } else {
            r.e = delta;
        }
        return r;
    }
};

/// FadedCellPolynomial on LocalForms with double gradients g[o]: the same operations on the same
/// operands in the same order (so the same forms, and the double reference is the template's),
/// written into their slots instead of through temporaries and copies (a LocalForm is 37 doubles;
/// the teapot of bench/real renders in 0.96 times the time): corner values accumulate in place,
/// and each lerp works in the slots of its level (stride 2^i) rather than moving them down.
inline LocalForm FadedCellPolynomialInPlace(const LocalForm* t, const LocalForm* fade, int dims, const double (*g)[4]) {
    LocalForm below[4];  // t_i - 1
    for (int i = 0; i < dims; ++i) below[i] = t[i] - 1.0;
    LocalForm v[16];
    const int corners = 1 << dims;
    for (int o = 0; o < corners; ++o) {
        // AddTerm's sum g_o . (t - o), term by term.
        LocalForm& acc = v[o];
        bool any = false;
        for (int i = 0; i < dims; ++i) {
            const double gi = g[o][i];
            if (gi == 0) continue;
            const LocalForm& x = (o >> i) & 1 ? below[i] : t[i];
            if (!any) {
                acc = gi == 1 ? x : gi == -1 ? -x : gi * x;
            } else if (gi == 1) {
                LocalForm::AddInPlace<false>(acc, x);
            } else if (gi == -1) {
                LocalForm::AddInPlace<true>(acc, x);
            } else {
                LocalForm::AddInPlace<false>(acc, gi * x);
            }
            any = true;
        }
        if (!any) acc = LocalForm(0.0);
    }
    // Lerp away dimension 0, then 1, ...: v[a] + s_i (v[b] - v[a]), a and b the slots of a pair.
    for (int i = 0, stride = 1; i < dims; ++i, stride *= 2)
        for (int a = 0; a < corners; a += 2 * stride) {
            const int b = a + stride;
            LocalForm::AddInPlace<true>(v[b], v[a]);
            LocalForm::AddInPlace<false>(v[a], fade[i] * v[b]);
        }
    return v[0];
}

/// One coordinate of the part of a region inside one cell, for LocalCell: the cell's local
/// coordinate over it, t_i = centre + reach*sigma_i, and the fade of t_i as a form in sigma_i and
/// one symbol of its own, fade0 + fadeLinear*sigma_i + fadeOwn*eps +- fadeError. The fade depends
/// only on the coordinate and its cell index k_i, so the cells of a region that share k_i share it
/// (a region straddling a face in each of d dimensions has 2^d cells but 2d axes).
/// The own symbol stands for the fade's nonlinear part, a function of sigma_i alone (MakeLocalAxis):
/// within a cell it appears only in that fade, and every later use multiplies it by one number,
/// so it is carried as a symbol of its own would be.
struct LocalAxis {
    double centre, reach;
    double fade0, fadeLinear, fadeOwn, fadeError;
};

/// The fade's Taylor coefficients at c in [0, 1], s^(k)(c)/k! for k = 0..4 (the fifth is 6), as
/// doubles compute them, and the magnitudes of their terms (each within 16 ulps of its exact value
/// relative to these: at most nine roundings).
struct FadeTaylor {
    double a[5], m[5];
};
inline FadeTaylor FadeTaylorAt(double c) {
    const double c2 = c * c, c3 = c2 * c;
    return {{c3 * (c * (c * 6.0 - 15.0) + 10.0), 30.0 * c2 * (c - 1.0) * (c - 1.0), c * (c * (60.0 * c - 90.0) + 30.0),
             c * (60.0 * c - 60.0) + 10.0, 30.0 * c - 15.0},
            {c3 * (c * (c * 6.0 + 15.0) + 10.0), 30.0 * c2 * (c2 + 2.0 * c + 1.0), c * (c * (60.0 * c + 90.0) + 30.0),
             c * (60.0 * c + 60.0) + 10.0, 30.0 * c + 15.0}};
}

/// The LocalAxis of coordinate p (a bound) in the cell whose index along it is k.
/// B holds every t_d = p - k in double: Interval subtraction contains the double one.
/// The fade over B is its Taylor polynomial at the centre c in sigma (t = c + reach sigma), in
/// closed form: s(c + h) = sum_k q_k sigma^k with q_k = s^(k)(c)/k! reach^k, k <= 5, whose
/// constant and linear terms make fade0 and fadeLinear (sigma^2 and sigma^4 as 0.5 +- 0.5, sigma^3
/// as 0.75 sigma +- 0.25, sigma^5 as +-1) and the rest fadeOwn: a function of sigma alone, so one
/// symbol of the coordinate's own holds it. fadeError holds the rounding of the q_k and of the sums,
/// and that of Fade in doubles at any t_d of B (at most 8 roundings of 6 t^5 + 15 t^4 + 10 t^3).
/// Cheaper than the fade in LocalForm arithmetic (five products) and no wider.
template <class T>
LocalAxis MakeLocalAxis(const T& p, double k) {
    LocalAxis axis;
    const Interval r = RangeOf(p) - k;
    const double lo = std::clamp(r.lo(), 0.0, 1.0), hi = std::clamp(r.hi(), 0.0, 1.0);
    axis.centre = 0.5 * (lo + hi);  // between lo and hi: both are in [0, 1]
    axis.reach = std::fmax(SubUp(axis.centre, lo), SubUp(hi, axis.centre));
    const double c = axis.centre, h = axis.reach;  // both in [0, 1]
    const double h2 = h * h, h3 = h2 * h, h4 = h3 * h, h5 = h4 * h;
    const FadeTaylor taylor = FadeTaylorAt(c);
    const double a0 = taylor.a[0], a1 = taylor.a[1], a2 = taylor.a[2], a3 = taylor.a[3], a4 = taylor.a[4];
    const double m0 = taylor.m[0], m1 = taylor.m[1], m2 = taylor.m[2], m3 = taylor.m[3], m4 = taylor.m[4];
    const double q0 = a0, q1 = a1 * h, q2 = a2 * h2, q3 = a3 * h3, q4 = a4 * h4, q5 = 6.0 * h5;
    axis.fade0 = q0 + 0.5 * q2 + 0.5 * q4;
    axis.fadeLinear = q1 + 0.75 * q3;
    UpperSum own;
    own.add(0.5 * std::fabs(q2));
    own.add(0.25 * std::fabs(q3));
    own.add(0.5 * std::fabs(q4));
    own.add(std::fabs(q5));
    axis.fadeOwn = own.value();
    // Each q_k is within 16 ulps of its exact value relative to its terms' magnitudes (at most
    // nine roundings); the two sums round by 3 ulps of their terms; Fade in doubles by 8 ulps of
    // 6 t^5 + 15 t^4 + 10 t^3 <= 31 hi^3 (t <= hi <= 1). Underflow adds at most a few 2^-1074.
    const double coefficients = m0 + m1 * h + m2 * h2 + m3 * h3 + m4 * h4 + 6.0 * h5;
    const double sums =
        std::fabs(q0) + std::fabs(q1) + 0.5 * std::fabs(q2) + 0.75 * std::fabs(q3) + 0.5 * std::fabs(q4);
    const double scalar = 31.0 * hi * hi * hi;
    axis.fadeError =
        (16 * kEpsilon * coefficients + 4 * kEpsilon * sums + 8 * kEpsilon * scalar + 0x1p-1060) * (1 + 0x1p-40);
    return axis;
}

/// One coordinate of a reduced affine region in one cell, for QuadraticCellOnRegion: the cell's
/// local coordinate t = p - k and its fade, as QuadForms on eps_u and eps_v.
struct QuadAxis {
    QuadForm t, fade;
};

/// The QuadAxis of reduced affine coordinate p in the cell whose index along it is k; the
/// coordinate's QuadForm symbols are own (its fade's terms beyond second order) and kOwn/2 + own
/// (its error). The double t_d = p_d - k at a point of the region is tc + L + xi xi_own, with
/// tc = p's centre - k (rounded), L = a eps_u + b eps_v (p's coefficients), xi = p's error plus
/// the roundings of tc and t_d, and xi_own in [-1, 1] a function of the point: that is the form t.
/// The fade is needed only at the points of the region inside this cell, whose t_d lie in the
/// part [lo, hi] of [0, 1] that p - k reaches (as in MakeLocalAxis): with c its centre and R its
/// reach, delta = t_d - c is in [-R, R] there, and s(c + delta) = sum q_k delta^k (q_k =
/// s^(k)(c)/k!, k <= 5) is reduced in sigma = delta/R in [-1, 1]: delta^3 = 0.75 R^2 delta +-
/// 0.25 R^3, delta^4 = R^2 delta^2 - R^4/8 +- R^4/8, delta^5 = +-R^5 (these remainders are a
/// function of delta alone: the own symbol). What is left, a0 + a1 delta + a2 delta^2, is
/// written on eps_u and eps_v through delta = (tc - c) + L + xi xi_own: a1 delta exactly (the
/// rounding of tc - c aside), a2 delta^2 but for the terms in xi, at most |a2| xi (2R + 3xi),
/// which go to the error. A part clipped to the
/// cell keeps a region straddling a face from paying for the cell polynomial's continuation past
/// it (the neighbouring cell bounds those points). The rounding: of each q_k (16 ulps of its
/// terms' magnitudes, as in MakeLocalAxis), of the form's coefficients (8 ulps of their
/// magnitudes), and of Fade in doubles at any t_d of the part (8 ulps of 6 t^5 + 15 t^4 + 10 t^3
/// <= 31 hi^3).
inline QuadAxis MakeQuadAxis(const ReducedAffine& p, double k, int own) {
    const double tc = p.center() - k;
    const double a = p.coefficientU(), b = p.coefficientV();
    const double xi = AddUp(AddUp(p.error(), std::fabs(tc) * kEpsilon), kEpsilon);
    QuadAxis axis{};
    axis.t = QuadForm::Linear(tc, a, b, 0.0);
    axis.t.o[QuadForm::kOwn / 2 + own] = xi;  // the point's own deviation from tc + L
    const Interval range = RangeOf(p) - k;
    const double lo = std::clamp(range.lo(), 0.0, 1.0), hi = std::clamp(range.hi(), 0.0, 1.0);
    const double c = 0.5 * (lo + hi);  // in [0, 1]
    const double R = std::max(SubUp(c, lo), SubUp(hi, c));
    const double offset = tc - c;                                     // rounded: an ulp of it, in xiOffset
    const double xiOffset = AddUp(xi, std::fabs(offset) * kEpsilon);  // delta = offset + L +- xiOffset
    const FadeTaylor taylor = FadeTaylorAt(c);
    const double q0 = taylor.a[0], q1 = taylor.a[1], q2 = taylor.a[2], q3 = taylor.a[3], q4 = taylor.a[4];
    const double m0 = taylor.m[0], m1 = taylor.m[1], m2 = taylor.m[2], m3 = taylor.m[3], m4 = taylor.m[4];
    const double R2 = R * R, R3 = R2 * R, R4 = R3 * R, R5 = R4 * R;
    double alpha0 = q0 - 0.125 * q4 * R4, alpha1 = q1 + 0.75 * q3 * R2, alpha2 = q2 + q4 * R2;
    double ownPart = 0.25 * std::fabs(q3) * R3 + 0.125 * std::fabs(q4) * R4 + 6.0 * R5;
    if (range.lo() < 0 || range.hi() > 1) {
        // A straddling region: a quadratic in eps_u, eps_v would be ranged over the whole region
        // at the end, where past the face |delta| exceeds R; delta^2 = R^2/2 +- R^2/2 instead.
        alpha0 += 0.5 * alpha2 * R2;
        ownPart += 0.5 * std::fabs(alpha2) * R2;
        alpha2 = 0;
    }
    QuadForm& f = axis.fade;
    f.c[QuadForm::k0] = alpha0 + alpha1 * offset + alpha2 * (offset * offset);
    f.c[QuadForm::kU] = alpha1 * a + alpha2 * (2 * offset * a);
    f.c[QuadForm::kV] = alpha1 * b + alpha2 * (2 * offset * b);
    f.c[QuadForm::kUU] = alpha2 * (a * a);
    f.c[QuadForm::kUV] = alpha2 * (2 * a * b);
    f.c[QuadForm::kVV] = alpha2 * (b * b);
    f.o[own] = ownPart * kSumSlack;
    // delta = offset + L + xi xi_own (xi_own the coordinate's symbol) exactly but for the rounding
    // of offset: alpha1 delta puts alpha1 xi on the symbol; the rest is error.
    f.o[QuadForm::kOwn / 2 + own] = alpha1 * xi;
    const double perturbed = std::fabs(alpha1) * std::fabs(offset) * kEpsilon + std::fabs(alpha1 * xi) * kEpsilon +
                             std::fabs(alpha2) * xiOffset * (2 * R + 3 * xiOffset);
    const double coefficients = m0 + m1 * R + m2 * R2 + m3 * R3 + m4 * R4 + 6.0 * R5;
    const double d = std::fabs(offset) + std::fabs(a) + std::fabs(b);  // the largest |offset + L|
    const double formed = std::fabs(alpha0) + std::fabs(alpha1) * d + std::fabs(alpha2) * d * d + std::fabs(q3) * R3 +
                          std::fabs(q4) * R4 + f.coefficientSum();
    const double scalar = 31.0 * hi * hi * hi;
    f.r = (perturbed + (16 * coefficients + 8 * formed + 8 * scalar) * kEpsilon) * kSumSlack + kUnderflowSlack;
    return axis;
}

/// One cell's noise value before the final clamp, raw * NoiseScale(dims) + 0.5, over a reduced
/// affine region, by the cell polynomial in QuadForm arithmetic (vm/numbers/quad_form.h) on the
/// region's own eps_u and eps_v: the operations of FadedCellPolynomial in its order (so each
/// form contains the double result at every point of the region in this cell, rounding
/// included; each lerp by Lerp, valid there since the fades lie in [0, 1]). Second order is kept
/// exactly through the fades and the lerps, so the error left is the quadratic part's range over
/// the region, the truncated higher orders and the rounding: about the noise's own deviation
/// from its plane (tests/vm/numbers/noise_test.cpp).
[[gnu::flatten]] inline ReducedAffine QuadraticCellOnRegion(const QuadAxis* const* axes, int dims,
                                                            const double (*g)[4]) {
    // The corner values g_o . (t - o), linear in eps_u, eps_v and the coordinates' own symbols
    // since each t_i is, with their coefficients summed in FadedCellPolynomial's order (offset
    // t_i - o_i, then the terms of AddTerm: a component +-1 adds or subtracts, 0 skips), so each
    // is the double that order gives. The remainder bounds the rounding of the double corner
    // value at any point of the region (at most 3 dims roundings: the offsets, the products and
    // the sums, each of at most M = sum |g_i| (|tc_i| + o_i + |a_i| + |b_i| + own_i + r_i) and a
    // little) and of these coefficients against the exact ones (at most 3 dims for the constant,
    // 2 dims each for the slopes and one for the own terms, each of at most M): (10 dims + 2) u M.
    QuadForm v[16];
    QuadSums vs[16];
    double tMagnitude[4];  // |tc_i| + 1 + sum |t_i's coefficients| + r_i
    for (int i = 0; i < dims; ++i) {
        const QuadForm& t = axes[i]->t;
        tMagnitude[i] = std::fabs(t.c[QuadForm::k0]) + 1.0 + t.coefficientSum() + t.r;
    }
    const int corners = 1 << dims;
    for (int o = 0; o < corners; ++o) {
        // (g_i x is exactly +-x for a component +-1, and 0 + x is x: the same doubles.)
        QuadForm& z = v[o];
        z = QuadForm{};
        double r = 0, magnitude = 0;
        for (int i = 0; i < dims; ++i) {
            const double gi = g[o][i];
            if (gi == 0) continue;
            const QuadForm& t = axes[i]->t;
            z.c[QuadForm::k0] += gi * ((o >> i) & 1 ? t.c[QuadForm::k0] - 1.0 : t.c[QuadForm::k0]);
            for (int k = QuadForm::kU; k < QuadForm::kCount; ++k) z.c[k] += gi * t.c[k];
            for (int k = 0; k < QuadForm::kOwn; ++k) z.o[k] += gi * t.o[k];
            const double ag = std::fabs(gi);
            r += ag * t.r;
            magnitude += ag * tMagnitude[i];
        }
        z.r = (r + (10 * dims + 2) * kEpsilon * magnitude) * kSumSlack + kUnderflowSlack;
        vs[o] = SumsOf(z);
    }
    // Lerp away dimension 0, then 1, ... (FadedCellPolynomial), each fade's sums computed once.
    for (int i = 0, n = corners; i < dims; ++i) {
        n >>= 1;
        const QuadForm& s = axes[i]->fade;
        const QuadSums ss = SumsOf(s);
        for (int j = 0; j < n; ++j) v[j] = Lerp(v[2 * j], vs[2 * j], v[2 * j + 1], vs[2 * j + 1], s, ss, &vs[j]);
    }
    const QuadForm raw = v[0] * NoiseScale(dims) + 0.5;
    double lo, hi;
    raw.quadraticRange(&lo, &hi);
    const double quadratic =
        std::fabs(raw.c[QuadForm::kUU]) + std::fabs(raw.c[QuadForm::kUV]) + std::fabs(raw.c[QuadForm::kVV]);
    const double mid = 0.5 * (lo + hi), center = raw.c[QuadForm::k0] + mid;
    const double error = (raw.r + raw.ownSum() + 0.5 * (hi - lo) +
                          (8 * quadratic + std::fabs(raw.c[QuadForm::k0]) + std::fabs(center)) * kEpsilon) *
                             kSumSlack +
                         kUnderflowSlack;
    return ReducedAffine::FromForm(center, raw.c[QuadForm::kU], raw.c[QuadForm::kV], error);
}

/// The part of a reduced affine region that can lie in one lattice cell, as a box of its eps:
/// eps_u = mu + su sigma_u, eps_v = mv + sv sigma_v with sigma in [-1, 1]^2.
struct CellPart {
    double mu, su, mv, sv;
};

/// The CellPart of cell k (its lowest corner) for coordinates p[0..dims): the bounding box of
/// the eps in [-1, 1]^2 at which some value of every p_i's form lies in [k_i, k_i + 1], the
/// square clipped by 2 dims half-planes (Sutherland-Hodgman), each widened by its coordinate's
/// error and far more than the rounding of its evaluation, and the box by far more than that of
/// the vertices (each a convex combination of two, computed without cancellation). False if no
/// eps can reach the cell: a plane through a box of cells meets only some of them.
inline bool CellPartOf(const ReducedAffine* p, const double* k, int dims, CellPart* part) {
    constexpr int kMaxVertices = 4 + 2 * 4;
    double xs[2][kMaxVertices + 1], ys[2][kMaxVertices + 1];
    int n = 4, from = 0;
    const double squareX[4] = {-1, 1, 1, -1}, squareY[4] = {-1, -1, 1, 1};
    for (int i = 0; i < 4; ++i) xs[0][i] = squareX[i], ys[0][i] = squareY[i];
    for (int i = 0; i < dims; ++i) {
        const double c = p[i].center(), a = p[i].coefficientU(), b = p[i].coefficientV();
        const double slack = p[i].error() + 1e-12 * (std::fabs(c) + std::fabs(a) + std::fabs(b) + std::fabs(k[i]) + 1);
        for (int side = 0; side < 2; ++side) {
            // Keep offset + sign (a x + b y) >= 0: c + a x + b y >= k_i, or <= k_i + 1.
            const double sign = side == 0 ? 1.0 : -1.0;
            const double offset = (side == 0 ? c - k[i] : k[i] + 1 - c) + slack;
            const double *x = xs[from], *y = ys[from];
            double *outX = xs[1 - from], *outY = ys[1 - from];
            int m = 0;
            for (int v = 0; v < n; ++v) {
                const int w = v + 1 == n ? 0 : v + 1;
                const double gv = offset + sign * (a * x[v] + b * y[v]), gw = offset + sign * (a * x[w] + b * y[w]);
                if (gv >= 0) outX[m] = x[v], outY[m++] = y[v];
                if ((gv >= 0) != (gw >= 0)) {
                    const double t = gv / (gv - gw);  // opposite signs: no cancellation
                    outX[m] = x[v] + t * (x[w] - x[v]);
                    outY[m++] = y[v] + t * (y[w] - y[v]);
                }
            }
            n = m;
            from = 1 - from;
            if (n == 0) return false;
        }
    }
    double u0 = INFINITY, u1 = -INFINITY, v0 = INFINITY, v1 = -INFINITY;
    for (int v = 0; v < n; ++v) {
        u0 = std::min(u0, xs[from][v]);
        u1 = std::max(u1, xs[from][v]);
        v0 = std::min(v0, ys[from][v]);
        v1 = std::max(v1, ys[from][v]);
    }
    constexpr double kMargin = 1e-12;
    u0 = std::max(-1.0, u0 - kMargin), u1 = std::min(1.0, u1 + kMargin);
    v0 = std::max(-1.0, v0 - kMargin), v1 = std::min(1.0, v1 + kMargin);
    if (!(u0 <= u1 && v0 <= v1)) return false;
    part->mu = 0.5 * (u0 + u1);
    part->su = std::max(u1 - part->mu, part->mu - u0) * (1 + 4 * kEpsilon);
    part->mv = 0.5 * (v0 + v1);
    part->sv = std::max(v1 - part->mv, part->mv - v0) * (1 + 4 * kEpsilon);
    return true;
}

/// x on a CellPart's sigma: x0 + a (mu + su sigma_u) + b (mv + sv sigma_v) +- e, the rounding
/// of the new coefficients (at most 3u of their terms) in the error.
inline ReducedAffine OnCellPart(const ReducedAffine& x, const CellPart& part) {
    const double a = x.coefficientU(), b = x.coefficientV();
    const double am = a * part.mu, bm = b * part.mv, as = a * part.su, bs = b * part.sv;
    const double rounding =
        2 * kEpsilon * (std::fabs(x.center()) + std::fabs(am) + std::fabs(bm) + std::fabs(as) + std::fabs(bs));
    return ReducedAffine::FromForm(x.center() + am + bm, as, bs, (x.error() + rounding) * kSumSlack + kUnderflowSlack);
}

/// A cell's bound r on its part's sigma, as a plane in the region's eps valid over the part's box,
/// c + a eps_u + b eps_v +- e (a = r's sigma_u coefficient / su; its rounding and that of c, at most
/// 4u of their terms over the box, in e), with r's range.
struct CellPiece {
    CellPart part;
    double c, a, b, e;
    Interval range;
};

inline CellPiece PieceOnRegion(const ReducedAffine& r, const CellPart& part) {
    CellPiece piece{part, 0, 0, 0, 0, r.range()};
    const double ru = r.coefficientU(), rv = r.coefficientV();
    double extra = 0;
    // A box of zero width along a parameter fixes it: the sigma term is then any value of its range.
    if (part.su > 0)
        piece.a = ru / part.su;
    else
        extra += std::fabs(ru);
    if (part.sv > 0)
        piece.b = rv / part.sv;
    else
        extra += std::fabs(rv);
    const double am = piece.a * part.mu, bm = piece.b * part.mv;
    piece.c = r.center() - am - bm;
    const double rounding = 2 * kEpsilon *
                            (std::fabs(r.center()) + std::fabs(am) + std::fabs(bm) + std::fabs(piece.a) * part.su +
                             std::fabs(piece.b) * part.sv);
    piece.e = (r.error() + extra + rounding) * kSumSlack + kUnderflowSlack;
    return piece;
}

/// The join of the pieces of a region's cells: the plane their planes average, weighted by their
/// boxes' areas, and the error that holds each piece over its own box: |difference of planes|
/// at most over the box plus the piece's error (not over the whole region, where a small piece's
/// plane would extrapolate far). Enclosed by the hull of the pieces' ranges.
inline ReducedAffine JoinPieces(const CellPiece* pieces, int count) {
    double weight = 0, c = 0, a = 0, b = 0;
    for (int k = 0; k < count; ++k) {
        const double w = pieces[k].part.su * pieces[k].part.sv + 1e-300;
        weight += w;
        c += w * pieces[k].c;
        a += w * pieces[k].a;
        b += w * pieces[k].b;
    }
    c /= weight, a /= weight, b /= weight;
    double error = 0;
    Interval hull = pieces[0].range;
    for (int k = 0; k < count; ++k) {
        const CellPiece& q = pieces[k];
        const double dc = c - q.c, da = a - q.a, db = b - q.b;
        const double at = std::fabs(dc + da * q.part.mu + db * q.part.mv),
                     spread = std::fabs(da) * q.part.su + std::fabs(db) * q.part.sv;
        const double rounding = 2 * kEpsilon *
                                (std::fabs(c) + std::fabs(q.c) + std::fabs(a) + std::fabs(q.a) + std::fabs(b) +
                                 std::fabs(q.b) + at + spread);
        error = std::max(error, at + spread + q.e + rounding);
        hull = Hull(hull, q.range);
    }
    error = error * kSumSlack + kUnderflowSlack;
    if (!(error <= kMaxFinite) || !std::isfinite(c + a + b)) return ReducedAffine::FromInterval(hull);
    return ReducedAffine::Within(ReducedAffine::FromForm(c, a, b, error), hull);
}

/// One cell's noise value before the final clamp, raw * NoiseScale(dims) + 0.5, over a region by
/// LocalForm (see the head comment): p the noise coordinates, k the cell, axes[i] the LocalAxis
/// of p[i] in it, g[o] the gradients of its corners. Contains the double value at every double
/// point of the region that lies in this cell (t_d = p - k in double, in [0, 1]^dims).
template <class T>
T LocalCell(const T* p, const double* k, int dims, const LocalAxis* const* axes, const double (*g)[4]) {
    // Symbols: sigma_i in slot i, the fade of coordinate i's own symbol in slot dims + i, then
    // the fresh symbols of this cell's products.
    LocalForm t[4], fade[4];
    LocalForm::Begin(2 * dims);
    for (int i = 0; i < dims; ++i) {
        const LocalAxis& a = *axes[i];
        t[i] = LocalForm::Coordinate(a.centre, a.reach, i);
        LocalForm& f = fade[i];
        f.c0 = a.fade0;
        f.e = a.fadeError;
        f.n = dims + i + 1;
        for (int s = 0; s < f.n; ++s) f.c[s] = 0;
        f.c[i] = a.fadeLinear;
        f.c[dims + i] = a.fadeOwn;
    }
    // The noise value before its clamp, as the double computes it (GradientNoise's last step).
    const LocalForm raw = FadedCellPolynomialInPlace(t, fade, dims, g) * NoiseScale(dims) + 0.5;
    // value(t_d) = z0 + sum_i z_i sigma_i + (fresh terms, e), sigma_i = (t_d,i - c_i)/reach_i,
    // and t_d,i = p_i - k_i + (its rounding, <= u since t_d,i <= 1):
    //   value(t_d) in sum_i a_i p_i + [z0 - sum_i a_i (k_i + c_i)] +- error
    // with a_i = z_i/reach_i rounded (its rounding times |t_d,i - c_i| <= reach_i is
    // <= 2u |z_i|), the subtraction's rounding |a_i| u, and the fresh terms and e.
    UpperSum error;
    error.add(raw.e);
    Interval constant(raw.c0);
    T linear(0.0);
    bool any = false;
    for (int s = 0; s < raw.n; ++s) {
        const double z = raw.c[s];
        if (z == 0) continue;
        if (s >= dims) {
            error.add(std::fabs(z));
            continue;
        }
        const double a = z / axes[s]->reach;
        error.add(MulUp(std::fabs(z), kEpsilon));
        error.add(MulUp(std::fabs(a), kEpsilon));
        constant = constant - Interval(a) * (Interval(k[s]) + Interval(axes[s]->centre));
        AddTerm(linear, any, a, p[s]);
    }
    const double e = AddUp(error.value(), kUnderflowSlack);
    const T rest = SpreadOf<T>(Interval(SubDown(constant.lo(), e), AddUp(constant.hi(), e)));
    return any ? linear + rest : rest;
}

/// The lattice cells a box of inputs touches: floor(lo_i) .. floor(hi_i) in each coordinate.
struct CellBox {
    double kLo[4] = {0, 0, 0, 0}, count[4] = {1, 1, 1, 1};
    double cells = 1;  // their number (a double: it may be huge)

    /// False if dims is out of 1..4, p is null or an input is unbounded.
    template <class T>
    bool Of(const T* p, int dims) {
        if (p == nullptr || dims < 1 || dims > 4) return false;
        for (int i = 0; i < dims; ++i) {
            Interval r = RangeOf(ValueOf(p[i]));
            if (r.isUnbounded()) return false;
            kLo[i] = std::floor(r.lo());
            count[i] = std::floor(r.hi()) - kLo[i] + 1;
            cells *= count[i];
        }
        return true;
    }

    /// Calls visit(k, j) for each cell k (its lowest corner; j its offsets from kLo) in turn: a
    /// mixed-radix counter.
    template <class Visit>
    void ForEach(int dims, Visit&& visit) const {
        int j[4] = {0, 0, 0, 0};
        for (;;) {
            double k[4] = {0, 0, 0, 0};
            for (int i = 0; i < dims; ++i) k[i] = kLo[i] + j[i];
            visit(k, static_cast<const int*>(j));
            int i = 0;
            while (i < dims && ++j[i] >= count[i]) j[i++] = 0;
            if (i == dims) return;
        }
    }
};

/// Noise and PNoise (period == nullptr for Noise), bounding regions by `method`.
/// Where a coordinate or period may be non-finite the value is unknown, and so are its derivatives:
/// at a finite point of the operand's range noise has a nonzero slope.
template <class T>
T GradientNoise(const T* p, const T* period, int dims, uint32_t seed,
                NoiseBoundMethod method = NoiseBoundMethod::Auto) {
    const auto unknown = [] { return SpreadOf<T>(Interval::Unbounded()); };
    CellBox box;
    if (!box.Of(p, dims)) return unknown();
    int64_t periods[4];
    bool cellwise = box.cells <= kNoiseCellCap;
    for (int i = 0; period && i < dims; ++i) {
        Interval r = RangeOf(ValueOf(period[i]));
        if (r.isUnbounded()) return unknown();
        if (r.isPoint())
            periods[i] = PeriodOf(r.lo());
        else
            cellwise = false;
    }
    bool local = false;
    if constexpr (kLocalNoise<T>)
        local = cellwise &&
                (method == NoiseBoundMethod::Local || (method == NoiseBoundMethod::Auto && kLocalNoiseByDefault<T>));
    T raw(0.0);
    if (cellwise) {
        constexpr bool kQuadratic = std::is_same_v<T, ReducedAffine>;  // QuadraticCellOnRegion
        // The gradients of cell k's corners.
        const auto cornerGradients = [&](const double* k, double(*g)[4]) {
            int64_t cell[4];
            for (int i = 0; i < dims; ++i) cell[i] = CellIndex(k[i]);
            for (int o = 0; o < (1 << dims); ++o) {
                int64_t c[4];
                for (int i = 0; i < dims; ++i) {
                    c[i] = cell[i] + ((o >> i) & 1);
                    if (period) c[i] = ((c[i] % periods[i]) + periods[i]) % periods[i];
                }
                LatticeGradient(c, dims, seed, g[o]);
            }
        };
        bool first = true;
        if constexpr (kQuadratic) {
            // A region straddling faces: each cell bounded over the box of its own part of the
            // region (CellPartOf; the cells the region cannot reach skipped), the pieces joined
            // over their boxes (JoinPieces). Should no cell be reachable (rounding), as below.
            if (local && box.cells > 1) {
                CellPiece pieces[kNoiseCellCap];
                int count = 0;
                box.ForEach(dims, [&](const double* k, const int*) {
                    CellPart part;
                    if (!CellPartOf(p, k, dims, &part)) return;
                    QuadAxis cellQuads[4];
                    const QuadAxis* cellAxes[4];
                    for (int i = 0; i < dims; ++i) {
                        cellQuads[i] = MakeQuadAxis(OnCellPart(p[i], part), k[i], i);
                        cellAxes[i] = &cellQuads[i];
                    }
                    double g[16][4];
                    cornerGradients(k, g);
                    pieces[count++] = PieceOnRegion(QuadraticCellOnRegion(cellAxes, dims, g), part);
                });
                if (count > 0) {
                    raw = JoinPieces(pieces, count);
                    first = false;
                }
            }
        }
        // Local: each coordinate's axes, one per cell index it touches (at most kNoiseCellCap).
        LocalAxis axes[4][kQuadratic ? 1 : kNoiseCellCap];
        QuadAxis quads[4][kQuadratic ? kNoiseCellCap : 1];
        if constexpr (kLocalNoise<T>) {
            if (local && first)
                for (int i = 0; i < dims; ++i)
                    for (int j = 0; j < static_cast<int>(box.count[i]); ++j) {
                        if constexpr (kQuadratic)
                            quads[i][j] = MakeQuadAxis(p[i], box.kLo[i] + j, i);
                        else
                            axes[i][j] = MakeLocalAxis(p[i], box.kLo[i] + j);
                    }
        }
        if (first)
            box.ForEach(dims, [&](const double* k, const int* j) {
                T t[4];
                for (int i = 0; i < dims; ++i)
                    if (!local) t[i] = ClampUnit(T(p[i] - k[i]), kNoiseOverhang);
                double g[16][4];
                cornerGradients(k, g);
                T v(0.0);
                if constexpr (kLocalNoise<T>) {
                    if (local) {
                        if constexpr (kQuadratic) {
                            const QuadAxis* cellAxes[4];
                            for (int i = 0; i < dims; ++i) cellAxes[i] = &quads[i][j[i]];
                            v = QuadraticCellOnRegion(cellAxes, dims, g);
                        } else {
                            const LocalAxis* cellAxes[4];
                            for (int i = 0; i < dims; ++i) cellAxes[i] = &axes[i][j[i]];
                            v = LocalCell(p, k, dims, cellAxes, g);
                        }
                    }
                }
                if (!local) v = CellPolynomial(t, dims, [&](int o, int i) { return g[o][i]; });
                raw = first ? v : Join(raw, v);
                first = false;
            });
    } else {
        T t[4];
        for (int i = 0; i < dims; ++i) t[i] = ClampUnit(T(p[i] - floor(p[i])));
        const double bound = NoiseGradients(dims).componentBound;
        raw = CellPolynomial(t, dims, [&](int, int) { return Join(T(-bound), T(bound)); });
    }
    // (LocalCell has scaled and offset its value already.)
    const T value = local ? raw : T(raw * NoiseScale(dims) + 0.5);
    // Every operand is finite here, so the value is in [0, 1]: a bound that overflowed (p -
    // floor(p) over a range reaching +-1e308) is that range, with unknown derivatives.
    if (RangeOf(ValueOf(value)).isUnbounded()) return SpreadOf<T>(Interval(0.0, 1.0));
    // (A region over more cells than are bounded one by one gets the cell polynomial with the
    // gradients' ranges: in reduced affine arithmetic a form with an error of thousands, which
    // the scaling above and the clamp narrow to their ranges, ReducedAffine::Tighten.)
    return ClampUnit(value);
}

}  // namespace noise_detail

/// RenderMan noise of p[0..dims), dims = 1..4, channel `seed`: values in [0, 1], mean 0.5.
template <class T>
T Noise(const T* p, int dims, uint32_t seed) {
    return noise_detail::GradientNoise<T>(p, nullptr, dims, seed);
}

/// RenderMan pnoise: Noise on a lattice wrapping with period max(1, round(period[i])) per
/// coordinate (uniform values; a bounded period that is not one point gives the cell-independent
/// bound).
template <class T>
T PNoise(const T* p, const T* period, int dims, uint32_t seed) {
    return noise_detail::GradientNoise<T>(p, period, dims, seed);
}

/// RenderMan cellnoise: a value in [0, 1) constant on each cell floor(p[0..dims)), dims = 1..4.
template <class T>
T CellNoise(const T* p, int dims, uint32_t seed) {
    noise_detail::CellBox box;
    if (!box.Of(p, dims)) return T(std::numeric_limits<double>::quiet_NaN());
    if (!(box.cells <= kNoiseCellCap)) return Join(T(0.0), T(1.0));
    T result(0.0);
    bool first = true;
    box.ForEach(dims, [&](const double* k, const int*) {
        int64_t cell[4];
        for (int i = 0; i < dims; ++i) cell[i] = noise_detail::CellIndex(k[i]);
        T v(noise_detail::CellValue(cell, dims, seed));
        result = first ? v : Join(result, v);
        first = false;
    });
    return result;
}

}  // namespace affray::vm
