// compiler/value_ops.h: typed values during lowering, and the arithmetic on them.
// A Value is a float (one IR node), a triple (three) or a matrix (sixteen). Every operator and
// built-in lowers through these helpers, so promotion (float -> triple, float -> matrix) and the
// scalar expansion of dot, cross, length, normalize and the matrix algebra are written once
// (the matrix part in value_matrix.cpp).
#pragma once

#include <array>

#include "compiler/ir.h"
#include "compiler/types.h"

namespace affray::compiler {

struct Value {
    Type type = Type::Void;
    /// A float is c[0] (repeated in c[1] and c[2]); a triple c[0..2]; a matrix c[0..15], row by
    /// row in RenderMan's convention: points are row vectors, p' = p * M, so the translation is
    /// c[12..14] (RI Spec 3.2, section 11.4).
    std::array<ValueId, 16> c{};

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
    /// A float promoted to a triple of `type` (all three components equal) or to a matrix (x
    /// times the identity, RenderMan's rule); triples retyped.
    Value Promote(const Value& v, Type type) const;

    // Componentwise arithmetic; a float operand is promoted when the other is a triple. The
    // result type is the triple operand's (the left one's if both are triples). Mul and Div of
    // matrices are the matrix product and the product by the inverse (`1/m` inverts m).
    Value Add(const Value& a, const Value& b) { return Componentwise(IrOp::Add, a, b); }
    Value Sub(const Value& a, const Value& b) { return Componentwise(IrOp::Sub, a, b); }
    Value Mul(const Value& a, const Value& b);
    Value Div(const Value& a, const Value& b);
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
    /// Every component of a equal to b's (a Bool); a float is promoted to the other's type.
    ValueId AllEqual(const Value& a, const Value& b);

    Value Dot(const Value& a, const Value& b);
    Value Cross(const Value& a, const Value& b);
    Value Length(const Value& a);
    Value Normalize(const Value& a);
    Value Distance(const Value& a, const Value& b) { return Length(Sub(a, b)); }
    Value Component(const Value& a, int i) const { return Float(a.c[i]); }

    // Matrices (value_matrix.cpp). A product or inverse whose entries are constants folds.
    Value MatrixProduct(const Value& a, const Value& b);
    ValueId Determinant(const Value& m);
    /// The inverse by cofactors over the determinant: a singular matrix gives inf or NaN
    /// entries (Unbounded in a bound), never a wrong finite value.
    Value Inverse(const Value& m);
    /// x transformed by the matrix m as `kind` (a point: p * m with the homogeneous divide; a
    /// vector: by m's upper 3x3; a normal: by the inverse transpose of that).
    Value TransformBy(const Value& m, const Value& x, Type kind);
    /// The matrix of a constant transform given column-vector style (compiler/spaces.h).
    Value MatrixConstant(const std::array<double, 16>& columnStyle);
    /// translate(m, t), rotate(m, angle, axis) and scale(m, s): the transform applied first,
    /// then m (as RiTranslate etc. concatenate onto the current transformation); angle in radians.
    Value Translate(const Value& m, const Value& t);
    Value Rotate(const Value& m, const Value& angle, const Value& axis);
    Value Scale(const Value& m, const Value& s);

  private:
    Value Componentwise(IrOp op, const Value& a, const Value& b);
    ValueId Scalar(IrOp op, ValueId a, ValueId b) { return m_ir.Binary(op, a, b, m_line); }
    ValueId Scalar(IrOp op, ValueId a) { return m_ir.Unary(op, a, m_line); }
    /// The 2x2 determinant |a b; c d|.
    ValueId Minor2(ValueId a, ValueId b, ValueId c, ValueId d);

    IrBuilder& m_ir;
    int m_line = 0;
};

}  // namespace affray::compiler
