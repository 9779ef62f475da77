// compiler/fold.cpp: the rewrite rules applied as each IR node is created.
// A rule may fire only if its result is the same for every number type the VM runs (double,
// interval, affine, dual), and a constant whose value is NaN or infinite is never folded (the
// run-time operation reports it instead). One deliberate exception: x * 0 => 0, which differs
// from IEEE only where x is infinite or NaN. Displacing along a constant axis (N = (0,0,1) on a
// flat patch) multiplies two components by 0 everywhere, and keeping those products would keep
// every singularity of the displacement in all three coordinates; since every number type then
// runs the same folded program, containment is unaffected. Constants fold with the scalar semantics (std:: functions),
// exactly what the scalar VM would compute.
#include <cmath>

#include "compiler/ir.h"

namespace affray::compiler {

namespace {

std::optional<double> Evaluate(IrOp op, double a, double b) {
    switch (op) {
        case IrOp::Neg: return -a;
        case IrOp::Sqr: return a * a;
        case IrOp::Sqrt: return std::sqrt(a);
        case IrOp::Exp: return std::exp(a);
        case IrOp::Log: return std::log(a);
        case IrOp::Sin: return std::sin(a);
        case IrOp::Cos: return std::cos(a);
        case IrOp::Abs: return std::fabs(a);
        case IrOp::Sign: return double((a > 0) - (a < 0));
        case IrOp::DerivU:
        case IrOp::DerivV: return 0.0;  // a constant does not vary over the surface
        case IrOp::Add: return a + b;
        case IrOp::Sub: return a - b;
        case IrOp::Mul: return a * b;
        case IrOp::Div: return a / b;
        case IrOp::Pow: return std::pow(a, b);
        case IrOp::Const:
        case IrOp::Global:
        case IrOp::Param: break;
    }
    return std::nullopt;
}

bool IsPowerOfTwo(double k) {
    int exponent = 0;
    return std::isfinite(k) && std::frexp(std::fabs(k), &exponent) == 0.5;
}

}  // namespace

std::optional<ValueId> Fold(IrBuilder& ir, IrOp op, ValueId a, ValueId b, int line) {
    std::optional<double> ka = ir.ConstValue(a);
    std::optional<double> kb = IsBinary(op) ? ir.ConstValue(b) : std::nullopt;

    // All operands constant => the constant result, unless it is NaN or infinite.
    if (ka && (kb || IsUnary(op))) {
        std::optional<double> r = Evaluate(op, *ka, kb.value_or(0.0));
        if (r && std::isfinite(*r)) return ir.Const(*r);
        return std::nullopt;
    }

    switch (op) {
        case IrOp::Neg:
            // -(-x) => x
            if (ir.node(a).op == IrOp::Neg) return ir.node(a).a;
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
        default:
            break;
    }
    return std::nullopt;
}

}  // namespace affray::compiler
