// compiler/lower_logic.cpp: comparisons, && || !, conditions and ?: (the values control flow
// selects on). A comparison is a Bool: 1 or 0 in the VM, an undecided [0, 1] in a bound type.
// Their operands are checked by the type rules (compiler/typecheck.h) before they get here.
#include "compiler/lowerer.h"

namespace affray::compiler {

using lang::Expr;

std::optional<Value> Lowerer::LowerComparison(const Expr& e, const Value& a, const Value& b) {
    using lang::BinaryOp;
    const BinaryOp op = e.binaryOp;
    auto boolean = [&](ValueId v) { return Value{Type::Bool, {v, v, v}}; };
    if (op == BinaryOp::And || op == BinaryOp::Or) {
        // A float operand means "!= 0".
        auto truth = [&](const Value& v) {
            return v.type == Type::Bool ? v.c[0] : ir().Binary(IrOp::Ne, v.c[0], ir().Const(0.0), e.loc.line);
        };
        return boolean(ir().Binary(op == BinaryOp::And ? IrOp::And : IrOp::Or, truth(a), truth(b), e.loc.line));
    }
    // Strings compare by their ids (one id per distinct text): folded when both are known, a
    // comparison of ids when a string was chosen by a condition.
    if (a.type == Type::String) {
        const ValueId same = ir().Binary(IrOp::Eq, a.c[0], b.c[0], e.loc.line);
        return boolean(op == BinaryOp::Equal ? same : ir().Unary(IrOp::Not, same, e.loc.line));
    }
    Value x = a, y = b;
    for (Value* v : {&x, &y})
        if (v->type == Type::Bool) v->type = Type::Float;
    if (op == BinaryOp::Equal || op == BinaryOp::NotEqual) {
        // Triples and matrices are equal when every component is.
        m_ops.SetLine(e.loc.line);
        const ValueId all = m_ops.AllEqual(x, y);
        return boolean(op == BinaryOp::Equal ? all : ir().Unary(IrOp::Not, all, e.loc.line));
    }
    // a > b is b < a, a >= b is b <= a.
    const bool swap = op == BinaryOp::Greater || op == BinaryOp::GreaterEq;
    const IrOp irOp = op == BinaryOp::Less || op == BinaryOp::Greater ? IrOp::Lt : IrOp::Le;
    return boolean(swap ? ir().Binary(irOp, y.c[0], x.c[0], e.loc.line)
                        : ir().Binary(irOp, x.c[0], y.c[0], e.loc.line));
}

std::optional<ValueId> Lowerer::LowerCondition(const Expr& e) {
    std::optional<Value> v = LowerExpr(e);
    if (!v) return std::nullopt;
    if (const Typed typed = ConditionType(v->type); !typed.ok()) {
        m_diags.error(e.loc, typed.error);
        return std::nullopt;
    }
    if (v->type == Type::Bool) return v->c[0];
    // A float condition means "!= 0" (C's rule; some RenderMan compilers accept it too).
    if (v->type == Type::Float) return ir().Binary(IrOp::Ne, v->c[0], ir().Const(0.0), e.loc.line);
    return std::nullopt;  // not reached: ConditionType accepts only these two
}

std::optional<Value> Lowerer::LowerTernary(const Expr& e) {
    std::optional<ValueId> c = LowerCondition(*e.args[0]);
    // The arm a constant condition rules out is lowered as dead code (alive 0), as an if's is:
    // `map != "" ? texture(map, s, t) : 0` calls nothing with the default "".
    const std::optional<double> k = c ? ir().ConstValue(*c) : std::nullopt;
    auto arm = [&](const Expr& x, bool dead) {
        const ValueId alive = m_state.alive;
        if (dead) m_state.alive = False();
        std::optional<Value> v = LowerExpr(x);
        m_state.alive = alive;
        return v;
    };
    std::optional<Value> a = arm(*e.args[1], k && *k == 0.0);
    std::optional<Value> b = arm(*e.args[2], k && *k != 0.0);
    if (!c || !a || !b) return std::nullopt;
    if (const Typed typed = TernaryType(a->type, b->type); !typed.ok()) {
        m_diags.error(e.loc, typed.error);
        return std::nullopt;
    }
    Value x = *a, y = *b;
    if (x.type == Type::Bool && y.type == Type::Bool) {
        ValueId v = ir().Select(*c, x.c[0], y.c[0], e.loc.line);
        return Value{Type::Bool, {v, v, v}};
    }
    for (Value* v : {&x, &y})
        if (v->type == Type::Bool) v->type = Type::Float;
    if (x.type == Type::String && y.type == Type::String) {
        ValueId id = ir().Select(*c, x.c[0], y.c[0], e.loc.line);
        return Value{Type::String, {id, id, id}};
    }
    m_ops.SetLine(e.loc.line);
    return m_ops.SelectValue(m_ops.Float(*c), x, y);
}

}  // namespace affray::compiler
