// tests/compiler/lower_logic_test.cpp: comparisons, && || !, conditions and ?: (compiler/lower_logic.cpp):
// their values on floats and points, and booleans used, stored and returned as floats.
// Part of the language-semantics suite: values worked out by hand on the unit square, each
// cross-checked as tests/compiler/semantics_util.h says.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>

#include "tests/compiler/semantics_util.h"

using namespace affray;
using namespace affray::test::semantics;

TEST_CASE("logical operators and comparisons", "[compiler][semantics]") {
    CHECK_THAT(Z("P += !(u < 0.5);", 0.25), WithinAbs(0, kEps));
    CHECK_THAT(Z("P += !(u < 0.5);", 0.75), WithinAbs(1, kEps));
    const std::string both = "if (u < 0.5 && v > 0.5) P += 1;";
    CHECK_THAT(Z(both, 0.25, 0.75), WithinAbs(1, kEps));
    CHECK_THAT(Z(both, 0.25, 0.25), WithinAbs(0, kEps));
    CHECK_THAT(Z(both, 0.75, 0.75), WithinAbs(0, kEps));
    const std::string either = "if (u < 0.5 || v < 0.5) P += 1;";
    CHECK_THAT(Z(either, 0.75, 0.75), WithinAbs(0, kEps));
    CHECK_THAT(Z(either, 0.75, 0.25), WithinAbs(1, kEps));
    CHECK_THAT(Z(either, 0.25, 0.75), WithinAbs(1, kEps));
    // Floats in '&&' and '||' mean "!= 0".
    CHECK_THAT(Z("P += 2 && 0.5;"), WithinAbs(1, kEps));
    CHECK_THAT(Z("P += 0 || 0;"), WithinAbs(0, kEps));
    CHECK_THAT(Z("P += !2;"), WithinAbs(0, kEps));
    // Every comparison: 1 < 2, 2 <= 2, 3 > 2 hold; 2 >= 3, 1 != 1 do not; 1 == 1 holds.
    CHECK_THAT(Z("P += (1 < 2) + 10 * (2 <= 2) + 100 * (3 > 2) + 1000 * (2 >= 3) + 10000 * (1 == 1) + "
                 "100000 * (1 != 1);"),
               WithinAbs(10111, kEps));
    CHECK_THAT(Z("P += (2 < 1) + 10 * (3 <= 2) + 100 * (2 > 3) + 1000 * (3 >= 3) + 10000 * (1 == 2) + "
                 "100000 * (1 != 2);"),
               WithinAbs(101000, kEps));
    // Varying comparisons.
    CHECK_THAT(Z("P += (u <= 0.25) + 10 * (u >= 0.25) + 100 * (u == 0.25);", 0.25), WithinAbs(111, kEps));
    CHECK_THAT(Z("P += (u <= 0.25) + 10 * (u >= 0.25) + 100 * (u == 0.25);", 0.5), WithinAbs(10, kEps));
}

TEST_CASE("== and != on points", "[compiler][semantics]") {
    CHECK_THAT(Z("P += point(1, 2, 3) == point(1, 2, 3);"), WithinAbs(1, kEps));
    CHECK_THAT(Z("P += point(1, 2, 3) == point(1, 2, 4);"), WithinAbs(0, kEps));
    CHECK_THAT(Z("P += point(1, 2, 3) == point(0, 2, 3);"), WithinAbs(0, kEps));
    CHECK_THAT(Z("P += point(1, 2, 3) != point(1, 2, 4);"), WithinAbs(1, kEps));
    CHECK_THAT(Z("P += point(1, 2, 3) != point(1, 2, 3);"), WithinAbs(0, kEps));
    // A float compares as a triple of three copies.
    CHECK_THAT(Z("P += point(2, 2, 2) == 2;"), WithinAbs(1, kEps));
    CHECK_THAT(Z("P += point(2, 2, 3) == 2;"), WithinAbs(0, kEps));
    // Varying, and across point, vector and normal.
    CHECK_THAT(Z("if (P == point(u, v, 0)) P += 1;"), WithinAbs(1, kEps));
    CHECK_THAT(Z("if (P != point(0.25, v, 0)) P += 1;", 0.25), WithinAbs(0, kEps));
    CHECK_THAT(Z("if (P != point(0.25, v, 0)) P += 1;", 0.75), WithinAbs(1, kEps));
    CHECK_THAT(Z("P += vector(0, 0, 1) == N;"), WithinAbs(1, kEps));
}

TEST_CASE("?: with float and point arms", "[compiler][semantics]") {
    CHECK_THAT(Z("P += u < 0.5 ? 1 : 2;", 0.25), WithinAbs(1, kEps));
    CHECK_THAT(Z("P += u < 0.5 ? 1 : 2;", 0.75), WithinAbs(2, kEps));
    // A float arm is promoted to the point's type.
    CheckVec(PAt("point q = u < 0.5 ? point(1, 2, 3) : 7; P = q;", 0.25), {1, 2, 3});
    CheckVec(PAt("point q = u < 0.5 ? point(1, 2, 3) : 7; P = q;", 0.75), {7, 7, 7});
    CheckVec(PAt("P = u < 0.5 ? P + vector(0, 0, 1) : P - vector(0, 0, 1);", 0.75), {0.75, 0.75, -1});
    // A constant condition picks its arm.
    CHECK_THAT(Z("P += 1 ? 5 : 6;"), WithinAbs(5, kEps));
    // Boolean arms: at (0.25, 0.75) v > 0.5 holds; at (0.75, 0.75) v < 0.5 does not.
    CHECK_THAT(Z("P += (u < 0.5 ? v > 0.5 : v < 0.5) ? 10 : 20;", 0.25, 0.75), WithinAbs(10, kEps));
    CHECK_THAT(Z("P += (u < 0.5 ? v > 0.5 : v < 0.5) ? 10 : 20;", 0.75, 0.75), WithinAbs(20, kEps));
}

TEST_CASE("booleans used as floats", "[compiler][semantics]") {
    CHECK_THAT(Z("P += (u < 0.5) * 10;", 0.25), WithinAbs(10, kEps));
    CHECK_THAT(Z("P += (u < 0.5) * 10;", 0.75), WithinAbs(0, kEps));
    CHECK_THAT(Z("float b; b = u < 0.5; P += b;", 0.25), WithinAbs(1, kEps));
    CHECK_THAT(Z("P += -(1 < 2);"), WithinAbs(-1, kEps));
    CHECK_THAT(Z("P += sin(1 < 2);"), WithinAbs(std::sin(1.0), kEps));
    CHECK_THAT(Z("float a[2] = {1 < 2, 2 < 1}; P += a[0] * 10 + a[1];"), WithinAbs(10, kEps));
    CHECK_THAT(ZSource("float twice(float x) { return 2 * x; }\n" + Shader("P += twice(1 < 2);")), WithinAbs(2, kEps));
}

TEST_CASE("booleans initialise and are returned as floats", "[compiler][semantics]") {
    // Was a bug (fixed in Lowerer::Convert): `b = u < 0.5` was accepted, but `float b = u < 0.5`
    // and `return 1 < 2` in a float function were rejected ("cannot assign a boolean to ...").
    CHECK_THAT(Z("float b = u < 0.5; P += b;", 0.25), WithinAbs(1, kEps));
    CHECK_THAT(Z("float b = u < 0.5; P += b;", 0.75), WithinAbs(0, kEps));
    CheckVec(PAt("vector w = u < 0.5; P = w;", 0.25), {1, 1, 1});
    CHECK_THAT(ZSource("float yes() { return 1 < 2; }\n" + Shader("P += yes();")), WithinAbs(1, kEps));
}
