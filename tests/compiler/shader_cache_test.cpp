// tests/compiler/shader_cache_test.cpp: compiled shaders are reused by content, never stale;
// string parameters take instance values; coordinate spaces fold into an instance; values for
// parameters a shader does not declare are left out.
#include <catch2/catch.hpp>

#include "compiler/shader_cache.h"
#include "tests/test_util.h"
#include "vm/bytecode_file.h"

using namespace affray;
using Catch::Matchers::WithinAbs;

namespace {
const char* kShader =
    "displacement c(float Km = 1; string mode = \"up\") {\n"
    "  P += (mode == \"up\" ? Km : -Km) * normalize(N);\n"
    "}\n";

double HeightOf(const compiler::CompiledShader& s) { return test::PointOnSquare(s.shade, 0.5, 0.5).z; }
}  // namespace

TEST_CASE("the shader cache reuses a compilation only for the same bytes and values", "[compiler][cache]") {
    test::TempDir dir;
    const std::string path = dir.Write("c.sl", kShader);
    compiler::ShaderCache cache;
    compiler::CompileResult a = cache.Load(path, {{"Km", {2}}}, {});
    compiler::CompileResult b = cache.Load(path, {{"Km", {2}}}, {});
    compiler::CompileResult c = cache.Load(path, {{"Km", {3}}}, {});
    REQUIRE((a.ok() && b.ok() && c.ok()));
    CHECK(cache.hits() == 1);
    CHECK(cache.misses() == 2);
    CHECK_THAT(HeightOf(*b.shader), WithinAbs(2, 0));
    // A hit is the shader compiled before, shared, not a copy (a mesh's faces hold one).
    CHECK(b.shader == a.shader);
    CHECK(c.shader != a.shader);
    CHECK_THAT(HeightOf(*c.shader), WithinAbs(3, 0));

    // The same name with other bytes is another shader: never served stale.
    dir.Write("c.sl", std::string(kShader).replace(std::string(kShader).find("Km : -Km"), 8, "2*Km : -Km"));
    compiler::CompileResult edited = cache.Load(path, {{"Km", {2}}}, {});
    REQUIRE(edited.ok());
    CHECK(cache.misses() == 3);
    CHECK_THAT(HeightOf(*edited.shader), WithinAbs(4, 0));

    // -D changes the key too; failures are not kept.
    cache.Load(path, {{"Km", {2}}}, {{}, {"X=1"}});
    CHECK(cache.misses() == 4);
    CHECK_FALSE(cache.Load(dir.Path("missing.sl"), {}, {}).ok());
    CHECK_FALSE(cache.Load(dir.Path("missing.sl"), {}, {}).ok());
    CHECK(cache.hits() == 1);
}

TEST_CASE("string parameters take instance values", "[compiler][cache]") {
    CHECK_THAT(HeightOf(test::CompileOrThrow(kShader)), WithinAbs(1, 0));
    CHECK_THAT(HeightOf(test::CompileOrThrow(kShader, {compiler::ParamOverride::String("mode", "down")})),
               WithinAbs(-1, 0));
    compiler::CompileResult wrong =
        compiler::CompileSource("c.sl", kShader, {compiler::ParamOverride::String("Km", "x")});
    CHECK(wrong.paramErrors ==
          std::vector<std::string>{"parameter 'Km' of shader 'c' is not a string, got a string value"});
    wrong = compiler::CompileSource("c.sl", kShader, {{"mode", {1}}});
    CHECK(wrong.paramErrors == std::vector<std::string>{"parameter 'mode' of shader 'c' is a string, got a number"});
    // A string value for a parameter the shader does not declare is left out, as a number is.
    wrong = compiler::CompileSource("c.sl", kShader, {compiler::ParamOverride::String("style", "x")});
    CHECK(wrong.ok());
    CHECK(wrong.paramErrors.empty());
    CHECK(wrong.undeclared == std::vector<std::string>{"shader 'c' has no parameter 'style'"});
}

TEST_CASE("coordinate spaces of an instance are folded into its programs", "[compiler][spaces]") {
    // Shader space: translated by (1, 2, 3) and scaled by 2 along x, from world (= current).
    compiler::SpaceTransform shader;
    shader.toCurrent = {2, 0, 0, 1, 0, 1, 0, 2, 0, 0, 1, 3, 0, 0, 0, 1};
    shader.fromCurrent = {0.5, 0, 0, -0.5, 0, 1, 0, -2, 0, 0, 1, -3, 0, 0, 0, 1};
    const compiler::Spaces spaces{{"shader", shader}};
    auto at = [&](const std::string& body, const compiler::Spaces* s) {
        compiler::CompileResult r = compiler::CompileSource("s.sl", "displacement s() {\n" + body + "\n}\n", {}, {}, s);
        REQUIRE(r.ok());
        return test::PointOnSquare(r.shader->shade, 0.5, 0.25);  // P = (0.5, 0.25, 0) there
    };
    auto same = [](glm::dvec3 a, glm::dvec3 b) {
        INFO(a.x << " " << a.y << " " << a.z << " vs " << b.x << " " << b.y << " " << b.z);
        CHECK(glm::length(a - b) < 1e-15);
    };
    same(at("P = transform(\"shader\", P);", &spaces), {(0.5 - 1) / 2, 0.25 - 2, -3});
    same(at("P = vtransform(\"shader\", vector P);", &spaces), {0.25, 0.25, 0});
    same(at("P = transform(\"shader\", \"world\", P);", &spaces), {2, 2.25, 3});
    same(at("P = point \"shader\" (0, 0, 0);", &spaces), {1, 2, 3});
    // A normal goes by the inverse transpose: (1, 0, 0) in world is (2, 0, 0) in shader space.
    same(at("P = point(0, 0, 0) + ntransform(\"shader\", normal(1, 0, 0));", &spaces), {2, 0, 0});
    same(at("P = transform(\"object\", P);", &spaces), {0.5, 0.25, 0});  // not given: the identity
    same(at("P = transform(\"shader\", P);", nullptr), {0.5, 0.25, 0});  // eval: the identity

    // Compiled bytecode computes every space as the identity, so it refuses a scene that
    // makes a space it uses something else.
    test::TempDir dir;
    compiler::CompileResult src =
        compiler::CompileSource("s.sl", "displacement s() {\n  P = transform(\"shader\", P);\n}\n");
    REQUIRE(src.ok());
    CHECK(src.shader->genericBound.spaces == std::vector<std::string>{"shader"});
    vm::BytecodeFile file{"s", "s.sl", 0, src.shader->genericBound, src.shader->genericShade};
    affray::diag::Report error;
    REQUIRE(vm::WriteBytecodeFile(dir.Path("s.afb"), file, &error));
    CHECK(compiler::LoadCompiledShader(dir.Path("s.afb"), {}, nullptr).ok());
    compiler::CompileResult refused = compiler::LoadCompiledShader(dir.Path("s.afb"), {}, &spaces);
    CHECK_FALSE(refused.ok());
    REQUIRE(refused.paramErrors.size() == 1);
    CHECK(refused.paramErrors[0].find("uses coordinate space 'shader'") != std::string::npos);
}

TEST_CASE("values for parameters a shader does not declare are left out, from source or bytecode",
          "[compiler][cache]") {
    const std::vector<std::string> said{"shader 'c' has no parameter 'power'"};
    test::TempDir dir;
    const std::string path = dir.Write("c.sl", kShader);
    compiler::ShaderCache cache;
    for (int pass = 0; pass < 2; ++pass) {  // compiled, then a cache hit: said both times
        compiler::CompileResult r = cache.Load(path, {{"power", {2}}, {"Km", {3}}}, {});
        REQUIRE(r.ok());
        CHECK(r.undeclared == said);
        CHECK(r.shader->undeclared == said);
        CHECK_THAT(HeightOf(*r.shader), WithinAbs(3, 0));
    }
    CHECK(cache.hits() == 1);

    // Bytecode leaves out numbers for names its programs lack; a string value it cannot check
    // (its string parameters were folded away) stays an error.
    const compiler::CompileResult src = compiler::CompileSource("c.sl", kShader);
    REQUIRE(src.ok());
    vm::BytecodeFile file{"c", "c.sl", 0, src.shader->genericBound, src.shader->genericShade};
    affray::diag::Report error;
    REQUIRE(vm::WriteBytecodeFile(dir.Path("c.afb"), file, &error));
    compiler::CompileResult loaded = compiler::LoadCompiledShader(dir.Path("c.afb"), {{"power", {2}}, {"Km", {3}}});
    REQUIRE(loaded.ok());
    CHECK(loaded.undeclared == said);
    CHECK(loaded.shader->undeclared == said);
    CHECK_THAT(HeightOf(*loaded.shader), WithinAbs(3, 0));
    loaded = compiler::LoadCompiledShader(dir.Path("c.afb"), {compiler::ParamOverride::String("style", "x")});
    CHECK_FALSE(loaded.ok());
    CHECK(loaded.undeclared.empty());
    REQUIRE(loaded.paramErrors.size() == 1);
    CHECK(loaded.paramErrors[0].find("string values need the shader's source") != std::string::npos);
}

TEST_CASE("the shader cache shares a compilation between instances that differ only in what it never reads",
          "[compiler][cache]") {
    test::TempDir dir;
    // Reads no space and no fact; reads "object" space; reads the attribute "Sides".
    const std::string plain = dir.Write("plain.sl", "displacement plain(float Km = 1) { P += Km * normalize(N); }\n");
    const std::string object = dir.Write("object.sl",
                                         "displacement object() {\n"
                                         "  point Po = transform(\"object\", P);\n"
                                         "  P += xcomp(Po) * normalize(N);\n"
                                         "}\n");
    const std::string sides = dir.Write("sides.sl",
                                        "displacement sides() {\n"
                                        "  float s = 0;\n"
                                        "  attribute(\"Sides\", s);\n"
                                        "  P += s * normalize(N);\n"
                                        "}\n");
    // Two objects placed apart (their object spaces differ), with other Sides and another Format.
    auto placed = [](double x) {
        compiler::Spaces spaces;
        compiler::SpaceTransform& t = spaces["object"];
        t.toCurrent[3] = x;  // row-major 4x4: x translation
        t.fromCurrent[3] = -x;
        spaces["shader"] = t;
        return spaces;
    };
    auto facts = [](double sidesValue, double xres) {
        compiler::SceneFacts f;
        f.attributes["Sides"].numbers = {sidesValue};
        f.options["Format"].numbers = {xres, 480, 1};
        return f;
    };
    const compiler::Spaces spacesA = placed(0), spacesB = placed(5);
    const compiler::SceneFacts factsA = facts(2, 640), factsB = facts(2, 320), factsC = facts(1, 640);

    compiler::ShaderCache cache;
    auto load = [&](const std::string& path, const compiler::Spaces& s, const compiler::SceneFacts& f) {
        compiler::CompileResult r = cache.Load(path, {}, {}, &s, &f);
        REQUIRE(r.ok());
        return r.shader;
    };
    // What it never reads does not matter: one compilation for both objects and both formats.
    const auto plainA = load(plain, spacesA, factsA);
    CHECK(plainA->reads.spaces.empty());
    CHECK(load(plain, spacesB, factsB) == plainA);
    CHECK(load(plain, spacesB, factsC) == plainA);
    CHECK(cache.misses() == 1);
    CHECK(cache.hits() == 2);

    // A space it reads tells instances apart (and the result is each instance's own), a fact it
    // does not read does not.
    const auto objectA = load(object, spacesA, factsA), objectB = load(object, spacesB, factsA);
    CHECK(objectA->reads.spaces.count("object"));
    CHECK(objectA != objectB);
    CHECK(load(object, spacesB, factsB) == objectB);
    const double x = test::PointOnSquare(objectA->shade, 0.5, 0.5).z,
                 y = test::PointOnSquare(objectB->shade, 0.5, 0.5).z;
    CHECK_THAT(x - y, WithinAbs(5, 1e-12));  // P in object space: 5 less in x for the second
    // The same with the cache cold: a hit is exactly what compiling again would give.
    compiler::ShaderCache cold;
    const compiler::CompileResult fresh = cold.Load(object, {}, {}, &spacesB, &factsB);
    REQUIRE(fresh.ok());
    CHECK(vm::SaveBytecode({fresh.shader->name, "", 0, fresh.shader->bound, fresh.shader->shade}) ==
          vm::SaveBytecode({objectB->name, "", 0, objectB->bound, objectB->shade}));

    // An attribute it reads tells instances apart, even one the scene does not give.
    const auto sides2 = load(sides, spacesA, factsA), sides1 = load(sides, spacesB, factsC);
    CHECK(sides2->reads.attributes.count("Sides"));
    CHECK(sides2 != sides1);
    CHECK_THAT(test::PointOnSquare(sides2->shade, 0.5, 0.5).z, WithinAbs(2, 1e-12));
    CHECK_THAT(test::PointOnSquare(sides1->shade, 0.5, 0.5).z, WithinAbs(1, 1e-12));
    CHECK(load(sides, spacesB, factsB) == sides2);  // Sides 2 again, another Format and place
    const compiler::SceneFacts none;
    const auto sidesNone = load(sides, spacesA, none);
    CHECK(sidesNone != sides2);
    CHECK_THAT(test::PointOnSquare(sidesNone->shade, 0.5, 0.5).z, WithinAbs(0, 1e-12));
}
