// tests/compiler/library_test.cpp: RenderMan's library as the compiler knows it. docs/builtins.md
// lists every built-in (a built-in missing from the table, or a row naming none, fails here);
// the values of the built-ins composed in compiler/lower_extras.cpp and builtins_color.cpp; the
// surface shaders' functions (compiler/lower_surface.cpp) accepted until they are called; the
// queries folded per instance (option, attribute, rendererinfo, displacement) and depth.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <set>
#include <sstream>

#include "compiler/builtins.h"
#include "compiler/regex_match.h"
#include "compiler/shader_cache.h"
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

TEST_CASE("mix with a color or point t mixes component by component", "[compiler][library]") {
    // x (1 - t) + y t per component; the result has x and y's type.
    test::RequireVec(PAt("color c = mix(color(0, 0, 0), color(1, 2, 4), color(0.5, 0.25, 1));\n"
                         "P = point(comp(c, 0), comp(c, 1), comp(c, 2));"),
                     {0.5, 0.5, 4});
    test::RequireVec(PAt("P = mix(point(0, 0, 0), point(2, 2, 2), color(0, 0.5, 1));"), {0, 1, 2});
    test::RequireVec(PAt("P = mix(point(2, 2, 2), point 0, vector(0, 0.5, 1));"), {2, 1, 0});
    test::RequireVec(PAt("color c = mix(1, 3, color(0, 0.5, 1)); P = point(comp(c, 0), comp(c, 1), comp(c, 2));"),
                     {1, 2, 3});
    // A float t still takes the float form, and mixing a point into a color is no version.
    test::RequireVec(PAt("P = mix(point(0, 0, 0), point(2, 4, 6), 0.5);"), {1, 2, 3});
    compiler::CompileResult wrong = Compile("displacement t() { color c = mix(P, P, color 1); P += c; }");
    CHECK_FALSE(wrong.ok());
}

namespace {

/// Camera space 5 units behind the world origin along -z (world z = 0 is at camera depth 5).
compiler::Spaces CameraBehind() {
    compiler::SpaceTransform camera;
    camera.toCurrent = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, -5, 0, 0, 0, 1};
    camera.fromCurrent = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 5, 0, 0, 0, 1};
    return {{"camera", camera}};
}

compiler::SceneFacts Facts(double nearClip, double farClip) {
    compiler::SceneFacts facts;
    facts.options["Clipping"] = {{nearClip, farClip}, std::nullopt};
    facts.options["Format"] = {{640, 480, 1}, std::nullopt};
    facts.attributes["Sides"] = {{1}, std::nullopt};
    return facts;
}

/// P of `body` compiled with the spaces of CameraBehind and `facts` (none: no scene).
glm::dvec3 PWith(const std::string& body, const compiler::SceneFacts* facts, double u = 0.5, double v = 0.25) {
    const compiler::Spaces spaces = CameraBehind();
    compiler::CompileResult r = compiler::CompileSource(
        "s.sl", "displacement s(float Km = 0.5; float arr[2] = {3, 4}) {\n" + body + "\n}\n", {}, {}, &spaces, facts);
    INFO(r.diagnostics.format());
    REQUIRE(r.ok());
    return test::PointOnSquare(r.shader->shade, u, v);  // P = (u, v, 0) there
}

}  // namespace

TEST_CASE("depth is camera-space z between the instance's clipping planes", "[compiler][library]") {
    const compiler::SceneFacts facts = Facts(1, 9);
    // World z = 0 is camera depth 5: (5 - 1) / (9 - 1).
    CHECK_THAT(PWith("P = point(depth(P), 0, 0);", &facts).x, WithinAbs(0.5, 1e-15));
    // The far plane (camera depth 9) is 1, the near one (1) is 0, and past them it goes on.
    test::RequireVec(PWith("P = point(depth(point(0, 0, 4)), depth(point(0, 0, -4)), depth(point(1, 2, 7)));", &facts),
                     {1, 0, 1.375});
    // Without a scene: RenderMan's default planes, 1e-10 and 1e30.
    CHECK_THAT(PWith("P = point(depth(P), 0, 0);", nullptr).x, WithinAbs((5 - 1e-10) / (1e30 - 1e-10), 1e-40));
    CHECK_FALSE(Compile("displacement t() { P += depth(1, 2) * N; }").ok());
    CHECK_FALSE(Compile("displacement t() { P += depth(\"x\") * N; }").ok());
    // The shader cache tells instances with other planes apart.
    test::TempDir dir;
    dir.Write("d.sl", "displacement d() { P = point(depth(P), 0, 0); }");
    compiler::ShaderCache cache;
    const compiler::Spaces spaces = CameraBehind();
    const compiler::SceneFacts other = Facts(1, 5);
    CHECK_THAT(test::PointOnSquare(cache.Load(dir.Path("d.sl"), {}, {}, &spaces, &facts).shader->shade, 0, 0).x,
               WithinAbs(0.5, 1e-15));
    CHECK_THAT(test::PointOnSquare(cache.Load(dir.Path("d.sl"), {}, {}, &spaces, &other).shader->shade, 0, 0).x,
               WithinAbs(1, 1e-15));
    CHECK(cache.misses() == 2);
}

TEST_CASE("option, attribute and rendererinfo fold per instance", "[compiler][library]") {
    const compiler::SceneFacts facts = Facts(1, 9);
    // Known with the right type: 1, and the variable written.
    test::RequireVec(PWith("float f[3]; float k = option(\"Format\", f); P = point(k, f[0], f[1] + f[2]);", &facts),
                     {1, 640, 481});
    test::RequireVec(PWith("float c[2]; float k = option(\"Clipping\", c); P = point(k, c[0], c[1]);", &facts),
                     {1, 1, 9});
    test::RequireVec(PWith("float s = 7; float k = attribute(\"Sides\", s); P = point(k, s, 0);", &facts), {1, 1, 0});
    // Unknown, or the wrong type or array size: 0, and the variable unchanged.
    test::RequireVec(PWith("float f[2] = {5, 6}; float k = option(\"Format\", f); P = point(k, f[0], f[1]);", &facts),
                     {0, 5, 6});
    test::RequireVec(
        PWith("float x = 5; float k = option(\"Format\", x) + option(\"Nope\", x); P = point(k, x, 0);", &facts),
        {0, 5, 0});
    test::RequireVec(PWith("string s = \"-\"; float k = attribute(\"Sides\", s); P = point(k, 0, 0);", &facts),
                     {0, 0, 0});
    test::RequireVec(PWith("float x = 5; float k = attribute(\"identifier:name\", x); P = point(k, x, 0);", &facts),
                     {0, 5, 0});
    // Without a scene, no option or attribute is known.
    test::RequireVec(PWith("float f[3] = {1, 2, 3}; float k = option(\"Format\", f); P = point(k, f[0], 0);", nullptr),
                     {0, 1, 0});
    // rendererinfo is the same everywhere; a string it writes folds like any constant string.
    test::RequireVec(PWith("string r, vs; float ver[4];\n"
                           "float k = rendererinfo(\"renderer\", r) + rendererinfo(\"version\", ver) +\n"
                           "          rendererinfo(\"versionstring\", vs) + rendererinfo(\"nope\", r);\n"
                           "P = point(k, match(\"^affray$\", r), ver[1] + match(\"^0[.]1\", vs));",
                           nullptr),
                     {3, 1, 2});
    // A branch on the answer folds: the arm that does not apply leaves no code.
    test::RequireVec(
        PWith("float f[3]; if (option(\"Format\", f) == 1) P = point(f[0] / 640, 0, 0); else P = 0;", &facts),
        {1, 0, 0});
    // The name must be a string known when the shader is compiled.
    CHECK_FALSE(Compile("displacement t() { float x; P += option(1, x) * N; }").ok());
    compiler::CompileResult varying =
        Compile("displacement t() { float x; string s = u > 0.5 ? \"a\" : \"b\"; P += option(s, x) * N; }");
    CHECK_FALSE(varying.ok());
}

TEST_CASE("displacement() reads the shader's own parameters", "[compiler][library]") {
    test::RequireVec(PWith("float k = 0; float r = displacement(\"Km\", k); P = point(r, k, 0);", nullptr),
                     {1, 0.5, 0});
    test::RequireVec(PWith("float a[2]; float r = displacement(\"arr\", a); P = point(r, a[0], a[1]);", nullptr),
                     {1, 3, 4});
    // The wrong type, array size or name: 0, and the variable unchanged.
    test::RequireVec(PWith("color c = 2; float r = displacement(\"Km\", c) + displacement(\"nope\", c);\n"
                           "float a[3] = {7, 8, 9}; r += displacement(\"arr\", a); P = point(r, comp(c, 0), a[0]);",
                           nullptr),
                     {0, 2, 7});
    // From a helper function too: the shader's parameter, not the helper's of that name.
    const std::string helper = "float km(float Km) { float k = 0; displacement(\"Km\", k); return k + Km; }\n";
    compiler::CompileResult r =
        compiler::CompileSource("s.sl", helper + "displacement s(float Km = 0.5) { P = point(km(10), 0, 0); }\n", {});
    REQUIRE(r.ok());
    CHECK_THAT(test::PointOnSquare(r.shader->shade, 0, 0).x, WithinAbs(10.5, 1e-15));
}

TEST_CASE("surface, displacement and atmosphere parse as calls and check like surface functions",
          "[compiler][library]") {
    // In a helper nobody calls: type-checked, accepted; `surface name()` still defines a shader.
    const std::string helper =
        "float kd() { float k = 1; surface(\"Kd\", k); atmosphere(\"d\", k); lightsource(\"i\", k); "
        "displacement(\"Km\", k); return k; }\n";
    CHECK(Compile(helper + "displacement t() { P += N; }").ok());
    compiler::CompileResult called = Compile(helper + "displacement t() { P += kd() * N; }");
    REQUIRE_FALSE(called.ok());
    CHECK(called.diagnostics.format().find("'surface' is a function of surface and light shaders") !=
          std::string::npos);
    CHECK(called.diagnostics.format().find("'atmosphere' is a function of surface and light shaders") !=
          std::string::npos);
    CHECK(called.diagnostics.format().find("'displacement'") == std::string::npos);
    CHECK_FALSE(Compile("float f() { return surface(\"Kd\"); }\ndisplacement t() { P += N; }").ok());
    CHECK_FALSE(Compile("float f() { return surface(1, 2); }\ndisplacement t() { P += N; }").ok());
    // A surface shader compiles, but does not get these queries yet.
    compiler::CompileResult surfaceShader = Compile("surface s() { float k; surface(\"Kd\", k); Ci = k; }");
    CHECK_FALSE(surfaceShader.ok());
    CHECK(surfaceShader.diagnostics.format().find("function 'surface' is not supported yet in surface shaders") !=
          std::string::npos);
}
