// compiler/fold.cpp: the rewrite rules applied as each IR node is created.
// Constant operands: the operation runs in the scalar VM (vm::RunScalarOpcode), so the folded
// constant is the run-time value bit for bit (tests/compiler/fold_test.cpp checks every foldable
// opcode on edge values); a constant whose value is NaN or infinite is never folded (the run-time
// operation reports it instead). The algebraic rules below (x + 0 => x, x * 1 => x, ...) may fire
// only if their result is the same for every number type the VM runs (double, interval, affine,
// dual), as a value: they may give the other zero where IEEE gives a signed one (-0 + 0 is +0).
// One deliberate exception: x * 0 => 0, which also differs from IEEE where x is infinite or NaN. Displacing along a constant axis (N = (0,0,1) on a
// flat patch) multiplies two components by 0 everywhere, and keeping those products would keep
// every singularity of the displacement in all three coordinates; since every number type then
// runs the same folded program, containment is unaffected. Constants fold by running the opcode in
// the scalar VM (vm::RunScalarOpcode): a folded value is the run-time value, bit for bit.
#include <cmath>

#include "compiler/ir.h"
#include "vm/interpreter.h"

namespace affray::compiler {

namespace {

/// The value of `n` on the constant operands `x`: the scalar VM's own (vm::RunScalarOpcode), so
/// that a folded constant equals the run-time value bit for bit. The derivative of a constant is
/// 0 (it does not vary over the surface), where the scalar VM, which has no derivatives, gives NaN.
std::optional<double> Evaluate(const IrNode& n, const double* x) {
    const vm::Operation f = OperationOf(n.op);
    if (vm::Has(f, vm::kDerivative)) return 0.0;
    if (!vm::Has(f, vm::kFoldable)) return std::nullopt;
    const vm::Op op = vm::OpcodeFor(f, n.count, vm::OperandForm::RR);
    if (op == vm::Op::Ext) return std::nullopt;
    return vm::RunScalarOpcode(op, x, n.channel);
}

bool IsPowerOfTwo(double k) {
    int exponent = 0;
    return std::isfinite(k) && std::frexp(std::fabs(k), &exponent) == 0.5;
}

}  // namespace

std::optional<ValueId> Fold(IrBuilder& ir, const IrNode& n) {
    const IrOp op = n.op;
    const int line = n.line;

    // All operands constant => the constant result, unless it is NaN or infinite.
    double k[kMaxIrOperands];
    bool allConstant = true;
    for (int i = 0; i < n.count && allConstant; ++i) {
        std::optional<double> c = ir.ConstValue(n.in[i]);
        allConstant = c.has_value() && std::isfinite(*c);
        if (allConstant) k[i] = *c;
    }
    if (allConstant && n.count > 0) {
        std::optional<double> r = Evaluate(n, k);
        if (r && std::isfinite(*r)) return ir.Const(*r);
        return std::nullopt;
    }

    const ValueId a = n.in[0], b = n.in[1];
    // (Plain doubles with flags rather than std::optional: GCC 12 warns falsely on the latter.)
    struct K {
        bool known = false;
        double value = 0;
        explicit operator bool() const { return known; }
        double operator*() const { return value; }
    };
    auto constantOf = [&](int i) {
        K k;
        if (n.count > i)
            if (std::optional<double> c = ir.ConstValue(n.in[i])) k = {true, *c};
        return k;
    };
    const K ka = constantOf(0), kb = constantOf(1);
    switch (op) {
        case IrOp::Neg:
            // -(-x) => x
            if (ir.node(a).op == IrOp::Neg) return ir.node(a).in[0];
            break;
        case IrOp::Add:
            // x + 0 => x, 0 + x => x
            if (kb && *kb == 0.0) return a;
            if (ka && *ka == 0.0) return b;
            break;
        case IrOp::Sub:
            // x - 0 => x
            if (kb && *kb == 0.0) return a;
            // 0 - x => -x
            if (ka && *ka == 0.0 && !std::signbit(*ka)) return ir.Unary(IrOp::Neg, b, line);
            break;
        case IrOp::Mul:
            // x * 1 => x, 1 * x => x
            if (kb && *kb == 1.0) return a;
            if (ka && *ka == 1.0) return b;
            // x * 0 => 0, 0 * x => 0 (see the head comment)
            if ((kb && *kb == 0.0) || (ka && *ka == 0.0)) return ir.Const(0.0);
            // x * -1 => -x
            if (kb && *kb == -1.0) return ir.Unary(IrOp::Neg, a, line);
            if (ka && *ka == -1.0) return ir.Unary(IrOp::Neg, b, line);
            // x * x => sqr(x): one operand keeps affine bounds correlated (x^2 >= 0)
            if (a == b) return ir.Unary(IrOp::Sqr, a, line);
            // x * -x => -sqr(x), -x * x likewise: the same double (negation is exact and rounding
            // symmetric; -0, infinities and NaN included), and a bound of sqr(x), not of a
            // product of two operands whose errors are taken as independent.
            if (ir.node(b).op == IrOp::Neg && ir.node(b).in[0] == a)
                return ir.Unary(IrOp::Neg, ir.Unary(IrOp::Sqr, a, line), line);
            if (ir.node(a).op == IrOp::Neg && ir.node(a).in[0] == b)
                return ir.Unary(IrOp::Neg, ir.Unary(IrOp::Sqr, b, line), line);
            break;
        case IrOp::Div:
            // x / 1 => x
            if (kb && *kb == 1.0) return a;
            // x / 2^n => x * 2^-n (exact, and multiplication is cheaper in every mode)
            if (kb && IsPowerOfTwo(*kb)) return ir.Binary(IrOp::Mul, a, ir.Const(1.0 / *kb), line);
            break;
        case IrOp::Pow:
            // pow(x, 1) => x
            if (kb && *kb == 1.0) return a;
            // pow(x, 2) => sqr(x)
            if (kb && *kb == 2.0) return ir.Unary(IrOp::Sqr, a, line);
            break;
        case IrOp::Min:
        case IrOp::Max:
            // min(x, x) => x
            if (a == b) return a;
            break;
        case IrOp::Not:
            // !!c => c for a boolean c
            if (ir.node(a).op == IrOp::Not && ir.IsBoolean(ir.node(a).in[0])) return ir.node(a).in[0];
            break;
        case IrOp::And:
            // c && c => c; false && x => false; true && c => c for a boolean c
            if (a == b && ir.IsBoolean(a)) return a;
            if ((ka && *ka == 0.0) || (kb && *kb == 0.0)) return ir.Const(0.0);
            if (ka && *ka == 1.0 && ir.IsBoolean(b)) return b;
            if (kb && *kb == 1.0 && ir.IsBoolean(a)) return a;
            break;
        case IrOp::Or:
            // c || c => c; true || x => true; false || c => c for a boolean c
            if (a == b && ir.IsBoolean(a)) return a;
            if ((ka && *ka == 1.0) || (kb && *kb == 1.0)) return ir.Const(1.0);
            if (ka && *ka == 0.0 && ir.IsBoolean(b)) return b;
            if (kb && *kb == 0.0 && ir.IsBoolean(a)) return a;
            break;
        case IrOp::Select: {
            // A decided condition runs one arm: this is what removes the branches a shader
            // instance does not take (its parameters are constants by then).
            const ValueId x = n.in[1], y = n.in[2];
            if (ka && std::isfinite(*ka)) return *ka != 0 ? x : y;
            // c ? x : x => x
            if (x == y) return x;
            // c ? 1 : 0 => c, c ? 0 : 1 => !c for a boolean c
            const K kx = constantOf(1), ky = constantOf(2);
            if (ir.IsBoolean(a) && kx && ky && *kx == 1.0 && *ky == 0.0) return a;
            if (ir.IsBoolean(a) && kx && ky && *kx == 0.0 && *ky == 1.0) return ir.Unary(IrOp::Not, a, line);
            // !c ? x : y => c ? y : x
            if (ir.node(a).op == IrOp::Not) return ir.Select(ir.node(a).in[0], y, x, line);
            break;
        }
        default: break;
    }
    return std::nullopt;
}

}  // namespace affray::compiler
