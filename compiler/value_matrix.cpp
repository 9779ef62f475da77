// compiler/value_matrix.cpp: the matrix algebra of the shading language, expanded into scalar IR.
// A matrix is sixteen IR values in RenderMan's row-vector convention (value_ops.h), so every
// number type bounds it entry by entry with no matrix type in the VM, and the entries the scene
// fixes fold: an identity space leaves no instruction behind, `x * 0` disappears.
#include <cmath>

#include "compiler/value_ops.h"

namespace affray::compiler {

namespace {
// Entry (row, column) of a matrix value.
ValueId At(const Value& m, int row, int column) { return m.c[4 * row + column]; }
}  // namespace

Value ValueOps::MatrixConstant(const std::array<double, 16>& columnStyle) {
    // Column-vector style M acts as p' = M p; the row-vector matrix with the same action is Mᵀ.
    Value r{Type::Matrix, {}};
    for (int row = 0; row < 4; ++row)
        for (int column = 0; column < 4; ++column) r.c[4 * row + column] = m_ir.Const(columnStyle[4 * column + row]);
    return r;
}

Value ValueOps::MatrixProduct(const Value& a, const Value& b) {
    Value r{Type::Matrix, {}};
    for (int row = 0; row < 4; ++row)
        for (int column = 0; column < 4; ++column) {
            ValueId sum = Scalar(IrOp::Mul, At(a, row, 0), At(b, 0, column));
            for (int k = 1; k < 4; ++k)
                sum = Scalar(IrOp::Add, sum, Scalar(IrOp::Mul, At(a, row, k), At(b, k, column)));
            r.c[4 * row + column] = sum;
        }
    return r;
}

ValueId ValueOps::Minor2(ValueId a, ValueId b, ValueId c, ValueId d) {
    return Scalar(IrOp::Sub, Scalar(IrOp::Mul, a, d), Scalar(IrOp::Mul, b, c));
}

ValueId ValueOps::Determinant(const Value& m) {
    // Laplace expansion along rows 0-1: each 2x2 minor of those rows times the complementary
    // minor of rows 2-3. Column pairs (0,1) (0,2) (0,3) (1,2) (1,3) (2,3) of rows 0-1 (s) and rows 2-3 (c); a pair's
    // complement is the pair at 5 - index.
    const int pairs[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};
    const double signs[6] = {1, -1, 1, 1, -1, 1};
    ValueId det = m_ir.Const(0.0);
    for (int i = 0; i < 6; ++i) {
        const int* p = pairs[i];
        const int* q = pairs[5 - i];
        ValueId top = Minor2(At(m, 0, p[0]), At(m, 0, p[1]), At(m, 1, p[0]), At(m, 1, p[1]));
        ValueId bottom = Minor2(At(m, 2, q[0]), At(m, 2, q[1]), At(m, 3, q[0]), At(m, 3, q[1]));
        ValueId term = Scalar(IrOp::Mul, top, bottom);
        det = Scalar(signs[i] > 0 ? IrOp::Add : IrOp::Sub, det, term);
    }
    return det;
}

Value ValueOps::Inverse(const Value& m) {
    // inverse = adjugate / determinant; the adjugate's entry (i, j) is the cofactor of (j, i):
    // (-1)^(i+j) times the 3x3 minor without row j and column i, expanded along its first row.
    auto a = [&](int r, int c) { return At(m, r, c); };
    auto minor3 = [&](int skipRow, int skipColumn) {
        int rows[3], columns[3];
        for (int i = 0, r = 0, c = 0; i < 4; ++i) {
            if (i != skipRow) rows[r++] = i;
            if (i != skipColumn) columns[c++] = i;
        }
        ValueId sum = m_ir.Const(0.0);
        for (int k = 0; k < 3; ++k) {
            const int c1 = columns[(k + 1) % 3], c2 = columns[(k + 2) % 3];
            // Cyclic order keeps the sign of every term positive: a0k (a1,k+1 a2,k+2 - a1,k+2 a2,k+1).
            ValueId sub = Minor2(a(rows[1], c1), a(rows[1], c2), a(rows[2], c1), a(rows[2], c2));
            sum = Scalar(IrOp::Add, sum, Scalar(IrOp::Mul, a(rows[0], columns[k]), sub));
        }
        return sum;
    };
    const ValueId det = Determinant(m);
    Value r{Type::Matrix, {}};
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) {
            ValueId cofactor = minor3(j, i);
            if ((i + j) % 2) cofactor = Scalar(IrOp::Neg, cofactor);
            r.c[4 * i + j] = Scalar(IrOp::Div, cofactor, det);
        }
    return r;
}

Value ValueOps::TransformBy(const Value& m, const Value& x, Type kind) {
    Value out{kind, {}};
    if (kind == Type::Normal) {
        // n' = n * (M^-1)ᵀ: normals stay perpendicular to transformed tangents.
        const Value inverse = Inverse(m);
        for (int j = 0; j < 3; ++j) {
            ValueId sum = Scalar(IrOp::Mul, x.c[0], At(inverse, j, 0));
            for (int i = 1; i < 3; ++i) sum = Scalar(IrOp::Add, sum, Scalar(IrOp::Mul, x.c[i], At(inverse, j, i)));
            out.c[j] = sum;
        }
        return out;
    }
    // (x y z 1) * M for a point, (x y z 0) * M for a vector.
    const int columns = kind == Type::Point ? 4 : 3;
    ValueId h[4];
    for (int j = 0; j < columns; ++j) {
        ValueId sum = Scalar(IrOp::Mul, x.c[0], At(m, 0, j));
        for (int i = 1; i < 3; ++i) sum = Scalar(IrOp::Add, sum, Scalar(IrOp::Mul, x.c[i], At(m, i, j)));
        h[j] = kind == Type::Point ? Scalar(IrOp::Add, sum, At(m, 3, j)) : sum;
    }
    // The homogeneous divide: w is the constant 1 for an affine matrix, and the division folds.
    for (int j = 0; j < 3; ++j) out.c[j] = kind == Type::Point ? Scalar(IrOp::Div, h[j], h[3]) : h[j];
    return out;
}

Value ValueOps::Translate(const Value& m, const Value& t) {
    Value step = Promote(Constant(1.0), Type::Matrix);
    for (int j = 0; j < 3; ++j) step.c[12 + j] = t.c[j];
    return MatrixProduct(step, m);
}

Value ValueOps::Scale(const Value& m, const Value& s) {
    Value step = Promote(Constant(1.0), Type::Matrix);
    for (int j = 0; j < 3; ++j) step.c[5 * static_cast<size_t>(j)] = s.c[j];
    return MatrixProduct(step, m);
}

Value ValueOps::Rotate(const Value& m, const Value& angle, const Value& axis) {
    // Rodrigues' formula for the unit axis a, row-vector style: R[i][j] = cos δij +
    // (1 - cos) a_i a_j + sin ε_ijk a_k, so that about +z the x axis turns towards +y.
    const Value a = Normalize(axis);
    const ValueId c = Scalar(IrOp::Cos, angle.c[0]), s = Scalar(IrOp::Sin, angle.c[0]);
    const ValueId oneMinusC = Scalar(IrOp::Sub, m_ir.Const(1.0), c);
    Value step = Promote(Constant(1.0), Type::Matrix);
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            ValueId e = Scalar(IrOp::Mul, oneMinusC, Scalar(IrOp::Mul, a.c[i], a.c[j]));
            if (i == j) {
                e = Scalar(IrOp::Add, e, c);
            } else {
                const int k = 3 - i - j;
                const bool even = (j == (i + 1) % 3);  // ε_ijk = +1 for (0 1 2) and its rotations
                const ValueId sa = Scalar(IrOp::Mul, s, a.c[k]);
                e = Scalar(even ? IrOp::Add : IrOp::Sub, e, sa);
            }
            step.c[4 * i + j] = e;
        }
    return MatrixProduct(step, m);
}

}  // namespace affray::compiler
