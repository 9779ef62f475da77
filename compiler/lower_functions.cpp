// compiler/lower_functions.cpp: user functions (inlined at each call) and arrays.
// RenderMan functions have no pointers, no recursion in practice and small bodies, so each call
// is lowered in place: the arguments are bound to the parameters, the body runs in a scope that
// sees the shader globals, its parameters and the variables it declares `extern`, and `output`
// parameters and extern variables are written back to the caller's variables afterwards. A
// call that reaches a function already being inlined is recursion, reported as an error.
// Arrays are a list of values, one per element; an index that is not a compile-time constant
// selects among them.
#include <cmath>
#include <limits>

#include "compiler/lowerer.h"

namespace affray::compiler {

using lang::Expr;
using lang::ExprKind;

namespace {

/// A `return` with a value somewhere in `body` (not in nested functions).
bool HasValueReturn(const std::vector<lang::StmtPtr>& body) {
    for (const lang::StmtPtr& s : body) {
        if (!s) continue;
        if (s->kind == lang::StmtKind::Return && s->expr) return true;
        if (s->kind != lang::StmtKind::FunctionDef && HasValueReturn(s->body)) return true;
    }
    return false;
}
}  // namespace

const lang::FunctionDef* Lowerer::FindFunction(const std::string& name) const {
    for (auto it = m_functions.rbegin(); it != m_functions.rend(); ++it)
        if (it->second->name == name) return it->second;
    return nullptr;
}

void Lowerer::DefineFunction(const lang::FunctionDef& f) {
    const size_t depth = m_state.scopes.size();
    for (const auto& [d, other] : m_functions) {
        if (d == depth && other->name == f.name) {
            m_diags.error(f.loc, "redefinition of function '" + f.name + "'");
            m_diags.note(other->loc, "'" + f.name + "' was defined here");
            return;
        }
    }
    m_functions.emplace_back(depth, &f);
    m_defined.push_back(&f);
    if (depth > 0) m_nested.insert(&f);
}

std::optional<Value> Lowerer::LowerUserCall(const Expr& call, const lang::FunctionDef& f) {
    for (const lang::FunctionDef* active : m_callStack) {
        if (active == &f) {
            m_diags.error(call.loc, "recursive call to '" + f.name +
                                        "': affray inlines functions, so a function cannot call itself");
            m_diags.note(f.loc, "'" + f.name + "' is defined here");
            return std::nullopt;
        }
    }
    if (m_callStack.size() >= m_maxCallDepth) {
        m_diags.error(call.loc, "calls nest deeper than " + std::to_string(m_maxCallDepth) + " functions " +
                                    diag::LimitNote(diag::Limit::CallDepth));
        return std::nullopt;
    }
    if (call.args.size() != f.params.size()) {
        m_diags.error(call.loc, "'" + f.name + "' expects " + std::to_string(f.params.size()) + " argument" +
                                    (f.params.size() == 1 ? "" : "s") + ", got " + std::to_string(call.args.size()));
        m_diags.note(f.loc, "'" + f.name + "' is defined here");
        return std::nullopt;
    }

    // Bind the arguments: by value, or (output parameters) from and back to a variable.
    std::vector<Variable> params;
    std::vector<std::string> writeBack(f.params.size());
    bool ok = true;
    for (size_t i = 0; i < f.params.size(); ++i) {
        const lang::VarDecl& p = f.params[i];
        const Expr& arg = *call.args[i];
        Variable param;
        param.type = FromTypeName(p.type);
        param.loc = p.loc;
        param.assigned = param.used = true;
        const bool wantsArray = p.arraySize >= 0;
        if (wantsArray || p.isOutput) {
            const Variable* source = arg.kind == ExprKind::Ident ? FindOrExtern(arg.name) : nullptr;
            if (!source) {
                m_diags.error(arg.loc, std::string("argument ") + std::to_string(i + 1) + " of '" + f.name +
                                           "' must be " +
                                           (wantsArray ? "an array variable" : "a variable (its parameter is output)"));
                ok = false;
                continue;
            }
            if (wantsArray != (source->arraySize >= 0) ||
                (wantsArray && p.arraySize > 0 && p.arraySize != source->arraySize) ||
                (p.isOutput && source->type != param.type && !(IsSpatial(source->type) && IsSpatial(param.type)))) {
                auto arrayText = [](int size) {
                    return size < 0    ? std::string()
                           : size == 0 ? std::string(" array")
                                       : " array of " + std::to_string(size);
                };
                m_diags.error(arg.loc, "argument " + std::to_string(i + 1) + " of '" + f.name + "' is " +
                                           Article(source->type) + arrayText(source->arraySize) + "; the parameter '" +
                                           p.name + "' is " + Article(param.type) + arrayText(p.arraySize) +
                                           (p.isOutput ? " (output)" : ""));
                ok = false;
                continue;
            }
            Variable* mutableSource = FindOrExtern(arg.name);
            mutableSource->used = true;
            param.arraySize = source->arraySize;
            param.elements = source->elements;
            param.value = m_ops.Promote(source->value, param.type);
            if (p.isOutput) {
                if (!source->writable) {
                    m_diags.error(arg.loc, "cannot pass '" + arg.name + "' to output parameter '" + p.name +
                                               "': it is read-only");
                    ok = false;
                    continue;
                }
                writeBack[i] = arg.name;
            }
        } else {
            std::optional<Value> v = LowerExpr(arg);
            if (!v) {
                ok = false;
                continue;
            }
            if (v->type == Type::Bool) v->type = Type::Float;
            std::optional<Value> converted =
                Convert(*v, param.type, arg.loc, "parameter '" + p.name + "' of '" + f.name + "'");
            if (!converted) {
                ok = false;
                continue;
            }
            param.value = *converted;
        }
        params.push_back(param);
    }
    if (!ok) return std::nullopt;

    // The body's scopes: the globals, then the parameters; the caller's other scopes wait.
    std::vector<std::unordered_map<std::string, Variable>> callerScopes(
        std::make_move_iterator(m_state.scopes.begin() + 1), std::make_move_iterator(m_state.scopes.end()));
    m_state.scopes.resize(1);
    // The function table as the call found it: scopes popped inside the body (whose depths
    // count from the globals again) must not take the caller's functions with them.
    const auto functionsBefore = m_functions;
    PushScope();
    if (m_checkingOnly) AddSurfaceGlobals(m_state.scopes.back());
    for (size_t i = 0; i < params.size(); ++i) m_state.scopes.back()[f.params[i].name] = params[i];
    m_externs.push_back({&callerScopes, {}});

    m_callStack.push_back(&f);
    m_called.insert(&f);
    const int errorsBefore = m_diags.errorCount();
    const ValueId aliveBefore = m_state.alive;
    FlowContext context;
    context.isLoop = false;
    context.left = context.skipped = False();
    context.returnType = FromTypeName(f.returnType);
    m_state.contexts.push_back(context);
    PushScope();
    for (const lang::StmtPtr& s : f.body) LowerStmt(*s);
    PopScope();
    const FlowContext done = m_state.contexts.back();
    m_state.contexts.pop_back();
    m_state.alive = aliveBefore;
    m_callStack.pop_back();

    // Collect what goes back to the caller, then restore its scopes.
    std::vector<Variable> outputs(params.size());
    for (size_t i = 0; i < params.size(); ++i)
        if (!writeBack[i].empty()) outputs[i] = m_state.scopes.back().at(f.params[i].name);
    std::vector<std::pair<std::string, Variable>> externs;
    for (const std::string& name : m_externs.back().names) externs.emplace_back(name, m_state.scopes[1].at(name));
    m_externs.pop_back();
    m_state.scopes.pop_back();  // the parameters (no unused warnings for them)
    m_functions = functionsBefore;
    for (auto& scope : callerScopes) m_state.scopes.push_back(std::move(scope));

    for (size_t i = 0; i < params.size(); ++i) {
        if (writeBack[i].empty()) continue;
        Variable* target = Find(writeBack[i]);
        target->elements = outputs[i].elements;
        target->value = m_ops.Promote(outputs[i].value, target->type);
        target->assigned = true;
    }
    for (auto& [name, value] : externs) {
        Variable* target = Find(name);
        target->value = value.value;
        target->elements = value.elements;
        target->assigned = target->assigned || value.assigned;
        target->used = true;
    }

    if (context.returnType == Type::Void) return Value{Type::Void, {}};
    if (done.returned.type == Type::Void && (m_diags.errorCount() > errorsBefore || HasValueReturn(f.body)))
        return std::nullopt;  // its return statements had errors, reported
    if (done.returned.type == Type::Void) {
        m_diags.error(f.loc, "function '" + f.name + "' returns " + Article(context.returnType) +
                                 " but has no 'return' with a value");
        return std::nullopt;
    }
    return done.returned;
}

void Lowerer::DeclareExtern(const lang::VarDecl& d) {
    if (m_externs.empty()) {
        // In the shader body every variable of an enclosing scope is visible anyway.
        if (!Find(d.name)) {
            m_diags.error(d.loc, "extern variable '" + d.name + "' is not declared in an enclosing scope");
            DeclarePlaceholder(d, FromTypeName(d.type));
        }
        return;
    }
    if (m_state.scopes[0].count(d.name)) return;  // a global: visible in functions already
    ExternFrame& frame = m_externs.back();
    const Variable* outer = nullptr;
    for (auto scope = frame.callerScopes->rbegin(); scope != frame.callerScopes->rend() && !outer; ++scope) {
        auto it = scope->find(d.name);
        if (it != scope->end()) outer = &it->second;
    }
    if (!outer) {
        if (!m_checkingOnly)
            m_diags.error(d.loc, "extern variable '" + d.name + "' is not declared in an enclosing scope");
        DeclarePlaceholder(d, FromTypeName(d.type));
        return;
    }
    const Type type = FromTypeName(d.type);
    if (outer->type != type && !(IsSpatial(outer->type) && IsSpatial(type))) {
        m_diags.error(d.loc, "extern variable '" + d.name + "' is declared " + Article(type) + " here but is " +
                                 Article(outer->type));
        return;
    }
    Variable alias = *outer;
    alias.loc = d.loc;
    alias.used = true;
    // In the function's parameter scope, so that it outlives the block declaring it.
    m_state.scopes[1][d.name] = alias;
    frame.names.push_back(d.name);
}

Variable* Lowerer::ImplicitExtern(const std::string& name) {
    if (m_callStack.empty() || m_externs.size() != m_callStack.size()) return nullptr;
    return AliasOuter(m_externs.size() - 1, name, m_state.scopes[1]);
}

Variable* Lowerer::AliasOuter(size_t k, const std::string& name, Scope& params) {
    if (!m_nested.count(m_callStack[k])) return nullptr;
    ExternFrame& frame = m_externs[k];
    const Variable* outer = nullptr;
    for (auto scope = frame.callerScopes->rbegin(); scope != frame.callerScopes->rend() && !outer; ++scope) {
        auto it = scope->find(name);
        if (it != scope->end()) outer = &it->second;
    }
    // Not the caller's: a variable of the body both are nested in, when the caller is a nested
    // function called from it (a method calling a method of a shader class). The caller's own
    // parameter scope (the first of its scopes, put aside for this call) gets an alias first.
    if (!outer && k > 0 && !frame.callerScopes->empty()) outer = AliasOuter(k - 1, name, frame.callerScopes->front());
    if (!outer) return nullptr;
    Variable alias = *outer;
    alias.used = true;
    params[name] = alias;
    frame.names.push_back(name);
    return &params[name];
}

void Lowerer::CheckUncalledFunctions() {
    // A function nobody calls is still checked: lowered once as dead code, its parameters 0,
    // and an `extern` it names taken on trust (there is no caller to look in).
    for (size_t i = 0; i < m_defined.size(); ++i) {  // (checking may define nested functions)
        const lang::FunctionDef* f = m_defined[i];
        if (m_called.count(f)) continue;
        m_called.insert(f);
        FlowState before = m_state;
        const auto functionsBefore = m_functions;
        m_state.scopes.resize(1);
        m_state.alive = False();
        m_checkingOnly = true;
        m_externs.push_back({&before.scopes, {}});
        PushScope();
        AddSurfaceGlobals(m_state.scopes.back());
        for (const lang::VarDecl& p : f->params) {
            Variable param;
            param.type = FromTypeName(p.type);
            param.value = param.type == Type::String ? StringValue(UnknownString())
                                                     : m_ops.Promote(m_ops.Constant(0.0), param.type);
            param.assigned = param.used = true;
            param.arraySize = p.arraySize;
            param.elements.assign(static_cast<size_t>(std::max(p.arraySize, 1)), param.value);
            param.loc = p.loc;
            m_state.scopes.back()[p.name] = param;
        }
        FlowContext context;
        context.isLoop = false;
        context.left = context.skipped = False();
        context.returnType = FromTypeName(f->returnType);
        m_state.contexts.push_back(context);
        m_callStack.push_back(f);
        PushScope();
        for (const lang::StmtPtr& s : f->body) LowerStmt(*s);
        PopScope();
        m_callStack.pop_back();
        m_externs.pop_back();
        m_checkingOnly = false;
        m_functions = functionsBefore;
        m_state = std::move(before);
    }
}

std::optional<Value> Lowerer::Element(const Variable& array, const Value& index, lang::SourceLoc loc) {
    if (index.type != Type::Float && index.type != Type::Bool) {  // (a boolean is 1 or 0, as in C)
        m_diags.error(loc, "an array index must be a float, not " + Article(index.type));
        return std::nullopt;
    }
    const int n = static_cast<int>(array.elements.size());
    if (std::optional<double> k = ir().ConstValue(index.c[0])) {
        if (!(*k >= 0 && *k < n)) {
            m_diags.error(loc, "index " + std::to_string(static_cast<long long>(*k)) + " is outside the array (size " +
                                   std::to_string(n) + ")");
            return std::nullopt;
        }
        return array.elements[static_cast<size_t>(*k)];
    }
    // A varying index: select the element whose index it equals (indices are whole numbers;
    // the fraction is dropped as RenderMan does). Outside the array: NaN, i.e. Unbounded.
    const ValueId i = ir().Unary(IrOp::Floor, index.c[0], Line());
    const ValueId nan = ir().Const(std::numeric_limits<double>::quiet_NaN());
    Value out{array.type, {}};
    out.c.fill(nan);  // every component, a matrix's off-diagonal ones too
    for (int k = n - 1; k >= 0; --k) {
        const ValueId here = ir().Binary(IrOp::Eq, i, ir().Const(k), Line());
        for (int c = 0; c < out.size(); ++c) out.c[c] = ir().Select(here, array.elements[k].c[c], out.c[c], Line());
    }
    if (out.size() == 1) out.c[1] = out.c[2] = out.c[0];
    return out;
}

void Lowerer::StoreElement(Variable& array, const Value& index, const Value& value) {
    if (std::optional<double> k = ir().ConstValue(index.c[0])) {
        Value& e = array.elements[static_cast<size_t>(*k)];  // Element() checked the range
        e = Guard(value, e);
        return;
    }
    const ValueId i = ir().Unary(IrOp::Floor, index.c[0], Line());
    for (size_t k = 0; k < array.elements.size(); ++k) {
        const ValueId here = ir().Binary(IrOp::Eq, i, ir().Const(static_cast<double>(k)), Line());
        Value& e = array.elements[k];
        Value updated = e;
        for (int c = 0; c < e.size(); ++c) updated.c[c] = ir().Select(here, value.c[c], e.c[c], Line());
        if (e.size() == 1) updated.c[1] = updated.c[2] = updated.c[0];
        e = Guard(updated, e);
    }
}

std::optional<Value> Lowerer::LowerIndex(const Expr& e) {
    const Expr& target = *e.args[0];
    std::optional<Value> index = LowerExpr(*e.args[1]);
    Variable* var = target.kind == ExprKind::Ident ? FindOrExtern(target.name) : nullptr;
    if (!var || var->arraySize < 0) {
        m_diags.error(target.loc, target.kind == ExprKind::Ident && !var ? "unknown identifier '" + target.name + "'"
                                                                         : "only an array can be indexed");
        return std::nullopt;
    }
    var->used = true;
    if (!index) return std::nullopt;
    return Element(*var, *index, e.args[1]->loc);
}

void Lowerer::LowerArrayDecl(const lang::VarDecl& d) {
    const Type type = FromTypeName(d.type);
    Variable var;
    var.type = type;
    var.loc = d.loc;
    var.arraySize = d.arraySize;
    var.assigned = true;
    const Value zero = m_ops.Promote(m_ops.Constant(0.0), type);
    var.elements.assign(static_cast<size_t>(std::max(d.arraySize, 0)), zero);
    if (d.arraySize == 0) m_diags.error(d.loc, "array '" + d.name + "' needs a size");
    if (!IsNumeric(type)) m_diags.error(d.loc, std::string(ToString(type)) + " arrays are not supported yet");
    for (size_t i = 0; i < d.initList.size() && i < var.elements.size(); ++i) {
        std::optional<Value> v = LowerExpr(*d.initList[i]);
        if (!v) continue;
        if (v->type == Type::Bool) v->type = Type::Float;
        std::optional<Value> converted = Convert(*v, type, d.initList[i]->loc, "an element of array '" + d.name + "'");
        if (converted) var.elements[i] = *converted;
    }
    m_state.scopes.back().emplace(d.name, var);
}

}  // namespace affray::compiler
