// tests/compiler/value_matrix_test.cpp: the matrix algebra of the shading language (compiler/value_matrix.cpp),
// in RenderMan's row-vector convention, p' = p * M with the translation in the last row:
// construction, transform and vtransform, translate, rotate and scale and their order, product,
// inverse, division and determinant, ntransform, comp and setcomp, comparisons and ?:, and
// matrices as parameters, function arguments, array elements and spaces.
// Part of the language-semantics suite: values worked out by hand on the unit square, each
// cross-checked as tests/compiler/semantics_util.h says.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>

#include "tests/compiler/semantics_util.h"

using namespace affray;
using namespace affray::test::semantics;

namespace {
const char* const kTranslate567 = "matrix t = (1, 0, 0, 0,  0, 1, 0, 0,  0, 0, 1, 0,  5, 6, 7, 1);";
}  // namespace

TEST_CASE("matrices: construction, transform and vtransform", "[compiler][semantics][matrix]") {
    CheckVec(PAt(std::string(kTranslate567) + " P = transform(t, point(1, 2, 3));"), {6, 8, 10});
    CheckVec(PAt(std::string(kTranslate567) + " P = vtransform(t, vector(1, 2, 3));"), {1, 2, 3});
    // A float is that float times the identity; w = 2 divides out of a point.
    CheckVec(PAt("matrix m = 2; P = transform(m, point(1, 2, 3));"), {1, 2, 3});
    CheckVec(PAt("matrix m = 2; P = vtransform(m, vector(1, 2, 3));"), {2, 4, 6});
    CheckVec(PAt("matrix m = 0; m = 3; P = vtransform(m, vector(1, 2, 3));"), {3, 6, 9});
    // A projective matrix: w = 1 + x.
    CheckVec(PAt("matrix m = (1, 0, 0, 1,  0, 1, 0, 0,  0, 0, 1, 0,  0, 0, 0, 1); P = transform(m, point(1, 2, 4));"),
             {0.5, 1, 2});
    // Varying entries: the translation follows u (0.25) and v (0.75).
    CheckVec(PAt("matrix m = (1, 0, 0, 0,  0, 1, 0, 0,  0, 0, 1, 0,  u, v, u * v, 1); P = transform(m, P);"),
             {0.5, 1.5, 0.1875});
    // Every argument form: transform(from, m, x) goes from `from` to current first (the identity here).
    CheckVec(PAt(std::string(kTranslate567) + " P = transform(\"object\", t, point(0, 0, 0));"), {5, 6, 7});
}

TEST_CASE("matrices: translate, rotate, scale and their order", "[compiler][semantics][matrix]") {
    CheckVec(PAt("P = transform(translate(matrix 1, vector(1, 2, 3)), point(0, 0, 0));"), {1, 2, 3});
    CheckVec(PAt("P = transform(scale(matrix 1, point(2, 3, 4)), point(1, 1, 1));"), {2, 3, 4});
    // About +z by 90 degrees, x turns to y and y to -x; about +x, y turns to z.
    CheckVec(PAt("P = transform(rotate(matrix 1, PI / 2, vector(0, 0, 1)), point(1, 0, 0));"), {0, 1, 0});
    CheckVec(PAt("P = transform(rotate(matrix 1, PI / 2, vector(0, 0, 3)), point(0, 1, 0));"), {-1, 0, 0});
    CheckVec(PAt("P = transform(rotate(matrix 1, PI / 2, vector(1, 0, 0)), point(0, 1, 0));"), {0, 0, 1});
    // 120 degrees about (1,1,1) permutes the axes: x -> y.
    CheckVec(PAt("P = transform(rotate(matrix 1, 2 * PI / 3, vector(1, 1, 1)), point(1, 0, 0));"), {0, 1, 0});
    // The new transform applies first, then m (as RiTranslate concatenates): translate(scale)
    // moves then scales, scale(translate) scales then moves.
    CheckVec(PAt("P = transform(translate(scale(matrix 1, point(2, 2, 2)), vector(1, 0, 0)), point(0, 0, 0));"),
             {2, 0, 0});
    CheckVec(PAt("P = transform(scale(translate(matrix 1, vector(1, 0, 0)), point(2, 2, 2)), point(0, 0, 0));"),
             {1, 0, 0});
    // rotate(Q, angle, P0, P1): about the line through P0 and P1.
    CheckVec(PAt("P = rotate(point(1, 0, 0), PI / 2, point(0, 0, 0), point(0, 0, 1));"), {0, 1, 0});
    CheckVec(PAt("P = rotate(point(2, 1, 0), PI / 2, point(1, 1, 0), point(1, 1, 5));"), {1, 2, 0});
}

TEST_CASE("matrices: product, inverse, division and determinant", "[compiler][semantics][matrix]") {
    const std::string m =
        "matrix m = translate(rotate(scale(matrix 1, point(2, 3, 0.5)), 0.7, vector(1, 2, 3)), "
        "vector(4, -1, 2));";
    const std::string n = "matrix n = rotate(translate(matrix 1, vector(-2, 1, 1)), -1.1, vector(0, 1, 1));";
    // (m * n) applies m, then n.
    CheckVec(PAt(m + n + " P = transform(m * n, point(1, 2, 3));"),
             PAt(m + n + " P = transform(n, transform(m, point(1, 2, 3)));"), 1e-12);
    // 1/m undoes m; m/n is m times n's inverse.
    CheckVec(PAt(m + " P = transform(1 / m, transform(m, point(1, 2, 3)));"), {1, 2, 3}, 1e-12);
    CheckVec(PAt(m + n + " P = transform(n, transform(m / n, point(1, 2, 3)));"),
             PAt(m + " P = transform(m, point(1, 2, 3));"), 1e-12);
    CheckVec(PAt(m + " m /= m; P = transform(m, point(1, 2, 3));"), {1, 2, 3}, 1e-12);
    CheckVec(PAt(m + " m *= 1 / m; P = transform(m, point(1, 2, 3));"), {1, 2, 3}, 1e-12);
    // A matrix divided by a float divides every entry (w too: the point is unchanged).
    CheckVec(PAt("matrix d = (matrix 1) / 4; P = vtransform(d, vector(4, 8, 12));"), {1, 2, 3});
    // Determinants: the product of the scales; a rotation's is 1; a row swap negates.
    CHECK_THAT(Z("P += determinant(scale(matrix 1, point(2, 3, 4)));"), WithinAbs(24, kEps));
    CHECK_THAT(Z(m + " P += determinant(m);"), WithinAbs(3, 1e-12));
    CHECK_THAT(Z("P += determinant((0, 1, 0, 0,  1, 0, 0, 0,  0, 0, 1, 0,  0, 0, 0, 1));"), WithinAbs(-1, kEps));
    // A general matrix, by hand: expanding along row 3 gives 2 * det(3x3) = 2 * (1*(4*1-0*2) - 2*(0*1-0*2) + 3*(0*2-4*0)) ... = 8
    CHECK_THAT(Z("P += determinant((1, 2, 3, 0,  0, 4, 5, 0,  0, 0, 1, 0,  7, 8, 9, 2));"), WithinAbs(8, kEps));
    // A singular matrix has no inverse: NaN or infinity, never a wrong number.
    const glm::dvec3 singular = PAt("matrix z = 0; P = transform(1 / z, point(1, 2, 3));");
    CHECK(!std::isfinite(singular.x));
}

TEST_CASE("matrices: ntransform keeps normals perpendicular", "[compiler][semantics][matrix]") {
    // Scaling x by 2: the normal of the plane x + y = c becomes (1/2, 1, 0).
    CheckVec(PAt("P = ntransform(scale(matrix 1, point(2, 1, 1)), normal(1, 1, 0));"), {0.5, 1, 0});
    // A rotation turns normals like vectors.
    CheckVec(PAt("P = ntransform(rotate(matrix 1, PI / 2, vector(0, 0, 1)), normal(1, 0, 0));"), {0, 1, 0});
}

TEST_CASE("matrices: comp, setcomp, comparisons and ?:", "[compiler][semantics][matrix]") {
    CHECK_THAT(Z(std::string(kTranslate567) + " P += comp(t, 3, 1);"), WithinAbs(6, kEps));
    CHECK_THAT(Z(std::string(kTranslate567) + " P += comp(t, 0, 0) + comp(t, 0, 3);"), WithinAbs(1, kEps));
    CheckVec(PAt(std::string(kTranslate567) + " setcomp(t, 3, 0, 9); P = transform(t, point(0, 0, 0));"), {9, 6, 7});
    // Under a varying condition, setcomp writes only where it runs.
    CHECK_THAT(Z("matrix m = 1; if (u > 0.5) setcomp(m, 3, 2, 4); P = transform(m, P);", 0.75), WithinAbs(4, kEps));
    CHECK_THAT(Z("matrix m = 1; if (u > 0.5) setcomp(m, 3, 2, 4); P = transform(m, P);", 0.25), WithinAbs(0, kEps));
    CHECK_THAT(Z("P += (matrix 1) == (1, 0, 0, 0,  0, 1, 0, 0,  0, 0, 1, 0,  0, 0, 0, 1);"), WithinAbs(1, kEps));
    CHECK_THAT(Z("P += (matrix 1) == 1;"), WithinAbs(1, kEps));
    CHECK_THAT(Z("P += (matrix 1) != 2;"), WithinAbs(1, kEps));
    CHECK_THAT(Z(std::string(kTranslate567) + " P += t == 1;"), WithinAbs(0, kEps));
    CHECK_THAT(Z("matrix m = u < 0.5 ? matrix 2 : 1; P += determinant(m);", 0.25), WithinAbs(16, kEps));
    CHECK_THAT(Z("matrix m = u < 0.5 ? matrix 2 : 1; P += determinant(m);", 0.75), WithinAbs(1, kEps));
}

TEST_CASE("matrices: parameters, functions, arrays and spaces", "[compiler][semantics][matrix]") {
    // A parameter takes 16 numbers (or one: that times the identity).
    const std::string source = Shader("P = transform(m, P);", "matrix m = 1");
    const Overrides moved{{"m", {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 1, 2, 3, 1}}};
    CheckVec(Eval(source, 0.25, 0.75), {0.25, 0.75, 0});
    CheckVec(Eval(source, 0.25, 0.75, moved), {1.25, 2.75, 3});
    CheckVec(Eval(Shader("P = vtransform(m, P);", "matrix m = 1"), 0.25, 0.75, {{"m", {2}}}), {0.5, 1.5, 0});
    // Functions take and return matrices; output parameters write them back.
    CheckVec(PAt("matrix twice(matrix a) { return a * a; }\n"
                 "P = transform(twice(translate(matrix 1, vector(1, 0, 0))), point(0, 0, 0));"),
             {2, 0, 0});
    CheckVec(PAt("void shift(output matrix a) { a = translate(a, vector(0, 0, 1)); }\n"
                 "matrix m = 1; shift(m); shift(m); P = transform(m, point(0, 0, 0));"),
             {0, 0, 2});
    // Arrays of matrices, with a varying index.
    CheckVec(PAt("matrix a[2] = {matrix 1, translate(matrix 1, vector(0, 1, 0))};\n"
                 "P = transform(a[u > 0.5], point(0, 0, 0));",
                 0.75),
             {0, 1, 0});
    // `matrix "space" 1` maps current to that space, like transform("space", x).
    const glm::dvec3 viaMatrix = PAt("P = transform(matrix \"shader\" 1, P);");
    CheckVec(viaMatrix, PAt("P = transform(\"shader\", P);"));
}
