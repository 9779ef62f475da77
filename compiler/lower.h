// compiler/lower.h: checking and lowering a shader's syntax tree to the value graph.
// One walk does both, as Lua's code generator does: each expression is type-checked and turned
// into IR nodes in the same visit, so there is no annotated tree to keep in step.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "compiler/value_ops.h"
#include "lang/ast.h"
#include "lang/diagnostics.h"

namespace affray::compiler {

/// A value given to a shader parameter by the scene (or `affray eval --param`).
struct ParamOverride {
    std::string name;
    std::vector<double> numbers;
};

/// A shader parameter as declared: its type and default (already folded to constants).
struct ParamInfo {
    std::string name;
    Type type = Type::Float;
    std::vector<double> defaults;
    bool isOutput = false;
};

/// The result of lowering one shader instance: its IR and the final values of P and N.
struct LoweredShader {
    std::string name;
    IrBuilder ir;
    Value finalP;
    Value finalN;
    bool writesP = false;
    bool writesN = false;
    std::vector<ParamInfo> params;
};

/// Checks and lowers the one displacement shader in `unit`, with every parameter bound to a
/// constant: its override if given, else its default (specialisation). Problems in the source go
/// to `diags`; problems with the overrides (unknown name, wrong count, NaN or infinite value) are
/// appended to *overrideErrors. Returns nothing if there was any error.
std::optional<LoweredShader> Lower(const lang::TranslationUnit& unit,
                                   const std::vector<ParamOverride>& overrides,
                                   lang::Diagnostics& diags,
                                   std::vector<std::string>* overrideErrors);

}  // namespace affray::compiler
