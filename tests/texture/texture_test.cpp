// tests/texture/texture_test.cpp: lookups of maps made from pixels (texture/lookup.cpp,
// texture/texture_map.cpp) against texture.h: the bilinear formula bit for bit, the fill rules,
// RangeOfTexels against brute force through every wrap mode, and property tests over random small
// maps of every wrap and filter: RangeOver and RangeOverQuad contain every lookup of their region,
// SampleGrad agrees with finite differences and SlopeOver bounds it.
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <limits>
#include <sstream>

#include "tests/test_random.h"
#include "tests/texture/texture_test_util.h"
#include "texture/texture.h"

using namespace affray::texture;
using affray::test::Rng;
using affray::test::Samples;
using affray::test::Tally;
using affray::test::tex::RandomTexels;
using affray::test::tex::RandomWrap;

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

/// A random small map (1..9 texels per axis, 1..3 channels) and random options for it.
struct Case {
    std::shared_ptr<const TextureMap> map;
    LookupOptions options;
    int offset = 0;
};

Case RandomCase(Rng& rng, bool blur) {
    Case c;
    const int w = rng.integer(1, 9), h = rng.integer(1, 9), ch = rng.integer(1, 3);
    c.map = TextureMap::FromPixels(w, h, ch, RandomTexels(rng, static_cast<size_t>(w) * h * ch), RandomWrap(rng),
                                   RandomWrap(rng));
    c.options.channel = rng.integer(0, ch - 1);
    c.offset = rng.integer(0, ch - 1 - c.options.channel);
    c.options.swrap = RandomWrap(rng);
    c.options.twrap = RandomWrap(rng);
    c.options.filter = static_cast<Filter>(rng.integer(0, 3));
    if (blur && rng.chance(0.5)) {
        c.options.sblur = rng.chance(0.3) ? 0 : rng.uniform(0, 0.6);
        c.options.tblur = rng.chance(0.3) ? 0 : rng.uniform(0, 0.6);
    }
    c.options.fill = rng.chance(0.5) ? 0 : rng.uniform(-5, 5);
    return c;
}

/// A random coordinate range along an axis of `size` texels: near the image, far outside it,
/// huge, zero-width, with ends on texel centres, or unbounded.
Range RandomRange(Rng& rng, int size) {
    const int kind = rng.integer(0, 9);
    double lo = 0, hi = 0;
    switch (kind) {
        case 0:  // zero width
            lo = hi = rng.uniform(-2, 3);
            break;
        case 1: {  // ends on texel centres
            lo = (rng.integer(-12, 12) + 0.5) / size;
            hi = lo + rng.integer(0, 3) / static_cast<double>(size);
            break;
        }
        case 2:  // far outside
            lo = rng.uniform(-40, 40);
            hi = lo + rng.uniform(0, 3);
            break;
        case 3: {  // huge, around the edge of reach
            const double edge = kMaxTexelCoordinate / size * (rng.chance(0.5) ? 1 : -1);
            lo = edge * rng.uniform(0.999, 1.001);
            hi = lo + rng.uniform(0, 20);
            break;
        }
        case 4:  // unbounded
            lo = rng.chance(0.5) ? -kInf : rng.uniform(-2, 2);
            hi = rng.chance(0.5) ? kInf : lo + rng.uniform(0, 2);
            break;
        case 5:  // tiny
            lo = rng.uniform(-1, 2);
            hi = lo + rng.uniform(0, 1e-9);
            break;
        default:
            lo = rng.uniform(-1.5, 2.5);
            hi = lo + rng.uniform(0, rng.chance(0.5) ? 0.3 : 2);
            break;
    }
    return {lo, hi};
}

/// Points of a range to look up at: its ends, texel centres in it, and random points.
std::vector<double> PointsIn(Rng& rng, Range r, int size) {
    std::vector<double> p;
    auto clampFinite = [](double v) { return std::clamp(v, -1e300, 1e300); };
    const double lo = clampFinite(r.lo), hi = clampFinite(r.hi);
    if (std::isfinite(r.lo)) p.push_back(r.lo);
    if (std::isfinite(r.hi)) p.push_back(r.hi);
    if (!std::isfinite(r.lo) || !std::isfinite(r.hi)) {
        p.push_back(r.lo);
        p.push_back(r.hi);
    }
    for (int i = 0; i < 6; ++i) {
        double v = lo + (hi - lo) * rng.uniform(0, 1);
        if (hi - lo > 1e12) v = rng.uniform(-3, 4);  // a point of interest inside an unbounded range
        if (v < lo || v > hi) continue;
        p.push_back(v);
        const double centre = (std::floor(v * size) + 0.5) / size;  // the nearest texel centre
        if (centre >= r.lo && centre <= r.hi) p.push_back(centre);
        p.push_back(std::nextafter(v, kInf) <= r.hi ? std::nextafter(v, kInf) : v);
    }
    return p;
}

bool Contains(Range r, double v) { return v >= r.lo && v <= r.hi; }

std::string Describe(const Case& c, Range s, Range t) {
    std::ostringstream o;
    o.precision(17);
    o << c.map->width() << "x" << c.map->height() << " ch " << c.options.channel << "+" << c.offset << " wrap "
      << WrapName(c.options.swrap) << "," << WrapName(c.options.twrap) << " " << FilterName(c.options.filter)
      << " blur " << c.options.sblur << "," << c.options.tblur << " fill " << c.options.fill << " s [" << s.lo << ", "
      << s.hi << "] t [" << t.lo << ", " << t.hi << "]";
    return o.str();
}

/// Brute-force range of channel c over [x0, x1] x [y0, y1] through the wrap modes; x1 - x0 and
/// y1 - y0 small (or the wrap periodic/clamp, where a few periods suffice).
Range BruteRange(const TextureMap& m, int64_t x0, int64_t x1, int64_t y0, int64_t y1, int c, Wrap sw, Wrap tw) {
    auto indices = [](int64_t i0, int64_t i1, int n, Wrap w) {
        std::vector<int64_t> out;  // -1 for black
        if (w == Wrap::Clamp) {
            for (int64_t i = std::clamp<int64_t>(i0, 0, n - 1); i <= std::clamp<int64_t>(i1, 0, n - 1); ++i)
                out.push_back(i);
        } else if (w == Wrap::Black) {
            if (i0 < 0 || i1 >= n) out.push_back(-1);
            for (int64_t i = std::max<int64_t>(i0, 0); i <= std::min<int64_t>(i1, n - 1); ++i) out.push_back(i);
        } else {
            for (int64_t k = 0;
                 k < n && static_cast<uint64_t>(k) <= static_cast<uint64_t>(i1) - static_cast<uint64_t>(i0); ++k) {
                const int64_t i = static_cast<int64_t>(static_cast<uint64_t>(i0) + static_cast<uint64_t>(k));
                out.push_back(((i % n) + n) % n);
            }
        }
        return out;
    };
    double lo = kInf, hi = -kInf;
    for (int64_t y : indices(y0, y1, m.height(), tw)) {
        for (int64_t x : indices(x0, x1, m.width(), sw)) {
            const double v = x < 0 || y < 0 ? 0.0 : m.Texel(static_cast<int>(x), static_cast<int>(y), c);
            lo = std::min(lo, v);
            hi = std::max(hi, v);
        }
    }
    return {lo, hi};
}

/// The bounding interval of the in-image indices [i0, i1] reaches through a wrap mode (lo > hi
/// if none), and whether it reaches a black texel.
struct Covered {
    int64_t lo = 0, hi = -1;
    bool black = false;
};
Covered CoveredIndices(int64_t i0, int64_t i1, int n, Wrap w) {
    if (w == Wrap::Clamp) return {std::clamp<int64_t>(i0, 0, n - 1), std::clamp<int64_t>(i1, 0, n - 1), false};
    if (w == Wrap::Black) return {std::max<int64_t>(i0, 0), std::min<int64_t>(i1, n - 1), i0 < 0 || i1 >= n};
    if (static_cast<uint64_t>(i1) - static_cast<uint64_t>(i0) >= static_cast<uint64_t>(n - 1)) return {0, n - 1, false};
    const int64_t a = ((i0 % n) + n) % n, b = ((i1 % n) + n) % n;
    return a <= b ? Covered{a, b, false} : Covered{0, n - 1, false};
}

}  // namespace

TEST_CASE("texture: wrap and filter names", "[texture]") {
    Wrap w;
    Filter f;
    for (Wrap x : {Wrap::Black, Wrap::Clamp, Wrap::Periodic}) {
        REQUIRE(ParseWrap(WrapName(x), &w));
        CHECK(w == x);
    }
    for (Filter x : {Filter::Box, Filter::Triangle, Filter::Gaussian, Filter::CatmullRom}) {
        REQUIRE(ParseFilter(FilterName(x), &f));
        CHECK(f == x);
    }
    CHECK((ParseWrap("repeat", &w) && w == Wrap::Periodic));
    CHECK((ParseFilter("catrom", &f) && f == Filter::CatmullRom));
    CHECK((ParseFilter("bicubic", &f) && f == Filter::CatmullRom));
    CHECK_FALSE(ParseWrap("mirror", &w));
    CHECK_FALSE(ParseFilter("lanczos", &f));
}

TEST_CASE("texture: maps from pixels, texels, non-finite texels, bilinear formula", "[texture]") {
    const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
    std::vector<float> px = {1, 2, nan, 4, 5, inf, 7, 8, 9, 10, 11, 12};  // 3 x 2, 2 channels
    auto map = TextureMap::FromPixels(3, 2, 2, px, Wrap::Clamp, Wrap::Black, "m");
    REQUIRE(map);
    CHECK(map->width() == 3);
    CHECK(map->height() == 2);
    CHECK(map->channels() == 2);
    CHECK(map->name() == "m");
    CHECK(map->swrap() == Wrap::Clamp);
    CHECK(map->twrap() == Wrap::Black);
    CHECK(map->nonFiniteTexels() == 2);
    CHECK(map->Texel(1, 0, 0) == 0.0f);
    CHECK(map->Texel(2, 0, 1) == 0.0f);
    CHECK(map->Texel(0, 1, 1) == 8.0f);
    CHECK(map->residentBytes() >= px.size() * sizeof(float));
    CHECK_FALSE(TextureMap::FromPixels(2, 2, 1, {1, 2, 3}));
    CHECK_FALSE(TextureMap::FromPixels(0, 2, 1, {}));

    // The header's formula, bit for bit, at random points of a random map.
    Rng rng(16001);
    const int w = 7, h = 5;
    auto m = TextureMap::FromPixels(w, h, 1, RandomTexels(rng, static_cast<size_t>(w) * h));
    LookupOptions o;
    o.swrap = Wrap::Periodic;
    o.twrap = Wrap::Clamp;
    auto T = [&](int64_t x, int64_t y) -> double {
        return m->Texel(static_cast<int>(((x % w) + w) % w), static_cast<int>(std::clamp<int64_t>(y, 0, h - 1)), 0);
    };
    for (int i = 0; i < 200; ++i) {
        const double s = rng.uniform(-3, 3), t = rng.uniform(-1, 2);
        const double fx = s * w - 0.5, fy = t * h - 0.5;
        const double x0 = std::floor(fx), y0 = std::floor(fy), a = fx - x0, b = fy - y0;
        const int64_t ix = static_cast<int64_t>(x0), iy = static_cast<int64_t>(y0);
        const double expect =
            (1 - b) * ((1 - a) * T(ix, iy) + a * T(ix + 1, iy)) + b * ((1 - a) * T(ix, iy + 1) + a * T(ix + 1, iy + 1));
        CHECK(Sample(m.get(), o, 0, s, t) == expect);
    }
    // Texel centres give the texel, with either interpolation.
    for (Filter f : {Filter::Box, Filter::CatmullRom}) {
        o.filter = f;
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) CHECK(Sample(m.get(), o, 0, (x + 0.5) / w, (y + 0.5) / h) == m->Texel(x, y, 0));
    }
}

TEST_CASE("texture: fill value for missing maps, channels and coordinates out of reach", "[texture]") {
    auto m = TextureMap::FromPixels(4, 4, 2, std::vector<float>(32, 1.0f));
    LookupOptions o;
    o.fill = 0.25;
    const double nan = std::numeric_limits<double>::quiet_NaN();
    CHECK(Sample(nullptr, o, 0, 0.5, 0.5) == 0.25);
    CHECK(Sample(m.get(), o, 2, 0.5, 0.5) == 0.25);
    CHECK(Sample(m.get(), o, -1, 0.5, 0.5) == 0.25);
    CHECK(Sample(m.get(), o, 1, 0.5, 0.5) == 1.0);
    CHECK(Sample(m.get(), o, 0, nan, 0.5) == 0.25);
    CHECK(Sample(m.get(), o, 0, 0.5, kInf) == 0.25);
    CHECK(Sample(m.get(), o, 0, -kInf, 0.5) == 0.25);
    // Exactly at the reach (2^40 texels before the image) still a texel; beyond it the fill.
    CHECK(Sample(m.get(), o, 0, -kMaxTexelCoordinate / 4, 0.5) == 1.0);
    CHECK(Sample(m.get(), o, 0, (kMaxTexelCoordinate + 4) / 4, 0.5) == 1.0);
    CHECK(Sample(m.get(), o, 0, -kMaxTexelCoordinate / 4 * 1.0001, 0.5) == 0.25);
    CHECK(Sample(m.get(), o, 0, 0.5, 1e300) == 0.25);
    double ds = 1, dt = 1;
    CHECK(SampleGrad(m.get(), o, 0, nan, 0.5, &ds, &dt) == 0.25);
    CHECK((ds == 0 && dt == 0));
    const double s4[4] = {0.1, 0.2, 0.1, 0.2}, t4[4] = {0.1, 0.1, 0.2, 0.2};
    CHECK(SampleQuad(nullptr, o, 0, s4, t4) == 0.25);
    CHECK(SampleQuad(m.get(), o, 0, s4, t4) == 1.0);
    const Range r = RangeOver(nullptr, o, 0, {0, 1}, {0, 1});
    CHECK((r.lo <= 0.25 && r.hi >= 0.25));
    double ss = 1, ts = 1;
    SlopeOver(nullptr, o, 0, {0, 1}, {0, 1}, &ss, &ts);
    CHECK((ss == 0 && ts == 0));
    SlopeOver(m.get(), o, 0, {0, kInf}, {0, 1}, &ss, &ts);
    CHECK(ss == kInf);
    // Black outside: half a texel past the edge, half the edge texel.
    o.swrap = Wrap::Black;
    CHECK(Sample(m.get(), o, 0, 0, 0.5) == 0.5);
    o.swrap = Wrap::Clamp;
    CHECK(Sample(m.get(), o, 0, -3, 0.5) == 1.0);
}

TEST_CASE("texture: blur and four-corner lookups average their taps", "[texture]") {
    Rng rng(16002);
    const int w = 6, h = 5;
    auto m = TextureMap::FromPixels(w, h, 1, RandomTexels(rng, static_cast<size_t>(w) * h));
    LookupOptions o;
    o.sblur = 0.3;
    o.tblur = 0.2;
    for (Filter f : {Filter::Box, Filter::Triangle, Filter::Gaussian}) {
        o.filter = f;
        // The taps' weights: equal, tent, gaussian; normalised.
        double wts[kBlurTaps], sum = 0;
        for (int i = 0; i < kBlurTaps; ++i) {
            const double x = (i + 0.5) / kBlurTaps - 0.5;
            wts[i] = f == Filter::Box ? 1 : f == Filter::Triangle ? 1 - std::fabs(x) * 2 : std::exp(-8 * x * x);
            sum += wts[i];
        }
        LookupOptions plain = o;
        plain.sblur = plain.tblur = 0;
        for (int n = 0; n < 20; ++n) {
            const double s = rng.uniform(-1, 2), t = rng.uniform(-1, 2);
            double expect = 0;
            for (int j = 0; j < kBlurTaps; ++j)
                for (int i = 0; i < kBlurTaps; ++i)
                    expect += wts[i] / sum * wts[j] / sum *
                              Sample(m.get(), plain, 0, s + o.sblur * ((i + 0.5) / kBlurTaps - 0.5),
                                     t + o.tblur * ((j + 0.5) / kBlurTaps - 0.5));
            CHECK(Sample(m.get(), o, 0, s, t) == Approx(expect).margin(1e-12));
        }
    }
    // A constant map blurs to itself; a quad of one point is that point's lookup.
    auto flat = TextureMap::FromPixels(3, 3, 1, std::vector<float>(9, 0.75f));
    CHECK(Sample(flat.get(), o, 0, 0.3, 0.4) == Approx(0.75).epsilon(1e-15));
    const double s4[4] = {0.3, 0.3, 0.3, 0.3}, t4[4] = {0.6, 0.6, 0.6, 0.6};
    CHECK(SampleQuad(m.get(), o, 0, s4, t4) == Approx(Sample(m.get(), o, 0, 0.3, 0.6)).margin(1e-12));
    // The quad's grid: cell centres of the bilinear quadrilateral, corners 1, 2 along s.
    o.sblur = o.tblur = 0;
    const double qs[4] = {0.1, 0.5, 0.2, 0.7}, qt[4] = {0.2, 0.3, 0.8, 0.6};
    double expect = 0;
    for (int j = 0; j < kQuadTaps; ++j) {
        for (int i = 0; i < kQuadTaps; ++i) {
            const double u = (i + 0.5) / kQuadTaps, v = (j + 0.5) / kQuadTaps;
            expect += Sample(m.get(), o, 0, (1 - v) * ((1 - u) * qs[0] + u * qs[1]) + v * ((1 - u) * qs[2] + u * qs[3]),
                             (1 - v) * ((1 - u) * qt[0] + u * qt[1]) + v * ((1 - u) * qt[2] + u * qt[3]));
        }
    }
    CHECK(SampleQuad(m.get(), o, 0, qs, qt) == Approx(expect / (kQuadTaps * kQuadTaps)).margin(1e-12));
}

TEST_CASE("texture: RangeOfTexels contains the brute-force range through every wrap mode", "[texture]") {
    Rng rng(16003);
    Tally tally;
    for (int n = 0; n < Samples(3000); ++n) {
        const int w = rng.integer(1, 40), h = rng.integer(1, 40);
        auto m = TextureMap::FromPixels(w, h, 1, RandomTexels(rng, static_cast<size_t>(w) * h));
        const Wrap sw = RandomWrap(rng), tw = RandomWrap(rng);
        auto interval = [&](int64_t size, Wrap wrap, int64_t* lo, int64_t* hi) {
            const int kind = rng.integer(0, 5);
            if (kind == 0 && wrap != Wrap::Black) {  // huge: any int64 (brute force sees a few periods)
                *lo = rng.integer<int64_t>(INT64_MIN, INT64_MAX - 1);
                *hi = rng.chance(0.5)        ? rng.integer<int64_t>(*lo, INT64_MAX)
                      : *lo > INT64_MAX - 60 ? INT64_MAX
                                             : *lo + rng.integer(0, 60);
            } else if (kind == 1) {  // at most 8 texels: read exactly
                *lo = rng.integer<int64_t>(-2 * size, 2 * size);
                *hi = *lo + rng.integer(0, 7);
            } else {
                *lo = rng.integer<int64_t>(-3 * size, 3 * size);
                *hi = *lo + rng.integer<int64_t>(0, 3 * size);
            }
        };
        int64_t x0, x1, y0, y1;
        interval(w, sw, &x0, &x1);
        interval(h, tw, &y0, &y1);
        const Range got = m->RangeOfTexels(x0, x1, y0, y1, 0, sw, tw);
        const Range want = BruteRange(*m, x0, x1, y0, y1, 0, sw, tw);
        ++tally.samples;
        std::ostringstream what;
        what << w << "x" << h << " " << WrapName(sw) << "," << WrapName(tw) << " [" << x0 << "," << x1 << "]x[" << y0
             << "," << y1 << "] got [" << got.lo << "," << got.hi << "] want [" << want.lo << "," << want.hi << "]";
        if (got.lo > want.lo || got.hi < want.hi) tally.fail("not contained: " + what.str());
        // Pieces of at most 8 x 8 texels are exact; larger rectangles may read blocks reaching
        // past them, by less than the rectangle's size.
        const uint64_t spanX = static_cast<uint64_t>(x1) - static_cast<uint64_t>(x0);
        const uint64_t spanY = static_cast<uint64_t>(y1) - static_cast<uint64_t>(y0);
        if (spanX < 8 && spanY < 8) {
            if (got.lo != want.lo || got.hi != want.hi) tally.fail("not exact: " + what.str());
        } else if (spanX < 1000 && spanY < 1000 && std::llabs(x0) < (int64_t{1} << 60) &&
                   std::llabs(y0) < (int64_t{1} << 60)) {
            // The blocks reach past the in-image pieces (after the wrap) by less than their size.
            const int64_t d = static_cast<int64_t>(std::max(spanX, spanY)) + 4;
            const Covered cx = CoveredIndices(x0, x1, w, sw), cy = CoveredIndices(y0, y1, h, tw);
            Range wide = BruteRange(*m, cx.lo - d, cx.hi + d, cy.lo - d, cy.hi + d, 0, Wrap::Clamp, Wrap::Clamp);
            if (cx.black || cy.black) wide = {std::min(wide.lo, 0.0), std::max(wide.hi, 0.0)};
            if (got.lo < wide.lo || got.hi > wide.hi) tally.fail("too wide: " + what.str());
            if (got.lo == want.lo && got.hi == want.hi) ++tally.bounded;
        }
    }
    INFO(tally.first.str());
    CHECK(tally.failures == 0);
}

TEST_CASE("texture: RangeOver contains every lookup over its region", "[texture]") {
    Rng rng(16004);
    Tally tally;
    for (int n = 0; n < Samples(3000); ++n) {
        const Case c = RandomCase(rng, true);
        const Range s = RandomRange(rng, c.map->width()), t = RandomRange(rng, c.map->height());
        const Range r = RangeOver(c.map.get(), c.options, c.offset, s, t);
        for (double ps : PointsIn(rng, s, c.map->width())) {
            for (double pt : PointsIn(rng, t, c.map->height())) {
                ++tally.samples;
                const double v = Sample(c.map.get(), c.options, c.offset, ps, pt);
                if (!Contains(r, v)) {
                    std::ostringstream o;
                    o.precision(17);
                    o << Describe(c, s, t) << " at (" << ps << ", " << pt << ") = " << v << " not in [" << r.lo << ", "
                      << r.hi << "]";
                    tally.fail(o.str());
                }
            }
        }
        // NaN ends: everything the map and the fill can give.
        const Range all = RangeOver(c.map.get(), c.options, c.offset, {std::nan(""), 1}, t);
        if (!(all.lo <= r.lo && all.hi >= r.hi) && std::isfinite(r.lo)) tally.fail("NaN range: " + Describe(c, s, t));
    }
    INFO(tally.first.str());
    CHECK(tally.failures == 0);
    CHECK(tally.samples > 10000);
}

TEST_CASE("texture: RangeOverQuad contains every four-corner lookup over its corner ranges", "[texture]") {
    Rng rng(16005);
    Tally tally;
    for (int n = 0; n < Samples(800); ++n) {
        const Case c = RandomCase(rng, true);
        Range s[4], t[4];
        for (int i = 0; i < 4; ++i) {
            s[i] = rng.chance(0.8) ? Range{rng.uniform(-1, 2), 0} : RandomRange(rng, c.map->width());
            if (s[i].hi < s[i].lo) s[i].hi = s[i].lo + rng.uniform(0, 0.5);
            t[i] = rng.chance(0.8) ? Range{rng.uniform(-1, 2), 0} : RandomRange(rng, c.map->height());
            if (t[i].hi < t[i].lo) t[i].hi = t[i].lo + rng.uniform(0, 0.5);
        }
        const Range r = RangeOverQuad(c.map.get(), c.options, c.offset, s, t);
        for (int k = 0; k < 6; ++k) {
            double ps[4], pt[4];
            for (int i = 0; i < 4; ++i) {
                auto pick = [&](Range x) {
                    if (!std::isfinite(x.lo) || !std::isfinite(x.hi)) return rng.chance(0.5) ? x.lo : x.hi;
                    return k == 0 ? x.lo : k == 1 ? x.hi : x.lo + (x.hi - x.lo) * rng.uniform(0, 1);
                };
                ps[i] = pick(s[i]);
                pt[i] = pick(t[i]);
            }
            ++tally.samples;
            const double v = SampleQuad(c.map.get(), c.options, c.offset, ps, pt);
            if (!Contains(r, v) && !std::isnan(v)) {
                std::ostringstream o;
                o.precision(17);
                o << Describe(c, s[0], t[0]) << " quad value " << v << " not in [" << r.lo << ", " << r.hi << "]";
                tally.fail(o.str());
            }
        }
    }
    INFO(tally.first.str());
    CHECK(tally.failures == 0);
}

TEST_CASE("texture: SampleGrad is Sample's value and agrees with finite differences", "[texture]") {
    Rng rng(16006);
    Tally tally;
    for (int n = 0; n < Samples(1500); ++n) {
        const Case c = RandomCase(rng, true);
        const double s = rng.uniform(-1.5, 2.5), t = rng.uniform(-1.5, 2.5);
        double ds = 0, dt = 0;
        const double v = SampleGrad(c.map.get(), c.options, c.offset, s, t, &ds, &dt);
        ++tally.samples;
        if (v != Sample(c.map.get(), c.options, c.offset, s, t))
            tally.fail("value differs: " + Describe(c, {s, s}, {t, t}));
        // Central differences where the two one-sided ones agree (no kink within the step).
        auto check = [&](bool alongS, double grad) {
            const double h = 1e-8;
            auto f = [&](double d) {
                return alongS ? Sample(c.map.get(), c.options, c.offset, s + d, t)
                              : Sample(c.map.get(), c.options, c.offset, s, t + d);
            };
            const double f0 = f(0), fwd = (f(h) - f0) / h, bwd = (f0 - f(-h)) / h, central = (f(h) - f(-h)) / (2 * h);
            const double tol = 1e-5 * (1 + std::fabs(grad));
            if (std::fabs(fwd - bwd) > tol) return;  // a kink
            ++tally.bounded;
            if (std::fabs(central - grad) > tol) {
                std::ostringstream o;
                o.precision(17);
                o << Describe(c, {s, s}, {t, t}) << (alongS ? " d/ds " : " d/dt ") << grad << " central " << central;
                tally.fail(o.str());
            }
        };
        check(true, ds);
        check(false, dt);
    }
    INFO(tally.first.str());
    CHECK(tally.failures == 0);
    CHECK(tally.bounded > tally.samples);  // most points are away from kinks
}

TEST_CASE("texture: SlopeOver bounds SampleGrad over its region, and Catmull-Rom's constants", "[texture]") {
    // The constants of texture.h, numerically: Catmull-Rom's negative tensor weights sum to at
    // most 9/32, and the positive derivative weights of one axis times the absolute weights of the
    // other stay below 2.
    auto weights = [](double f, double w[4]) {
        w[0] = (-f * f * f + 2 * f * f - f) / 2;
        w[1] = (3 * f * f * f - 5 * f * f + 2) / 2;
        w[2] = (-3 * f * f * f + 4 * f * f + f) / 2;
        w[3] = (f * f * f - f * f) / 2;
    };
    double worstNegative = 0, worstSlope = 0;
    for (int i = 0; i <= 200; ++i) {
        for (int j = 0; j <= 200; ++j) {
            const double f = i / 200.0, g = j / 200.0, h = 1e-6;
            double wf[4], wg[4], wfh[4];
            weights(f, wf);
            weights(g, wg);
            weights(std::min(f + h, 1.0), wfh);
            double negative = 0, positiveSlope = 0, absG = 0;
            for (int a = 0; a < 4; ++a) {
                absG += std::fabs(wg[a]);
                const double d = (wfh[a] - wf[a]) / (std::min(f + h, 1.0) - f);
                if (d > 0 && f < 1) positiveSlope += d;
                for (int b = 0; b < 4; ++b)
                    if (wf[a] * wg[b] < 0) negative -= wf[a] * wg[b];
            }
            worstNegative = std::max(worstNegative, negative);
            worstSlope = std::max(worstSlope, positiveSlope * absG);
        }
    }
    CHECK(worstNegative <= 9.0 / 32 + 1e-12);
    CHECK(worstNegative > 9.0 / 32 - 1e-3);
    CHECK(worstSlope <= 2.0);

    Rng rng(16007);
    Tally tally;
    for (int n = 0; n < Samples(2000); ++n) {
        const Case c = RandomCase(rng, true);
        Range s = RandomRange(rng, c.map->width()), t = RandomRange(rng, c.map->height());
        double ss = 0, ts = 0;
        SlopeOver(c.map.get(), c.options, c.offset, s, t, &ss, &ts);
        if (!std::isfinite(ss) || !std::isfinite(ts)) continue;
        ++tally.finite;
        for (double ps : PointsIn(rng, s, c.map->width())) {
            for (double pt : PointsIn(rng, t, c.map->height())) {
                double ds = 0, dt = 0;
                SampleGrad(c.map.get(), c.options, c.offset, ps, pt, &ds, &dt);
                ++tally.samples;
                if (std::fabs(ds) > ss || std::fabs(dt) > ts) {
                    std::ostringstream o;
                    o.precision(17);
                    o << Describe(c, s, t) << " at (" << ps << ", " << pt << ") grad " << ds << ", " << dt << " slopes "
                      << ss << ", " << ts;
                    tally.fail(o.str());
                }
            }
        }
    }
    INFO(tally.first.str());
    CHECK(tally.failures == 0);
    CHECK(tally.finite > 1000);
}
