// vm/disasm.h: readable listings of programs, for `affray compile --disasm` and debugging.
#pragma once

#include <string>

#include "vm/program.h"

namespace affray::vm {

/// The instruction starting at `in` as text, e.g. "MulRK   r3, r1, k2 (0.5)", its Ext words
/// included; `available` is the number of words from `in` to the end of the code.
std::string DisassembleInstr(const Program& program, const Instr* in, size_t available);

/// The whole program: a header (globals read, outputs, constants), then one line per
/// instruction, preceded by the source line it came from whenever that line changes.
/// `sourceText` is the shader's source (may be empty: then line numbers only).
std::string Disassemble(const Program& program, const std::string& sourceText);

/// The instruction set as a Markdown table, read off the opcode table (vm/opcodes.h): number,
/// name, operand format, the operation with its facts and RSL spelling, and the meaning. What
/// `affray opcodes` prints and docs/opcodes.md holds.
std::string OpcodeTable();

}  // namespace affray::vm
