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

}  // namespace affray::compiler
