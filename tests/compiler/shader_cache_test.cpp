// tests/compiler/shader_cache_test.cpp: compiled shaders are reused by content, never stale;
// string parameters take instance values.
#include <catch2/catch.hpp>

#include "../test_util.h"
#include "compiler/shader_cache.h"

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
    compiler::CompileResult wrong = compiler::CompileSource("c.sl", kShader, {compiler::ParamOverride::String("Km", "x")});
    CHECK(wrong.paramErrors == std::vector<std::string>{"parameter 'Km' of shader 'c' is not a string, got a string value"});
    wrong = compiler::CompileSource("c.sl", kShader, {{"mode", {1}}});
    CHECK(wrong.paramErrors == std::vector<std::string>{"parameter 'mode' of shader 'c' is a string, got a number"});
    wrong = compiler::CompileSource("c.sl", kShader, {compiler::ParamOverride::String("style", "x")});
    CHECK(wrong.paramErrors == std::vector<std::string>{"shader 'c' has no parameter 'style'"});
}
