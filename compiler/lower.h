// compiler/lower.h: checking and lowering a shader's syntax tree to the value graph.
// One walk does both, as Lua's code generator does: each expression is checked and turned into
// IR nodes in the same visit. What an operator, condition, conversion or cast accepts is decided
// by the type rules (compiler/typecheck.h), which the walk asks with its operands' types; names,
// built-in calls, and everything that depends on values (constant indices, space names, loop
// bounds) are still checked here.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "compiler/scene_facts.h"
#include "compiler/spaces.h"
#include "compiler/value_ops.h"
#include "lang/ast.h"
#include "lang/diagnostics.h"
#include "vm/program.h"

namespace affray::compiler {

/// A shader parameter as declared: its type and default (already folded to constants).
struct ParamInfo {
    std::string name;
    Type type = Type::Float;
    std::vector<double> defaults;  // element by element for an array
    bool isOutput = false;
    int arraySize = -1;  // an array of that many elements of `type`, else -1
};

/// The result of lowering one shader instance: its IR and the final values of its outputs, P and
/// N for a displacement shader, Ci and Oi for a surface shader.
struct LoweredShader {
    std::string name;
    lang::ShaderKind kind = lang::ShaderKind::Displacement;
    IrBuilder ir;
    Value finalP;
    Value finalN;
    Value finalCi;
    Value finalOi;
    /// A light shader's outputs: Cl, L (from the light to the point lit) and `lit` (1 where an
    /// illuminate or solar statement ran, else 0), and which of them it has: neither (an ambient
    /// light), illuminate (a local light) or solar (a distant one).
    Value finalCl, finalL, finalLit;
    enum class Emission { Ambient, Illuminate, Solar } emission = Emission::Ambient;
    bool writesP = false;
    bool writesN = false;
    std::vector<ParamInfo> params;
    /// String parameters: compile-time constants (their default, or the instance's value), so
    /// not in `params` and not in the programs.
    std::vector<std::string> stringParams;
    /// Their values, as lowered (a value that is not one constant string is left out).
    std::map<std::string, std::string> stringValues;
    /// The coordinate spaces the shader names, "current" aside (sorted, once each).
    std::vector<std::string> spaces;
    /// Every name of the scene's spaces and facts that lowering looked up (compiler/scene_facts.h).
    SceneReads reads;
    /// The texture lookups' slots (IR Texture nodes name theirs by their channel).
    std::vector<vm::TextureSlot> textures;
};

/// Checks and lowers the one displacement or surface shader in `unit`. Parameters stay IR Param nodes (the
/// i-th declared parameter is index i of `params`), with constant defaults, unless
/// `paramValues` gives every parameter's value: then they are constants, and every branch and
/// loop they decide is folded while lowering (a shader instance's specialisation); string
/// parameters take their value from `stringValues` when it names them, named coordinate
/// spaces their matrices from `spaces` (else the identity), and option(), attribute() and
/// depth() their values from `facts` (compiler/scene_facts.h). Problems go to `diags`; returns
/// nothing if there was any error.
std::optional<LoweredShader> Lower(const lang::TranslationUnit& unit, lang::Diagnostics& diags,
                                   const std::vector<std::vector<double>>* paramValues = nullptr,
                                   const std::map<std::string, std::string>* stringValues = nullptr,
                                   const Spaces* spaces = nullptr, const SceneFacts* facts = nullptr);

}  // namespace affray::compiler
