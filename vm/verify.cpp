// vm/verify.cpp: the bytecode verifier, driven by the operand formats in vm/opcodes.h.
#include "vm/verify.h"

#include <vector>

namespace affray::vm {

namespace {
bool Fail(std::string* error, const std::string& message) {
    if (error) *error = message;
    return false;
}
}  // namespace

bool Verify(const Program& program, std::string* error, bool lights) {
    const int nRegs = program.registerCount;
    if (nRegs < 0 || nRegs > kMaxRegisters) return Fail(error, "register count out of range");
    if (program.constants.size() > static_cast<size_t>(kMaxConstants)) return Fail(error, "too many constants");
    if (!program.lines.empty() && program.lines.size() != program.code.size())
        return Fail(error, "line table length differs from code length");

    if (program.textures && program.textures->size() > static_cast<size_t>(kMaxTextureSlots))
        return Fail(error, "too many texture slots");
    std::vector<bool> written(nRegs, false);
    for (int g = 0; g < kGlobalCount; ++g) {
        uint16_t base = program.globalRegisters[g];
        if (base == kNoRegister) continue;
        int size = GlobalSize(static_cast<Global>(g));
        if (base + size > nRegs)
            return Fail(error, std::string("global ") + GlobalName(static_cast<Global>(g)) + " register out of range");
        for (int i = 0; i < size; ++i) written[base + i] = true;
    }

    for (const ProgramParam& p : program.params) {
        if (p.size < 1) return Fail(error, "parameter " + p.name + " has a bad size");
        if (p.defaults.size() != static_cast<size_t>(p.size))
            return Fail(error, "parameter " + p.name + " has the wrong number of defaults");
        if (p.firstRegister == kNoRegister) continue;  // not read
        if (p.firstRegister + p.size > nRegs) return Fail(error, "parameter " + p.name + " register out of range");
        for (int i = 0; i < p.size; ++i) written[p.firstRegister + i] = true;
    }

    for (size_t pc = 0; pc < program.code.size(); ++pc) {
        const Instr& in = program.code[pc];
        std::string where = "instruction " + std::to_string(pc) + ": ";
        if (static_cast<int>(in.op) >= kOpCount)
            return Fail(error, where + "unknown opcode " + std::to_string(int(in.op)));
        if (in.op == Op::Ext) return Fail(error, where + "an Ext word without an instruction before it");
        const char* format = Info(in.op).format;
        const int words = WordCount(format);
        if (pc + words > program.code.size()) return Fail(error, where + "its operand words are missing");
        for (int w = 1; w < words; ++w)
            if (program.code[pc + w].op != Op::Ext) return Fail(error, where + "its operand words are missing");
        if (OperationOf(in.op) == Operation::Texture && (!program.textures || in.flags >= program.textures->size()))
            return Fail(error, where + "texture slot " + std::to_string(in.flags) + " out of range");
        if ((in.op == Op::Light || in.op == Op::Trace) && !lights)
            return Fail(error, where + "a light query outside a surface program");
        // Reads first, then the write: an instruction may overwrite one of its own operands.
        for (int i = 0; format[i]; ++i) {
            uint16_t x = OperandOf(&in, i);
            switch (format[i]) {
                case 'r':
                    if (x >= nRegs) return Fail(error, where + "register r" + std::to_string(x) + " out of range");
                    if (!written[x])
                        return Fail(error, where + "register r" + std::to_string(x) + " read before it is written");
                    break;
                case 'k':
                    if (x >= program.constants.size())
                        return Fail(error, where + "constant k" + std::to_string(x) + " out of range");
                    break;
                default: break;
            }
        }
        if (format[0] == 'w') {
            if (in.a >= nRegs) return Fail(error, where + "register r" + std::to_string(in.a) + " out of range");
            written[in.a] = true;
        }
        pc += words - 1;
    }

    for (const ProgramOutput& out : program.outputs) {
        if (out.size != 1 && out.size != 3) return Fail(error, "output " + out.name + " has a bad size");
        for (int i = 0; i < out.size; ++i) {
            uint16_t r = out.registers[i];
            if (r >= nRegs || !written[r])
                return Fail(error, "output " + out.name + " register out of range or never written");
        }
    }
    return true;
}

}  // namespace affray::vm
