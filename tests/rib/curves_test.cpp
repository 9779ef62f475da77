// tests/rib/curves_test.cpp: rib/curves.cpp. Curves become truncated cones (Hyperboloid quadrics)
// along them: one a segment of a linear curve, kCubicPieces (8) a span of a cubic one, their ends
// on the curve (checked against the bases written out by hand), their radii half the widths, and
// their colours the curve's at the piece's middle; and each malformed request is refused, located.
#include <catch2/catch.hpp>
#include <string>
#include <vector>

#include "tests/rib/rib_test_util.h"

using namespace affray;
using namespace affray::test;
using renderer::PrimitiveDesc;

namespace {

/// A piece's cone: the ends of its axis in world space and its radii there.
struct Cone {
    glm::dvec3 a, b;
    double ra, rb;
};

Cone ConeOf(const PrimitiveDesc& p) {
    REQUIRE(p.base.kind() == renderer::BaseSurface::Kind::Quadric);
    const renderer::PlacedQuadric& q = p.base.quadric();
    REQUIRE(q.quadric.kind == renderer::Quadric::Kind::Hyperboloid);
    CHECK(q.quadric.point1[1] == 0);
    CHECK(q.quadric.point1[2] == 0);
    CHECK(q.quadric.point2[1] == 0);
    CHECK(q.quadric.thetamax == 360);
    const glm::dvec3 a(q.objectToWorld * glm::dvec4(0, 0, 0, 1));
    const glm::dvec3 b(q.objectToWorld * glm::dvec4(0, 0, q.quadric.point2[2], 1));
    return {a, b, q.quadric.point1[0], q.quadric.point2[0]};
}

void CheckNear(const glm::dvec3& x, const glm::dvec3& y) {
    INFO(x.x << " " << x.y << " " << x.z << " against " << y.x << " " << y.y << " " << y.z);
    CHECK(glm::length(x - y) < 1e-12);
}

}  // namespace

TEST_CASE("rib: a linear curve is one cone a segment, with varying widths and uniform colours", "[rib][curves]") {
    diag::Report report;
    const renderer::SceneDesc scene = ParseWorld(
        "Translate 0 0 1\n"
        "Curves \"linear\" [3 2] \"nonperiodic\" \"P\" [0 0 0  1 0 0  1 2 0   5 5 5  5 5 6]\n"
        "  \"width\" [0.2 0.4 0.6  1 3] \"Cs\" [1 0 0  0 0 1]\n"
        "Curves \"linear\" [3] \"periodic\" \"P\" [0 0 0  1 0 0  0 1 0] \"constantwidth\" [0.1]",
        &report);
    REQUIRE(scene.primitives.size() == 3 + 3);
    const Cone c0 = ConeOf(scene.primitives[0]), c1 = ConeOf(scene.primitives[1]), c2 = ConeOf(scene.primitives[2]);
    CheckNear(c0.a, {0, 0, 1});
    CheckNear(c0.b, {1, 0, 1});
    CheckNear(c1.a, {1, 0, 1});
    CheckNear(c1.b, {1, 2, 1});
    CheckNear(c2.a, {5, 5, 6});
    CheckNear(c2.b, {5, 5, 7});
    CHECK(c0.ra == Approx(0.1));
    CHECK(c0.rb == Approx(0.2));
    CHECK(c1.rb == Approx(0.3));
    CHECK(c2.ra == Approx(0.5));
    CHECK(c2.rb == Approx(1.5));
    CHECK(scene.primitives[0].color == glm::dvec3(1, 0, 0));
    CHECK(scene.primitives[2].color == glm::dvec3(0, 0, 1));
    // The periodic triangle closes: its third segment runs from the last vertex to the first.
    const Cone closing = ConeOf(scene.primitives[5]);
    CheckNear(closing.a, {0, 1, 1});
    CheckNear(closing.b, {0, 0, 1});
    CHECK(closing.ra == Approx(0.05));
}

TEST_CASE("rib: a cubic curve is eight cones a span, their ends on the curve", "[rib][curves]") {
    // A bezier span (step 3: 7 vertices are two spans) and a periodic b-spline of 4 vertices (4 spans).
    const glm::dvec3 b[7] = {{0, 0, 0}, {1, 2, 0}, {2, 2, 0}, {3, 0, 0}, {4, -2, 1}, {5, -2, 1}, {6, 0, 0}};
    std::string points;
    for (const glm::dvec3& p : b)
        points += std::to_string(p.x) + " " + std::to_string(p.y) + " " + std::to_string(p.z) + "  ";
    diag::Report report;
    const renderer::SceneDesc scene =
        ParseWorld("Curves \"cubic\" [7] \"nonperiodic\" \"P\" [" + points +
                       "] \"vertex float width\" [0 1 1 0 0 1 1]\n"
                       "Basis \"b-spline\" 1 \"b-spline\" 1\n"
                       "Curves \"cubic\" [4] \"periodic\" \"P\" [1 0 0  0 1 0  -1 0 0  0 -1 0] \"varying color Cs\" "
                       "[1 0 0  0 1 0  0 0 1  1 1 1]",
                   &report);
    REQUIRE(scene.primitives.size() == 2 * 8 + 4 * 8);
    const auto bezier = [&](int span, double t) {
        const glm::dvec3* p = &b[3 * span];
        const double s = 1 - t;
        return s * s * s * p[0] + 3 * s * s * t * p[1] + 3 * s * t * t * p[2] + t * t * t * p[3];
    };
    const auto bezierWidth = [](int span, double t) {  // widths 0 1 1 0 (span 0) and 0 0 1 1 (span 1)
        const double s = 1 - t;
        return span == 0 ? 3 * s * s * t + 3 * s * t * t : 3 * s * t * t + t * t * t;
    };
    for (int span = 0; span < 2; ++span)
        for (int piece = 0; piece < 8; ++piece) {
            INFO("span " << span << " piece " << piece);
            const Cone c = ConeOf(scene.primitives[size_t(8 * span + piece)]);
            CheckNear(c.a, bezier(span, piece / 8.0));
            CheckNear(c.b, bezier(span, (piece + 1) / 8.0));
            CHECK(c.ra == Approx(0.5 * bezierWidth(span, piece / 8.0)).margin(1e-12));
            CHECK(c.rb == Approx(0.5 * bezierWidth(span, (piece + 1) / 8.0)).margin(1e-12));
        }
    // The uniform b-spline's span j starts at (P_j + 4 P_j+1 + P_j+2) / 6; colours vary linearly
    // along the span, taken at each piece's middle.
    const glm::dvec3 q[4] = {{1, 0, 0}, {0, 1, 0}, {-1, 0, 0}, {0, -1, 0}};
    const glm::dvec3 cs[4] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 1}};
    for (int span = 0; span < 4; ++span) {
        const Cone first = ConeOf(scene.primitives[size_t(16 + 8 * span)]);
        CheckNear(first.a, (q[span] + 4.0 * q[(span + 1) % 4] + q[(span + 2) % 4]) / 6.0);
        CHECK(first.ra == Approx(0.5));  // RI's default width, 1
        CheckNear(scene.primitives[size_t(16 + 8 * span)].color, glm::mix(cs[span], cs[(span + 1) % 4], 1.0 / 16));
    }
}

TEST_CASE("rib: a declared storage class decides how Curves spread a value, where counts coincide too",
          "[rib][curves]") {
    // A periodic b-spline of vstep 1 has as many varying points as vertices (4): undeclared (and
    // by the standard declaration) the widths are varying, linear along each span; declared
    // "vertex" they go through the basis, as the points do.
    const std::string curve =
        "Basis \"b-spline\" 1 \"b-spline\" 1\n"
        "Curves \"cubic\" [4] \"periodic\" \"P\" [1 0 0  0 1 0  -1 0 0  0 -1 0] ";
    const double w[4] = {0.2, 0.4, 0.6, 0.8};
    const std::string widths = "[0.2 0.4 0.6 0.8]";
    for (const std::string& declared :
         {std::string("\"width\""), std::string("\"varying float width\""), std::string("\"vertex float width\"")}) {
        INFO(declared);
        diag::Report report;
        const renderer::SceneDesc scene = ParseWorld(curve + declared + " " + widths, &report);
        REQUIRE(scene.primitives.size() == 4 * 8);
        const bool vertex = declared.find("vertex") != std::string::npos;
        for (int span = 0; span < 4; ++span) {
            const double start = vertex ? (w[span] + 4 * w[(span + 1) % 4] + w[(span + 2) % 4]) / 6 : w[span];
            CHECK(ConeOf(scene.primitives[size_t(8 * span)]).ra == Approx(0.5 * start).margin(1e-12));
        }
    }
    // Uniform: one width per curve.
    diag::Report report;
    const renderer::SceneDesc two = ParseWorld(
        "Curves \"linear\" [2 2] \"nonperiodic\" \"P\" [0 0 0 1 0 0  0 1 0 1 1 0] \"uniform float width\" [0.2 0.6]",
        &report);
    REQUIRE(two.primitives.size() == 2);
    CHECK(ConeOf(two.primitives[0]).ra == Approx(0.1));
    CHECK(ConeOf(two.primitives[1]).rb == Approx(0.3));
    // A declared class whose count does not fit, or one curves do not have, is refused.
    CHECK(WorldError("Curves \"linear\" [3] \"nonperiodic\" \"P\" [0 0 0 1 0 0 2 0 0] \"uniform float width\" "
                     "[1 2 3]") ==
          "t.rib:2: error: 'Curves' parameter 'width' (uniform float) expects 1 number (1 for each of 1 uniform "
          "value), got 3");
    CHECK(WorldError("Curves \"linear\" [2] \"nonperiodic\" \"P\" [0 0 0 1 0 0] \"facevarying float width\" [1 2]") ==
          "t.rib:2: error: 'Curves' parameter 'width': storage class 'facevarying' is not defined on curves");
}

TEST_CASE("rib: malformed Curves are refused, located", "[rib][curves]") {
    CHECK(WorldError("Curves \"quadratic\" [2] \"nonperiodic\" \"P\" [0 0 0 1 1 1]") ==
          "t.rib:2: error: 'Curves' type must be \"linear\" or \"cubic\", got 'quadratic'");
    CHECK(WorldError("Curves \"linear\" [2] \"closed\" \"P\" [0 0 0 1 1 1]") ==
          "t.rib:2: error: 'Curves' wrap must be \"periodic\" or \"nonperiodic\", got 'closed'");
    CHECK(WorldError("Curves \"linear\" [2] \"nonperiodic\"") == "t.rib:2: error: 'Curves' needs \"P\"");
    CHECK(WorldError("Curves \"linear\" [2 1] \"nonperiodic\" \"P\" [0 0 0 1 1 1 2 2 2]") ==
          "t.rib:2: error: 'Curves' linear curve of 1 vertex: a curve needs 2 or more");
    CHECK(WorldError("Curves \"cubic\" [5] \"nonperiodic\" \"P\" [0 0 0 1 1 1 2 2 2 3 3 3 4 4 4]") ==
          "t.rib:2: error: 'Curves' cubic curve of 5 vertices: with vstep 3 a nonperiodic curve needs 4 + a multiple "
          "of vstep (at least 4)");
    CHECK(WorldError("Curves \"linear\" [2] \"nonperiodic\" \"P\" [0 0 0 1 1]") ==
          "t.rib:2: error: 'Curves' parameter 'P' expects 6 numbers (3 for each of 2 vertices), got 5");
    CHECK(WorldError("Curves \"linear\" [2] \"nonperiodic\" \"P\" [0 0 0 1 1 1] \"width\" [1 2 3]") ==
          "t.rib:2: error: 'Curves' parameter 'width' expects 1, or that per curve, varying point or vertex, numbers "
          "(1 curves, 2 varying points, 2 vertices), got 3");
    CHECK(WorldError("Curves \"linear\" [2] \"nonperiodic\" \"P\" [0 0 0 1 1 1] \"constantwidth\" [1 2]") ==
          "t.rib:2: error: 'Curves' parameter 'constantwidth' expects 1 numbers (1 curves, 2 varying points, 2 "
          "vertices), got 2");
    CHECK(WorldError("Curves \"linear\" [0] \"nonperiodic\" \"P\" []") ==
          "t.rib:2: error: 'Curves' vertex counts must be positive integers, got 0");
}
