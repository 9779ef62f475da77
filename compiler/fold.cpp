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
#include "vm/noise.h"

namespace affray::compiler {

namespace {

std::optional<double> Evaluate(const IrNode& n, const double* x) {
    const double a = x[0], b = x[1];
    auto truth = [](double v) { return v != 0; };  // NaN counts as true, as in the VM
    switch (n.op) {
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
        case IrOp::Floor: return std::floor(a);
        case IrOp::Ceil: return std::ceil(a);
        case IrOp::Round: return std::round(a);
        case IrOp::Asin: return std::asin(a);
        case IrOp::Acos: return std::acos(a);
        case IrOp::Atan: return std::atan(a);
        case IrOp::Not: return double(!truth(a));
        case IrOp::Add: return a + b;
        case IrOp::Sub: return a - b;
        case IrOp::Mul: return a * b;
        case IrOp::Div: return a / b;
        case IrOp::Pow: return std::pow(a, b);
        case IrOp::Min: return std::fmin(a, b);
        case IrOp::Max: return std::fmax(a, b);
        case IrOp::Atan2: return std::atan2(a, b);
        case IrOp::Lt: return double(a < b);
        case IrOp::Le: return double(a <= b);
        case IrOp::Eq: return double(a == b);
        case IrOp::Ne: return double(a != b);
        case IrOp::And: return double(truth(a) && truth(b));
        case IrOp::Or: return double(truth(a) || truth(b));
        case IrOp::Select: return truth(a) ? b : x[2];
        case IrOp::Noise: return vm::Noise(x, n.count, n.channel);
        case IrOp::PNoise: return vm::PNoise(x, x + n.count / 2, n.count / 2, n.channel);
        case IrOp::CellNoise: return vm::CellNoise(x, n.count, n.channel);

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
        default:
            break;
    }
    return std::nullopt;
}

}  // namespace affray::compiler
