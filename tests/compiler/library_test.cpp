// tests/compiler/library_test.cpp: RenderMan's library as the compiler knows it. docs/builtins.md
// lists every built-in (a built-in missing from the table, or a row naming none, fails here);
// the values of the built-ins composed in compiler/lower_extras.cpp and builtins_color.cpp; the
// surface shaders' functions (compiler/lower_surface.cpp) accepted until they are called.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <set>
#include <sstream>

#include "compiler/builtins.h"
#include "compiler/regex_match.h"
#include "tests/test_util.h"

using namespace affray;
using Catch::Matchers::WithinAbs;

namespace {

/// The displaced P of `body` (statements of a displacement shader) at (u, v).
glm::dvec3 PAt(const std::string& body, double u = 0.25, double v = 0.5, const std::string& before = "") {
    compiler::CompiledShader s = test::CompileOrThrow(before + "displacement t() {\n" + body + "\n}\n");
    return test::PointOnSquare(s.shade, u, v);
}

compiler::CompileResult Compile(const std::string& source) { return compiler::CompileSource("test.sl", source, {}); }

}  // namespace

TEST_CASE("docs/builtins.md lists every built-in the compiler knows, and no other", "[compiler][library]") {
    const std::string doc = test::ReadText(test::SourceDir() + "/docs/builtins.md");
    REQUIRE(!doc.empty());
    // Rows of the table: "| `name` | ...".
    std::set<std::string> listed;
    std::istringstream lines(doc);
    // (Read by hand, not with <regex>: GCC 12 warns inside libstdc++'s regex in the sanitizer build.)
    for (std::string line; std::getline(lines, line);) {
        if (line.rfind("| `", 0) != 0) continue;
        const size_t end = line.find("` |", 3);
        const std::string name = end == std::string::npos ? "" : line.substr(3, end - 3);
        const bool identifier = !name.empty() && !std::isdigit(static_cast<unsigned char>(name[0])) &&
                                std::all_of(name.begin(), name.end(), [](char c) {
                                    return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
                                });
        if (identifier) listed.insert(name);
    }
    const std::vector<std::string> known = compiler::KnownBuiltinNames();
    for (const std::string& name : known) {
        INFO("built-in '" << name << "' has no row in docs/builtins.md");
        CHECK(listed.count(name));
    }
    for (const std::string& name : listed) {
        INFO("docs/builtins.md lists '" << name << "', which the compiler does not know");
        CHECK(std::find(known.begin(), known.end(), name) != known.end());
    }
}

TEST_CASE("ctransform converts among rgb, hsv, hsl, xyz, xyY and YIQ", "[compiler][library]") {
    // Red in hsv is (0, 1, 1); hsl (0, 1, 0.5); white's XYZ is D65's (0.9505, 1, 1.0888).
    test::RequireVec(PAt("color c = ctransform(\"hsv\", color(1, 0, 0)); P = point(comp(c, 0), comp(c, 1), "
                         "comp(c, 2));"),
                     {0, 1, 1});
    test::RequireVec(PAt("color c = ctransform(\"rgb\", \"hsl\", color(1, 0, 0)); P = point(comp(c, 0), comp(c, "
                         "1), comp(c, 2));"),
                     {0, 1, 0.5});
    const glm::dvec3 white = PAt("color c = ctransform(\"XYZ\", 1); P = point(comp(c, 0), comp(c, 1), comp(c, 2));");
    CHECK_THAT(white.x, WithinAbs(0.950456, 1e-5));
    CHECK_THAT(white.y, WithinAbs(1.0, 1e-5));
    CHECK_THAT(white.z, WithinAbs(1.088754, 1e-5));
    // From hsv back to rgb, with a varying hue through all six sectors.
    for (double u : {0.05, 0.2, 0.4, 0.55, 0.7, 0.9}) {
        const glm::dvec3 rgb =
            PAt("color c = ctransform(\"hsv\", \"rgb\", color(u, 1, 1)); P = point(comp(c, 0), "
                "comp(c, 1), comp(c, 2));",
                u);
        const glm::dvec3 back =
            PAt("color c = ctransform(\"hsv\", ctransform(\"hsv\", \"rgb\", color(u, 0.5, "
                "0.75))); P = point(comp(c, 0), comp(c, 1), comp(c, 2));",
                u);
        INFO("hue " << u);
        CHECK_THAT(std::max({rgb.x, rgb.y, rgb.z}), WithinAbs(1.0, 1e-12));
        CHECK_THAT(std::min({rgb.x, rgb.y, rgb.z}), WithinAbs(0.0, 1e-12));
        test::RequireVec(back, {u, 0.5, 0.75});
    }
}

TEST_CASE("refract, fresnel and ptlined", "[compiler][library]") {
    // Straight through at normal incidence; total internal reflection gives (0, 0, 0).
    test::RequireVec(PAt("P = refract(vector(0, 0, -1), normal(0, 0, 1), 0.5);"), {0, 0, -1});
    test::RequireVec(PAt("P = refract(normalize(vector(1, 0, -0.1)), normal(0, 0, 1), 1.5);"), {0, 0, 0});
    // Normal incidence: Kr = ((n - 1) / (n + 1))^2 = 0.04 for n = 1.5.
    const glm::dvec3 f =
        PAt("float kr, kt; fresnel(vector(0, 0, -1), normal(0, 0, 1), 1 / 1.5, kr, kt); "
            "P = point(kr, kt, kr + kt);");
    CHECK_THAT(f.x, WithinAbs(0.04, 1e-12));
    CHECK_THAT(f.z, WithinAbs(1.0, 1e-12));
    // Past the ends of the segment, the distance to the nearer end.
    test::RequireVec(PAt("P = point(ptlined(0, point(1, 0, 0), point(0.5, 2, 0)), ptlined(0, point(1, 0, 0), "
                         "point(3, 0, 0)), ptlined(1, 1, 4));"),
                     {2, 2, std::sqrt(27.0)});
}

TEST_CASE("random is deterministic, between 0 and 1, and differs between calls", "[compiler][library]") {
    const std::string body = "P = point(random(), random(), float random());";
    const glm::dvec3 a = PAt(body, 0.3, 0.6), b = PAt(body, 0.3, 0.6), c = PAt(body, 0.31, 0.6);
    test::RequireVec(a, b);
    CHECK(a.x != a.y);
    CHECK(a.x != c.x);
    for (double x : {a.x, a.y, a.z, c.x}) CHECK((x >= 0 && x < 1));
}

TEST_CASE("use before assignment is a warning and reads 0", "[compiler][library]") {
    compiler::CompileResult r = Compile("displacement t() { float x; P += (x + 1) * N; }");
    REQUIRE(r.ok());
    CHECK(r.diagnostics.format().find("warning: variable 'x' is used before it is assigned a value") !=
          std::string::npos);
    test::RequireVec(PAt("float x; vector w; setzcomp(w, 2); P = point(x + 1, 0, zcomp(w));"), {1, 0, 2});
}

TEST_CASE("surface shaders' functions: accepted in helpers nobody calls, an error when called", "[compiler][library]") {
    const std::string helper =
        "color lit(normal n) { color c = diffuse(n) + Cs; illuminance(P) { c += Cl; } "
        "return c; }\n";
    CHECK(Compile(helper + "displacement t() { P += N; }").ok());
    compiler::CompileResult called = Compile(helper + "displacement t() { color c = lit(N); P += N; }");
    REQUIRE(!called.ok());
    CHECK(called.diagnostics.format().find("'diffuse' is a function of surface and light shaders") !=
          std::string::npos);
    // Type errors are reported even where nothing calls the function.
    CHECK(!Compile("color lit() { return diffuse(\"n\"); }\ndisplacement t() { P += N; }").ok());
}

TEST_CASE("Deriv of a function of u alone is its derivative, not 0/0 from Dv", "[compiler][library]") {
    CHECK_THAT(PAt("P = point(Deriv(u * u, u), Deriv(v * u, v), 0);", 0.3, 0.4).x, WithinAbs(0.6, 1e-12));
    CHECK_THAT(PAt("P = point(Deriv(u * u, u), Deriv(v * u, v), 0);", 0.3, 0.4).y, WithinAbs(0.3, 1e-12));
}

TEST_CASE("match searches a regular expression, and an invalid or overlong one is an error at the pattern",
          "[compiler][library]") {
    test::RequireVec(PAt("P = point(match(\"^ab+c$\", \"abbbc\"), match(\"x\", \"abc\"), match(\"b|z\", \"abc\"));"),
                     {1, 0, 1});
    const compiler::CompileResult invalid = Compile("displacement t() { P += match(\"a(\", \"a\") * N; }");
    CHECK(!invalid.ok());
    CHECK(invalid.diagnostics.format().find("test.sl:1:31: error: invalid regular expression 'a('") !=
          std::string::npos);
    // A long subject would take libstdc++'s recursive matcher deep into the stack: refused instead.
    const std::string longText(compiler::kMaxMatchLength + 1, 'a');
    const compiler::CompileResult overlong =
        Compile("displacement t() { P += match(\"a*\", \"" + longText + "\") * N; }");
    CHECK(!overlong.ok());
    CHECK(overlong.diagnostics.format().find("error: 'match' takes strings of at most 1000 characters") !=
          std::string::npos);
    CHECK(Compile("displacement t() { P += match(\"a*\", \"" + longText.substr(1) + "\") * N; }").ok());
}
