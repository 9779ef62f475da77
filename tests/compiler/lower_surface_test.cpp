// tests/compiler/lower_surface_test.cpp: surface shaders in the compiler (compiler/lower_surface.cpp):
// their globals and outputs, their light loops unrolled over the light slots of the instance
// (SceneFacts::lightCategories) with each light's L and Cl asked through Light instructions, the
// shadow wanted only for the lights a loop's cone admits, categories, and ambient, diffuse,
// specular, specularbrdf and phong against their RI Spec 3.2 definitions, worked out here with
// GLM. The renderer's answers to the Light instructions are tests/renderer/shade_test.cpp's.
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>

#include <glm/glm.hpp>

#include "compiler/compile.h"
#include "vm/interpreter.h"
#include "vm/lights.h"
#include "vm/verify.h"

using namespace affray;

namespace {

/// Lights given by hand: per slot L and Cl, the ambient colour, and what was asked.
struct FakeLights final : vm::LightQueries {
    std::vector<glm::dvec3> L, Cl;
    glm::dvec3 ambient{0.0};
    std::vector<int> shadowWanted;  // per slot: colour queries with shadows wanted
    std::vector<int> asked;         // per slot: queries of any kind

    double Trace(const double direction[3], int channel) override { return direction[channel] * 0.5; }
    double Light(int slot, int component, bool shadowed) override {
        if (slot == vm::kAmbientSlot) return component < 3 ? 0.0 : ambient[component - 3];
        REQUIRE(slot >= 0);
        REQUIRE(static_cast<size_t>(slot) < L.size());
        shadowWanted.resize(L.size());
        asked.resize(L.size());
        ++asked[size_t(slot)];
        if (component >= 3 && shadowed) ++shadowWanted[size_t(slot)];
        return component < 3 ? L[size_t(slot)][component] : Cl[size_t(slot)][component - 3];
    }
};

/// The shading point of these tests: P at the origin, N up (+z), seen from `eye`.
struct Point {
    glm::dvec3 P{0.0}, N{0, 0, 1}, eye{0, -1, 1};
    glm::dvec3 Cs{1.0, 0.5, 0.25}, Os{1.0};
};

/// Compiles the surface shader `source` for an instance whose light slots have `categories`.
compiler::CompileResult Compile(const std::string& source, const std::vector<std::string>& categories,
                                const std::vector<compiler::ParamOverride>& params = {}) {
    compiler::SceneFacts facts;
    facts.lightCategories = categories;
    return compiler::CompileSource("test.sl", source, params, {}, nullptr, &facts);
}

/// Ci and Oi of the compiled surface shader at `at` under `lights`.
std::pair<glm::dvec3, glm::dvec3> Shade(const compiler::CompiledShader& shader, FakeLights& lights,
                                        const Point& at = {}) {
    using vm::Global;
    vm::Interpreter<double> interp(shader.surface);
    interp.SetLights(&lights);
    auto triple = [](const glm::dvec3& x) { return vm::Vec3<double>(x.x, x.y, x.z); };
    interp.SetGlobal(Global::P, triple(at.P));
    interp.SetGlobal(Global::N, triple(at.N));
    interp.SetGlobal(Global::Ng, triple(at.N));
    interp.SetGlobal(Global::E, triple(at.eye));
    interp.SetGlobal(Global::I, triple(at.P - at.eye));
    interp.SetGlobal(Global::Cs, triple(at.Cs));
    interp.SetGlobal(Global::Os, triple(at.Os));
    for (Global g : {Global::s, Global::t, Global::u, Global::v, Global::du, Global::dv, Global::time, Global::dtime})
        interp.SetGlobal(g, 0.0);
    for (Global g : {Global::dPdu, Global::dPdv}) interp.SetGlobal(g, triple(glm::dvec3(0.0)));
    interp.Run();
    auto out = [&](const char* name) {
        const vm::ProgramOutput* o = shader.surface.findOutput(name);
        REQUIRE(o);
        const vm::Vec3<double> x = interp.OutputTriple(*o);
        return glm::dvec3(x.x, x.y, x.z);
    };
    return {out("Ci"), out("Oi")};
}

glm::dvec3 CiOf(const std::string& source, FakeLights& lights, const std::vector<std::string>& categories,
                const Point& at = {}) {
    compiler::CompileResult r = Compile(source, categories);
    INFO(r.diagnostics.format());
    REQUIRE(r.ok());
    return Shade(*r.shader, lights, at).first;
}

void CheckClose(const glm::dvec3& got, const glm::dvec3& want) {
    INFO("got " << got.x << " " << got.y << " " << got.z << ", want " << want.x << " " << want.y << " " << want.z);
    for (int i = 0; i < 3; ++i) CHECK(got[i] == Approx(want[i]).margin(1e-12));
}

/// Three lights about the point of Point{}: above and to the side, grazing from behind, and
/// straight above but far.
FakeLights ThreeLights() {
    FakeLights l;
    l.L = {{1, 0, 2}, {0, 3, -0.5}, {0, 0, 10}};
    l.Cl = {{0.5, 0.25, 1}, {2, 2, 2}, {0.1, 0.2, 0.3}};
    l.ambient = {0.05, 0.1, 0.15};
    return l;
}

}  // namespace

TEST_CASE("surface shader: a compiled instance has one surface program of Ci and Oi, and light queries",
          "[compiler][surface]") {
    compiler::CompileResult r = Compile("surface t() { Ci = Cs * diffuse(N); }", {"", ""});
    REQUIRE(r.ok());
    const compiler::CompiledShader& s = *r.shader;
    CHECK(s.kind == lang::ShaderKind::Surface);
    CHECK(s.bound.code.empty());
    CHECK(s.shade.code.empty());
    REQUIRE(s.surface.findOutput("Ci"));
    REQUIRE(s.surface.findOutput("Oi"));
    CHECK(s.surface.readsGlobal(vm::Global::Cs));
    CHECK(s.reads.lights);
    int queries = 0;
    for (const vm::Instr& in : s.surface.code) queries += in.op == vm::Op::Light;
    CHECK(queries == 12);  // two lights: L's three components and Cl's three each
    // Only a surface program may ask for lights: the verifier refuses the instruction elsewhere.
    std::string error;
    CHECK(vm::Verify(s.surface, &error, true));
    CHECK_FALSE(vm::Verify(s.surface, &error));
    CHECK(error.find("a light query outside a surface program") != std::string::npos);
}

TEST_CASE("surface shader: Ci starts black and Oi as Os, Cs and Os are the surface's", "[compiler][surface]") {
    FakeLights none;
    Point at;
    at.Os = {0.5, 0.25, 1};
    compiler::CompileResult r = Compile("surface t() { }", {});
    REQUIRE(r.ok());
    auto [Ci, Oi] = Shade(*r.shader, none, at);
    CheckClose(Ci, glm::dvec3(0.0));
    CheckClose(Oi, at.Os);
    CheckClose(CiOf("surface t() { Ci = Cs * Os; }", none, {}, at), at.Cs * at.Os);
    // A displacement shader has no Cs.
    CHECK_FALSE(compiler::CompileSource("test.sl", "displacement t() { P += Cs[0] * N; }").ok());
}

TEST_CASE("surface shader: illuminance visits each light in its cone with that light's L and Cl",
          "[compiler][surface]") {
    FakeLights lights = ThreeLights();
    // A hemisphere about N: the first and third lights (the second is below the surface).
    const glm::dvec3 hemisphere =
        CiOf("surface t() { illuminance (P, N, PI / 2) { Ci += Cl * (normalize(L) . N); } }", lights, {"", "", ""});
    const glm::dvec3 want =
        lights.Cl[0] * (2 / std::sqrt(5.0)) + lights.Cl[2] * 1.0;  // normalize(1, 0, 2).z, normalize(0, 0, 10).z
    CheckClose(hemisphere, want);
    // Shadows are wanted for the lights inside the cone only.
    CHECK(lights.shadowWanted == std::vector<int>{3, 0, 3});
    // No cone: every light, the one behind too.
    lights = ThreeLights();
    CheckClose(CiOf("surface t() { illuminance (P) Ci += Cl; }", lights, {"", "", ""}),
               lights.Cl[0] + lights.Cl[1] + lights.Cl[2]);
    CHECK(lights.shadowWanted == std::vector<int>{3, 3, 3});
    // A narrow cone about +z (10 degrees): the light straight above only.
    lights = ThreeLights();
    CheckClose(CiOf("surface t() { illuminance (P, vector(0, 0, 1), radians(10)) Ci += Cl; }", lights, {"", "", ""}),
               lights.Cl[2]);
    // A cone of a half turn or more admits every direction.
    lights = ThreeLights();
    CheckClose(CiOf("surface t() { illuminance (P, N, PI) Ci += Cl; }", lights, {"", "", ""}),
               lights.Cl[0] + lights.Cl[1] + lights.Cl[2]);
    // Outside a loop, L and Cl are 0; a shader without lights compiles and gets black.
    lights = ThreeLights();
    CheckClose(CiOf("surface t() { Ci = Cl + color(length(L)); }", lights, {"", "", ""}), glm::dvec3(0.0));
    CheckClose(CiOf("surface t() { illuminance (P) Ci += Cl; }", lights, {}), glm::dvec3(0.0));
}

TEST_CASE("surface shader: illuminance by category", "[compiler][surface]") {
    FakeLights lights;
    lights.L = {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}, {0, 0, 1}};
    lights.Cl = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 1}};
    const std::vector<std::string> categories = {"", "key", "fill,key", "keys"};
    const std::string loop = "surface t() { illuminance (CATEGORY P) Ci += Cl; }";
    auto with = [&](const std::string& category) {
        std::string source = loop;
        source.replace(source.find("CATEGORY"), 8, category);
        return CiOf(source, lights, categories);
    };
    CheckClose(with(""), glm::dvec3(2, 2, 2));
    CheckClose(with("\"\", "), glm::dvec3(2, 2, 2));
    CheckClose(with("\"key\", "), glm::dvec3(0, 1, 1));  // "keys" is another category
    CheckClose(with("\"fill\", "), glm::dvec3(0, 0, 1));
    CheckClose(with("\"-key\", "), glm::dvec3(2, 1, 1));
    CheckClose(with("\"spot\", "), glm::dvec3(0.0));
}

TEST_CASE("surface shader: ambient, diffuse, specular, specularbrdf and phong as RI Spec 3.2 defines them",
          "[compiler][surface]") {
    const Point at;
    const glm::dvec3 N = at.N, V = glm::normalize(at.eye - at.P);
    FakeLights lights = ThreeLights();
    const std::vector<std::string> three = {"", "", ""};
    // The lights in the hemisphere about N, as the definitions' illuminance (P, N, PI/2) takes them.
    std::vector<int> front;
    for (size_t i = 0; i < lights.L.size(); ++i)
        if (glm::dot(glm::normalize(lights.L[i]), N) >= 0) front.push_back(static_cast<int>(i));
    REQUIRE(front == std::vector<int>{0, 2});

    CheckClose(CiOf("surface t() { Ci = ambient(); }", lights, three), lights.ambient);

    glm::dvec3 diffuse(0.0), specular(0.0), phong(0.0);
    const double roughness = 0.2, size = 12;
    const glm::dvec3 R = glm::reflect(-V, N);
    for (int i : front) {
        const glm::dvec3 Ln = glm::normalize(lights.L[size_t(i)]);
        const glm::dvec3 Cl = lights.Cl[size_t(i)];
        diffuse += Cl * glm::dot(Ln, N);
        specular += Cl * std::pow(std::max(0.0, glm::dot(N, glm::normalize(Ln + V))), 1 / roughness);
        phong += Cl * std::pow(std::max(0.0, glm::dot(R, Ln)), size);
    }
    CheckClose(CiOf("surface t() { Ci = diffuse(N); }", lights, three), diffuse);
    // N and V need not be normalised.
    CheckClose(CiOf("surface t() { Ci = specular(3 * N, -2 * I, 0.2); }", lights, three), specular);
    CheckClose(CiOf("surface t() { Ci = phong(N, -I, 12); }", lights, three), phong);
    const glm::dvec3 L(1, 1, 1);
    const double brdf = std::pow(std::max(0.0, glm::dot(N, glm::normalize(glm::normalize(L) + V))), 1 / roughness);
    CheckClose(CiOf("surface t() { Ci = specularbrdf(vector(1, 1, 1), N, -I, 0.2); }", lights, three),
               glm::dvec3(brdf));
    // The standard plastic, from the specification's source.
    const std::string plastic =
        "surface plastic(float Ks = .5, Kd = .5, Ka = 1, roughness = .1; color specularcolor = 1) {\n"
        "    normal Nf = faceforward(normalize(N), I);\n"
        "    vector V = -normalize(I);\n"
        "    Oi = Os;\n"
        "    Ci = Os * (Cs * (Ka * ambient() + Kd * diffuse(Nf)) + specularcolor * Ks * specular(Nf, V, roughness));\n"
        "}\n";
    glm::dvec3 plasticSpecular(0.0);
    for (int i : front)
        plasticSpecular +=
            lights.Cl[size_t(i)] *
            std::pow(std::max(0.0, glm::dot(N, glm::normalize(glm::normalize(lights.L[size_t(i)]) + V))), 1 / 0.1);
    CheckClose(CiOf(plastic, lights, three),
               at.Os * (at.Cs * (lights.ambient + 0.5 * diffuse) + 0.5 * plasticSpecular));
}

TEST_CASE("surface shader: instances share a compilation only for the same light categories", "[compiler][surface]") {
    // (compiler/shader_cache.cpp keys on SceneReads::lights; here the two programs differ.)
    compiler::CompileResult one = Compile("surface t() { Ci = diffuse(N); }", {""});
    compiler::CompileResult two = Compile("surface t() { Ci = diffuse(N); }", {"", "key"});
    REQUIRE(one.ok());
    REQUIRE(two.ok());
    CHECK(one.shader->surface.code.size() < two.shader->surface.code.size());
    // A shader that visits no light does not depend on them.
    compiler::CompileResult plain = Compile("surface t() { Ci = Cs; }", {""});
    REQUIRE(plain.ok());
    CHECK_FALSE(plain.shader->reads.lights);
}

TEST_CASE("surface shader: a vector normalised by construction is not normalised again", "[compiler][surface]") {
    // diffuse and specular normalise N and V (RI Spec 3.2); Nf = faceforward(normalize(N), I) and
    // V = -normalize(I) are unit already: the program takes four square roots (N, I, L, and H),
    // not six.
    auto roots = [](const std::string& source) {
        compiler::CompileResult r = Compile(source, {""});
        REQUIRE(r.ok());
        int n = 0;
        for (const vm::Instr& in : r.shader->surface.code) n += in.op == vm::Op::Sqrt;
        return n;
    };
    CHECK(roots("surface t() { normal Nf = faceforward(normalize(N), I); vector V = -normalize(I);\n"
                "Ci = diffuse(Nf) + specular(Nf, V, 0.1); }") == 4);
    // A vector that is not unit by construction still is normalised: N scaled, then I.
    CHECK(roots("surface t() { Ci = diffuse(2 * N) + specular(N, -I, 0.1); }") == 5);
}

namespace {

/// A light shader's Cl, L and lit at the point Ps.
struct LightAt {
    glm::dvec3 Cl, L;
    bool lit;
};
LightAt RunLight(const compiler::CompiledShader& shader, const glm::dvec3& Ps) {
    vm::Interpreter<double> interp(shader.light);
    interp.SetGlobal(vm::Global::Ps, vm::Vec3<double>(Ps.x, Ps.y, Ps.z));
    interp.Run();
    auto triple = [&](const char* name) {
        const vm::Vec3<double> x = interp.OutputTriple(*shader.light.findOutput(name));
        return glm::dvec3(x.x, x.y, x.z);
    };
    return {triple("Cl"), triple("L"), interp.Register(shader.light.findOutput("lit")->registers[0]) != 0};
}

compiler::CompiledShader CompileLight(const std::string& file,
                                      const std::vector<compiler::ParamOverride>& params = {}) {
    compiler::CompileResult r = compiler::CompileFile(std::string(AFFRAY_SOURCE_DIR) + "/shaders/" + file, params);
    INFO(r.diagnostics.format());
    REQUIRE(r.ok());
    REQUIRE(r.shader->kind == lang::ShaderKind::Light);
    return *r.shader;
}

}  // namespace

TEST_CASE("light shader: the standard lights of shaders/ as RI Spec 3.2 defines them", "[compiler][light]") {
    using Emission = compiler::LoweredShader::Emission;
    const compiler::CompiledShader ambient = CompileLight("ambientlight.sl", {{"intensity", {0.5}}});
    CHECK(ambient.emission == Emission::Ambient);
    LightAt a = RunLight(ambient, {1, 2, 3});
    CheckClose(a.Cl, glm::dvec3(0.5));
    CHECK_FALSE(a.lit);

    const compiler::CompiledShader distant =
        CompileLight("distantlight.sl", {{"from", {0, 0, 5}}, {"to", {0, 0, 0}}, {"intensity", {2}}});
    CHECK(distant.emission == Emission::Solar);
    a = RunLight(distant, {1, 2, 3});
    CheckClose(a.Cl, glm::dvec3(2.0));
    CheckClose(a.L, glm::dvec3(0, 0, -5));  // the direction the light travels
    CHECK(a.lit);

    const compiler::CompiledShader point = CompileLight("pointlight.sl", {{"from", {0, 0, 2}}, {"intensity", {8}}});
    CHECK(point.emission == Emission::Illuminate);
    a = RunLight(point, {0, 0, 0});
    CheckClose(a.Cl, glm::dvec3(2.0));  // 8 / 2^2
    CheckClose(a.L, glm::dvec3(0, 0, -2));
    CHECK(a.lit);

    // The spotlight: inside its cone, its beam; outside, nothing lit.
    const compiler::CompiledShader spot =
        CompileLight("spotlight.sl", {{"from", {0, 0, 2}}, {"to", {0, 0, 0}}, {"intensity", {4}}});
    a = RunLight(spot, {0, 0, 0});
    CHECK(a.lit);
    CheckClose(a.Cl, glm::dvec3(1.0));
    a = RunLight(spot, {3, 0, 0});
    CHECK_FALSE(a.lit);
}

TEST_CASE("light shader: shadow() is no occlusion, other surface functions are errors, __category is kept",
          "[compiler][light]") {
    compiler::CompileResult r =
        compiler::CompileSource("test.sl",
                                "light t(string shadowname = \"\"; string __category = \"rim\") {\n"
                                "  illuminate (point(0, 0, 1)) { Cl = 1 - shadow(shadowname, Ps); }\n}\n",
                                {compiler::ParamOverride::String("shadowname", "key.shd")});
    REQUIRE(r.ok());
    CHECK(r.shader->strings.at("__category") == "rim");
    CHECK(r.shader->strings.at("shadowname") == "key.shd");
    CheckClose(RunLight(*r.shader, {0, 0, 0}).Cl, glm::dvec3(1.0));
    compiler::CompileResult bad = compiler::CompileSource("test.sl", "light t() { Cl = diffuse(N); }\n");
    CHECK_FALSE(bad.ok());
    CHECK(bad.diagnostics.format().find("function 'diffuse' is not supported yet in light shaders") !=
          std::string::npos);
    compiler::CompileResult noAxis = compiler::CompileSource("test.sl", "light t() { solar () Cl = 1; }\n");
    CHECK_FALSE(noAxis.ok());
    CHECK(noAxis.diagnostics.format().find("'solar' expects an axis and an angle, got 0 arguments") !=
          std::string::npos);
}
