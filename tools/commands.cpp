// tools/commands.cpp: what `affray compile`, `affray eval` and `affray render` do.
#include "tools/commands.h"

#include "diag/limits.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <set>

#include "compiler/compile.h"
#include "image/exr_writer.h"
#include "image/png_writer.h"
#include "renderer/render_identity.h"
#include "renderer/renderer.h"
#include "renderer/tiling.h"
#include "rib/rib.h"
#include "scene/geometry/surface.h"
#include "texture/texture.h"
#include "tools/frame_output.h"
#include "tools/interrupt.h"
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
           ",\"shade_generic\":" + count(s.genericShade) + ",\"shade_specialised\":" + count(s.shade) +
           (s.kind == lang::ShaderKind::Surface
                ? ",\"surface_generic\":" + count(s.genericSurface) + ",\"surface_specialised\":" + count(s.surface)
                : std::string()) +
           (s.kind == lang::ShaderKind::Light
                ? ",\"light_generic\":" + count(s.genericLight) + ",\"light_specialised\":" + count(s.light)
                : std::string());
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
    const bool surface = shader.kind == lang::ShaderKind::Surface;
    const bool light = shader.kind == lang::ShaderKind::Light;
    if (surface) {
        listing += "; ---- surface program (Ci and Oi) ----\n" + vm::Disassemble(shader.surface, shader.sourceText);
    } else if (light) {
        listing += "; ---- light program (Cl, L and lit) ----\n" + vm::Disassemble(shader.light, shader.sourceText);
    } else {
        listing += "; ---- bound program (displaced P only) ----\n" + vm::Disassemble(shader.bound, shader.sourceText);
        listing += "; ---- shade program (P and N) ----\n" + vm::Disassemble(shader.shade, shader.sourceText);
    }
    if (cmd.disasm) std::fputs(listing.c_str(), out);
    if (!cmd.outputPath.empty() && (surface || light)) {
        // (Checked before the statistics, so that nothing is printed for a refused command.)
        const std::string kind = lang::ToString(shader.kind);
        diag::Report report;
        report.error({shader.sourcePath}, kind + " shader '" + shader.name +
                                              "' cannot be written as bytecode (.afb files hold displacement "
                                              "shaders); a scene compiles its " +
                                              kind + " shaders from source");
        Print(report, err);
        return diag::kExitBadInput;
    }
    if (cmd.stats) {
        const vm::Program& read = surface ? shader.surface : light ? shader.light : shader.shade;
        std::string globals;
        for (int g = 0; g < vm::kGlobalCount; ++g)
            if (read.readsGlobal(static_cast<vm::Global>(g)))
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
    // A --param the shader does not declare is a typo on the command line, not a scene's value
    // for another shader: an error here (the renderer warns and ignores it, as prman does).
    for (const std::string& e : result.undeclared) report.error({"affray"}, e);
    Print(report, err);
    if (!result.ok() || !result.undeclared.empty()) return diag::kExitBadInput;
    const compiler::CompiledShader& shader = *result.shader;
    if (shader.kind != lang::ShaderKind::Displacement) {
        diag::Report refused;
        refused.error({cmd.shaderPath}, "'affray eval' evaluates displacement shaders; '" + shader.name + "' is a " +
                                            lang::ToString(shader.kind) + " shader (render a scene that uses it)");
        Print(refused, err);
        return diag::kExitBadInput;
    }
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

std::string FrameOutputPath(const std::string& path, int frame) {
    char number[16];
    std::snprintf(number, sizeof number, ".%04d", frame);
    const size_t slash = path.find_last_of('/');
    const size_t dot = path.find_last_of('.');
    const bool hasExtension = dot != std::string::npos && (slash == std::string::npos || dot > slash + 1);
    if (!hasExtension) return path + number;
    return path.substr(0, dot) + number + path.substr(dot);
}

namespace {

/// "frame 2 (line 9)", or "the scene" for a world outside frames.
std::string FrameName(const renderer::SceneDesc& frame) {
    if (!frame.frame) return "the scene";
    return "frame " + std::to_string(*frame.frame) + " (line " + std::to_string(frame.frameLine) + ")";
}

/// Warns, at its Displacement request, about each parameter value that a shader instance of
/// `prepared` does not declare and so was compiled without (prman warns and ignores them too);
/// once per shader and name over the run (`warned`).
void WarnUndeclared(const renderer::PreparedScene& prepared, std::set<std::string>* warned, diag::Report* report) {
    const renderer::SceneDesc& desc = prepared.desc;
    const renderer::PrimitiveAttributes* previous = nullptr;  // a mesh's faces share theirs
    for (const renderer::Primitive& prim : prepared.primitives) {
        if (!prim.shader() || prim.shader()->undeclared.empty() || !prim.attributes().displacement) continue;
        if (&prim.attributes() == previous) continue;
        previous = &prim.attributes();
        const renderer::ShaderRef& ref = *prim.attributes().displacement;
        const std::string& file = ref.file.empty() ? desc.path : ref.file;
        for (const std::string& sentence : prim.shader()->undeclared)
            if (warned->insert(sentence).second)
                report->warning({file, ref.line, ref.column, diag::ReadLine(file, ref.line)}, sentence + "; ignored");
    }
}

/// The Renderer's options from the command line: shaders are looked for beside the RIB file, in
/// ../shaders from there and in ./shaders, after the scene's own search path.
renderer::Options OptionsOf(const RenderCommand& cmd) {
    std::filesystem::path ribDir = std::filesystem::path(cmd.scenePath).parent_path();
    if (ribDir.empty()) ribDir = ".";
    renderer::Options options;
    options.threads = cmd.threads;
    options.shaderPaths = {ribDir.string(), (ribDir / ".." / "shaders").string(), "shaders"};
    options.preprocess = cmd.preprocess;
    options.tolerancePixels = cmd.tolerance;
    options.sceneTolerance = !cmd.toleranceGiven;
    options.bounds = cmd.bounds;
    options.maxDepth = cmd.maxDepth;
    options.regionBudget = cmd.regionBudget;
    options.cacheBytes = cmd.cacheBytes;
    options.rayGroupPixels = cmd.rayGroupPixels;
    options.newton = cmd.newton;
    options.reverseTileOrder = cmd.reverseTiles;
    options.bvhSplit = cmd.medianBvh ? renderer::Bvh::Split::kMedian : renderer::Bvh::Split::kSah;
    return options;
}

/// Renders one frame to `outputPath` (and `pngPath` if not empty); prints the frame's shader
/// diagnostics (with WarnUndeclared's warnings, `warned` over the run) and, with --stats, its figures.
int RenderFrame(const RenderCommand& cmd, const renderer::Renderer& renderer, renderer::SceneDesc scene,
                const std::string& outputPath, const std::string& pngPath, std::set<std::string>* warned,
                double readSeconds, FILE* out, FILE* err) {
    diag::Report report;
    if (cmd.crop) scene.camera.cropWindow = glm::dvec4((*cmd.crop)[0], (*cmd.crop)[1], (*cmd.crop)[2], (*cmd.crop)[3]);
    if (cmd.samples > 0) scene.camera.xsamples = scene.camera.ysamples = cmd.samples;
    const texture::CacheStats texturesBefore = texture::Stats();
    renderer::PreparedScene prepared;
    const std::optional<int> frameNumber = scene.frame;
    const auto prepareStart = std::chrono::steady_clock::now();
    const bool preparedOk = renderer.Prepare(std::move(scene), &prepared, &report);
    const double prepareSeconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - prepareStart).count();
    if (preparedOk) WarnUndeclared(prepared, warned, &report);
    // The shaders' warnings are printed before the render starts.
    Print(report, err);
    if (!preparedOk) return diag::kExitBadInput;
    // Outputs checked, checkpoint started or resumed, signals stop the render.
    FrameOutput files(outputPath, pngPath);
    renderer::RenderControl control;
    if (const int status = files.Begin(cmd.resume, prepared, renderer, &control, err); status != diag::kExitSuccess)
        return status;
    ProgressBar bar(Progress::ShouldShow(cmd.quiet, stderr));
    control.progress = &bar;
    image::ImageBuffer image;
    renderer::RenderStats stats;
    renderer.Render(prepared, &image, &stats, control);
    stats.readSeconds = readSeconds;
    stats.prepareSeconds = prepareSeconds;
    if (const int status = files.AfterRender(stats, err); status != diag::kExitSuccess) return status;
    // The header says which render and which pixels this is, for affray merge (renderer/tiling.h).
    renderer::StampTile(renderer::IdentifyFrame(prepared, renderer.options()),
                        renderer::CropPixels(prepared.desc.camera), kVersion, &image);
    diag::Report output;
    const bool written = image::WriteExr(outputPath, image, &output) &&
                         (pngPath.empty() || image::WritePngPreview(pngPath, image, &output));
    files.Finish();
    if (!written) {
        Print(output, err);
        return diag::kExitOutput;
    }
    if (cmd.stats) {
        // The render's figures, then each shader instance's instruction counts: one entry per
        // instance and specialised program size, with the number of primitives that share it (a
        // mesh of a thousand faces is one entry, not a thousand).
        std::string json = stats.ToJson();
        json.pop_back();
        if (frameNumber) json.insert(1, "\"frame\":" + std::to_string(*frameNumber) + ",");
        // The texture tiles this frame read and dropped, and what all maps hold now.
        const texture::CacheStats textures = texture::Stats();
        char texturesJson[256];
        std::snprintf(
            texturesJson, sizeof texturesJson,
            ",\"textures\":{\"budget_mb\":%.1f,\"tiles_read\":%lld,\"tiles_dropped\":%lld,\"resident_mb\":%.2f}",
            double(texture::TileMemoryBudget()) / (1 << 20),
            static_cast<long long>(textures.tilesRead - texturesBefore.tilesRead),
            static_cast<long long>(textures.tilesDropped - texturesBefore.tilesDropped),
            double(textures.residentBytes) / (1 << 20));
        json += texturesJson;
        json += ",\"shader_compilations\":" + std::to_string(prepared.shadersCompiled) +
                ",\"shader_compilations_reused\":" + std::to_string(prepared.shadersReused) + ",\"shaders\":[";
        struct Entry {
            const compiler::CompiledShader* shader;
            size_t bound, shade;
            int primitives;
        };
        std::vector<Entry> entries;
        for (const renderer::Primitive& prim : prepared.primitives) {
            if (!prim.shader()) continue;
            const Entry key{prim.shader().get(), prim.bound().code.size(), prim.shade().code.size(), 1};
            auto same = std::find_if(entries.begin(), entries.end(), [&](const Entry& e) {
                return e.shader == key.shader && e.bound == key.bound && e.shade == key.shade;
            });
            if (same == entries.end())
                entries.push_back(key);
            else
                ++same->primitives;
        }
        bool first = true;
        for (const Entry& e : entries) {
            json += std::string(first ? "" : ",") + "{\"name\":\"" + e.shader->name + "\"," +
                    InstructionCounts(*e.shader) + ",\"bound_on_surface\":" + std::to_string(e.bound) +
                    ",\"shade_on_surface\":" + std::to_string(e.shade) +
                    ",\"primitives\":" + std::to_string(e.primitives) + "}";
            first = false;
        }
        std::fprintf(out, "%s]}\n", json.c_str());
        std::fflush(out);
    }
    return diag::kExitSuccess;
}

}  // namespace

std::vector<const renderer::SceneDesc*> ReadChosenFrames(const std::string& scenePath, std::optional<int> frame,
                                                         FILE* err, std::vector<renderer::SceneDesc>* framesOut,
                                                         int* status) {
    diag::Report report;
    std::optional<std::vector<renderer::SceneDesc>> read = rib::ReadRibFrames(scenePath, &report);
    // The scene's warnings and notes, before anything renders.
    Print(report, err);
    if (!read) {
        *status = diag::kExitBadInput;
        return {};
    }
    *framesOut = std::move(*read);
    const std::vector<renderer::SceneDesc>& frames = *framesOut;
    // Every frame, or those --frame names; skipped ones (shadow passes) not.
    std::vector<const renderer::SceneDesc*> chosen;
    for (const renderer::SceneDesc& f : frames)
        if (!frame || f.frame == frame) chosen.push_back(&f);
    if (chosen.empty()) {
        std::string known;
        for (const renderer::SceneDesc& f : frames)
            if (f.frame)
                known +=
                    (known.empty() ? "" : ", ") + std::to_string(*f.frame) + " on line " + std::to_string(f.frameLine);
        const std::string message = "--frame " + std::to_string(*frame) + ": the scene has no frame " +
                                    std::to_string(*frame) +
                                    (known.empty() ? " (it has no FrameBegin)" : " (its frames: " + known + ")");
        std::fputs(diag::Format({diag::Severity::Error, {scenePath}, message, {}}).c_str(), err);
        *status = diag::kExitUsage;
        return {};
    }
    std::erase_if(chosen, [](const renderer::SceneDesc* f) { return !f->skipped.empty(); });
    if (chosen.empty()) {
        const std::string message =
            frame ? "frame " + std::to_string(*frame) + " renders no image" : "no frame of the scene renders an image";
        std::fputs(diag::Format({diag::Severity::Note, {scenePath}, message + ": nothing written", {}}).c_str(), err);
        *status = diag::kExitSuccess;
    }
    return chosen;
}

std::vector<std::string> FrameOutputs(const std::vector<const renderer::SceneDesc*>& chosen,
                                      const std::string& outputPath) {
    auto base = [&](const renderer::SceneDesc* f) { return outputPath.empty() ? f->displayName : outputPath; };
    std::vector<std::string> outputs;
    for (const renderer::SceneDesc* frame : chosen) {
        const bool shared = std::count_if(chosen.begin(), chosen.end(),
                                          [&](const renderer::SceneDesc* f) { return base(f) == base(frame); }) > 1;
        outputs.push_back(shared ? FrameOutputPath(base(frame), frame->frame.value_or(0)) : base(frame));
    }
    return outputs;
}

int RunRender(const RenderCommand& cmd, FILE* out, FILE* err) {
    // From here SIGINT and SIGTERM only set a flag, which the render checks (tools/interrupt.h).
    Interrupts interrupts;
    // And so does the time limit, counted from here for every frame together.
    interrupts.StopAfter(static_cast<double>(diag::LimitValue(diag::Limit::TimeLimit)));
    std::vector<renderer::SceneDesc> frames;
    int status = diag::kExitSuccess;
    const auto readStart = std::chrono::steady_clock::now();
    const std::vector<const renderer::SceneDesc*> chosen =
        ReadChosenFrames(cmd.scenePath, cmd.frame, err, &frames, &status);
    // The whole file's, given with every frame's figures.
    const double readSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - readStart).count();
    if (chosen.empty()) return status;

    // Each frame's files: -o or its Display name, numbered when several frames would share it.
    const std::vector<std::string> outputs = FrameOutputs(chosen, cmd.outputPath);
    std::vector<std::string> pngs;
    for (const renderer::SceneDesc* frame : chosen)
        pngs.push_back(cmd.pngPath.empty() || chosen.size() == 1
                           ? cmd.pngPath
                           : FrameOutputPath(cmd.pngPath, frame->frame.value_or(0)));
    for (size_t i = 0; i < chosen.size(); ++i)
        for (size_t j = 0; j < i; ++j)
            if (outputs[i] == outputs[j] || (!pngs[i].empty() && pngs[i] == pngs[j])) {
                const std::string message = FrameName(*chosen[j]) + " and " + FrameName(*chosen[i]) +
                                            " would both write " + (outputs[i] == outputs[j] ? outputs[i] : pngs[i]) +
                                            "; give the frames different numbers or Display names";
                std::fputs(diag::Format({diag::Severity::Error, {cmd.scenePath}, message, {}}).c_str(), err);
                return diag::kExitBadInput;
            }

    // The texture maps' tile budget is the process's (docs/design.md 6b); the Renderer, one for
    // the run: its options from the command line, its threads started once.
    if (cmd.textureBytes) texture::SetTileMemoryBudget(*cmd.textureBytes);
    const renderer::Renderer renderer(OptionsOf(cmd));
    // Frame by frame: an error stops the run, and the frames written before it stay complete.
    // SIGINT and SIGTERM stop it too, giving up the frame being rendered.
    std::set<std::string> warned;  // WarnUndeclared's, once over the frames
    for (size_t i = 0; i < chosen.size(); ++i) {
        // Each frame is rendered once: its description moves into the render (no copy of its
        // primitives).
        renderer::SceneDesc& frame = frames[static_cast<size_t>(chosen[i] - frames.data())];
        const int status =
            RenderFrame(cmd, renderer, std::move(frame), outputs[i], pngs[i], &warned, readSeconds, out, err);
        if (status != diag::kExitSuccess) return status;
    }
    return diag::kExitSuccess;
}

}  // namespace affray::tools
