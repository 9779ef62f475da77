// tests/scene/number_text_test.cpp: scene/number_text.h writes what an ostream writes.
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>

#include "scene/number_text.h"
#include "tests/test_random.h"

using affray::renderer::AppendNumber;

TEST_CASE("AppendNumber writes a double as an ostream does by default", "[renderer][scene]") {
    affray::test::Rng rng(5);
    auto same = [](double x) {
        std::ostringstream stream;
        stream << x;
        std::string text;
        AppendNumber(text, x);
        INFO(stream.str() << " vs " << text);
        CHECK(text == stream.str());
    };
    for (double x : {0.0, -0.0, 1.0, -1.0, 0.5, 1e-5, 1e-4, 123456.0, 1234567.0, 1e21, 1e-300, 5e-324, 0.1 + 0.2,
                     std::numeric_limits<double>::max(), std::numeric_limits<double>::infinity(),
                     -std::numeric_limits<double>::infinity(), std::nan("")})
        same(x);
    for (int n = 0; n < 20000; ++n) same(rng.uniform(-1, 1) * std::ldexp(1.0, rng.integer(-1074, 1023)));
    for (int n = 0; n < 2000; ++n) same(std::round(rng.uniform(-1e7, 1e7)));  // integers, 9.99999e+06 and the like
}
