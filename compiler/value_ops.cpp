// compiler/value_ops.cpp: scalar expansion of triple arithmetic.
#include "compiler/value_ops.h"

#include <algorithm>

namespace affray::compiler {

Value ValueOps::Promote(const Value& v, Type type) const {
    if (v.type == Type::Float && IsTriple(type)) return {type, {v.c[0], v.c[0], v.c[0]}};
    if (v.type == Type::Float && type == Type::Matrix) {
        Value r{Type::Matrix, {}};
        const ValueId zero = m_ir.Const(0.0);
        for (int i = 0; i < 16; ++i) r.c[i] = i % 5 == 0 ? v.c[0] : zero;  // the diagonal: 0, 5, 10, 15
        return r;
    }
    Value r = v;
    r.type = type;
    return r;
}

Value ValueOps::Componentwise(IrOp op, const Value& a, const Value& b) {
    if (a.type == Type::Float && b.type == Type::Float) return Float(Scalar(op, a.c[0], b.c[0]));
    Type type = IsTriple(a.type) ? a.type : b.type;
    Value x = Promote(a, type), y = Promote(b, type);
    return {type, {Scalar(op, x.c[0], y.c[0]), Scalar(op, x.c[1], y.c[1]), Scalar(op, x.c[2], y.c[2])}};
}

Value ValueOps::Mul(const Value& a, const Value& b) {
    if (a.type == Type::Matrix || b.type == Type::Matrix)
        return MatrixProduct(Promote(a, Type::Matrix), Promote(b, Type::Matrix));
    return Componentwise(IrOp::Mul, a, b);
}

Value ValueOps::Div(const Value& a, const Value& b) {
    if (a.type == Type::Matrix && b.type == Type::Float) {
        // m / x divides every entry: the inverse of x times the identity, without its rounding.
        Value r = a;
        for (ValueId& e : r.c) e = Scalar(IrOp::Div, e, b.c[0]);
        return r;
    }
    if (a.type == Type::Matrix || b.type == Type::Matrix) return MatrixProduct(Promote(a, Type::Matrix), Inverse(b));
    return Componentwise(IrOp::Div, a, b);
}

Value ValueOps::Map(IrOp op, const Value& a) {
    if (a.type == Type::Float) return Float(Scalar(op, a.c[0]));
    return {a.type, {Scalar(op, a.c[0]), Scalar(op, a.c[1]), Scalar(op, a.c[2])}};
}

Value ValueOps::SelectValue(const Value& c, const Value& a, const Value& b) {
    Type type = a.type == Type::Float ? b.type : a.type;
    Value x = Promote(a, type), y = Promote(b, type);
    Value out{type, {}};
    const int n = std::max(3, ScalarCount(type));  // a float's copies in c[1], c[2] too
    for (int i = 0; i < n; ++i) out.c[i] = m_ir.Select(c.c[0], x.c[i], y.c[i], m_line);
    return out;
}

ValueId ValueOps::AllEqual(const Value& a, const Value& b) {
    const Type type = a.type == Type::Float ? b.type : a.type;
    const Value x = Promote(a, type), y = Promote(b, type);
    ValueId all = Scalar(IrOp::Eq, x.c[0], y.c[0]);
    for (int i = 1; i < ScalarCount(type); ++i) all = Scalar(IrOp::And, all, Scalar(IrOp::Eq, x.c[i], y.c[i]));
    return all;
}

Value ValueOps::Dot(const Value& a, const Value& b) {
    ValueId xy = Scalar(IrOp::Add, Scalar(IrOp::Mul, a.c[0], b.c[0]), Scalar(IrOp::Mul, a.c[1], b.c[1]));
    return Float(Scalar(IrOp::Add, xy, Scalar(IrOp::Mul, a.c[2], b.c[2])));
}

Value ValueOps::Cross(const Value& a, const Value& b) {
    auto term = [&](int i, int j) {
        return Scalar(IrOp::Sub, Scalar(IrOp::Mul, a.c[i], b.c[j]), Scalar(IrOp::Mul, a.c[j], b.c[i]));
    };
    return {Type::Vector, {term(1, 2), term(2, 0), term(0, 1)}};
}

Value ValueOps::Length(const Value& a) {
    // sqr, not x*x: the same node squared keeps affine bounds non-negative and tight.
    Value squares = Map(IrOp::Sqr, a);
    ValueId sum = Scalar(IrOp::Add, Scalar(IrOp::Add, squares.c[0], squares.c[1]), squares.c[2]);
    return Float(Scalar(IrOp::Sqrt, sum));
}

Value ValueOps::Normalize(const Value& a) {
    // a*(1/|a|) componentwise, kept finite (issue 12): where |a| is not > 0 (the zero vector, or
    // NaN) the zero vector, as OSL; and each component clamped to [-1, 1], where it lies but for
    // rounding (fmin/fmax: a NaN component gives -1). 1/|a| is finite wherever |a| > 0 (|a| is at
    // least the square root of the least subnormal), and a clamped component lies in [-1, 1]
    // whatever the bound of a, so a vector renormalised again and again stays bounded.
    const ValueId length = Length(a).c[0];
    const Value positive = Float(Scalar(IrOp::Lt, m_ir.Const(0.0), length));
    const Value inverse = SelectValue(positive, Float(Scalar(IrOp::Div, m_ir.Const(1.0), length)), Constant(0.0));
    return Clamp(Mul(a, inverse), Constant(-1.0), Constant(1.0));
}

}  // namespace affray::compiler
