// compiler/lower.cpp: lowering of names, declarations and expressions (their types checked by
// the rules of typecheck.h), and the entry point. Siblings: lower_logic.cpp (comparisons,
// conditions, ?:), lower_flow.cpp (statements and control flow), lower_functions.cpp (user
// functions, arrays), lower_library.cpp (noise, transforms, spline, filterstep); the state
// they share: lowerer.h. Names: a stack of scopes over the shader globals (P, N, ... from
// vm/program.h) and the parameters. A variable holds a Value (IR node ids), so assignment
// rebinds and never copies. Every error is reported where it happens and the expression yields
// nothing; callers pass the nothing on silently, so one mistake gives one message.
#include "compiler/lower.h"

#include <cmath>
#include <numbers>
#include <unordered_map>

#include "compiler/builtins.h"
#include "compiler/builtins_color.h"
#include "compiler/lowerer.h"

namespace affray::compiler {

using lang::Expr;
using lang::ExprKind;
using lang::SourceLoc;

Lowerer::Lowerer(LoweredShader& out, lang::Diagnostics& diags, const std::vector<std::vector<double>>* paramValues,
                 const std::map<std::string, std::string>* stringValues, const Spaces* spaces, const SceneFacts* facts)
    : m_out(out),
      m_diags(diags),
      m_ops(out.ir),
      m_paramValues(paramValues),
      m_stringValues(stringValues),
      m_spaces(spaces),
      m_facts(facts),
      m_varyingLoopBudget(static_cast<int>(diag::LimitValue(diag::Limit::VaryingLoopIterations))),
      m_constantLoopBudget(static_cast<int>(diag::LimitValue(diag::Limit::LoopIterations))),
      m_maxOps(diag::LimitValue(diag::Limit::ProgramOps)),
      m_maxCallDepth(static_cast<size_t>(diag::LimitValue(diag::Limit::CallDepth))) {}

bool Lowerer::TooLarge(const lang::SourceLoc& loc) {
    if (m_reportedSize) return true;
    if (ir().requestedOps() <= m_maxOps) return false;
    m_reportedSize = true;
    m_diags.error(loc, "the shader grows past " + std::to_string(m_maxOps) +
                           " operations as its loops are unrolled and its calls inlined " +
                           diag::LimitNote(diag::Limit::ProgramOps));
    if (!m_unrolling.empty() && (m_unrolling.back().line != loc.line || m_unrolling.back().file != loc.file))
        m_diags.note(m_unrolling.back(), "while unrolling this loop");
    return true;
}

Value Lowerer::StringValue(const std::string& text) {
    size_t index = 0;
    while (index < m_strings.size() && m_strings[index] != text) ++index;
    if (index == m_strings.size()) m_strings.push_back(text);
    ValueId id = ir().Const(static_cast<double>(index));
    return {Type::String, {id, id, id}};
}

std::optional<std::string> Lowerer::StringOf(const Value& v) const {
    std::optional<double> k = m_out.ir.ConstValue(v.c[0]);
    if (v.type != Type::String || !k || !(*k >= 0 && *k < static_cast<double>(m_strings.size()))) return std::nullopt;
    return m_strings[static_cast<size_t>(*k)];
}

const std::string& Lowerer::UnknownString() {
    static const std::string unknown = std::string(1, '\0') + "(a string parameter)";
    return unknown;
}

Variable* Lowerer::Find(const std::string& name) {
    for (auto scope = m_state.scopes.rbegin(); scope != m_state.scopes.rend(); ++scope) {
        auto it = scope->find(name);
        if (it != scope->end()) return &it->second;
    }
    return nullptr;
}

void Lowerer::PopScope() {
    // After an error, "unused" is more often a consequence than a finding: stay quiet.
    for (const auto& [name, var] : m_state.scopes.back())
        if (!var.used && !var.isGlobal && !m_diags.hasErrors())
            m_diags.warning(var.loc, "unused variable '" + name + "'");
    m_state.scopes.pop_back();
    // Functions defined in the scope go with it.
    while (!m_functions.empty() && m_functions.back().first > m_state.scopes.size()) m_functions.pop_back();
}

std::optional<Value> Lowerer::Convert(const Value& value, Type target, SourceLoc loc, const std::string& what) {
    const Typed typed = ConvertType(value.type, target, what);
    if (!typed.ok()) {
        m_diags.error(loc, typed.error);
        return std::nullopt;
    }
    Value v = value;
    if (v.type == Type::Bool && target != Type::Bool) v.type = Type::Float;  // 1 or 0, as in C
    return v.type == target ? v : m_ops.Promote(v, target);
}

std::optional<Value> Lowerer::LowerIdent(const Expr& e) {
    Variable* var = FindOrExtern(e.name);
    if (!var) {
        if (e.name == "PI") return m_ops.Constant(std::numbers::pi);
        if (SurfaceGlobalType(e.name) != Type::Void)
            m_diags.error(e.loc, "'" + e.name +
                                     "' is a global variable of surface and light shaders: a displacement "
                                     "shader cannot use it");
        else
            m_diags.error(e.loc, "unknown identifier '" + e.name + "'");
        return std::nullopt;
    }
    var->used = true;
    if (!var->assigned) {
        // As prman and aqsis: a warning, and the value is 0 (or ""). Once per variable.
        m_diags.warning(e.loc, "variable '" + e.name + "' is used before it is assigned a value (it is 0 here)");
        var->assigned = true;
    }
    return var->value;
}

std::optional<Value> Lowerer::LowerComponentCall(const Expr& e) {
    const bool isSet = e.name != "comp";
    const bool indexed = e.name == "comp" || e.name == "setcomp";
    // (A plain Value and a flag: GCC 12 misreads an optional's state through the checks below.)
    Value target;
    bool haveTarget = false;
    Variable* unassigned =
        isSet && !e.args.empty() && e.args[0]->kind == ExprKind::Ident ? FindOrExtern(e.args[0]->name) : nullptr;
    if (unassigned && !unassigned->assigned) {
        // Setting a component of a variable not yet assigned starts from 0: no warning.
        unassigned->used = unassigned->assigned = true;
        target = unassigned->value;
        haveTarget = true;
    } else if (!e.args.empty()) {
        if (std::optional<Value> t = LowerExpr(*e.args[0])) {
            target = *t;
            haveTarget = true;
        }
    }
    // A matrix entry takes a row and a column: comp(m, row, column), setcomp(m, row, column, x).
    const bool ofMatrix = indexed && haveTarget && target.type == Type::Matrix;
    const size_t want = (indexed ? (isSet ? 3 : 2) : 2) + (ofMatrix ? 1 : 0);
    if (e.args.size() != want) {
        m_diags.error(e.loc, "'" + e.name + "' expects " + std::to_string(want) + " arguments" +
                                 (ofMatrix ? " for a matrix" : "") + ", got " + std::to_string(e.args.size()));
        return std::nullopt;
    }
    int index = e.name == "setxcomp" ? 0 : e.name == "setycomp" ? 1 : 2;
    if (indexed) {
        // Constant indices: a varying one would select among all the components.
        const int limit = ofMatrix ? 3 : 2;
        index = 0;
        for (size_t a = 1; a <= (ofMatrix ? 2u : 1u); ++a) {
            std::optional<Value> i = LowerExpr(*e.args[a]);
            if (!i) return std::nullopt;
            std::optional<double> k = i->type == Type::Float ? m_out.ir.ConstValue(i->c[0]) : std::nullopt;
            if (!k || *k < 0 || *k > limit || *k != std::floor(*k)) {
                m_diags.error(e.args[a]->loc, "the " +
                                                  std::string(ofMatrix ? (a == 1 ? "row" : "column") : "component") +
                                                  " index of '" + e.name + "' must be the constant 0, 1" +
                                                  (ofMatrix ? ", 2 or 3" : " or 2"));
                return std::nullopt;
            }
            index = index * 4 + static_cast<int>(*k);
        }
    }
    std::optional<Value> x = isSet ? LowerExpr(*e.args.back()) : std::nullopt;
    if (!haveTarget || (isSet && !x)) return std::nullopt;
    if (!IsTriple(target.type) && !ofMatrix) {
        m_diags.error(e.args[0]->loc, "the first argument of '" + e.name + "' must be a point, vector, normal" +
                                          (indexed ? ", color or matrix" : " or color"));
        return std::nullopt;
    }
    if (!isSet) return m_ops.Component(target, index);
    if (x->type == Type::Bool) x->type = Type::Float;
    if (x->type != Type::Float) {
        m_diags.error(e.args.back()->loc,
                      "the new component of '" + e.name + "' must be a float, got " + Article(x->type));
        return std::nullopt;
    }
    Variable* var = e.args[0]->kind == ExprKind::Ident ? FindOrExtern(e.args[0]->name) : nullptr;
    if (!var) {
        m_diags.error(e.args[0]->loc, "the first argument of '" + e.name + "' must be a variable");
        return std::nullopt;
    }
    if (!var->writable) {
        m_diags.error(e.args[0]->loc, "cannot assign to '" + e.args[0]->name + "': it is a read-only global");
        return std::nullopt;
    }
    Value updated = var->value;
    updated.c[index] = x->c[0];
    Store(*var, updated);
    return m_ops.Float(x->c[0]);
}

std::optional<Value> Lowerer::LowerBinary(const Expr& e) {
    using lang::BinaryOp;
    std::optional<Value> a = LowerExpr(*e.args[0]);
    std::optional<Value> b = LowerExpr(*e.args[1]);
    if (!a || !b) return std::nullopt;
    const Typed typed = BinaryType(e.binaryOp, a->type, b->type);
    if (!typed.ok()) {
        m_diags.error(e.loc, typed.error);
        return std::nullopt;
    }
    m_ops.SetLine(e.loc.line);
    switch (e.binaryOp) {
        case BinaryOp::Less:
        case BinaryOp::LessEq:
        case BinaryOp::Greater:
        case BinaryOp::GreaterEq:
        case BinaryOp::Equal:
        case BinaryOp::NotEqual:
        case BinaryOp::And:
        case BinaryOp::Or: return LowerComparison(e, *a, *b);
        default: break;
    }
    // A boolean in arithmetic is the float 1 or 0, as in C.
    if (a->type == Type::Bool) a->type = Type::Float;
    if (b->type == Type::Bool) b->type = Type::Float;
    switch (e.binaryOp) {
        case BinaryOp::Add: return m_ops.Add(*a, *b);
        case BinaryOp::Sub: return m_ops.Sub(*a, *b);
        case BinaryOp::Mul: return m_ops.Mul(*a, *b);
        case BinaryOp::Div: return m_ops.Div(*a, *b);  // a matrix divides by the other's inverse
        case BinaryOp::Dot: return m_ops.Dot(*a, *b);
        case BinaryOp::Cross: return m_ops.Cross(*a, *b);
        default: break;
    }
    return std::nullopt;  // the comparisons were handled above
}

std::optional<Value> Lowerer::LowerAssign(const Expr& e) {
    const Variable* target = FindOrExtern(e.name);
    std::optional<Value> rhs = LowerExpecting(*e.args[0], target ? target->type : Type::Void);
    const bool isElement = e.args.size() == 2;
    std::optional<Value> index = isElement ? LowerExpr(*e.args[1]) : std::nullopt;
    Variable* var = FindOrExtern(e.name);
    if (!var) {
        if (SurfaceGlobalType(e.name) != Type::Void)
            m_diags.error(e.loc, "'" + e.name +
                                     "' is a global variable of surface and light shaders: a displacement "
                                     "shader cannot use it");
        else
            m_diags.error(e.loc, "assignment to undeclared variable '" + e.name + "'");
        return std::nullopt;
    }
    if (!var->writable) {
        m_diags.error(
            e.loc, "cannot assign to '" + e.name + "': it is " + (var->isGlobal ? "a read-only global" : "read-only"));
        return std::nullopt;
    }
    if (isElement != (var->arraySize >= 0)) {
        m_diags.error(e.loc, isElement ? "'" + e.name + "' is not an array"
                                       : "cannot assign to the whole array '" + e.name + "'");
        return std::nullopt;
    }
    if (!rhs || (isElement && !index)) return std::nullopt;
    m_ops.SetLine(e.loc.line);
    const std::string what =
        std::string(ToString(var->type)) + (isElement ? " element of '" : " variable '") + e.name + "'";
    std::optional<Value> current = isElement ? Element(*var, *index, e.args[1]->loc) : var->value;
    if (!current) return std::nullopt;
    Value value = *rhs;
    if (value.type == Type::Bool) value.type = Type::Float;
    if (e.assignOp != lang::AssignOp::Assign) {
        if (!var->assigned) {
            m_diags.warning(e.loc, "variable '" + e.name + "' is used before it is assigned a value (it is 0 here)");
            var->assigned = true;
        }
        const Typed typed = CompoundAssignType(e.assignOp, var->type, value.type, what);
        if (!typed.ok()) {
            m_diags.error(e.loc, typed.error);
            return std::nullopt;
        }
        switch (e.assignOp) {
            case lang::AssignOp::AddAssign: value = m_ops.Add(*current, value); break;
            case lang::AssignOp::SubAssign: value = m_ops.Sub(*current, value); break;
            case lang::AssignOp::MulAssign: value = m_ops.Mul(*current, value); break;
            case lang::AssignOp::DivAssign: value = m_ops.Div(*current, value); break;
            case lang::AssignOp::Assign: break;
        }
    }
    std::optional<Value> converted = Convert(value, var->type, e.loc, what);
    if (!converted) return std::nullopt;
    if (isElement)
        StoreElement(*var, *index, *converted);
    else
        Store(*var, *converted);
    return converted;
}

std::optional<Value> Lowerer::LowerCast(const Expr& e) {
    Type target = FromTypeName(e.castType);
    // A space on a spatial cast is checked like a transform's (all are the identity for now, see
    // lower_library.cpp); a color's is "rgb" (the only color space affray knows).
    if (!e.castSpace.empty()) {
        if (target == Type::Color && !IsColorSpace(e.castSpace)) {
            m_diags.error(e.loc,
                          "unknown color space '" + e.castSpace + "' (rgb, hsv, hsl, xyz, XYZ, xyY and YIQ are known)");
            return std::nullopt;
        }
        if (target != Type::Color && !SpaceName(StringValue(e.castSpace), e.loc)) return std::nullopt;
    }
    std::optional<Value> v = LowerExpecting(*e.args[0], target);
    if (!v) return std::nullopt;
    if (const Typed typed = CastType(v->type, target, !e.castSpace.empty()); !typed.ok()) {
        m_diags.error(e.loc, typed.error);
        return std::nullopt;
    }
    if (v->type == Type::Bool) v->type = Type::Float;
    if (!e.castSpace.empty() && target == Type::Color && (v->type == Type::Float || IsTriple(v->type))) {
        // `color "hsv" (h, s, v)`: components given in that space, converted to rgb.
        m_ops.SetLine(e.loc.line);
        return ColorToRgb(m_ops, e.castSpace, *v);
    }
    if (!e.castSpace.empty() && IsSpatial(target) && (v->type == Type::Float || IsSpatial(v->type))) {
        // `point "shader" (x, y, z)`: coordinates given in that space, converted to current.
        m_ops.SetLine(e.loc.line);
        return ToCurrent(e.castSpace, m_ops.Promote(*v, target), target);
    }
    if (target == Type::Matrix && (v->type == Type::Float || v->type == Type::Matrix)) {
        // `matrix "shader" 1` maps current to shader space; `matrix "world" (...)` prepends the
        // current-to-world transform to the given one (RI Spec 3.2, section 11.4).
        m_ops.SetLine(e.loc.line);
        const Value m = m_ops.Promote(*v, Type::Matrix);
        return e.castSpace.empty() ? m : m_ops.MatrixProduct(CurrentTo(e.castSpace), m);
    }
    if (v->type == target) return v;
    return m_ops.Promote(*v, target);
}

std::optional<Value> Lowerer::LowerCall(const Expr& e, Type expected) {
    // A user function wins over a built-in of the same name.
    if (const lang::FunctionDef* f = FindFunction(e.name)) return LowerUserCall(e, *f);
    if (e.name == "comp" || e.name == "setcomp" || e.name == "setxcomp" || e.name == "setycomp" || e.name == "setzcomp")
        return LowerComponentCall(e);
    if (IsSurfaceCall(e.name)) return LowerSurfaceCall(e, expected);
    if (IsExtraCall(e.name)) return LowerExtraCall(e, expected);
    std::vector<Value> args;
    bool ok = true;
    for (const lang::ExprPtr& arg : e.args) {
        // spline(t, knots) with an array of knots: its elements.
        if (const Variable* array =
                e.name == "spline" && arg->kind == ExprKind::Ident ? FindOrExtern(arg->name) : nullptr;
            array && array->arraySize >= 0) {
            FindOrExtern(arg->name)->used = true;
            args.insert(args.end(), array->elements.begin(), array->elements.end());
            continue;
        }
        std::optional<Value> v = LowerExpr(*arg);
        if (v) args.push_back(*v);
        ok = ok && v.has_value();
    }
    if (!ok) return std::nullopt;
    m_ops.SetLine(e.loc.line);
    if (IsLibraryCall(e.name)) return LowerLibraryCall(e, args, expected);
    for (Value& a : args)
        if (a.type == Type::Bool) a.type = Type::Float;
    return LowerBuiltin(m_ops, e, args, m_diags);
}

std::optional<Value> Lowerer::LowerExpecting(const Expr& e, Type expected) {
    return e.kind == ExprKind::Call ? LowerCall(e, expected) : LowerExpr(e);
}

std::optional<Value> Lowerer::LowerExpr(const Expr& e) {
    std::optional<Value> v = LowerExprOnce(e);
    if (m_observer && v) m_observer(e, *v);
    return v;
}

std::optional<Value> Lowerer::LowerExprOnce(const Expr& e) {
    switch (e.kind) {
        case ExprKind::Number: return m_ops.Constant(e.number);
        case ExprKind::String: return StringValue(e.text);
        case ExprKind::Ident: return LowerIdent(e);
        case ExprKind::Unary: {
            if (e.unaryOp == lang::UnaryOp::Not) {
                std::optional<ValueId> c = LowerCondition(*e.args[0]);
                if (!c) return std::nullopt;
                ValueId v = ir().Unary(IrOp::Not, *c, e.loc.line);
                return Value{Type::Bool, {v, v, v}};
            }
            std::optional<Value> a = LowerExpr(*e.args[0]);
            if (!a) return std::nullopt;
            if (const Typed typed = NegateType(a->type); !typed.ok()) {
                m_diags.error(e.loc, typed.error);
                return std::nullopt;
            }
            if (a->type == Type::Bool) a->type = Type::Float;
            m_ops.SetLine(e.loc.line);
            return m_ops.Neg(*a);
        }
        case ExprKind::Binary: return LowerBinary(e);
        case ExprKind::Assign: return LowerAssign(e);
        case ExprKind::Call: return LowerCall(e, Type::Void);
        case ExprKind::Triple: {
            std::array<ValueId, 3> c{};
            bool ok = true;
            for (int i = 0; i < 3; ++i) {
                std::optional<Value> v = LowerExpr(*e.args[i]);
                if (const Typed typed = v ? TripleComponentType(v->type) : Typed{}; !typed.ok()) {
                    m_diags.error(e.args[i]->loc, typed.error);
                    v.reset();
                }
                if (v) c[i] = v->c[0];
                ok = ok && v.has_value();
            }
            if (!ok) return std::nullopt;
            return m_ops.Triple(Type::Point, c[0], c[1], c[2]);
        }
        case ExprKind::Cast: return LowerCast(e);
        case ExprKind::Ternary: return LowerTernary(e);
        case ExprKind::Index: return LowerIndex(e);
        case ExprKind::Tuple16: {
            Value m{Type::Matrix, {}};
            bool ok = true;
            for (int i = 0; i < 16; ++i) {
                std::optional<Value> v = LowerExpr(*e.args[i]);
                if (const Typed typed = v ? MatrixEntryType(v->type) : Typed{}; !typed.ok()) {
                    m_diags.error(e.args[i]->loc, typed.error);
                    v.reset();
                }
                if (v) m.c[i] = v->c[0];
                ok = ok && v.has_value();
            }
            if (!ok) return std::nullopt;
            return m;
        }
    }
    return std::nullopt;
}

void Lowerer::LowerDecl(const lang::VarDecl& d, std::optional<Value> init) {
    Type type = FromTypeName(d.type);
    auto& scope = m_state.scopes.back();
    if (auto it = scope.find(d.name); it != scope.end()) {
        m_diags.error(d.loc, "redefinition of '" + d.name + "'");
        m_diags.note(it->second.loc, "'" + d.name + "' was declared here");
        return;
    }
    if (type != Type::String && !IsNumeric(type)) {
        m_diags.error(d.loc, std::string(ToString(type)) + " variables are not supported yet");
        return;
    }
    Variable var;
    var.type = type;
    var.loc = d.loc;
    // Not yet assigned: 0, so that a path that never assigns it still has a value to merge.
    var.value = type == Type::String ? StringValue("") : m_ops.Promote(m_ops.Constant(0.0), type);
    if (init) {
        std::optional<Value> converted =
            Convert(*init, type, d.loc, std::string(ToString(type)) + " variable '" + d.name + "'");
        if (converted) var.value = *converted;
        var.assigned = true;  // (after an error too: its uses should not add "used before assigned")
        var.used = var.used || !converted;
    }
    scope.emplace(d.name, var);
}

void Lowerer::DeclarePlaceholder(const lang::VarDecl& d, Type type) {
    Variable var;
    var.type = type;
    var.value = m_ops.Promote(m_ops.Constant(0.0), type);
    var.assigned = var.used = true;
    var.loc = d.loc;
    m_state.scopes.back().emplace(d.name, var);
}

bool Lowerer::Run(const lang::ShaderDef& shader, const std::vector<std::shared_ptr<lang::FunctionDef>>& functions) {
    m_out.name = shader.name;
    m_out.kind = m_kind = shader.kind;
    for (const auto& f : functions) DefineFunction(*f);
    // Scope 0: the globals. P and N are the ones a displacement shader may write; Cs and Os are a
    // surface shader's (a displacement shader cannot name them).
    PushScope();
    for (int g = 0; g < vm::kGlobalCount; ++g) {
        auto global = static_cast<vm::Global>(g);
        Variable var;
        std::string name = vm::GlobalName(global);
        if (!KindHasGlobal(m_kind, name)) continue;
        var.type = GlobalType(name, vm::GlobalSize(global));
        var.isGlobal = true;
        var.assigned = true;
        var.writable = name == "P" || name == "N";
        for (int i = 0; i < vm::GlobalSize(global); ++i) var.value.c[i] = m_out.ir.Global(global, i);
        if (var.type == Type::Float) var.value.c[1] = var.value.c[2] = var.value.c[0];
        var.value.type = var.type;
        m_state.scopes.back().emplace(name, var);
    }
    if (IsSurface()) {
        // A surface shader's outputs Ci (black until it sets it) and Oi (Os until then), and the
        // rest of its globals: L and Cl, which a light loop sets for each light (0 outside
        // one), Ol, alpha, ncomps and dPdtime, which affray gives as 0 (or 3 components).
        AddSurfaceGlobals(m_state.scopes.back());
        m_state.scopes.back().at("Oi").value = Find("Os")->value;
        m_state.scopes.back().at("ncomps").value = m_ops.Constant(3.0);
        for (const char* name : {"Ci", "Oi"}) m_state.scopes.back().at(name).writable = true;
    }
    if (IsLight()) {
        // A light shader's outputs L (from the light to Ps) and Cl, black until it sets them, and
        // Ol; it has no surface of its own to colour (Cs, Os, Ci, Oi are not its).
        for (const SurfaceGlobal& g : kSurfaceGlobals) {
            const std::string name = g.name;
            if (!KindHasGlobal(m_kind, name)) continue;
            Variable var;
            var.type = g.type;
            var.value = m_ops.Promote(m_ops.Constant(0.0), g.type);
            var.assigned = var.used = var.isGlobal = true;
            m_state.scopes.back().emplace(name, var);
        }
        m_lit = False();
    }
    const Value inputP = Find("P")->value, inputN = Find("N")->value;

    // Scope 1: the parameters. A default is a constant expression, evaluated with the earlier
    // parameters at their defaults; the body then sees each parameter as an IR Param node, bound
    // to a constant per shader instance later (compiler/specialise).
    PushScope();
    std::vector<std::string> defaultStrings;  // "name = \"value\"" of string parameters at their defaults
    for (const lang::VarDecl& p : shader.params) {
        Type type = FromTypeName(p.type);
        if (m_state.scopes.back().count(p.name)) {
            m_diags.error(p.loc, "redefinition of parameter '" + p.name + "'");
            continue;
        }
        if (p.arraySize >= 0) {
            // An array parameter: its default is an initialiser list of constants, and the scene
            // sets all its elements at once.
            if (!p.hasInitList) m_diags.error(p.loc, "array parameter '" + p.name + "' needs a default value ({...})");
            LowerArrayDecl(p);
            Variable& var = m_state.scopes.back().at(p.name);
            var.used = true;
            ParamInfo info{p.name, type, {}, p.isOutput, p.arraySize};
            bool constant = true;
            for (const Value& element : var.elements)
                for (int c = 0; c < ScalarCount(type) && constant; ++c) {
                    std::optional<double> k = m_out.ir.ConstValue(element.c[c]);
                    constant = k.has_value();
                    if (k) info.defaults.push_back(*k);
                }
            if (!constant)
                m_diags.error(p.loc, "default value of parameter '" + p.name + "' must be a constant expression");
            if (!m_diags.hasErrors()) m_out.params.push_back(info);
            continue;
        }
        if (!p.init) {
            m_diags.error(p.loc, "parameter '" + p.name + "' needs a default value");
            DeclarePlaceholder(p, type);
            continue;
        }
        if (type == Type::String) {
            // A string parameter is a constant: its default, or the value a scene gives it. The
            // compiler folds what depends on it (a space name, a switch between variants).
            std::optional<Value> init = LowerExpr(*p.init);
            if (init && init->type != Type::String) {
                m_diags.error(p.loc, "default value of string parameter '" + p.name + "' must be a string");
                init.reset();
            }
            Variable var;
            var.type = Type::String;
            var.value = init ? *init : StringValue("");
            m_out.stringParams.push_back(p.name);
            if (m_stringValues && m_stringValues->count(p.name))
                var.value = StringValue(m_stringValues->at(p.name));
            else if (std::optional<std::string> text = StringOf(var.value))
                defaultStrings.push_back(p.name + " = \"" + *text + "\"");
            if (std::optional<std::string> text = StringOf(var.value)) m_out.stringValues[p.name] = *text;
            var.assigned = var.used = true;
            var.writable = false;
            var.loc = p.loc;
            m_state.scopes.back().emplace(p.name, var);
            continue;
        }
        std::optional<Value> init = LowerExpr(*p.init);
        std::optional<Value> value;
        if (init) value = Convert(*init, type, p.loc, std::string(ToString(type)) + " parameter '" + p.name + "'");
        ParamInfo info{p.name, type, {}, p.isOutput};
        for (int i = 0; value && i < value->size(); ++i) {
            std::optional<double> k = m_out.ir.ConstValue(value->c[i]);
            if (!k) {
                m_diags.error(p.loc, "default value of parameter '" + p.name + "' must be a constant expression");
                value.reset();
                break;
            }
            info.defaults.push_back(*k);
        }
        if (!value) {
            DeclarePlaceholder(p, type);
            continue;
        }
        Variable var;
        var.type = type;
        var.value = *value;  // the default, while later defaults are evaluated
        var.assigned = true;
        var.used = true;  // an unused parameter is not worth a warning: the scene may set it
        var.loc = p.loc;
        m_state.scopes.back().emplace(p.name, var);
        m_out.params.push_back(info);
    }
    for (size_t i = 0; i < m_out.params.size(); ++i) {
        const ParamInfo& info = m_out.params[i];
        Variable& var = m_state.scopes.back().at(info.name);
        // Scalar `c` of the parameter (element by element for an array).
        auto scalar = [&](int c) {
            return m_paramValues ? m_out.ir.Const((*m_paramValues)[i][c]) : m_out.ir.Param(static_cast<int>(i), c);
        };
        const int n = ScalarCount(info.type);
        std::vector<Value*> values{&var.value};
        if (info.arraySize >= 0) {
            values.clear();
            for (Value& element : var.elements) values.push_back(&element);
        }
        for (size_t k = 0; k < values.size(); ++k) {
            for (int c = 0; c < n; ++c) values[k]->c[c] = scalar(static_cast<int>(k) * n + c);
            if (info.type == Type::Float) values[k]->c[1] = values[k]->c[2] = values[k]->c[0];
        }
    }

    // Scope 2: the body, lowered as a function that returns nothing.
    PushScope();
    m_state.alive = True();
    FlowContext body;
    body.isLoop = false;
    body.isShader = true;
    body.left = body.skipped = False();
    m_state.contexts.push_back(body);
    for (const lang::StmtPtr& s : shader.body) LowerStmt(*s);
    m_state.contexts.pop_back();
    CheckUncalledFunctions();  // nested ones still in scope, and the top-level ones
    PopScope();
    PopScope();

    const Variable& P = *Find("P");
    const Variable& N = *Find("N");
    m_out.finalP = P.value;
    m_out.finalN = N.value;
    m_out.writesP = P.value.c != inputP.c;
    m_out.writesN = N.value.c != inputN.c;
    if (IsSurface()) {
        m_out.finalCi = Find("Ci")->value;
        m_out.finalOi = Find("Oi")->value;
    } else if (IsLight()) {
        m_out.finalCl = Find("Cl")->value;
        m_out.finalL = Find("L")->value;
        m_out.finalLit = m_ops.Float(m_lit);
    } else if (!m_out.writesP && !m_out.writesN && !m_diags.hasErrors()) {
        // String parameters are folded: a shader may move P only for a value a scene gives them.
        std::string defaults;
        for (const std::string& d : defaultStrings) defaults += (defaults.empty() ? "" : ", ") + d;
        m_diags.warning(
            shader.loc,
            "shader '" + shader.name + "' never changes P or N" +
                (defaults.empty() ? "" : " with its string parameters at their defaults (" + defaults + ")"));
    }
    return !m_diags.hasErrors();
}

namespace {
/// Lower() and LowerObserved(): the checks of the unit as a whole, then the one shader.
std::optional<LoweredShader> LowerUnit(const lang::TranslationUnit& unit, lang::Diagnostics& diags,
                                       const std::vector<std::vector<double>>* paramValues,
                                       const std::map<std::string, std::string>* stringValues, const Spaces* spaces,
                                       const SceneFacts* facts, Lowerer::Observer observe) {
    if (unit.shaders.empty()) {
        if (!diags.hasErrors()) diags.error({1, 1}, "no shader definition in file");
        return std::nullopt;
    }
    for (size_t i = 1; i < unit.shaders.size(); ++i)
        diags.error(unit.shaders[i].loc, "only one shader per file is supported");
    const lang::ShaderDef& shader = unit.shaders.front();
    if (shader.kind != lang::ShaderKind::Displacement && shader.kind != lang::ShaderKind::Surface &&
        shader.kind != lang::ShaderKind::Light) {
        diags.error(shader.loc, std::string(lang::ToString(shader.kind)) +
                                    " shaders are not supported yet; affray runs displacement, surface and light "
                                    "shaders");
        return std::nullopt;
    }
    LoweredShader out;
    Lowerer lowerer(out, diags, paramValues, stringValues, spaces, facts);
    lowerer.Observe(std::move(observe));
    if (!lowerer.Run(shader, unit.functions)) return std::nullopt;
    return out;
}
}  // namespace

std::optional<LoweredShader> Lower(const lang::TranslationUnit& unit, lang::Diagnostics& diags,
                                   const std::vector<std::vector<double>>* paramValues,
                                   const std::map<std::string, std::string>* stringValues, const Spaces* spaces,
                                   const SceneFacts* facts) {
    return LowerUnit(unit, diags, paramValues, stringValues, spaces, facts, nullptr);
}

std::optional<LoweredShader> LowerObserved(const lang::TranslationUnit& unit, lang::Diagnostics& diags,
                                           Lowerer::Observer observe) {
    return LowerUnit(unit, diags, nullptr, nullptr, nullptr, nullptr, std::move(observe));
}

}  // namespace affray::compiler
