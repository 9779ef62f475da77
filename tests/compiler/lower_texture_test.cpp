// tests/compiler/lower_texture_test.cpp: texture() in the compiler (compiler/lower_texture.cpp):
// the forms and parameters a shader may give, the slots they become, the file search, the errors
// with their locations, and the programs' values against texture::Sample of the same map. Every
// number type's rules for the opcodes are tests/vm/conformance_test.cpp's; the maps' own,
// tests/texture/.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>

#include "tests/test_util.h"
#include "tests/texture/texture_test_util.h"
#include "vm/bytecode_file.h"
#include "vm/disasm.h"
#include "vm/interpreter.h"

using namespace affray;

namespace {

/// A 8x4 map of two channels: channel 0 = x + 10 y, channel 1 = -(x + 10 y).
std::vector<float> Ramp() {
    std::vector<float> texels;
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 8; ++x) {
            texels.push_back(static_cast<float>(x + 10 * y));
            texels.push_back(static_cast<float>(-(x + 10 * y)));
        }
    return texels;
}

/// The scalar P.z of `program` at (s, t) = (u, v) of the unit square (P = (u, v, 0), N = +z).
double ZAt(const vm::Program& program, double u, double v) { return test::PointOnSquare(program, u, v).z; }

/// Compiles `body` (a displacement shader's source) in `dir` as test.sl; returns the result.
compiler::CompileResult CompileIn(const test::tex::ScratchDir& dir, const std::string& source,
                                  const compiler::SceneFacts* facts = nullptr) {
    const std::string path = dir.path("test.sl");
    return compiler::CompileSource(path, source, {}, {}, nullptr, facts);
}

}  // namespace

TEST_CASE("texture(): a float lookup displaces by the map's bilinear value", "[compiler][texture]") {
    test::tex::ScratchDir dir;
    test::tex::WriteImage(dir.path("ramp.exr"), 8, 4, 2, Ramp());
    compiler::CompileResult r = CompileIn(dir, R"(
        displacement d(float Km = 0.5) {
            P += Km * texture("ramp.exr", s, t) * normalize(N);
        })");
    INFO(r.diagnostics.format());
    REQUIRE(r.ok());
    REQUIRE(r.shader->bound.textures);
    REQUIRE(r.shader->bound.textures->size() == 1);
    const vm::TextureSlot& slot = r.shader->bound.textures->front();
    CHECK(slot.map);
    CHECK(slot.options.channel == 0);
    for (double u : {0.0, 0.1, 0.33, 0.5, 0.77, 1.0})
        for (double v : {0.0, 0.2, 0.5, 0.9}) {
            const double want = 0.5 * texture::Sample(slot.map.get(), slot.options, 0, u, v);
            CHECK(ZAt(r.shader->bound, u, v) == Approx(want).margin(1e-12));
        }
    // The disassembly names the slot.
    const std::string text = vm::Disassemble(r.shader->bound, "");
    CHECK(text.find("; texture 0 = \"") != std::string::npos);
    CHECK(text.find("[texture 0]") != std::string::npos);
}

TEST_CASE("texture(): channels, colors, parameters and the four-corner form", "[compiler][texture]") {
    test::tex::ScratchDir dir;
    test::tex::WriteImage(dir.path("ramp.exr"), 8, 4, 2, Ramp());
    test::tex::WriteImage(dir.path("grey.exr"), 2, 2, 1, {1, 2, 3, 4});
    SECTION("name[1] reads channel 1") {
        compiler::CompileResult r =
            CompileIn(dir, R"(displacement d() { P += texture("ramp.exr"[1], s, t) * normalize(N); })");
        REQUIRE(r.ok());
        const vm::TextureSlot& slot = r.shader->bound.textures->front();
        CHECK(slot.options.channel == 1);
        CHECK(ZAt(r.shader->bound, 0.5, 0.5) == Approx(-texture::Sample(slot.map.get(), slot.options, -1, 0.5, 0.5)));
    }
    SECTION("a color lookup reads three channels; a one-channel map gives its channel to all three") {
        compiler::CompileResult r = CompileIn(dir, R"(
            displacement d() {
                color c = texture("grey.exr", s, t);
                color r = texture("ramp.exr", s, t, "fill", 7);
                P += (comp(c, 0) + comp(c, 1) + comp(c, 2) + 100 * comp(r, 2)) * normalize(N);
            })");
        INFO(r.diagnostics.format());
        REQUIRE(r.ok());
        const vm::TextureSlots& slots = *r.shader->bound.textures;
        // grey: one slot (channel 0, three times); ramp: channels 0, 1 and 2 (2 is the fill).
        CHECK(slots.size() == 4);
        const double grey = texture::Sample(slots[0].map.get(), slots[0].options, 0, 0.3, 0.6);
        CHECK(ZAt(r.shader->bound, 0.3, 0.6) == Approx(3 * grey + 700));
    }
    SECTION("blur, filter and wrap give the slot's options; width and samples are accepted") {
        compiler::CompileResult r = CompileIn(dir, R"(
            displacement d(float b = 0.25) {
                P += texture("ramp.exr", s, t, "blur", b, "filter", "gaussian", "swrap", "clamp",
                             "twrap", "black", "width", 0, "samples", 4) * normalize(N);
            })");
        INFO(r.diagnostics.format());
        REQUIRE(r.ok());
        const texture::LookupOptions& o = r.shader->bound.textures->front().options;
        CHECK(o.sblur == 0.25);
        CHECK(o.tblur == 0.25);
        CHECK(o.filter == texture::Filter::Gaussian);
        CHECK(o.swrap == texture::Wrap::Clamp);
        CHECK(o.twrap == texture::Wrap::Black);
        // The generic program took b's default and says so; the instance's options are its own.
        CHECK(r.shader->genericBound.textures->front().dependsOn == std::vector<std::string>{"b"});
        CHECK(r.shader->bound.textures->front().dependsOn.empty());
    }
    SECTION("no coordinates: the globals s and t") {
        compiler::CompileResult a = CompileIn(dir, R"(displacement d() { P += texture("ramp.exr") * normalize(N); })");
        compiler::CompileResult b =
            CompileIn(dir, R"(displacement d() { P += texture("ramp.exr", s, t) * normalize(N); })");
        REQUIRE((a.ok() && b.ok()));
        CHECK(ZAt(a.shader->bound, 0.4, 0.7) == ZAt(b.shader->bound, 0.4, 0.7));
    }
    SECTION("four corners") {
        compiler::CompileResult r = CompileIn(dir, R"(
            displacement d() {
                float h = texture("ramp.exr", s, t, s + 0.1, t, s, t + 0.1, s + 0.1, t + 0.1);
                P += h * normalize(N);
            })");
        INFO(r.diagnostics.format());
        REQUIRE(r.ok());
        const vm::TextureSlot& slot = r.shader->bound.textures->front();
        const double s[4] = {0.2, 0.3, 0.2, 0.3}, t[4] = {0.5, 0.5, 0.6, 0.6};
        CHECK(ZAt(r.shader->bound, 0.2, 0.5) ==
              Approx(texture::SampleQuad(slot.map.get(), slot.options, 0, s, t)).margin(1e-12));
    }
}

TEST_CASE("texture(): files are found in the search path, beside the shader, then as given", "[compiler][texture]") {
    test::tex::ScratchDir dir;
    std::filesystem::create_directories(dir.path("maps"));
    std::filesystem::create_directories(dir.path("other"));
    test::tex::WriteImage(dir.path("maps/a.exr"), 1, 1, 1, {2});
    test::tex::WriteImage(dir.path("other/a.exr"), 1, 1, 1, {5});
    const std::string source = R"(displacement d() { P += texture("a.exr", s, t) * normalize(N); })";
    compiler::SceneFacts facts;
    facts.textureSearchPath = {dir.path("other"), dir.path("maps")};
    compiler::CompileResult r = CompileIn(dir, source, &facts);
    INFO(r.diagnostics.format());
    REQUIRE(r.ok());
    CHECK(ZAt(r.shader->bound, 0.5, 0.5) == 5);
    facts.textureSearchPath = {dir.path("maps")};
    r = CompileIn(dir, source, &facts);
    REQUIRE(r.ok());
    CHECK(ZAt(r.shader->bound, 0.5, 0.5) == 2);
    // Beside the shader: maps/a.exr relative to test.sl's directory.
    r = CompileIn(dir, R"(displacement d() { P += texture("maps/a.exr") * normalize(N); })");
    REQUIRE(r.ok());
    CHECK(ZAt(r.shader->bound, 0.5, 0.5) == 2);
}

TEST_CASE("texture(): a missing file is an error at the call, or a warning and the fill value",
          "[compiler][texture][diagnostics]") {
    test::tex::ScratchDir dir;
    compiler::CompileResult r = CompileIn(dir, "displacement d() {\n    P += texture(\"nowhere.exr\", s, t) * N;\n}\n");
    REQUIRE_FALSE(r.ok());
    const std::string message = test::LastMessage(r.diagnostics);
    INFO(r.diagnostics.format());
    CHECK(message.find("test.sl:2:18: error: ") != std::string::npos);
    CHECK(message.find("nowhere.exr") != std::string::npos);

    r = CompileIn(dir, R"(displacement d() { P += texture("nowhere.exr", s, t, "fill", 0.5) * normalize(N); })");
    INFO(r.diagnostics.format());
    REQUIRE(r.ok());
    CHECK(r.diagnostics.format().find("warning: ") != std::string::npos);
    CHECK(ZAt(r.shader->bound, 0.3, 0.3) == 0.5);

    // Code that never runs reads no file: an uncalled function, a branch ruled out.
    r = CompileIn(dir, R"(
        float unused(string name) { return texture(name, s, t); }
        displacement d(string map = "") {
            if (map != "") P += texture(map) * normalize(N);
        })");
    INFO(r.diagnostics.format());
    CHECK(r.ok());
}

TEST_CASE("texture(): malformed calls are located errors", "[compiler][texture][diagnostics]") {
    test::tex::ScratchDir dir;
    test::tex::WriteImage(dir.path("a.exr"), 1, 1, 1, {2});
    const std::vector<std::pair<std::string, std::string>> cases = {
        {R"(texture("a.exr", s))", "texture() takes s and t, four corners"},
        {R"(texture("a.exr", s, t, "blur", s))", "texture parameter 'blur' must be a constant"},
        {R"(texture("a.exr", s, t, "blur", -1))", "texture parameter 'blur' must be a constant float >= 0"},
        {R"(texture("a.exr", s, t, "filter", "sinc"))", "must be a constant string naming a filter"},
        {R"(texture("a.exr", s, t, "swrap", "mirror"))", "naming a wrap mode"},
        {R"(texture("a.exr", s, t, "blur"))", "texture parameters come in pairs"},
        {R"(texture("a.exr"[s], s, t))", "the texture channel must be a constant whole number"},
        {R"(texture("a.exr", P, t))", "texture coordinates must be floats"},
    };
    for (const auto& [call, want] : cases) {
        compiler::CompileResult r = CompileIn(dir, "displacement d() { P += " + call + " * normalize(N); }");
        INFO(call << "\n" << r.diagnostics.format());
        CHECK_FALSE(r.ok());
        CHECK(r.diagnostics.format().find(want) != std::string::npos);
        CHECK(r.diagnostics.format().find("test.sl:1:") != std::string::npos);
    }
    // An unknown parameter is a warning (another renderer's option), the call still compiles.
    compiler::CompileResult r =
        CompileIn(dir, R"(displacement d() { P += texture("a.exr", s, t, "lerp", 1) * normalize(N); })");
    REQUIRE(r.ok());
    CHECK(r.diagnostics.format().find("unknown texture parameter 'lerp' ignored") != std::string::npos);
}

// Found by fuzz_sl (fuzz/regressions/fuzz_sl/texture_unknown_identifier.sl): a name that did not
// lower (an unknown identifier, reported as such) left the lookup going on with no name, which
// it then read.
TEST_CASE("texture(): a name that is an unknown identifier is that one error", "[compiler][texture][diagnostics]") {
    test::tex::ScratchDir dir;
    for (const std::string call : {"texture(maq)", "texture(maq[1], s, t)", "texture(maq, s, t, \"blur\", 0)"}) {
        compiler::CompileResult r = CompileIn(dir, "displacement d() { float h = " + call + "; P += h * N; }");
        INFO(call << "\n" << r.diagnostics.format());
        CHECK_FALSE(r.ok());
        CHECK(r.diagnostics.errorCount() == 1);
        CHECK(r.diagnostics.format().find("error: unknown identifier 'maq'") != std::string::npos);
    }
    // In color context, as the fuzzer found it first.
    compiler::CompileResult r = CompileIn(dir, "displacement d() { color c = texture(maq); P += comp(c, 0) * N; }");
    CHECK(r.diagnostics.errorCount() == 1);
}

TEST_CASE("texture(): compiled bytecode keeps its slots and reads the maps again", "[compiler][texture]") {
    test::tex::ScratchDir dir;
    test::tex::WriteImage(dir.path("ramp.exr"), 8, 4, 2, Ramp());
    compiler::CompileResult r = CompileIn(dir, R"(
        displacement d(float b = 0.1) {
            P += texture("ramp.exr"[1], s, t, "blur", b, "fill", 3) * normalize(N);
        })");
    REQUIRE(r.ok());
    vm::BytecodeFile file;
    file.shaderName = r.shader->name;
    file.bound = r.shader->genericBound;
    file.shade = r.shader->genericShade;
    const std::string afb = dir.path("d.afb");
    diag::Report report;
    REQUIRE(vm::WriteBytecodeFile(afb, file, &report));
    compiler::CompileResult loaded = compiler::LoadCompiledShader(afb);
    INFO(loaded.diagnostics.format());
    REQUIRE(loaded.ok());
    const vm::TextureSlot& slot = loaded.shader->bound.textures->front();
    CHECK(slot.map);
    CHECK(slot.options.channel == 1);
    CHECK(slot.options.sblur == 0.1);
    CHECK(slot.options.fill == 3);
    CHECK(slot.fillIfMissing);
    for (double u : {0.1, 0.5, 0.9}) CHECK(ZAt(loaded.shader->bound, u, 0.4) == ZAt(r.shader->bound, u, 0.4));
    // The blur came from b's default: another b needs the source.
    loaded = compiler::LoadCompiledShader(afb, {{"b", {0.5}}});
    REQUIRE_FALSE(loaded.ok());
    REQUIRE(loaded.paramErrors.size() == 1);
    CHECK(loaded.paramErrors[0].find("parameter 'b' sets an option of the lookup of texture") != std::string::npos);
    // The map gone: the loader says which file, unless the lookup has a fill (it has, here).
    std::filesystem::remove(dir.path("ramp.exr"));
    loaded = compiler::LoadCompiledShader(afb);
    CHECK(loaded.ok());
}

TEST_CASE("texture(): a map with NaN or infinite texels reads them as 0, with a warning", "[compiler][texture]") {
    test::tex::ScratchDir dir;
    const float inf = std::numeric_limits<float>::infinity();
    test::tex::WriteImage(dir.path("bad.exr"), 2, 1, 1, {std::numeric_limits<float>::quiet_NaN(), inf});
    compiler::CompileResult r = CompileIn(dir, R"(displacement d() { P += texture("bad.exr", s, t) * normalize(N); })");
    INFO(r.diagnostics.format());
    REQUIRE(r.ok());
    CHECK(r.diagnostics.format().find("has 2 texels that are NaN or infinite: they are read as 0") !=
          std::string::npos);
    CHECK(ZAt(r.shader->bound, 0.25, 0.5) == 0);
}
