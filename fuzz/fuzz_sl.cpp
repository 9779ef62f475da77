// fuzz/fuzz_sl.cpp: shader source (.sl text) -> preprocessor (mcpp) -> parser -> type checker ->
// lowering -> bytecode, the whole of `affray compile`; then the four programs of a shader that
// compiles run once each, in number types the input picks (every type in the replay program:
// fuzz_util.h), and its generic programs go through the .afb writer and loader, which must read
// back what was written; a surface shader (compiled with two light slots) or a light shader runs
// its programs on a point instead. The compiler's program-ops and loop-iterations limits are lowered
// (fuzz_util.h: SetSmallLimits).
// The source is named as a file in shaders/ of the source tree, with shaders/, tests/corpus and
// tests/golden as include directories, so that the seeds' #includes and texture names resolve.
#include <cstdio>
#include <cstdlib>
#include <string>

#include "compiler/compile.h"
#include "diag/limits.h"
#include "fuzz/fuzz_util.h"
#include "vm/bytecode_file.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace affray;
    static const bool kLimited = (fuzz::SetSmallLimits(), true);
    (void)kLimited;
    static const std::string kPath = fuzz::SourceDir() + "/shaders/fuzz_input.sl";
    static const lang::PreprocessOptions kPreprocess{
        {fuzz::SourceDir() + "/shaders", fuzz::SourceDir() + "/tests/corpus", fuzz::SourceDir() + "/tests/golden"}, {}};
    // Two light slots, one of category "key": a surface shader's light loops visit them.
    static const compiler::SceneFacts kFacts = [] {
        compiler::SceneFacts facts;
        facts.lightCategories = {"", "key"};
        return facts;
    }();
    const std::string text(reinterpret_cast<const char*>(data), size);
    const compiler::CompileResult result = compiler::CompileSource(kPath, text, {}, kPreprocess, nullptr, &kFacts);
    if (!result.ok()) return 0;
    const compiler::CompiledShader& shader = *result.shader;
    const uint64_t pick = fuzz::PickOf(text);
    if (shader.kind == lang::ShaderKind::Surface || shader.kind == lang::ShaderKind::Light) {
        // Surface and light programs run on points only; .afb files do not hold them.
        const bool surface = shader.kind == lang::ShaderKind::Surface;
        fuzz::RunSurface(surface ? shader.genericSurface : shader.genericLight, pick);
        fuzz::RunSurface(surface ? shader.surface : shader.light, pick + 1);
        return 0;
    }
    int k = 0;
    for (const vm::Program* p : {&shader.genericBound, &shader.genericShade, &shader.bound, &shader.shade})
        fuzz::RunNumberTypes(*p, pick + k++);

    const vm::BytecodeFile file{shader.name, shader.sourcePath, vm::HashSource(text), shader.genericBound,
                                shader.genericShade};
    std::string error;
    if (!vm::LoadBytecode(vm::SaveBytecode(file), nullptr, &error)) {
        std::fprintf(stderr, "fuzz_sl: the compiled shader does not load back from .afb: %s\n", error.c_str());
        std::abort();
    }
    return 0;
}
