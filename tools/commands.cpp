// tools/commands.cpp: what `affray compile`, `affray eval` and `affray render` do.
#include "tools/commands.h"

#include <cmath>
#include <filesystem>
#include <memory>

#include "compiler/compile.h"
#include "renderer/geometry/surface.h"
#include "renderer/image/exr_writer.h"
#include "renderer/image/png_writer.h"
#include "renderer/render.h"
#include "rib/rib.h"
#include "tools/progress.h"
#include "vm/bytecode_file.h"
#include "vm/disasm.h"

namespace affray::tools {

namespace {

/// The progress bar on stderr, fed by the render (shown only on a terminal, unless --quiet).
class ProgressBar final : public renderer::RenderProgress {
  public:
    explicit ProgressBar(bool enabled) : m_enabled(enabled) {}
    void Begin(int tiles) override { m_bar = std::make_unique<Progress>(tiles, stderr, m_enabled); }
    void TileDone() override { m_bar->TileDone(); }
    void Finish() override { m_bar->Finish(); }

  private:
    bool m_enabled;
    std::unique_ptr<Progress> m_bar;
};

/// A number with round-trip precision, or null if it is not finite (JSON has no NaN).
std::string Json(double x) {
    if (!std::isfinite(x)) return "null";
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.17g", x);
    return buf;
}

std::string Json(const double (&v)[3]) { return "[" + Json(v[0]) + "," + Json(v[1]) + "," + Json(v[2]) + "]"; }

/// Bounds P over [u0,u1] x [v0,v1] of the unit square with number type N and prints the ranges.
template <class N>
void PrintBound(const vm::Program& program, double u0, double u1, double v0, double v1, FILE* out) {
    vm::Interpreter<N> interp(program);
    vm::Vec3<N> p = renderer::EvaluateOnPatch(interp, renderer::BilinearPatch::UnitSquare(), u0, u1, v0, v1,
                                              glm::dvec3(0.0), *program.findOutput("P"));
    double lo[3], hi[3];
    bool unbounded = false;
    for (int i = 0; i < 3; ++i) {
        vm::Interval r = RangeOf(vm::ValueOf(p[i]));
        unbounded = unbounded || r.isUnbounded();
        lo[i] = r.lo();
        hi[i] = r.hi();
    }
    std::fprintf(out, "{\"P\":{\"lo\":%s,\"hi\":%s}%s}\n", Json(lo).c_str(), Json(hi).c_str(),
                 unbounded ? ",\"unbounded\":true" : "");
}

/// Instruction counts of one shader instance, as a JSON object's members (no braces).
std::string InstructionCounts(const compiler::CompiledShader& s) {
    auto count = [](const vm::Program& p) { return std::to_string(p.code.size()); };
    return "\"operations_requested\":" + std::to_string(s.opsBeforeOptimisation) +
           ",\"bound_generic\":" + count(s.genericBound) + ",\"bound_specialised\":" + count(s.bound) +
           ",\"shade_generic\":" + count(s.genericShade) + ",\"shade_specialised\":" + count(s.shade);
}

}  // namespace

void Print(const diag::Report& report, FILE* err) { std::fputs(report.format().c_str(), err); }

int RunCompile(const CompileCommand& cmd, FILE* out, FILE* err) {
    compiler::CompileResult result = compiler::CompileFile(cmd.shaderPath, {}, cmd.preprocess);
    Print(result.diagnostics, err);
    if (!result.ok()) return diag::kExitBadInput;
    const compiler::CompiledShader& shader = *result.shader;
    std::string listing = "; " + shader.name + " from " + shader.sourcePath + ": " +
                          std::to_string(shader.opsBeforeOptimisation) + " operations before optimisation\n";
    listing += "; ---- bound program (displaced P only) ----\n" + vm::Disassemble(shader.bound, shader.sourceText);
    listing += "; ---- shade program (P and N) ----\n" + vm::Disassemble(shader.shade, shader.sourceText);
    if (cmd.disasm) std::fputs(listing.c_str(), out);
    if (cmd.stats) {
        std::string globals;
        for (int g = 0; g < vm::kGlobalCount; ++g)
            if (shader.shade.readsGlobal(static_cast<vm::Global>(g)))
                globals +=
                    std::string(globals.empty() ? "" : ",") + "\"" + vm::GlobalName(static_cast<vm::Global>(g)) + "\"";
        std::fprintf(out, "{\"shader\":\"%s\",%s,\"params\":%zu,\"globals_read\":[%s]}\n", shader.name.c_str(),
                     InstructionCounts(shader).c_str(), shader.params.size(), globals.c_str());
    }
    if (!cmd.outputPath.empty()) {
        vm::BytecodeFile file{shader.name, shader.sourcePath, vm::HashSource(shader.sourceText), shader.genericBound,
                              shader.genericShade};
        diag::Report report;
        if (!vm::WriteBytecodeFile(cmd.outputPath, file, &report)) {
            Print(report, err);
            return diag::kExitOutput;
        }
    }
    return diag::kExitSuccess;
}

int RunEval(const EvalCommand& cmd, FILE* out, FILE* err) {
    compiler::CompileResult result = compiler::LoadShader(cmd.shaderPath, cmd.params, cmd.preprocess);
    diag::Report report = result.diagnostics;
    for (const std::string& e : result.paramErrors) report.error({"affray"}, e);
    Print(report, err);
    if (!result.ok()) return diag::kExitBadInput;
    const compiler::CompiledShader& shader = *result.shader;
    const renderer::BilinearPatch square = renderer::BilinearPatch::UnitSquare();

    auto bound = [&](double u0, double u1, double v0, double v1) {
        const vm::Program& p = shader.bound;
        bool dual = p.usesDerivatives();
        if (cmd.mode == "affine") {
            if (dual)
                PrintBound<vm::Dual<vm::Affine>>(p, u0, u1, v0, v1, out);
            else
                PrintBound<vm::Affine>(p, u0, u1, v0, v1, out);
        } else {
            if (dual)
                PrintBound<vm::Dual<vm::Interval>>(p, u0, u1, v0, v1, out);
            else
                PrintBound<vm::Interval>(p, u0, u1, v0, v1, out);
        }
    };
    if (cmd.hasRegion) {
        bound(cmd.region[0], cmd.region[1], cmd.region[2], cmd.region[3]);
        return diag::kExitSuccess;
    }
    vm::Interpreter<vm::Dual<double>> interp(shader.shade);
    for (const auto& [u, v] : cmd.points) {
        if (cmd.mode != "scalar") {
            bound(u, u, v, v);
            continue;
        }
        vm::Vec3<vm::Dual<double>> P =
            renderer::EvaluateOnPatch(interp, square, u, u, v, v, glm::dvec3(0.0), *shader.shade.findOutput("P"));
        vm::Vec3<vm::Dual<double>> N = interp.OutputTriple(*shader.shade.findOutput("N"));
        double p[3] = {P.x.v, P.y.v, P.z.v}, n[3] = {N.x.v, N.y.v, N.z.v};
        std::fprintf(out, "{\"P\":%s,\"N\":%s}\n", Json(p).c_str(), Json(n).c_str());
    }
    return diag::kExitSuccess;
}

int RunRender(const RenderCommand& cmd, FILE* out, FILE* err) {
    diag::Report report;
    std::optional<renderer::SceneDesc> scene = rib::ReadRib(cmd.scenePath, &report);
    if (!scene) {
        Print(report, err);
        return diag::kExitBadInput;
    }
    std::filesystem::path ribDir = std::filesystem::path(cmd.scenePath).parent_path();
    if (ribDir.empty()) ribDir = ".";
    std::vector<std::string> shaderPaths = {ribDir.string(), (ribDir / ".." / "shaders").string(), "shaders"};
    if (cmd.crop) scene->camera.cropWindow = glm::dvec4((*cmd.crop)[0], (*cmd.crop)[1], (*cmd.crop)[2], (*cmd.crop)[3]);
    if (cmd.samples > 0) scene->camera.xsamples = scene->camera.ysamples = cmd.samples;
    renderer::PreparedScene prepared;
    const bool preparedOk = renderer::PrepareScene(*scene, shaderPaths, cmd.preprocess, &prepared, &report);
    // The scene's and the shaders' warnings are printed before the render starts.
    Print(report, err);
    if (!preparedOk) return diag::kExitBadInput;
    renderer::RenderOptions options;
    options.threads = cmd.threads;
    options.tolerancePixels = cmd.tolerance;
    options.bounds = cmd.bounds;
    options.maxDepth = cmd.maxDepth;
    options.regionBudget = cmd.regionBudget;
    options.cacheBytes = cmd.cacheBytes;
    options.rayGroupPixels = cmd.rayGroupPixels;
    ProgressBar bar(Progress::ShouldShow(cmd.quiet, stderr));
    options.progress = &bar;
    renderer::ImageBuffer image;
    renderer::RenderStats stats;
    renderer::RenderImage(prepared, options, &image, &stats);
    std::string outputPath = cmd.outputPath.empty() ? scene->displayName : cmd.outputPath;
    diag::Report output;
    if (!renderer::WriteExr(outputPath, image, &output) ||
        (!cmd.pngPath.empty() && !renderer::WritePngPreview(cmd.pngPath, image, &output))) {
        Print(output, err);
        return diag::kExitOutput;
    }
    if (cmd.stats) {
        // The render's figures, then each shader instance's instruction counts.
        std::string json = stats.ToJson();
        json.pop_back();
        json += ",\"shader_compilations\":" + std::to_string(prepared.shadersCompiled) +
                ",\"shader_compilations_reused\":" + std::to_string(prepared.shadersReused) + ",\"shaders\":[";
        bool first = true;
        for (const renderer::Primitive& prim : prepared.primitives) {
            if (!prim.shader) continue;
            json += std::string(first ? "" : ",") + "{\"name\":\"" + prim.shader->name + "\"," +
                    InstructionCounts(*prim.shader) +
                    ",\"bound_on_surface\":" + std::to_string(prim.bound.code.size()) +
                    ",\"shade_on_surface\":" + std::to_string(prim.shade.code.size()) + "}";
            first = false;
        }
        std::fprintf(out, "%s]}\n", json.c_str());
    }
    return diag::kExitSuccess;
}

}  // namespace affray::tools
