// compiler/opcode_map.cpp: the rows, one per opcode that implements an operation, read off the
// opcode table (see the header).
#include "compiler/opcode_map.h"

#include <array>

namespace affray::compiler {

namespace {

/// Indexed by opcode; `vm` is Op::Ext where the opcode is no operation (LoadK, Move, Ext).
constexpr std::array<OpcodeRow, vm::kOpCount> MakeRows() {
    std::array<OpcodeRow, vm::kOpCount> rows{};
    for (int i = 0; i < vm::kOpCount; ++i) {
        const vm::Op op = static_cast<vm::Op>(i);
        const vm::Operation f = vm::OperationOf(op);
        rows[i] = f == vm::Operation::None ? OpcodeRow{IrOp::Const, 0, OperandForm::RR, vm::Op::Ext}
                                           : OpcodeRow{IrOpOf(f), vm::OperandCount(op), vm::FormOf(op), op};
    }
    return rows;
}

constexpr std::array<OpcodeRow, vm::kOpCount> kRows = MakeRows();

}  // namespace

std::optional<vm::Op> OpcodeFor(IrOp op, int count, OperandForm form) {
    const vm::Op found = vm::OpcodeFor(OperationOf(op), count, form);
    if (found == vm::Op::Ext) return std::nullopt;
    return found;
}

const OpcodeRow* RowOf(vm::Op op) {
    const OpcodeRow& row = kRows[static_cast<int>(op)];
    return row.vm == vm::Op::Ext ? nullptr : &row;
}

}  // namespace affray::compiler
