// compiler/typecheck.h: the shading language's type rules.
// The rules are functions of operand types alone: each gives the construct's result type, or the
// error message to report at the construct's location. They are the one statement of what the
// operators, conditions, conversions and casts accept; the lowering (compiler/lower*.cpp) asks
// them at each such node it reaches and reports their verdict there, so that diagnostics keep the
// order, the dead-code checking and the once-per-place rule of its walk (golden-pinned).
#pragma once

#include <string>

#include "compiler/types.h"
#include "lang/ast.h"

namespace affray::compiler {

/// The verdict of a type rule: the result type, or why the construct is ill-typed.
struct Typed {
    Type type = Type::Void;
    std::string error;  // empty: well typed
    bool ok() const { return error.empty(); }
};

/// "a float", "an integer": a type with its indefinite article, for messages.
std::string Article(Type t);

/// Unary minus: a float or a triple, negated component by component.
Typed NegateType(Type a);
/// A binary operator on operands of types `a` and `b` (a comparison or && || gives Bool).
Typed BinaryType(lang::BinaryOp op, Type a, Type b);
/// A condition (if, while, for, ?:, !): a comparison or a float meaning "!= 0".
Typed ConditionType(Type t);
/// The two results of `c ? x : y`.
Typed TernaryType(Type x, Type y);
/// A component of a parenthesised triple `(a, b, c)`, and an entry of a 16-tuple matrix.
Typed TripleComponentType(Type t);
Typed MatrixEntryType(Type t);
/// A value of type `from` stored in something of type `target` (a variable, a parameter, a
/// return value): float -> triple and matrix promotion, point/vector/normal interchange.
/// `what` names the target in the message ("float variable 'x'").
Typed ConvertType(Type from, Type target, const std::string& what);
/// `var op= value`: the type of `var op value` before it is converted back to `var`'s type.
Typed CompoundAssignType(lang::AssignOp op, Type var, Type value, const std::string& what);
/// A cast `target (x)` of a value of type `from`, with a space name or not.
Typed CastType(Type from, Type target, bool withSpace);

}  // namespace affray::compiler
