// tests/vm/numbers/affine_capacity_test.cpp: Affine::SetCapacity really changes how many terms a form
// keeps, the folded terms go to the error (never eps_u or eps_v), and every bound stays valid
// at every capacity. Each test restores the default capacity on the way out (CapacityGuard), so
// the other tests of the binary see kCapacity whatever the order.
#include <catch2/catch.hpp>
#include <cmath>

#include "tests/test_random.h"
#include "vm/numbers/number.h"

using namespace affray::vm;
using affray::test::Rng;

namespace {

struct CapacityGuard {
    explicit CapacityGuard(int n) { REQUIRE(Affine::SetCapacity(n)); }
    ~CapacityGuard() { Affine::SetCapacity(Affine::kCapacity); }
};

// Many nonlinear terms, each on its own fresh symbol, then a linear combination of the sum with
// itself: with every symbol kept, s - s/2 is half as wide as s; with symbols folded into the
// independent error, that error no longer cancels and the bound is wider.
template <class T>
T ManyTerms(const T& u, const T& v) {
    using std::cos;
    T s = 0.25 * v;
    for (int k = 1; k <= 24; ++k) s = s + (1.0 / k) * cos(k * u + 0.5 * v);
    return s - 0.5 * s;
}

}  // namespace

TEST_CASE("SetCapacity accepts 2 to kMaxCapacity and Capacity reports it", "[vm][affine]") {
    CHECK(Affine::Capacity() == Affine::kCapacity);
    CHECK_FALSE(Affine::SetCapacity(1));
    CHECK_FALSE(Affine::SetCapacity(Affine::kMaxCapacity + 1));
    CHECK(Affine::Capacity() == Affine::kCapacity);
    {
        CapacityGuard guard(Affine::kMaxCapacity);
        CHECK(Affine::Capacity() == Affine::kMaxCapacity);
    }
    CHECK(Affine::Capacity() == Affine::kCapacity);
}

TEST_CASE("a form past the active capacity keeps its largest terms and eps_u and eps_v", "[vm][affine]") {
    for (int capacity : {2, 3, 4, 8, Affine::kCapacity, Affine::kMaxCapacity}) {
        INFO("capacity " << capacity);
        CapacityGuard guard(capacity);
        Affine::BeginEvaluation();
        Affine x = Affine::FromSymbol(0.5, 1e-12, Affine::kSymbolU) + Affine::FromSymbol(2.0, 1e-13, Affine::kSymbolV);
        const int fresh = 3 * Affine::kMaxCapacity;
        double total = 0;  // sum of the fresh radii: what the terms and the error hold between them
        for (int k = 0; k < fresh; ++k) {
            x = x + Affine::FromInterval(Interval(-1.0 - k, 1.0 + k));
            total += 1.0 + k;
        }
        CHECK(x.termCount() == capacity);
        CHECK(x.coefficientOf(Affine::kSymbolU) == 1e-12);
        CHECK(x.coefficientOf(Affine::kSymbolV) == 1e-13);
        // The kept fresh terms are the largest: radii fresh, fresh - 1, ...
        for (int i = 0; i < x.termCount(); ++i)
            if (x.termSymbol(i) >= Affine::kFirstFreshSymbol) CHECK(std::fabs(x.termCoef(i)) >= fresh - (capacity - 2));
        double kept = 0;
        for (int i = 0; i < x.termCount(); ++i)
            if (x.termSymbol(i) >= Affine::kFirstFreshSymbol) kept += std::fabs(x.termCoef(i));
        CHECK(x.error() >= total - kept);
        CHECK(x.error() <= (total - kept) * (1 + 1e-9));  // plus only the rounding bounds
    }
}

TEST_CASE("bounds hold at every capacity and a small capacity gives a wider one", "[vm][affine]") {
    const double uc = 0.5, ur = 0.25, vc = 0.25, vr = 0.125;  // exact, as are the sample points
    Rng rng(71);
    double widthAt2 = 0, widthAtMax = 0;
    for (int capacity : {2, 3, 4, 6, 8, Affine::kCapacity, 16, Affine::kMaxCapacity}) {
        INFO("capacity " << capacity);
        CapacityGuard guard(capacity);
        Affine::BeginEvaluation();
        Affine u = Affine::FromSymbol(uc, ur, Affine::kSymbolU);
        Affine f = ManyTerms(u, Affine::FromSymbol(vc, vr, Affine::kSymbolV));
        REQUIRE_FALSE(f.isUnbounded());
        CHECK(f.termCount() <= capacity);
        CHECK(f.coefficientOf(Affine::kSymbolU) != 0);
        CHECK(f.coefficientOf(Affine::kSymbolV) != 0);
        int failures = 0;
        for (int s = 0; s < 300; ++s) {
            double eu = rng.eps(), ev = rng.eps();
            double d = ManyTerms(uc + ur * eu, vc + vr * ev);
            failures += !f.evaluateAt(eu, ev).contains(d) || !f.range().contains(d);
        }
        CHECK(failures == 0);
        if (capacity == 2) widthAt2 = f.range().width();
        if (capacity == Affine::kMaxCapacity) widthAtMax = f.range().width();
    }
    CHECK(widthAt2 > 1.2 * widthAtMax);
}
