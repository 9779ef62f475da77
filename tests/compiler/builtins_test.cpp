// tests/compiler/builtins_test.cpp: the built-ins of the table (compiler/builtins.cpp), each against its
// RenderMan value: abs, sign, floor, ceil, round, mod, min, max, clamp, step, smoothstep, pow,
// sqrt, inversesqrt, exp, log, trigonometry, length, distance, normalize, the component setters,
// mix, faceforward, reflect, calculatenormal, Du, Dv, area, filterwidth and Deriv. (docs/builtins.md against
// the table, and the built-ins composed elsewhere, are tests/compiler/library_test.cpp's.)
// Part of the language-semantics suite: values worked out by hand on the unit square, each
// cross-checked as tests/compiler/semantics_util.h says.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>

#include "tests/compiler/semantics_util.h"

using namespace affray;
using namespace affray::test::semantics;

TEST_CASE("built-ins: abs sign floor ceil round", "[compiler][semantics][builtins]") {
    CHECK_THAT(Z("P += abs(-2.5);"), WithinAbs(2.5, kEps));
    CHECK_THAT(Z("P += abs(u - 0.5);", 0.25), WithinAbs(0.25, kEps));
    CHECK_THAT(Z("P += sign(-3) + 10 * sign(0) + 100 * sign(2);"), WithinAbs(99, kEps));
    CHECK_THAT(Z("P += floor(-1.5) + 10 * floor(1.5);"), WithinAbs(8, kEps));  // -2 + 10
    CHECK_THAT(Z("P += ceil(-1.5) + 10 * ceil(1.2);"), WithinAbs(19, kEps));   // -1 + 20
    CHECK_THAT(Z("P += floor(3) + ceil(3);"), WithinAbs(6, kEps));
    // round: halves away from 0.
    CHECK_THAT(Z("P += round(0.5);"), WithinAbs(1, kEps));
    CHECK_THAT(Z("P += round(-0.5);"), WithinAbs(-1, kEps));
    CHECK_THAT(Z("P += round(1.5);"), WithinAbs(2, kEps));
    CHECK_THAT(Z("P += round(2.5);"), WithinAbs(3, kEps));
    CHECK_THAT(Z("P += round(-2.5);"), WithinAbs(-3, kEps));
    CHECK_THAT(Z("P += round(1.4) + 10 * round(-1.6);"), WithinAbs(-19, kEps));  // 1 - 20
    // On triples, componentwise.
    CheckVec(PAt("P = floor(point(1.5, -1.5, 2));"), {1, -2, 2});
    CheckVec(PAt("P = ceil(vector(1.5, -1.5, 2));"), {2, -1, 2});
    CheckVec(PAt("P = round(point(0.5, -0.5, 1.49));"), {1, -1, 1});
    CheckVec(PAt("P = floor(P * 4);", 0.3, 0.6), {1, 2, 0});
}

TEST_CASE("built-ins: mod has the sign of the divisor", "[compiler][semantics][builtins]") {
    CHECK_THAT(Z("P += mod(-1.5, 1);"), WithinAbs(0.5, kEps));
    CHECK_THAT(Z("P += mod(5, 3);"), WithinAbs(2, kEps));
    CHECK_THAT(Z("P += mod(-5, 3);"), WithinAbs(1, kEps));
    CHECK_THAT(Z("P += mod(5, -3);"), WithinAbs(-1, kEps));
    CHECK_THAT(Z("P += mod(7.5, 2);"), WithinAbs(1.5, kEps));
    CHECK_THAT(Z("P += mod(u * 10, 1);", 0.25), WithinAbs(0.5, kEps));
    CheckVec(PAt("P = mod(point(5, -5, 7.5), 3);"), {2, 1, 1.5});
}

TEST_CASE("built-ins: min max clamp", "[compiler][semantics][builtins]") {
    CHECK_THAT(Z("P += min(1, 2);"), WithinAbs(1, kEps));
    CHECK_THAT(Z("P += max(1, 2);"), WithinAbs(2, kEps));
    CHECK_THAT(Z("P += min(3, 1, 2);"), WithinAbs(1, kEps));
    CHECK_THAT(Z("P += max(3, 1, 2);"), WithinAbs(3, kEps));
    CHECK_THAT(Z("P += max(1, 2, 3);"), WithinAbs(3, kEps));
    CHECK_THAT(Z("P += min(u, v);", 0.25, 0.75), WithinAbs(0.25, kEps));
    CheckVec(PAt("P = min(point(1, 5, 3), point(4, 2, 6));"), {1, 2, 3});
    CheckVec(PAt("P = max(point(1, 5, 3), point(4, 2, 6), point(0, 0, 9));"), {4, 5, 9});
    CheckVec(PAt("P = min(point(1, 5, 3), 2);"), {1, 2, 2});
    CHECK_THAT(Z("P += clamp(5, 0, 1) + 10 * clamp(-1, 0, 1) + 100 * clamp(0.5, 0, 1);"), WithinAbs(51, kEps));
    CheckVec(PAt("P = clamp(point(-1, 0.5, 2), 0, 1);"), {0, 0.5, 1});
    CheckVec(PAt("P = clamp(point(-1, 0.5, 2), point(0, 0.75, 0), point(1, 1, 1.5));"), {0, 0.75, 1.5});
}

TEST_CASE("built-ins: step and smoothstep", "[compiler][semantics][builtins]") {
    // step(edge, x) = x < edge ? 0 : 1
    CHECK_THAT(Z("P += step(0.5, 0.4);"), WithinAbs(0, kEps));
    CHECK_THAT(Z("P += step(0.5, 0.5);"), WithinAbs(1, kEps));
    CHECK_THAT(Z("P += step(0.5, 0.6);"), WithinAbs(1, kEps));
    CHECK_THAT(Z("P += step(0.5, u);", 0.25), WithinAbs(0, kEps));
    // smoothstep: 0 below, 1 above, 3t^2 - 2t^3 between.
    CHECK_THAT(Z("P += smoothstep(0, 1, -1);"), WithinAbs(0, kEps));
    CHECK_THAT(Z("P += smoothstep(0, 1, 2);"), WithinAbs(1, kEps));
    CHECK_THAT(Z("P += smoothstep(0, 1, 0.5);"), WithinAbs(0.5, kEps));
    CHECK_THAT(Z("P += smoothstep(0, 2, 0.5);"), WithinAbs(0.15625, kEps));  // t = 1/4
    CHECK_THAT(Z("P += smoothstep(1, 3, 2.5);"), WithinAbs(0.84375, kEps));  // t = 3/4
    CHECK_THAT(Z("P += smoothstep(0, 1, u);", 0.25), WithinAbs(0.15625, kEps));
}

TEST_CASE("built-ins: pow sqrt inversesqrt exp log", "[compiler][semantics][builtins]") {
    CHECK_THAT(Z("P += pow(2, 0.5);"), WithinAbs(std::sqrt(2.0), kEps));
    CHECK_THAT(Z("P += pow(2, -1);"), WithinAbs(0.5, kEps));
    CHECK_THAT(Z("P += pow(9, u);", 0.5), WithinAbs(3, kEps));
    CHECK_THAT(Z("P += sqrt(2);"), WithinAbs(std::sqrt(2.0), kEps));
    CHECK_THAT(Z("P += sqrt(u);", 0.25), WithinAbs(0.5, kEps));
    CHECK_THAT(Z("P += inversesqrt(16);"), WithinAbs(0.25, kEps));
    CHECK_THAT(Z("P += exp(0);"), WithinAbs(1, kEps));
    CHECK_THAT(Z("P += exp(log(2));"), WithinAbs(2, kEps));
    CHECK_THAT(Z("P += log(1);"), WithinAbs(0, kEps));
    CHECK_THAT(Z("P += log(100, 10);"), WithinAbs(2, kEps));
    CHECK_THAT(Z("P += log(0.25, 2);"), WithinAbs(-2, kEps));
}

TEST_CASE("built-ins: trigonometry, radians, degrees and PI", "[compiler][semantics][builtins]") {
    CHECK_THAT(Z("P += sin(PI / 6);"), WithinAbs(0.5, kEps));
    CHECK_THAT(Z("P += cos(PI / 3);"), WithinAbs(0.5, kEps));
    CHECK_THAT(Z("P += tan(PI / 4);"), WithinAbs(1, kEps));
    CHECK_THAT(Z("P += tan(-PI / 4);"), WithinAbs(-1, kEps));
    CHECK_THAT(Z("P += asin(1);"), WithinAbs(kPi / 2, kEps));
    CHECK_THAT(Z("P += asin(0.5);"), WithinAbs(kPi / 6, kEps));
    CHECK_THAT(Z("P += acos(0);"), WithinAbs(kPi / 2, kEps));
    CHECK_THAT(Z("P += acos(-1);"), WithinAbs(kPi, kEps));
    CHECK_THAT(Z("P += atan(1);"), WithinAbs(kPi / 4, kEps));
    // atan(y, x): the angle of (x, y).
    CHECK_THAT(Z("P += atan(1, -1);"), WithinAbs(3 * kPi / 4, kEps));
    CHECK_THAT(Z("P += atan(-1, -1);"), WithinAbs(-3 * kPi / 4, kEps));
    CHECK_THAT(Z("P += atan(0, -1);"), WithinAbs(kPi, kEps));
    CHECK_THAT(Z("P += atan(2, 0);"), WithinAbs(kPi / 2, kEps));
    CHECK_THAT(Z("P += radians(90);"), WithinAbs(kPi / 2, kEps));
    CHECK_THAT(Z("P += degrees(PI / 2);"), WithinAbs(90, kEps));
    CHECK_THAT(Z("P += PI;"), WithinAbs(kPi, kEps));
    CHECK_THAT(Z("P += sin(u * PI);", 0.5), WithinAbs(1, kEps));
}

TEST_CASE("built-ins: length distance normalize and components", "[compiler][semantics][builtins]") {
    CHECK_THAT(Z("P += length(vector(2, 3, 6));"), WithinAbs(7, kEps));
    CHECK_THAT(Z("P += distance(point(1, 2, 3), point(4, 6, 3));"), WithinAbs(5, kEps));
    CHECK_THAT(Z("P += length(P);", 0.6, 0.8), WithinAbs(1, kEps));
    CheckVec(PAt("P = normalize(vector(0, 3, 4));"), {0, 0.6, 0.8});
    CheckVec(PAt("P = normalize(P);", 0.6, 0.8), {0.6, 0.8, 0});
    CHECK_THAT(Z("P += xcomp(point(1, 2, 3)) + 10 * ycomp(point(1, 2, 3)) + 100 * zcomp(point(1, 2, 3));"),
               WithinAbs(321, kEps));
    CHECK_THAT(Z("P += zcomp(N) + ycomp(P);", 0.25, 0.75), WithinAbs(1.75, kEps));
    CHECK_THAT(Z("P += comp(point(4, 5, 6), 0) + comp(vector(4, 5, 6), 2) + comp(color(1, 2, 3), 1);"),
               WithinAbs(12, kEps));
}

TEST_CASE("built-ins: setxcomp setycomp setzcomp setcomp", "[compiler][semantics][builtins]") {
    CheckVec(PAt("setxcomp(P, 5);"), {5, 0.75, 0});
    CheckVec(PAt("setycomp(P, 5);"), {0.25, 5, 0});
    CheckVec(PAt("setzcomp(P, 5);"), {0.25, 0.75, 5});
    CheckVec(PAt("point q = (1, 2, 3); setcomp(q, 0, 7); setcomp(q, 1, 8); P = q;"), {7, 8, 3});
    CheckVec(PAt("vector w = (1, 2, 3); setcomp(w, 2, u); P = w;", 0.25), {1, 2, 0.25});
    CheckVec(PAt("setzcomp(P, u * 2);", 0.25), {0.25, 0.75, 0.5});
    // Under a varying condition.
    CheckVec(PAt("if (u < 0.5) setycomp(P, 9);", 0.25), {0.25, 9, 0});
    CheckVec(PAt("if (u < 0.5) setycomp(P, 9);", 0.75), {0.75, 0.75, 0});
}

TEST_CASE("built-ins: mix", "[compiler][semantics][builtins]") {
    CHECK_THAT(Z("P += mix(0, 10, 0.3);"), WithinAbs(3, kEps));
    CHECK_THAT(Z("P += mix(2, 4, u);", 0.25), WithinAbs(2.5, kEps));
    CheckVec(PAt("P = mix(point(0, 0, 0), point(2, 4, 8), 0.25);"), {0.5, 1, 2});
    CheckVec(PAt("P = mix(P, point(1, 1, 1), 1);"), {1, 1, 1});
}

TEST_CASE("built-ins: faceforward and reflect", "[compiler][semantics][builtins]") {
    // faceforward(N, I) flips N when I . Ng > 0 (Ng = (0, 0, 1)).
    CheckVec(PAt("P = faceforward(normal(0, 0, 1), vector(0, 0, -1));"), {0, 0, 1});
    CheckVec(PAt("P = faceforward(normal(0, 0, 1), vector(0, 0, 1));"), {0, 0, -1});
    CheckVec(PAt("P = faceforward(normal(0, 1, 0), vector(0, 0, 1));"), {0, -1, 0});
    // faceforward(N, I, Nref) flips N when I . Nref > 0.
    CheckVec(PAt("P = faceforward(normal(1, 0, 0), vector(1, 0, 0), normal(1, 0, 0));"), {-1, 0, 0});
    CheckVec(PAt("P = faceforward(normal(1, 0, 0), vector(1, 0, 0), normal(-1, 0, 0));"), {1, 0, 0});
    // reflect(I, N) = I - 2 (I . N) N
    CheckVec(PAt("P = reflect(vector(1, -1, 0), normal(0, 1, 0));"), {1, 1, 0});
    CheckVec(PAt("P = reflect(vector(1, 2, 3), normal(0, 0, 1));"), {1, 2, -3});
}

TEST_CASE("built-ins: calculatenormal", "[compiler][semantics][builtins]") {
    // P = (u, v, uv): Du(P) = (1, 0, v), Dv(P) = (0, 1, u), cross = (-v, -u, 1).
    const std::string src = Shader("P += u * v * N; N = calculatenormal(P);");
    CheckVec(Eval(src, 0.25, 0.75, {}, Generic::Check, "N"), {-0.75, -0.25, 1});
    CheckVec(Eval(src, 0.5, 0.5, {}, Generic::Check, "N"), {-0.5, -0.5, 1});
    CheckVec(Eval(src, 0.25, 0.75), {0.25, 0.75, 0.1875});
    // A flat P: (0, 0, 1).
    CheckVec(Eval(Shader("N = calculatenormal(P);"), 0.25, 0.75, {}, Generic::Check, "N"), {0, 0, 1});
    // A normal passed where a point is expected (as real shaders do): Du = (1, 0, 0), Dv = (0, 1, 0).
    CheckVec(Eval(Shader("normal nn = normal(u, v, 0); N = calculatenormal(nn);"), 0.25, 0.75, {}, Generic::Check, "N"),
             {0, 0, 1});
}

TEST_CASE("built-ins: Du Dv area Deriv", "[compiler][semantics][builtins]") {
    // d(u^2 v)/du = 2uv = 0.375, d(u^2 v)/dv = u^2 = 0.0625.
    CHECK_THAT(Z("P += Du(u * u * v) + 10 * Dv(u * u * v);", 0.25, 0.75), WithinAbs(0.375 + 0.625, kEps));
    CheckVec(PAt("P = Du(P) + 10 * Dv(P);"), {1, 10, 0});
    CHECK_THAT(Z("P += Du(3) + Dv(3);"), WithinAbs(0, kEps));
    CheckVec(PAt("P = Du(vector(u * u, v, u * v));", 0.25, 0.75), {0.5, 0, 0.75});
    // area(P) = |Du(P) du ^ Dv(P) dv|; P scaled by 2 has 4 du dv.
    CHECK_THAT(Z("P *= 2; P += area(P) * 1024 * 1024;"), WithinAbs(4, 1e-9));
    // filterwidth(x) = |Du(x) du| + |Dv(x) dv|, at least 1e-6: 8 du + 2 dv for 8u - 2v;
    // filterwidthp(P) = sqrt(area(P)): 2 du for P scaled by 2 (du = dv).
    CHECK_THAT(Z("P += filterwidth(8 * u - 2 * v) * 1024;"), WithinAbs(10, 1e-9));
    CHECK_THAT(Z("P += filterwidth(3);"), WithinAbs(1e-6, 1e-18));
    CHECK_THAT(Z("P *= 2; P += filterwidthp(P) * 1024;"), WithinAbs(2, 1e-9));
    // Deriv(uv, u + v) = v / 1 + u / 1.
    CHECK_THAT(Z("P += Deriv(u * v, u + v);", 0.25, 0.75), WithinAbs(1, kEps));
    // Derivatives of variables and of user function results.
    CHECK_THAT(ZSource("float sq(float x) { return x * x; }\n" + Shader("float a = sq(u); P += Du(a);"), 0.25),
               WithinAbs(0.5, kEps));
}
