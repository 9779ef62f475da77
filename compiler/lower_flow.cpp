// compiler/lower_flow.cpp: statements, and control flow turned into data flow (see lowerer.h).
#include <cmath>
#include <functional>
#include <limits>
#include <unordered_set>

#include "compiler/lowerer.h"

namespace affray::compiler {

using lang::Stmt;
using lang::StmtKind;

Value Lowerer::Guard(const Value& value, const Value& old) {
    const ValueId alive = m_state.alive;
    if (ir().ConstValue(alive) == 1.0 || old.type == Type::Void) return value;
    return m_ops.SelectValue(m_ops.Float(alive), value, old);
}

void Lowerer::Store(Variable& var, const Value& value) {
    var.value = var.assigned ? Guard(value, var.value) : value;
    var.assigned = true;
}

ValueId Lowerer::AliveExcludingLeft(ValueId base, size_t firstContext) {
    ValueId alive = base;
    for (size_t k = firstContext; k < m_state.contexts.size(); ++k) {
        const FlowContext& c = m_state.contexts[k];
        ValueId gone = ir().Binary(IrOp::Or, c.left, c.skipped, Line());
        alive = ir().Binary(IrOp::And, alive, ir().Unary(IrOp::Not, gone, Line()), Line());
    }
    return alive;
}

ValueId Lowerer::AssumingAlive(ValueId v) {
    // The conditions `alive` implies: itself and, through And, its operands.
    std::unordered_set<ValueId> implied;
    std::vector<ValueId> stack{m_state.alive};
    while (!stack.empty()) {
        ValueId c = stack.back();
        stack.pop_back();
        if (!implied.insert(c).second) continue;
        const IrNode& n = ir().node(c);
        if (n.op == IrOp::And) stack.insert(stack.end(), {n.in[0], n.in[1]});
    }
    // Rewrite v with every implied condition replaced by 1 (the builder may have folded a
    // guarded `alive ? 1 : 0` into alive itself) and every Select on one by its first arm.
    std::unordered_map<ValueId, ValueId> memo;
    constexpr int kMaxDepth = 4000;
    std::function<ValueId(ValueId, int)> rewrite = [&](ValueId x, int depth) -> ValueId {
        const IrNode n = ir().node(x);  // a copy: rewriting creates nodes, which may move the table
        if (n.count == 0 || depth > kMaxDepth) return x;
        if (auto it = memo.find(x); it != memo.end()) return it->second;
        ValueId result;
        if (implied.count(x)) {
            result = True();
        } else if (n.op == IrOp::Select && implied.count(n.in[0])) {
            result = rewrite(n.in[1], depth + 1);
        } else {
            IrNode copy = n;
            bool changed = false;
            for (int i = 0; i < n.count; ++i) {
                copy.in[i] = rewrite(n.in[i], depth + 1);
                changed = changed || copy.in[i] != n.in[i];
            }
            result = changed ? ir().Create(copy) : x;
        }
        memo[x] = result;
        return result;
    };
    return rewrite(v, 0);
}

void Lowerer::Merge(ValueId cond, const FlowState& thenState) {
    auto select = [&](const Value& t, const Value& e) { return m_ops.SelectValue(m_ops.Float(cond), t, e); };
    for (size_t s = 0; s < m_state.scopes.size(); ++s) {
        for (auto& [name, var] : m_state.scopes[s]) {
            const Variable& t = thenState.scopes[s].at(name);
            var.used = var.used || t.used;
            if (!t.assigned) continue;
            if (!var.assigned) {
                var = t;  // assigned on the then path only: its value there is the only one
                continue;
            }
            if (t.value.c != var.value.c) var.value = select(t.value, var.value);
            for (size_t i = 0; i < var.elements.size(); ++i)
                if (t.elements[i].c != var.elements[i].c) var.elements[i] = select(t.elements[i], var.elements[i]);
        }
    }
    m_state.alive = ir().Select(cond, thenState.alive, m_state.alive, Line());
    for (size_t k = 0; k < m_state.contexts.size(); ++k) {
        FlowContext& e = m_state.contexts[k];
        const FlowContext& t = thenState.contexts[k];
        e.left = ir().Select(cond, t.left, e.left, Line());
        e.skipped = ir().Select(cond, t.skipped, e.skipped, Line());
        // A value returned on one arm only is the value on the paths that returned; the other
        // paths have not returned yet, and a later return overwrites it there (Guard).
        if (e.returned.type == Type::Void)
            e.returned = t.returned;
        else if (t.returned.type != Type::Void && t.returned.c != e.returned.c)
            e.returned = select(t.returned, e.returned);
    }
}

bool Lowerer::DependsOnParameter(ValueId v) const {
    std::unordered_set<ValueId> seen;
    std::vector<ValueId> stack{v};
    while (!stack.empty()) {
        const ValueId x = stack.back();
        stack.pop_back();
        if (!seen.insert(x).second) continue;
        const IrNode& n = m_out.ir.node(x);
        if (n.op == IrOp::Param) return true;
        for (int i = 0; i < n.count; ++i) stack.push_back(n.in[i]);
    }
    return false;
}

void Lowerer::KeepUsedFlags(FlowState& into) const {
    for (size_t sc = 0; sc < into.scopes.size() && sc < m_state.scopes.size(); ++sc)
        for (auto& [name, var] : into.scopes[sc]) {
            auto it = m_state.scopes[sc].find(name);
            if (it != m_state.scopes[sc].end()) var.used = var.used || it->second.used;
        }
}

void Lowerer::LowerIf(const Stmt& s) {
    if (IsSurface() && s.expr && s.expr->kind == lang::ExprKind::Call && s.expr->name == "illuminance")
        return LowerIlluminance(s);
    if (IsLight() && s.expr && s.expr->kind == lang::ExprKind::Call &&
        (s.expr->name == "illuminate" || s.expr->name == "solar"))
        return LowerIlluminate(s);
    std::optional<ValueId> cond = LowerCondition(*s.expr);
    const ValueId c = cond.value_or(True());  // after an error, both arms still get checked
    LowerBranches(c, *s.body[0], s.body.size() > 1 ? s.body[1].get() : nullptr);
}

void Lowerer::LowerBranches(ValueId c, const Stmt& thenStmt, const Stmt* elseStmt) {
    const std::optional<double> k = ir().ConstValue(c);
    FlowState before = m_state;

    // An arm a constant condition rules out is still checked, but lowered as dead code (alive
    // 0), so its assignments fold away and its loops do not unroll.
    if (k && *k == 0.0) m_state.alive = False();
    PushScope();
    LowerStmt(thenStmt);
    PopScope();
    FlowState thenState = std::move(m_state);

    m_state = std::move(before);
    if (k && *k != 0.0) m_state.alive = False();
    if (elseStmt) {
        PushScope();
        LowerStmt(*elseStmt);
        PopScope();
    }
    if (k) {
        // A constant condition: the live arm's state is the result; the dead arm only adds the
        // variables it read (for the unused-variable warnings).
        if (*k == 0.0) std::swap(m_state, thenState);  // now thenState is the live arm's
        KeepUsedFlags(thenState);                      // ...plus what the dead arm used
        m_state = std::move(thenState);
        return;
    }
    Merge(c, thenState);
}

void Lowerer::LowerLoop(const Stmt& s) {
    const bool isFor = s.kind == StmtKind::For;
    PushScope();
    if (isFor && s.init) LowerExpr(*s.init);
    const ValueId aliveBefore = m_state.alive;
    const FlowState entry = m_state;
    const size_t contextIndex = m_state.contexts.size();
    m_state.contexts.push_back({true, false, False(), False(), {}, Type::Void});

    // The body checked as dead code (alive 0: nothing unrolls, nothing is kept), so that its
    // mistakes are reported before, not after, an unrolling that may be long or endless.
    auto checkBody = [&] {
        FlowState before = m_state;
        m_state.alive = False();
        PushScope();
        LowerStmt(*s.body[0]);
        PopScope();
        if (isFor && s.step) LowerExpr(*s.step);
        KeepUsedFlags(before);
        m_state = std::move(before);
    };
    bool checked = false, wrong = false;
    if (s.body[0] && m_checkedLoops.insert(&s).second) {
        const int errorsBefore = m_diags.errorCount(), requestsBefore = ir().requestedOps();
        checkBody();
        ir().ForgetRequestsSince(requestsBefore);  // nothing of the check is kept
        checked = true;
        wrong = m_diags.errorCount() > errorsBefore;  // then the loop is not unrolled
    }
    bool varying = false, ranBody = false;
    // A loop that ran past its budget once (reported) is not unrolled again, as it would be for
    // every iteration of the loops around it: that multiplied the budget by theirs.
    const bool ranOut = m_endlessLoops.count(&s) > 0;
    for (int iteration = 0; !wrong; ++iteration) {
        std::optional<ValueId> cond = s.expr ? LowerCondition(*s.expr) : std::optional<ValueId>(True());
        if (!cond) break;  // reported
        // The condition matters only where the loop is still alive, so it is simplified under
        // that assumption: a counter that a break left behind on other paths is still the
        // constant it is on this one, and the unrolling ends exactly.
        const ValueId assumed = AssumingAlive(*cond);
        const ValueId run = ir().Binary(IrOp::And, m_state.alive, assumed, Line());
        if (ir().ConstValue(run) == 0.0) break;
        // The iteration count is known at compile time while the condition is a constant on
        // the paths still running (a break on some paths does not make it unknown), unless the
        // condition is a constant by itself (`while (1)`): then only breaks end the loop, and
        // whether they do varies if `run` does.
        const bool endsOnlyByBreaking = ir().ConstValue(*cond) == 1.0 && !ir().ConstValue(run);
        varying = varying || !ir().ConstValue(assumed) || endsOnlyByBreaking;
        const int budget = varying ? m_varyingLoopBudget : m_constantLoopBudget;
        if (iteration >= budget || ranOut || TooLarge(s.loc)) {
            if (m_reportedSize) {
                // reported by TooLarge
            } else if (!varying || ranOut) {
                if (m_endlessLoops.insert(&s).second)
                    m_diags.error(s.loc, "this loop runs more than " + std::to_string(m_constantLoopBudget) +
                                             " iterations: affray unrolls loops; is its condition ever false? " +
                                             diag::LimitNote(diag::Limit::LoopIterations));
            } else {
                // The paths still running past the budget get NaN: Unbounded in every bound type,
                // never a value the loop would not have computed.
                // A loop that varies only because a parameter bounds it (a generic program)
                // gets a NaN the specialiser recognises (kParameterLoopPoison).
                const ValueId nan = ir().Const(DependsOnParameter(assumed) ? kParameterLoopPoison
                                                                           : std::numeric_limits<double>::quiet_NaN());
                m_state.alive = run;
                for (size_t sc = 0; sc < entry.scopes.size(); ++sc)
                    for (auto& [name, var] : m_state.scopes[sc]) {
                        auto before = entry.scopes[sc].find(name);
                        if (before == entry.scopes[sc].end() || var.type == Type::String) continue;
                        const Value poison = m_ops.Promote(m_ops.Float(nan), var.type);
                        for (size_t i = 0; i < var.elements.size(); ++i)
                            if (before->second.elements[i].c != var.elements[i].c)
                                var.elements[i] = Guard(poison, var.elements[i]);
                        if (before->second.value.c != var.value.c) var.value = Guard(poison, var.value);
                    }
            }
            break;
        }
        m_state.alive = run;
        ranBody = true;
        PushScope();
        m_unrolling.push_back(s.loc);
        LowerStmt(*s.body[0]);
        m_unrolling.pop_back();
        PopScope();
        // Paths that continued run the step; paths that left (break, return, an outer jump) do not.
        FlowContext& loop = m_state.contexts[contextIndex];
        loop.skipped = False();
        m_state.alive = AliveExcludingLeft(run, 0);
        if (isFor && s.step) LowerExpr(*s.step);
    }
    // The body never runs here, but its mistakes are still mistakes: check it as dead code.
    if (!ranBody && !checked && s.body[0]) checkBody();
    m_state.contexts.pop_back();
    // Every path that entered goes on after the loop, except those that left an enclosing loop
    // or function from inside it.
    m_state.alive = AliveExcludingLeft(aliveBefore, 0);
    PopScope();
}

void Lowerer::LowerJump(const Stmt& s) {
    const ValueId alive = m_state.alive;
    auto leave = [&](FlowContext& c) { c.left = ir().Binary(IrOp::Or, c.left, alive, Line()); };
    if (s.kind == StmtKind::Return) {
        size_t k = m_state.contexts.size();
        while (k > 0 && m_state.contexts[k - 1].isLoop) --k;
        const size_t functionIndex = k - 1;  // the shader body is a function too
        // (An index, not a reference: lowering the value may inline calls, which push contexts.)
        const FlowContext& function = m_state.contexts[functionIndex];
        const Type returnType = function.returnType;
        const bool isShader = function.isShader;
        if (s.expr) {
            std::optional<Value> v = LowerExpecting(*s.expr, returnType);
            if (returnType == Type::Void) {
                m_diags.error(
                    s.loc, isShader ? "a shader does not return a value" : "a void function does not return a value");
            } else if (v) {
                std::optional<Value> converted = Convert(*v, returnType, s.expr->loc, "the return value");
                Value& returned = m_state.contexts[functionIndex].returned;
                if (converted) returned = returned.type == Type::Void ? *converted : Guard(*converted, returned);
            }
        } else if (returnType != Type::Void) {
            m_diags.error(s.loc, "'return' needs a value in a function returning " + std::string(ToString(returnType)));
        }
        for (size_t i = functionIndex; i < m_state.contexts.size(); ++i) leave(m_state.contexts[i]);
        m_state.alive = False();
        return;
    }
    const bool isBreak = s.kind == StmtKind::Break;
    const char* word = isBreak ? "break" : "continue";
    int loops = 0;
    size_t k = m_state.contexts.size();
    while (k > 0 && m_state.contexts[k - 1].isLoop && loops < s.level) {
        --k;
        ++loops;
    }
    if (s.level < 1 || loops < s.level) {
        m_diags.error(s.loc, loops == 0
                                 ? "'" + std::string(word) + "' outside of a loop"
                                 : "'" + std::string(word) + " " + std::to_string(s.level) + "' is inside only " +
                                       std::to_string(loops) + (loops == 1 ? " loop" : " loops"));
        return;
    }
    // The loops passed through are left; the target loop is left (break) or skips to its next
    // iteration (continue).
    for (size_t i = k + 1; i < m_state.contexts.size(); ++i) leave(m_state.contexts[i]);
    FlowContext& target = m_state.contexts[k];
    if (isBreak)
        leave(target);
    else
        target.skipped = ir().Binary(IrOp::Or, target.skipped, alive, Line());
    m_state.alive = False();
}

void Lowerer::LowerStmt(const Stmt& s) {
    if (TooLarge(s.loc)) return;
    m_line = s.loc.line;
    m_ops.SetLine(m_line);
    switch (s.kind) {
        case StmtKind::Expr: LowerExpr(*s.expr); break;
        case StmtKind::FunctionDef: DefineFunction(*s.function); break;
        case StmtKind::Decl:
            for (const lang::VarDecl& d : s.decls) {
                if (d.isExtern) {
                    DeclareExtern(d);
                    continue;
                }
                if (d.arraySize >= 0) {
                    LowerArrayDecl(d);
                    continue;
                }
                std::optional<Value> init = d.init ? LowerExpecting(*d.init, FromTypeName(d.type)) : std::nullopt;
                if (d.init && !init) {
                    DeclarePlaceholder(d, FromTypeName(d.type));  // the initialiser's error is reported
                    continue;
                }
                LowerDecl(d, init);
            }
            break;
        case StmtKind::Block:
            PushScope();
            for (const lang::StmtPtr& child : s.body) LowerStmt(*child);
            PopScope();
            break;
        case StmtKind::Empty: break;
        case StmtKind::If: LowerIf(s); break;
        case StmtKind::For:
        case StmtKind::While: LowerLoop(s); break;
        case StmtKind::Return:
        case StmtKind::Break:
        case StmtKind::Continue: LowerJump(s); break;
    }
}

}  // namespace affray::compiler
