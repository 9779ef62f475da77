// compiler/typecheck.cpp: the type rules (see typecheck.h), and the pass that types a shader.
// A rule takes the operand types as the lowering sees them: Bool is the type of a comparison,
// taken as the float 1 or 0 in arithmetic (as in C) but not as a triple's component.
#include "compiler/typecheck.h"

#include <algorithm>
#include <iterator>
#include <map>

#include "vm/program.h"

namespace affray::compiler {

using lang::AssignOp;
using lang::BinaryOp;

namespace {
Typed Ok(Type t) { return {t, {}}; }
Typed Error(std::string message) { return {Type::Void, std::move(message)}; }
Type Arithmetic(Type t) { return t == Type::Bool ? Type::Float : t; }
bool MixesColor(Type a, Type b) { return (a == Type::Color && IsSpatial(b)) || (b == Type::Color && IsSpatial(a)); }
bool MixesMatrix(Type a, Type b) { return (a == Type::Matrix && IsTriple(b)) || (b == Type::Matrix && IsTriple(a)); }

/// Comparisons and && ||: on the operands as written (a Bool is named "boolean").
Typed ComparisonType(BinaryOp op, Type a, Type b) {
    const std::string opName = lang::ToString(op);
    auto bad = [&](const std::string& why) {
        return Error("invalid operands to '" + opName + "' (" + ToString(a) + " and " + ToString(b) + ")" + why);
    };
    if (op == BinaryOp::And || op == BinaryOp::Or) {
        auto truth = [](Type t) { return t == Type::Bool || t == Type::Float; };
        if (!truth(a) || !truth(b)) return bad(": '" + opName + "' combines conditions");
        return Ok(Type::Bool);
    }
    // Strings compare by their ids (one id per distinct text).
    if (a == Type::String || b == Type::String) {
        if (a != b || (op != BinaryOp::Equal && op != BinaryOp::NotEqual))
            return bad(": strings compare only with == and != to strings");
        return Ok(Type::Bool);
    }
    const Type x = Arithmetic(a), y = Arithmetic(b);
    if (!IsNumeric(x) || !IsNumeric(y)) return bad("");
    if (op == BinaryOp::Equal || op == BinaryOp::NotEqual) {
        if (MixesColor(x, y)) return bad(": a color does not compare with a point, vector or normal");
        if (MixesMatrix(x, y)) return bad(": a matrix compares with a matrix or a float");
        return Ok(Type::Bool);  // triples and matrices: equal when every component is
    }
    if (x != Type::Float || y != Type::Float) return bad(": only floats are ordered");
    return Ok(Type::Bool);
}
}  // namespace

std::string Article(Type t) {
    std::string name = ToString(t);
    return (name[0] == 'a' || name[0] == 'e' || name[0] == 'i' || name[0] == 'o' || name[0] == 'u' ? "an " : "a ") +
           name;
}

Type GlobalType(const std::string& name, int size) {
    for (const SurfaceGlobal& g : kSurfaceGlobals)
        if (name == g.name) return g.type;
    return size == 1                                    ? Type::Float
           : name == "N" || name == "Ng"                ? Type::Normal
           : name == "P" || name == "E" || name == "Ps" ? Type::Point
                                                        : Type::Vector;
}

bool KindHasGlobal(lang::ShaderKind kind, const std::string& name) {
    const bool surfaceGlobal = std::any_of(std::begin(kSurfaceGlobals), std::end(kSurfaceGlobals),
                                           [&](const SurfaceGlobal& g) { return name == g.name; });
    if (name == "L" || name == "Cl" || name == "Ol")
        return kind == lang::ShaderKind::Surface || kind == lang::ShaderKind::Light;
    if (surfaceGlobal) return kind == lang::ShaderKind::Surface;
    if (name == "Ps") return kind == lang::ShaderKind::Light;
    return true;
}

Typed NegateType(Type a) {
    const Type x = Arithmetic(a);
    if (x != Type::Float && !IsTriple(x))
        return Error("invalid operand to unary '-' (" + std::string(ToString(x)) + ")");
    return Ok(x);
}

Typed BinaryType(BinaryOp op, Type a, Type b) {
    switch (op) {
        case BinaryOp::Less:
        case BinaryOp::LessEq:
        case BinaryOp::Greater:
        case BinaryOp::GreaterEq:
        case BinaryOp::Equal:
        case BinaryOp::NotEqual:
        case BinaryOp::And:
        case BinaryOp::Or: return ComparisonType(op, a, b);
        default: break;
    }
    // A boolean in arithmetic is the float 1 or 0, as in C.
    const Type x = Arithmetic(a), y = Arithmetic(b);
    auto bad = [&](const std::string& why) {
        return Error("invalid operands to '" + std::string(lang::ToString(op)) + "' (" + ToString(x) + " and " +
                     ToString(y) + ")" + why);
    };
    if (!IsNumeric(x) || !IsNumeric(y)) return bad("");
    if (x == Type::Matrix || y == Type::Matrix) {
        // Matrices multiply and divide (by the inverse) each other and floats; a point goes
        // through transform().
        const bool mulOrDiv = op == BinaryOp::Mul || op == BinaryOp::Div;
        if (!mulOrDiv || IsTriple(x) || IsTriple(y))
            return bad(": a matrix only multiplies or divides a matrix or a float (transform() applies it to a point)");
        return Ok(Type::Matrix);
    }
    switch (op) {
        case BinaryOp::Add:
        case BinaryOp::Sub:
        case BinaryOp::Mul:
        case BinaryOp::Div: {
            const bool mixesColor = MixesColor(x, y);
            if (mixesColor) return bad(": a color does not combine with a point, vector or normal");
            return Ok(IsTriple(x) ? x : y);  // a float with a triple: the triple's type
        }
        case BinaryOp::Dot:
            if (!IsTriple(x) || !IsTriple(y)) return bad(": '.' is the dot product of two triples");
            return Ok(Type::Float);
        case BinaryOp::Cross:
            if (!IsSpatial(x) || !IsSpatial(y)) return bad(": '^' is the cross product of two vectors");
            return Ok(Type::Vector);
        default: break;
    }
    return Error("invalid operands to '" + std::string(lang::ToString(op)) + "'");  // not reached: all ops above
}

Typed ConditionType(Type t) {
    // A float condition means "!= 0" (C's rule; some RenderMan compilers accept it too).
    if (t == Type::Bool || t == Type::Float) return Ok(Type::Bool);
    return Error("a condition must be a comparison or a float, not " + Article(t));
}

Typed TernaryType(Type x, Type y) {
    if (x == Type::Bool && y == Type::Bool) return Ok(Type::Bool);
    x = Arithmetic(x);
    y = Arithmetic(y);
    if (x == Type::String && y == Type::String) return Ok(Type::String);
    if (!IsNumeric(x) || !IsNumeric(y) || MixesColor(x, y) || MixesMatrix(x, y))
        return Error("the two results of '?:' have incompatible types (" + std::string(ToString(x)) + " and " +
                     ToString(y) + ")");
    return Ok(x == Type::Float ? y : x);  // a float arm is promoted to the other's type
}

Typed TripleComponentType(Type t) {
    // A comparison is not a component: (x > 0, 0, 0) is more likely a mistake than a mask.
    if (t != Type::Float) return Error("a triple's components must be floats, got " + Article(t));
    return Ok(Type::Float);
}

Typed MatrixEntryType(Type t) {
    if (Arithmetic(t) != Type::Float) return Error("a matrix's entries must be floats, got " + Article(t));
    return Ok(Type::Float);
}

Typed ConvertType(Type from, Type target, const std::string& what) {
    if (from == Type::Bool && target != Type::Bool) from = Type::Float;  // 1 or 0, as in C
    if (from == target) return Ok(target);
    if ((IsTriple(target) || target == Type::Matrix) && from == Type::Float) return Ok(target);
    if (IsSpatial(target) && IsSpatial(from)) return Ok(target);
    return Error("cannot assign " + Article(from) + " to " + what);
}

Typed CompoundAssignType(AssignOp op, Type var, Type value, const std::string& what) {
    value = Arithmetic(value);
    const bool matrixOp = var == Type::Matrix && (op == AssignOp::MulAssign || op == AssignOp::DivAssign);
    if ((!IsTriple(var) && var != Type::Float && !matrixOp) ||
        (var == Type::Matrix && value != Type::Float && value != Type::Matrix) ||
        (value == Type::Matrix && var != Type::Matrix))
        return Error("invalid operands to '" + std::string(lang::ToString(op)) + "' (" + ToString(var) + " and " +
                     ToString(value) + ")");
    if (IsTriple(value) && !IsTriple(var)) return Error("cannot assign " + Article(value) + " to " + what);
    if (MixesColor(var, value)) return Error("cannot assign " + Article(value) + " to " + what);
    return Ok(var);
}

Typed CastType(Type from, Type target, bool withSpace) {
    from = Arithmetic(from);
    // `color "hsv" (h, s, v)`, `point "shader" (x, y, z)`: components given in that space.
    if (withSpace && target == Type::Color && (from == Type::Float || IsTriple(from))) return Ok(target);
    if (withSpace && IsSpatial(target) && (from == Type::Float || IsSpatial(from))) return Ok(target);
    if (target == Type::Matrix && (from == Type::Float || from == Type::Matrix)) return Ok(target);
    if (from == target) return Ok(target);
    if (target == Type::Float || from == Type::String || target == Type::String || target == Type::Void ||
        target == Type::Matrix || from == Type::Matrix)
        return Error("cannot cast " + Article(from) + " to " + ToString(target));
    return Ok(target);
}

namespace {
using lang::Expr;
using lang::ExprKind;
using lang::Stmt;
using lang::StmtKind;

/// A name's declaration as the checker sees it.
struct Symbol {
    Type type = Type::Void;
    SymbolKind kind = SymbolKind::Local;
    int arraySize = -1;
};

/// The checking walk: lexical scopes of variables and of user functions over one shader.
class Checker {
  public:
    explicit Checker(TypedShader& out) : m_out(out) {}

    void Shader(const lang::ShaderDef& shader, const std::vector<std::shared_ptr<lang::FunctionDef>>& functions) {
        m_functions.emplace_back();
        for (const auto& f : functions) m_functions.back().emplace(f->name, f.get());
        m_scopes.emplace_back();
        for (int g = 0; g < vm::kGlobalCount; ++g) {
            const auto global = static_cast<vm::Global>(g);
            const std::string name = vm::GlobalName(global);
            if (KindHasGlobal(shader.kind, name))
                m_scopes.back()[name] = {GlobalType(name, vm::GlobalSize(global)), SymbolKind::Global, -1};
        }
        for (const SurfaceGlobal& g : kSurfaceGlobals)
            if (KindHasGlobal(shader.kind, g.name)) m_scopes.back()[g.name] = {g.type, SymbolKind::Global, -1};
        // A top-level function sees the globals only (its callers' variables through extern).
        for (const auto& f : functions) Function(*f);
        Push();
        for (const lang::VarDecl& p : shader.params) {
            if (p.init) Walk(*p.init);
            for (const lang::ExprPtr& x : p.initList) Walk(*x);
            Declare(p, SymbolKind::Parameter);
        }
        Push();
        for (const lang::StmtPtr& s : shader.body) Statement(*s);
    }

  private:
    void Push() {
        m_scopes.emplace_back();
        m_functions.emplace_back();
    }
    void Pop() {
        m_scopes.pop_back();
        m_functions.pop_back();
    }
    void Declare(const lang::VarDecl& d, SymbolKind kind) {
        // The first declaration of a name in a scope stands (a second one is an error).
        m_scopes.back().emplace(d.name, Symbol{FromTypeName(d.type), kind, d.arraySize});
    }
    const Symbol* FindName(const std::string& name) const {
        for (auto it = m_scopes.rbegin(); it != m_scopes.rend(); ++it)
            if (auto found = it->find(name); found != it->end()) return &found->second;
        return nullptr;
    }
    const lang::FunctionDef* FindFunction(const std::string& name) const {
        for (auto it = m_functions.rbegin(); it != m_functions.rend(); ++it)
            if (auto found = it->find(name); found != it->end()) return found->second;
        return nullptr;
    }

    /// A function's body, in the scopes where it is defined (its parameters in a scope of their own).
    void Function(const lang::FunctionDef& f) {
        Push();
        for (const lang::VarDecl& p : f.params) Declare(p, SymbolKind::Parameter);
        Push();
        for (const lang::StmtPtr& s : f.body) Statement(*s);
        Pop();
        Pop();
    }

    void Statement(const Stmt& s) {
        switch (s.kind) {
            case StmtKind::Expr: Walk(*s.expr); break;
            case StmtKind::Decl:
                for (const lang::VarDecl& d : s.decls) {
                    if (d.init) Walk(*d.init);
                    for (const lang::ExprPtr& x : d.initList) Walk(*x);
                    Declare(d, SymbolKind::Local);
                }
                break;
            case StmtKind::Block:
                Push();
                for (const lang::StmtPtr& child : s.body) Statement(*child);
                Pop();
                break;
            case StmtKind::Empty:
            case StmtKind::Break:
            case StmtKind::Continue: break;
            case StmtKind::If:
                Walk(*s.expr);
                for (const lang::StmtPtr& arm : s.body) {
                    if (!arm) continue;
                    Push();
                    Statement(*arm);
                    Pop();
                }
                break;
            case StmtKind::For:
            case StmtKind::While:
                Push();
                if (s.init) Walk(*s.init);
                if (s.expr) Walk(*s.expr);
                if (s.body[0]) {
                    Push();
                    Statement(*s.body[0]);
                    Pop();
                }
                if (s.step) Walk(*s.step);
                Pop();
                break;
            case StmtKind::Return:
                if (s.expr) Walk(*s.expr);
                break;
            case StmtKind::FunctionDef:
                // Visible from here to the end of the enclosing scope; a first definition stands.
                m_functions.back().emplace(s.function->name, s.function.get());
                Function(*s.function);
                break;
        }
    }

    /// Types `e` and its operands; Void if it cannot be typed (an error, or a type the source
    /// alone does not decide). Every typed node is recorded.
    Type Walk(const Expr& e) {
        ExprType t = Type_(e);
        if (t.type != Type::Void) m_out.Set(e, t);
        return t.type;
    }

    ExprType Type_(const Expr& e) {
        auto of = [](const Typed& typed) { return ExprType{typed.ok() ? typed.type : Type::Void}; };
        switch (e.kind) {
            case ExprKind::Number: return {Type::Float};
            case ExprKind::String: return {Type::String};
            case ExprKind::Ident: {
                if (const Symbol* s = FindName(e.name)) return {s->type, s->kind, s->arraySize};
                if (e.name == "PI") return {Type::Float, SymbolKind::Global};
                return {};  // unknown here (reported by the lowering), or a caller's (implicit extern)
            }
            case ExprKind::Unary: {
                const Type a = Walk(*e.args[0]);
                if (a == Type::Void) return {};
                if (e.unaryOp == lang::UnaryOp::Not) return of(ConditionType(a));
                return of(NegateType(a));
            }
            case ExprKind::Binary: {
                const Type a = Walk(*e.args[0]);
                const Type b = Walk(*e.args[1]);
                if (a == Type::Void || b == Type::Void) return {};
                return of(BinaryType(e.binaryOp, a, b));
            }
            case ExprKind::Assign: {
                const Type value = Walk(*e.args[0]);
                if (e.args.size() == 2) Walk(*e.args[1]);
                const Symbol* target = FindName(e.name);
                if (!target || value == Type::Void) return {};
                // The assignment's value is the stored one, in the variable's type.
                const Typed stored = e.assignOp == lang::AssignOp::Assign
                                         ? ConvertType(value, target->type, e.name)
                                         : CompoundAssignType(e.assignOp, target->type, value, e.name);
                return {stored.ok() ? target->type : Type::Void, target->kind};
            }
            case ExprKind::Call: {
                for (const lang::ExprPtr& arg : e.args) Walk(*arg);
                // A user function wins over a built-in of the same name; a built-in's result type
                // is left to the lowering, which chooses among its overloads.
                if (const lang::FunctionDef* f = FindFunction(e.name))
                    return {FromTypeName(f->returnType), SymbolKind::Function, -1, f};
                return {};
            }
            case ExprKind::Triple: {
                bool ok = true;
                for (int i = 0; i < 3; ++i) ok = TripleComponentType(Walk(*e.args[i])).ok() && ok;
                return {ok ? Type::Point : Type::Void};
            }
            case ExprKind::Tuple16: {
                bool ok = true;
                for (int i = 0; i < 16; ++i) ok = MatrixEntryType(Walk(*e.args[i])).ok() && ok;
                return {ok ? Type::Matrix : Type::Void};
            }
            case ExprKind::Cast: {
                const Type from = Walk(*e.args[0]);
                if (from == Type::Void) return {};
                return of(CastType(from, FromTypeName(e.castType), !e.castSpace.empty()));
            }
            case ExprKind::Ternary: {
                const Type c = Walk(*e.args[0]);
                const Type x = Walk(*e.args[1]);
                const Type y = Walk(*e.args[2]);
                if (c == Type::Void || x == Type::Void || y == Type::Void || !ConditionType(c).ok()) return {};
                return of(TernaryType(x, y));
            }
            case ExprKind::Index: {
                Walk(*e.args[1]);
                const Type array = Walk(*e.args[0]);
                const ExprType* base = m_out.Find(*e.args[0]);
                if (array == Type::Void || !base || base->arraySize < 0) return {};
                return {array};
            }
        }
        return {};
    }

    TypedShader& m_out;
    std::vector<std::map<std::string, Symbol>> m_scopes;
    std::vector<std::map<std::string, const lang::FunctionDef*>> m_functions;
};
}  // namespace

TypedShader Typecheck(const lang::ShaderDef& shader, const std::vector<std::shared_ptr<lang::FunctionDef>>& functions) {
    TypedShader out;
    Checker(out).Shader(shader, functions);
    return out;
}

}  // namespace affray::compiler
