// compiler/builtins.h: the built-in functions of the shading language.
// Each built-in lowers to scalar IR through ValueOps; overloads are chosen by argument types.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "compiler/value_ops.h"
#include "lang/ast.h"
#include "lang/diagnostics.h"

namespace affray::compiler {

/// Lowers the call `call` to built-in `call.name` with already lowered `args`. Reports a
/// diagnostic at the call (unknown overload, wrong argument count, unsupported function) and
/// returns nothing on error.
std::optional<Value> LowerBuiltin(ValueOps& ops, const lang::Expr& call, const std::vector<Value>& args,
                                  lang::Diagnostics& diags);

/// The names of the built-ins above: their rows and the opcode table's.
std::vector<std::string> TableBuiltinNames();
/// Every built-in function the compiler knows by name, sorted: the above and those the lowerer
/// handles itself (noise, transform, spline, printf, diffuse...). docs/builtins.md lists them.
std::vector<std::string> KnownBuiltinNames();

}  // namespace affray::compiler
