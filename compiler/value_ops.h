// compiler/value_ops.h: typed values during lowering, and the triple-aware arithmetic on them.
// A Value is a float (one IR node) or a triple (three). Every operator and built-in lowers
// through these helpers, so promotion (float -> triple) and the scalar expansion of dot, cross,
// length and normalize are written once.
#pragma once

#include <array>

#include "compiler/ir.h"
#include "compiler/types.h"

namespace affray::compiler {

struct Value {
    Type type = Type::Void;
    std::array<ValueId, 3> c{};  // c[0] only for floats

    /// IR values it holds: a string is one (its id, see Lowerer::StringValue).
    int size() const { return type == Type::String ? 1 : ScalarCount(type); }
};

class ValueOps {
  public:
    explicit ValueOps(IrBuilder& ir) : m_ir(ir) {}

    /// Source line recorded on the nodes created from now on.
    void SetLine(int line) { m_line = line; }
    IrBuilder& ir() { return m_ir; }

    Value Float(ValueId v) const { return {Type::Float, {v, v, v}}; }
    Value Constant(double k) { return Float(m_ir.Const(k)); }
    Value Triple(Type type, ValueId x, ValueId y, ValueId z) const { return {type, {x, y, z}}; }
    /// A float promoted to a triple of `type` (all three components equal); triples retyped.
    Value Promote(const Value& v, Type type) const;

    // Componentwise arithmetic; a float operand is promoted when the other is a triple. The
    // result type is the triple operand's (the left one's if both are triples).
    Value Add(const Value& a, const Value& b) { return Componentwise(IrOp::Add, a, b); }
    Value Sub(const Value& a, const Value& b) { return Componentwise(IrOp::Sub, a, b); }
    Value Mul(const Value& a, const Value& b) { return Componentwise(IrOp::Mul, a, b); }
    Value Div(const Value& a, const Value& b) { return Componentwise(IrOp::Div, a, b); }
    Value Neg(const Value& a) { return Map(IrOp::Neg, a); }
    /// Applies a unary scalar operation to each component.
    Value Map(IrOp op, const Value& a);
    Value Pow(const Value& a, const Value& b) { return Componentwise(IrOp::Pow, a, b); }
    /// Any binary scalar operation, componentwise (min, max, atan2, comparisons...).
    Value Binary(IrOp op, const Value& a, const Value& b) { return Componentwise(op, a, b); }
    /// min(max(x, lo), hi), componentwise.
    Value Clamp(const Value& x, const Value& lo, const Value& hi) {
        return Binary(IrOp::Min, Binary(IrOp::Max, x, lo), hi);
    }
    /// c ? a : b for a float condition c (1 or 0), componentwise.
    Value SelectValue(const Value& c, const Value& a, const Value& b);

    Value Dot(const Value& a, const Value& b);
    Value Cross(const Value& a, const Value& b);
    Value Length(const Value& a);
    Value Normalize(const Value& a);
    Value Distance(const Value& a, const Value& b) { return Length(Sub(a, b)); }
    Value Component(const Value& a, int i) const { return Float(a.c[i]); }

  private:
    Value Componentwise(IrOp op, const Value& a, const Value& b);
    ValueId Scalar(IrOp op, ValueId a, ValueId b) { return m_ir.Binary(op, a, b, m_line); }
    ValueId Scalar(IrOp op, ValueId a) { return m_ir.Unary(op, a, m_line); }

    IrBuilder& m_ir;
    int m_line = 0;
};

}  // namespace affray::compiler
