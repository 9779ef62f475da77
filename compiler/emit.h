// compiler/emit.h: from the value graph to register bytecode.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "compiler/value_ops.h"
#include "vm/program.h"

namespace affray::compiler {

struct NamedValue {
    std::string name;  // "P", "N"
    Value value;
};

/// Emits a program computing `outputs` from the IR: only nodes the outputs reach are kept (dead
/// code elimination), constant operands become K operands where an opcode takes one, and
/// registers are reused as soon as a value's last use has passed.
/// `params` describes the IR's Param nodes (by index); those the outputs read get registers.
vm::Program Emit(const IrBuilder& ir, const std::vector<NamedValue>& outputs,
                 const std::vector<vm::ProgramParam>& params = {});

}  // namespace affray::compiler
