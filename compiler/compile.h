// compiler/compile.h: the compiler's front door, from a .sl file to the programs the renderer
// runs. Each shader instance is compiled with its parameter values, so the programs contain only
// what that instance needs: the *bound program* computes the displaced P alone (what the
// intersector evaluates millions of times), the *shade program* computes P and N.
#pragma once

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "compiler/lower.h"
#include "compiler/specialise.h"
#include "diag/diagnostic.h"
#include "lang/preprocess.h"
#include "vm/program.h"

namespace affray::compiler {

struct CompiledShader {
    std::string name;
    std::string sourcePath;
    std::string sourceText;
    /// Displacement (bound and shade programs) or surface (the surface program; bound and shade
    /// are empty).
    lang::ShaderKind kind = lang::ShaderKind::Displacement;
    /// The programs as compiled: parameters are registers (see vm::Program::params).
    vm::Program genericBound;  // outputs: P
    vm::Program genericShade;  // outputs: P, N
    /// The same, specialised for this instance's parameter values.
    vm::Program bound;
    vm::Program shade;
    /// A surface shader's programs, generic and specialised: outputs Ci and Oi, with Light
    /// instructions for its light loops (vm/lights.h); run on points only.
    vm::Program genericSurface;
    vm::Program surface;
    /// surface.usesDerivatives(), once: the renderer then runs it in duals.
    bool surfaceDerivatives = false;
    /// A light shader's programs, generic and specialised: outputs Cl, L (from the light to the
    /// point lit, the global Ps) and lit (1 where an illuminate or solar statement ran); run on
    /// points only. `emission` says which statement it has (neither: an ambient light).
    vm::Program genericLight;
    vm::Program light;
    LoweredShader::Emission emission = LoweredShader::Emission::Ambient;
    /// The instance's string parameters and their values (the scene's, else the defaults): a
    /// light's `__category` is one.
    std::map<std::string, std::string> strings;
    /// The generic program parameters are bound against: genericBound, genericSurface or
    /// genericLight.
    const vm::Program& generic() const {
        return kind == lang::ShaderKind::Surface ? genericSurface
               : kind == lang::ShaderKind::Light ? genericLight
                                                 : genericBound;
    }
    std::vector<ParamInfo> params;
    std::vector<std::string> stringParams;
    /// The instance's parameter values that name no parameter of the shader, left out of it, as
    /// CompileResult::undeclared says them.
    std::vector<std::string> undeclared;
    /// Scalar operations lowering asked for, before folding, sharing and dead-code removal.
    int opsBeforeOptimisation = 0;
    /// What compiling it looked up in the instance's spaces and facts: all the shader depends on
    /// of them (ShaderCache shares it between instances that agree on these).
    SceneReads reads;
};

struct CompileResult {
    /// The compiled shader, shared (never changed once made): a shader cache and every primitive
    /// of a mesh that uses the instance hold the one copy.
    std::shared_ptr<const CompiledShader> shader;
    /// Errors and warnings (diag/diagnostic.h); print them with diagnostics.format().
    diag::Report diagnostics;
    /// Problems with the parameter overrides, each a full sentence.
    std::vector<std::string> paramErrors;
    /// Overrides that name no parameter of the shader, one sentence each ("shader 'wave' has no
    /// parameter 'Kx'"), set even when the compilation fails. They are left out of the instance,
    /// which compiles without them, as prman ignores them with a warning; the caller decides what
    /// they are: the renderer warns at the scene's request, `affray eval` refuses a misspelt --param.
    std::vector<std::string> undeclared;
    bool ok() const { return shader != nullptr; }
};

/// Preprocesses (C preprocessor: #include, #define, #if...) and compiles the shader in the file
/// at `path`, then specialises it with `overrides` bound to its
/// parameters (defaults for the others; overrides it does not declare are left out, see
/// CompileResult::undeclared).
CompileResult CompileFile(const std::string& path, const std::vector<ParamOverride>& overrides = {},
                          const lang::PreprocessOptions& preprocess = {}, const Spaces* spaces = nullptr,
                          const SceneFacts* facts = nullptr);
/// Loads a shader compiled earlier (`affray compile -o NAME.afb`): the generic programs from the
/// file, checked by the loader and the verifier, then specialised with `overrides`. The result
/// has no source text; its ParamInfo list is rebuilt from the programs.
/// A compiled file computes every space as the identity: `spaces` making one the shader names
/// anything else is an error (the source is needed).
CompileResult LoadCompiledShader(const std::string& path, const std::vector<ParamOverride>& overrides = {},
                                 const Spaces* spaces = nullptr);
/// A shader from either kind of file: `.afb` is loaded, anything else compiled with `facts`
/// (bytecode was compiled without a scene: its option(), attribute() and depth() are as there).
CompileResult LoadShader(const std::string& path, const std::vector<ParamOverride>& overrides = {},
                         const lang::PreprocessOptions& preprocess = {}, const Spaces* spaces = nullptr,
                         const SceneFacts* facts = nullptr);
/// Same as CompileFile, from text already in memory (`path` names it in diagnostics).
/// `spaces`: the instance's coordinate spaces (compiler/spaces.h), folded into `bound` and
/// `shade`; the generic programs compute every space as the identity. `facts`: the instance's
/// options and attributes (compiler/scene_facts.h), folded into all four programs.
CompileResult CompileSource(const std::string& path, const std::string& text,
                            const std::vector<ParamOverride>& overrides = {},
                            const lang::PreprocessOptions& preprocess = {}, const Spaces* spaces = nullptr,
                            const SceneFacts* facts = nullptr);

}  // namespace affray::compiler
