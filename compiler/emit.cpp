// compiler/emit.cpp: instruction selection, then the one back end (vm/assemble.h) for dead-code
// removal, register allocation and emission. Node ids are already a topological order (an
// operand is always created before its user), so selection is one forward walk: each operation
// picks the opcode form that takes its constant operands as K operands where one exists; a
// constant an opcode must read from a register is loaded once (LoadK).
#include "compiler/emit.h"

#include "compiler/opcode_map.h"
#include "vm/assemble.h"

namespace affray::compiler {

namespace {

/// The opcode for a node and which operands it takes as constants (swap: the operands of a
/// commutative operation exchanged so that its constant comes second).
struct Selection {
    vm::Op op = vm::Op::Move;
    bool aIsK = false, bIsK = false, swap = false;
};

Selection Select(const IrBuilder& ir, const IrNode& n) {
    Selection s;
    if (n.count != 2) {
        s.op = OpcodeFor(n.op, n.count, OperandForm::RR).value();
        return s;
    }
    auto isConst = [&](ValueId x) { return ir.node(x).op == IrOp::Const; };
    const bool aK = isConst(n.in[0]), bK = isConst(n.in[1]);
    if (bK)
        if (auto op = OpcodeFor(n.op, 2, OperandForm::RK)) {
            s.op = *op;
            s.bIsK = true;
            return s;
        }
    if (aK && IsCommutative(n.op))
        if (auto op = OpcodeFor(n.op, 2, OperandForm::RK)) {
            s.op = *op;
            s.aIsK = true;
            s.swap = true;
            return s;
        }
    if (aK)
        if (auto op = OpcodeFor(n.op, 2, OperandForm::KR)) {
            s.op = *op;
            s.aIsK = true;
            return s;
        }
    s.op = OpcodeFor(n.op, 2, OperandForm::RR).value();
    return s;
}

}  // namespace

vm::Program Emit(const IrBuilder& ir, const std::vector<NamedValue>& outputs,
                 const std::vector<vm::ProgramParam>& params) {
    vm::Assembler as;
    std::vector<int> value(ir.size(), -1);  // the assembler's value of each node computed in a register
    // A node's value in a register: a constant is loaded.
    auto inRegister = [&](ValueId v) {
        const IrNode& n = ir.node(v);
        return n.op == IrOp::Const ? as.Load(n.k, n.line) : value[v];
    };
    for (ValueId v = 0; v < ir.size(); ++v) {
        const IrNode& n = ir.node(v);
        switch (n.op) {
            case IrOp::Const: break;  // a K operand, or loaded where a register is needed
            case IrOp::Global:
                value[v] = as.Global(static_cast<vm::Global>(n.in[0])) + static_cast<int>(n.in[1]);
                break;
            case IrOp::Param: value[v] = as.Param(n.in[0], params.at(n.in[0]).size) + static_cast<int>(n.in[1]); break;
            default: {
                const Selection sel = Select(ir, n);
                int operands[kMaxIrOperands] = {};
                for (int i = 0; i < n.count; ++i) {
                    const bool isK = (i == 0 && sel.aIsK) || (i == 1 && sel.bIsK);
                    operands[i] = isK ? as.Constant(ir.node(n.in[i]).k) : inRegister(n.in[i]);
                }
                if (sel.swap) std::swap(operands[0], operands[1]);
                value[v] = as.Operation(sel.op, operands, n.line, n.channel);
            }
        }
    }
    std::vector<vm::Assembler::Output> outs;
    for (const NamedValue& o : outputs) {
        vm::Assembler::Output out;
        out.name = o.name;
        out.size = o.value.size();
        for (int i = 0; i < out.size; ++i) out.values[i] = inRegister(o.value.c[i]);
        outs.push_back(out);
    }
    vm::Program program;
    as.Finish(outs, params, true, &program);
    return program;
}

}  // namespace affray::compiler
