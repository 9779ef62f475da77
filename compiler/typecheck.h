// compiler/typecheck.h: the shading language's type rules, and the pass that applies them to a
// shader's syntax tree (the typed AST).
// The rules are functions of operand types alone: each gives the construct's result type, or the
// error message to report at the construct's location. They are the one statement of what the
// operators, conditions, conversions and casts accept; the lowering (compiler/lower*.cpp) asks
// them at each such node it reaches and reports their verdict there, so that diagnostics keep the
// order, the dead-code checking and the once-per-place rule of its walk (golden-pinned).
// Typecheck() walks a shader as written (lexical scopes, declarations, user functions) and
// records every expression's type, and what a name or call resolves to, in a side table keyed by
// node (TypedShader), leaving the tree as the parser built it. It reports nothing. The lowering
// does not read it yet: built-in calls (typed by the lowering's overload choice) and names a
// nested function reaches in its caller's scopes are not typed here (docs/design.md, "Compiler
// passes"). Where it does give a type, a test holds it to the lowering's (LowerObserved, over
// every shader of the suite and the library).
#pragma once

#include <memory>
#include <string>
#include <unordered_map>
#include <vector>

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

/// The type of the shader global `name` (a VM global of `size` scalars, vm/program.h, or one
/// of kSurfaceGlobals), and whether a shader of `kind` has it: Cs and Os and the surface
/// globals are a surface shader's, Ps and L, Cl, Ol a light shader's, the other VM globals
/// every shader's.
Type GlobalType(const std::string& name, int size);
bool KindHasGlobal(lang::ShaderKind kind, const std::string& name);

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

/// What a name in an expression refers to.
enum class SymbolKind { Unknown, Global, Parameter, Local, Function };

/// One expression of the typed AST: its type (Void if it has none or is ill-typed) and, for a
/// name or a call, what it resolved to.
struct ExprType {
    Type type = Type::Void;
    SymbolKind symbol = SymbolKind::Unknown;
    int arraySize = -1;                         // a name of an array: its size (0: unsized)
    const lang::FunctionDef* callee = nullptr;  // a call of a user function
};

/// The typed AST of one shader: the syntax tree (owned by the TranslationUnit, which must outlive
/// it) with a type for every expression the checker could type. Types that depend on more than
/// the source (a variable a nested function reaches in its caller's scopes, a built-in's result
/// under a type the checker does not know) are left out: Find gives null for them.
class TypedShader {
  public:
    const ExprType* Find(const lang::Expr& e) const {
        auto it = m_types.find(&e);
        return it == m_types.end() ? nullptr : &it->second;
    }
    /// The type of `e`, or Void if the checker could not type it.
    Type TypeOf(const lang::Expr& e) const {
        const ExprType* t = Find(e);
        return t ? t->type : Type::Void;
    }
    void Set(const lang::Expr& e, const ExprType& t) { m_types[&e] = t; }
    size_t size() const { return m_types.size(); }

  private:
    std::unordered_map<const lang::Expr*, ExprType> m_types;
};

/// Types `shader` and the user functions visible to it (`functions`: the top-level ones).
TypedShader Typecheck(const lang::ShaderDef& shader, const std::vector<std::shared_ptr<lang::FunctionDef>>& functions);

}  // namespace affray::compiler
