// compiler/opcode_map.h: between IR operations and VM opcodes, derived from the one opcode table
// (vm/opcodes.h). An IR operation has one VM opcode per operand form: all registers (RR), a
// constant second operand (RK) or a constant first operand (KR); the noise functions have one
// opcode per operand count. Emission picks a form (compiler/emit.cpp); specialisation lifts each
// opcode back to its IR operation (compiler/specialise.cpp). Both read the same table, so they
// cannot disagree.
#pragma once

#include <optional>

#include "compiler/ir.h"
#include "vm/opcodes.h"

namespace affray::compiler {

using OperandForm = vm::OperandForm;

struct OpcodeRow {
    IrOp ir;
    int count;  // IR operands
    OperandForm form;
    vm::Op vm;
};

/// The opcode for `op` with `count` operands in `form`, if the VM has one.
std::optional<vm::Op> OpcodeFor(IrOp op, int count, OperandForm form);
/// The row of a VM opcode (nothing for LoadK, Move and Ext, which are not IR operations).
const OpcodeRow* RowOf(vm::Op op);

}  // namespace affray::compiler
