// compiler/compile.cpp: parse -> check and lower -> emit two programs -> verify.
#include "compiler/compile.h"

#include <algorithm>
#include <map>
#include <set>
#include <stdexcept>

#include "compiler/emit.h"
#include "diag/check.h"
#include "lang/parse.h"
#include "vm/bytecode_file.h"
#include "vm/verify.h"

namespace affray::compiler {

namespace {
/// Specialises the generic programs of `shader` with `overrides` into bound and shade.
bool SpecialiseShader(CompiledShader& shader, const std::vector<ParamOverride>& overrides,
                      std::vector<std::string>* errors) {
    std::optional<vm::Program> bound = Specialise(shader.genericBound, overrides, errors);
    if (!bound) return false;
    // Compiled together, the two programs take the same parameters and fail together; a loaded
    // file's shade program need not (its params and constants are its own), so check it too.
    std::vector<std::string> again;
    std::optional<vm::Program> shade = Specialise(shader.genericShade, overrides, &again);
    if (!shade) {
        for (const std::string& e : again)
            if (std::find(errors->begin(), errors->end(), e) == errors->end()) errors->push_back(e);
        if (errors->empty()) errors->push_back("shader '" + shader.name + "': its shade program cannot be specialised");
        return false;
    }
    shader.bound = std::move(*bound);
    shader.shade = std::move(*shade);
    return true;
}

/// A parameter's type as the bytecode names it: "point", or "float[3]" for an array.
std::string ParamTypeName(const ParamInfo& p) {
    return std::string(ToString(p.type)) + (p.arraySize >= 0 ? "[" + std::to_string(p.arraySize) + "]" : "");
}

/// Adds to *to the diagnostics of `from` that it does not hold yet.
void AddNew(const diag::Report& from, diag::Report* to) {
    std::set<std::string> seen;
    for (const diag::Diagnostic& d : to->all()) seen.insert(diag::Format(d));
    for (const diag::Diagnostic& d : from.all())
        if (seen.insert(diag::Format(d)).second) to->add(d);
}

/// The slot table the programs of one lowering share (null if it reads no texture).
std::shared_ptr<const vm::TextureSlots> TexturesOf(const LoweredShader& lowered) {
    if (lowered.textures.empty()) return nullptr;
    return std::make_shared<const vm::TextureSlots>(lowered.textures);
}

/// `overrides` without those whose name is not in `declared` (the parameters of shader `shader`),
/// string values aside if `keepStrings`; each name left out is said once in *undeclared. prman
/// ignores such a value, with a warning: the caller says so (see CompileResult::undeclared).
std::vector<ParamOverride> KeepDeclared(const std::vector<ParamOverride>& overrides,
                                        const std::set<std::string>& declared, bool keepStrings,
                                        const std::string& shader, std::vector<std::string>* undeclared) {
    std::vector<ParamOverride> kept;
    for (const ParamOverride& o : overrides) {
        const std::string sentence = "shader '" + shader + "' has no parameter '" + o.name + "'";
        if (declared.count(o.name) || (keepStrings && o.text))
            kept.push_back(o);
        else if (std::find(undeclared->begin(), undeclared->end(), sentence) == undeclared->end())
            undeclared->push_back(sentence);
    }
    return kept;
}

ParamInfo ParamFromProgram(const vm::ProgramParam& p) {
    ParamInfo info{p.name, Type::Float, p.defaults, false};
    const size_t bracket = p.type.find('[');
    const std::string base = p.type.substr(0, bracket);
    for (Type t : {Type::Float, Type::Point, Type::Vector, Type::Normal, Type::Color, Type::Matrix})
        if (base == ToString(t)) info.type = t;
    if (bracket != std::string::npos)
        info.arraySize = static_cast<int>(std::strtol(p.type.c_str() + bracket + 1, nullptr, 10));
    return info;
}
}  // namespace

CompileResult CompileSource(const std::string& path, const std::string& text,
                            const std::vector<ParamOverride>& overrides, const lang::PreprocessOptions& preprocess,
                            const Spaces* spaces, const SceneFacts* facts) {
    CompileResult result;
    lang::SourceFile file(path, text);
    lang::Diagnostics diags(file);
    lang::TranslationUnit unit = lang::PreprocessAndParse(diags, preprocess);
    std::optional<LoweredShader> lowered;
    // The generic programs are lowered with the instance's spaces too, only so that a scene's
    // CoordinateSystem names are known (their matrices are folded again into the instance).
    if (!diags.hasErrors()) lowered = Lower(unit, diags, nullptr, nullptr, spaces, facts);
    result.diagnostics = diags.report();
    if (!lowered) return result;

    CompiledShader shader;
    shader.name = lowered->name;
    shader.sourcePath = path;
    shader.sourceText = text;
    shader.params = lowered->params;
    shader.opsBeforeOptimisation = lowered->ir.requestedOps();
    std::vector<vm::ProgramParam> params;
    for (const ParamInfo& p : lowered->params)
        params.push_back(
            {p.name, ParamTypeName(p), ScalarCount(p.type) * std::max(p.arraySize, 1), vm::kNoRegister, p.defaults});
    shader.kind = lowered->kind;
    const bool surface = shader.kind == lang::ShaderKind::Surface;
    const bool light = shader.kind == lang::ShaderKind::Light;
    shader.emission = lowered->emission;
    // The programs of one lowering: a displacement's bound and shade, a surface's, or a light's.
    auto emit = [&](const LoweredShader& l, const std::vector<vm::ProgramParam>& with, vm::Program* bound,
                    vm::Program* shade, vm::Program* surfaceProgram, vm::Program* lightProgram) {
        if (surface) {
            *surfaceProgram = Emit(l.ir, {{"Ci", l.finalCi}, {"Oi", l.finalOi}}, with);
        } else if (light) {
            *lightProgram = Emit(l.ir, {{"Cl", l.finalCl}, {"L", l.finalL}, {"lit", l.finalLit}}, with);
        } else {
            *bound = Emit(l.ir, {{"P", l.finalP}}, with);
            *shade = Emit(l.ir, {{"P", l.finalP}, {"N", l.finalN}}, with);
        }
    };
    try {
        emit(*lowered, params, &shader.genericBound, &shader.genericShade, &shader.genericSurface,
             &shader.genericLight);
        auto genericTextures = TexturesOf(*lowered);
        for (vm::Program* p :
             {&shader.genericBound, &shader.genericShade, &shader.genericSurface, &shader.genericLight}) {
            p->shaderName = shader.name;
            p->sourcePath = path;
            p->spaces = lowered->spaces;
            p->textures = genericTextures;
        }
        // The instance: lowered again with its parameter values as constants, so that the
        // branches and loops they decide fold during lowering (bytecode specialisation cannot
        // undo the unrolling of a loop whose bound was a parameter).
        std::set<std::string> declared(lowered->stringParams.begin(), lowered->stringParams.end());
        for (const vm::ProgramParam& p : params) declared.insert(p.name);
        std::vector<ParamOverride> numeric;
        std::map<std::string, std::string> strings;
        bool stringsOk = true;
        for (const ParamOverride& o : KeepDeclared(overrides, declared, false, shader.name, &result.undeclared)) {
            const bool isStringParam =
                std::count(lowered->stringParams.begin(), lowered->stringParams.end(), o.name) > 0;
            if (o.text && !isStringParam) {
                result.paramErrors.push_back("parameter '" + o.name + "' of shader '" + shader.name +
                                             "' is not a string, got a string value");
                stringsOk = false;
            } else if (o.text) {
                strings[o.name] = *o.text;
            } else if (isStringParam) {
                result.paramErrors.push_back("parameter '" + o.name + "' of shader '" + shader.name +
                                             "' is a string, got a number");
                stringsOk = false;
            } else {
                numeric.push_back(o);
            }
        }
        std::optional<std::vector<std::vector<double>>> values =
            BindParameters(shader.generic(), numeric, &result.paramErrors);
        if (!values || !stringsOk) return result;
        lang::Diagnostics again(file);  // the same diagnostics as the generic lowering, and more
        std::optional<LoweredShader> instance = Lower(unit, again, &*values, &strings, spaces, facts);
        // A string value can make code reachable that the defaults left out (a space name), and
        // the instance reads its texture maps (the generic lowering reports none): its
        // diagnostics that the generic lowering did not give.
        AddNew(again.report(), &result.diagnostics);
        if (!instance && again.hasErrors()) return result;
        // The generic lowering succeeded, so the instance's can fail only by its own errors.
        AFFRAY_CHECK(instance);
        shader.stringParams = lowered->stringParams;
        shader.undeclared = result.undeclared;
        shader.reads = lowered->reads;
        shader.reads.Add(instance->reads);
        emit(*instance, {}, &shader.bound, &shader.shade, &shader.surface, &shader.light);
        shader.surfaceDerivatives = shader.surface.usesDerivatives();
        shader.emission = instance->emission;
        shader.strings = instance->stringValues;
        auto instanceTextures = TexturesOf(*instance);
        for (vm::Program* p : {&shader.bound, &shader.shade, &shader.surface, &shader.light}) {
            p->shaderName = shader.name;
            p->sourcePath = path;
            p->textures = instanceTextures;
        }
    } catch (const std::length_error& e) {
        result.diagnostics.error({path}, e.what());
        return result;
    }
    for (vm::Program* p : {&shader.genericBound, &shader.genericShade, &shader.bound, &shader.shade,
                           &shader.genericSurface, &shader.surface, &shader.genericLight, &shader.light}) {
        std::string error;
        // The emitter's programs are valid by construction; the verifier checks that they are.
        const bool valid = vm::Verify(*p, &error, surface);
        AFFRAY_CHECK_EQ(error, std::string());
        AFFRAY_CHECK(valid);
    }
    result.shader = std::make_shared<const CompiledShader>(std::move(shader));
    return result;
}

CompileResult LoadCompiledShader(const std::string& path, const std::vector<ParamOverride>& overrides,
                                 const Spaces* spaces) {
    CompileResult result;
    vm::BytecodeFile file;
    if (!vm::ReadBytecodeFile(path, &file, &result.diagnostics)) return result;
    // The verifier checks a program, not what its caller reads: the renderer and `eval` take P
    // from both programs and N from the shade program.
    auto hasOutput = [&](const vm::Program& program, const std::string& tag, const std::string& name) {
        const vm::ProgramOutput* out = program.findOutput(name);
        if (out && out->size == 3) return true;
        result.diagnostics.error({path}, "program '" + tag + "' has no output " + name + " of three values");
        return false;
    };
    if (!hasOutput(file.bound, "bound", "P") || !hasOutput(file.shade, "shade", "P") ||
        !hasOutput(file.shade, "shade", "N"))
        return result;
    CompiledShader shader;
    shader.name = file.shaderName;
    shader.sourcePath = file.sourcePath;
    shader.genericBound = std::move(file.bound);
    shader.genericShade = std::move(file.shade);
    for (const vm::ProgramParam& p : shader.genericShade.params) shader.params.push_back(ParamFromProgram(p));
    shader.opsBeforeOptimisation = static_cast<int>(shader.genericShade.code.size());
    for (const std::string& space : shader.genericBound.spaces) {
        if (spaces && spaces->count(space) && spaces->at(space).toCurrent != kIdentity4) {
            result.paramErrors.push_back("shader '" + shader.name + "' uses coordinate space '" + space +
                                         "', which is not world space here; compiled bytecode treats every space "
                                         "as world space: use the shader's source (.sl)");
            return result;
        }
    }
    // A string value cannot be checked against a compiled file (its string parameters were
    // folded away), so only numbers for names the programs do not have are left out.
    std::set<std::string> declared;
    for (const vm::Program* program : {&shader.genericBound, &shader.genericShade})
        for (const vm::ProgramParam& p : program->params) declared.insert(p.name);
    const std::vector<ParamOverride> kept = KeepDeclared(overrides, declared, true, shader.name, &result.undeclared);
    for (const ParamOverride& o : kept) {
        if (o.text) {
            result.paramErrors.push_back("parameter '" + o.name + "': string values need the shader's source (.sl); '" +
                                         path + "' is compiled bytecode");
            return result;
        }
        // A texture option computed from a parameter was fixed at its default when compiled.
        if (shader.genericBound.textures)
            for (const vm::TextureSlot& slot : *shader.genericBound.textures)
                if (std::count(slot.dependsOn.begin(), slot.dependsOn.end(), o.name)) {
                    result.paramErrors.push_back(
                        "parameter '" + o.name + "' sets an option of the lookup of texture '" + slot.path +
                        "', fixed when '" + path + "' was compiled: use the shader's source (.sl)");
                    return result;
                }
    }
    if (!SpecialiseShader(shader, kept, &result.paramErrors)) return result;
    shader.undeclared = result.undeclared;
    // A compiled file reads no facts; its spaces only to check that they are the world's.
    for (const vm::Program* p : {&shader.genericBound, &shader.genericShade})
        shader.reads.spaces.insert(p->spaces.begin(), p->spaces.end());
    result.shader = std::make_shared<const CompiledShader>(std::move(shader));
    return result;
}

CompileResult LoadShader(const std::string& path, const std::vector<ParamOverride>& overrides,
                         const lang::PreprocessOptions& preprocess, const Spaces* spaces, const SceneFacts* facts) {
    bool compiled = path.size() > 4 && path.compare(path.size() - 4, 4, ".afb") == 0;
    return compiled ? LoadCompiledShader(path, overrides, spaces)
                    : CompileFile(path, overrides, preprocess, spaces, facts);
}

CompileResult CompileFile(const std::string& path, const std::vector<ParamOverride>& overrides,
                          const lang::PreprocessOptions& preprocess, const Spaces* spaces, const SceneFacts* facts) {
    lang::SourceFile file("", "");
    std::string error;
    if (!lang::SourceFile::Load(path, &file, &error)) {
        CompileResult result;
        result.diagnostics.error({path}, error);
        return result;
    }
    return CompileSource(path, file.text(), overrides, preprocess, spaces, facts);
}

}  // namespace affray::compiler
